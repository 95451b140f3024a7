"""Shared pieces of bench/compare: paths, the process runner, time budgets, formatting.

Used by compare.py (planning, volume sections, report) and sections.py (check, grid,
union, hull, area).
"""

from __future__ import annotations

import json
import math
import os
import re
import shlex
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
PY = sys.executable
OUT = ROOT / "bench" / "out"
DATA = OUT / "data"
TOOLS_DIR = HERE / "tools"


def log(*a):
    print("[compare]", *a, flush=True)


def load_json(path: Path, default):
    try:
        return json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return default


def last_line(text: str, limit=200) -> str:
    lines = [ln for ln in (text or "").strip().splitlines() if ln.strip()]
    return re.sub(r"\x1b\[[0-9;]*m", "", lines[-1] if lines else "?")[:limit]


def parse_json_lines(text: str, keys=("volume", "refused")) -> dict | None:
    """The first JSON object on a line of `text` that has one of `keys` (None: any object)."""
    for line in (text or "").splitlines():
        line = line.strip()
        if line.startswith("{"):
            try:
                d = json.loads(line)
            except ValueError:
                continue
            if isinstance(d, dict) and (keys is None or any(k in d for k in keys)):
                return d
    return None


# --------------------------------------------------------------------------- time budget


class Clock:
    """The whole run's time budget, shared out among the sections as they start.

    A section that starts gets (time left) * its weight / (weights of the sections not yet
    started), so time a section does not use passes to the later ones.
    """

    def __init__(self, total_s: float, weights: dict[str, float]):
        self.t0 = time.perf_counter()
        self.total = total_s
        self.weights = dict(weights)
        self.started: list[str] = []
        self.deadline = self.t0 + total_s
        self.allowance: dict[str, float] = {}
        self.used: dict[str, float] = {}
        self._cur = None
        self._cur_t0 = None

    def elapsed(self) -> float:
        return time.perf_counter() - self.t0

    def start(self, name: str):
        self.finish()
        pending = [s for s in self.weights if s not in self.started]
        share = self.weights.get(name, 1.0) / max(1e-9, sum(self.weights[s] for s in pending))
        left = max(0.0, self.total - self.elapsed())
        self.started.append(name)
        self.allowance[name] = left * share
        self.deadline = time.perf_counter() + left * share
        self._cur, self._cur_t0 = name, time.perf_counter()
        log(f"--- {name}: {left * share:.0f} s of the run's time budget ({left:.0f} s left)")

    def finish(self):
        if self._cur is not None:
            self.used[self._cur] = time.perf_counter() - self._cur_t0
            self._cur = None

    def left(self) -> float:
        return self.deadline - time.perf_counter()


class Projector:
    """Skips a run whose time, projected linearly from the same tool's last run, is over cap.

    Keys are tuples (section, tool, format...); a key's basis is itself, else its first two
    parts (the same tool in the same section, any file). A run that was cut off is recorded
    at the cut-off time, a lower bound, and flagged as such.
    """

    def __init__(self):
        self.seen: dict[tuple, tuple[float, float, bool]] = {}

    def basis(self, key):
        if key in self.seen:
            return self.seen[key]
        return self.seen.get(key[:2])

    def project(self, key, size):
        b = self.basis(key)
        if b is None:
            return None
        size0, secs, over = b
        return secs * size / size0, over, size0

    def record(self, key, size, seconds, over=False):
        for k in {key, key[:2]}:
            if k not in self.seen or size >= self.seen[k][0]:
                self.seen[k] = (size, seconds, over)


def plan_cell(clock: Clock, proj: Projector, key, size, cap: float, min_left=1.0):
    """(cap to use, reason to skip or None) for one peer cell."""
    p = proj.project(key, size)
    if p is not None:
        secs, over, size0 = p
        # a cut-off run is a lower bound: also skip inputs of about its size (>= 80%)
        if secs > cap or (over and size >= 0.8 * size0):
            how = "cut off at" if over else "took"
            return cap, (f"> {cap:.0f} s (projected ~{secs:.0f} s: it {how} "
                         f"{proj.basis(key)[1]:.0f} s on {size0:,.0f})")
    left = clock.left()
    if left < min_left:
        return cap, "not run: the section's time budget was spent"
    return min(cap, max(left, min_left)), None


# --------------------------------------------------------------------------- running


def run_group(argv, timeout, keep_stdout=True):
    """Run argv in its own process group; on timeout kill the whole group (the tool under
    /usr/bin/time or a launcher is a grandchild, which killing the child alone would orphan).
    Returns (returncode or "timeout", stdout text, stderr text)."""
    p = subprocess.Popen(argv, stdout=subprocess.PIPE if keep_stdout else subprocess.DEVNULL,
                         stderr=subprocess.PIPE, start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        kill_group(p)
        return "timeout", "", ""
    except BaseException:
        kill_group(p)
        raise
    return (p.returncode, (out or b"").decode("utf-8", "replace"),
            (err or b"").decode("utf-8", "replace"))


def kill_group(p):
    try:
        os.killpg(p.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    try:
        p.communicate(timeout=10)
    except Exception:
        pass


class Runner:
    """Times a command: a warm-up run (output kept, peak memory) then timed runs."""

    def __init__(self, args):
        self.hyperfine = shutil.which("hyperfine") if not args.no_hyperfine else None
        gnu_time = Path("/usr/bin/time")
        self.gnu_time = None
        if gnu_time.exists() and not args.no_gnu_time:
            probe = subprocess.run([str(gnu_time), "-v", "true"], capture_output=True, text=True)
            if "Maximum resident set size" in probe.stderr:
                self.gnu_time = str(gnu_time)
        self.runs = args.runs

    def once(self, argv, timeout, keep_stdout=True):
        """One run with peak RSS: (seconds, returncode or 'timeout', stdout, stderr, peak MB)."""
        with tempfile.TemporaryDirectory() as td:
            if self.gnu_time:
                mfile = os.path.join(td, "time.txt")
                full = [self.gnu_time, "-v", "-o", mfile] + argv
            else:  # tools/rss_launch.py reports the child's own rusage
                mfile = os.path.join(td, "rss.txt")
                full = [PY, str(TOOLS_DIR / "rss_launch.py"), mfile] + argv
            t0 = time.perf_counter()
            rc, out, err = run_group(full, timeout, keep_stdout)
            dt = time.perf_counter() - t0
            if rc == "timeout":
                return dt, "timeout", "", "", None
            peak = None
            try:
                text = Path(mfile).read_text()
                if self.gnu_time:
                    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", text)
                    peak = int(m.group(1)) / 1024.0 if m else None
                else:
                    peak = int(text) / 1024.0
            except (OSError, ValueError):
                pass
            return dt, rc, out, err, peak

    def measure(self, argv, cap, budget, keep_stdout=True, runs=None, ok_codes=(0,)):
        """Warm-up (output, peak memory), then min(runs, budget // warm-up) timed runs.

        A warm-up longer than `cap` is cut off: the result has "over": cap and no times.
        When not even one timed run fits the budget, the warm-up is the one sample.
        """
        runs = self.runs if runs is None else runs
        warm, rc, out, err, peak = self.once(argv, cap, keep_stdout)
        res = {"warmup_s": warm, "peak_mb": peak, "stdout": out, "stderr": err[-2000:],
               "cmd": shlex.join(argv)}
        if rc == "timeout":
            res["over"] = cap
            res["error"] = f"> {cap:.0f} s (cut off)"
            return res
        if rc not in ok_codes:
            res["error"] = f"exit {rc}: " + last_line(err)
            return res
        if rc != 0:
            res["exit_code"] = rc
        n = min(runs, int(max(0.0, budget) // warm)) if warm > 0 else runs
        if n <= 0:
            res.update(times=[warm], warmup_is_sample=True, timer="warm-up run")
        elif self.hyperfine:
            with tempfile.TemporaryDirectory() as td:
                j = os.path.join(td, "h.json")
                cmd = [self.hyperfine, "-N", "--style", "none", "--runs", str(n),
                       "--export-json", j] + (["-i"] if rc != 0 else []) + ["--", shlex.join(argv)]
                hrc, _, herr = run_group(cmd, 2 * budget + cap + 10)
                if hrc == 0:
                    res.update(times=json.loads(Path(j).read_text())["results"][0]["times"],
                               timer="hyperfine")
                elif hrc == "timeout":
                    res.update(times=[warm], warmup_is_sample=True, timer="warm-up run")
                else:
                    log("hyperfine failed, timing with perf_counter:", herr.strip()[-300:])
        if "times" not in res:
            times = []
            for _ in range(n):
                t0 = time.perf_counter()
                run_group(argv, cap, keep_stdout=False)
                times.append(time.perf_counter() - t0)
            res.update(times=times, timer="perf_counter")
        res["median_s"] = statistics.median(res["times"])
        return res


# --------------------------------------------------------------------------- formatting


def fmt_s(s):
    if s is None:
        return ""
    return f"{s:.4f}" if s < 0.1 else f"{s:.3f}" if s < 10 else f"{s:.1f}"


def fmt_ratio(x):
    if x is None:
        return ""
    return f"{x:.2f}" if 0.1 <= x < 100 else f"{x:.2g}" if x < 0.1 else f"{x:.0f}"


def fmt_err(e):
    if e is None:
        return ""
    if isinstance(e, float) and math.isnan(e):
        return "n/a"
    return "0 (exact)" if e == 0 else f"{e:.1e}"


def fmt_mb(m):
    return "" if m is None else f"{m:.0f}"


def runs_cell(r) -> str:
    if "times" not in r:
        return ""
    return "1*" if r.get("warmup_is_sample") else str(len(r["times"]))


def time_cell(r, bold=False) -> str:
    """Median seconds, or '> N s' for a run cut off, or the reason it did not run."""
    if "median_s" in r:
        t = fmt_s(r["median_s"])
        return f"**{t}**" if bold else t
    if r.get("over") is not None:
        return f"> {r['over']:.0f} s"
    if r.get("skipped"):
        return "> " + r["skipped"].split(" ", 2)[1] + " s" if r["skipped"].startswith("> ") else "not run"
    return "failed"


def seconds_of(r):
    """(seconds, is_lower_bound) for comparisons; None when the row has no time."""
    if "median_s" in r:
        return r["median_s"], False
    if r.get("over") is not None:
        return float(r["over"]), True
    s = r.get("skipped") or ""
    m = re.match(r"> (\d+(?:\.\d+)?) s", s)
    if m:
        return float(m.group(1)), True
    return None


def ratio_cell(r, mv_s) -> str:
    s = seconds_of(r)
    if s is None or not mv_s:
        return ""
    return ("> " if s[1] else "") + fmt_ratio(s[0] / mv_s)


def failure_note(r) -> str:
    """Why row `r` has no result (refused, failed, not started), or "" when it has one."""
    if r.get("refused"):
        return f"refused: {r['refused']}"
    if r.get("error") and "median_s" not in r and "over" not in r:
        return r["error"]
    return r.get("skipped") or ""


def ahead_cell(r, mv_s) -> str:
    """'yes' when the peer took longer than meshvol, '**no**' when it did not."""
    if r.get("refused"):
        return "n/a (refused)"
    s = seconds_of(r)
    if s is None or not mv_s:
        return "n/a"
    if s[1]:
        return "yes"
    return "yes" if s[0] > mv_s else "**no**"


def is_behind(r, mv_s) -> bool:
    """meshvol is not ahead of this peer row (the peer was as fast or faster)."""
    s = seconds_of(r)
    return bool(s and mv_s and not s[1] and not r.get("refused") and s[0] <= mv_s)


def md_cell(text) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


# --------------------------------------------------------------------------- one cell


class Ctx:
    """What every section needs: options, the runner, the clock and the installed peers."""

    def __init__(self, args, runner: Runner, clock: Clock, available: set, meshvol: list):
        self.args, self.runner, self.clock = args, runner, clock
        self.available, self.meshvol = available, meshvol
        self.proj = Projector()

    def wants(self, tool: str) -> bool:
        """Is this peer installed and selected (--tools)?"""
        base = tool.split()[0].split("-valid")[0].split("-watertight")[0]
        if base == "meshvol" or base == "cat":
            return True
        if base in ("meshvol-py", "meshvol-py-mp"):  # meshvol's own Python binding, when installed
            return "meshvol-py" in self.available
        if base not in self.available:
            return False
        return not self.args.tools or base in self.args.tools

    def run(self, row: dict, argv, key=None, size=1.0, meshvol=False, main=False,
            keep_stdout=True, parse_keys=None, budget=None, ok_codes=(0,)) -> dict:
        """Measure one cell into `row`: meshvol always runs (bounded by --timeout); a peer is
        cut off at --peer-timeout (or what is left of the section's budget), and not started
        when its projected time is over that or the section's budget is spent. `main` gives
        the cell --main-cell-seconds of timed runs instead of --cell-seconds."""
        a = self.args
        if budget is None:
            budget = a.main_cell_seconds if main else a.cell_seconds
        if meshvol:
            cap = a.timeout
            budget = min(budget, max(0.0, self.clock.left()))
        else:
            cap, skip = plan_cell(self.clock, self.proj, key, size, a.peer_timeout)
            if skip:
                row["skipped"] = skip
                log(f"{row.get('section', '')}: {row.get('item', '')} {row.get('tool', '')}: {skip}")
                return row
            budget = min(budget, max(0.0, self.clock.left() - cap))
        res = self.runner.measure(argv, cap, budget, keep_stdout=keep_stdout, ok_codes=ok_codes)
        out = parse_json_lines(res.pop("stdout", ""), keys=parse_keys) if keep_stdout else None
        res.pop("stderr", None) if "error" not in res else None
        row.update(res)
        if out is not None:
            row["output"] = out
            if "refused" in out:
                row["refused"] = out["refused"]
        if "over" in row and cap < a.peer_timeout and not meshvol:
            row["error"] += " (what was left of the section's time budget)"
        if key is not None:
            if "over" in row:
                self.proj.record(key, size, cap, over=True)
            elif "error" in row:  # a crash: not tried on bigger files
                self.proj.record(key, size, a.peer_timeout + 1, over=True)
            else:
                self.proj.record(key, size, row["warmup_s"])
        msg = row.get("error") or (f"refused: {row['refused']}" if "refused" in row else
                                   f"{row['median_s']:.3f} s (n={len(row['times'])})")
        log(f"{row.get('section', '')}: {row.get('item', '')} {row.get('tool', '')}: {msg}")
        return row
