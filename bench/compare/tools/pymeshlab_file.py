"""End-to-end PyMeshLab: MeshSet.load_new_mesh + get_geometric_measures, as JSON.

Run as a fresh process by compare.py; the whole process is what gets timed. MeshLab gives
a volume only for a closed two-manifold mesh (no `mesh_volume` key otherwise): that is
printed as {"refused": reason}.
"""
import json
import sys

import pymeshlab

ms = pymeshlab.MeshSet()
ms.load_new_mesh(sys.argv[1])
g = ms.get_geometric_measures()
m = ms.current_mesh()
if "mesh_volume" not in g:
    print(json.dumps({"refused": "no mesh_volume from get_geometric_measures (mesh not closed "
                      "two-manifold)", "triangles": m.face_number()}))
    sys.exit(0)
print(json.dumps({
    "volume": float(g["mesh_volume"]),
    "area": float(g["surface_area"]),
    "centroid": [float(x) for x in g["center_of_mass"]],
    "inertia": [[float(x) for x in row] for row in g["inertia_tensor"]],
    "triangles": int(m.face_number()),
    "vertices": int(m.vertex_number()),
}))
