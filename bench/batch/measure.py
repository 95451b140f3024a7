#!/usr/bin/env python3
"""Files per second of meshvol.measure and meshvol.dask.measure on many small files.

Generates N files (default 10,000) in a temporary folder, a mix as mesh datasets have:
UV spheres (binary STL and OBJ, 448 triangles), boxes (OBJ, 12 triangles), open boxes
(capped and warned), and broken files (an error row each); then times

- meshvol.measure(folder) (all cores, the files spread over a rayon pool), and
- meshvol.dask.measure(folder) on a LocalCluster of W worker processes (default 2, one
  thread each), computed to a pandas DataFrame, the cluster started beforehand,

each the best of R runs (default 3), and checks that both tables agree (volumes, errors).

    python bench/batch/measure.py [--files 10000] [--workers 2] [--runs 3]

Needs meshvol with pandas (and dask[dataframe], distributed for the cluster run).
"""

import argparse
import os
import resource
import struct
import tempfile
import time
import warnings

import numpy as np

import meshvol


def uv_sphere(radius, rings=15, segments=16, centre=(0.0, 0.0, 0.0)):
    theta = np.linspace(0.0, np.pi, rings + 1)[1:-1]
    phi = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    circle = np.stack([np.outer(np.sin(theta), np.cos(phi)), np.outer(np.sin(theta), np.sin(phi)),
                       np.repeat(np.cos(theta)[:, None], segments, axis=1)], axis=-1).reshape(-1, 3)
    vertices = np.vstack([[0.0, 0.0, 1.0], circle, [0.0, 0.0, -1.0]]) * radius + centre
    j = np.arange(segments)
    after = (j + 1) % segments
    south = 1 + (rings - 1) * segments
    faces = [np.stack([np.zeros(segments, dtype=np.int64), 1 + j, 1 + after], axis=1)]
    for ring in range(rings - 2):
        upper, lower = 1 + ring * segments, 1 + (ring + 1) * segments
        faces.append(np.stack([upper + j, lower + j, lower + after], axis=1))
        faces.append(np.stack([upper + j, lower + after, upper + after], axis=1))
    last = 1 + (rings - 2) * segments
    faces.append(np.stack([last + j, np.full(segments, south), last + after], axis=1))
    return vertices, np.concatenate(faces)


BOX_TRIANGLES = np.array([[0, 2, 3], [4, 5, 7], [0, 1, 5], [2, 6, 7], [0, 4, 6], [1, 3, 7],
                          [0, 3, 1], [4, 7, 6], [0, 5, 4], [2, 7, 3], [0, 6, 2], [1, 7, 5]])


def box(size, at):
    unit = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float)
    return unit * size + at, BOX_TRIANGLES


def obj_text(vertices, faces):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces.tolist()]
    return "\n".join(lines) + "\n"


def stl_bytes(vertices, faces):
    out = [b"\0" * 80, struct.pack("<I", len(faces))]
    for t in faces:
        a, b, c = vertices[t]
        out.append(struct.pack("<12fH", 0, 0, 0, *a, *b, *c, 0))
    return b"".join(out)


def generate(folder, count, seed=0):
    """count files: 40 % spheres as STL, 20 % spheres as OBJ, 25 % boxes, 10 % open
    boxes, 5 % broken. Returns the expected volume of the closed ones (None otherwise)."""
    rng = np.random.default_rng(seed)
    for k in range(count):
        kind = k % 20
        size = rng.uniform(0.5, 3.0, 3)
        at = rng.uniform(-100, 100, 3)
        if kind < 8:
            v, f = uv_sphere(size[0], centre=at)
            open(os.path.join(folder, f"{k:07}.stl"), "wb").write(stl_bytes(v, f))
        elif kind < 12:
            v, f = uv_sphere(size[0], centre=at)
            open(os.path.join(folder, f"{k:07}.obj"), "w").write(obj_text(v, f))
        elif kind < 17:
            open(os.path.join(folder, f"{k:07}.obj"), "w").write(obj_text(*box(size, at)))
        elif kind < 19:
            v, f = box(size, at)
            open(os.path.join(folder, f"{k:07}.obj"), "w").write(obj_text(v, f[:-1]))
        else:
            open(os.path.join(folder, f"{k:07}.obj"), "w").write("v 0 0 0\nv 1 0 0\nf 1 2 3\nf 1 2 9\n")


def best(runs, f):
    times, result = [], None
    for _ in range(runs):
        start = time.perf_counter()
        result = f()
        times.append(time.perf_counter() - start)
    return min(times), result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--files", type=int, default=10_000)
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--no-dask", action="store_true")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        start = time.perf_counter()
        generate(folder, args.files)
        print(f"meshvol {meshvol.__version__}: {args.files} files generated in "
              f"{time.perf_counter() - start:.1f} s, {os.cpu_count()} cores")
        cpu_before = resource.getrusage(resource.RUSAGE_SELF)
        seconds, local = best(args.runs, lambda: meshvol.measure(folder))
        cpu_after = resource.getrusage(resource.RUSAGE_SELF)
        cpu = (cpu_after.ru_utime + cpu_after.ru_stime - cpu_before.ru_utime - cpu_before.ru_stime) / args.runs
        failed = int(local["error"].notna().sum())
        print(f"meshvol.measure          {seconds:7.2f} s  {args.files / seconds:8.0f} files/s"
              f"  ({failed} error rows; {cpu:.2f} CPU s a run: {args.files / cpu:.0f} files per CPU second;"
              f" load average {os.getloadavg()[0]:.1f})")
        if args.no_dask:
            return
        import distributed

        from meshvol import dask as meshvol_dask

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with distributed.LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                          processes=True, dashboard_address=None) as cluster, \
                    distributed.Client(cluster):
                per = max(1, args.files // (4 * args.workers))
                frame = lambda: meshvol_dask.measure(folder, files_per_partition=per).compute()
                seconds, remote = best(args.runs, frame)
        same = np.allclose(local["volume"].to_numpy(float), remote["volume"].to_numpy(float), equal_nan=True)
        print(f"meshvol.dask.measure     {seconds:7.2f} s  {args.files / seconds:8.0f} files/s"
              f"  (LocalCluster, {args.workers} workers x 1 thread; same volumes: {same})")


if __name__ == "__main__":
    main()
