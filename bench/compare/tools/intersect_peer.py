"""Intersection volume by a peer, fresh process: read two binary STLs, intersect them,
print the volume.

Usage: intersect_peer.py MODE A.stl B.stl  MODE one of
  manifold3d  Manifold(mesh) per body, A ^ B, volume()
  trueform    tf.read_stl, boolean_intersection, signed_volume of the result
  meshlib     mrmeshpy.loadMesh, boolean(A, B, BooleanOperation.Intersection), Mesh.volume()
Prints one JSON object (volume, kernel_s: the builds, the boolean and the volume, after
reading).
"""
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

mode, a, b = sys.argv[1:4]
if mode == "manifold3d":
    from manifold3d import Manifold, Mesh

    from meshread import read_stl_binary_indexed

    meshes = [read_stl_binary_indexed(p) for p in (a, b)]
    t0 = time.perf_counter()
    ma, mb = (Manifold(Mesh(vert_properties=v, tri_verts=f)) for v, f in meshes)
    volume = (ma ^ mb).volume()
elif mode == "trueform":
    import trueform as tf

    (fa, pa), (fb, pb) = tf.read_stl(a), tf.read_stl(b)
    t0 = time.perf_counter()
    (rf, rp), *_ = tf.boolean_intersection(tf.Mesh(fa, pa), tf.Mesh(fb, pb))
    volume = tf.signed_volume(tf.Mesh(rf, rp))
elif mode == "meshlib":
    from meshlib import mrmeshpy as mr

    ma, mb = mr.loadMesh(a), mr.loadMesh(b)
    t0 = time.perf_counter()
    res = mr.boolean(ma, mb, mr.BooleanOperation.Intersection)
    if not res.valid():
        print(json.dumps({"refused": f"boolean failed: {res.errorString}"}))
        sys.exit(0)
    volume = res.mesh.volume()
else:
    sys.exit(f"unknown mode {mode}")
kernel = time.perf_counter() - t0
print(json.dumps({"volume": float(volume), "kernel_s": kernel}))
