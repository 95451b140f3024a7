"""Topology check by a peer, fresh process: load a mesh file, answer "does it bound a volume?".

Usage: check_peer.py MODE FILE, MODE one of
  trimesh            trimesh.load (merges vertices) + is_watertight, is_winding_consistent,
                     body_count
  open3d             read_triangle_mesh + remove_duplicated_vertices + is_edge_manifold(no
                     boundary) + is_vertex_manifold + is_orientable + cluster_connected_triangles
  open3d-watertight  the same read + is_watertight(), which adds an all-pairs
                     self-intersection test
  pymeshlab          load_new_mesh + get_topological_measures (two-manifold, boundary edges,
                     connected components)
Prints one JSON object: watertight, winding_consistent, bodies, self_intersecting (null
where the tool does not answer), kernel_s (the checks alone, after loading).
"""
import json
import sys
import time

mode, path = sys.argv[1], sys.argv[2]
out = {"mode": mode, "watertight": None, "winding_consistent": None, "bodies": None,
       "self_intersecting": None}
if mode == "trimesh":
    import trimesh

    mesh = trimesh.load(path)
    t0 = time.perf_counter()
    out.update(watertight=bool(mesh.is_watertight),
               winding_consistent=bool(mesh.is_winding_consistent),
               bodies=int(mesh.body_count))
elif mode in ("open3d", "open3d-watertight"):
    import numpy as np
    import open3d as o3d

    o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
    mesh = o3d.io.read_triangle_mesh(path)
    mesh.remove_duplicated_vertices()
    t0 = time.perf_counter()
    if mode == "open3d":
        edge = mesh.is_edge_manifold(allow_boundary_edges=False)
        vert = mesh.is_vertex_manifold()
        clusters = np.asarray(mesh.cluster_connected_triangles()[0])
        out.update(watertight=bool(edge and vert), winding_consistent=bool(mesh.is_orientable()),
                   bodies=int(len(np.unique(clusters))))
    else:
        w = bool(mesh.is_watertight())
        out.update(watertight=w)
elif mode == "pymeshlab":
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(path)
    t0 = time.perf_counter()
    g = ms.get_topological_measures()
    out.update(watertight=bool(g["is_mesh_two_manifold"] and g["boundary_edges"] == 0),
               bodies=int(g["connected_components_number"]))
else:
    sys.exit(f"unknown mode {mode}")
out["kernel_s"] = time.perf_counter() - t0
print(json.dumps(out))
