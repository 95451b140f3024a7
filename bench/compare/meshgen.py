"""Test meshes, file writers and the exact reference volume for bench/compare.

Everything here is numpy only, so the timing workers can import it cheaply.

Coordinates are snapped to a dyadic grid (a multiple of 2**-q) chosen so that every
coordinate has at most 24 significant bits. Such a number is exactly a float32, exactly a
float64, and exactly the short decimal that "%.{q}f" prints. So the binary STL, the ASCII
STL and the OBJ of one mesh hold the very same numbers, whichever precision a reader
parses them into, and one exact reference volume serves all of them (binary PLY, float32,
included).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

# --------------------------------------------------------------------------- meshes


def _snap(v: np.ndarray, q: int) -> np.ndarray:
    """Round to multiples of 2**-q and check that the result is exact in float32."""
    s = float(2**q)
    out = np.round(v * s) / s
    if not np.array_equal(out.astype(np.float32).astype(np.float64), out):
        raise ValueError(f"grid 2**-{q} does not fit float32 for these coordinates")
    return out


def uv_sphere(target_tris: int, radius=100.0, center=(0.0, 0.0, 0.0), q=10):
    """A closed, outward-facing UV sphere with about `target_tris` triangles.

    k latitude bands and 2k longitudes give 4k(k-1) triangles. Returns (vertices float64
    (V,3), faces int64 (F,3), q).
    """
    k = max(3, int(round((1.0 + math.sqrt(1.0 + target_tris)) / 2.0)))
    nu = 2 * k
    theta = np.pi * np.arange(1, k) / k  # ring polar angles, k-1 rings
    phi = 2.0 * np.pi * np.arange(nu) / nu
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    ring = np.stack(
        [st * np.cos(phi)[None, :], st * np.sin(phi)[None, :], np.broadcast_to(ct, (k - 1, nu))],
        axis=-1,
    ).reshape(-1, 3)
    verts = np.concatenate([[[0.0, 0.0, 1.0]], ring, [[0.0, 0.0, -1.0]]]) * radius
    verts = verts + np.asarray(center, dtype=np.float64)
    north, south = 0, 1 + (k - 1) * nu

    def idx(i, j):  # ring i in [0, k-2], longitude j (wrapped)
        return 1 + i * nu + (j % nu)

    j = np.arange(nu)
    top = np.stack([np.full(nu, north), idx(0, j), idx(0, j + 1)], axis=1)
    i = np.arange(k - 2)[:, None]
    a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
    band = np.concatenate(
        [np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)]
    )
    bottom = np.stack([np.full(nu, south), idx(k - 2, j + 1), idx(k - 2, j)], axis=1)
    faces = np.concatenate([top, band, bottom]).astype(np.int64)
    return _snap(verts, q), faces, q


def torus(target_tris: int, major=100.0, minor=40.0, q=10):
    """A closed, outward-facing torus: n x 2n grid, 4n^2 triangles."""
    n = max(3, int(round(math.sqrt(target_tris / 4.0))))
    nu, nv = 2 * n, n  # around the axis, around the tube
    u = 2.0 * np.pi * np.arange(nu) / nu
    w = 2.0 * np.pi * np.arange(nv) / nv
    cu, su = np.cos(u)[:, None], np.sin(u)[:, None]
    cw, sw = np.cos(w)[None, :], np.sin(w)[None, :]
    r = major + minor * cw
    verts = np.stack([r * cu, r * su, np.broadcast_to(minor * sw, (nu, nv))], -1).reshape(-1, 3)
    i, j = np.arange(nu)[:, None], np.arange(nv)[None, :]

    def idx(a, b):
        return (a % nu) * nv + (b % nv)

    p00, p10, p11, p01 = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
    faces = np.concatenate(
        [np.stack([p00, p10, p11], -1).reshape(-1, 3), np.stack([p00, p11, p01], -1).reshape(-1, 3)]
    ).astype(np.int64)
    return _snap(verts, q), faces, q


_CUBE_V = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
    dtype=np.float64,
)
_CUBE_F = np.array(
    [
        [0, 2, 1], [0, 3, 2],  # z = 0 (outward -z)
        [4, 5, 6], [4, 6, 7],  # z = 1
        [0, 1, 5], [0, 5, 4],  # y = 0
        [3, 7, 6], [3, 6, 2],  # y = 1
        [0, 4, 7], [0, 7, 3],  # x = 0
        [1, 2, 6], [1, 6, 5],  # x = 1
    ],
    dtype=np.int64,
)


def cubes(target_tris: int, seed=1, q=8):
    """Many disjoint axis-aligned boxes (12 triangles each) on a grid with spacing 2.

    Box sides are random multiples of 2**-q in [0.5, 1.5]; corners on the integer grid.
    """
    n = max(2, int(round((target_tris / 12.0) ** (1.0 / 3.0))))
    rng = np.random.default_rng(seed)
    g = np.stack(np.meshgrid(*(np.arange(n),) * 3, indexing="ij"), -1).reshape(-1, 3) * 2.0
    sides = np.round(rng.uniform(0.5, 1.5, size=(len(g), 3)) * 2**q) / 2**q
    verts = (g[:, None, :] + _CUBE_V[None, :, :] * sides[:, None, :]).reshape(-1, 3)
    faces = (_CUBE_F[None, :, :] + 8 * np.arange(len(g))[:, None, None]).reshape(-1, 3)
    return _snap(verts, q), faces, q


def make(kind: str, tris: int):
    if kind == "sphere":
        return uv_sphere(tris)
    if kind == "sphere_far":  # the same sphere 1e6 away: float32 ulp there is 2**-4
        return uv_sphere(tris, center=(1e6, 1e6, 1e6), q=4)
    if kind == "sphere_shuffled":  # the same sphere, its vertices numbered in random order
        v, f, q = uv_sphere(tris)
        order = np.random.default_rng(7).permutation(len(v))
        shuffled = np.empty_like(v)
        shuffled[order] = v
        return shuffled, order[f], q
    if kind == "torus":
        return torus(tris)
    if kind == "cubes":
        return cubes(tris)
    raise ValueError(kind)


# --------------------------------------------------------------------------- writers


def face_normals(tri: np.ndarray) -> np.ndarray:
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    ln = np.linalg.norm(n, axis=1, keepdims=True)
    ln[ln == 0] = 1.0
    return n / ln


STL_DTYPE = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])
assert STL_DTYPE.itemsize == 50


def write_stl_binary(path, verts, faces, chunk=1 << 20):
    with open(path, "wb") as fh:
        fh.write(b"meshvol bench/compare test mesh".ljust(80, b" "))
        fh.write(np.uint32(len(faces)).tobytes())
        for s in range(0, len(faces), chunk):
            tri = verts[faces[s : s + chunk]]
            rec = np.zeros(len(tri), dtype=STL_DTYPE)
            rec["normal"] = face_normals(tri)
            rec["v"] = tri
            fh.write(rec.tobytes())


def _write_formatted(fh, template: str, rows: np.ndarray, chunk: int):
    """Write `template % row` for every row, formatting one chunk in one % operation."""
    for s in range(0, len(rows), chunk):
        block = rows[s : s + chunk]
        fh.write((template * len(block)) % tuple(block.ravel().tolist()))


def write_stl_ascii(path, verts, faces, q, chunk=50_000):
    c = f"%.{q}f"
    vline = f"      vertex {c} {c} {c}\n"
    template = (
        "  facet normal %.7e %.7e %.7e\n    outer loop\n" + vline * 3 + "    endloop\n  endfacet\n"
    )
    with open(path, "w") as fh:
        fh.write("solid meshvol_bench\n")
        for s in range(0, len(faces), chunk):
            tri = verts[faces[s : s + chunk]]
            rows = np.concatenate([face_normals(tri), tri.reshape(-1, 9)], axis=1)
            _write_formatted(fh, template, rows, chunk)
        fh.write("endsolid meshvol_bench\n")


def write_obj(path, verts, faces, q, chunk=200_000):
    c = f"%.{q}f"
    with open(path, "w") as fh:
        fh.write("# meshvol bench/compare test mesh\n")
        _write_formatted(fh, f"v {c} {c} {c}\n", verts, chunk)
        _write_formatted(fh, "f %d %d %d\n", faces + 1, chunk)


def write_sphere_stl_stream(path, target_tris, radius=100.0, q=10, rows_per_chunk=None):
    """The binary STL of uv_sphere(target_tris), byte for byte, written a band block at a time.

    Only the vertices (V = 2k(k-1) + 2 rows of float64, 240 MB at 20M triangles) are held
    whole; faces and corner coordinates are made per block of latitude rows (about 1M
    triangles), so a 20M-triangle file needs well under 1 GB of memory.
    """
    k = max(3, int(round((1.0 + math.sqrt(1.0 + target_tris)) / 2.0)))
    nu = 2 * k
    theta = np.pi * np.arange(1, k) / k
    phi = 2.0 * np.pi * np.arange(nu) / nu
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    ring = np.stack(
        [st * np.cos(phi)[None, :], st * np.sin(phi)[None, :], np.broadcast_to(ct, (k - 1, nu))],
        axis=-1,
    ).reshape(-1, 3)
    verts = _snap(np.concatenate([[[0.0, 0.0, 1.0]], ring, [[0.0, 0.0, -1.0]]]) * radius, q)
    del ring
    north, south = 0, 1 + (k - 1) * nu
    j = np.arange(nu)
    ntri = 4 * k * (k - 1)
    rows = rows_per_chunk or max(1, (1 << 20) // nu)

    def idx(i, jj):
        return 1 + i * nu + (jj % nu)

    def emit(fh, faces):
        tri = verts[faces]
        rec = np.zeros(len(tri), dtype=STL_DTYPE)
        rec["normal"] = face_normals(tri)
        rec["v"] = tri
        fh.write(rec.tobytes())

    with open(path, "wb") as fh:
        fh.write(b"meshvol bench/compare test mesh".ljust(80, b" "))
        fh.write(np.uint32(ntri).tobytes())
        emit(fh, np.stack([np.full(nu, north), idx(0, j), idx(0, j + 1)], axis=1))
        for second in (False, True):  # uv_sphere's order: every (a, b, c), then every (a, c, d)
            for i0 in range(0, k - 2, rows):
                i = np.arange(i0, min(k - 2, i0 + rows))[:, None]
                a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
                emit(fh, np.stack([a, c, d] if second else [a, b, c], -1).reshape(-1, 3))
        emit(fh, np.stack([np.full(nu, south), idx(k - 2, j + 1), idx(k - 2, j)], axis=1))
    return ntri


PLY_FACE_DTYPE = np.dtype([("n", "u1"), ("v", "<i4", (3,))])
assert PLY_FACE_DTYPE.itemsize == 13


def write_ply_binary(path, verts, faces, chunk=1 << 20):
    """Little-endian binary PLY: float32 x y z, `property list uchar int vertex_indices`.

    The coordinates are snapped to at most 24 significant bits, so float32 holds them
    exactly: the PLY holds the very same numbers as the STL, ASCII STL and OBJ files.
    """
    header = (
        "ply\nformat binary_little_endian 1.0\ncomment meshvol bench/compare test mesh\n"
        f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    if len(verts) >= 2**31:
        raise ValueError("too many vertices for int indices")
    with open(path, "wb") as fh:
        fh.write(header.encode("ascii"))
        for s in range(0, len(verts), chunk):
            fh.write(np.ascontiguousarray(verts[s : s + chunk], dtype="<f4").tobytes())
        for s in range(0, len(faces), chunk):
            rec = np.empty(len(faces[s : s + chunk]), dtype=PLY_FACE_DTYPE)
            rec["n"] = 3
            rec["v"] = faces[s : s + chunk]
            fh.write(rec.tobytes())


def read_ply_binary(path):
    """Read back what write_ply_binary writes (vertices float64, faces int64); for the self-test."""
    with open(path, "rb") as fh:
        data = fh.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    head = data[:end].decode("ascii").split("\n")
    nv = int(next(ln for ln in head if ln.startswith("element vertex")).split()[2])
    nf = int(next(ln for ln in head if ln.startswith("element face")).split()[2])
    v = np.frombuffer(data, "<f4", nv * 3, end).reshape(nv, 3).astype(np.float64)
    rec = np.frombuffer(data, PLY_FACE_DTYPE, nf, end + 12 * nv)
    assert (rec["n"] == 3).all()
    return v, rec["v"].astype(np.int64)


# --------------------------------------------------------------------------- exact volume
#
# Method. Every coordinate c has at most 26 significant bits (float32 has 24), so the
# product of two coordinates is exact in float64. Expand 6V = sum over triangles of
# det[a, b, c] into the six triple products +-a_i*b_j*c_k. For each, p = a_i*b_j is exact,
# and Dekker's two-product turns p*c_k into hi + lo exactly (no FMA needed). So 6V is
# exactly the sum of 12 float64 numbers per triangle. Sum them exactly: write each as
# m * 2**E with m a 53-bit integer (np.frexp), split m = mh * 2**26 + ml, and add the
# mh and the ml of each exponent E separately with np.bincount. Every partial sum is an
# integer of magnitude < (12 * chunk) * 2**27 < 2**53, so float64 adds it exactly. The
# per-exponent totals (a few hundred) are combined in Python ints into a Fraction.
# Cost: about a dozen numpy passes per chunk; ~1 s per million triangles on one core.


def _two_prod(a, b):
    p = a * b
    split = 134217729.0  # 2**27 + 1
    t = split * a
    ah = t - (t - a)
    al = a - ah
    t = split * b
    bh = t - (t - b)
    bl = b - bh
    err = ((ah * bh - p) + ah * bl + al * bh) + al * bl
    return p, err


_TERMS = [  # (sign, i, j, k): sign * a_i * b_j * c_k
    (1, 0, 1, 2), (-1, 0, 2, 1), (-1, 1, 0, 2), (1, 1, 2, 0), (1, 2, 0, 1), (-1, 2, 1, 0),
]


def exact_signed_volume(verts: np.ndarray, faces: np.ndarray, chunk=1 << 20) -> Fraction:
    """The exact signed volume (a Fraction) of the mesh with these vertices and faces."""
    verts = np.asarray(verts, dtype=np.float64)
    if not np.array_equal(verts.astype(np.float32).astype(np.float64), verts):
        raise ValueError("exact_signed_volume needs float32-representable coordinates")
    if np.abs(verts).max(initial=0.0) > 1e60:
        raise ValueError("coordinates too large for the two-product method")
    assert 12 * chunk * 2**27 < 2**53
    totals: dict[int, int] = {}
    for s in range(0, len(faces), chunk):
        tri = verts[faces[s : s + chunk]]
        a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
        parts = []
        for sign, i, j, k in _TERMS:
            hi, lo = _two_prod(a[:, i] * b[:, j], c[:, k])
            if sign < 0:
                hi, lo = -hi, -lo
            parts += [hi, lo]
        x = np.concatenate(parts)
        mant, exp = np.frexp(x)
        m = (mant * 2.0**53).astype(np.int64)  # exact: |mant| < 1 has 53 bits
        e = exp.astype(np.int64) - 53
        nz = m != 0
        m, e = m[nz], e[nz]
        if len(m) == 0:
            continue
        emin = int(e.min())
        bins = e - emin
        mh = (m >> 26).astype(np.float64)  # floor division: m = mh*2**26 + ml
        ml = (m & ((1 << 26) - 1)).astype(np.float64)
        sh = np.bincount(bins, weights=mh)
        sl = np.bincount(bins, weights=ml)
        for off in np.nonzero((sh != 0) | (sl != 0))[0]:
            key = emin + int(off)
            totals[key] = totals.get(key, 0) + (int(sh[off]) << 26) + int(sl[off])
    if not totals:
        return Fraction(0)
    lo = min(totals)
    num = sum(v << (k - lo) for k, v in totals.items())
    return Fraction(num, 6) * (Fraction(2) ** lo)


def fraction_signed_volume(verts, faces) -> Fraction:
    """Slow, obviously exact version (Fractions) to check exact_signed_volume."""
    total = Fraction(0)
    for f in faces:
        a, b, c = (tuple(Fraction(float(x)) for x in verts[i]) for i in f)
        total += (
            a[0] * (b[1] * c[2] - b[2] * c[1])
            - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
        )
    return total / 6


def rel_error(value: float, exact: Fraction) -> float:
    """|value - exact| / |exact|, computed exactly, rounded at the end."""
    if value is None or not math.isfinite(value):
        return float("nan")
    if exact == 0:
        return abs(value)
    return float(abs(Fraction(value) - exact) / abs(exact))


def selftest(verbose=True):
    rng = np.random.default_rng(7)
    cases = []
    for scale, offset in [(1.0, 0.0), (1e-20, 0.0), (1e3, 1e6), (1.0, 1e30)]:
        v = (rng.standard_normal((40, 3)) * scale + offset).astype(np.float32).astype(np.float64)
        f = rng.integers(0, 40, size=(300, 3))
        cases.append((v, f))
    for kind in ("sphere", "sphere_far", "torus", "cubes"):
        v, f, _ = make(kind, 2000)
        cases.append((v, f))
    for v, f in cases:
        fast = exact_signed_volume(v, f, chunk=97)  # small chunks exercise the merging
        slow = fraction_signed_volume(v, f)
        assert fast == slow, (fast, slow)
    for kind in ("sphere", "torus", "cubes"):
        v, f, _ = make(kind, 2000)
        assert exact_signed_volume(v, f) > 0, f"{kind} is not outward-facing"
    import os
    import tempfile

    v, f, _ = make("torus", 2000)
    with tempfile.TemporaryDirectory() as td:
        path = os.path.join(td, "t.ply")
        write_ply_binary(path, v, f, chunk=333)
        v2, f2 = read_ply_binary(path)
        assert np.array_equal(v, v2) and np.array_equal(f, f2), "PLY round trip"
        v, f, _ = make("sphere", 5000)
        a, b = os.path.join(td, "a.stl"), os.path.join(td, "b.stl")
        write_stl_binary(a, v, f)
        assert write_sphere_stl_stream(b, 5000, rows_per_chunk=7) == len(f)
        assert open(a, "rb").read() == open(b, "rb").read(), "streamed sphere STL differs"
    if verbose:
        print(f"meshgen selftest: {len(cases)} exact-volume cases agree with Fractions")


if __name__ == "__main__":
    selftest()
