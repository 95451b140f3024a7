"""Type stubs for meshvol._meshvol, the extension module (the runtime objects carry the
full docstrings). Its classes' __module__ is "meshvol": the errors, Mesh, MassProperties,
Check and Shell are written in __init__.pyi and imported here; the other reports and the
functions are written here and imported there (two files, each under 600 lines).
Checked against the runtime by mypy's stubtest (tests/test_typing.py)."""

import os
from typing import Any, BinaryIO, Iterable, Mapping, Optional, Sequence, Tuple, Union as _Union, final

import numpy as np
import numpy.typing as npt

from meshvol import (
    MeshError as MeshError,
    ReadError as ReadError,
    InvalidMeshError as InvalidMeshError,
    LossyWriteError as LossyWriteError,
    MeshWarning as MeshWarning,
    Mesh as Mesh,
    MassProperties as MassProperties,
    Check as Check,
    Shell as Shell,
)

__version__: str
__all__ = [
    "__version__",
    "MeshError",
    "ReadError",
    "InvalidMeshError",
    "LossyWriteError",
    "MeshWarning",
    "Mesh",
    "MassProperties",
    "Check",
    "Shell",
    "Profile",
    "Union",
    "AreaProperties",
    "Hull",
    "Below",
    "CutFill",
    "Intersection",
    "Section",
    "load",
    "union",
    "intersection",
    "intersections",
    "polygon_area",
    "convex_hull",
    "hull_volume",
    "cutfill",
    "_measure_files",
    "_expand",
    "_mesh_name_endings",
    "volume",
]

_ArrayLike = npt.ArrayLike
_F64 = npt.NDArray[np.float64]
_Faces = _Union[npt.ArrayLike, Sequence[Sequence[int]]]
_Density = _Union[float, str]
_Timings = list[dict[str, Any]]
_Path = _Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]

class _Report:
    """What every report of a command has (a base of the stubs alone, as _CheckFacts)."""

    units: Optional[dict[str, Any]]
    """Names of the reported units; None: the file's own units."""
    warnings: list[str]
    timings: _Timings
    """With timings=True: the stages' {stage, wall_s, cpu_s} (else absent)."""
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of the command's --json report."""

@final
class Profile(_Report):
    """Volume below each level (`meshvol profile --json`'s keys)."""
    axis: str
    file: Optional[str]
    @property
    def levels(self) -> _F64: ...
    @property
    def volume_below(self) -> _F64: ...
    @property
    def slab_volume(self) -> _F64: ...
    @property
    def section_area(self) -> _F64: ...

@final
class Union(_Report):
    """The union's volume as a certified interval (`meshvol union --json`'s keys)."""
    lower: float
    upper: float
    certified: bool
    """Whether [lower, upper] is proven to hold the union (see uncertified_reason)."""
    uncertified_reason: Optional[str]
    """Why the interval is not certified; None when it is."""
    volume: float
    bodies: int
    sum_of_volumes: float
    cells_refined: int
    cells_resolved_exactly: int
    columns_unresolved: int
    flipped: list[int]
    volume_uncertainty: float
    """The caps on holes' uncertainty, included in [lower, upper]."""
    file: str
    """The meshes' names (their files, or 'mesh'), joined by ', '."""
    files: list[str]
    body_names: list[str]
    grid: list[int]
    seconds: float

@final
class Intersection(_Report):
    """The intersection of two bodies, certified (`meshvol intersect --json`'s keys)."""
    lower: float
    upper: float
    certified: bool
    """Whether [lower, upper] is proven to hold |A∩B| (see uncertified_reason)."""
    uncertified_reason: Optional[str]
    """Why the interval is not certified; None when it is."""
    volume: float
    """The midpoint of [lower, upper], which holds |A∩B|."""
    volume_a: float
    volume_b: float
    union: float
    union_lower: float
    union_upper: float
    a_minus_b: float
    b_minus_a: float
    iou: float
    iou_lower: float
    iou_upper: float
    dice: float
    contact_area: Optional[float]
    """Area of A's surface inside B plus B's inside A (0 when apart)."""
    disjoint: bool
    """The bodies' boxes (as placed) are apart or only touch: volume is exactly 0."""
    cells_refined: int
    cells_resolved_exactly: int
    columns_unresolved: int
    flipped: list[int]
    volume_uncertainty: float
    """The caps on holes' uncertainty, included in [lower, upper]."""
    method: str
    """'boxes' (apart: 0), 'boundary' (each face's part inside the other body) or 'grid'."""
    file: str
    """The meshes' names (their files, or 'mesh'), joined by ', '."""
    files: list[str]
    grid: list[int]
    seconds: float
    @property
    def centroid(self) -> Optional[_F64]: ...
    @property
    def inertia(self) -> Optional[_F64]: ...
    @property
    def contact_vector(self) -> Optional[_F64]:
        """∫ n dA over B's surface inside A: d|A∩B|/dt = e · contact_vector as B moves by t·e."""
    @property
    def contact_normal(self) -> Optional[_F64]:
        """contact_vector scaled to length 1 (None where it is 0)."""

@final
class AreaProperties(_Report):
    """Area, perimeter, centroid and second moments of plane polygons."""
    area: float
    perimeter: float
    ix: float
    iy: float
    ixy: float
    polar: float
    principal_angle_degrees: float
    issues: list[str]
    file: Optional[str]
    format: Optional[str]
    polygons: int
    inertia: Optional[dict[str, Any]]
    """The second moments as `meshvol area --json` nests them; None without area."""
    rings: list[dict[str, Any]]
    @property
    def centroid(self) -> Optional[_F64]:
        """Shape (2,); None when the area is zero."""
    @property
    def principal_moments(self) -> _F64:
        """Shape (2,), ascending (as MassProperties')."""
    @property
    def principal_axes(self) -> _F64:
        """Shape (2, 2): row k is the axis of principal_moments[k]."""

@final
class Below(_Report):
    """The part of a solid below a plane (`meshvol below --json`'s keys)."""
    file: Optional[str]
    level: float
    volume: float
    wetted_area: float
    section_area: float
    @property
    def normal(self) -> _F64:
        """Shape (3,): the plane's unit normal."""
    @property
    def centroid(self) -> Optional[_F64]:
        """Shape (3,): the centre of buoyancy; None without volume."""
    @property
    def section_centroid(self) -> Optional[_F64]:
        """Shape (3,): the waterplane's centroid; None without a section."""

@final
class CutFill(_Report):
    """Cut and fill between two surfaces (`meshvol cutfill --json`'s keys)."""
    file: Optional[str]
    design: str
    level: Optional[float]
    cut: float
    fill: float
    net: float
    area_cut: float
    area_fill: float
    footprint_area: float
    existing_area: float
    design_area: Optional[float]
    grid: Optional[dict[str, list[Any]]]
    @property
    def footprint_bounds(self) -> Optional[_F64]:
        """Shape (2, 2): [[x0, y0], [x1, y1]]; None without a footprint."""
    @property
    def cut_cells(self) -> Optional[_F64]:
        """Shape (nx, ny): cut volume per plan cell; None without cells or pitch."""
    @property
    def fill_cells(self) -> Optional[_F64]:
        """Shape (nx, ny): fill volume per plan cell; None without cells or pitch."""

@final
class Hull(_Report):
    """A convex hull (`meshvol hull --json`'s keys) and its mesh."""
    points: int
    point_count: int
    hull_vertices: int
    hull_vertex_count: int
    hull_faces: int
    hull_face_count: int
    volume: float
    volume_error_bound: float
    area: float
    degenerate: Optional[str]
    mesh: Optional[Mesh]
    file: Optional[str]
    format: Optional[str]
    @property
    def centroid(self) -> Optional[_F64]: ...

@final
class Section(_Report):
    """The cross-section of a solid by a plane (`meshvol section --json`'s keys)."""

    file: Optional[str]
    format: Optional[str]
    plane: dict[str, list[float]]
    """origin, normal and the 2D axes u, v: a point (s, t) is origin + s·u + t·v."""
    area: float
    signed_area: float
    perimeter: float
    inertia: Optional[dict[str, Any]]
    polygons: int
    holes: int
    loops: int
    segments: int
    open_chains: int
    @property
    def centroid(self) -> Optional[_F64]:
        """Shape (2,), in the plane's coordinates; None without area."""
    @property
    def centroid_3d(self) -> Optional[_F64]:
        """Shape (3,); None without area."""
    @property
    def principal_moments(self) -> _F64:
        """Shape (2,), ascending."""
    @property
    def principal_axes(self) -> _F64:
        """Shape (2, 2): row k is the axis of principal_moments[k], in 2D."""
    @property
    def outlines(self) -> list[Tuple[_F64, list[_F64]]]:
        """(exterior, holes) of each polygon, (n, 2) arrays in the plane's coordinates."""
    def to_wkt(self) -> str:
        """A WKT MULTIPOLYGON (`meshvol section --wkt`)."""
    def to_geojson(self) -> dict[str, Any]:
        """A GeoJSON Feature (`meshvol section --geojson`)."""

_MeshArg = _Union[Mesh, _Path, Any]
"""A meshvol.Mesh, a path (read as load reads it), or an object with .vertices and
.faces (a trimesh.Trimesh)."""

def load(file: _Union[_Path, BinaryIO], file_type: Optional[str] = None) -> Mesh:
    """Read a mesh file as the command reads it.

    Parameters
    ----------
    file : str, bytes, os.PathLike or binary file object
        The file: a path, or anything whose read() returns bytes (open(p, "rb"),
        io.BytesIO, a zip member).
    file_type : str, optional
        The format when the name does not say it: 'stl', 'obj', 'off', 'ply', '3mf',
        'gltf', 'glb', each also compressed ('stl.gz', 'obj.bz2', 'ply.zst'), or a
        compression alone ('gz', 'bz2', 'zst', 'zip'). None: by name and content.

    Returns
    -------
    Mesh
        With .format, .unit, .warnings and .objects saying what the file said.

    Raises
    ------
    MeshFileNotFoundError, MeshPermissionError, MeshIsADirectoryError
        The file cannot be opened (OSError subclasses, and ReadError).
    ReadError
        The file is not a mesh meshvol reads; the message names the file and the place.
    """

def union(
    meshes: _Union[_MeshArg, Iterable[_MeshArg]],
    tolerance: float = 1e-6,
    check: bool = True,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> Union:
    """The volume of the union of closed bodies as a certified interval (`meshvol union`).

    Parameters
    ----------
    meshes : mesh, path, or an iterable of them
        The bodies. One mesh or path (or a list of one) stands for its bodies.
    tolerance : float
        Refinement stops once upper - lower <= tolerance * lower.
    check : bool
        True: each mesh's checked solid (holes capped); False: the surfaces as wound.
    units, density : str, optional
        As the command's --units and --density.
    timings : bool
        Add `timings`: each check (run again), then measuring.

    Returns
    -------
    Union
    """

def intersection(
    a: _MeshArg,
    b: _MeshArg,
    pose_a: Optional[_ArrayLike] = None,
    pose_b: Optional[_ArrayLike] = None,
    tolerance: float = 1e-9,
    check: bool = True,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> Intersection:
    """The volume of A∩B as a certified interval, with IoU, Dice and moments
    (`meshvol intersect`).

    Parameters
    ----------
    a, b : mesh or path
        Each one body (every shell).
    pose_a, pose_b : array_like, optional
        A 4×4 rigid transform placing each body's checked solid.
    tolerance, check, units, density, timings
        As for union.

    Returns
    -------
    Intersection
    """

def intersections(
    a: _MeshArg,
    b: _MeshArg,
    poses_a: Optional[_ArrayLike] = None,
    poses_b: Optional[_ArrayLike] = None,
    tolerance: float = 1e-9,
    check: bool = True,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> list[Intersection]:
    """`intersection` for many poses, in parallel, each result bit for bit the pose's alone.

    Parameters
    ----------
    a, b : mesh or path
        Each one body, checked once.
    poses_a, poses_b : array_like, optional
        None, one 4×4 rigid transform, or an (N, 4, 4) array (two arrays: the same N).
    tolerance, check, units, density
        As for intersection.
    timings : bool
        Give each result the call's `timings`: each check (run again), then measuring
        every pose.

    Returns
    -------
    list of Intersection
        One per pose.
    """

def polygon_area(
    exterior: _Union[_ArrayLike, Mapping[str, Any], Any],
    holes: Optional[Iterable[_ArrayLike]] = None,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> AreaProperties:
    """Area properties of plane polygons (`meshvol area`).

    Parameters
    ----------
    exterior : array_like (n, 2), GeoJSON dict, or object with __geo_interface__
        The outer ring, or a (Multi)Polygon.
    holes : iterable of array_like (n, 2), optional
        The holes of an outer ring.
    units, density : str, optional
        As the command's --units and --density (a mass per area).
    timings : bool
        Add `timings`.

    Returns
    -------
    AreaProperties
    """

def convex_hull(
    points: _ArrayLike,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> Hull:
    """The convex hull of points and its mesh (`meshvol hull`).

    Parameters
    ----------
    points : array_like (n, 3)
    units, density : str, optional
        As the command's --units and --density.
    timings : bool
        Add `timings`.

    Returns
    -------
    Hull
    """

def hull_volume(points: _ArrayLike) -> float:
    """The volume of the convex hull of an (n, 3) point array.

    Parameters
    ----------
    points : array_like (n, 3)

    Returns
    -------
    float
    """

def volume(vertices: _ArrayLike, faces: _Faces, check: bool = True) -> Tuple[float, float]:
    """The volume alone of a mesh given as arrays (`meshvol volume`).

    Parameters
    ----------
    vertices : array_like (n, 3)
    faces : array_like (m, 3) of int, or a list of index lists
    check : bool
        True: the checked solid's volume (never negative), as
        Mesh(vertices, faces).mass_properties(); False: the signed volume as wound, in
        one pass, C-contiguous float64 vertices and int32/int64/uint32/uint64 faces
        read in place.

    Returns
    -------
    (float, float)
        The volume and its error bound.

    Examples
    --------
    >>> import numpy as np, meshvol
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)
    >>> meshvol.volume(v, f, check=False)[0] == 1 / 6
    True
    """

def cutfill(
    existing: _MeshArg,
    design: Optional[_MeshArg] = None,
    level: Optional[float] = None,
    cells: Optional[_ArrayLike] = None,
    pitch: Optional[float] = None,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> CutFill:
    """Cut and fill between an existing surface and a design or a level (`meshvol cutfill`).

    Parameters
    ----------
    existing, design : mesh or path
        Height fields z = f(x, y); give design, or level.
    level : float, optional
        The plane z = level, in the files' units.
    cells : (int, int), optional
        Per-cell volumes on an (nx, ny) plan grid (cut_cells, fill_cells).
    pitch : float, optional
        Per-cell volumes on square plan cells of this size.
    units, density : str, optional
        As the command's --units and --density (the fill's mass).
    timings : bool
        Add `timings`.

    Returns
    -------
    CutFill
    """

def _measure_files(
    paths: Sequence[_Union[str, "os.PathLike[str]"]],
    workers: Optional[int] = None,
    check: bool = True,
    density: Optional[_Density] = 1.0,
    units: Optional[str] = None,
    exact: bool = False,
    timings: bool = False,
) -> list[str]:
    """Each file's `meshvol volume --json` line, in order (meshvol.measure's native part)."""

def _expand(
    paths: Sequence[_Union[str, "os.PathLike[str]"]],
    recursive: bool = True,
    globs: Sequence[str] = ...,
) -> Tuple[list["os.PathLike[str]"], list[Tuple[str, str]]]:
    """The files the paths stand for, and each folder or pattern that gave none with its error."""

def _mesh_name_endings() -> list[str]:
    """The endings of the file names a folder is searched for, lower case."""
