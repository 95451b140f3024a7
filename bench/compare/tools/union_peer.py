"""Union volume by a peer, fresh process: read binary STLs, unite them, print the volume.

Usage: union_peer.py [MODE] FILE...  MODE one of
  manifold3d (default)  Manifold(mesh) per body, Manifold.batch_boolean(OpType.Add), volume()
  trueform              tf.read_stl, then boolean_union folded over the bodies one at a time
                        (it is a two-operand call), signed_volume of the result
  meshlib               mrmeshpy.loadMesh, then boolean(A, B, BooleanOperation.Union) folded
                        over the bodies, Mesh.volume() of the result
Prints one JSON object (volume, kernel_s: the builds, the booleans and the volume, after
reading).
"""
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

args = sys.argv[1:]
mode = "manifold3d"
if args and args[0] in ("manifold3d", "trueform", "meshlib"):
    mode, args = args[0], args[1:]
if mode == "manifold3d":
    from manifold3d import Manifold, Mesh, OpType

    from meshread import read_stl_binary_indexed

    meshes = [read_stl_binary_indexed(p) for p in args]
    t0 = time.perf_counter()
    bodies = [Manifold(Mesh(vert_properties=v, tri_verts=f)) for v, f in meshes]
    volume = Manifold.batch_boolean(bodies, OpType.Add).volume()
elif mode == "trueform":
    import trueform as tf

    meshes = [tf.read_stl(p) for p in args]
    t0 = time.perf_counter()
    acc = tf.Mesh(*meshes[0])
    for faces, points in meshes[1:]:
        (rf, rp), *_ = tf.boolean_union(acc, tf.Mesh(faces, points))
        acc = tf.Mesh(rf, rp)
    volume = tf.signed_volume(acc)
else:
    from meshlib import mrmeshpy as mr

    meshes = [mr.loadMesh(p) for p in args]
    t0 = time.perf_counter()
    acc = meshes[0]
    for m in meshes[1:]:
        res = mr.boolean(acc, m, mr.BooleanOperation.Union)
        if not res.valid():
            print(json.dumps({"refused": f"boolean failed: {res.errorString}"}))
            sys.exit(0)
        acc = res.mesh
    volume = acc.volume()
kernel = time.perf_counter() - t0
print(json.dumps({"volume": float(volume), "kernel_s": kernel, "bodies": len(args)}))
