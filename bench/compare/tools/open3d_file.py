"""End-to-end Open3D: read_triangle_mesh + remove_duplicated_vertices + get_volume, as JSON.

Run as a fresh process by compare.py; the whole process is what gets timed. STL files are
read as triangle soup, and get_volume() refuses a mesh that is not watertight, so the
duplicated vertices are merged first, as Open3D's documentation does. get_volume() then
checks watertightness itself, which includes an all-pairs self-intersection test.
A refusal prints {"refused": reason}.
"""
import json
import re
import sys

import open3d as o3d

o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
mesh = o3d.io.read_triangle_mesh(sys.argv[1])
read_vertices = len(mesh.vertices)
mesh.remove_duplicated_vertices()
try:
    volume = mesh.get_volume()
except RuntimeError as e:
    reason = re.sub(r"\x1b\[[0-9;]*m", "", str(e)).strip()
    reason = re.sub(r"^\[Open3D Error\] \(.*?\) \S+:\d+: ", "", reason)
    print(json.dumps({"refused": reason}))
    sys.exit(0)
print(json.dumps({
    "volume": float(volume),
    "area": float(mesh.get_surface_area()),
    "triangles": len(mesh.triangles),
    "vertices_read": read_vertices,
    "vertices": len(mesh.vertices),
}))
