"""The `dask` extra, installed from the package index, at work (scripts/test-python-extras.sh
runs it in a fresh virtualenv): meshvol.dask.measure and meshvol.dask.grid on a
LocalCluster of two worker processes, each result compared with the non-Dask Python path
(meshvol.measure, Mesh.grid) and, when MESHVOL_BIN names the command, with the command's
own output (`volume -r --json`, `grid --out cells.npy`). Exits non-zero on a mismatch."""

import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

# The import a broken dask/distributed pair fails (dask 2026.11 with distributed 2021.4:
# ImportError: cannot import name 'collections_to_dsk').
from dask.distributed import Client, LocalCluster

import meshvol
import meshvol.dask

SAMPLES = "samples"
PART = os.path.join(SAMPLES, "flanged-bushing.stl")
CELLS = (24, 24, 12)


def fail(message):
    print(f"test-python-extras.py: {message}", file=sys.stderr)
    sys.exit(1)


def command(*args):
    """The command's stdout, or None without MESHVOL_BIN."""
    binary = os.environ.get("MESHVOL_BIN")
    if not binary:
        return None
    run = subprocess.run([binary, *args], capture_output=True, text=True)
    if run.returncode not in (0, 1):  # 1: some file failed, its line says which
        fail(f"meshvol {' '.join(args)} exited {run.returncode}: {run.stderr}")
    return run.stdout


def same(a, b):
    """Equal, NaN equal to NaN (a failed file has no volume)."""
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b


def check_measure():
    frame = meshvol.dask.measure(SAMPLES, files_per_partition=3).compute()
    local = meshvol.measure(SAMPLES)
    if list(frame["file"]) != list(local["file"]) or len(frame) < 4:
        fail(f"dask.measure's files {list(frame['file'])} are not meshvol.measure's {list(local['file'])}")
    for column in ("volume", "area", "closed"):
        got, want = frame[column].tolist(), local[column].tolist()
        if not all(same(g, w) for g, w in zip(got, want)):
            fail(f"dask.measure's {column} {got} differs from meshvol.measure's {want}")
    out = command("volume", "-r", SAMPLES, "--json")
    if out is not None:
        lines = [json.loads(line) for line in out.splitlines()]
        if [row["file"] for row in lines] != list(frame["file"]):
            fail(f"dask.measure's files differ from the command's {[r['file'] for r in lines]}")
        for row, volume in zip(lines, frame["volume"]):
            if "error" not in row and row["volume"] != volume:
                fail(f"{row['file']}: dask.measure's volume {volume} is not the command's {row['volume']}")
    print(f"meshvol.dask.measure: {len(frame)} files, as meshvol.measure"
          + (" and the command" if out is not None else ""))


def check_grid():
    cells = meshvol.dask.grid(PART, cells=CELLS, chunks=(8, 12, -1)).compute()
    whole = meshvol.load(PART).grid(cells=CELLS).values
    if cells.shape != CELLS or not np.array_equal(cells, whole):
        fail(f"dask.grid's cells (shape {cells.shape}) are not Mesh.grid's, bit for bit")
    with tempfile.TemporaryDirectory() as folder:
        npy = os.path.join(folder, "cells.npy")
        out = command("grid", PART, "--cells", ",".join(map(str, CELLS)), "--out", npy, "--quiet")
        if out is not None and not np.array_equal(np.load(npy), cells):
            fail("dask.grid's cells are not the command's .npy, bit for bit")
    moments = meshvol.dask.grid(PART, cells=CELLS, chunks=(12, 12, -1), moments=True)
    local = meshvol.load(PART).cells(cells=CELLS)
    for name, array in moments.items():
        if not np.array_equal(array.compute(), local[name], equal_nan=True):
            fail(f"dask.grid(moments=True)'s {name} is not Mesh.cells's, bit for bit")
    print(f"meshvol.dask.grid: {CELLS} cells and {len(moments)} cut-cell arrays, as Mesh.grid"
          + (" and the command" if out is not None else ""))


def main():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        workers = client.scheduler_info()["workers"]
        pids = set(client.run(os.getpid).values())
        if len(workers) != 2 or len(pids) != 2 or os.getpid() in pids:
            fail(f"expected two worker processes, got {len(workers)} workers, pids {pids}")
        check_measure()
        check_grid()


if __name__ == "__main__":
    main()
