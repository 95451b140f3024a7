#!/usr/bin/env python3
"""Side-by-side benchmark of meshvol against its peers, in one run.

Sections: mesh volume end-to-end (fresh process: load a file + volume) and in-process;
topology check; per-cell grid volumes; union of overlapping bodies; convex hull; 2D polygon
area. Peers: trimesh, numpy-stl, manifold3d, Open3D, PyMeshLab, VTK, scipy (qhull),
shapely, each where it is installed. Every section runs under a share of one time budget
(--time-budget) and every peer run is cut off at --peer-timeout ("> N s").

Normally started by bench/compare/run, which makes the virtualenv and builds meshvol.
Writes test data to bench/out/data/, raw numbers to bench/out/results.json, and the report
to bench/RESULTS.md and bench/RESULTS.png. See bench/compare/README.md.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import hashlib
import json
import os
import platform
import queue
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import threading
import time
from fractions import Fraction
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import meshgen  # noqa: E402
import sections  # noqa: E402
from harness import (DATA, OUT, PY, ROOT, TOOLS_DIR, Clock, Ctx, Runner, ahead_cell,  # noqa: E402
                     fmt_err, fmt_mb, fmt_s, is_behind, kill_group, last_line,
                     load_json, log, md_cell, parse_json_lines, plan_cell, ratio_cell, runs_cell,
                     seconds_of, time_cell)

CRITERION_NOTE = (
    "meshvol's own in-memory numbers come from its criterion benchmarks: "
    "`cargo bench -p meshvol-bench` ([crates/meshvol-bench](../crates/meshvol-bench/)); "
    "reports land in `target/criterion/`."
)
FORMAT_LABEL = {"stl": "binary STL", "stl-ascii": "ASCII STL", "obj": "OBJ", "ply": "binary PLY"}
FORMAT_EXT = {"stl": ".stl", "stl-ascii": "_ascii.stl", "obj": ".obj", "ply": ".ply"}

# peer -> (module to import, distribution on PyPI, what it is used for here)
PEERS = {
    "trimesh": ("trimesh", "trimesh", "volume (end-to-end, in-process), check, grid"),
    "numpy-stl": ("stl", "numpy-stl", "volume (end-to-end on STL, in-process)"),
    "manifold3d": ("manifold3d", "manifold3d", "volume (in-process), grid, union, intersection"),
    "open3d": ("open3d", "open3d", "volume (end-to-end, in-process), check"),
    "pymeshlab": ("pymeshlab", "pymeshlab", "volume (end-to-end, in-process), check"),
    "vtk": ("vtkmodules.vtkFiltersCore", "vtk", "volume (end-to-end, in-process)"),
    "scipy": ("scipy.spatial", "scipy", "convex hull (qhull)"),
    "shapely": ("shapely", "shapely", "2D area"),
    "trueform": ("trueform", "trueform", "volume (end-to-end, in-process), check, union, "
                 "intersection"),
    "meshlib": ("meshlib.mrmeshpy", "meshlib", "volume (end-to-end, in-process), check, union, "
                "intersection, "
                "profile"),
    # not a peer: meshvol's own Python binding, for a measured meshvol row in-process
    "meshvol-py": ("meshvol", "meshvol", "meshvol's in-process row (optional: "
                   "`pip install ./crates/meshvol-py`, which builds it with maturin)"),
}
# volume tools: end-to-end worker script (None: in-process only), formats it reads. The
# strongest peers first: when a section's time budget runs out, the slower ones are left out.
E2E_TOOLS = {
    "trueform": ("trueform_file.py", ("stl", "stl-ascii", "obj")),
    "meshlib": ("meshlib_file.py", ("stl", "stl-ascii", "obj", "ply")),
    "vtk": ("vtk_file.py", ("stl", "stl-ascii", "obj", "ply")),
    "trimesh": ("trimesh_file.py", ("stl", "stl-ascii", "obj", "ply")),
    "numpy-stl": ("numpystl_file.py", ("stl", "stl-ascii")),
    "pymeshlab": ("pymeshlab_file.py", ("stl", "stl-ascii", "obj", "ply")),
    "open3d": ("open3d_file.py", ("stl", "stl-ascii", "obj", "ply")),
}
IMPORT_ONLY = {"trimesh": "trimesh", "numpy-stl": "stl.mesh", "open3d": "open3d",
               "pymeshlab": "pymeshlab", "vtk": "vtkmodules.vtkFiltersCore",
               "trueform": "trueform", "meshlib": "meshlib.mrmeshpy"}
INPROCESS_TOOLS = ("meshvol-py", "meshvol-py-mp", "trueform", "meshlib", "vtk", "trimesh", "manifold3d", "numpy-stl",
                   "pymeshlab", "open3d")
NO_VERDICT = "(no verdict)"
SECTIONS = ["volume", "inprocess", "check", "grid", "union", "intersect", "profile", "hull", "area",
            "scaling"]
# run only when named in --only: the scaling section is meshvol alone on spheres up to 20M
# triangles (about 1 GB of STL to write), not a comparison
DEFAULT_OFF = {"scaling"}
WEIGHTS = {"volume": 0.38, "inprocess": 0.09, "check": 0.17, "grid": 0.11, "union": 0.04, "intersect": 0.04,
           "profile": 0.03, "hull": 0.11, "area": 0.10, "scaling": 0.5}
SECTION_TITLE = {"volume": "mesh volume, end-to-end", "inprocess": "mesh volume, in-process",
                 "check": "topology check", "grid": "grid", "union": "union", "intersect": "intersection",
                 "profile": "profile (volume below levels)", "hull": "convex hull",
                 "area": "2D area", "scaling": "scaling (meshvol alone)"}


# --------------------------------------------------------------------------- planning


def parse_size(s: str) -> int:
    s = s.strip().lower().replace("_", "")
    mult = {"k": 1_000, "m": 1_000_000}.get(s[-1:], 1)
    return int(float(s[:-1] if mult > 1 else s) * mult)


size_label = sections.size_label


def mesh_file(kind, n, fmt) -> dict:
    name = f"{kind}_{size_label(n)}{FORMAT_EXT[fmt]}"
    return {"name": name, "kind": kind, "target": n, "fmt": fmt, "path": DATA / name}


def plan_files(sizes: list[int], quick: bool) -> tuple[list[dict], str]:
    """The end-to-end files and the name of the main one (chart; every tool runs on it).

    Binary STL: spheres of every size (and, unless --quick, tori up to 5M), the far sphere and the
    cubes at the middle size. Binary PLY: spheres up to 1M. ASCII STL and OBJ: the sphere
    of the largest size up to 1M (text files of 5M are GBs).
    """
    mid = 1_000_000 if 1_000_000 in sizes else min(sizes)
    files = []
    for n in sorted(sizes):
        files.append(mesh_file("sphere", n, "stl"))
        if not quick and n <= 5_000_000:  # 10M and more: the sphere only (time, disk)
            files.append(mesh_file("torus", n, "stl"))
    files.append(mesh_file("sphere_far", mid, "stl"))
    files.append(mesh_file("cubes", mid, "stl"))
    for n in sorted(s for s in sizes if s <= 1_000_000):
        files.append(mesh_file("sphere", n, "ply"))
    text_n = max((s for s in sizes if s <= 1_000_000), default=None)
    if text_n:
        files.append(mesh_file("sphere", text_n, "stl-ascii"))
        files.append(mesh_file("sphere", text_n, "obj"))
    return files, f"sphere_{size_label(mid)}.stl"


# --------------------------------------------------------------------------- data + refs


def gen_version() -> str:
    return hashlib.sha256((HERE / "meshgen.py").read_bytes()).hexdigest()[:16]


class Refs:
    """Exact reference volumes, cached in bench/out/data/refs.json per generator version."""

    def __init__(self):
        self.path = DATA / "refs.json"
        self.ver = gen_version()
        d = load_json(self.path, {})
        self.d = d.get("refs", {}) if d.get("gen") == self.ver else {}

    def get(self, kind, n, arrays=None):
        key = f"{kind}:{n}"
        if key not in self.d:
            v, f, _ = arrays if arrays is not None else meshgen.make(kind, n)
            t0 = time.perf_counter()
            ref = meshgen.exact_signed_volume(v, f)
            dt = time.perf_counter() - t0
            self.d[key] = {"num": str(ref.numerator), "den": str(ref.denominator),
                           "triangles": int(len(f)), "seconds": dt}
            log(f"exact volume of {key}: {float(ref):.17g} ({len(f)} triangles, {dt:.2f} s)")
            DATA.mkdir(parents=True, exist_ok=True)
            self.path.write_text(json.dumps({"gen": self.ver, "refs": self.d}, indent=1))
        e = self.d[key]
        return Fraction(int(e["num"]), int(e["den"])), e["triangles"], e["seconds"]


def generate(files: list[dict], refs: Refs):
    DATA.mkdir(parents=True, exist_ok=True)
    manifest_path = DATA / "manifest.json"
    manifest = load_json(manifest_path, {})
    ver = refs.ver
    groups: dict[tuple, list[dict]] = {}
    for f in files:
        groups.setdefault((f["kind"], f["target"]), []).append(f)
    writers = {"stl": lambda p, v, f, q: meshgen.write_stl_binary(p, v, f),
               "stl-ascii": meshgen.write_stl_ascii, "obj": meshgen.write_obj,
               "ply": lambda p, v, f, q: meshgen.write_ply_binary(p, v, f)}
    for (kind, n), group in groups.items():
        todo = [f for f in group
                if not (f["path"].exists() and manifest.get(f["name"], {}).get("gen") == ver
                        and manifest[f["name"]].get("bytes") == f["path"].stat().st_size)]
        arrays = None
        if todo or f"{kind}:{n}" not in refs.d:
            arrays = meshgen.make(kind, n)
        for f in todo:
            v, faces, q = arrays
            t0 = time.perf_counter()
            writers[f["fmt"]](f["path"], v, faces, q)
            manifest[f["name"]] = {"gen": ver, "bytes": f["path"].stat().st_size,
                                   "triangles": int(len(faces))}
            manifest_path.write_text(json.dumps(manifest, indent=1))
            log(f"wrote {f['name']} ({f['path'].stat().st_size / 1e6:.1f} MB, "
                f"{time.perf_counter() - t0:.1f} s)")
        ref, ntri, _ = refs.get(kind, n, arrays)
        for f in group:
            f["ref"] = ref
            f["triangles"] = ntri
            f["mb"] = f["path"].stat().st_size / 1e6
        del arrays


# --------------------------------------------------------------------------- peers


PROBE = r"""
import importlib, importlib.metadata, json, sys
out = {}
for name, mod, dist in json.loads(sys.argv[1]):
    try:
        importlib.import_module(mod)
        try:
            ver = importlib.metadata.version(dist)
        except Exception:
            ver = "installed"
        out[name] = {"ok": True, "version": ver}
    except BaseException as e:
        out[name] = {"ok": False, "reason": f"{type(e).__name__}: {e}".splitlines()[0][:200]}
print(json.dumps(out))
"""


def probe_peers() -> dict:
    """Which peers import, in a child process (an import can fail on a missing system library,
    as Open3D does without libusb); with the reason from `run`'s pip log when pip failed."""
    spec = json.dumps([[n, m, d] for n, (m, d, _) in PEERS.items()])
    try:
        p = subprocess.run([PY, "-c", PROBE, spec], capture_output=True, text=True, timeout=300)
        res = json.loads(p.stdout.strip().splitlines()[-1])
    except (subprocess.SubprocessError, ValueError, IndexError) as e:
        res = {n: {"ok": False, "reason": f"import probe failed: {e}"} for n in PEERS}
    installs = load_json(OUT / "install.json", {})
    for name, (_, dist, _) in PEERS.items():
        r = res.setdefault(name, {"ok": False, "reason": "not probed"})
        if not r["ok"] and dist in installs and installs[dist].get("error"):
            r["reason"] = f"pip install failed: {installs[dist]['error']}"
        elif not r["ok"] and "No module named" in r.get("reason", ""):
            r["reason"] = "not installed in the venv (" + r["reason"] + ")"
    return res


# --------------------------------------------------------------------------- end-to-end


def tool_volume(out: dict | None):
    if not out or "refused" in out:
        return None
    v = out.get("signed_volume", out.get("volume"))
    return float(v) if v is not None else None


def run_end_to_end(ctx: Ctx, files, main_name):
    args = ctx.args
    rows = []
    meshvol = ctx.meshvol
    helptext = ""
    try:
        helptext = subprocess.run(meshvol + ["volume", "--help"], capture_output=True, text=True,
                                  timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        pass
    variants = []  # meshvol's own options, timed on binary STL where the binary has them
    if "--threads" in helptext:
        variants.append(("meshvol --threads 1", ["--threads", "1"], True))
    if "--exact" in helptext:
        variants.append(("meshvol --exact", ["--exact"], False))
    if "--no-check" in helptext:
        # Read and measure only, as wound, like the peers: the topology check skipped.
        variants.append(("meshvol --no-check", ["--no-check"], False))
    # smallest first, so that a peer's time on a small file decides whether it is started on a
    # bigger one (Projector); of equal sizes the main file first, then binary before text
    fmts = ["stl", "ply", "stl-ascii", "obj"]
    order = sorted(files, key=lambda f: (f["target"], f["name"] != main_name,
                                         fmts.index(f["fmt"]), f["name"]))
    for f in order:
        path = str(f["path"])
        main = f["name"] == main_name
        tools = [("cat", ["cat", path]), ("meshvol", meshvol + ["volume", path, "--json"])]
        for name, extra, before in variants:
            # Every variant on binary STL; on the other formats, the unchecked path only.
            if f["fmt"] == "stl" or extra == ["--no-check"]:
                tools.append((name, meshvol + extra + ["volume", path, "--json"] if before
                              else meshvol + ["volume", path, "--json"] + extra))
        for tool, (script, fmts) in E2E_TOOLS.items():
            if f["fmt"] in fmts and ctx.wants(tool):
                tools.append((tool, [PY, str(TOOLS_DIR / script), path]))
        if main and not args.quick:  # how much of a Python tool's time is start-up alone
            for tool, mod in IMPORT_ONLY.items():
                if ctx.wants(tool):
                    tools.append((f"{tool} (import only)", [PY, "-c", f"import {mod}"]))
        for tool, argv in tools:
            row = {"category": "end-to-end", "section": "volume", "item": f["name"], "tool": tool,
                   "file": f["name"], "fmt": f["fmt"], "triangles": f["triangles"], "mb": f["mb"],
                   "main": main}
            is_mv = tool == "cat" or tool.startswith("meshvol")
            if tool.endswith("(import only)"):
                ctx.run(row, argv, key=("volume", tool), size=1, keep_stdout=False, budget=1.0)
                rows.append(row)
                continue
            ctx.run(row, argv, meshvol=is_mv, key=None if is_mv else ("volume", tool, f["fmt"]),
                    size=f["triangles"], main=main, keep_stdout=tool != "cat")
            rows.append(row)
            if tool == "cat" or "median_s" not in row and "output" not in row:
                continue
            out = row.get("output")
            vol = tool_volume(out)
            if row.get("refused"):
                continue
            if vol is None:
                row.setdefault("error", "no JSON object with a volume in its output")
                continue
            row["volume"] = vol
            row["rel_err"] = meshgen.rel_error(vol, f["ref"])
            row["correctly_rounded"] = vol == float(f["ref"])
            bound = out.get("volume_error_bound")
            if isinstance(bound, (int, float)) and abs(Fraction(vol) - f["ref"]) > Fraction(bound):
                row["note"] = f"error exceeds its own volume_error_bound {bound:.3g}"
            if out.get("triangles") not in (None, f["triangles"]):
                row["note"] = (row.get("note", "") + f"; reports {out.get('triangles')} "
                               "triangles").lstrip("; ")
    return rows


# --------------------------------------------------------------------------- in-process


def _staged(argv, setup_timeout, cap, rest_timeout):
    """Run an inprocess.py worker: wait up to setup_timeout for its 'ready' line, up to cap
    for the warm-up line, then up to rest_timeout for the result. (result dict | None, error)."""
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    q: queue.Queue = queue.Queue()
    err_lines: list[str] = []

    def pump():
        for line in p.stdout:
            q.put(line)
        q.put(None)

    def pump_err():
        for line in p.stderr:
            err_lines.append(line)

    threading.Thread(target=pump, daemon=True).start()
    threading.Thread(target=pump_err, daemon=True).start()
    stage, limits = 0, [setup_timeout, cap, rest_timeout]
    deadline = time.perf_counter() + limits[0]
    result, over = None, None
    while True:
        try:
            line = q.get(timeout=max(0.01, deadline - time.perf_counter()))
        except queue.Empty:
            over = ("setup", setup_timeout) if stage == 0 else ("warm-up", cap) if stage == 1 \
                else ("runs", rest_timeout)
            kill_group(p)
            break
        if line is None:
            break
        d = parse_json_lines(line, keys=None)
        if not d:
            continue
        if "ready" in d and stage == 0:
            stage, deadline = 1, time.perf_counter() + limits[1]
        elif "warmup_s" in d and "times" not in d and stage == 1:
            stage, deadline = 2, time.perf_counter() + limits[2]
        elif "refused" in d or "times" in d:
            result = d
    p.wait()
    if over:
        return None, over
    if result is None:
        return None, f"exit {p.returncode}: " + last_line("".join(err_lines))
    return result, None


# The in-process meshes: a UV sphere numbered ring by ring (each triangle's corners near
# the last one's in memory), and the same sphere with its vertices numbered in random order
# (as meshes from remeshing or format conversion can be), where every corner read misses.
INPROCESS_KINDS = {"sphere": "sphere", "sphere_shuffled": "sphere, vertices shuffled"}

# Timed calls per in-process cell, at most (within the cell's budget): calls of a few
# milliseconds vary by ±30% one to the next on a shared machine. With five (the
# whole-process default) the 2026-11-28 run gave meshvol's 1M volume 3.3 ms, where sixty
# calls in each of six processes right after gave medians of 1.9–2.6 ms.
INPROCESS_RUNS = 60


def run_in_process(ctx: Ctx, sizes, refs):
    args = ctx.args
    rows = []
    for tool, kind, n in ((t, k, n) for t in INPROCESS_TOOLS for k in INPROCESS_KINDS for n in sizes):
        if not ctx.wants(tool):
            continue
        label = f"{INPROCESS_KINDS[kind]} {size_label(n)} (arrays)"
        row = {"category": "in-process", "section": "inprocess",
               "tool": {"meshvol-py": "meshvol (Python)",
                        "meshvol-py-mp": "meshvol mass_properties (Python)"}.get(tool, tool),
               "item": label, "file": label, "kind": kind, "target": n}
        key = ("inprocess", tool)
        cap, skip = plan_cell(ctx.clock, ctx.proj, key, n, args.peer_timeout)
        if skip:
            row["skipped"] = skip
            log(f"in-process {tool:<10} {kind} {size_label(n):<5} {skip}")
            rows.append(row)
            continue
        ref, ntri, _ = refs.get(kind, n)
        row["triangles"] = ntri
        budget = max(0.0, min(args.cell_seconds, ctx.clock.left() - cap))
        argv = [PY, str(TOOLS_DIR / "inprocess.py"), tool, kind, str(n),
                str(INPROCESS_RUNS), str(budget)]
        out, err = _staged(argv, setup_timeout=max(60.0, 20 * n / 1e6), cap=cap,
                           rest_timeout=2 * budget + cap + 10)
        if isinstance(err, tuple):
            stage, secs = err
            if stage == "warm-up":
                row["over"] = cap
                row["error"] = f"> {cap:.0f} s (cut off)"
            else:
                row["error"] = f"{stage} took over {secs:.0f} s"
            ctx.proj.record(key, n, cap, over=True)
        elif err:
            row["error"] = err
            ctx.proj.record(key, n, args.peer_timeout + 1, over=True)
        elif "refused" in out:
            row["refused"] = out["refused"]
        else:
            row.update(times=out["times"], median_s=statistics.median(out["times"]),
                       peak_mb=out["peak_rss_mb"], setup_mb=out["rss_before_timing_mb"],
                       volume=out["volume"], rel_err=meshgen.rel_error(out["volume"], ref),
                       correctly_rounded=out["volume"] == float(ref),
                       warmup_is_sample=out["warmup_is_sample"], method=out["note"])
            ctx.proj.record(key, n, out["warmup_s"])
        msg = row.get("error") or (f"refused: {row['refused']}" if "refused" in row
                                   else f"{row['median_s']:.3f} s (n={len(row['times'])})")
        log(f"in-process {tool:<10} {kind} {size_label(n):<5} {msg}")
        rows.append(row)
    return rows


# --------------------------------------------------------------------------- environment


def sh(cmd: list[str]) -> str:
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=30, cwd=ROOT)
        return (p.stdout or p.stderr).strip().splitlines()[0] if p.returncode == 0 else ""
    except (OSError, subprocess.SubprocessError, IndexError):
        return ""


def machine_info() -> dict:
    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    ram = "unknown"
    try:
        kb = int(re.search(r"MemTotal:\s+(\d+)", Path("/proc/meminfo").read_text()).group(1))
        ram = f"{kb / 1024**2:.1f} GiB"
    except (OSError, AttributeError):
        pass
    try:
        load = " ".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        load = "unknown"
    return {"nproc": os.cpu_count(), "cpu": cpu, "ram": ram, "load": load,
            "os": f"{platform.system()} {platform.release()}",
            "python": platform.python_version()}


def versions(args) -> dict:
    v = {}
    mv = shlex.split(args.meshvol)
    ver = sh(mv + ["--version"])
    rev = sh(["git", "rev-parse", "--short", "HEAD"])
    dirty = sh(["git", "status", "--porcelain", "--untracked-files=no"])
    v["meshvol"] = (ver or "(no --version)") + (f", git {rev}" if rev else "") + \
        (" + uncommitted changes" if dirty else "") + f"; command: `{args.meshvol}`"
    for dist in ("numpy", "matplotlib"):
        try:
            import importlib.metadata

            v[dist] = importlib.metadata.version(dist)
        except Exception:
            v[dist] = "not installed"
    v["rustc"] = sh(["rustc", "--version"]) or "unknown"
    v["hyperfine"] = sh(["hyperfine", "--version"]) if shutil.which("hyperfine") else \
        "not installed (own perf_counter timing)"
    return v


def criterion_estimates() -> list[tuple[str, float, str]]:
    base = ROOT / "target" / "criterion"
    found = []
    if not base.is_dir():
        return found
    for est in sorted(base.glob("**/new/estimates.json")):
        bench = est.parent / "benchmark.json"
        name = load_json(bench, {}).get("full_id") or str(est.parent.parent.relative_to(base))
        mean = load_json(est, {}).get("mean", {}).get("point_estimate")
        if mean is not None:
            when = _dt.datetime.fromtimestamp(est.stat().st_mtime, _dt.timezone.utc)
            found.append((name, mean / 1e9, f"{when:%Y-%m-%d %H:%M}"))
    return found


# --------------------------------------------------------------------------- report


def report_volume(e2e, main_name) -> tuple[list[str], list[str]]:
    L = ["## Mesh volume, end-to-end, by file\n"]
    if not e2e:
        return L + ["Not run.\n"], []
    L.append("Fresh process per run: read the file, print volume (and, where the tool gives them, "
             "centroid and inertia). `cat` is the I/O floor; `(import only)` rows time "
             "`python -c 'import MODULE'`, the start-up part of a Python tool's time. The ratio and "
             "**meshvol ahead?** compare each row with the plain `meshvol` row of the same file; "
             "a refusal is not a result, so it is neither ahead nor behind.\n")
    L.append("| tool | file | size MB | median s | runs | ratio to meshvol | peak MB | relative volume error | meshvol ahead? |")
    L.append("|---|---|--:|--:|--:|--:|--:|--:|---|")
    behind, acc, compared = [], [], 0
    by_file: dict[str, list[dict]] = {}
    for r in e2e:
        by_file.setdefault(r["file"], []).append(r)
    kinds = ["sphere", "torus", "sphere_far", "cubes"]
    fmts = ["stl", "ply", "stl-ascii", "obj"]
    file_order = sorted(by_file, key=lambda n: (
        n != main_name, fmts.index(by_file[n][0]["fmt"]),
        kinds.index(n.rsplit("_", 1)[0]) if n.rsplit("_", 1)[0] in kinds else 9,
        by_file[n][0]["triangles"], n))
    for name in file_order:
        group = by_file[name]
        mv = next((r for r in group if r["tool"] == "meshvol" and "median_s" in r), None)
        mv_s = mv["median_s"] if mv else None
        timed = [r for r in group if "median_s" in r
                 and r["tool"] != "cat" and not r["tool"].endswith("(import only)")]
        fastest = min(timed, key=lambda r: r["median_s"]) if timed else None
        if not mv:
            behind.append(f"`{name}` (meshvol has no time: "
                          f"{next((r.get('error') for r in group if r['tool'] == 'meshvol'), 'not run')})")
        for r in group:
            tool = r["tool"] + (" (I/O floor)" if r["tool"] == "cat" else "")
            label = f"{r['file']} ({FORMAT_LABEL[r['fmt']]}, {r['triangles']:,} tri)"
            peer = not (r["tool"] == "cat" or r["tool"].startswith("meshvol")
                        or r["tool"].endswith("(import only)"))
            if peer and seconds_of(r) and mv_s and not r.get("refused"):
                compared += 1
                if is_behind(r, mv_s):
                    behind.append(f"{r['tool']} on `{name}` ({fmt_s(r['median_s'])} s vs meshvol "
                                  f"{fmt_s(mv_s)} s)")
                if mv and "rel_err" in mv and "rel_err" in r and r["rel_err"] < mv["rel_err"]:
                    acc.append(f"{r['tool']} on `{name}` ({fmt_err(r['rel_err'])} vs meshvol "
                               f"{fmt_err(mv['rel_err'])})")
            if r.get("skipped") and not r["skipped"].startswith(">"):
                L.append(f"| {tool} | {label} | {r['mb']:.1f} | not run | | | | {md_cell(r['skipped'])} | |")
                continue
            err = fmt_err(r.get("rel_err")) if "rel_err" in r else ""
            if r.get("correctly_rounded"):
                err += " ✓"
            if r.get("refused"):
                err = f"refused: {r['refused']}"
            elif "over" in r:
                err = r["error"].replace(f"> {r['over']:.0f} s (cut off)", "cut off")
            elif r.get("error"):
                err = r["error"]
            elif r.get("skipped"):
                err = "not started: " + r["skipped"].split("(", 1)[-1].rstrip(")")
            if r.get("note"):
                err += f" ({r['note']})"
            ratio = ratio_cell(r, mv_s) if r["tool"] != "meshvol" else ("1.00" if mv else "")
            ahead = ahead_cell(r, mv_s) if peer else ""
            L.append(f"| {tool} | {label} | {r['mb']:.1f} | {time_cell(r, bold=r is fastest)} | "
                     f"{runs_cell(r)} | {ratio} | {fmt_mb(r.get('peak_mb'))} | {md_cell(err)} | {ahead} |")
    L.append("")
    if behind:
        L.append("**Where meshvol is not ahead (end-to-end volume):** " + "; ".join(behind) + ".\n")
    elif compared:
        L.append(f"meshvol is ahead of every peer that gave a volume, on every file "
                 f"({compared} comparisons; `cat` aside).\n")
    if acc:
        L.append("**More accurate than meshvol:** " + "; ".join(acc) + ".\n")
    return L, behind + [f"accuracy: {a}" for a in acc]


def report_inprocess(inp) -> tuple[list[str], list[str]]:
    L = ["## Mesh volume, in-process, on arrays already in memory\n"]
    if not inp:
        return L + ["Not run.\n"], []
    measured = any(r["tool"] == "meshvol (Python)" and "median_s" in r for r in inp)
    L.append(f"Each tool runs in its own Python process: one warm-up call, then up to "
             f"{INPROCESS_RUNS} timed calls within the cell's time budget; the table gives their median. "
             "Each run builds the tool's mesh object from (vertices, faces) outside the timer, "
             "so no cached result carries over; the timer covers the mass-property call only (for "
             "manifold3d, which has no other way in, the `Manifold` build plus `volume()` and "
             "`surface_area()`; for Open3D, `get_volume()`, which first runs `is_watertight()` "
             "with its all-pairs self-intersection test). Peak MB is the whole Python process. "
             "meshvol's row is its Python binding (`meshvol.volume(v, f, check=False)`: the signed volume and "
             "its rounding bound of the surface as wound, like the peers, the arrays read in place; "
             "crates/meshvol-py) when that is installed in the venv, and the next row its full "
             "`meshvol.Mesh(v, f).mass_properties(check=False)` (mesh built outside the timer); the ratio and **meshvol "
             "ahead?** then compare with it. Otherwise they compare with meshvol's criterion "
             "estimate (†) of a mesh within 10% of the row's size, where there is one: "
             + CRITERION_NOTE + " A † verdict is indicative only (a different mesh, measured "
             "by `cargo bench`, not by this run).\n")
    if not measured:
        L.append("meshvol's Python binding is not installed in the venv, so meshvol has no "
                 "measured row here (`bench/out/venv/bin/pip install ./crates/meshvol-py` adds "
                 "one; it builds the binding with maturin).\n")
    crit = criterion_estimates()
    crit_mv = {}
    for name, secs, _ in crit:
        m = re.fullmatch(r"mass_properties/meshvol/(\d+)", name)
        if m:
            crit_mv[int(m.group(1))] = (name, secs)
    mv_rows = {(r.get("kind"), r["target"]): r for r in inp
               if r["tool"] == "meshvol (Python)" and "median_s" in r}
    L.append("| tool | mesh | triangles | median s | runs | ratio to meshvol | peak MB | relative volume error | meshvol ahead? |")
    L.append("|---|---|--:|--:|--:|--:|--:|--:|---|")
    behind, compared = [], 0
    for r in inp:
        tri = f"{r['triangles']:,}" if "triangles" in r else f"~{size_label(r['target'])}"
        # meshvol's own rows (the reference, and its mass_properties row): no verdict
        is_mv = r["tool"].startswith("meshvol")
        is_ref = r["tool"] == "meshvol (Python)"
        mv_s, dagger = None, ""
        if (r.get("kind"), r["target"]) in mv_rows:
            mv_s = mv_rows[(r.get("kind"), r["target"])]["median_s"]
        elif "triangles" in r:
            near = [v for n, v in crit_mv.items() if abs(n - r["triangles"]) <= 0.1 * n]
            if near:
                mv_s, dagger = near[0][1], " †"
        ahead = "" if is_mv else (ahead_cell(r, mv_s) + dagger if mv_s else "n/a")
        if not is_mv and mv_s and seconds_of(r) and not r.get("refused"):
            compared += 1
        if not is_mv and is_behind(r, mv_s):
            behind.append(f"{r['tool']} on {r['file']} ({fmt_s(r['median_s'])} s vs meshvol "
                          f"{fmt_s(mv_s)} s{' (criterion, indicative)' if dagger else ''})")
        note = ""
        if r.get("refused"):
            note = f"refused: {r['refused']}"
        elif r.get("skipped"):
            note = r["skipped"]
        elif "median_s" not in r:
            note = r.get("error", "")
        if "median_s" not in r:
            L.append(f"| {r['tool']} | {r['file']} | {tri} | {time_cell(r)} | | "
                     f"{'' if is_mv else ratio_cell(r, mv_s) + (dagger if mv_s else '')} | | "
                     f"{md_cell(note)} | {ahead} |")
            continue
        ratio = "1.00" if is_ref else (ratio_cell(r, mv_s) + dagger if mv_s else "")
        cr = " ✓" if r.get("correctly_rounded") else ""
        L.append(f"| {r['tool']} | {r['file']} | {tri} | {fmt_s(r['median_s'])} | {runs_cell(r)} | "
                 f"{ratio} | {fmt_mb(r['peak_mb'])} | {fmt_err(r['rel_err'])}{cr} | {ahead} |")
    L.append("")
    if behind:
        L.append("**Where meshvol is not ahead (in-process volume):** " + "; ".join(behind) + ".\n")
    elif compared:
        L.append(f"meshvol is ahead of every peer with a time and a meshvol figure to compare with "
                 f"({compared} comparisons{'; † ones indicative' if not measured else ''}).\n")
    else:
        L.append("No peer row has a meshvol figure of its size to compare with, so this table "
                 "gives no verdict.\n")
        behind = [NO_VERDICT]
    if crit and not measured:
        L.append("meshvol criterion estimates found in `target/criterion/` (mean per iteration; from "
                 "the last `cargo bench -p meshvol-bench`, not from this run):\n")
        L.append("| benchmark | mean s | measured (UTC) |")
        L.append("|---|--:|---|")
        for name, secs, when in crit:
            L.append(f"| {name} | {secs:.6f} | {when} |")
        L.append("")
    return L, behind


def write_report(path: Path, res: dict, files, info, vers, peers, args, started, main_name,
                 chart_ok, duration, clock: Clock):
    L = []
    L.append("# meshvol compared with its peers\n")
    cmdline = "bench/compare/run" + ("" if not args.argv else " " + shlex.join(args.argv))
    L.append(f"Generated by `{cmdline}` on {started:%Y-%m-%d %H:%M} UTC in {duration / 60:.1f} min "
             f"(time budget {args.time_budget:g} min). Not part of CI; see "
             "[bench/compare/README.md](compare/README.md) for the method.\n")
    if args.quick:
        L.append("**Quick run: small sizes, short budgets. For checking the harness, not the numbers "
                 "to quote.**\n")
    if not is_release_build(args.meshvol):
        L.append(f"**meshvol was run as `{args.meshvol}`, not the release build "
                 "`target/release/meshvol`: its times are not meshvol's.**\n")
    reports = {}
    reports["volume"] = report_volume(res.get("volume", []), main_name)
    reports["inprocess"] = report_inprocess(res.get("inprocess", []))
    reports["check"] = sections.report_check(res.get("check", []), res.get("check_files", []))
    if res.get("grid_file"):
        reports["grid"] = sections.report_grid(res.get("grid", []), res["grid_file"], res["params"])
    reports["union"] = sections.report_union(res.get("union", []))
    reports["intersect"] = sections.report_intersect(res.get("intersect", []),
                                                     res.get("intersect_voxels", []))
    if res.get("profile_file"):
        reports["profile"] = sections.report_profile(res.get("profile", []), res["profile_file"])
    reports["scaling"] = sections.report_scaling(res.get("scaling", []), res.get("scaling_files", []))
    if res.get("scaling_chart"):
        reports["scaling"][0].append(f"![meshvol time and memory against triangles]"
                                     f"({os.path.relpath(res['scaling_chart'], path.parent)})\n")
    reports["hull"] = sections.report_hull(res.get("hull", []), res.get("hull_clouds", []))
    reports["area"] = sections.report_area(res.get("area", []), res.get("area_files", []))

    L.append("## Summary: where meshvol is not ahead\n")
    L.append("Computed from the tables below: a peer is \"ahead\" where its time is at most "
             "meshvol's (or its error smaller), in the comparison each section defines. A peer "
             "that was cut off (`> N s`) or refused the input is not ahead.\n")
    for s in SECTIONS:
        if s not in args.sections:
            L.append(f"- {SECTION_TITLE[s]}: not run (not selected).")
            continue
        lines, behind = reports.get(s, ([], []))
        if s == "scaling":
            L.append(f"- {SECTION_TITLE[s]}: no peers, no verdict; see its table.")
            continue
        if NO_VERDICT in behind:
            L.append(f"- {SECTION_TITLE[s]}: no verdict (no meshvol figure of a matching size in "
                     "this run or in target/criterion/).")
            continue
        proc = [b for b in behind if not b.startswith("kernel only: ")]
        kern: dict[str, int] = {}
        for b in behind:
            if b.startswith("kernel only: "):
                tool = b[len("kernel only: "):].split(" on ")[0]
                kern[tool] = kern.get(tool, 0) + 1
        text = ("**not ahead** on " + "; ".join(proc) + "." if proc else
                "ahead of every peer with a result" + (" (whole process)." if kern else "."))
        if kern:
            text += (" **Kernel alone**, the peer's computation after reading and parsing took no "
                     "longer than meshvol's whole process for " +
                     ", ".join(f"{t} on {n} input{'s' if n > 1 else ''}" for t, n in kern.items()) +
                     " (meshvol reports no kernel time there; see the section).")
        L.append(f"- {SECTION_TITLE[s]}: {text}")
    L.append("")

    L.append("## Peers\n")
    L.append("| peer | version | used for | status |")
    L.append("|---|---|---|---|")
    for name, (_, dist, use) in PEERS.items():
        p = peers.get(name, {})
        shown = "meshvol (Python binding)" if name == "meshvol-py" else name
        if p.get("ok"):
            sel = "" if not args.tools or name in args.tools or name == "meshvol-py" \
                else " (left out by --tools)"
            L.append(f"| {shown} | {p.get('version', '')} | {use} | installed{sel} |")
        elif name == "meshvol-py":
            L.append(f"| {shown} | | {use} | not installed (optional) |")
        else:
            L.append(f"| {shown} | | {use} | **skipped**: {md_cell(p.get('reason', 'unknown'))} |")
    L.append("")
    L.append("## Machine and versions\n")
    L.append(f"- CPU: {info['cpu']}, {info['nproc']} logical CPUs (`nproc`); RAM {info['ram']}; "
             f"{info['os']}; Python {info['python']}")
    L.append(f"- Load average (1, 5, 15 min): {info['load']} at the start, "
             f"{info.get('load_end', '?')} at the end. Above {info['nproc']} means other work "
             "competed for the CPUs and every time here is inflated.")
    for k, val in vers.items():
        L.append(f"- {k}: {val}")
    L.append("")
    L.append("## Method\n")
    L.append(
        f"- Timing: every command is a fresh process. One warm-up run (page cache warm, output "
        f"kept, peak memory from `/usr/bin/time -v` or tools/rss_launch.py), then up to {args.runs} "
        f"timed runs (hyperfine `-N` where installed) within {args.cell_seconds:g} s "
        f"({args.main_cell_seconds:g} s on the main file `{main_name}`); the table gives the "
        "median. `1*`: the warm-up itself is the only sample.")
    L.append(
        f"- Cut-offs: a peer's run is stopped after {args.peer_timeout:g} s (`--peer-timeout`) and "
        "shown as `> N s`; a peer whose time, projected linearly from its last run in the section, "
        "is over that (or that was cut off on an input at most 25% larger) is not started and is "
        "shown as `> N s (projected ...)`. The whole "
        f"run has a budget of {args.time_budget:g} min (`--time-budget`), shared among the "
        "sections as they start (" + ", ".join(
            f"{s} {clock.allowance.get(s, 0):.0f} s (used {clock.used.get(s, 0):.0f} s)"
            for s in SECTIONS if s in args.sections) +
        "); a peer cell with no time left is `not run`. meshvol itself always runs.")
    L.append(
        "- **Ratio** = tool time / meshvol time on the same input (above 1: slower than meshvol). "
        "The fastest tool of each file (ignoring `cat`) is in bold in the volume table.")
    L.append(
        "- **Relative error** = |tool − exact| / |exact|, exact being the exact rational value "
        "for the numbers in the file (all formats of a mesh hold the same numbers). ✓ marks a "
        "result equal to the exact volume correctly rounded to float64.")
    L.append(
        "- Meshes: UV spheres (radius 100) and tori (100, 40), coordinates on a 2^-10 grid; "
        "`sphere_far` is centred at (1e6, 1e6, 1e6), where float32 spacing is 1/16; `cubes` is a "
        "grid of disjoint boxes of random sizes. Binary STL and PLY are float32; ASCII STL and OBJ "
        "print the same values exactly.")
    L.append("")
    for s in SECTIONS:
        if s in args.sections and s in reports:
            L.extend(reports[s][0])
    if files:
        L.append("## Reference volumes\n")
        L.append("| mesh | triangles | exact volume (rounded) |")
        L.append("|---|--:|--:|")
        seen = set()
        for f in files:
            k = (f["kind"], f["target"])
            if k not in seen and "ref" in f:
                seen.add(k)
                L.append(f"| {f['kind']} {size_label(f['target'])} | {f['triangles']:,} | {float(f['ref']):.17g} |")
        L.append("")
    if chart_ok:
        L.append("## Chart\n\n![Seconds per tool in each section](RESULTS.png)\n")
    path.write_text("\n".join(L))


def write_chart(path: Path, res: dict, main_name) -> bool:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log("matplotlib missing: no chart")
        return False
    panels = []
    pts = []
    for r in res.get("volume", []):
        if r["file"] == main_name and not r["tool"].endswith("(import only)"):
            s = seconds_of(r)
            if s:
                pts.append(("cat (I/O floor)" if r["tool"] == "cat" else r["tool"] + (" (>)" if s[1] else ""),
                            s[0], r["tool"].startswith("meshvol") or r["tool"] == "cat"))
    if pts:
        panels.append((f"volume, end-to-end: {main_name}", pts))
    for s in ("check", "grid", "union", "intersect", "profile", "hull", "area"):
        c = sections.chart_items(s, res.get(s, []))
        if c:
            panels.append(c)
    if not panels:
        return False
    ncol = 2 if len(panels) > 1 else 1
    nrow = (len(panels) + ncol - 1) // ncol
    heights = [max(len(p[1]) for p in panels[i * ncol:(i + 1) * ncol]) for i in range(nrow)]
    fig, axes = plt.subplots(nrow, ncol, figsize=(7 * ncol, sum(0.42 * h + 1.3 for h in heights)),
                             gridspec_kw={"height_ratios": [0.42 * h + 1.3 for h in heights]},
                             squeeze=False)
    for ax in axes.ravel()[len(panels):]:
        ax.axis("off")
    for ax, (title, items, *rest) in zip(axes.ravel(), panels):
        xlabel = rest[0] if rest else "seconds, whole process, median (log; lower is better)"
        names = [n for n, _, _ in items]
        vals = [v for _, v, _ in items]
        colors = ["#999999" if n.startswith("cat") else "#d62728" if mv else "#1f77b4"
                  for n, _, mv in items]
        bars = ax.barh(names, vals, color=colors)
        ax.set_xscale("log")
        ax.invert_yaxis()
        for b, v in zip(bars, vals):
            ax.text(b.get_width() * 1.05, b.get_y() + b.get_height() / 2, f"{v:.3g} s", va="center",
                    fontsize=8)
        ax.set_xlim(min(vals) / 2, max(vals) * 8)
        ax.set_title(title, fontsize=10)
        ax.tick_params(axis="y", labelsize=8)
        ax.set_xlabel(xlabel, fontsize=8)
    fig.suptitle("meshvol (red) and its peers (blue); (>) = cut off, at least that long", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


# --------------------------------------------------------------------------- main


def default_meshvol() -> str:
    return str(ROOT / "target" / "release" / "meshvol")


def is_release_build(cmd: str) -> bool:
    parts = shlex.split(cmd)
    return len(parts) == 1 and Path(parts[0]).resolve() == Path(default_meshvol()).resolve()


def build_parser():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    g = ap.add_argument_group("what to run")
    g.add_argument("--quick", action="store_true",
                   help="small sizes and short budgets (< 4 min): for checking the harness")
    g.add_argument("--only", help="comma-separated sections to run: " + ",".join(SECTIONS) +
                   " (scaling runs only when named here)")
    g.add_argument("--skip", help="comma-separated sections to leave out")
    g.add_argument("--tools", help="comma-separated peers to run (default: all installed): " +
                   ",".join(PEERS))
    g.add_argument("--meshvol", default=default_meshvol(),
                   help="meshvol command (default: target/release/meshvol)")
    g.add_argument("--no-build", action="store_true",
                   help="(for `run`) use target/release/meshvol as it is, without cargo build")
    g.add_argument("--no-inprocess", action="store_true", help="same as --skip inprocess")
    g.add_argument("--no-end-to-end", action="store_true", help="same as --skip volume")
    s = ap.add_argument_group("sizes")
    s.add_argument("--sizes", help="mesh sizes in triangles for the volume section, e.g. "
                   "100k,1m,5m,10m (default; --quick: 100k)")
    s.add_argument("--inprocess-sizes", help="in-process sphere sizes (default 100k,1m; --quick 100k)")
    s.add_argument("--check-size", type=parse_size,
                   help="triangles of the check and grid meshes (default 1m; --quick 100k)")
    s.add_argument("--grid-cells", help="grid sizes n (n³ cells); peers run on the first "
                   "(default 256,512; --quick 64,128)")
    s.add_argument("--grid-sample", type=int, help="partial cells timed with manifold3d (30; quick 10)")
    s.add_argument("--union-bodies", help="COUNT,TRIANGLES of the union spheres (20,20k; quick 6,5k)")
    s.add_argument("--hull-points", type=parse_size, help="points per hull cloud (1M; quick 10k)")
    s.add_argument("--area-vertices", type=parse_size,
                   help="vertices of the big polygon (1m; quick 100k)")
    s.add_argument("--area-polygons", type=parse_size,
                   help="number of small polygons (100k; quick 10k)")
    s.add_argument("--profile-levels", type=int,
                   help="slabs of the profile section, on the --check-size sphere (100; quick 20)")
    s.add_argument("--scaling-sizes", help="sphere sizes of the scaling section (only run when "
                   "named in --only), e.g. 100k,1m,5m,10m,20m (default; quick 100k,1m)")
    s.add_argument("--scaling-cells", type=int, help="grid n (n³ cells) timed in the scaling section (128)")
    t = ap.add_argument_group("time")
    t.add_argument("--time-budget", type=float,
                   help="minutes for the whole run, shared among the sections (13.5; quick 3)")
    t.add_argument("--peer-timeout", type=float,
                   help="a peer's run is cut off after this many seconds and reported as '> N s' "
                        "(30; quick 3)")
    t.add_argument("--timeout", type=float, default=300, help="hard limit for one meshvol run, s")
    t.add_argument("--runs", type=int, help="timed runs after the warm-up (5; quick 3)")
    t.add_argument("--cell-seconds", type=float,
                   help="timed-run budget per cell after the warm-up (2.5; quick 1)")
    t.add_argument("--main-cell-seconds", type=float,
                   help="the same on the main file (10; quick 2)")
    t.add_argument("--no-hyperfine", action="store_true", help="time with perf_counter")
    t.add_argument("--no-gnu-time", action="store_true",
                   help="peak memory from tools/rss_launch.py instead of /usr/bin/time -v")
    g.add_argument("--strict-hull", action="store_true",
                   help="exit 1 when meshvol's hull volume or area differs from the reference by "
                        "more than 1e-12 (relative), after writing the report")
    o = ap.add_argument_group("output")
    o.add_argument("--results", type=Path, default=ROOT / "bench" / "RESULTS.md")
    o.add_argument("--chart", type=Path, default=ROOT / "bench" / "RESULTS.png")
    return ap


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    args = build_parser().parse_args(argv)
    args.argv = argv
    q = args.quick
    started = _dt.datetime.now(_dt.timezone.utc)
    info = machine_info()
    if args.sizes:
        sizes = sorted({parse_size(s) for s in args.sizes.split(",") if s.strip()})
    else:
        sizes = [100_000] if q else [100_000, 1_000_000, 5_000_000, 10_000_000]
    if args.inprocess_sizes:
        inproc = sorted({parse_size(s) for s in args.inprocess_sizes.split(",") if s.strip()})
    else:
        inproc = [100_000] if q else [100_000, 1_000_000]
    defaults = dict(time_budget=3.0 if q else 13.5, peer_timeout=3.0 if q else 30.0,
                    runs=3 if q else 5, cell_seconds=1.0 if q else 2.5,
                    main_cell_seconds=2.0 if q else 10.0)
    for k, v in defaults.items():
        if getattr(args, k) is None:
            setattr(args, k, v)
    args.tools = set(args.tools.split(",")) if args.tools else None
    chosen = ([s.strip() for s in args.only.split(",")] if args.only
              else [s for s in SECTIONS if s not in DEFAULT_OFF])
    skip = {s.strip() for s in (args.skip or "").split(",") if s.strip()}
    if args.no_inprocess:
        skip.add("inprocess")
    if args.no_end_to_end:
        skip.add("volume")
    bad = [s for s in chosen + list(skip) if s not in SECTIONS]
    if bad:
        sys.exit(f"unknown section(s) {bad}; sections: {','.join(SECTIONS)}")
    args.sections = [s for s in SECTIONS if s in chosen and s not in skip]
    clock = Clock(args.time_budget * 60.0, {s: WEIGHTS[s] for s in args.sections})
    p = sections.params(args)

    peers = probe_peers()
    available = {n for n, r in peers.items() if r.get("ok")}
    for n, r in peers.items():
        if not r.get("ok"):
            log(f"{n} skipped: {r.get('reason')}")
    if args.tools:
        unknown = args.tools - set(PEERS) - {"meshvol"}
        if unknown:
            sys.exit(f"unknown tool(s) {sorted(unknown)}; peers: {','.join(PEERS)}")

    meshgen.selftest(verbose=False)
    mv = shlex.split(args.meshvol)
    if not shutil.which(mv[0]) and not Path(mv[0]).exists():
        sys.exit(f"meshvol not found at {mv[0]}: build it (cargo build --release -p meshvol-cli) "
                 "or pass --meshvol")

    files, main_name = plan_files(sizes, q) if "volume" in args.sections else ([], None)
    if main_name is None:
        main_name = f"sphere_{size_label(p['check_size'])}.stl"
    extra = []
    if "check" in args.sections or "grid" in args.sections or "profile" in args.sections:
        have = {f["name"] for f in files}
        for kind in (("sphere", "torus", "cubes") if "check" in args.sections else ("sphere",)):
            f = mesh_file(kind, p["check_size"], "stl")
            if f["name"] not in have:
                extra.append(f)
    refs = Refs()
    t0 = time.perf_counter()
    generate(files + extra, refs)
    log(f"meshes ready in {time.perf_counter() - t0:.1f} s: {len(files) + len(extra)} files in {DATA}")
    byname = {f["name"]: f for f in files + extra}

    runner = Runner(args)
    log("timing with", "hyperfine" if runner.hyperfine else "perf_counter",
        "; peak memory from", "/usr/bin/time -v" if runner.gnu_time else "tools/rss_launch.py")
    ctx = Ctx(args, runner, clock, available, mv)
    res: dict = {"params": p}
    for s in args.sections:
        clock.start(s)
        if s == "volume":
            res["volume"] = run_end_to_end(ctx, files, main_name)
        elif s == "inprocess":
            res["inprocess"] = run_in_process(ctx, inproc, refs)
        elif s == "check":
            cf = [byname[f"{k}_{size_label(p['check_size'])}.stl"] for k in ("sphere", "torus", "cubes")]
            res["check_files"] = cf
            res["check"] = sections.run_check(ctx, cf)
        elif s == "grid":
            res["grid_file"] = byname[f"sphere_{size_label(p['check_size'])}.stl"]
            res["grid"] = sections.run_grid(ctx, res["grid_file"], p)
        elif s == "union":
            res["union"] = sections.run_union(ctx, p)
        elif s == "intersect":
            res["intersect"], res["intersect_voxels"] = sections.run_intersect(ctx, p)
        elif s == "profile":
            res["profile_file"] = byname[f"sphere_{size_label(p['check_size'])}.stl"]
            res["profile"] = sections.run_profile(ctx, res["profile_file"], p)
        elif s == "scaling":
            res["scaling"], res["scaling_files"] = sections.run_scaling(ctx, p)
        elif s == "hull":
            res["hull"], res["hull_clouds"] = sections.run_hull(ctx, p)
        elif s == "area":
            res["area"], res["area_files"] = sections.run_area(ctx, p)
    clock.finish()

    info["load_end"] = machine_info()["load"]
    vers = versions(args)
    OUT.mkdir(parents=True, exist_ok=True)

    def clean(x):
        if isinstance(x, dict):
            return {k: clean(v) for k, v in x.items()}
        if isinstance(x, (list, tuple)):
            if len(x) > 100 and not all(isinstance(v, (int, float)) for v in x):
                return f"[{len(x)} items, left out]"
            return [clean(v) for v in x]
        if isinstance(x, (Path, Fraction)):
            return str(x)
        if isinstance(x, set):
            return sorted(x)
        return x

    raw = {"started": started.isoformat(), "machine": info, "versions": vers, "peers": peers,
           "args": clean({k: v for k, v in vars(args).items()}),
           "budget": {"allowance_s": clock.allowance, "used_s": clock.used},
           "results": clean(res)}
    (OUT / "results.json").write_text(json.dumps(raw, indent=1, default=str))
    chart_ok = write_chart(args.chart, res, main_name)
    scaling_chart = args.chart.with_name(args.chart.stem + "-scaling" + args.chart.suffix)
    res["scaling_chart"] = scaling_chart if sections.write_scaling_chart(
        scaling_chart, res.get("scaling", [])) else None
    duration = clock.elapsed()
    write_report(args.results, res, files + extra, info, vers, peers, args, started, main_name,
                 chart_ok, duration, clock)
    log(f"wrote {args.results}" + (f" and {args.chart}" if chart_ok else "") +
        f" in {duration / 60:.1f} min; raw numbers in {OUT / 'results.json'}")
    if args.strict_hull and "hull" in args.sections:
        worst = sections.hull_worst(res.get("hull", []), res.get("hull_clouds", []), "meshvol")
        if worst is None or worst > 1e-12:
            sys.exit(f"--strict-hull: meshvol's largest relative hull difference is {worst}")
        log(f"--strict-hull: meshvol's largest relative hull difference {worst:.1e} <= 1e-12")


if __name__ == "__main__":
    main()
