"""End-to-end MeshLib: mrmeshpy.loadMesh (STL, ASCII STL, OBJ, PLY) + Mesh.volume(), as JSON.

Run as a fresh process by compare.py; the whole process is what gets timed. loadMesh welds
an STL's corners into MeshLib's half-edge topology. MeshLib's coordinates are float32;
Mesh.volume() sums in double. A mesh with holes is refused (volume() of an open surface is
not a volume). kernel_s: volume() (and the hole count), after loading.
"""
import json
import sys
import time

from meshlib import mrmeshpy as mr

mesh = mr.loadMesh(sys.argv[1])
t0 = time.perf_counter()
holes = mesh.topology.findNumHoles()
if holes:
    print(json.dumps({"refused": f"{holes} holes (open surface)",
                      "triangles": int(mesh.topology.numValidFaces())}))
    sys.exit(0)
volume = mesh.volume()
kernel = time.perf_counter() - t0
print(json.dumps({"volume": float(volume), "area": float(mesh.area()),
                  "triangles": int(mesh.topology.numValidFaces()),
                  "vertices": int(mesh.topology.numValidVerts()), "kernel_s": kernel}))
