"""End-to-end trueform: read a mesh file (STL or OBJ), signed_volume, print it as JSON.

Run as a fresh process by compare.py; the whole process is what gets timed. trueform's
readers return an indexed mesh (float32 points, int32 faces); `tf.signed_volume(Mesh)`
sums the divergence theorem in the points' precision (float32), so its relative error is
of the order of float32's. kernel_s: Mesh + signed_volume, after reading.
"""
import json
import sys
import time

import trueform as tf

path = sys.argv[1]
if path.lower().endswith(".obj"):
    faces, points = tf.read_obj(path, ngon=3)
else:
    faces, points = tf.read_stl(path)
t0 = time.perf_counter()
mesh = tf.Mesh(faces, points)
volume = tf.signed_volume(mesh)
kernel = time.perf_counter() - t0
print(json.dumps({"volume": float(volume), "triangles": int(len(faces)),
                  "vertices": int(len(points)), "kernel_s": kernel}))
