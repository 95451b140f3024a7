"""Type stubs for meshvol (the runtime objects carry the full docstrings): the errors,
Mesh, MassProperties, Check and Shell of the extension module are written here, its
other reports and its functions in _meshvol.pyi; measure, Grid, CutCells and the OSError
classes are typed Python (_batch.py, _grid.py, _errors.py). Checked against the runtime
by mypy's stubtest (tests/test_typing.py)."""

import os
from typing import Any, Literal, Optional, Tuple, Union as _Union, final

import numpy as np
import numpy.typing as npt

from ._batch import measure as measure
from ._errors import (
    MeshFileNotFoundError as MeshFileNotFoundError,
    MeshIsADirectoryError as MeshIsADirectoryError,
    MeshOSError as MeshOSError,
    MeshPermissionError as MeshPermissionError,
)
from ._grid import CutCells as CutCells, Grid as Grid
from ._meshvol import (
    __version__ as __version__,
    Profile as Profile,
    Union as Union,
    AreaProperties as AreaProperties,
    Hull as Hull,
    Below as Below,
    CutFill as CutFill,
    Intersection as Intersection,
    Section as Section,
    load as load,
    union as union,
    intersection as intersection,
    intersections as intersections,
    polygon_area as polygon_area,
    convex_hull as convex_hull,
    hull_volume as hull_volume,
    cutfill as cutfill,
    volume as volume,
)
# The aliases _meshvol.pyi types its functions with (private: not re-exported).
from ._meshvol import _ArrayLike, _Density, _F64, _Faces, _Timings

__all__ = [
    "AreaProperties",
    "Below",
    "Check",
    "CutCells",
    "CutFill",
    "Grid",
    "Hull",
    "Intersection",
    "InvalidMeshError",
    "LossyWriteError",
    "MassProperties",
    "Mesh",
    "MeshError",
    "MeshFileNotFoundError",
    "MeshIsADirectoryError",
    "MeshOSError",
    "MeshPermissionError",
    "MeshWarning",
    "Profile",
    "ReadError",
    "Section",
    "Shell",
    "Union",
    "__version__",
    "convex_hull",
    "cutfill",
    "hull_volume",
    "intersection",
    "intersections",
    "load",
    "measure",
    "polygon_area",
    "union",
    "volume",
]

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

class InvalidMeshError(MeshError):
    """Arrays that cannot be used as given: shape, dtype, non-finite value, index range."""

class LossyWriteError(MeshError):
    """Mesh.save refused a file that does not read back as the mesh's solid (float32)."""

class MeshWarning(UserWarning):
    """A measurement of a solid that may not be the one meant (open, overlapping, ...)."""

@final
class Mesh:
    """A surface mesh: float64 vertices and faces (triangles or polygons) indexing them.

    Mesh(vertices, faces) copies and checks the arrays; Mesh(obj) takes obj.vertices and
    obj.faces (a trimesh.Trimesh, another Mesh). A Mesh never changes once built.
    """

    def __new__(cls, vertices: Any, faces: Optional[_Faces] = None) -> Mesh: ...
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
        """Volume, area, centroid and inertia of the checked solid (`meshvol volume`).

        Parameters
        ----------
        density : float or str
            2.5, or with a unit: '7.85g/cm3' (--density).
        exact : bool
            The volume in exact arithmetic, rounded once (--exact).
        check : bool
            True: the checked solid; False: the surface as wound (--no-check).
        units : str, optional
            As --units: 'mm:cm', ':in', 'm'.
        timings : bool
            Add `timings`, the stages with wall and CPU seconds (--timings).

        Returns
        -------
        MassProperties
        """
    def check(
        self,
        weld_tolerance: Optional[float] = None,
        intersections: bool = True,
        units: Optional[str] = None,
        density: Optional[_Density] = None,
        timings: bool = False,
    ) -> Check:
        """Topology facts (`meshvol check`).

        Parameters
        ----------
        weld_tolerance : float, optional
            Weld vertices this close (--weld-tolerance); None: equal ones only.
        intersections : bool
            Search for crossing faces (False: --no-intersections).
        units, density : str, optional
            As --units and --density.
        timings : bool
            Add `timings`.

        Returns
        -------
        Check
        """
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
        """The solid's volume in each cell of a grid (`meshvol grid`).

        Parameters
        ----------
        cells : array_like of 3 int, optional
            Cells along x, y, z (or give pitch).
        bounds : array_like (2, 3), optional
            The grid's box; default the solid's bounding box.
        fraction : bool
            Each cell's filled fraction instead of its volume.
        pitch : float or array_like of 3, optional
            The cells' size (whole cells covering bounds).
        check : bool
            True: the checked solid; False: the surface as wound.
        region : array_like (3, 2), optional
            Only the block ((i0, i1), (j0, j1), (k0, k1)): the same bits as the whole's.
        units, density : str, optional
            As --units and --density (density: the cells hold masses).
        timings : bool
            Add `timings`.
        backend : {'auto', 'cpu', 'opencl'}
            As --backend: the same bits.
        opencl_device : int, optional
            As --opencl-device.

        Returns
        -------
        Grid
        """
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
        """The cut-cell geometry on a grid (`meshvol grid --moments`).

        Parameters
        ----------
        cells, bounds, pitch, check, region, units, backend, opencl_device
            As for grid.
        second_moments : bool
            Add `inertia`, each cell's solid's inertia about its centroid.
        face_centroids : bool
            Add aperture_x_centroid, aperture_y_centroid, aperture_z_centroid.
        moments : True
            False is a ValueError: grid gives the volumes alone.

        Returns
        -------
        CutCells
            volume, fraction, centroid, boundary_area, boundary_vector,
            boundary_centroid, aperture_x, aperture_y, aperture_z (and the extras).
        """
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
        plane: Optional[_Union[str, _ArrayLike]] = None,
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
        """The cross-section by a plane (`meshvol section`).

        Parameters
        ----------
        plane : str or array_like
            'z=H' ('x=H', 'y=H'), [point, normal], or (nx, ny, nz, d).
        check : bool
            True: the checked solid; False: the surface as wound.
        units : str, optional
            As --units.
        density : float or str, optional
            A mass per area ('62.8kg/m2'): `mass`, a sheet's with this outline.
        timings : bool
            Add `timings`.

        Returns
        -------
        Section
        """
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

@final
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
    """With timings=True: the stages' {stage, wall_s, cpu_s, peak_mb} (else absent)."""
    def to_dict(self) -> dict[str, Any]:
        """Plain values with the keys of `meshvol volume --json`."""

@final
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
    def __getitem__(self, key: str, /) -> Any: ...
    def to_dict(self) -> dict[str, Any]: ...

@final
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
