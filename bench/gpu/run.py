#!/usr/bin/env python3
"""The grid on an OpenCL device against the CPU path on the same host (issue 50):
`meshvol grid` of UV spheres of 1M, 5M and 20M triangles at 256³, 512³ and 1024³, with
`--backend opencl` and `--backend cpu`, alternated, the median of RUNS each; and the cut
cells (`grid --moments`, written as .npz) at 256³ and 512³ (`--moment-sizes`: fourteen
values a cell, 15 GB at 512³). Prints a Markdown table, a row for each kind of run
(`volumes`, `moments`), from each run's `--timings` and `seconds`:

- the kernel: the CPU's stage of cutting faces into cells (the sweeps and the sums, on
  all its threads) against the device's (`OpenCL: the kernel`), `kernel ×` their
  ratio; both after the faces are sorted into tiles, which the CPU does for both
  (`CPU sorting s`; inside `OpenCL layout (CPU)` for the device);
- the cell volumes as the run reports them (`seconds`: for OpenCL, from opening the
  device to the cells read back), and their ratio;
- the whole command's wall time (reading, the check, the cells, writing the .npy);
- where the OpenCL run's time went: opening the device, building the kernel, laying
  out the tiles on the CPU, uploading, the kernel, reading back, for the cut cells the
  sums across columns on the CPU (the x and y apertures), writing the file.

Every pair of files is compared byte for byte: a difference stops the run.

    cargo build --release -p meshvol-cli -p meshvol-io --example sphere
    python3 bench/gpu/run.py [--runs 3] [--opencl-device N] [--raw runs.jsonl]
    python3 bench/gpu/run.py --smoke      # tiny sizes, one run: that the script works

Needs an OpenCL device with f64 (`meshvol devices`); the release binary built by cargo,
not the static one of scripts/dist.sh (which cannot load libOpenCL.so.1). `--smoke` runs
on any device, PoCL's CPU device included; its times say nothing about a GPU.
"""

import argparse
import hashlib
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# The OpenCL run's stages, as `--timings` names them, in the order they run.
STAGES = [
    ("open", "OpenCL: opening the device"),
    ("build", "OpenCL: building the kernel"),
    ("layout (CPU)", "laying out the tiles (CPU)"),
    ("upload", "OpenCL: uploading"),
    ("kernel", "OpenCL: the kernel"),
    ("read back", "OpenCL: reading back"),
    ("apertures (CPU)", "summing apertures (CPU)"),
    ("write", "writing"),
]


def run(meshvol, stl, n, backend, device, out, moments):
    """One whole command (with `moments`, `--moments`): its wall time, the cells' time it
    reports, its stages' wall times summed by name (a grid in several slabs repeats
    them), and its file's digest."""
    args = [meshvol, "grid", stl, "--cells", f"{n},{n},{n}", "--out", out, "--backend", backend,
            "--json", "--timings", "-q"] + (["--moments"] if moments else [])
    if backend == "opencl":
        args += ["--opencl-device", str(device)]
    start = time.perf_counter()
    result = subprocess.run(args, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {result.returncode}\n{result.stderr}")
    report = json.loads(result.stdout)
    stages = {}
    for t in report["timings"]:
        stages[t["stage"]] = stages.get(t["stage"], 0.0) + t["wall_s"]
    digest = hashlib.sha256()
    with open(out, "rb") as f:
        for block in iter(lambda: f.read(1 << 24), b""):
            digest.update(block)
    os.remove(out)
    return {"backend": backend, "kind": "moments" if moments else "volumes", "cells": n, "wall_s": wall, "seconds": report["seconds"],
            "stages": stages, "sha256": digest.hexdigest()}


NO_GPU = """no OpenCL GPU with f64 is listed (meshvol devices). On an NVIDIA host the
driver ships the OpenCL library, libnvidia-opencl.so.1; what may be missing is the
loader and the file that names it:
    apt-get install ocl-icd-libopencl1        # the loader, libOpenCL.so.1
    echo libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd
Or name a device: --opencl-device N."""


def device_to_use(meshvol, asked, smoke):
    """The device number to pass as --opencl-device: the one asked for; else the GPU
    `auto` takes; with --smoke, else the first device with f64 (PoCL's included)."""
    if asked is not None:
        return asked
    listed = json.loads(subprocess.run([meshvol, "devices", "--json"], check=True,
                                       capture_output=True, text=True).stdout)
    if listed["auto"] is not None:
        return listed["auto"]
    if smoke:
        for d in listed["devices"]:
            if d["fp64"]:
                return d["index"]
    sys.exit(NO_GPU)


def describe(meshvol):
    """The host and the OpenCL devices, for the table's heading."""
    devices = subprocess.run([meshvol, "devices"], capture_output=True, text=True).stdout.strip()
    version = subprocess.run([meshvol, "--version"], capture_output=True, text=True).stdout.strip()
    return f"{version}; {os.cpu_count()} CPUs; devices:\n{devices}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--triangles", default="1000000,5000000,20000000")
    parser.add_argument("--sizes", default="256,512,1024")
    parser.add_argument("--moment-sizes", default="256,512",
                        help="the grids of the cut cells (--moments) rows; empty: none")
    parser.add_argument("--opencl-device", type=int)
    parser.add_argument("--meshvol", default=os.path.join(ROOT, "target/release/meshvol"))
    parser.add_argument("--sphere", default=os.path.join(ROOT, "target/release/examples/sphere"))
    parser.add_argument("--raw", help="append every run as a JSON line to this file")
    parser.add_argument("--smoke", action="store_true",
                        help="2,000 and 8,000 triangles at 8³ and 20³, one run: that the script works")
    parser.add_argument("--tmp", help="where the spheres and grids are written (default: a temporary folder)")
    a = parser.parse_args()
    if a.smoke:
        a.triangles, a.sizes, a.moment_sizes, a.runs = "2000,8000", "8,20", "8,20", 1
    triangles = [int(t) for t in a.triangles.split(",")]
    kinds = [(int(n), False) for n in a.sizes.split(",") if n]
    kinds += [(int(n), True) for n in a.moment_sizes.split(",") if n]
    device = device_to_use(a.meshvol, a.opencl_device, a.smoke)
    print(describe(a.meshvol))
    print(f"OpenCL runs on device {device}")
    print()
    stage_heads = " | ".join(f"OpenCL {name} s" for name, _ in STAGES)
    print(f"| triangles | grid | kind | CPU sorting s | CPU cutting s | kernel × | CPU cells s | "
          f"OpenCL cells s | cells × | CPU command s | OpenCL command s | command × | "
          f"{stage_heads} |")
    print("|" + "---|" * (12 + len(STAGES)))
    raw = open(a.raw, "a") if a.raw else None
    with tempfile.TemporaryDirectory(dir=a.tmp) as tmp:
        for count in triangles:
            stl = os.path.join(tmp, f"sphere-{count}.stl")
            subprocess.run([a.sphere, str(count), stl], check=True, capture_output=True)
            for n, moments in kinds:
                kind = "moments" if moments else "volumes"
                runs = {"cpu": [], "opencl": []}
                for r in range(a.runs):
                    # Alternated, the CPU first on even runs: neither always runs on a
                    # host just warmed (or slowed) by the other.
                    order = ["cpu", "opencl"] if r % 2 == 0 else ["opencl", "cpu"]
                    for backend in order:
                        out = os.path.join(tmp, f"{backend}.{'npz' if moments else 'npy'}")
                        one = run(a.meshvol, stl, n, backend, device, out, moments)
                        one["triangles"] = count
                        runs[backend].append(one)
                        if raw:
                            raw.write(json.dumps(one) + "\n")
                    digests = {runs[b][-1]["sha256"] for b in runs}
                    if len(digests) != 1:
                        sys.exit(f"{count} triangles at {n}³, {kind}: the OpenCL file differs from the CPU's")
                med = lambda backend, f: statistics.median(f(x) for x in runs[backend])
                cpu_s, gpu_s = med("cpu", lambda x: x["seconds"]), med("opencl", lambda x: x["seconds"])
                kernel = med("opencl", lambda x: x["stages"].get("OpenCL: the kernel", 0.0))
                sorting = med("cpu", lambda x: x["stages"].get("sorting faces into tiles of columns", 0.0))
                cutting = med("cpu", lambda x: x["stages"].get("cutting faces into cells", 0.0))
                cpu_wall, gpu_wall = med("cpu", lambda x: x["wall_s"]), med("opencl", lambda x: x["wall_s"])
                stages = " | ".join(f"{med('opencl', lambda x, s=s: x['stages'].get(s, 0.0)):.3f}"
                                    for _, s in STAGES)
                ratio = lambda p, q: f"{p / q:.1f}" if q > 0 else "–"
                print(f"| {count:,} | {n}³ | {kind} | {sorting:.3f} | {cutting:.3f} | {ratio(cutting, kernel)} | "
                      f"{cpu_s:.3f} | {gpu_s:.3f} | {ratio(cpu_s, gpu_s)} | {cpu_wall:.3f} | {gpu_wall:.3f} | "
                      f"{ratio(cpu_wall, gpu_wall)} | {stages} |", flush=True)
            os.remove(stl)
    if raw:
        raw.close()


if __name__ == "__main__":
    main()
