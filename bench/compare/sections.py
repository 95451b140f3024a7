"""The sections of bench/compare beyond mesh volume: topology check, grid, union, convex hull
and 2D area. Each has run_X(ctx, ...) -> list of rows and report_X(rows, ...) -> Markdown.

Every timed command is a fresh process (meshvol, or a worker script in tools/), measured by
harness.Runner: a warm-up with peak memory, then timed runs; a peer is cut off at
--peer-timeout and reported as "> N s". See README.md for what each section compares.
"""

from __future__ import annotations

import hashlib
import json
import math
import subprocess
import time
from fractions import Fraction
from pathlib import Path

import numpy as np

import meshgen
import pointgen
from harness import (DATA, HERE, PY, TOOLS_DIR, ahead_cell, failure_note, fmt_err, fmt_mb, fmt_ratio, fmt_s,
                     is_behind, load_json, md_cell, ratio_cell, runs_cell, seconds_of,
                     time_cell)


def size_label(n: int) -> str:
    if n >= 1_000_000 and n % 1_000_000 == 0:
        return f"{n // 1_000_000}m"
    if n >= 1_000 and n % 1_000 == 0:
        return f"{n // 1_000}k"
    return str(n)


def params(args) -> dict:
    """Section sizes: --quick's small ones, the defaults, or the options given."""
    q = args.quick
    p = {
        "check_size": 100_000 if q else 1_000_000,
        "grid_cells": [64, 128] if q else [256, 512],
        "grid_sample": 10 if q else 30,
        "union": (6, 5_000) if q else (20, 20_000),
        "intersect": 100_000 if q else 1_000_000,
        "hull_points": 10_000 if q else 1_000_000,
        "area_vertices": 100_000 if q else 1_000_000,
        "area_polygons": 10_000 if q else 100_000,
        "profile_levels": 20 if q else 100,
        "scaling_sizes": [100_000, 1_000_000] if q else
                         [100_000, 1_000_000, 5_000_000, 10_000_000, 20_000_000],
        "scaling_cells": 128,
    }
    if args.profile_levels:
        p["profile_levels"] = args.profile_levels
    if args.scaling_sizes:
        p["scaling_sizes"] = sorted({_parse_size(x) for x in args.scaling_sizes.split(",") if x.strip()})
    if args.scaling_cells:
        p["scaling_cells"] = args.scaling_cells
    if args.check_size:
        p["check_size"] = args.check_size
    if args.grid_cells:
        p["grid_cells"] = [int(x) for x in args.grid_cells.split(",")]
    if args.grid_sample is not None:
        p["grid_sample"] = args.grid_sample
    if args.union_bodies:
        n, t = args.union_bodies.split(",")
        p["union"] = (int(n), int(float(t)))
    if args.hull_points:
        p["hull_points"] = args.hull_points
    if args.area_vertices:
        p["area_vertices"] = args.area_vertices
    if args.area_polygons:
        p["area_polygons"] = args.area_polygons
    return p


def _parse_size(s: str) -> int:
    s = s.strip().lower().replace("_", "")
    mult = {"k": 1_000, "m": 1_000_000}.get(s[-1:], 1)
    return int(float(s[:-1] if mult > 1 else s) * mult)


def gen_stamp() -> str:
    h = hashlib.sha256()
    for f in ("meshgen.py", "pointgen.py"):
        h.update((HERE / f).read_bytes())
    return h.hexdigest()[:16]


class Cache:
    """Files made once per generator version, recorded in DATA/<sub>/stamp.json."""

    def __init__(self, sub: str):
        self.dir = DATA / sub
        self.dir.mkdir(parents=True, exist_ok=True)
        self.stamp_path = self.dir / "stamp.json"
        d = load_json(self.stamp_path, {})
        self.stamp = gen_stamp()
        self.d = d.get("files", {}) if d.get("gen") == self.stamp else {}

    def fresh(self, name: str) -> bool:
        p = self.dir / name
        return p.exists() and name in self.d and self.d[name].get("bytes") == p.stat().st_size

    def done(self, name: str, **meta):
        self.d[name] = {"bytes": (self.dir / name).stat().st_size, **meta}
        self.stamp_path.write_text(json.dumps({"gen": self.stamp, "files": self.d}, indent=1))

    def meta(self, name: str) -> dict:
        return self.d.get(name, {})


def mv_row(rows, item, tool="meshvol"):
    return next((r for r in rows if r["item"] == item and r["tool"] == tool and "median_s" in r), None)


def kernel_of(r):
    out = r.get("output") or {}
    if r["tool"].startswith("meshvol"):
        return out.get("seconds")
    return out.get("kernel_s")


def base_row(section, item, tool, **kw):
    return {"category": section, "section": section, "item": item, "tool": tool, **kw}


def kernel_check(r, mv) -> str | None:
    """When meshvol reports no kernel time but the peer does: the peer's kernel alone (after
    reading) took no longer than meshvol's whole process. Returns a description or None."""
    if mv is None or kernel_of(mv) is not None or r.get("refused") or "output" not in r:
        return None
    k = kernel_of(r)
    if k is None or k > mv["median_s"]:
        return None
    return (f"{r['tool']} on {r['item']}: its kernel {fmt_s(k)} s vs meshvol's whole process "
            f"{fmt_s(mv['median_s'])} s")


def kernel_sentence(notes: list[str]) -> list[str]:
    if not notes:
        return []
    return ["**Kernel alone, meshvol not shown ahead:** the peer's call after reading and parsing "
            "took no longer than meshvol's whole process (start, read, compute, print) on: "
            + "; ".join(notes) + ". meshvol reports no kernel time for this command, so which "
            "kernel is faster is not measured here; for data already in memory in Python, the "
            "peer may well be the faster choice.\n"]


def ahead_sentence(section_title, behind: list[str], compared: int) -> str:
    if behind:
        return (f"**Where meshvol is not ahead ({section_title}):** " + "; ".join(behind) + ".\n")
    if compared:
        return f"meshvol is ahead of every peer that gave a result in this section ({compared} comparisons).\n"
    return "No peer gave a timed result in this section, so there is nothing to compare.\n"


class Verdicts:
    """One section's tally of peer rows against meshvol's: the "meshvol ahead?" cells, the
    peers ahead of meshvol, and the peers whose kernel alone beat meshvol's whole process."""

    def __init__(self, title: str):
        self.title, self.compared, self.behind, self.kernel_notes = title, 0, [], []

    def cell(self, r, mv, label: str, mv_label: str = "", kernel_mv=None, kernel_suffix="") -> str:
        """The "meshvol ahead?" cell of peer row `r` against meshvol's row `mv` (or None);
        `label` names the peer row and `mv_label` meshvol's in the not-ahead list. The kernel
        comparison uses `kernel_mv` when given (a different meshvol row), else `mv`."""
        mv_s = mv["median_s"] if mv else None
        if seconds_of(r) and mv_s:
            self.compared += 1
            if is_behind(r, mv_s):
                self.behind.append(f"{label} ({fmt_s(r['median_s'])} s vs {mv_label}{fmt_s(mv_s)} s)")
        ahead = ahead_cell(r, mv_s)
        kn = kernel_check(r, mv if kernel_mv is None else kernel_mv)
        if kn:
            self.kernel_notes.append(kn + kernel_suffix)
            ahead += "; kernel: **no**"
        return ahead

    def sentences(self) -> list[str]:
        """The lines closing the section's table."""
        return ["", ahead_sentence(self.title, self.behind, self.compared),
                *kernel_sentence(self.kernel_notes)]

    def not_ahead(self) -> list[str]:
        return self.behind + [f"kernel only: {k}" for k in self.kernel_notes]


# --------------------------------------------------------------------------- check


# Strongest peers first: when the section's time budget runs out, it is the slow ones
# (Open3D, already past the cut-off on the first file) that are left out, not these.
CHECK_PEERS = [  # (tool, mode, meshvol row compared with, what it answers)
    ("trueform", "trueform", "meshvol check",
     "read_stl + Mesh + is_closed + is_manifold + has_self_intersections (exact, stops at the "
     "first contact) + label_connected_components(manifold_edge_link)"),
    ("meshlib", "meshlib", "meshvol check",
     "loadMesh + topology.findNumHoles + findSelfCollidingTriangles (any pair) + "
     "MeshComponents.getNumComponents"),
    ("trimesh", "trimesh", "meshvol check --no-intersections",
     "load (merges vertices) + is_watertight + is_winding_consistent + body_count"),
    ("pymeshlab", "pymeshlab", "meshvol check --no-intersections",
     "load_new_mesh + get_topological_measures (two-manifold, boundary edges, components)"),
    ("open3d", "open3d", "meshvol check --no-intersections",
     "read + remove_duplicated_vertices + is_edge_manifold + is_vertex_manifold + is_orientable "
     "+ cluster_connected_triangles"),
    ("open3d-watertight", "open3d-watertight", "meshvol check",
     "read + remove_duplicated_vertices + is_watertight() (includes an all-pairs self-intersection test)"),
]


def run_check(ctx, files: list[dict]) -> list[dict]:
    rows = []
    for f in files:
        path, item = str(f["path"]), f["name"]
        for tool, extra in (("meshvol check", []), ("meshvol check --no-intersections", ["--no-intersections"])):
            r = base_row("check", item, tool, triangles=f["triangles"])
            # exit 1 is a verdict ("does not bound a volume"), not a failure
            rows.append(ctx.run(r, ctx.meshvol + ["check", path, "--json"] + extra, meshvol=True,
                                parse_keys=("closed",), ok_codes=(0, 1)))
        for tool, mode, cmp, _ in CHECK_PEERS:
            if not ctx.wants(tool):
                continue
            r = base_row("check", item, tool, triangles=f["triangles"], compare_to=cmp)
            rows.append(ctx.run(r, [PY, str(TOOLS_DIR / "check_peer.py"), mode, path],
                                key=("check", tool), size=f["triangles"], parse_keys=("mode",)))
    return rows


def _check_verdict(r):
    out = r.get("output") or {}
    if r["tool"].startswith("meshvol"):
        si = out.get("self_intersections")
        return (out.get("closed"), out.get("consistently_oriented"), out.get("shells"),
                None if si is None else si)
    return (out.get("watertight"), out.get("winding_consistent"), out.get("bodies"),
            out.get("self_intersecting"))


def _yn(x):
    return "" if x is None else ("yes" if x is True else "no" if x is False else str(x))


def report_check(rows, files) -> tuple[list[str], list[str]]:
    L = ["## Topology check: does the file bound a volume?\n"]
    if not rows:
        return L + ["Not run.\n"], []
    L.append("Fresh process per run, load included. `meshvol check FILE --json` welds vertices, "
             "finds boundary and non-manifold edges, winding, shells, cavities, overlapping shells "
             "and (unless `--no-intersections`) crossing triangles. Peers: "
             + "; ".join(f"**{t}**: {d}" for t, _, _, d in CHECK_PEERS)
             + ". Each peer is compared with the meshvol row that answers at least as much: "
               "peers without a self-intersection test against `meshvol check --no-intersections`, "
               "Open3D's `is_watertight()` against the full `meshvol check`. Self-intersections: "
               "meshvol gives a count, trueform and MeshLib yes/no, Open3D only inside "
               "`is_watertight()`; trueform, MeshLib and those with a self-intersection test are "
               "compared with the full `meshvol check`.\n")
    L.append("| file | tool | median s | runs | kernel s | ratio to meshvol | peak MB | closed | "
             "consistent winding | bodies | self-intersections | meshvol ahead? |")
    L.append("|---|---|--:|--:|--:|--:|--:|---|---|--:|--:|---|")
    verdicts = Verdicts("topology check")
    for f in files:
        group = [r for r in rows if r["item"] == f["name"]]
        for r in group:
            cmp = mv_row(group, f["name"], r.get("compare_to", r["tool"]))
            mv_s = cmp["median_s"] if cmp else None
            closed, wind, bodies, si = _check_verdict(r)
            if r["tool"] == "open3d-watertight":
                closed = (r.get("output") or {}).get("watertight")
                si = None
            note = failure_note(r)
            is_mv = r["tool"].startswith("meshvol")
            ahead = "" if is_mv else verdicts.cell(
                r, {"median_s": mv_s} if mv_s else None, f"{r['tool']} on `{f['name']}`",
                f"`{r['compare_to']}` ", kernel_mv=cmp, kernel_suffix=f" (`{r['compare_to']}`)")
            k = kernel_of(r) if not is_mv and "output" in r else None
            L.append(f"| {f['name']} | {r['tool']} | {time_cell(r)} | {runs_cell(r)} | {fmt_s(k)} | "
                     f"{'' if is_mv else ratio_cell(r, mv_s)} | {fmt_mb(r.get('peak_mb'))} | "
                     f"{_yn(closed) or md_cell(note)} | {_yn(wind)} | {_yn(bodies)} | {_yn(si)} | {ahead} |")
    L.extend(verdicts.sentences())
    behind = verdicts.not_ahead()
    # do the verdicts agree?
    disagree = []
    for f in files:
        group = [r for r in rows if r["item"] == f["name"] and "output" in r and not r.get("refused")]
        mv = next((r for r in group if r["tool"] == "meshvol check"), None)
        if not mv:
            continue
        mclosed, _, mbodies, _ = _check_verdict(mv)
        for r in group:
            if r["tool"].startswith("meshvol"):
                continue
            closed, _, bodies, _ = _check_verdict(r)
            if closed is not None and closed != mclosed:
                disagree.append(f"{r['tool']} on `{f['name']}` says closed={closed}")
            if bodies is not None and mbodies is not None and bodies != mbodies:
                disagree.append(f"{r['tool']} on `{f['name']}` counts {bodies} bodies, meshvol {mbodies}")
    if disagree:
        L.append("Verdicts that differ from meshvol's: " + "; ".join(disagree) + ".\n")
    else:
        L.append("Every verdict given agrees with meshvol's (closed, body count).\n")
    return L, behind


# --------------------------------------------------------------------------- grid


def run_grid(ctx, f: dict, p: dict) -> list[dict]:
    rows = []
    path, lo, hi = str(f["path"]), -100.0, 100.0
    bounds = f"{lo},{lo},{lo},{hi},{hi},{hi}"
    cache = DATA / "grid"
    cache.mkdir(parents=True, exist_ok=True)
    first = p["grid_cells"][0]
    for n in p["grid_cells"]:
        item = f"{f['name']} @ {n}³"
        r = base_row("grid", item, "meshvol", cells=n, triangles=f["triangles"])
        rows.append(ctx.run(r, ctx.meshvol + ["grid", path, "--cells", f"{n},{n},{n}", "--bounds",
                                               bounds, "--json"], meshvol=True, parse_keys=("total",)))
    n = first
    item = f"{f['name']} @ {n}³"
    pitch = (hi - lo) / n
    npy = cache / f"cells_{f['name']}_{n}.npy"
    need_npy = ctx.wants("manifold3d")
    if need_npy:  # meshvol's cell volumes, for the per-cell comparison (not timed)
        npy.unlink(missing_ok=True)
        subprocess.run(ctx.meshvol + ["grid", path, "--cells", f"{n},{n},{n}", "--bounds", bounds,
                                      "--out", str(npy), "--json"], capture_output=True, timeout=600)
    if ctx.wants("trimesh"):
        r = base_row("grid", item, "trimesh", cells=n, triangles=f["triangles"])
        rows.append(ctx.run(r, [PY, str(TOOLS_DIR / "grid_peer.py"), "trimesh", path, repr(pitch)],
                            key=("grid", "trimesh"), size=n**3, parse_keys=("filled",)))
    if ctx.wants("manifold3d") and npy.exists():
        r = base_row("grid", item, "manifold3d", cells=n, triangles=f["triangles"])
        rows.append(ctx.run(r, [PY, str(TOOLS_DIR / "grid_peer.py"), "manifold", path, str(npy),
                                repr(lo), repr(lo), repr(lo), repr(pitch), str(p["grid_sample"])],
                            key=("grid", "manifold3d"), size=1, parse_keys=("per_cell_s", "refused")))
    return rows


def report_grid(rows, f, p) -> tuple[list[str], list[str]]:
    L = ["## Grid: volume of the solid in each cell\n"]
    if not rows:
        return L + ["Not run.\n"], []
    ref = f["ref"]
    L.append(f"The sphere `{f['name']}` ({f['triangles']:,} triangles, radius 100) on an n³ grid over "
             "[-100, 100]³. `meshvol grid --cells n,n,n --bounds ... --json` computes the exact "
             "volume of the solid in every cell; its kernel time is the `seconds` it reports. "
             "Peers: **trimesh** `voxelized(pitch).fill()` (occupancy of voxels, not volumes; its "
             "kernel is that call after loading); **manifold3d** mesh ∩ box, one boolean per "
             "partial cell: timed on a random sample of the partial cells (`--grid-sample`), "
             "after the `Manifold` build, and extrapolated to all partial cells (a lower bound: a "
             "user would also have to find those cells). Relative error: meshvol's total and "
             "trimesh's voxel count × cell volume against the exact volume of the mesh; for "
             "manifold3d, the largest difference from meshvol's cell volumes, as a fraction of a "
             "cell. **meshvol ahead?** compares kernel times.\n")
    L.append("| grid | tool | whole process s | runs | kernel s | ratio to meshvol (kernel) | peak MB | result | relative error | meshvol ahead? |")
    L.append("|---|---|--:|--:|--:|--:|--:|---|--:|---|")
    behind, compared = [], 0
    for r in rows:
        out = r.get("output") or {}
        mv = mv_row(rows, r["item"])
        mv_k = kernel_of(mv) if mv else None
        k = kernel_of(r) if "output" in r and not r.get("refused") else None
        result, err = "", ""
        if r["tool"] == "meshvol" and out:
            result = f"total {out.get('total'):.10g}; {out.get('cells_partial', 0):,} partial cells"
            err = fmt_err(meshgen.rel_error(out.get("total"), ref))
        elif r["tool"] == "trimesh" and out:
            result = f"{out['filled']:,} filled voxels"
            err = fmt_err(meshgen.rel_error(out["volume"], ref))
        elif r["tool"] == "manifold3d" and "per_cell_s" in out:
            result = (f"{fmt_s(out['per_cell_s'])} s per cell × {out['partial']:,} partial cells "
                      f"({out['sampled']} timed) + {fmt_s(out['build_s'])} s build")
            err = f"{out['max_diff_of_cell']:.1e} of a cell vs meshvol"
        result = failure_note(r) or result
        ahead, ratio = "", ""
        if r["tool"] != "meshvol":
            if k is not None and mv_k:
                ratio = fmt_ratio(k / mv_k)
                compared += 1
                ahead = "yes" if k > mv_k else "**no**"
                if k <= mv_k:
                    behind.append(f"{r['tool']} on {r['item']} (kernel {fmt_s(k)} s vs {fmt_s(mv_k)} s)")
            else:
                ahead = ahead_cell(r, mv["median_s"] if mv else None)
                ratio = ratio_cell(r, mv["median_s"] if mv else None)
        L.append(f"| {r['item']} | {r['tool']} | {time_cell(r)} | {runs_cell(r)} | {fmt_s(k)} | {ratio} | "
                 f"{fmt_mb(r.get('peak_mb'))} | {md_cell(result)} | {err} | {ahead} |")
    L.append("")
    L.append(ahead_sentence("grid", behind, compared))
    return L, behind


# --------------------------------------------------------------------------- union


def prepare_union(p) -> list[Path]:
    count, tris = p["union"]
    cache = Cache("union")
    paths = []
    bodies = None
    for k in range(count):
        name = f"sphere{k:02d}_{size_label(tris)}.stl"
        if not cache.fresh(name):
            if bodies is None:
                bodies = pointgen.union_bodies(count, tris)
            v, f = bodies[k]
            meshgen.write_stl_binary(cache.dir / name, v, f)
            cache.done(name, triangles=int(len(f)))
        paths.append(cache.dir / name)
    return paths


def run_union(ctx, p) -> list[dict]:
    paths = prepare_union(p)
    count, tris = p["union"]
    item = f"{count} spheres × {size_label(tris)} triangles"
    rows = []
    r = base_row("union", item, "meshvol")
    rows.append(ctx.run(r, ctx.meshvol + ["union"] + [str(x) for x in paths] +
                        ["--tolerance", "1e-6", "--json"], meshvol=True, parse_keys=("lower",)))
    for tool in UNION_PEERS:
        if ctx.wants(tool):
            r = base_row("union", item, tool)
            rows.append(ctx.run(r, [PY, str(TOOLS_DIR / "union_peer.py"), tool] +
                                [str(x) for x in paths], key=("union", tool), size=1))
    return rows


UNION_PEERS = ("manifold3d", "trueform", "meshlib")


def interval_table(L: list[str], rows, section: str) -> "Verdicts":
    """Appends the table of a section whose meshvol row is a certified interval (union,
    intersect): each peer's volume is checked against it. Returns the verdicts."""
    L.append("| bodies | tool | median s | runs | kernel s | ratio to meshvol | peak MB | volume | check | meshvol ahead? |")
    L.append("|---|---|--:|--:|--:|--:|--:|--:|---|---|")
    verdicts = Verdicts(section)
    mv = next((r for r in rows if r["tool"] == "meshvol" and "median_s" in r), None)
    mvo = (mv or {}).get("output") or {}
    for r in rows:
        out = r.get("output") or {}
        vol, check = "", ""
        if r["tool"] == "meshvol" and out:
            vol = f"[{out['lower']:.12g}, {out['upper']:.12g}]"
            check = f"width {(out['upper'] - out['lower']) / out['lower']:.1e} relative"
        elif "volume" in out:
            vol = f"{out['volume']:.12g}"
            if mvo:
                if mvo["lower"] <= out["volume"] <= mvo["upper"]:
                    check = "inside meshvol's interval"
                else:
                    gap = min(abs(out["volume"] - mvo["lower"]), abs(out["volume"] - mvo["upper"]))
                    check = f"**outside** meshvol's interval (by {gap / mvo['lower']:.1e} relative)"
        check = failure_note(r) or check
        is_mv = r["tool"] == "meshvol"
        mv_s = mv["median_s"] if mv else None
        ahead = "" if is_mv else verdicts.cell(r, mv, r["tool"])
        L.append(f"| {r['item']} | {r['tool']} | {time_cell(r)} | {runs_cell(r)} | "
                 f"{fmt_s(kernel_of(r)) if not is_mv else ''} | {'' if is_mv else ratio_cell(r, mv_s)} | "
                 f"{fmt_mb(r.get('peak_mb'))} | {vol} | {md_cell(check)} | {ahead} |")
    L.extend(verdicts.sentences())
    return verdicts


def report_union(rows) -> tuple[list[str], list[str]]:
    L = ["## Union of overlapping bodies\n"]
    if not rows:
        return L + ["Not run.\n"], []
    L.append("Overlapping UV spheres (radius 100, centres 120 apart on a 5-wide grid, alternately "
             "lifted by 30), one binary STL each; fresh process per run, reading included. "
             "`meshvol union FILES --tolerance 1e-6 --json` gives a certified interval [lower, "
             "upper] for the volume of the union without building a boolean mesh; **manifold3d** "
             "builds each `Manifold`, `batch_boolean(..., OpType.Add)` and `volume()`; **trueform** "
             "`boolean_union` folded over the bodies two at a time, then `signed_volume`; "
             "**MeshLib** `boolean(A, B, BooleanOperation.Union)` folded the same way, then "
             "`Mesh.volume()` (kernel s: those calls after reading). No exact reference exists; the check is whether "
             "each peer's volume lies inside meshvol's certified interval (trueform's "
             "signed_volume sums in float32, about 1e-6 relative, so its result can fall "
             "outside an interval of width ~1e-10 without its boolean being wrong).\n")
    verdicts = interval_table(L, rows, "union")
    return L, verdicts.not_ahead()


# --------------------------------------------------------------------------- intersect

# Two spheres of radius 100, centres INTERSECT_OFFSET apart.
INTERSECT_OFFSET = (50.0, 30.0, 40.0)
INTERSECT_PEERS = ("manifold3d", "trueform", "meshlib")


def prepare_intersect(p) -> list[Path]:
    tris = p["intersect"]
    cache = Cache("intersect")
    paths = []
    for name, centre in (("a", (0.0, 0.0, 0.0)), ("b", INTERSECT_OFFSET)):
        file = f"intersect_{name}_{size_label(tris)}.stl"
        if not cache.fresh(file):
            v, f, _ = meshgen.uv_sphere(tris, radius=100.0, center=centre)
            meshgen.write_stl_binary(cache.dir / file, v, f)
            cache.done(file, triangles=int(len(f)))
        paths.append(cache.dir / file)
    return paths


def smooth_lens(d: float, r: float = 100.0) -> tuple[float, float]:
    """The volume of two balls of radius r, centres d apart, in common, and their IoU."""
    lens = math.pi * (4 * r + d) * (2 * r - d) ** 2 / 12
    ball = 4 / 3 * math.pi * r ** 3
    return lens, lens / (2 * ball - lens)


def voxel_iou(res: int, r: float = 100.0) -> tuple[float, float]:
    """IoU of the balls as a voxel count at `res`³ over the box holding both: a voxel is
    in a ball when its centre is (what voxelising a mesh at that pitch gives, less the
    mesh's own discretization). Returns (IoU, seconds)."""
    t0 = time.perf_counter()
    c = np.array(INTERSECT_OFFSET)
    lo, hi = np.minimum(0.0, c) - r, np.maximum(0.0, c) + r
    axes = [lo[k] + (np.arange(res) + 0.5) * (hi[k] - lo[k]) / res for k in range(3)]
    x, y, z = np.meshgrid(*axes, indexing="ij", sparse=True)
    in_a = x * x + y * y + z * z <= r * r
    in_b = (x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2 <= r * r
    both, either = np.count_nonzero(in_a & in_b), np.count_nonzero(in_a | in_b)
    return both / either, time.perf_counter() - t0


def run_intersect(ctx, p) -> tuple[list[dict], list[dict]]:
    a, b = prepare_intersect(p)
    item = f"2 spheres × {size_label(p['intersect'])} triangles"
    rows = []
    r = base_row("intersect", item, "meshvol")
    rows.append(ctx.run(r, ctx.meshvol + ["intersect", str(a), str(b), "--json"], meshvol=True,
                        parse_keys=("lower",)))
    for tool in INTERSECT_PEERS:
        if ctx.wants(tool):
            r = base_row("intersect", item, tool)
            rows.append(ctx.run(r, [PY, str(TOOLS_DIR / "intersect_peer.py"), tool, str(a), str(b)],
                                key=("intersect", tool), size=1))
    voxels = []
    for res in (32, 64, 128, 256):
        iou, seconds = voxel_iou(res)
        voxels.append({"res": res, "iou": iou, "seconds": seconds})
    return rows, voxels


def report_intersect(rows, voxels) -> tuple[list[str], list[str]]:
    L = ["## Intersection of two bodies\n"]
    if not rows:
        return L + ["Not run.\n"], []
    d = math.dist((0.0, 0.0, 0.0), INTERSECT_OFFSET)
    L.append(f"Two UV spheres of radius 100, centres {d:.4g} apart, one binary STL each; fresh "
             "process per run, reading included. `meshvol intersect A B --json` gives a certified "
             "interval for |A∩B| without a boolean mesh, with IoU, Dice, the moments and the "
             "contact interface; **manifold3d** builds each `Manifold`, `A ^ B`, `volume()`; "
             "**trueform** `boolean_intersection`, `signed_volume`; **MeshLib** `boolean(A, B, "
             "BooleanOperation.Intersection)`, `Mesh.volume()` (kernel s: those calls after "
             "reading). The check is whether each peer's volume lies inside meshvol's interval.\n")
    verdicts = interval_table(L, rows, "intersect")
    mv = next((r for r in rows if r["tool"] == "meshvol" and "median_s" in r), None)
    mvo = (mv or {}).get("output") or {}
    lens, smooth_iou = smooth_lens(d)
    if mvo and voxels:
        L.append("\n**IoU by voxels.** The same two balls voxelised at n³ over the box holding both "
                 "(a voxel counts when its centre is inside: what voxelising the meshes gives, without "
                 "the meshes' own discretization), against meshvol's IoU of the polyhedra and the "
                 f"smooth balls' IoU {smooth_iou:.6f}:\n")
        L.append("| voxels | IoU | error vs meshvol's IoU | seconds |")
        L.append("|---|--:|--:|--:|")
        for v in voxels:
            err = (v["iou"] - mvo["iou"]) / mvo["iou"]
            L.append(f"| {v['res']}³ | {v['iou']:.6f} | {err:+.1e} | {v['seconds']:.3f} |")
        L.append(f"| meshvol (polyhedra) | {mvo['iou']:.6f} | interval [{mvo['iou_lower']:.9f}, "
                 f"{mvo['iou_upper']:.9f}] | |")
        L.append("")
    return L, verdicts.not_ahead()


# --------------------------------------------------------------------------- hull


def prepare_hull(p) -> list[dict]:
    n = p["hull_points"]
    cache = Cache("hull")
    made = None
    out = []
    names = [f"{k}@{o:g}" for k in ("ball", "sphere", "lattice") for o in (0.0, 1e5, 1e7)]
    refs_path = cache.dir / f"refs_{n}.json"
    refs = load_json(refs_path, {}) if all(cache.fresh(f"{nm}_{n}.xyz") for nm in names) else {}
    for i, name in enumerate(names):
        fname = f"{name}_{n}.xyz"
        if not cache.fresh(fname) or name not in refs:
            if made is None:
                made = pointgen.clouds(n)
            _, at_origin, pts = made[i]
            np.savetxt(cache.dir / fname, pts, fmt="%.17g")
            cache.done(fname, points=int(len(pts)))
            refs[name] = hull_reference(name, at_origin)
            refs_path.write_text(json.dumps(refs, indent=1))
        out.append({"name": name, "path": cache.dir / fname, "points": cache.meta(fname).get("points"),
                    "ref": refs[name]})
    return out


def hull_reference(name, at_origin) -> dict:
    """Exact for the lattice; otherwise qhull on the same cloud at the origin (if scipy is here)."""
    if name.startswith("lattice"):
        k = round(len(at_origin) ** (1 / 3))
        v, a = pointgen.lattice_exact(k)
        return {"volume": v, "area": a, "how": "exact"}
    try:
        from scipy.spatial import ConvexHull
    except ImportError:
        return {"volume": None, "area": None, "how": "none (scipy missing)"}
    h = ConvexHull(at_origin)
    return {"volume": float(h.volume), "area": float(h.area), "how": "qhull at the origin"}


def run_hull(ctx, p) -> tuple[list[dict], list[dict]]:
    clouds = prepare_hull(p)
    rows = []
    for c in clouds:
        r = base_row("hull", c["name"], "meshvol", points=c["points"])
        rows.append(ctx.run(r, ctx.meshvol + ["hull", str(c["path"]), "--json"], meshvol=True))
        if ctx.wants("scipy"):
            r = base_row("hull", c["name"], "scipy (qhull)", points=c["points"])
            rows.append(ctx.run(r, [PY, str(TOOLS_DIR / "hull_peer.py"), str(c["path"])],
                                key=("hull", "scipy", c["name"].split("@")[0]), size=c["points"]))
    return rows, clouds


def hull_worst(rows, clouds, tool="meshvol"):
    """The tool's largest relative volume or area difference from the references (None: no result)."""
    by = {c["name"]: c["ref"] for c in clouds}
    worst = None
    for r in rows:
        out = r.get("output") or {}
        ref = by.get(r["item"], {})
        if r["tool"] == tool and "volume" in out and ref.get("volume"):
            e = max(abs(out["volume"] - ref["volume"]) / ref["volume"],
                    abs(out["area"] - ref["area"]) / ref["area"])
            worst = e if worst is None else max(worst, e)
    return worst


def report_hull(rows, clouds) -> tuple[list[str], list[str]]:
    L = ["## Convex hull of a point cloud\n"]
    if not rows:
        return L + ["Not run.\n"], []
    n = clouds[0]["points"] if clouds else 0
    L.append(f"Clouds of {n:,} points (`.xyz`, `%.17g`): in a ball and on a sphere of radius 10 "
             "(coordinates on a 2⁻²⁰ grid) and a k³ lattice (many coplanar points on every face), "
             "each at offsets 0, 1e5 and 1e7, exact translates of one another. Fresh process per "
             "run, reading included: `meshvol hull FILE --json` against **scipy** "
             "`np.loadtxt` + `scipy.spatial.ConvexHull` (qhull; kernel s: ConvexHull alone). "
             "Reference: the exact hull for the lattice, otherwise qhull on the same cloud at the "
             "origin (qhull works in the input coordinates, so far from the origin its own "
             "result loses digits). Relative differences above 1e-12 are in bold.\n")
    L.append("| cloud | tool | median s | runs | kernel s | ratio to meshvol | peak MB | volume rel. diff | area rel. diff | meshvol ahead? |")
    L.append("|---|---|--:|--:|--:|--:|--:|--:|--:|---|")
    verdicts, worst = Verdicts("convex hull"), {}
    by = {c["name"]: c for c in clouds}
    for r in rows:
        out = r.get("output") or {}
        ref = by[r["item"]]["ref"]
        dv = da = ""
        if "volume" in out and ref.get("volume"):
            ev = abs(out["volume"] - ref["volume"]) / ref["volume"]
            ea = abs(out["area"] - ref["area"]) / ref["area"]
            worst[r["tool"]] = max(worst.get(r["tool"], 0.0), ev, ea)
            dv = fmt_err(ev) if ev <= 1e-12 else f"**{fmt_err(ev)}**"
            da = fmt_err(ea) if ea <= 1e-12 else f"**{fmt_err(ea)}**"
        else:
            dv = md_cell(failure_note(r))
        is_mv = r["tool"] == "meshvol"
        mv = mv_row(rows, r["item"])
        mv_s = mv["median_s"] if mv else None
        ahead = "" if is_mv else verdicts.cell(r, mv, f"{r['tool']} on {r['item']}")
        L.append(f"| {r['item']} | {r['tool']} | {time_cell(r)} | {runs_cell(r)} | "
                 f"{'' if is_mv else fmt_s(kernel_of(r))} | {'' if is_mv else ratio_cell(r, mv_s)} | "
                 f"{fmt_mb(r.get('peak_mb'))} | {dv} | {da} | {ahead} |")
    L.extend(verdicts.sentences())
    behind = verdicts.not_ahead()
    if worst:
        L.append("Largest relative difference from the reference: " +
                 "; ".join(f"{t} {e:.1e}" for t, e in worst.items()) + ".\n")
    return L, behind


# --------------------------------------------------------------------------- area


def prepare_area(p) -> list[dict]:
    nv, npoly = p["area_vertices"], p["area_polygons"]
    cache = Cache("area")
    out = []
    for kind, n in (("big", nv), ("small", npoly)):
        data = None
        for ext in ("wkt", "geojson"):
            name = f"{kind}_{size_label(n)}.{ext}"
            if not cache.fresh(name):
                if data is None:
                    data = pointgen.big_polygon(n) if kind == "big" else pointgen.small_polygons(n)
                    ref = pointgen.exact_area_big(data) if kind == "big" else pointgen.exact_area_small(data)
                if kind == "big":
                    (pointgen.write_polygon_wkt if ext == "wkt" else pointgen.write_polygon_geojson)(
                        cache.dir / name, data)
                    verts = sum(len(r) - 1 for rings in data for r in rings)
                    polys = 1
                else:
                    (pointgen.write_small_wkt if ext == "wkt" else pointgen.write_small_geojson)(
                        cache.dir / name, data)
                    verts = int(data.shape[0] * (data.shape[1] - 1))
                    polys = int(data.shape[0])
                cache.done(name, num=str(ref.numerator), den=str(ref.denominator),
                           vertices=verts, polygons=polys)
            m = cache.meta(name)
            out.append({"name": name, "path": cache.dir / name, "kind": kind,
                        "ref": Fraction(int(m["num"]), int(m["den"])), "vertices": m["vertices"],
                        "polygons": m["polygons"], "mb": (cache.dir / name).stat().st_size / 1e6})
    return out


def run_area(ctx, p) -> tuple[list[dict], list[dict]]:
    files = prepare_area(p)
    rows = []
    for f in files:
        r = base_row("area", f["name"], "meshvol", vertices=f["vertices"])
        rows.append(ctx.run(r, ctx.meshvol + ["area", str(f["path"]), "--json"], meshvol=True,
                            parse_keys=("area",)))
        for tool in ("shapely", "shapely-valid"):
            if ctx.wants(tool):
                r = base_row("area", f["name"], tool, vertices=f["vertices"])
                rows.append(ctx.run(r, [PY, str(TOOLS_DIR / "area_peer.py"), tool, str(f["path"])],
                                    key=("area", tool, f["kind"]), size=f["vertices"],
                                    parse_keys=("area",)))
    return rows, files


def report_area(rows, files) -> tuple[list[str], list[str]]:
    L = ["## 2D polygon area\n"]
    if not rows:
        return L + ["Not run.\n"], []
    L.append("Polygons at a UTM-like offset (500 km, 4 200 km), coordinates multiples of 2⁻⁸ written "
             "exactly: `big` is one star-shaped polygon with a hole, `small` many octagons (one "
             "feature each; in WKT one `POLYGON` per line, in GeoJSON a FeatureCollection). Fresh "
             "process per run, parsing included. `meshvol area FILE --json` gives area, perimeter, "
             "centroid and second moments per feature and in total, and checks rings for "
             "self-intersections and crossings. **shapely**: the file read and parsed with "
             "`shapely.from_wkt` (one per line) or `shapely.from_geojson`, then vectorised "
             "`area`, `length` and `centroid`; **shapely-valid** adds `is_valid`, GEOS's own "
             "ring check, the like-for-like row. Relative area error against the exact area of "
             "the numbers in the file.\n")
    L.append("| file | tool | size MB | median s | runs | kernel s | ratio to meshvol | peak MB | relative area error | meshvol ahead? |")
    L.append("|---|---|--:|--:|--:|--:|--:|--:|--:|---|")
    verdicts, acc = Verdicts("2D area"), []
    by = {f["name"]: f for f in files}
    for r in rows:
        f = by[r["item"]]
        out = r.get("output") or {}
        err = ""
        if "area" in out:
            r["rel_err"] = meshgen.rel_error(out["area"], f["ref"])
            err = fmt_err(r["rel_err"])
            if out.get("valid") is False:
                err += " (says invalid)"
        else:
            err = md_cell(failure_note(r))
        is_mv = r["tool"] == "meshvol"
        mv = mv_row(rows, r["item"])
        mv_s = mv["median_s"] if mv else None
        if not is_mv and seconds_of(r) and mv_s and "rel_err" in mv and "rel_err" in r \
                and r["rel_err"] < mv["rel_err"]:
            acc.append(f"{r['tool']} on `{r['item']}` ({fmt_err(r['rel_err'])} vs meshvol "
                       f"{fmt_err(mv['rel_err'])})")
        ahead = "" if is_mv else verdicts.cell(r, mv, f"{r['tool']} on `{r['item']}`")
        L.append(f"| {r['item']} ({f['vertices']:,} vertices) | {r['tool']} | {f['mb']:.1f} | {time_cell(r)} | "
                 f"{runs_cell(r)} | {'' if is_mv else fmt_s(kernel_of(r))} | "
                 f"{'' if is_mv else ratio_cell(r, mv_s)} | {fmt_mb(r.get('peak_mb'))} | {err} | {ahead} |")
    L.extend(verdicts.sentences())
    behind = verdicts.not_ahead()
    if acc:
        L.append("**More accurate than meshvol:** " + "; ".join(acc) + ".\n")
        behind = behind + [f"accuracy: {a}" for a in acc]
    return L, behind


# --------------------------------------------------------------------------- chart data


def chart_items(section, rows) -> tuple[str, list[tuple[str, float, bool]]] | None:
    """(title, [(label, seconds, is_meshvol)]) for one panel of RESULTS.png, or None."""
    if not rows:
        return None
    item = rows[0]["item"]
    pts = []
    for r in rows:
        if r["item"] != item:
            continue
        s = seconds_of(r)
        if s is None:
            continue
        label = r["tool"] + (" (>)" if s[1] else "")
        pts.append((label, s[0], r["tool"].startswith("meshvol")))
    titles = {"check": "topology check", "grid": "grid", "union": "union", "intersect": "intersection",
              "profile": "profile", "hull": "convex hull",
              "area": "2D area"}
    if section == "grid":  # kernel times: manifold3d's is extrapolated to all partial cells
        pts = [(r["tool"] + (" (extrapolated)" if r["tool"] == "manifold3d" else ""), kernel_of(r),
                r["tool"] == "meshvol") for r in rows
               if r["item"] == item and r.get("output") and kernel_of(r) is not None]
        return (f"grid: {item}", pts, "kernel seconds (log; lower is better)") if pts else None
    return (f"{titles.get(section, section)}: {item}", pts) if pts else None


# --------------------------------------------------------------------------- profile


def run_profile(ctx, f: dict, p: dict) -> list[dict]:
    """`meshvol profile FILE --axis z --levels N --json` (checked, and --no-check) against
    MeshLib's computeBasinVolume at the same N + 1 levels (tools/profile_peer.py)."""
    path, n = str(f["path"]), p["profile_levels"]
    item = f"{f['name']} @ {n} levels"
    rows = []
    for tool, extra in (("meshvol", []), ("meshvol --no-check", ["--no-check"])):
        r = base_row("profile", item, tool, triangles=f["triangles"], levels=n)
        rows.append(ctx.run(r, ctx.meshvol + ["profile", path, "--axis", "z", "--levels", str(n),
                                               "--json"] + extra, meshvol=True,
                            parse_keys=("volume_below",)))
    if ctx.wants("meshlib"):
        r = base_row("profile", item, "meshlib", triangles=f["triangles"], levels=n)
        rows.append(ctx.run(r, [PY, str(TOOLS_DIR / "profile_peer.py"), "meshlib", path, str(n)],
                            key=("profile", "meshlib"), size=f["triangles"],
                            parse_keys=("volume_below", "refused")))
    return rows


def report_profile(rows, f) -> tuple[list[str], list[str]]:
    L = ["## Profile: volume below each level (strapping table)\n"]
    if not rows:
        return L + ["Not run.\n"], []
    n = rows[0].get("levels")
    L.append(f"The sphere `{f['name']}` ({f['triangles']:,} triangles), {n} slabs along z (N + 1 "
             "equally spaced levels from its lowest to its highest point). Fresh process per run, "
             f"reading included. `meshvol profile FILE --axis z --levels {n} --json` (checked, "
             "and `--no-check`) gives the volume below every level, slab volumes and section "
             "areas; **MeshLib**: `loadMesh`, then `computeBasinVolume(mesh, all faces, level)` "
             "per level (the volume between the surface and the water plane; minus the solid's "
             "volume below the level on a closed outward solid, so the sign is flipped; kernel s: "
             "those calls after loading). The peer is compared with the checked `meshvol` row. "
             "Difference: the largest |peer − meshvol| over the levels, relative to the total "
             "volume.\n")
    L.append("| mesh | tool | median s | runs | kernel s | ratio to meshvol | peak MB | volume below the top level | largest difference from meshvol | meshvol ahead? |")
    L.append("|---|---|--:|--:|--:|--:|--:|--:|--:|---|")
    verdicts = Verdicts("profile")
    mv = mv_row(rows, rows[0]["item"])
    mvb = ((mv or {}).get("output") or {}).get("volume_below")
    for r in rows:
        out = r.get("output") or {}
        vb = out.get("volume_below")
        top = f"{vb[-1]:.12g}" if vb else md_cell(failure_note(r))
        diff = ""
        if vb and mvb and len(vb) == len(mvb) and r is not mv:
            diff = fmt_err(max(abs(a - b) for a, b in zip(vb, mvb)) / abs(mvb[-1]))
        elif vb and mvb and len(vb) != len(mvb):
            diff = f"{len(vb)} levels vs meshvol's {len(mvb)}"
        is_mv = r["tool"].startswith("meshvol")
        mv_s = mv["median_s"] if mv else None
        ahead = "" if is_mv else verdicts.cell(r, mv, f"{r['tool']} on {r['item']}")
        L.append(f"| {r['item']} | {r['tool']} | {time_cell(r)} | {runs_cell(r)} | "
                 f"{'' if is_mv else fmt_s(kernel_of(r))} | "
                 f"{'' if r is mv else ratio_cell(r, mv_s)} | {fmt_mb(r.get('peak_mb'))} | {top} | "
                 f"{diff} | {ahead} |")
    L.extend(verdicts.sentences())
    return L, verdicts.not_ahead()


# --------------------------------------------------------------------------- scaling


SCALING_COMMANDS = [  # (label, argv after `meshvol`, with {path} and {n})
    ("volume", ["volume", "{path}", "--json"]),
    ("volume --no-check", ["volume", "{path}", "--json", "--no-check"]),
    ("check", ["check", "{path}", "--json"]),
    ("grid {n}³", ["grid", "{path}", "--cells", "{n},{n},{n}", "--bounds",
                   "-100,-100,-100,100,100,100", "--json"]),
]


def prepare_scaling(sizes) -> list[dict]:
    """Spheres of each size, streamed to binary STL (the same bytes as meshgen.make + the STL
    writer, but without the whole face array in memory): DATA/scaling/sphere_N.stl."""
    cache = Cache("scaling")
    out = []
    for n in sizes:
        name = f"sphere_{size_label(n)}.stl"
        if not cache.fresh(name):
            import time as _time

            t0 = _time.perf_counter()
            tris = meshgen.write_sphere_stl_stream(cache.dir / name, n)
            cache.done(name, triangles=int(tris))
            print(f"[compare] wrote scaling/{name} ({(cache.dir / name).stat().st_size / 1e6:.0f} MB, "
                  f"{_time.perf_counter() - t0:.1f} s)", flush=True)
        out.append({"name": name, "path": cache.dir / name, "target": n,
                    "triangles": cache.meta(name)["triangles"]})
    return out


def run_scaling(ctx, p) -> tuple[list[dict], list[dict]]:
    files = prepare_scaling(p["scaling_sizes"])
    cells = p["scaling_cells"]
    rows = []
    for label, argv in SCALING_COMMANDS:
        label = label.format(n=cells)
        for f in files:
            a = [x.format(path=str(f["path"]), n=cells) for x in argv]
            r = base_row("scaling", f["name"], label, triangles=f["triangles"])
            rows.append(ctx.run(r, ctx.meshvol + a, meshvol=True, parse_keys=None, ok_codes=(0, 1)))
    return rows, files


def report_scaling(rows, files) -> tuple[list[str], list[str]]:
    L = ["## Scaling: meshvol's time and memory against triangle count\n"]
    if not rows:
        return L + ["Not run.\n"], []
    L.append("UV spheres (radius 100) of " + ", ".join(f"{f['triangles']:,}" for f in files) +
             " triangles, binary STL (written a block at a time). meshvol only, fresh process per "
             "run, reading included: `volume` (checked), `volume --no-check`, `check` (with the "
             "self-intersection search) and `grid` on a fixed grid over [-100, 100]³. Peak MB is "
             "the process's maximum resident set; bytes per triangle = peak / triangles (the "
             "binary STL itself is 50 bytes per triangle). **Step** = (time / previous size's "
             "time) / (triangles / previous size's triangles): 1 is linear, above 1 worse than "
             "linear; at small sizes process start-up makes it fall below 1.\n")
    L.append("| command | triangles | median s | runs | peak MB | bytes per triangle | ns per triangle | step (time ratio / size ratio) |")
    L.append("|---|--:|--:|--:|--:|--:|--:|--:|")
    for label in dict.fromkeys(r["tool"] for r in rows):
        prev = None
        for r in (x for x in rows if x["tool"] == label):
            t, n = r.get("median_s"), r["triangles"]
            bpt = f"{r['peak_mb'] * 2**20 / n:.0f}" if r.get("peak_mb") else ""
            ns = f"{t / n * 1e9:.0f}" if t else ""
            step = ""
            if t and prev and prev.get("median_s"):
                step = f"{(t / prev['median_s']) / (n / prev['triangles']):.2f}"
            note = "" if t else md_cell(failure_note(r) or r.get("error", "failed"))
            L.append(f"| `meshvol {label}` | {n:,} | {time_cell(r) if t else note} | {runs_cell(r)} | "
                     f"{fmt_mb(r.get('peak_mb'))} | {bpt} | {ns} | {step} |")
            prev = r
    L.append("")
    return L, []


def write_scaling_chart(path, rows) -> bool:
    """Log-log time and peak memory against triangles, one line per command."""
    if not rows:
        return False
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return False
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    for label in dict.fromkeys(r["tool"] for r in rows):
        rs = [r for r in rows if r["tool"] == label and r.get("median_s")]
        if not rs:
            continue
        n = [r["triangles"] for r in rs]
        ax1.plot(n, [r["median_s"] for r in rs], "o-", label=f"meshvol {label}")
        mem = [(r["triangles"], r["peak_mb"]) for r in rs if r.get("peak_mb")]
        if mem:
            ax2.plot([m[0] for m in mem], [m[1] for m in mem], "o-", label=f"meshvol {label}")
    ns = sorted({r["triangles"] for r in rows})
    for ax, what in ((ax1, "seconds, whole process, median"), (ax2, "peak MB (max RSS)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles (log)")
        ax.set_ylabel(what + " (log)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    if len(ns) > 1 and any(r.get("median_s") for r in rows):  # a linear reference line
        t0 = max(r["median_s"] for r in rows if r["triangles"] == ns[-1] and r.get("median_s"))
        ax1.plot(ns, [t0 * n / ns[-1] for n in ns], "k:", label="linear (slope 1)")
        ax1.legend(fontsize=8)
    ax1.set_title("time against triangles")
    ax2.set_title("peak memory against triangles")
    fig.suptitle("meshvol scaling on UV spheres (bench/compare --only scaling)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True
