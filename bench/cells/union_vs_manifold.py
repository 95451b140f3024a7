#!/usr/bin/env python3
"""The union's cut cells against a peer's union mesh: two overlapping UV spheres,
`meshvol grid A B --union --moments` against `meshvol grid U --moments` where U is
manifold3d's boolean union of A and B (float64 meshes). Prints, per array, the largest
difference over the cells (NaN face centroids must match).

Run with a Python that has manifold3d and numpy (the bench venv):

    cargo build --release -p meshvol-cli
    bench/out/venv/bin/python bench/cells/union_vs_manifold.py [--cells 17,13,15]
"""

import argparse
import math
import os
import subprocess
import tempfile

import manifold3d
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MESHVOL = os.path.join(ROOT, "target/release/meshvol")


def sphere(r, segments, rings, c):
    """A UV sphere: poles and rings of `segments` vertices, triangles wound outward."""
    v = [[c[0], c[1], c[2] + r]]
    for i in range(1, rings):
        t = math.pi * i / rings
        for j in range(segments):
            p = 2 * math.pi * j / segments
            v.append([c[0] + r * math.sin(t) * math.cos(p), c[1] + r * math.sin(t) * math.sin(p),
                      c[2] + r * math.cos(t)])
    v.append([c[0], c[1], c[2] - r])
    last = len(v) - 1
    at = lambda i, j: 1 + (i - 1) * segments + j % segments
    f = [[0, at(1, j), at(1, j + 1)] for j in range(segments)]
    for i in range(1, rings - 1):
        for j in range(segments):
            f += [[at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]]
    f += [[last, at(rings - 1, j + 1), at(rings - 1, j)] for j in range(segments)]
    return np.array(v, dtype=np.float64), np.array(f, dtype=np.uint64)


def write_obj(path, v, f):
    with open(path, "w") as out:
        for p in v:
            out.write("v %r %r %r\n" % tuple(float(x) for x in p[:3]))
        for t in f:
            out.write("f %d %d %d\n" % tuple(int(x) + 1 for x in t))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cells", default="17,13,15")
    a = parser.parse_args()
    bodies = [sphere(1.0, 64, 32, (0, 0, 0)), sphere(0.8, 60, 30, (0.9, 0.3, -0.2))]
    grid = ["--bounds=-1.1,-1.1,-1.1,1.8,1.2,1.1", "--cells", a.cells]
    extras = ["--moments", "--second-moments", "--face-centroids"]
    with tempfile.TemporaryDirectory() as tmp:
        files = []
        for n, (v, f) in enumerate(bodies):
            files.append(os.path.join(tmp, f"body{n}.obj"))
            write_obj(files[-1], v, f)
        meshes = [manifold3d.Manifold(manifold3d.Mesh64(vert_properties=v, tri_verts=f)) for v, f in bodies]
        union = (meshes[0] + meshes[1]).to_mesh64()
        peer = os.path.join(tmp, "union.obj")
        write_obj(peer, np.asarray(union.vert_properties), np.asarray(union.tri_verts))
        ours, theirs = os.path.join(tmp, "ours.npz"), os.path.join(tmp, "theirs.npz")
        subprocess.run([MESHVOL, "grid", *files, "--union", *grid, *extras, "--out", ours], check=True,
                       capture_output=True)
        subprocess.run([MESHVOL, "grid", peer, *grid, *extras, "--out", theirs], check=True,
                       capture_output=True)
        x, y = np.load(ours), np.load(theirs)
        print(f"manifold3d's union: {len(union.tri_verts)} triangles, volume {(meshes[0] + meshes[1]).volume()!r}")
        print(f"Σ volume: meshvol --union --moments {float(x['volume'].sum())!r}, of manifold3d's mesh {float(y['volume'].sum())!r}")
        print("| array | largest difference | NaN where the other is not |")
        print("|---|---|---|")
        for name in x.files:
            p, q = x[name], y[name]
            both = ~(np.isnan(p) | np.isnan(q))
            print(f"| {name} | {np.abs(p[both] - q[both]).max():.1e} | {int((np.isnan(p) != np.isnan(q)).sum())} |")


if __name__ == "__main__":
    main()
