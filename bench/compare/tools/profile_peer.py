"""Volume below each level along z by MeshLib, fresh process: the peer of `meshvol profile`.

Usage: profile_peer.py meshlib FILE LEVELS
  mrmeshpy.loadMesh, then for each of the LEVELS + 1 equally spaced levels from the mesh's
  lowest to its highest z, computeBasinVolume(mesh, all faces, level): the volume between
  the surface and the water plane below the level. On a closed outward-facing solid that is
  minus the solid's volume below the level, so its sign is flipped here.
Prints one JSON object: levels, volume_below, kernel_s (the basin volumes alone, after loading).
"""
import json
import sys
import time

from meshlib import mrmeshpy as mr

mode, path, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
if mode != "meshlib":
    sys.exit(f"unknown mode {mode}")
mesh = mr.loadMesh(path)
box = mesh.computeBoundingBox()
lo, hi = float(box.min.z), float(box.max.z)
levels = [lo + (hi - lo) * i / n for i in range(n + 1)]
t0 = time.perf_counter()
faces = mesh.topology.getValidFaces()
below = [-mr.computeBasinVolume(mesh, faces, z) for z in levels]
kernel = time.perf_counter() - t0
print(json.dumps({"levels": levels, "volume_below": below, "kernel_s": kernel}))
