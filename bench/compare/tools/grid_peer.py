"""Per-cell volume peers of `meshvol grid`, fresh process. Prints one JSON object.

  grid_peer.py trimesh FILE PITCH
      trimesh.load + mesh.voxelized(PITCH).fill(): occupancy (filled voxels), not volumes.
  grid_peer.py manifold FILE CELLS.npy X0 Y0 Z0 H SAMPLE
      manifold3d: Manifold(mesh), then mesh ^ cube for SAMPLE random partial cells of the grid
      with origin (X0, Y0, Z0) and cubic cells of side H, the partial cells being those where
      meshvol's CELLS.npy (cell volumes) is strictly between empty and full. Reports the
      build time, the time per cell and the largest difference from meshvol's cell volumes.
"""
import json
import os
import sys
import time

import numpy as np

mode = sys.argv[1]
if mode == "trimesh":
    import trimesh

    path, pitch = sys.argv[2], float(sys.argv[3])
    mesh = trimesh.load(path)
    t0 = time.perf_counter()
    vox = mesh.voxelized(pitch=pitch).fill()
    kernel = time.perf_counter() - t0
    n = int(vox.filled_count)
    print(json.dumps({"filled": n, "pitch": pitch, "volume": n * pitch**3, "kernel_s": kernel}))
elif mode == "manifold":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from manifold3d import Manifold, Mesh

    from meshread import read_stl_binary_indexed

    path, npy = sys.argv[2], sys.argv[3]
    x0, y0, z0, h = (float(x) for x in sys.argv[4:8])
    sample = int(sys.argv[8])
    v, f = read_stl_binary_indexed(path)
    t0 = time.perf_counter()
    solid = Manifold(Mesh(vert_properties=v, tri_verts=f))
    status = str(solid.status()).split(".")[-1]
    build = time.perf_counter() - t0
    if status != "NoError":
        print(json.dumps({"refused": f"manifold3d status {status}"}))
        sys.exit(0)
    cells = np.load(npy, mmap_mode="r")
    cv = h**3
    frac = np.asarray(cells) / cv
    partial = np.argwhere((frac > 1e-9) & (frac < 1 - 1e-9))
    rng = np.random.default_rng(1)
    chosen = partial[rng.choice(len(partial), size=min(sample, len(partial)), replace=False)]
    t0 = time.perf_counter()
    diffs = []
    for i, j, k in chosen:
        box = Manifold.cube([h, h, h]).translate([x0 + i * h, y0 + j * h, z0 + k * h])
        diffs.append(abs((solid ^ box).volume() - float(cells[i, j, k])) / cv)
    per_cell = (time.perf_counter() - t0) / max(1, len(chosen))
    print(json.dumps({"build_s": build, "per_cell_s": per_cell, "partial": int(len(partial)),
                      "sampled": int(len(chosen)), "max_diff_of_cell": float(max(diffs, default=0)),
                      "kernel_s": build + per_cell * len(partial)}))
else:
    sys.exit(f"unknown mode {mode}")
