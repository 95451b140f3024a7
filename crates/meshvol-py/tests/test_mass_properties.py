"""Mass properties compared with closed forms computed here, independently of meshvol."""

from fractions import Fraction

import numpy as np
import pytest

import meshvol
from solids import (
    BOX_QUADS,
    OPENSCAD_CUBE_FACES,
    OPENSCAD_CUBE_POINTS,
    TETRA_FACES,
    box,
    box_inertia,
    sphere_volume,
    uv_sphere,
)


def test_box_matches_closed_forms():
    lo, hi = (1.0, 2.0, 3.0), (3.0, 5.0, 7.0)
    size = np.subtract(hi, lo)
    mp = meshvol.Mesh(*box(lo, hi)).mass_properties(density=2.5)
    assert mp.volume == 24.0 and mp.signed_volume == 24.0
    assert mp.area == 2 * (6 + 12 + 8)
    np.testing.assert_allclose(mp.centroid, [2.0, 3.5, 5.0], rtol=0, atol=1e-14)
    np.testing.assert_allclose(mp.inertia, box_inertia(size, 2.5), rtol=1e-14, atol=1e-12)
    assert mp.mass == 2.5 * 24.0 and mp.density == 2.5
    # Principal moments ascending: about z (smallest), y, x.
    np.testing.assert_allclose(mp.principal_moments, [2.5 * 26, 2.5 * 40, 2.5 * 50], rtol=1e-14)
    np.testing.assert_allclose(np.abs(mp.principal_axes), np.eye(3)[::-1], atol=1e-12)
    assert np.isclose(np.linalg.det(mp.principal_axes), 1.0)
    assert mp.faces == 12 and mp.triangles == 12
    lo_found, hi_found = mp.bounds
    assert lo_found.tolist() == list(lo) and hi_found.tolist() == list(hi)


def test_corner_tetrahedron_matches_closed_forms():
    # The unit corner tetrahedron: V = 1/6, centroid 1/4, ∫x² dV = 1/60, ∫xy dV = 1/120,
    # so Ixx = 2/60 - V·2/16 = 1/80 and Ixy = -(1/120 - V/16) = 1/480.
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    mp = meshvol.Mesh(vertices, TETRA_FACES).mass_properties()
    assert mp.signed_volume == pytest.approx(1 / 6, rel=1e-15)
    np.testing.assert_allclose(mp.centroid, [0.25] * 3, rtol=1e-15)
    expected = np.full((3, 3), 1 / 480) + np.eye(3) * (1 / 80 - 1 / 480)
    np.testing.assert_allclose(mp.inertia, expected, rtol=1e-13)
    assert mp.area == pytest.approx(1.5 + np.sqrt(3) / 2, rel=1e-15)


def test_general_tetrahedron_matches_determinant():
    rng = np.random.default_rng(7)
    vertices = rng.normal(size=(4, 3)) * 10 + 100
    six_volume = np.linalg.det(vertices[1:] - vertices[0])
    faces = TETRA_FACES if six_volume > 0 else TETRA_FACES[:, ::-1]
    mp = meshvol.Mesh(vertices, faces).mass_properties()
    assert mp.signed_volume == pytest.approx(abs(six_volume) / 6, rel=1e-12)
    np.testing.assert_allclose(mp.centroid, vertices.mean(axis=0), rtol=1e-13)


def test_openscad_cube_has_signed_volume_minus_one():
    mesh = meshvol.Mesh(OPENSCAD_CUBE_POINTS, OPENSCAD_CUBE_FACES)
    mp = mesh.mass_properties()
    assert mp.signed_volume == -1.0
    assert mp.volume == 1.0
    np.testing.assert_allclose(mp.centroid, [0.5] * 3, atol=1e-15)
    # The inertia is the solid's whatever the winding: a unit cube's 1/6 on the diagonal.
    np.testing.assert_allclose(mp.inertia, np.eye(3) / 6, atol=1e-15)
    assert mesh.flipped().mass_properties().signed_volume == 1.0


def test_far_from_origin_box_keeps_its_digits():
    offset = np.array([1.0e7, -3.0e6, 2.5e7])
    mp = meshvol.Mesh(*box(offset, offset + [2.0, 3.0, 4.0])).mass_properties()
    assert abs(mp.signed_volume - 24.0) <= mp.volume_error_bound
    assert mp.volume_error_bound < 1e-9
    np.testing.assert_allclose(mp.centroid, offset + [1.0, 1.5, 2.0], rtol=1e-15)


def test_sphere_converges_to_four_thirds_pi_r_cubed():
    errors = []
    for rings in (16, 32, 64):
        vertices, faces = uv_sphere(radius=2.0, rings=rings, segments=2 * rings)
        mp = meshvol.Mesh(vertices, faces).mass_properties()
        errors.append(sphere_volume(2.0) - mp.volume)
        np.testing.assert_allclose(mp.centroid, [0, 0, 0], atol=1e-12)
    # An inscribed polyhedron: below the sphere, the gap shrinking as 1/n².
    assert all(e > 0 for e in errors)
    assert 3.5 < errors[0] / errors[1] < 4.5 and 3.5 < errors[1] / errors[2] < 4.5
    assert errors[2] / sphere_volume(2.0) < 2e-3


def test_quad_faces_measure_as_their_triangles():
    vertices, triangles = box((0, 0, 0), (2, 3, 4))
    by_triangles = meshvol.Mesh(vertices, triangles).mass_properties()
    for faces in (BOX_QUADS, BOX_QUADS.tolist()):
        mesh = meshvol.Mesh(vertices, faces)
        assert not mesh.is_triangle_mesh and mesh.face_count == 6 and mesh.triangle_count == 12
        mp = mesh.mass_properties()
        assert mp.volume == 24.0 and mp.area == 52.0
        np.testing.assert_allclose(mp.inertia, by_triangles.inertia, rtol=1e-14, atol=1e-13)
    assert meshvol.Mesh(vertices, BOX_QUADS).triangulated().triangle_count == 12


def exact_signed_volume(vertices, faces):
    """Σ det(a, b, c) / 6 in exact rational arithmetic."""
    total = Fraction(0)
    for a, b, c in (vertices[f] for f in faces):
        a, b, c = ([Fraction(float(x)) for x in p] for p in (a, b, c))
        total += (
            a[0] * (b[1] * c[2] - b[2] * c[1])
            - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
        )
    return total / 6


def test_exact_volume_is_the_correctly_rounded_rational_sum():
    rng = np.random.default_rng(3)
    vertices, faces = uv_sphere(radius=1.0, rings=8, segments=12)
    vertices = vertices * (1 + 0.1 * rng.random((len(vertices), 1))) + 12345.678
    mp = meshvol.Mesh(vertices, faces).mass_properties(exact=True)
    assert mp.exact
    assert mp.signed_volume == float(exact_signed_volume(vertices, faces))
    plain = meshvol.Mesh(vertices, faces).mass_properties()
    assert not plain.exact
    assert abs(plain.signed_volume - mp.signed_volume) <= plain.volume_error_bound


def test_flat_surface_has_no_centroid():
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float)
    mesh = meshvol.Mesh(vertices, [[0, 1, 2], [0, 2, 1]])
    mp = mesh.mass_properties(check=False)
    assert mp.volume == 0.0 and mp.centroid is None
    assert mp.area == 1.0
    assert not mp.inertia.any()
    # Checked, the two sides of the triangle bound nothing either, and it is said.
    with pytest.warns(meshvol.MeshWarning):
        mp = mesh.mass_properties()
    assert mp.volume == 0.0 and mp.centroid is None
    assert any("encloses no solid" in w for w in mp.warnings)


def test_to_dict_has_the_volume_report_keys():
    mp = meshvol.Mesh(*box()).mass_properties(density=3.0)
    d = mp.to_dict()
    assert list(d)[:25] == [
        "file", "format", "format_source", "vertices",
        "faces", "triangles", "volume", "signed_volume", "volume_error_bound", "exact",
        "area", "cap_area", "centroid", "inertia", "principal_moments", "principal_axes", "density",
        "density_unit", "mass", "mass_unit", "bounds", "units", "warnings", "bounds_a_volume",
        "verdict",
    ]
    assert (d["file"], d["format"], d["vertices"], d["units"]) == (None, None, 8, None)
    # Unchecked, the check's facts are absent, as with `meshvol volume --no-check`.
    unchecked = meshvol.Mesh(*box()).mass_properties(check=False).to_dict()
    assert list(unchecked) == list(d)[:23]
    assert d["mass"] == 3.0 and d["centroid"] == [0.5, 0.5, 0.5]
    assert d["bounds"] == {"min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 1.0]}
    assert d["inertia"] == mp.inertia.tolist()


@pytest.mark.parametrize("density", [0.0, -1.0, float("nan"), float("inf")])
def test_density_must_be_positive(density):
    with pytest.raises(ValueError, match="density must be a positive number"):
        meshvol.Mesh(*box()).mass_properties(density=density)


def test_mesh_without_faces_has_nothing_to_measure():
    empty = meshvol.Mesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int32))
    assert empty.face_count == 0
    with pytest.raises(meshvol.MeshError, match="^no faces: there is no surface to measure$"):
        empty.mass_properties()


def test_exact_volume_out_of_range_is_an_error():
    vertices, faces = box((0, 0, 0), (1e120, 1e120, 1e120))
    with pytest.raises(meshvol.MeshError, match="overflow or underflow"):
        meshvol.Mesh(vertices, faces).mass_properties(exact=True)


def test_overflowing_moments_are_an_error_as_in_the_command():
    # A box 1e100 on a side: its volume fits a float64, its inertia (1e500) does not.
    mesh = meshvol.Mesh(*box((0, 0, 0), (1e100, 1e100, 1e100)))
    with pytest.raises(meshvol.MeshError, match="inertia overflows f64"):
        mesh.mass_properties()
    # In other units it fits: 1e100 um = 1e94 m, an inertia of 1e470 m^5 still does not,
    # but the volume does in any unit; a smaller box converts fine.
    small = meshvol.Mesh(*box((0, 0, 0), (1e60, 1e60, 1e60)))
    mp = small.mass_properties(units="um:m")
    assert mp.volume == pytest.approx(1e162, rel=1e-12)
    assert mp.to_dict()["units"]["volume"] == "m^3"


def test_inertial_elements_of_a_steel_cube():
    # A 10 mm steel cube: m = 7850 kg/m³ · 1e-6 m³, ixx = m (b² + c²) / 12.
    vertices, faces = box((0, 0, 0), (10, 10, 10))
    mp = meshvol.Mesh(vertices, faces).mass_properties(density=7850.0, units="mm:m")
    m = 7850.0 * 1e-6
    i = m * (0.01**2 + 0.01**2) / 12
    urdf = mp.to_urdf()
    assert f'<mass value="{mp.mass!r}"/>' in urdf
    assert mp.mass == pytest.approx(m, rel=1e-14)
    ixx = float(urdf.split('ixx="')[1].split('"')[0])
    assert ixx == pytest.approx(i, rel=1e-12)
    assert 'xyz="0.005 0.005 0.005"' in urdf
    assert "<ixx>" in mp.to_sdf() and "fullinertia=" in mp.to_mjcf()
    # Not in metres: refused, saying how.
    with pytest.raises(ValueError, match="units"):
        meshvol.Mesh(vertices, faces).mass_properties(density=7850.0).to_urdf()


def test_below_a_plane_of_the_unit_cube():
    # x + z <= 1: a prism of volume 1/2 and centroid (1/3, 1/2, 1/3); waterplane √2.
    cube = meshvol.Mesh(*box())
    b = cube.below(plane=(1.0, 0.0, 1.0, 1.0))
    assert b.volume == pytest.approx(0.5, rel=1e-15)
    assert b.centroid == pytest.approx([1 / 3, 0.5, 1 / 3], rel=1e-14)
    assert b.section_area == pytest.approx(2**0.5, rel=1e-14)
    # The level of z that holds 0.3.
    assert cube.below(volume=0.3).level == pytest.approx(0.3, rel=1e-14)
    with pytest.raises(ValueError, match="not both"):
        cube.below(plane=(0, 0, 1, 0.5), volume=0.3)
