"""End-to-end trimesh: load a mesh file, compute its mass properties, print them as JSON.

Run as a fresh process by compare.py; the whole process is what gets timed.
"""
import json
import sys

import trimesh

mesh = trimesh.load(sys.argv[1])
if isinstance(mesh, trimesh.Scene):  # multi-object files load as a Scene
    mesh = mesh.to_geometry() if hasattr(mesh, "to_geometry") else mesh.dump(concatenate=True)
mp = mesh.mass_properties
get = (lambda k: getattr(mp, k)) if hasattr(mp, "volume") else (lambda k: mp[k])
inertia = get("inertia")
print(json.dumps({
    "volume": float(get("volume")),
    "centroid": [float(x) for x in get("center_mass")],
    "inertia": [[float(x) for x in row] for row in inertia],
    "area": float(mesh.area),
    "triangles": int(len(mesh.faces)),
    "vertices": int(len(mesh.vertices)),
}))
