#!/usr/bin/env python3
"""Peer comparison of meshvol with trimesh, numpy-stl and manifold3d.

Normally started by bench/compare/run, which makes the virtualenv and builds meshvol.
Writes test meshes to bench/out/data/, raw numbers to bench/out/results.json, and the
report to bench/RESULTS.md and bench/RESULTS.png. See bench/compare/README.md.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import hashlib
import importlib.metadata
import importlib.util
import json
import math
import os
import platform
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from fractions import Fraction
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

import meshgen  # noqa: E402

PY = sys.executable
OUT = ROOT / "bench" / "out"
DATA = OUT / "data"
TOOLS_DIR = HERE / "tools"
CRITERION_NOTE = (
    "meshvol's own in-memory numbers come from its criterion benchmarks: "
    "`cargo bench -p meshvol-bench` ([crates/meshvol-bench](../crates/meshvol-bench/)); "
    "reports land in `target/criterion/`."
)
FORMAT_LABEL = {"stl": "binary STL", "stl-ascii": "ASCII STL", "obj": "OBJ"}
PY_TOOLS = {  # tool name -> (python module to import, distribution name)
    "trimesh": ("trimesh", "trimesh"),
    "numpy-stl": ("stl", "numpy-stl"),
    "manifold3d": ("manifold3d", "manifold3d"),
}


def log(*a):
    print("[compare]", *a, flush=True)


# --------------------------------------------------------------------------- planning


def parse_size(s: str) -> int:
    s = s.strip().lower().replace("_", "")
    mult = {"k": 1_000, "m": 1_000_000}.get(s[-1:], 1)
    return int(float(s[:-1] if mult > 1 else s) * mult)


def size_label(n: int) -> str:
    if n >= 1_000_000 and n % 1_000_000 == 0:
        return f"{n // 1_000_000}m"
    if n >= 1_000 and n % 1_000 == 0:
        return f"{n // 1_000}k"
    return str(n)


def plan_files(sizes: list[int]) -> tuple[list[dict], str]:
    """The end-to-end files and the name of the main one (chart, numpy-stl always runs)."""
    files = []

    def add(kind, n, fmt):
        ext = {"stl": ".stl", "stl-ascii": "_ascii.stl", "obj": ".obj"}[fmt]
        name = f"{kind}_{size_label(n)}{ext}"
        files.append({"name": name, "kind": kind, "target": n, "fmt": fmt, "path": DATA / name})

    mid = 1_000_000 if 1_000_000 in sizes else min(sizes)
    for n in sorted(sizes):
        add("sphere", n, "stl")
        add("torus", n, "stl")
        if n == mid:
            add("sphere_far", n, "stl")
            add("cubes", n, "stl")
    for n in sorted(s for s in sizes if s <= 1_000_000):  # text files of 5M+ are GBs
        add("sphere", n, "stl-ascii")
        add("sphere", n, "obj")
    return files, f"sphere_{size_label(mid)}.stl"


# --------------------------------------------------------------------------- data + refs


def gen_version() -> str:
    return hashlib.sha256((HERE / "meshgen.py").read_bytes()).hexdigest()[:16]


def load_json(path: Path, default):
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return default


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
            if f["fmt"] == "stl":
                meshgen.write_stl_binary(f["path"], v, faces)
            elif f["fmt"] == "stl-ascii":
                meshgen.write_stl_ascii(f["path"], v, faces, q)
            else:
                meshgen.write_obj(f["path"], v, faces, q)
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


# --------------------------------------------------------------------------- running


class Runner:
    def __init__(self, args):
        self.hyperfine = shutil.which("hyperfine") if not args.no_hyperfine else None
        gnu_time = Path("/usr/bin/time")
        self.gnu_time = None
        if gnu_time.exists() and not args.no_gnu_time:
            probe = subprocess.run([str(gnu_time), "-v", "true"], capture_output=True, text=True)
            if "Maximum resident set size" in probe.stderr:
                self.gnu_time = str(gnu_time)
        self.runs = args.runs
        self.cell_seconds = args.cell_seconds

    def once(self, argv, timeout, keep_stdout=True):
        """One run with peak RSS: (seconds, returncode, stdout, stderr, peak MB)."""
        with tempfile.TemporaryDirectory() as td:
            tfile = os.path.join(td, "time.txt")
            full = [self.gnu_time, "-v", "-o", tfile] + argv if self.gnu_time else argv
            t0 = time.perf_counter()
            try:
                p = subprocess.run(full, stdout=subprocess.PIPE if keep_stdout else subprocess.DEVNULL,
                                   stderr=subprocess.PIPE, timeout=timeout)
            except subprocess.TimeoutExpired:
                return time.perf_counter() - t0, "timeout", "", "", None
            dt = time.perf_counter() - t0
            out = (p.stdout or b"").decode("utf-8", "replace")
            err = p.stderr.decode("utf-8", "replace")
            peak = None
            if self.gnu_time:
                m = re.search(r"Maximum resident set size \(kbytes\): (\d+)",
                              Path(tfile).read_text() if os.path.exists(tfile) else "")
                peak = int(m.group(1)) / 1024.0 if m else None
            return dt, p.returncode, out, err, peak

    def once_rusage(self, argv, timeout, keep_stdout=True):
        """Like once() without /usr/bin/time: tools/rss_launch.py reports the child's rusage."""
        with tempfile.TemporaryDirectory() as td:
            rfile = os.path.join(td, "rss.txt")
            full = [PY, str(TOOLS_DIR / "rss_launch.py"), rfile] + argv
            t0 = time.perf_counter()
            try:
                p = subprocess.run(full, stdout=subprocess.PIPE if keep_stdout else subprocess.DEVNULL,
                                   stderr=subprocess.PIPE, timeout=timeout)
            except subprocess.TimeoutExpired:
                return time.perf_counter() - t0, "timeout", "", "", None
            dt = time.perf_counter() - t0
            try:
                peak = int(Path(rfile).read_text()) / 1024.0
            except (OSError, ValueError):
                peak = None
            return (dt, p.returncode, (p.stdout or b"").decode("utf-8", "replace"),
                    p.stderr.decode("utf-8", "replace"), peak)

    def measure(self, argv, timeout, keep_stdout=True, budget=None):
        """Warm-up (with output and peak memory), then the timed runs."""
        budget = self.cell_seconds if budget is None else budget
        first = (self.once if self.gnu_time else self.once_rusage)(argv, timeout, keep_stdout)
        warm, rc, out, err, peak = first
        res = {"warmup_s": warm, "peak_mb": peak, "stdout": out, "cmd": shlex.join(argv)}
        if rc != 0:
            res["error"] = ("timed out after %.0f s" % timeout) if rc == "timeout" else \
                f"exit {rc}: " + (err.strip().splitlines() or ["?"])[-1][:200]
            return res
        n = min(self.runs, int(budget // warm)) if warm > 0 else self.runs
        if n <= 0:
            res.update(times=[warm], warmup_is_sample=True, timer="warm-up run")
        elif self.hyperfine:
            with tempfile.TemporaryDirectory() as td:
                j = os.path.join(td, "h.json")
                cmd = [self.hyperfine, "-N", "--style", "none", "--runs", str(n),
                       "--export-json", j, "--", shlex.join(argv)]
                p = subprocess.run(cmd, capture_output=True, text=True)
                if p.returncode == 0:
                    res.update(times=json.loads(Path(j).read_text())["results"][0]["times"],
                               timer="hyperfine")
                else:
                    log("hyperfine failed, timing with perf_counter:", p.stderr.strip()[-300:])
        if n > 0 and "times" not in res:
            times = []
            for _ in range(n):
                t0 = time.perf_counter()
                try:
                    subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                   timeout=timeout)
                except subprocess.TimeoutExpired:
                    pass
                times.append(time.perf_counter() - t0)
            res.update(times=times, timer="perf_counter")
        res["median_s"] = statistics.median(res["times"])
        return res


def parse_json_lines(text: str) -> dict | None:
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("{"):
            try:
                d = json.loads(line)
            except ValueError:
                continue
            if isinstance(d, dict) and "volume" in d:
                return d
    return None


def tool_volume(out: dict | None):
    if not out:
        return None
    v = out.get("signed_volume", out.get("volume"))
    return float(v) if v is not None else None


class Projector:
    """Skips a run whose projected warm-up (from the tool's last, smaller run) is too long."""

    def __init__(self, cap):
        self.cap = cap
        self.seen: dict[tuple, tuple[int, float]] = {}

    def basis(self, key):
        """The run to project from: same tool and format, else the same tool on any format."""
        if key in self.seen:
            return self.seen[key]
        return self.seen.get(key[:1]) if isinstance(key, tuple) else None

    def check(self, key, tris):
        b = self.basis(key)
        if b is None:
            return None
        proj = b[1] * tris / b[0]
        return proj if proj > self.cap else None

    def record(self, key, tris, seconds):
        for k in ([key, key[:1]] if isinstance(key, tuple) else [key]):
            if k not in self.seen or tris >= self.seen[k][0]:
                self.seen[k] = (tris, seconds)


def run_end_to_end(files, main_name, args, runner, available):
    rows = []
    proj = Projector(args.max_cell_seconds)
    meshvol = shlex.split(args.meshvol)
    helptext = ""
    try:
        helptext = subprocess.run(meshvol + ["volume", "--help"], capture_output=True, text=True,
                                  timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        pass
    variants = []  # meshvol's own options, timed as extra rows where the binary has them
    if "--threads" in helptext:
        variants.append(("meshvol --threads 1", ["--threads", "1"]))
    if "--exact" in helptext:
        variants.append(("meshvol --exact", ["--exact"]))
    # the main file first: every tool runs on it, and it is the basis for skipping others
    order = sorted(files, key=lambda f: (f["name"] != main_name, f["triangles"], f["name"]))
    for f in order:
        path = str(f["path"])
        tools = [("cat", ["cat", path]), ("meshvol", meshvol + ["volume", path, "--json"])]
        for name, extra in variants:
            if name == "meshvol --threads 1":
                tools.append((name, meshvol + extra + ["volume", path, "--json"]))
            else:
                tools.append((name, meshvol + ["volume", path, "--json"] + extra))
        if "trimesh" in available:
            tools.append(("trimesh", [PY, str(TOOLS_DIR / "trimesh_file.py"), path]))
        if "numpy-stl" in available and f["fmt"] in ("stl", "stl-ascii"):
            tools.append(("numpy-stl", [PY, str(TOOLS_DIR / "numpystl_file.py"), path]))
        if f["name"] == main_name:  # how much of a Python tool's time is start-up alone
            for t, mod in (("trimesh", "trimesh"), ("numpy-stl", "stl.mesh")):
                if t in available:
                    tools.append((f"{t} (import only)", [PY, "-c", f"import {mod}"]))
        for tool, argv in tools:
            if args.tools and tool.split()[0] not in args.tools and tool != "cat":
                continue
            row = {"category": "end-to-end", "tool": tool, "file": f["name"], "fmt": f["fmt"],
                   "triangles": f["triangles"], "mb": f["mb"], "main": f["name"] == main_name}
            key = (tool, f["fmt"])
            skip = None if row["main"] or tool.startswith(("cat", "meshvol")) else proj.check(key, f["triangles"])
            if skip:
                row["skipped"] = (f"projected ~{skip:.0f} s per run from its {proj.basis(key)[0]:,}"
                                  f"-triangle run (over --max-cell-seconds {args.max_cell_seconds:.0f})")
                log(f"{f['name']:<22} {tool:<24} skipped: {row['skipped']}")
                rows.append(row)
                continue
            timeout = args.timeout * (3 if row["main"] else 1)
            budget = args.main_cell_seconds if row["main"] else args.cell_seconds
            res = runner.measure(argv, timeout, keep_stdout=tool != "cat", budget=budget)
            row.update({k: v for k, v in res.items() if k != "stdout"})
            if "error" not in res:
                proj.record(key, f["triangles"], res["warmup_s"])
                if tool != "cat" and not tool.endswith("(import only)"):
                    out = parse_json_lines(res["stdout"])
                    row["output"] = out
                    vol = tool_volume(out)
                    if vol is None:
                        row["error"] = "no JSON object with a volume in its output"
                    else:
                        row["volume"] = vol
                        row["rel_err"] = meshgen.rel_error(vol, f["ref"])
                        row["correctly_rounded"] = vol == float(f["ref"])
                        bound = out.get("volume_error_bound")
                        if isinstance(bound, (int, float)) and \
                                abs(Fraction(vol) - f["ref"]) > Fraction(bound):
                            row["note"] = f"error exceeds its own volume_error_bound {bound:.3g}"
                        if out.get("triangles") not in (None, f["triangles"]):
                            row["note"] = (row.get("note", "") + f"; reports {out.get('triangles')} "
                                           "triangles").lstrip("; ")
            else:
                # a tool that failed or timed out on a file is not tried on bigger ones
                proj.record(key, f["triangles"], max(res["warmup_s"], args.max_cell_seconds + 1))
            msg = row.get("error") or f"{row['median_s']:.3f} s (n={len(row['times'])})"
            log(f"{f['name']:<22} {tool:<24} {msg}")
            rows.append(row)
    return rows


def run_in_process(sizes, args, refs, available):
    rows = []
    proj = Projector(args.max_cell_seconds)
    for tool in ("trimesh", "manifold3d", "numpy-stl"):
        if tool not in available or (args.tools and tool not in args.tools):
            continue
        for n in sizes:
            row = {"category": "in-process", "tool": tool, "file": f"sphere {size_label(n)} (arrays)",
                   "kind": "sphere", "target": n}
            skip = proj.check(tool, n)
            if skip:
                row["skipped"] = (f"projected ~{skip:.0f} s per run from its {proj.basis(tool)[0]:,}"
                                  f"-triangle run (over --max-cell-seconds {args.max_cell_seconds:.0f})")
                log(f"in-process {tool:<10} {size_label(n):<5} skipped: {row['skipped']}")
                rows.append(row)
                continue
            ref, ntri, _ = refs.get("sphere", n)
            row["triangles"] = ntri
            argv = [PY, str(TOOLS_DIR / "inprocess.py"), tool, "sphere", str(n),
                    str(args.runs), str(args.cell_seconds)]
            try:
                p = subprocess.run(argv, capture_output=True, text=True, timeout=args.timeout * 3)
            except subprocess.TimeoutExpired:
                row["error"] = f"timed out after {args.timeout * 3:.0f} s"
                rows.append(row)
                proj.record(tool, n, args.max_cell_seconds + 1)
                continue
            out = parse_json_lines(p.stdout) if p.returncode == 0 else None
            if out is None:
                row["error"] = f"exit {p.returncode}: " + (p.stderr.strip().splitlines() or ["?"])[-1][:200]
                proj.record(tool, n, args.max_cell_seconds + 1)
            else:
                row.update(times=out["times"], median_s=statistics.median(out["times"]),
                           peak_mb=out["peak_rss_mb"], setup_mb=out["rss_before_timing_mb"],
                           volume=out["volume"], rel_err=meshgen.rel_error(out["volume"], ref),
                           correctly_rounded=out["volume"] == float(ref),
                           warmup_is_sample=out["warmup_is_sample"], method=out["note"])
                proj.record(tool, n, out["warmup_s"])
            msg = row.get("error") or f"{row['median_s']:.3f} s (n={len(row['times'])})"
            log(f"in-process {tool:<10} {size_label(n):<5} {msg}")
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


def versions(args, available) -> dict:
    v = {}
    mv = shlex.split(args.meshvol)
    ver = sh(mv + ["--version"])
    rev = sh(["git", "rev-parse", "--short", "HEAD"])
    dirty = sh(["git", "status", "--porcelain", "--untracked-files=no"])
    v["meshvol"] = (ver or "(no --version)") + (f", git {rev}" if rev else "") + \
        (" + uncommitted changes" if dirty else "") + f"; command: `{args.meshvol}`"
    for tool in ("trimesh", "numpy-stl", "manifold3d"):
        dist = PY_TOOLS[tool][1]
        v[tool] = importlib.metadata.version(dist) if tool in available else "not installed (skipped)"
    for dist in ("numpy", "scipy", "matplotlib"):
        try:
            v[dist] = importlib.metadata.version(dist)
        except importlib.metadata.PackageNotFoundError:
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


def fmt_s(s):
    if s is None:
        return ""
    return f"{s:.4f}" if s < 0.1 else f"{s:.3f}" if s < 10 else f"{s:.1f}"


def fmt_ratio(x):
    return f"{x:.2f}" if 0.1 <= x < 100 else f"{x:.2g}" if x < 0.1 else f"{x:.0f}"


def fmt_err(e):
    if e is None:
        return ""
    if isinstance(e, float) and math.isnan(e):
        return "n/a"
    return "0 (exact)" if e == 0 else f"{e:.1e}"


def fmt_mb(m):
    return "" if m is None else f"{m:.0f}"


def write_report(path: Path, rows, files, info, vers, args, started, main_name, chart_ok,
                 available, duration):
    e2e = [r for r in rows if r["category"] == "end-to-end"]
    inp = [r for r in rows if r["category"] == "in-process"]
    L = []
    L.append("# meshvol compared with its peers\n")
    L.append(f"Generated by `bench/compare/run{' --quick' if args.quick else ''}"
             f"{' --sizes ' + args.sizes if args.sizes else ''}` on "
             f"{started:%Y-%m-%d %H:%M} UTC in {duration / 60:.1f} min. "
             "Not part of CI; see [bench/compare/README.md](compare/README.md) for the method.\n")
    if args.quick:
        L.append("**Quick run: 100k-triangle meshes only. Not the numbers to quote.**\n")
    if args.meshvol != default_meshvol():
        L.append(f"**meshvol was run as `{args.meshvol}`, not the release build "
                 "`target/release/meshvol`: its times are not meshvol's.**\n")
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
        "- **End-to-end**: each tool is a fresh process per run, reading the file and printing "
        "volume, centroid and inertia: `meshvol volume FILE --json`; a Python script doing "
        "`trimesh.load(FILE)` + `mesh.mass_properties`; a Python script doing numpy-stl "
        "`Mesh.from_file(FILE)` + `get_mass_properties()` (STL only). `cat FILE` (to /dev/null) "
        "is the I/O floor. Python start-up and imports are part of the Python tools' time, as a "
        "user of them pays it.")
    L.append(
        f"- Timing: one warm-up run (page cache warm, output kept, peak memory measured with "
        f"`/usr/bin/time -v` or, without it, tools/rss_launch.py), then up to {args.runs} timed runs "
        f"(hyperfine `-N` where installed); the table gives the median. A tool whose run takes "
        f"long gets fewer runs (at most {args.cell_seconds:.0f} s of timed runs per cell, "
        f"{args.main_cell_seconds:.0f} s on the main file); "
        "`1*` means the warm-up itself is the only sample. On the main file, `(import only)` rows "
        "time `python -c 'import MODULE'`: the start-up part of that tool's time. `meshvol --threads 1` and "
        "`meshvol --exact` rows are the same binary with those options. A run projected, from the same tool on "
        f"a smaller file, to take over {args.max_cell_seconds:.0f} s is skipped, except on the "
        f"main file `{main_name}`, which every tool runs.")
    L.append(
        "- **Ratio** = tool time / meshvol time on the same file: above 1 means slower than "
        "meshvol, below 1 faster. The fastest tool of each file (ignoring `cat`) is in bold.")
    L.append(
        "- **Relative volume error** = |tool volume - exact| / |exact|, where exact is the exact "
        "rational volume of the numbers in the file (all formats of a mesh hold the same numbers; "
        "see the README for how it is computed). ✓ marks a result equal to the exact volume "
        "correctly rounded to float64, the best a float64 answer can be. A meshvol result "
        "farther from the exact volume than its own `volume_error_bound` is flagged.")
    L.append(
        "- Meshes: UV spheres (radius 100) and tori (100, 40) with coordinates on a 2^-10 grid; "
        "`sphere_far` is a sphere of radius 100 centred at (1e6, 1e6, 1e6), where float32 "
        "spacing is 1/16; `cubes` is a grid of disjoint boxes of random sizes. Binary STL is "
        "float32; ASCII STL and OBJ print the same values exactly.")
    L.append("")
    L.append("## End-to-end, by file\n")
    L.append("| tool | file | size MB | median s | runs | ratio to meshvol | peak MB | relative volume error |")
    L.append("|---|---|--:|--:|--:|--:|--:|--:|")
    not_fastest = []
    by_file: dict[str, list[dict]] = {}
    for r in e2e:
        by_file.setdefault(r["file"], []).append(r)
    kinds = ["sphere", "torus", "sphere_far", "cubes"]
    file_order = sorted(by_file, key=lambda n: (
        n != main_name, ["stl", "stl-ascii", "obj"].index(by_file[n][0]["fmt"]),
        kinds.index(n.rsplit("_", 1)[0]) if n.rsplit("_", 1)[0] in kinds else 9,
        by_file[n][0]["triangles"], n))
    for name in file_order:
        group = by_file[name]
        mv = next((r for r in group if r["tool"] == "meshvol" and "median_s" in r), None)
        timed = [r for r in group if "median_s" in r
                 and r["tool"] != "cat" and not r["tool"].endswith("(import only)")]
        fastest = min(timed, key=lambda r: r["median_s"]) if timed else None
        peers = [r for r in timed if not r["tool"].startswith("meshvol")]
        fastest_peer = min(peers, key=lambda r: r["median_s"]) if peers else None
        if mv and fastest_peer and fastest_peer["median_s"] <= mv["median_s"]:
            fastest = fastest_peer  # for the sentence below
            not_fastest.append(f"`{name}` ({fastest['tool']}: {fmt_s(fastest['median_s'])} s vs "
                               f"meshvol {fmt_s(mv['median_s'])} s)")
        if not mv:
            not_fastest.append(f"`{name}` (meshvol has no time: "
                               f"{next((r.get('error') for r in group if r['tool'] == 'meshvol'), 'not run')})")
        for r in group:
            tool = r["tool"] + (" (I/O floor)" if r["tool"] == "cat" else "")
            label = f"{r['file']} ({FORMAT_LABEL[r['fmt']]}, {r['triangles']:,} tri)"
            if "skipped" in r:
                L.append(f"| {tool} | {label} | {r['mb']:.1f} | skipped | | | | {r['skipped']} |")
                continue
            if "error" in r and "median_s" not in r:
                L.append(f"| {tool} | {label} | {r['mb']:.1f} | failed | | | {fmt_mb(r.get('peak_mb'))} | {r['error']} |")
                continue
            t = fmt_s(r["median_s"])
            if timed and r is min(timed, key=lambda x: x["median_s"]):
                t = f"**{t}**"
            runs = "1*" if r.get("warmup_is_sample") else str(len(r["times"]))
            ratio = fmt_ratio(r["median_s"] / mv["median_s"]) if mv else "n/a"
            err = fmt_err(r.get("rel_err")) if "rel_err" in r else ""
            if r.get("correctly_rounded"):
                err += " ✓"
            if r.get("error"):
                err = r["error"]
            if r.get("note"):
                err += f" ({r['note']})"
            L.append(f"| {tool} | {label} | {r['mb']:.1f} | {t} | {runs} | {ratio} | "
                     f"{fmt_mb(r.get('peak_mb'))} | {err} |")
    L.append("")
    if not_fastest:
        L.append("meshvol is **not** the fastest tool on: " + "; ".join(not_fastest) + ".\n")
    elif e2e:
        L.append("meshvol is the fastest tool on every file (`cat` aside).\n")
    if inp:
        L.append("## In-process, on arrays already in memory\n")
        L.append("Each run builds the tool's mesh object from (vertices, faces) outside the timer, "
                 "so no cached result carries over; the timer covers the mass-property call only "
                 "(for manifold3d, which has no other way in, the `Manifold` build plus `volume()` "
                 "and `surface_area()`; it gives no centroid or inertia). Peak MB is the whole "
                 "Python process. " + CRITERION_NOTE + "\n")
        crit = criterion_estimates()
        crit_mv = {}  # triangle count -> (name, seconds) for criterion's default meshvol kernel
        for name, secs, _ in crit:
            m = re.fullmatch(r"mass_properties/meshvol/(\d+)", name)
            if m:
                crit_mv[int(m.group(1))] = (name, secs)
        used_crit = False
        L.append("| tool | mesh | triangles | median s | runs | ratio to meshvol | peak MB | relative volume error |")
        L.append("|---|---|--:|--:|--:|--:|--:|--:|")
        for r in inp:
            tri = f"{r['triangles']:,}" if "triangles" in r else f"~{size_label(r['target'])}"
            if "skipped" in r:
                L.append(f"| {r['tool']} | {r['file']} | {tri} | skipped | | | | {r['skipped']} |")
                continue
            if "median_s" not in r:
                L.append(f"| {r['tool']} | {r['file']} | {tri} | failed | | | | {r.get('error')} |")
                continue
            runs = "1*" if r.get("warmup_is_sample") else str(len(r["times"]))
            near = [(n, v) for n, v in crit_mv.items() if abs(n - r["triangles"]) <= 0.1 * n]
            ratio = "see criterion"
            if near:
                ratio = f"{fmt_ratio(r['median_s'] / near[0][1][1])} †"
                used_crit = True
            cr = " ✓" if r.get("correctly_rounded") else ""
            L.append(f"| {r['tool']} | {r['file']} | {tri} | {fmt_s(r['median_s'])} | {runs} | "
                     f"{ratio} | {fmt_mb(r['peak_mb'])} | {fmt_err(r['rel_err'])}{cr} |")
        L.append("")
        if used_crit:
            L.append("† against the criterion estimate `mass_properties/meshvol/N` below with N "
                     "within 10% of the row's triangle count: a different mesh of about the same "
                     "size, measured by `cargo bench`, not by this run; indicative only.\n")
        if crit:
            L.append("meshvol criterion estimates found in `target/criterion/` (mean per iteration; "
                     "from the last `cargo bench -p meshvol-bench`, not from this run):\n")
            L.append("| benchmark | mean s | measured (UTC) |")
            L.append("|---|--:|---|")
            for name, secs, when in crit:
                L.append(f"| {name} | {secs:.6f} | {when} |")
            L.append("")
    missing = [t for t in PY_TOOLS if t not in available]
    if missing:
        L.append("Skipped tools (not installed in the venv): " + ", ".join(missing) + ".\n")
    L.append("## Reference volumes\n")
    L.append("| mesh | triangles | exact volume (rounded) |")
    L.append("|---|--:|--:|")
    seen = set()
    for f in files:
        k = (f["kind"], f["target"])
        if k not in seen:
            seen.add(k)
            L.append(f"| {f['kind']} {size_label(f['target'])} | {f['triangles']:,} | {float(f['ref']):.17g} |")
    L.append("")
    if chart_ok:
        L.append(f"## Chart\n\n![End-to-end seconds on {main_name}](RESULTS.png)\n")
    path.write_text("\n".join(L))


def write_chart(path: Path, rows, main_name) -> bool:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log("matplotlib missing: no chart")
        return False
    pts = [(r["tool"], r["median_s"]) for r in rows
           if r["category"] == "end-to-end" and r["file"] == main_name and "median_s" in r
           and not r["tool"].endswith("(import only)")]
    if not pts:
        return False
    fig, ax = plt.subplots(figsize=(7, 0.6 * len(pts) + 1.4))
    names = [("cat (I/O floor)" if t == "cat" else t) for t, _ in pts]
    vals = [s for _, s in pts]
    colors = ["#999999" if t == "cat" else "#d62728" if t.startswith("meshvol") else "#1f77b4"
              for t, _ in pts]
    bars = ax.barh(names, vals, color=colors)
    ax.set_xscale("log")
    ax.invert_yaxis()
    for b, s in zip(bars, vals):
        ax.text(b.get_width() * 1.05, b.get_y() + b.get_height() / 2, f"{s:.3g} s", va="center")
    ax.set_xlim(min(vals) / 2, max(vals) * 6)
    r0 = next(r for r in rows if r.get("file") == main_name)
    ax.set_xlabel("seconds, whole process, median (log scale; lower is better)")
    ax.set_title(f"Volume + centroid + inertia of {main_name}\n"
                 f"(binary STL, {r0['triangles']:,} triangles, {r0['mb']:.0f} MB)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


# --------------------------------------------------------------------------- main


def default_meshvol() -> str:
    return str(ROOT / "target" / "release" / "meshvol")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="100k-triangle meshes only (< 3 min)")
    ap.add_argument("--sizes", help="comma-separated triangle counts, e.g. 100k,1m,5m (default)")
    ap.add_argument("--inprocess-sizes", help="in-process sphere sizes (default 100k,1m,5m,10m; with --sizes or --quick: those sizes)")
    ap.add_argument("--meshvol", default=default_meshvol(),
                    help="meshvol command (default: target/release/meshvol)")
    ap.add_argument("--tools", help="comma-separated subset of meshvol,trimesh,numpy-stl,manifold3d")
    ap.add_argument("--runs", type=int, default=5, help="timed runs after the warm-up (default 5)")
    ap.add_argument("--cell-seconds", type=float, help="timed-run budget per cell (20; quick 8; main file at least 60)")
    ap.add_argument("--max-cell-seconds", type=float,
                    help="skip runs projected to take longer (60; quick 5)")
    ap.add_argument("--timeout", type=float, default=200, help="hard limit for one run, s")
    ap.add_argument("--no-inprocess", action="store_true")
    ap.add_argument("--no-end-to-end", action="store_true")
    ap.add_argument("--no-hyperfine", action="store_true", help="time with perf_counter")
    ap.add_argument("--no-gnu-time", action="store_true",
                    help="peak memory from tools/rss_launch.py instead of /usr/bin/time -v")
    ap.add_argument("--results", type=Path, default=ROOT / "bench" / "RESULTS.md")
    ap.add_argument("--chart", type=Path, default=ROOT / "bench" / "RESULTS.png")
    args = ap.parse_args(argv)

    started = _dt.datetime.now(_dt.timezone.utc)
    info = machine_info()
    t_start = time.perf_counter()
    if args.sizes:
        sizes = sorted({parse_size(s) for s in args.sizes.split(",") if s.strip()})
    else:
        sizes = [100_000] if args.quick else [100_000, 1_000_000, 5_000_000]
    if args.inprocess_sizes:
        inproc = sorted({parse_size(s) for s in args.inprocess_sizes.split(",") if s.strip()})
    else:
        inproc = sorted(set(sizes) | ({10_000_000} if not args.quick and not args.sizes else set()))
    if args.cell_seconds is None:
        args.cell_seconds = 8.0 if args.quick else 20.0
    args.main_cell_seconds = max(args.cell_seconds, 8.0 if args.quick else 60.0)
    if args.max_cell_seconds is None:
        args.max_cell_seconds = 5.0 if args.quick else 60.0
    args.tools = set(args.tools.split(",")) if args.tools else None

    available = []
    for tool, (mod, _) in PY_TOOLS.items():
        if importlib.util.find_spec(mod) is not None:
            available.append(tool)
        else:
            log(f"{tool} is not installed: skipped")

    meshgen.selftest(verbose=False)
    mv = shlex.split(args.meshvol)
    if not shutil.which(mv[0]) and not Path(mv[0]).exists():
        sys.exit(f"meshvol not found at {mv[0]}: build it (cargo build --release -p meshvol-cli) "
                 "or pass --meshvol")

    files, main_name = plan_files(sizes)
    refs = Refs()
    t0 = time.perf_counter()
    generate(files, refs)
    log(f"data ready in {time.perf_counter() - t0:.1f} s: {len(files)} files in {DATA}")

    runner = Runner(args)
    log("timing with", "hyperfine" if runner.hyperfine else "perf_counter",
        "; peak memory from", "/usr/bin/time -v" if runner.gnu_time else "tools/rss_launch.py")
    rows = []
    if not args.no_end_to_end:
        rows += run_end_to_end(files, main_name, args, runner, available)
    if not args.no_inprocess:
        rows += run_in_process(inproc, args, refs, available)

    info["load_end"] = machine_info()["load"]
    vers = versions(args, available)
    OUT.mkdir(parents=True, exist_ok=True)
    raw = {"started": started.isoformat(), "machine": info, "versions": vers,
           "args": {k: (sorted(v) if isinstance(v, set) else str(v) if isinstance(v, Path) else v)
                    for k, v in vars(args).items()},
           "rows": [{k: (str(v) if isinstance(v, (Path, Fraction)) else v) for k, v in r.items()}
                    for r in rows]}
    (OUT / "results.json").write_text(json.dumps(raw, indent=1, default=str))
    chart_ok = write_chart(args.chart, rows, main_name)
    duration = time.perf_counter() - t_start
    write_report(args.results, rows, files, info, vers, args, started, main_name, chart_ok,
                 available, duration)
    log(f"wrote {args.results}" + (f" and {args.chart}" if chart_ok else "") +
        f" in {duration / 60:.1f} min; raw numbers in {OUT / 'results.json'}")


if __name__ == "__main__":
    main()
