"""Mesh.grid, Mesh.profile and meshvol.union against volumes known in closed form."""

import numpy as np
import pytest

import meshvol
from solids import BOX_TRIANGLES, box, box_vertices, sphere_volume, uv_sphere


def test_box_on_unit_cells():
    # A 1.5 x 1 x 1 box on two unit cells: one full, one half.
    cells = meshvol.Mesh(*box((0, 0, 0), (1.5, 1, 1))).grid(cells=(2, 1, 1), bounds=((0, 0, 0), (2, 1, 1)))
    assert cells.shape == (2, 1, 1) and cells.dtype == np.float64
    assert cells.ravel().tolist() == [1.0, 0.5]


def test_offset_box_cells_are_exact_overlaps():
    lo, hi = np.array([0.3, 0.1, 0.45]), np.array([2.7, 1.9, 1.2])
    grid_lo, grid_hi, counts = np.zeros(3), np.array([3.0, 2.0, 1.5]), np.array([6, 4, 3])
    cells = meshvol.Mesh(*box(lo, hi)).grid(cells=tuple(counts), bounds=(grid_lo, grid_hi))
    # Each cell's volume is the overlap of two boxes: a product of interval overlaps.
    edges = [np.linspace(grid_lo[a], grid_hi[a], counts[a] + 1) for a in range(3)]
    overlap = [np.clip(np.minimum(e[1:], hi[a]) - np.maximum(e[:-1], lo[a]), 0, None) for a, e in enumerate(edges)]
    expected = np.einsum("i,j,k->ijk", *overlap)
    np.testing.assert_allclose(cells, expected, rtol=0, atol=1e-15)


def test_sphere_cells_sum_to_its_volume():
    mesh = meshvol.Mesh(*uv_sphere(radius=1.0, rings=24, segments=48))
    volume = mesh.mass_properties().volume
    cells = mesh.grid(cells=(7, 8, 9))
    assert cells.sum() == pytest.approx(volume, rel=1e-13)
    size = 2.0 / np.array([7, 8, 9])
    cell_volume = np.prod(size)
    assert cells.min() >= -1e-15 and cells.max() <= cell_volume * (1 + 1e-12)
    fractions = mesh.grid(cells=(7, 8, 9), fraction=True)
    np.testing.assert_allclose(fractions, cells / cell_volume, rtol=1e-15)


def test_pitch_covers_the_bounds():
    cells = meshvol.Mesh(*box((0, 0, 0), (1, 0.3, 0.5))).grid(pitch=0.25)
    assert cells.shape == (4, 2, 2)
    assert cells.sum() == pytest.approx(0.15, rel=1e-14)
    assert meshvol.Mesh(*box()).grid(pitch=(0.5, 1.0, 0.25)).shape == (2, 1, 4)


def test_flat_mesh_needs_bounds():
    flat = meshvol.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float), [[0, 1, 2]])
    with pytest.raises(meshvol.MeshError, match="the mesh is flat: give bounds$"):
        flat.grid(cells=(2, 2, 2))


def test_profile_of_a_box():
    p = meshvol.Mesh(*box((0, 0, 0), (2, 3, 4))).profile(levels=4)
    assert p.axis == "z"
    assert p.levels.tolist() == [0, 1, 2, 3, 4]
    assert p.volume_below.tolist() == [0, 6, 12, 18, 24]
    assert p.slab_volume.tolist() == [6] * 4
    assert p.section_area.tolist() == [6] * 5
    along_x = meshvol.Mesh(*box((0, 0, 0), (2, 3, 4))).profile(axis="x", step=0.5)
    assert along_x.levels.tolist() == [0, 0.5, 1, 1.5, 2]
    assert along_x.volume_below[-1] == 24.0 and along_x.section_area.tolist() == [12] * 5


def test_profile_of_a_sphere_follows_the_cap_volume():
    radius = 1.5
    mesh = meshvol.Mesh(*uv_sphere(radius=radius, rings=96, segments=192))
    p = mesh.profile(levels=12)
    h = p.levels - p.levels[0]
    cap = np.pi * h**2 * (3 * radius - h) / 3  # the volume of a spherical cap of height h
    np.testing.assert_allclose(p.volume_below, cap, rtol=0, atol=2e-3 * sphere_volume(radius))
    assert p.volume_below[-1] == pytest.approx(mesh.mass_properties().volume, rel=1e-13)
    assert np.all(np.diff(p.volume_below) > 0)


def test_union_of_two_overlapping_boxes():
    a, b = meshvol.Mesh(*box((0, 0, 0), (2, 2, 2))), meshvol.Mesh(*box((1, 1, 1), (3, 3, 3)))
    u = meshvol.union([a, b], tolerance=1e-9)
    assert u.lower <= 15.0 <= u.upper and u.upper - u.lower < 1e-8
    assert u.volume == pytest.approx(15.0, rel=1e-12)
    assert (u.bodies, u.sum_of_volumes, u.flipped) == (2, 16.0, [])
    assert u.certified and u.uncertified_reason is None


def test_union_of_the_shells_of_one_mesh():
    v = np.vstack([box_vertices((0, 0, 0), (2, 2, 2)), box_vertices((1, 0.5, 0.25), (3, 2.5, 2.25))])
    f = np.vstack([BOX_TRIANGLES, BOX_TRIANGLES[:, ::-1] + 8])  # the second wound inward
    overlap = 1.0 * 1.5 * 1.75
    # Checked (the default), the inward shell is a solid turned outward, and said so.
    with pytest.warns(meshvol.MeshWarning, match="wound against its role"):
        u = meshvol.union(meshvol.Mesh(v, f))
    assert u.lower <= 16.0 - overlap <= u.upper
    assert u.upper - u.lower <= 1e-6 * u.lower
    assert u.bodies == 2 and u.flipped == [] and u.volume_uncertainty == 0.0
    assert any("role" in w for w in u.warnings)
    # As wound, the union turns it itself, and says so as the command does.
    with pytest.warns(meshvol.MeshWarning, match="shell 1: wound inward"):
        u = meshvol.union(meshvol.Mesh(v, f), check=False)
    assert u.lower <= 16.0 - overlap <= u.upper
    assert u.bodies == 2 and u.flipped == [1]
    # Unchecked, the bodies are not known to be closed solids: not certified, and why.
    assert not u.certified and "unchecked" in u.uncertified_reason
    assert len(u.warnings) == 1 and "measured as a solid turned outward" in u.warnings[0]


def test_union_accepts_mesh_like_objects():
    class MeshLike:
        def __init__(self, vertices, faces):
            self.vertices, self.faces = vertices, faces

    bodies = [MeshLike(*box((0, 0, 0), (1, 1, 1))), MeshLike(*box((0.5, 0, 0), (1.5, 1, 1)))]
    u = meshvol.union(bodies)
    assert u.lower <= 1.5 <= u.upper


def test_a_region_is_the_same_bits_as_the_whole_grid():
    mesh = meshvol.Mesh(*uv_sphere(radius=1.0, rings=24, segments=48))
    whole = mesh.grid(cells=(9, 8, 11))
    rng = np.random.default_rng(18)
    for _ in range(20):
        region = []
        for n in (9, 8, 11):
            start = int(rng.integers(0, n))
            region.append((start, int(rng.integers(start + 1, n + 1))))
        block = mesh.grid(cells=(9, 8, 11), region=region)
        expected = whole[tuple(slice(a, b) for a, b in region)]
        assert block.shape == expected.shape
        assert np.array_equal(block.view(np.uint64), expected.view(np.uint64)), region


def test_bad_regions_are_refused():
    mesh = meshvol.Mesh(*box())
    with pytest.raises(meshvol.MeshError, match="the region is empty along y"):
        mesh.grid(cells=(4, 4, 4), region=((0, 4), (2, 2), (0, 4)))
    with pytest.raises(meshvol.MeshError, match="beyond the grid's 4 cells"):
        mesh.grid(cells=(4, 4, 4), region=((0, 4), (0, 4), (1, 5)))
    with pytest.raises(ValueError, match="cell indices ≥ 0"):
        mesh.grid(cells=(4, 4, 4), region=((-1, 4), (0, 4), (0, 4)))
