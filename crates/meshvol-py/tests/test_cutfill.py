"""meshvol.cutfill against closed forms: planes against planes and levels, per-cell
arrays that add up to the totals, and the errors of wrong arguments and folded sheets."""

import numpy as np
import pytest

import meshvol


def square(z, n=1, flip=False):
    """The unit square in n × n quads at heights z(x, y), as a Mesh."""
    xs = np.linspace(0.0, 1.0, n + 1)
    vertices = np.array([[x, y, z(x, y)] for x in xs for y in xs])
    at = lambda i, j: i * (n + 1) + j
    faces = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
            faces += [[a, b, d], [b, c, d]] if flip else [[a, b, c], [a, c, d]]
    return meshvol.Mesh(vertices, np.array(faces))


def test_a_flat_surface_against_a_ramp():
    # z = 1 against z = x: cut is the integral of 1 - x over the unit square, 1/2.
    r = meshvol.cutfill(square(lambda x, y: 1.0), design=square(lambda x, y: x, 3, True))
    assert r.cut == pytest.approx(0.5, abs=1e-15) and r.fill == 0.0
    assert r.area_cut == pytest.approx(1.0, abs=1e-15) and r.net == r.cut
    assert r.design == "mesh" and r.level is None and r.cut_cells is None
    assert set(r.to_dict()) >= {"cut", "fill", "net", "area_cut", "area_fill", "footprint_area"}


def test_a_ramp_against_a_level_in_cells(tmp_path):
    # z = x against z = 1/2: 1/8 of cut and 1/8 of fill; cell i of 4 along x holds the
    # integral of (x - 1/2) over its quarter, on its side of 1/2.
    r = meshvol.cutfill(square(lambda x, y: x, 2), level=0.5, cells=(4, 1))
    assert r.cut == pytest.approx(0.125, abs=1e-15) and r.fill == pytest.approx(0.125, abs=1e-15)
    part = lambda a, b: (b * b - a * a) / 2 - 0.5 * (b - a)
    assert r.cut_cells.shape == (4, 1)
    np.testing.assert_allclose(
        r.cut_cells[:, 0], [0, 0, part(0.5, 0.75), part(0.75, 1.0)], atol=1e-15
    )
    np.testing.assert_allclose(
        r.fill_cells[:, 0], [-part(0, 0.25), -part(0.25, 0.5), 0, 0], atol=1e-15
    )
    assert r.grid == {"counts": [4, 1], "origin": [0.0, 0.0], "cell": [0.25, 1.0]}
    by_pitch = meshvol.cutfill(square(lambda x, y: x, 2), level=0.5, pitch=0.3)
    assert by_pitch.cut_cells.shape == (4, 4)
    assert by_pitch.cut_cells.sum() == pytest.approx(by_pitch.cut, abs=1e-15)


def test_wrong_arguments():
    flat = square(lambda x, y: 1.0)
    for kwargs in [{}, {"design": flat, "level": 1.0}]:
        with pytest.raises(ValueError, match="design=SURFACE or level=Z"):
            meshvol.cutfill(flat, **kwargs)
    with pytest.raises(ValueError, match="cells"):
        meshvol.cutfill(flat, level=1.0, cells=(0, 2))
    with pytest.raises(ValueError, match="not both"):
        meshvol.cutfill(flat, level=1.0, cells=(2, 2), pitch=0.5)
    with pytest.raises(ValueError, match="pitch"):
        meshvol.cutfill(flat, level=1.0, pitch=-1.0)
    with pytest.raises(meshvol.ReadError):
        meshvol.cutfill("no/such/terrain.obj", level=1.0)


def test_a_folded_sheet_is_refused():
    vertices = np.array(
        [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0, 1], [0.5, 1, 1]], float
    )
    folded = meshvol.Mesh(vertices, np.array([[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]]))
    with pytest.raises(meshvol.MeshError, match="faces 0 and 2 overlap in plan"):
        meshvol.cutfill(folded, level=0.0)
