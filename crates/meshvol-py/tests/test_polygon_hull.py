"""meshvol.polygon_area and meshvol.convex_hull against closed forms."""

import numpy as np
import pytest

import meshvol

ORIGIN = np.array([5.0e6, 1.0e7])  # survey coordinates: far from 0


def rectangle(x0, y0, x1, y1):
    return ORIGIN + np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)


def test_rectangle_with_a_hole_far_from_the_origin():
    outline, hole = rectangle(0, 0, 4, 2), rectangle(1, 0.5, 2, 1.5)
    p = meshvol.polygon_area(outline, [hole])
    assert p.area == 7.0 and p.perimeter == 16.0
    # Centroid: (8·2 − 1·1.5) / 7 along x, 1 along y.
    np.testing.assert_allclose(p.centroid, ORIGIN + [14.5 / 7, 1.0], rtol=0, atol=1e-9)
    # ix about the centroid's x axis: 4·2³/12 − 1·1³/12 (both centred on y = 1).
    assert p.ix == pytest.approx(32 / 12 - 1 / 12, rel=1e-13)
    # iy: each rectangle about its own centre, moved to the centroid (parallel axes).
    cx = 14.5 / 7
    iy = (2 * 4**3 / 12 + 8 * (2 - cx) ** 2) - (1 / 12 + 1 * (1.5 - cx) ** 2)
    assert p.iy == pytest.approx(iy, rel=1e-13)
    assert p.polar == pytest.approx(p.ix + p.iy, rel=1e-15)
    assert p.issues == []
    # The hole's winding does not matter; a closing copy of the first point is dropped.
    closed = np.vstack([outline, outline[:1]])
    assert meshvol.polygon_area(closed, [hole[::-1]]).area == 7.0


def test_geojson_and_geo_interface():
    outline, hole = rectangle(0, 0, 4, 2), rectangle(1, 0.5, 2, 1.5)
    geometry = {"type": "Polygon", "coordinates": [outline.tolist(), hole.tolist()]}
    assert meshvol.polygon_area(geometry).area == 7.0

    class Shape:  # as shapely's geometries are
        __geo_interface__ = {
            "type": "MultiPolygon",
            "coordinates": [
                [outline.tolist(), hole.tolist()],
                [[[x, y, 9.0] for x, y in rectangle(10, 0, 11, 1).tolist()]],  # z ignored
            ],
        }

    assert meshvol.polygon_area(Shape()).area == 8.0


def test_principal_moments_of_a_turned_rectangle():
    angle = np.radians(30)
    turn = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    corners = np.array([[-1, -0.5], [1, -0.5], [1, 0.5], [-1, 0.5]]) @ turn.T
    p = meshvol.polygon_area(corners)
    # A 2 x 1 rectangle: b h³ / 12 about its long axis, h b³ / 12 about its short one.
    # Ascending, as in 3D; principal_angle_degrees is the larger one's axis.
    np.testing.assert_allclose(p.principal_moments, [1 / 6, 2 / 3], rtol=1e-13)
    assert p.principal_angle_degrees == pytest.approx(120.0, abs=1e-9)


def test_bowtie_is_reported():
    p = meshvol.polygon_area([[0, 0], [1, 1], [1, 0], [0, 1]])
    assert any("intersects itself" in issue for issue in p.issues)


def test_hull_of_a_cube_with_inner_points():
    rng = np.random.default_rng(5)
    corners = np.array([[x, y, z] for x in (0, 2) for y in (0, 3) for z in (0, 1)], float) + 1e6
    points = np.vstack([corners, 1e6 + rng.random((500, 3)) * [2, 3, 1]])
    hull = meshvol.convex_hull(points)
    assert hull.volume == 6.0 and hull.area == 2 * (6 + 2 + 3)
    np.testing.assert_allclose(hull.centroid, 1e6 + np.array([1, 1.5, 0.5]), rtol=0, atol=1e-9)
    assert (hull.points, hull.hull_vertices, hull.degenerate) == (508, 8, None)
    assert hull.mesh.check().bounds_a_volume
    assert hull.mesh.mass_properties().volume == 6.0
    assert meshvol.hull_volume(points) == 6.0


def test_hull_of_points_on_a_sphere_approaches_the_ball():
    rng = np.random.default_rng(2)
    directions = rng.normal(size=(20000, 3))
    points = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    volume = meshvol.hull_volume(points)
    assert 0.99 * 4 / 3 * np.pi < volume < 4 / 3 * np.pi


@pytest.mark.parametrize(
    "points, why",
    [
        (np.zeros((0, 3)), "no points"),
        (np.ones((4, 3)), "coincident"),
        ([[0, 0, 0], [1, 1, 1], [2, 2, 2]], "collinear"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], "coplanar"),
    ],
)
def test_degenerate_hulls_have_no_volume(points, why):
    hull = meshvol.convex_hull(points)
    assert (hull.volume, hull.degenerate, hull.mesh, hull.centroid) == (0.0, why, None, None)
