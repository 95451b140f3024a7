"""Agreement with trimesh on the same arrays (skipped where trimesh is not installed)."""

import numpy as np
import pytest

import meshvol

trimesh = pytest.importorskip("trimesh")


@pytest.mark.parametrize(
    "make",
    [
        lambda: trimesh.creation.icosphere(subdivisions=4, radius=2.0),
        lambda: trimesh.creation.box(extents=(1.0, 2.0, 3.0)),
        lambda: trimesh.creation.capsule(height=2.0, radius=0.5, count=(24, 24)),
        lambda: trimesh.creation.annulus(r_min=0.5, r_max=1.0, height=0.3),
        lambda: trimesh.creation.torus(major_radius=2.0, minor_radius=0.4),
    ],
)
def test_mass_properties_agree(make):
    tm = make()
    tm.apply_translation([3.0, -1.0, 2.0])
    mp = meshvol.Mesh(tm).mass_properties()  # duck-typed: tm.vertices, tm.faces
    reference = trimesh.Trimesh(tm.vertices, tm.faces, process=False).mass_properties
    assert mp.volume == pytest.approx(reference["volume"], rel=1e-12)
    assert mp.area == pytest.approx(tm.area, rel=1e-12)
    np.testing.assert_allclose(mp.centroid, reference["center_mass"], rtol=1e-12)
    scale = np.abs(reference["inertia"]).max()
    np.testing.assert_allclose(mp.inertia, reference["inertia"], rtol=0, atol=1e-11 * scale)


def test_checks_agree():
    sphere = trimesh.creation.icosphere(subdivisions=3)
    c = meshvol.Mesh(sphere).check()
    assert c.closed == sphere.is_watertight and c.consistently_oriented == sphere.is_winding_consistent
    assert c.euler_characteristic == sphere.euler_number == 2
    open_sphere = trimesh.Trimesh(sphere.vertices, sphere.faces[1:], process=False)
    c = meshvol.Mesh(open_sphere).check()
    assert not c.closed and not open_sphere.is_watertight
    assert c.boundary_edges == 3 and c.boundary_loops == 1


def test_union_of_trimesh_bodies():
    a = trimesh.creation.box(extents=(2, 2, 2))
    b = trimesh.creation.box(extents=(2, 2, 2))
    b.apply_translation([1.0, 0.5, 0.25])
    u = meshvol.union([a, b])
    expected = 8 + 8 - 1.0 * 1.5 * 1.75
    assert u.lower <= expected <= u.upper


def test_mesh_round_trips_into_trimesh():
    mesh = meshvol.Mesh(trimesh.creation.icosphere(subdivisions=2))
    tm = trimesh.Trimesh(mesh.vertices, mesh.faces, process=False)
    assert tm.volume == pytest.approx(mesh.mass_properties().volume, rel=1e-12)
