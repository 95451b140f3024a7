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
  trueform           read_stl (indexed) + Mesh + is_closed, is_manifold, has_self_intersections
                     (exact, stops at the first contact), label_connected_components over the
                     mesh's manifold_edge_link
  meshlib            mrmeshpy.loadMesh (half-edge topology) + topology.findNumHoles,
                     findSelfCollidingTriangles (any pair), MeshComponents.getNumComponents
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
elif mode == "trueform":
    import trueform as tf

    if path.lower().endswith(".obj"):
        faces, points = tf.read_obj(path, ngon=3)
    else:
        faces, points = tf.read_stl(path)
    t0 = time.perf_counter()
    mesh = tf.Mesh(faces, points)
    closed, manifold = bool(tf.is_closed(mesh)), bool(tf.is_manifold(mesh))
    bodies, _ = tf.label_connected_components(mesh.manifold_edge_link)
    out.update(watertight=closed and manifold, bodies=int(bodies),
               self_intersecting=bool(tf.has_self_intersections(mesh)))
elif mode == "meshlib":
    from meshlib import mrmeshpy as mr

    mesh = mr.loadMesh(path)
    t0 = time.perf_counter()
    holes = int(mesh.topology.findNumHoles())
    si = bool(mr.findSelfCollidingTriangles(mr.MeshPart(mesh), None))
    out.update(watertight=holes == 0, bodies=int(mr.MeshComponents.getNumComponents(mesh)),
               self_intersecting=si)
else:
    sys.exit(f"unknown mode {mode}")
out["kernel_s"] = time.perf_counter() - t0
print(json.dumps(out))
