"""Union volume by manifold3d, fresh process: read binary STLs, batch_boolean(Add), volume().

Usage: union_peer.py FILE... Prints one JSON object (volume, kernel_s: the Manifold builds,
the boolean and volume(), after reading).
"""
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from manifold3d import Manifold, Mesh, OpType  # noqa: E402

from meshread import read_stl_binary_indexed  # noqa: E402

meshes = [read_stl_binary_indexed(p) for p in sys.argv[1:]]
t0 = time.perf_counter()
bodies = [Manifold(Mesh(vert_properties=v, tri_verts=f)) for v, f in meshes]
volume = Manifold.batch_boolean(bodies, OpType.Add).volume()
kernel = time.perf_counter() - t0
print(json.dumps({"volume": float(volume), "kernel_s": kernel, "bodies": len(bodies)}))
