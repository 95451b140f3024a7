"""meshvol: exact, fast volume, area, centroid and inertia of solids bounded by meshes.

Build a Mesh from NumPy arrays (or anything with .vertices and .faces, such as a
trimesh.Trimesh), or read one with load(); then measure it:

>>> import numpy as np, meshvol
>>> corners = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], float)
>>> hull = meshvol.convex_hull(corners)
>>> hull.volume
1.0
>>> mesh = hull.mesh
>>> mp = mesh.mass_properties()
>>> float(mp.volume), mp.centroid.tolist()
(1.0, [0.5, 0.5, 0.5])
>>> mesh.check().verdict
'closed, 1 shell: volume is exact'

The answers and names are those of the meshvol command: Mesh.mass_properties() is
`meshvol volume`, Mesh.check() is `meshvol check`, Mesh.grid() is `meshvol grid`,
Mesh.profile() is `meshvol profile`, union() is `meshvol union`, intersection() is
`meshvol intersect` (with optional rigid poses), polygon_area() is
`meshvol area`, convex_hull() is `meshvol hull` and cutfill() is `meshvol cutfill`
(which reads surfaces as terrains, not solids). Like the commands, every measure of a
solid takes the checked solid (welded, shells turned outward, cavities subtracted,
holes capped) and issues a MeshWarning naming why that solid may not be the one
meant; check=False measures the surface as wound (`--no-check`). Errors raise
MeshError (a ValueError) or one of its subclasses, ReadError, InvalidMeshError and
LossyWriteError, with the command's messages. Mesh.save() writes a mesh and reads it
back: a file that is not the same solid (float32 STL far from the origin) is refused,
as `meshvol repair -o` refuses it. Computations release the GIL, so threads measure in
parallel.
"""

from ._meshvol import (
    AreaProperties,
    Below,
    Check,
    CutFill,
    Hull,
    Intersection,
    InvalidMeshError,
    LossyWriteError,
    MassProperties,
    Mesh,
    MeshError,
    MeshWarning,
    Profile,
    ReadError,
    Section,
    Shell,
    Union,
    __version__,
    convex_hull,
    cutfill,
    hull_volume,
    intersection,
    intersections,
    load,
    polygon_area,
    union,
    volume,
)
from ._batch import measure
from ._errors import MeshFileNotFoundError, MeshIsADirectoryError, MeshOSError, MeshPermissionError
from ._grid import CutCells, Grid

# The public names are those imported above, and __version__ (`from meshvol import *`
# gives them); __init__.pyi lists them for type checkers, and stubtest checks the two agree.
__all__ = sorted([name for name in globals() if not name.startswith("_")] + ["__version__"])
