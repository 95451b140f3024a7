#!/usr/bin/env python3
"""Cut cells against volumes alone: `meshvol grid --moments` and plain `meshvol grid` on
a 1M-triangle UV sphere at n³, the kernel time each reports (`seconds`), alternated, the
median of RUNS each. Prints a Markdown table with the ratio and cells per second, and the
cut cells' stage of allocating their arrays (median and range): the first touch of fresh
memory, which moves most between runs.

    cargo build --release -p meshvol-cli -p meshvol-io --example sphere
    python3 bench/cells/run.py [--runs 5] [--sizes 64,128,256]
"""

import argparse
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MESHVOL = os.path.join(ROOT, "target/release/meshvol")
SPHERE = os.path.join(ROOT, "target/release/examples/sphere")


def seconds(stl, n, out, moments):
    """The kernel time a run reports, and (with --moments) its stage of allocating the
    arrays, whose first touch of fresh memory is what varies most between runs."""
    args = [MESHVOL, "grid", stl, "--cells", f"{n},{n},{n}", "--no-check", "--out", out, "--json",
            "--timings", "-q"]
    if moments:
        args.insert(2, "--moments")
    result = subprocess.run(args, check=True, capture_output=True, text=True)
    os.remove(out)
    report = json.loads(result.stdout)
    stages = {t["stage"]: t["wall_s"] for t in report["timings"]}
    return report["seconds"], stages.get("allocating the cells' arrays", 0.0)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--sizes", default="64,128,256")
    parser.add_argument("--triangles", type=int, default=1_000_000)
    a = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        stl = os.path.join(tmp, "sphere.stl")
        subprocess.run([SPHERE, str(a.triangles), stl], check=True, capture_output=True)
        print("| grid | volumes s | cut cells s | of which allocating s (range) | ratio | cut cells, cells/s |")
        print("|---|---|---|---|---|---|")
        for n in map(int, a.sizes.split(",")):
            plain, cut, allocating = [], [], []
            for _ in range(a.runs):
                plain.append(seconds(stl, n, os.path.join(tmp, "v.npz"), False)[0])
                c, alloc = seconds(stl, n, os.path.join(tmp, "c.npz"), True)
                cut.append(c)
                allocating.append(alloc)
            p, c = statistics.median(plain), statistics.median(cut)
            spread = f"{statistics.median(allocating):.3f} ({min(allocating):.3f}–{max(allocating):.3f})"
            print(f"| {n}³ | {p:.3f} | {c:.3f} | {spread} | {c / p:.2f} | {n**3 / c:.3g} |")


if __name__ == "__main__":
    main()
