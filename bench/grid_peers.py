#!/usr/bin/env python3
"""meshvol's grid and union against their peers, on the same meshes and machine.

- per-cell volumes of a 1M-triangle sphere on a 256^3 grid (and 512^3 for meshvol):
  `meshvol grid` against trimesh's voxelize + fill (occupancy only, not volumes) and
  against manifold3d mesh∩box booleans, one per partial cell (timed on a sample of
  cells, scaled to all partial cells; values compared with meshvol's);
- the union of 20 overlapping spheres of 20k triangles: `meshvol union --tolerance 1e-6`
  against manifold3d's boolean union + volume.

Run (after `cargo build --release -p meshvol-cli`):

    bench/out/venv/bin/python bench/grid_peers.py [--meshvol target/release/meshvol]
        [--threads 2] [--sample 200] [--no-512]

The venv needs numpy, trimesh and manifold3d. Results print as Markdown and go to
bench/out/grid_peers.json.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np


def uv_sphere(radius, segments, rings):
    """meshvol::shapes::uv_sphere(radius, segments, rings).triangulated(): (vertices, faces)."""
    m, n = max(segments, 3), max(rings, 2)
    verts = [(0.0, 0.0, radius)]
    for k in range(1, n):
        phi = math.pi * k / n
        for j in range(m):
            theta = 2.0 * math.pi * j / m
            x = radius * math.sin(phi)
            verts.append((x * math.cos(theta), x * math.sin(theta), radius * math.cos(phi)))
    verts.append((0.0, 0.0, -radius))
    south = len(verts) - 1

    def ring(k, j):
        return 1 + (k - 1) * m + j % m

    faces = []
    for j in range(m):
        faces.append((0, ring(1, j), ring(1, j + 1)))
        for k in range(1, n - 1):
            a, b, c, d = ring(k, j), ring(k + 1, j), ring(k + 1, j + 1), ring(k, j + 1)
            faces.append((a, b, c))
            faces.append((a, c, d))
        faces.append((south, ring(n - 1, j + 1), ring(n - 1, j)))
    return np.array(verts, dtype=np.float64), np.array(faces, dtype=np.int64)


def sphere_with_triangles(t):
    """meshvol_bench::sphere_with_triangles(t)."""
    rings = max(round(math.sqrt(t / 4.0)), 3)
    return uv_sphere(1.0, 2 * rings, rings + 1)


def write_stl(path, verts, faces):
    tris = verts[faces].astype("<f4")
    record = np.zeros(len(faces), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    record["v"] = tris
    with open(path, "wb") as f:
        f.write(b" " * 80)
        f.write(np.uint32(len(faces)).tobytes())
        f.write(record.tobytes())


def run_meshvol(exe, args, threads):
    cmd = [exe, "--threads", str(threads)] + args
    start = time.perf_counter()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True)
    wall = time.perf_counter() - start
    return json.loads(out.stdout), wall


def best(f, runs):
    times = []
    result = None
    for _ in range(runs):
        start = time.perf_counter()
        result = f()
        times.append(time.perf_counter() - start)
    return min(times), result


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(here)
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--meshvol", default=os.path.join(root, "target", "release", "meshvol"))
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--sample", type=int, default=200, help="partial cells timed with manifold3d")
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--no-512", action="store_true", help="skip the 512^3 grid")
    args = p.parse_args()
    import trimesh

    try:
        import manifold3d
    except ImportError:
        manifold3d = None
    results = {"machine": {"cpus": os.cpu_count(), "load": os.getloadavg()}, "versions": {
        "numpy": np.__version__, "trimesh": trimesh.__version__,
        "manifold3d": getattr(manifold3d, "__version__", "installed") if manifold3d else None}}
    work = tempfile.mkdtemp(prefix="grid_peers_")
    verts, faces = sphere_with_triangles(1_000_000)
    stl = os.path.join(work, "sphere-1m.stl")
    write_stl(stl, verts, faces)
    # Both tools measure the float32 coordinates in the file.
    v32 = verts.astype(np.float32).astype(np.float64)
    rows = []

    sizes = [256] if args.no_512 else [256, 512]
    npy = os.path.join(work, "cells.npy")
    for n in sizes:
        kernel, wall = [], []
        for _ in range(args.runs):
            out_args = ["--out", npy] if n == 256 else []
            report, w = run_meshvol(args.meshvol, ["grid", stl, "--cells", f"{n},{n},{n}",
                                                   "--bounds", "-1,-1,-1,1,1,1", "--json"] + out_args,
                                    args.threads)
            kernel.append(report["seconds"])
            wall.append(w)
        results[f"meshvol_grid_{n}"] = {"kernel_s": min(kernel), "process_s": min(wall),
                                        "total": report["total"], "partial": report["cells_partial"],
                                        "full": report["cells_full"]}
        rows.append((f"meshvol grid, {n}³ (kernel / whole process incl. reading{', writing .npy' if n == 256 else ''})",
                     f"{min(kernel):.3f} / {min(wall):.3f} s", "exact volumes"))

    cells = np.load(npy)
    pitch = 2.0 / 256
    mesh = trimesh.Trimesh(v32, faces, process=False)

    def voxelize():
        return mesh.voxelized(pitch=pitch).fill()

    t_vox, vox = best(voxelize, 1)
    results["trimesh_voxelize_fill_256"] = {"s": t_vox, "filled_voxels": int(vox.filled_count)}
    rows.append(("trimesh voxelized(2/256).fill() (occupancy only)", f"{t_vox:.3f} s",
                 f"{t_vox / results['meshvol_grid_256']['kernel_s']:.0f}× meshvol's kernel"))

    if manifold3d is not None:
        from manifold3d import Manifold, Mesh

        solid = Manifold(Mesh(vert_properties=v32.astype(np.float32), tri_verts=faces.astype(np.uint32)))
        cv = pitch ** 3
        fractions = cells / cv
        partial = np.argwhere((fractions > 1e-9) & (fractions < 1 - 1e-9))
        rng = np.random.default_rng(1)
        chosen = partial[rng.choice(len(partial), size=min(args.sample, len(partial)), replace=False)]
        start = time.perf_counter()
        diffs = []
        for i, j, k in chosen:
            lo = np.array([-1.0 + i * pitch, -1.0 + j * pitch, -1.0 + k * pitch])
            box = Manifold.cube([pitch] * 3).translate(lo.tolist())
            v = (solid ^ box).volume()
            diffs.append(abs(v - cells[i, j, k]) / cv)
        per_cell = (time.perf_counter() - start) / len(chosen)
        all_partial = per_cell * len(partial)
        results["manifold_per_cell_256"] = {"s_per_cell": per_cell, "partial_cells": int(len(partial)),
                                            "s_all_partial": all_partial,
                                            "max_abs_diff_in_cell_volumes": float(max(diffs))}
        rows.append((f"manifold3d mesh∩box per partial cell ({len(partial)} cells, {len(chosen)} timed)",
                     f"{all_partial:.1f} s (scaled)",
                     f"{all_partial / results['meshvol_grid_256']['kernel_s']:.0f}× meshvol; "
                     f"max |difference| {max(diffs):.1e} of a cell"))

    # Union of 20 overlapping spheres of 20k triangles.
    sv, sf = sphere_with_triangles(20_000)
    files, moved = [], []
    for k in range(20):
        c = np.array([1.2 * (k % 5), 1.2 * (k // 5), 0.3 * (k % 2)])
        path = os.path.join(work, f"s{k}.stl")
        write_stl(path, sv + c, sf)
        files.append(path)
        moved.append((sv + c).astype(np.float32))
    times, report = [], None
    for _ in range(args.runs):
        report, w = run_meshvol(args.meshvol, ["union"] + files + ["--tolerance", "1e-6", "--json"], args.threads)
        times.append(w)
    results["meshvol_union_20"] = {"process_s": min(times), **report}
    rows.append(("meshvol union, 20 spheres × 20k triangles, tolerance 1e-6 (whole process)",
                 f"{min(times):.3f} s", f"[{report['lower']:.10f}, {report['upper']:.10f}]"))
    if manifold3d is not None:
        from manifold3d import Manifold, Mesh, OpType

        bodies = [Manifold(Mesh(vert_properties=v, tri_verts=sf.astype(np.uint32))) for v in moved]

        def boolean_union():
            return Manifold.batch_boolean(bodies, OpType.Add).volume()

        t_union, volume = best(boolean_union, args.runs)
        inside = report["lower"] <= volume <= report["upper"]
        results["manifold_union_20"] = {"s": t_union, "volume": volume, "inside_meshvol_interval": inside}
        rows.append(("manifold3d batch_boolean(Add) + volume", f"{t_union:.3f} s",
                     f"{volume:.10f} ({'inside' if inside else 'outside'} meshvol's interval; "
                     f"{t_union / min(times):.1f}× meshvol)"))

    print(f"machine: {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}; meshvol --threads {args.threads}\n")
    print("| what | time | notes |\n|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]} |")
    os.makedirs(os.path.join(here, "out"), exist_ok=True)
    with open(os.path.join(here, "out", "grid_peers.json"), "w") as f:
        json.dump(results, f, indent=2)


if __name__ == "__main__":
    sys.exit(main())
