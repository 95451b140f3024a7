"""The same answers through the Python API whatever the arrays' order or the solid's pose
(issue 26): faces shuffled, each face started at another corner, vertices renumbered,
a signed axis permutation (a mirror with its faces reversed), a translation by 2**k and
a scaling by 2**k. Answers move and scale as they must: volumes s**3, areas s**2,
centroids with the solid, grid cells with the grid, profiles along the moved axis (read
from the top where it is flipped). Every expected value is a closed form or the
untransformed call; the kernels' own suite is crates/meshvol/tests/invariance, the
table docs/invariance.md."""

import itertools

import numpy as np
import pytest

import meshvol
from solids import BOX_QUADS, box_vertices, uv_sphere

REL = 1e-9  # issue 26's bound


def near(got, want, scale):
    assert abs(got - want) <= REL * abs(scale), f"{got} against {want} (allowed {REL * abs(scale):g})"


def snapped(vertices):
    """Coordinates rounded to multiples of 2**-24, so that the transforms are exact."""
    return np.round(np.asarray(vertices, dtype=float) * 2.0**24) / 2.0**24


def cavity_box():
    """A 2 x 2 x 2 box with a 1 x 1 x 1 cavity wound inward: volume 7, section 3."""
    outer = box_vertices((0, 0, 0), (2, 2, 2))
    inner = box_vertices((0.5, 0.5, 0.5), (1.5, 1.5, 1.5))
    faces = [[int(v) for v in q] for q in BOX_QUADS] + [[int(v) + 8 for v in q[::-1]] for q in BOX_QUADS]
    return np.vstack([outer, inner]), faces, 7.0


def l_prism():
    """An L (area 3) from z = -0.5 to 1: volume 4.5, planar polygon faces."""
    ring = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
    vertices = np.array([(x, y, -0.5) for x, y in ring] + [(x, y, 1.0) for x, y in ring], dtype=float)
    n = len(ring)
    faces = [[0] + list(range(n - 1, 0, -1)), list(range(n, 2 * n))]
    faces += [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    return vertices, faces, 4.5


def sphere():
    vertices, faces = uv_sphere(radius=1.25, rings=8, segments=12, centre=(0.25, -0.5, 0.125))
    return snapped(vertices), [[int(v) for v in f] for f in faces], None


SOLIDS = {"cavity box": cavity_box, "L prism": l_prism, "sphere": sphere}

# (seed, axes, signs, scale, shift): new axis a = signs[a] * scale * old axis axes[a] + shift[a].
TRANSFORMS = [
    (0, (0, 1, 2), (1, 1, 1), 1.0, (0.0, 0.0, 0.0)),
    (1, (1, 0, 2), (1, 1, 1), 1.0, (0.0, 0.0, 0.0)),
    (2, (1, 2, 0), (1, -1, 1), 2.0, (1024.0, 0.0, -64.0)),
    (3, (2, 1, 0), (-1, -1, -1), 0.5, (0.0, 4096.0, 0.25)),
]


class Moved:
    """A transform and what it does to points, directions, meshes and grids."""

    def __init__(self, seed, axes, signs, scale, shift):
        self.seed, self.axes, self.signs = seed, list(axes), np.array(signs, dtype=float)
        self.scale, self.shift = scale, np.array(shift)
        odd = sum(1 for i, j in itertools.combinations(range(3), 2) if axes[i] > axes[j]) % 2
        self.mirror = (odd + int(np.sum(self.signs < 0))) % 2 == 1

    def point(self, p):
        p = np.asarray(p, dtype=float)
        return self.signs * self.scale * p[..., self.axes] + self.shift

    def direction(self, v):
        return self.signs * np.asarray(v, dtype=float)[self.axes]

    def mesh(self, vertices, faces):
        rng = np.random.default_rng(self.seed)
        n = len(vertices)
        new = rng.permutation(n) if self.seed else np.arange(n)
        moved = np.empty((n, 3))
        moved[new] = self.point(vertices)
        out = []
        for f in faces:
            f = [int(new[v]) for v in f]
            if self.seed:
                k = int(rng.integers(len(f)))
                f = f[k:] + f[:k]
            if self.mirror:
                f = f[::-1]
            out.append(f)
        if self.seed:
            out = [out[i] for i in rng.permutation(len(out))]
        return meshvol.Mesh(moved, out)

    def new_axis(self, b):
        return self.axes.index(b)

    def bounds(self, lo, hi):
        lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
        a, b = self.point(lo), self.point(hi)
        return np.minimum(a, b), np.maximum(a, b)

    def cells(self, values):
        """Cell values of a grid, as the moved grid holds them."""
        moved = np.transpose(values, self.axes)
        flips = [a for a in range(3) if self.signs[a] < 0]
        return self.scale**3 * (np.flip(moved, flips) if flips else moved)


CASES = [(name, t) for name in SOLIDS for t in TRANSFORMS]


def ids(case):
    name, (seed, axes, signs, scale, shift) = case
    return f"{name}-{seed}-{''.join(map(str, axes))}-{scale}"


@pytest.fixture(params=CASES, ids=[ids(c) for c in CASES])
def pair(request):
    name, args = request.param
    vertices, faces, volume = SOLIDS[name]()
    t = Moved(*args)
    return name, meshvol.Mesh(vertices, faces), t.mesh(vertices, faces), t, volume, vertices


FACTS = [
    "bounds_a_volume", "closed", "welded_vertices", "edges", "boundary_edges", "boundary_loops",
    "non_manifold_edges", "non_manifold_vertices", "degenerate_faces", "flat_faces",
    "duplicate_faces", "double_wall_faces", "consistently_oriented", "orientation", "winding",
    "shells", "cavities", "self_intersections", "euler_characteristic",
]


def test_mass_properties_and_check(pair):
    name, before, after, t, volume, _ = pair
    s = t.scale
    m0, m1 = before.mass_properties(), after.mass_properties()
    v = m0.volume if volume is None else volume
    near(m0.volume, v, v)
    near(m1.volume, s**3 * v, s**3 * v)
    near(m1.area, s**2 * m0.area, s**2 * m0.area)
    reach = 4 * s + np.max(np.abs(t.shift))
    for got, want in zip(m1.centroid, t.point(m0.centroid)):
        near(got, want, reach)
    turned = s**5 * np.outer(t.signs, t.signs) * m0.inertia[np.ix_(t.axes, t.axes)]
    for got, want in zip(m1.inertia.ravel(), turned.ravel()):
        near(got, want, np.max(np.abs(turned)))
    c0, c1 = before.check(), after.check()
    assert [getattr(c1, k) for k in FACTS] == [getattr(c0, k) for k in FACTS]
    assert c1.verdict == c0.verdict
    near(c1.solid_volume, s**3 * c0.solid_volume, s**3 * v)


def test_grid_cells_move_with_the_grid(pair):
    name, before, after, t, volume, vertices = pair
    v = before.mass_properties().volume
    lo, hi = vertices.min(axis=0) - 0.25, vertices.max(axis=0) + 0.5
    counts = (3, 4, 5)
    g0 = before.grid(cells=counts, bounds=(lo, hi))
    g1 = after.grid(cells=tuple(counts[b] for b in t.axes), bounds=t.bounds(lo, hi))
    near(g0.sum(), v, v)
    want = t.cells(g0)
    assert g1.shape == want.shape
    np.testing.assert_allclose(g1, want, rtol=0, atol=REL * t.scale**3 * v)


def test_profiles_move_with_the_axis(pair):
    name, before, after, t, volume, _ = pair
    s3 = t.scale**3
    v = before.mass_properties().volume
    for b in range(3):
        a = t.new_axis(b)
        p0 = before.profile(axis="xyz"[b], levels=4)
        p1 = after.profile(axis="xyz"[a], levels=4)
        near(p0.volume_below[-1], v, v)
        if t.signs[a] < 0:
            want = s3 * (v - p0.volume_below[::-1])
        else:
            want = s3 * p0.volume_below
        np.testing.assert_allclose(p1.volume_below, want, rtol=0, atol=REL * s3 * v)


@pytest.mark.parametrize("normal", [(0.0, 0.0, 1.0), (0.48, -0.6, 0.64)])
def test_below_moves_with_the_plane(pair, normal):
    name, before, after, t, volume, vertices = pair
    s = t.scale
    m0 = before.mass_properties()
    v = m0.volume
    o = 0.4 * vertices.min(axis=0) + 0.6 * vertices.max(axis=0) + 1.0 / 64
    d = float(np.dot(normal, o))
    n1 = t.direction(normal)
    d1 = float(np.dot(n1, t.point(o)))
    b0 = before.below(plane=(*normal, d))
    b1 = after.below(plane=(*n1, d1))
    near(b1.volume, s**3 * b0.volume, s**3 * v)
    near(b1.wetted_area, s**2 * b0.wetted_area, s**2 * m0.area)
    # Sections of a non-convex face fanned from a corner that does not see all of it are
    # a known bug (see the kernels' suite), so the L's waterplane is compared unrotated.
    if name != "L prism" or t.seed == 0:
        near(b1.section_area, s**2 * b0.section_area, s**2 * m0.area)
    # The part below and the part above make the whole.
    up = after.below(plane=(*(-n1), -d1))
    near(b1.volume + up.volume, s**3 * v, s**3 * v)
    # The level holding 30% of the volume moves with the solid.
    level0 = before.below(volume=0.3 * v, direction=normal).level
    level1 = after.below(volume=0.3 * s**3 * v, direction=tuple(n1)).level
    near(level1, s * level0 + float(np.dot(n1, t.shift)), 4 * s)


def test_union_holds_the_volume(pair):
    name, before, after, t, volume, _ = pair
    v = before.mass_properties().volume
    for mesh, want in [(before, v), (after, t.scale**3 * v)]:
        u = meshvol.union(mesh)
        assert u.lower - REL * want <= want <= u.upper + REL * want


def test_intersection_with_itself_holds_the_volume(pair):
    # A∩A = A, the solid moved as arrays (any transform of the suite) or by one rigid
    # pose on both (a quarter turn about z, then a shift).
    name, before, after, t, volume, _ = pair
    v = before.mass_properties().volume
    pose = np.array([[0.0, -1, 0, 3.5], [1, 0, 0, -2.25], [0, 0, 1, 0.5], [0, 0, 0, 1]])
    for mesh, want in [(before, v), (after, t.scale**3 * v)]:
        for p in (None, pose):
            i = meshvol.intersection(mesh, mesh, pose_a=p, pose_b=p)
            assert i.lower - REL * want <= want <= i.upper + REL * want, (name, p is None)


def test_hull_of_points_moves_with_them():
    vertices, _, _ = sphere()
    points = np.vstack([vertices, vertices.mean(axis=0), vertices[:5]])
    h0 = meshvol.convex_hull(points)
    for args in TRANSFORMS:
        t = Moved(*args)
        order = np.random.default_rng(args[0]).permutation(len(points))
        h1 = meshvol.convex_hull(t.point(points)[order])
        s = t.scale
        near(h1.volume, s**3 * h0.volume, s**3 * h0.volume)
        near(meshvol.hull_volume(t.point(points)), s**3 * h0.volume, s**3 * h0.volume)
        near(h1.area, s**2 * h0.area, s**2 * h0.area)
        assert h1.hull_vertices == h0.hull_vertices
    # The box's corners with points inside: the box.
    corners = np.vstack([box_vertices((0, 0, 0), (2.0, 0.5, 1.5)), [[1.0, 0.25, 0.75]]])
    near(meshvol.hull_volume(corners), 1.5, 1.5)


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("swap", [False, True])
def test_polygon_area_moves_with_the_polygon(seed, swap):
    """An L (area 12) with a square hole (1): rings started anywhere, wound either way,
    swapped, flipped, far and scaled."""
    exterior = np.array([(0, 0), (4, 0), (4, 2), (2, 2), (2, 4), (0, 4)], dtype=float)
    hole = np.array([(0.5, 0.5), (0.5, 1.5), (1.5, 1.5), (1.5, 0.5)])
    p0 = meshvol.polygon_area(exterior, [hole])
    near(p0.area, 11.0, 11.0)
    rng = np.random.default_rng(seed)
    signs = np.array([1.0, -1.0]) if seed else np.ones(2)
    s, shift = 2.0**seed, np.array([2.0**20, -(2.0**18)]) if seed else np.zeros(2)

    def move(ring):
        ring = ring[:, ::-1] if swap else ring
        ring = signs * s * ring + shift
        ring = np.roll(ring, int(rng.integers(len(ring))), axis=0)
        return ring[::-1] if rng.integers(2) else ring

    p1 = meshvol.polygon_area(move(exterior), [move(hole)])
    near(p1.area, s**2 * p0.area, s**2 * p0.area)
    near(p1.perimeter, s * p0.perimeter, s * p0.perimeter)
    c = p0.centroid[::-1] if swap else p0.centroid
    for got, want in zip(p1.centroid, signs * s * c + shift):
        near(got, want, 4 * s + np.max(np.abs(shift)))
    ix, iy = (p0.iy, p0.ix) if swap else (p0.ix, p0.iy)
    near(p1.ix, s**4 * ix, s**4 * p0.polar)
    near(p1.iy, s**4 * iy, s**4 * p0.polar)
    near(p1.ixy, signs[0] * signs[1] * s**4 * p0.ixy, s**4 * p0.polar)


def terrain(seed):
    """A 4 x 3 grid of cells (pitch 0.5, footprint 3), heights from 1 to 2 in steps of 1/64."""
    rng = np.random.default_rng(26)
    nx, ny = 4, 3
    vertices = np.array(
        [[i * 0.5, j * 0.5, 1.0 + rng.integers(65) / 64.0] for i in range(nx + 1) for j in range(ny + 1)]
    )
    at = lambda i, j: i * (ny + 1) + j
    faces = []
    for i in range(nx):
        for j in range(ny):
            a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
            faces += [[a, b, c], [a, c, d]] if (i + j) % 2 else [[a, b, d], [b, c, d]]
    return vertices, faces


@pytest.mark.parametrize("args", TRANSFORMS[:3])
def test_cutfill_moves_with_the_terrain(args):
    seed, axes, signs, scale, shift = args
    # In plan only: x and y permuted, z kept up.
    t = Moved(seed, (axes[0] % 2, 1 - axes[0] % 2, 2), (signs[0], signs[1], 1), scale, shift)
    vertices, faces = terrain(seed)
    level = 1.5
    r0 = meshvol.cutfill(meshvol.Mesh(vertices, faces), level=level)
    r1 = meshvol.cutfill(t.mesh(vertices, faces), level=scale * level + shift[2])
    v = r0.cut + r0.fill
    near(r1.cut, scale**3 * r0.cut, scale**3 * v)
    near(r1.fill, scale**3 * r0.fill, scale**3 * v)
    near(r1.area_cut, scale**2 * r0.area_cut, scale**2 * r0.footprint_area)
    near(r1.footprint_area, scale**2 * 3.0, scale**2 * 3.0)
