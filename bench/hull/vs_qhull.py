#!/usr/bin/env python3
"""Cross-check `meshvol hull` against qhull (scipy.spatial.ConvexHull), and time both.

Usage: bench/out/venv/bin/python bench/hull/vs_qhull.py [path/to/meshvol] [--points N]

For each cloud (points in a ball, on a sphere, a lattice with many coplanar points,
each also offset far from the origin) it writes a .xyz file, runs `meshvol hull --json`
and compares volume and area with qhull's. qhull works in the input coordinates, so far
from the origin its own result loses digits: the reference there is qhull on the same
cloud at the origin (the offset clouds are exact translates: coordinates on a 2^-20 grid).
Exits 1 when a relative difference exceeds 1e-12.
"""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.spatial import ConvexHull


def clouds(n, rng):
    grid = lambda a: np.round(a * 2.0**20) / 2.0**20
    ball = rng.normal(size=(n, 3))
    ball *= (rng.random(n) ** (1 / 3) / np.linalg.norm(ball, axis=1))[:, None]
    sphere = rng.normal(size=(n, 3))
    sphere /= np.linalg.norm(sphere, axis=1)[:, None]
    k = max(2, round(n ** (1 / 3)))
    lattice = np.stack(np.meshgrid(*[np.arange(k, dtype=float)] * 3), -1).reshape(-1, 3)
    for name, pts in [("ball", grid(ball * 10)), ("sphere", grid(sphere * 10)), ("lattice", lattice)]:
        for offset in [0.0, 1e5, 1e7]:
            yield f"{name}@{offset:g}", pts, pts + offset


def main():
    args = sys.argv[1:]
    n = 100_000
    if "--points" in args:
        i = args.index("--points")
        n = int(args[i + 1])
        del args[i : i + 2]
    exe = args[0] if args else "target/release/meshvol"
    rng = np.random.default_rng(1)
    worst = 0.0
    print(f"{'cloud':<16} {'points':>8} {'meshvol s':>9} {'qhull s':>8} {'volume rel. diff':>17} {'area rel. diff':>15}")
    with tempfile.TemporaryDirectory() as tmp:
        for name, at_origin, pts in clouds(n, rng):
            path = os.path.join(tmp, "cloud.xyz")
            np.savetxt(path, pts, fmt="%.17g")
            start = time.perf_counter()
            out = subprocess.run([exe, "hull", "--json", path], capture_output=True, text=True, check=True)
            ours_s = time.perf_counter() - start
            ours = json.loads(out.stdout)
            start = time.perf_counter()
            ConvexHull(pts)
            qhull_s = time.perf_counter() - start
            ref = ConvexHull(at_origin)
            dv = abs(ours["volume"] - ref.volume) / ref.volume
            da = abs(ours["area"] - ref.area) / ref.area
            worst = max(worst, dv, da)
            print(f"{name:<16} {len(pts):>8} {ours_s:>9.3f} {qhull_s:>8.3f} {dv:>17.2e} {da:>15.2e}")
    print(f"worst relative difference {worst:.2e}")
    return 0 if worst <= 1e-12 else 1


if __name__ == "__main__":
    sys.exit(main())
