"""Type stubs for meshvol (the runtime objects carry the full docstrings)."""

import os
from typing import TYPE_CHECKING, Any, BinaryIO, Iterable, Literal, Mapping, Optional, Sequence, Tuple, Union as _Union

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    import pandas

__version__: str
__all__: list[str]

_ArrayLike = npt.ArrayLike
_F64 = npt.NDArray[np.float64]
_Faces = _Union[npt.ArrayLike, Sequence[Sequence[int]]]
_Density = _Union[float, str]
_Timings = list[dict[str, Any]]
_Path = _Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]

class MeshError(ValueError):
    """Base class of meshvol's errors, with the meshvol command's messages."""

class ReadError(MeshError):
    """A file could not be read."""

    path: str
    """The file."""
    location: Optional[str]
    """Where in it: 'line 12', 'byte 84', 'face 3', an archive part's line, a JSON path."""
    line: Optional[int]
    """The line (from 1), when the location is a line of a text file."""
    byte: Optional[int]
    """The byte offset (from 0), when the location is one."""
    face: Optional[int]
    """The face (from 0), when the location is one."""
    reason: str
    """The message without path and location."""

class MeshOSError(OSError, ReadError):
    """A mesh file could not be opened: an OSError and a ReadError ('PATH: REASON')."""

class MeshFileNotFoundError(FileNotFoundError, MeshOSError):
    """The file does not exist."""

class MeshPermissionError(PermissionError, MeshOSError):
    """The file cannot be read with the permissions given."""

class MeshIsADirectoryError(IsADirectoryError, MeshOSError):
    """The path is a directory."""

class InvalidMeshError(MeshError):
    """Arrays that cannot be used as given: shape, dtype, non-finite value, index range."""

class LossyWriteError(MeshError):
    """Mesh.save refused a file that does not read back as the mesh's solid (float32)."""

class MeshWarning(UserWarning):
    """A measurement of a solid that may not be the one meant (open, overlapping, ...)."""

class Mesh:
    """A surface mesh: float64 vertices and faces (triangles or polygons) indexing them.

    Mesh(vertices, faces) copies and checks the arrays; Mesh(obj) takes obj.vertices and
    obj.faces (a trimesh.Trimesh, another Mesh). A Mesh never changes once built.
    """

    def __init__(self, vertices: Any, faces: Optional[_Faces] = None) -> None: ...
    @property
    def vertices(self) -> _F64:
        """The (n, 3) float64 vertices: a read-only view of the mesh's memory."""
    @property
    def faces(self) -> _Union[npt.NDArray[np.uint32], list[list[int]]]:
        """(m, 3) uint32 read-only view for triangles; else a list of index lists."""
    @property
    def face_indices(self) -> npt.NDArray[np.uint32]:
        """Every face's vertex indices, one after another (uint32), for any mesh."""
    @property
    def face_offsets(self) -> npt.NDArray[np.uint64]:
        """Where each face starts in face_indices (face_count + 1 entries, from 0)."""
    @property
    def vertex_count(self) -> int: ...
    @property
    def face_count(self) -> int: ...
    @property
    def triangle_count(self) -> int:
        """Triangles in the faces' fans: a face of k vertices counts k - 2."""
    @property
    def is_triangle_mesh(self) -> bool: ...
    @property
    def format(self) -> Optional[str]:
        """The format of the file read ('stl-binary', 'obj', ...); None for arrays."""
    @property
    def file(self) -> Optional[str]:
        """The path given to load(); None for arrays."""
    @property
    def unit(self) -> Optional[str]:
        """The length unit the file declares ('mm', 'm', ...), or None."""
    @property
    def warnings(self) -> list[str]:
        """What the reader read but did not use, or had to guess."""
    @property
    def objects(self) -> list[Tuple[str, int, int]]:
        """(name, first face, end face) of each named part, when there are two or more."""
    def mass_properties(
        self,
        density: _Density = 1.0,
        exact: bool = False,
        check: bool = True,
        units: Optional[str] = None,
        timings: bool = False,
    ) -> MassProperties:
        """Mass properties of the checked solid (`meshvol volume`); check=False: as wound;
        units: as --units ('mm:cm', ':in', ...); density: 2.5 or '7.85g/cm3'."""
    def check(
        self,
        weld_tolerance: Optional[float] = None,
        intersections: bool = True,
        units: Optional[str] = None,
        density: Optional[_Density] = None,
        timings: bool = False,
    ) -> Check:
        """Topology facts (`meshvol check`)."""
    def grid(
        self,
        cells: Optional[_ArrayLike] = None,
        bounds: Optional[_ArrayLike] = None,
        fraction: bool = False,
        pitch: _Union[float, _ArrayLike, None] = None,
        check: bool = True,
        region: Optional[_ArrayLike] = None,
        units: Optional[str] = None,
        density: Optional[_Density] = None,
        timings: bool = False,
        backend: Literal["auto", "cpu", "opencl"] = "auto",
        opencl_device: Optional[int] = None,
    ) -> Grid:
        """The solid's volume in each cell, a Grid over an (nx, ny, nz) array (`meshvol
        grid`), or the block `region` of it. cells: 3 ints; bounds: (2, 3); pitch: a
        number or 3; region: (3, 2) cell ranges; any array-like."""
    def cells(
        self,
        cells: Optional[_ArrayLike] = None,
        bounds: Optional[_ArrayLike] = None,
        pitch: _Union[float, _ArrayLike, None] = None,
        check: bool = True,
        region: Optional[_ArrayLike] = None,
        units: Optional[str] = None,
        second_moments: bool = False,
        face_centroids: bool = False,
        moments: Literal[True] = True,
        backend: Literal["auto", "cpu", "opencl"] = "auto",
        opencl_device: Optional[int] = None,
    ) -> CutCells:
        """The cut-cell geometry on a grid (`meshvol grid --moments`): volume, fraction,
        centroid, boundary_area, boundary_vector, boundary_centroid, aperture_x/_y/_z;
        with second_moments, inertia; with face_centroids, aperture_x/_y/_z_centroid.
        moments=False is a ValueError: Mesh.grid gives the volumes alone."""
    def profile(
        self,
        axis: str = "z",
        levels: Optional[int] = None,
        step: Optional[float] = None,
        check: bool = True,
        units: Optional[str] = None,
        density: Optional[_Density] = None,
        timings: bool = False,
    ) -> Profile:
        """Volume below each level along an axis (`meshvol profile`)."""
    def below(
        self,
        plane: Optional[_ArrayLike] = None,
        volume: Optional[float] = None,
        direction: _ArrayLike = (0.0, 0.0, 1.0),
        heel: float = 0.0,
        trim: float = 0.0,
        check: bool = True,
        units: Optional[str] = None,
        density: Optional[_Density] = None,
        timings: bool = False,
    ) -> Below:
        """The solid below a plane, or below the level holding `volume` (`meshvol below`)."""
    def section(
        self,
        plane: _Union[str, _ArrayLike],
        check: bool = True,
        units: Optional[str] = None,
        density: Optional[_Density] = None,
        timings: bool = False,
    ) -> Section:
        """The cross-section by a plane: 'z=H', [point, normal] or (nx, ny, nz, d)
        (`meshvol section`); density: a mass per area ('62.8kg/m2'), mass a sheet's."""
    def bodies(self, check: bool = True) -> list[Mesh]:
        """The solid's bodies as meshes (each outermost shell with its cavities)."""
    def triangulated(self) -> Mesh:
        """Every face replaced by its fan of triangles."""
    def flipped(self) -> Mesh:
        """Every face's winding reversed."""
    def save(
        self, path: _Union[str, "os.PathLike[str]"], allow_lossy: bool = False
    ) -> dict[str, Any]:
        """Write .ply/.obj/.stl/.glb, read it back, refuse it unless it is the same solid."""

class _CheckFacts:
    """The facts of `meshvol check` that Check and (checked) MassProperties share."""

    bounds_a_volume: bool
    verdict: str
    closed: bool
    weld_tolerance: Optional[float]
    welded_vertices: int
    edges: int
    boundary_edges: int
    boundary_loops: int
    non_manifold_edges: int
    unpaired_at_non_manifold_edges: int
    non_manifold_vertices: int
    degenerate_faces: int
    flat_faces: int
    duplicate_faces: int
    double_wall_faces: int
    consistently_oriented: bool
    orientation: Optional[str]
    winding: Optional[str]
    shells: int
    cavities: int
    overlapping_objects: list[dict[str, Any]]
    """Objects (of a 3MF or glTF) that share volume: {'objects': [name, name], 'nested': bool}."""
    self_intersections: Optional[int]
    euler_characteristic: int
    solid_volume: float
    volume_uncertainty: float

class MassProperties(_CheckFacts):
    """Volume, area, centroid and inertia, named as `meshvol volume --json`'s keys.

    Checked (the default), the check's facts are attributes too, as in the command's
    JSON; unchecked (check=False) they are absent."""

    file: Optional[str]
    format: Optional[str]
    format_source: Optional[str]
    vertex_count: int
    """The key `vertices` of the JSON (mp.vertices: deprecated, warns)."""
    units: Optional[dict[str, Any]]
    """Names of the reported units (length, area, volume, file, file_declared)."""
    overlapping_shells: list[list[int]]
    intersection_examples: list[list[int]]
    face_count: int
    """The key `faces` of the JSON (mp.faces: deprecated, warns)."""
    triangles: int
    triangle_count: int
    volume: float
    signed_volume: float
    volume_error_bound: float
    exact: bool
    area: float
    """The surface's own area (caps over holes left out)."""
    cap_area: float
    """The area of the caps over holes: with area, the solid's boundary."""
    density: float
    density_unit: Optional[str]
    """The density's unit (None: mass in the file's units cubed times the density)."""
    mass: float
    mass_unit: Optional[str]
    warnings: list[str]
    """Why the measured solid may not be the one meant (the command's warnings)."""
    @property
    def centroid(self) -> Optional[_F64]:
        """Shape (3,); None when the volume is zero."""
    @property
    def inertia(self) -> _F64:
        """Shape (3, 3), about the centroid, scaled by density."""
    @property
    def principal_moments(self) -> _F64:
        """Shape (3,), ascending, scaled by density."""
    @property
    def principal_axes(self) -> _F64:
        """Shape (3, 3): row k is the axis of principal_moments[k]."""
    @property
    def bounds(self) -> Optional[_F64]:
        """Shape (2, 3): [min, max] corners of the vertices' bounding box."""
    @property
    def shell_details(self) -> list[Shell]:
        """Each shell's facts (checked; [] with check=False)."""
    def to_urdf(self) -> str:
        """URDF's <inertial> element (report in metres: units="mm:m"; density in kg/m³)."""
    def to_sdf(self) -> str:
        """SDF's <inertial> element."""
    def to_mjcf(self) -> str:
        """MuJoCo's <inertial pos mass fullinertia> element."""
    timings: _Timings
    """With timings=True: the stages' {stage, wall_s, cpu_s} (else absent)."""
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol volume --json`."""

class Shell:
    """One connected component of a checked mesh."""

    face_count: int
    """The key `faces` of the JSON (shell.faces: deprecated, warns)."""
    closed: bool
    orientable: bool
    volume: float
    cavity: bool
    parent: Optional[int]
    wound_outward: Optional[bool]
    boundary_loops: int
    euler_characteristic: int
    genus: Optional[int]
    def __getitem__(self, key: str) -> Any: ...
    def to_dict(self) -> dict[str, Any]: ...

class Check(_CheckFacts):
    """The facts of `meshvol check`, named as its JSON keys."""

    file: Optional[str]
    format: Optional[str]
    units: Optional[dict[str, Any]]
    """Names of the reported units; None (the file's own units) for a check."""
    warnings: list[str]
    shell_details: list[Shell]
    overlapping_shells: list[Tuple[int, int]]
    intersection_examples: list[Tuple[int, int]]
    repairs: Tuple[int, int, int]
    def mass_properties(
        self,
        density: _Density = 1.0,
        exact: bool = False,
        units: Optional[str] = None,
        timings: bool = False,
    ) -> MassProperties:
        """Mass properties of the repaired solid (`meshvol volume`)."""
    def solid_mesh(self, caps: bool = False) -> Mesh:
        """The repaired solid as a welded mesh (`meshvol repair`)."""
    timings: _Timings
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol check --json`."""

class Profile:
    """Volume below each level (`meshvol profile --json`'s keys)."""
    units: Optional[dict[str, Any]]
    """Names of the reported units; None: the file's own units."""

    axis: str
    file: Optional[str]
    warnings: list[str]
    timings: _Timings
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol profile --json`."""
    @property
    def levels(self) -> _F64: ...
    @property
    def volume_below(self) -> _F64: ...
    @property
    def slab_volume(self) -> _F64: ...
    @property
    def section_area(self) -> _F64: ...

class Union:
    """The union's volume as a certified interval (`meshvol union --json`'s keys)."""
    units: Optional[dict[str, Any]]
    """Names of the reported units; None: the file's own units."""

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
    warnings: list[str]
    file: str
    """The meshes' names (their files, or 'mesh'), joined by ', '."""
    files: list[str]
    body_names: list[str]
    grid: list[int]
    seconds: float
    timings: _Timings
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol union --json`."""

class Intersection:
    """The intersection of two bodies, certified (`meshvol intersect --json`'s keys)."""
    units: Optional[dict[str, Any]]
    """Names of the reported units; None: the file's own units."""

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
    warnings: list[str]
    file: str
    """The meshes' names (their files, or 'mesh'), joined by ', '."""
    files: list[str]
    grid: list[int]
    seconds: float
    timings: _Timings
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol intersect --json`."""
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

class AreaProperties:
    """Area, perimeter, centroid and second moments of plane polygons."""
    units: Optional[dict[str, Any]]
    """Names of the reported units; None: the file's own units."""

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
    warnings: list[str]
    timings: _Timings
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol area --json`."""
    @property
    def centroid(self) -> Optional[_F64]:
        """Shape (2,); None when the area is zero."""
    @property
    def principal_moments(self) -> _F64:
        """Shape (2,), ascending (as MassProperties')."""
    @property
    def principal_axes(self) -> _F64:
        """Shape (2, 2): row k is the axis of principal_moments[k]."""

class Below:
    """The part of a solid below a plane (`meshvol below --json`'s keys)."""
    units: Optional[dict[str, Any]]
    """Names of the reported units; None: the file's own units."""

    file: Optional[str]
    level: float
    volume: float
    wetted_area: float
    section_area: float
    warnings: list[str]
    @property
    def normal(self) -> _F64:
        """Shape (3,): the plane's unit normal."""
    @property
    def centroid(self) -> Optional[_F64]:
        """Shape (3,): the centre of buoyancy; None without volume."""
    @property
    def section_centroid(self) -> Optional[_F64]:
        """Shape (3,): the waterplane's centroid; None without a section."""
    timings: _Timings
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol below --json`."""

class CutFill:
    """Cut and fill between two surfaces (`meshvol cutfill --json`'s keys)."""
    units: Optional[dict[str, Any]]
    """Names of the reported units; None: the file's own units."""

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
    warnings: list[str]
    timings: _Timings
    @property
    def footprint_bounds(self) -> Optional[_F64]:
        """Shape (2, 2): [[x0, y0], [x1, y1]]; None without a footprint."""
    @property
    def cut_cells(self) -> Optional[_F64]:
        """Shape (nx, ny): cut volume per plan cell; None without cells or pitch."""
    @property
    def fill_cells(self) -> Optional[_F64]:
        """Shape (nx, ny): fill volume per plan cell; None without cells or pitch."""
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol cutfill --json`."""

class Hull:
    """A convex hull (`meshvol hull --json`'s keys) and its mesh."""
    units: Optional[dict[str, Any]]
    """Names of the reported units; None: the file's own units."""

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
    warnings: list[str]
    timings: _Timings
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol hull --json`."""
    @property
    def centroid(self) -> Optional[_F64]: ...

class Section:
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
    units: Optional[dict[str, Any]]
    warnings: list[str]
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
    timings: _Timings
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol section --json`."""

class CutCells(dict[str, _F64]):
    """The cut-cell geometry of Mesh.cells: a dict of float64 arrays (docs/cells.md)."""

    origin: _F64
    """Shape (3,): the lower corner of cell (0, 0, 0)."""
    spacing: _F64
    """Shape (3,): the cells' size."""
    def __init__(self, arrays: Mapping[str, _F64], origin: _ArrayLike, spacing: _ArrayLike) -> None: ...
    @property
    def shape(self) -> Tuple[int, ...]: ...
    def to_xarray(self) -> Any:
        """An xarray.Dataset: dims x, y, z (cells), x_face, y_face, z_face, component."""

class Grid:
    """Cell volumes (Mesh.grid) and where the cells are; np.asarray(grid) is values."""

    def __init__(
        self, values: _ArrayLike, origin: _ArrayLike, spacing: _ArrayLike, fraction: bool = False
    ) -> None: ...
    @property
    def values(self) -> _F64:
        """Shape (nx, ny, nz)."""
    @property
    def origin(self) -> _F64:
        """Shape (3,): the lower corner of cell (0, 0, 0)."""
    @property
    def spacing(self) -> _F64:
        """Shape (3,): the cells' size."""
    @property
    def bounds(self) -> _F64:
        """Shape (2, 3): the box the cells cover."""
    @property
    def fraction(self) -> bool: ...
    @property
    def timings(self) -> _Timings:
        """With Mesh.grid(timings=True): the stages (else absent)."""
    @property
    def cell_volume(self) -> float: ...
    @property
    def shape(self) -> Tuple[int, ...]: ...
    @property
    def dtype(self) -> np.dtype[Any]: ...
    def centers(self) -> Tuple[_F64, _F64, _F64]:
        """The cells' centres along x, y and z."""
    def to_xarray(self, name: Optional[str] = None) -> Any:
        """An xarray.DataArray with dims ('x', 'y', 'z') (needs xarray)."""
    def __array__(self, dtype: Any = None, copy: Optional[bool] = None) -> _F64: ...
    def __getitem__(self, key: Any) -> Any: ...
    def __len__(self) -> int: ...
    def __getattr__(self, name: str) -> Any: ...

def load(file: _Union[_Path, BinaryIO], file_type: Optional[str] = None) -> Mesh:
    """Read a mesh file (STL, OBJ, OFF, PLY, 3MF, glTF/GLB) from a path or a binary
    file object; file_type names the format ('stl', 'obj', ...) when the name does not."""

def measure(
    paths: _Union[_Path, Iterable[_Path]],
    workers: Optional[int] = None,
    check: bool = True,
    density: _Density = 1.0,
    units: Optional[str] = None,
    exact: bool = False,
    *,
    recursive: bool = True,
    glob: _Union[str, Iterable[str], None] = None,
) -> "pandas.DataFrame":
    """`meshvol volume --json` of many files as a DataFrame, one row a file, columns
    flattened as pandas.json_normalize(sep='.'); failed files have 'error'.
    measure(folder) is `meshvol volume -r folder --json`: the same rows, in order."""

def union(
    meshes: _Union[Any, Iterable[Any]],
    tolerance: float = 1e-6,
    check: bool = True,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> Union:
    """Volume of the union of closed bodies, certified (`meshvol union`)."""

def intersection(
    a: Any,
    b: Any,
    pose_a: Optional[_ArrayLike] = None,
    pose_b: Optional[_ArrayLike] = None,
    tolerance: float = 1e-9,
    check: bool = True,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> Intersection:
    """Volume of the intersection of two bodies, each placed by an optional 4×4 rigid
    pose, certified, with IoU, Dice and moments (`meshvol intersect`)."""

def intersections(
    a: Any,
    b: Any,
    poses_a: Optional[_ArrayLike] = None,
    poses_b: Optional[_ArrayLike] = None,
    tolerance: float = 1e-9,
    check: bool = True,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
) -> list[Intersection]:
    """`intersection` for many poses in parallel: poses_a/poses_b each None, one 4×4
    rigid transform, or an (N, 4, 4) array; one Intersection per pose."""

def polygon_area(
    exterior: _Union[_ArrayLike, Mapping[str, Any], Any],
    holes: Optional[Iterable[_ArrayLike]] = None,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> AreaProperties:
    """Area properties of a polygon with holes, or of a GeoJSON (Multi)Polygon."""

def convex_hull(
    points: _ArrayLike,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> Hull:
    """The convex hull of an (n, 3) point array (`meshvol hull`)."""

def hull_volume(points: _ArrayLike) -> float:
    """The volume of the convex hull of an (n, 3) point array."""

def volume(vertices: _ArrayLike, faces: _Faces, check: bool = True) -> Tuple[float, float]:
    """(volume, volume_error_bound) of a mesh given as arrays.

    check=True: the checked solid's (never negative), as Mesh(vertices, faces).mass_properties().
    check=False: the signed volume of the surface as wound, in one pass; C-contiguous float64 vertices with
    int32/int64/uint32/uint64 (m, 3) faces are read in place (no copy), with the GIL held.

    >>> import numpy as np, meshvol
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)
    >>> meshvol.volume(v, f, check=False)[0] == 1 / 6
    True
    """

def cutfill(
    existing: _Union[str, "os.PathLike[str]", Any],
    design: _Union[str, "os.PathLike[str]", Any, None] = None,
    level: Optional[float] = None,
    cells: Optional[_ArrayLike] = None,
    pitch: Optional[float] = None,
    units: Optional[str] = None,
    density: Optional[_Density] = None,
    timings: bool = False,
) -> CutFill:
    """Cut and fill between an existing surface and a design or level (`meshvol cutfill`)."""
