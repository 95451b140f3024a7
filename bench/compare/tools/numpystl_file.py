"""End-to-end numpy-stl: Mesh.from_file + get_mass_properties, printed as JSON.

Run as a fresh process by compare.py; the whole process is what gets timed.
"""
import json
import sys

from stl import mesh as stl_mesh

m = stl_mesh.Mesh.from_file(sys.argv[1])
volume, cog, inertia = m.get_mass_properties()
print(json.dumps({
    "volume": float(volume),
    "centroid": [float(x) for x in cog],
    "inertia": [[float(x) for x in row] for row in inertia],
    "area": float(m.areas.sum()),
    "triangles": int(len(m.vectors)),
}))
