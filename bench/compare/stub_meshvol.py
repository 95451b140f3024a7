"""A stand-in for `meshvol volume FILE --json`, to test the harness before the binary exists.

NOT meshvol: plain float64 numpy, no exactness, no speed. Usage:
  bench/compare/run --quick --only volume,inprocess \
      --meshvol "bench/out/venv/bin/python bench/compare/stub_meshvol.py"
The report then says in bold that meshvol's numbers are not meshvol's.
"""

import json
import sys

import numpy as np


def read_triangles(path):
    if path.endswith(".ply"):  # the binary PLY that meshgen.write_ply_binary writes
        sys.path.insert(0, __file__.rsplit("/", 1)[0])
        import meshgen

        v, f = meshgen.read_ply_binary(path)
        return v[f], "ply-binary-le"
    with open(path, "rb") as fh:
        head = fh.read(80)
        if path.endswith(".obj"):
            text = head + fh.read()
            lines = text.split(b"\n")
            v = np.array([ln.split()[1:4] for ln in lines if ln.startswith(b"v ")], dtype=np.float64)
            f = np.array([ln.split()[1:4] for ln in lines if ln.startswith(b"f ")], dtype=np.int64) - 1
            return v[f], "obj"
        if head.lstrip().startswith(b"solid") and b"facet" in fh.read(1000):
            fh.seek(0)
            vals = [ln.split()[1:4] for ln in fh if ln.lstrip().startswith(b"vertex")]
            return np.array(vals, dtype=np.float64).reshape(-1, 3, 3), "stl-ascii"
        fh.seek(80)
        n = int(np.frombuffer(fh.read(4), "<u4")[0])
        dt = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
        rec = np.frombuffer(fh.read(n * 50), dtype=dt)
        return rec["v"].astype(np.float64), "stl"


def main():
    if len(sys.argv) < 3 or sys.argv[1] != "volume":
        sys.exit("stub_meshvol.py stands in for `meshvol volume` only (use --only volume,inprocess)")
    path = sys.argv[2]
    tri, fmt = read_triangles(path)
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    det = np.einsum("ij,ij->i", a, np.cross(b, c))
    vol = det.sum() / 6.0
    centroid = ((a + b + c) * det[:, None]).sum(0) / (24.0 * vol)
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    print(json.dumps({
        "file": path, "format": fmt, "triangles": len(tri), "volume": abs(vol),
        "signed_volume": vol, "area": area, "centroid": centroid.tolist(),
        "inertia": np.zeros((3, 3)).tolist(), "stub": True,
    }))


if __name__ == "__main__":
    main()
