"""Polygon files (for `meshvol area`), point clouds (for `meshvol hull`) and the union bodies.

numpy only. Like meshgen.py, every coordinate is a multiple of 2**-q small enough to be
exact in float64 and printed exactly by "%.{q}f", so the reference values computed here
are those of the numbers in the files.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

import meshgen

# --------------------------------------------------------------------------- polygons
#
# Coordinates sit at a UTM-like offset (500 km, 4 200 km), where naive shoelace sums lose
# digits; they are multiples of 2**-8 (about 4 mm), written with "%.8f", which prints such
# a number exactly.

AREA_Q = 8
AREA_OFFSET = (500_000.0, 4_200_000.0)


def _snap2(xy: np.ndarray, q: int = AREA_Q) -> np.ndarray:
    s = float(2**q)
    return np.round(xy * s) / s


def big_polygon(n_vertices: int):
    """One star-shaped polygon (simple by construction) of about n_vertices, with one hole.

    The exterior is r(t) = R (1 + 0.2 sin 13t + 0.05 sin 97t) around the centre, counter-
    clockwise; the hole, clockwise, a circle of radius 0.25 R with 1% of the vertices.
    Star-shaped about the centre, with vertices far apart compared with the 2**-8 grid, so
    snapping keeps it simple. Returns [exterior, hole] as closed (k+1, 2) arrays.
    """
    R = 100_000.0
    n_hole = max(8, n_vertices // 100)
    n_ext = max(16, n_vertices - n_hole)
    t = 2.0 * np.pi * np.arange(n_ext) / n_ext
    r = R * (1.0 + 0.2 * np.sin(13 * t) + 0.05 * np.sin(97 * t))
    ext = np.stack([r * np.cos(t), r * np.sin(t)], axis=1) + AREA_OFFSET
    th = -2.0 * np.pi * np.arange(n_hole) / n_hole  # clockwise
    hole = np.stack([0.25 * R * np.cos(th), 0.25 * R * np.sin(th)], axis=1) + AREA_OFFSET
    rings = []
    for ring in (ext, hole):
        ring = _snap2(ring)
        rings.append(np.concatenate([ring, ring[:1]]))
    return [rings]  # one polygon


def small_polygons(count: int, seed: int = 3):
    """`count` octagons of random radius (15..45) on a grid of spacing 100, counter-clockwise."""
    rng = np.random.default_rng(seed)
    side = int(math.ceil(math.sqrt(count)))
    idx = np.arange(count)
    centres = np.stack([idx % side, idx // side], axis=1) * 100.0 + AREA_OFFSET
    radius = rng.uniform(15.0, 45.0, size=count)
    rot = rng.uniform(0.0, 2.0 * np.pi, size=count)
    t = 2.0 * np.pi * np.arange(8) / 8
    ang = rot[:, None] + t[None, :]
    pts = centres[:, None, :] + radius[:, None, None] * np.stack([np.cos(ang), np.sin(ang)], -1)
    pts = _snap2(pts)
    closed = np.concatenate([pts, pts[:, :1]], axis=1)  # (count, 9, 2)
    return closed


def ring_twice_area(ring: np.ndarray, q: int = AREA_Q) -> int:
    """2 * signed area * 4**q of a closed ring, exactly (Python int).

    Coordinates become integers (multiples of 2**-q) relative to the first vertex, where the
    shoelace products are exact in int64; partial sums of 1024 stay below 2**63.
    """
    z = np.round((ring - ring[0]) * 2.0**q).astype(np.int64)
    x, y = z[:-1, 0], z[:-1, 1]
    x1, y1 = z[1:, 0], z[1:, 1]
    assert np.abs(z).max(initial=0) < 2**26
    cross = x * y1 - x1 * y
    pad = (-len(cross)) % 1024
    cross = np.concatenate([cross, np.zeros(pad, np.int64)]).reshape(-1, 1024).sum(axis=1)
    return sum(int(c) for c in cross)


def exact_area_big(polys) -> Fraction:
    total = sum(ring_twice_area(r) for rings in polys for r in rings)
    return Fraction(total, 2 * 4**AREA_Q)


def exact_area_small(closed: np.ndarray) -> Fraction:
    z = np.round((closed - closed[:, :1]) * 2.0**AREA_Q).astype(np.int64)
    cross = z[:, :-1, 0] * z[:, 1:, 1] - z[:, 1:, 0] * z[:, :-1, 1]
    return Fraction(sum(int(c) for c in cross.sum(axis=1)), 2 * 4**AREA_Q)


def _ring_wkt(ring: np.ndarray) -> str:
    c = f"%.{AREA_Q}f"
    tmpl = ", ".join([f"{c} {c}"] * len(ring))
    return "(" + tmpl % tuple(ring.ravel().tolist()) + ")"


def _ring_geojson(ring: np.ndarray) -> str:
    c = f"%.{AREA_Q}f"
    tmpl = ",".join([f"[{c},{c}]"] * len(ring))
    return "[" + tmpl % tuple(ring.ravel().tolist()) + "]"


def write_polygon_wkt(path, polys):
    """One POLYGON per line (each line a feature)."""
    with open(path, "w") as fh:
        for rings in polys:
            fh.write("POLYGON (" + ", ".join(_ring_wkt(r) for r in rings) + ")\n")


def write_polygon_geojson(path, polys):
    """A FeatureCollection, one Feature per polygon."""
    with open(path, "w") as fh:
        fh.write('{"type":"FeatureCollection","features":[\n')
        for i, rings in enumerate(polys):
            if i:
                fh.write(",\n")
            fh.write('{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[' +
                     ",".join(_ring_geojson(r) for r in rings) + "]}}")
        fh.write("\n]}\n")


def write_small_wkt(path, closed: np.ndarray, chunk=20_000):
    c = f"%.{AREA_Q}f"
    line = "POLYGON ((" + ", ".join([f"{c} {c}"] * closed.shape[1]) + "))\n"
    with open(path, "w") as fh:
        for s in range(0, len(closed), chunk):
            block = closed[s : s + chunk]
            fh.write((line * len(block)) % tuple(block.ravel().tolist()))


def write_small_geojson(path, closed: np.ndarray, chunk=20_000):
    c = f"%.{AREA_Q}f"
    feat = ('{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[' +
            ",".join([f"[{c},{c}]"] * closed.shape[1]) + "]]}}")
    with open(path, "w") as fh:
        fh.write('{"type":"FeatureCollection","features":[\n')
        for s in range(0, len(closed), chunk):
            block = closed[s : s + chunk]
            text = ",\n".join([feat] * len(block)) % tuple(block.ravel().tolist())
            fh.write((",\n" if s else "") + text)
        fh.write("\n]}\n")


# --------------------------------------------------------------------------- point clouds


def clouds(n: int, seed: int = 1):
    """The clouds of the old bench/hull/vs_qhull.py: (name, at_origin, points).

    Points in a ball and on a sphere (radius 10, coordinates on a 2**-20 grid) and a k^3
    lattice (many coplanar points on every face), each at offsets 0, 1e5 and 1e7: exact
    translates, so qhull on the cloud at the origin is the reference for all three.
    """
    rng = np.random.default_rng(seed)

    def grid(a):
        return np.round(a * 2.0**20) / 2.0**20

    ball = rng.normal(size=(n, 3))
    ball *= (rng.random(n) ** (1 / 3) / np.linalg.norm(ball, axis=1))[:, None]
    sphere = rng.normal(size=(n, 3))
    sphere /= np.linalg.norm(sphere, axis=1)[:, None]
    k = max(2, round(n ** (1 / 3)))
    lattice = np.stack(np.meshgrid(*[np.arange(k, dtype=float)] * 3), -1).reshape(-1, 3)
    out = []
    for name, pts in [("ball", grid(ball * 10)), ("sphere", grid(sphere * 10)), ("lattice", lattice)]:
        for offset in (0.0, 1e5, 1e7):
            out.append((f"{name}@{offset:g}", pts, pts + offset))
    return out


def lattice_exact(k: int):
    """Volume and area of the hull of the k^3 lattice {0..k-1}^3."""
    return float((k - 1) ** 3), float(6 * (k - 1) ** 2)


# --------------------------------------------------------------------------- union bodies


def union_bodies(count: int, tris: int):
    """`count` overlapping spheres of about `tris` triangles (radius 100, 2**-10 grid).

    Centres 120 apart on a 5-wide grid, alternately lifted by 30: the layout of the old
    bench/grid_peers.py (there radius 1, spacing 1.2). Returns [(vertices, faces)].
    """
    out = []
    for k in range(count):
        c = (120.0 * (k % 5), 120.0 * (k // 5), 30.0 * (k % 2))
        v, f, _ = meshgen.uv_sphere(tris, radius=100.0, center=c)
        out.append((v, f))
    return out


def selftest():
    polys = big_polygon(1000)
    ext, hole = polys[0]
    # shoelace in Fractions on the same numbers
    def frac(ring):
        s = Fraction(0)
        for (x0, y0), (x1, y1) in zip(ring[:-1], ring[1:]):
            s += Fraction(x0) * Fraction(y1) - Fraction(x1) * Fraction(y0)
        return s / 2
    assert exact_area_big(polys) == frac(ext) + frac(hole)
    assert frac(ext) > 0 > frac(hole)
    sm = small_polygons(50)
    assert exact_area_small(sm) == sum(frac(r) for r in sm)
    text = "%.8f" % sm[3, 2, 0]
    assert Fraction(text) == Fraction(float(sm[3, 2, 0])), "coordinates print exactly"
    print("pointgen selftest: exact areas agree with Fractions")


if __name__ == "__main__":
    selftest()
