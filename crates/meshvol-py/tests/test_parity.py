"""What the command does, Python does too (issue 31, item 3): Mesh.section (`meshvol
section`), Mesh.bodies (each body with its own mass properties), and saving a repaired
solid. Compared with closed forms, with trimesh, and with the command's JSON."""

import json
import math
import os
import subprocess

import numpy as np
import pytest

import meshvol
from solids import BOX_TRIANGLES, box, box_inertia

COMMAND = os.environ.get("MESHVOL_BIN")


def write_obj(path, vertices, faces):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices).tolist()]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in np.asarray(faces).tolist()]
    path.write_text("\n".join(lines) + "\n")


def boxes(*corners, inward=()):
    """Several boxes as one mesh; those numbered in `inward` wound inward."""
    vertices, faces = [], []
    for k, (lo, hi) in enumerate(corners):
        v, f = box(lo, hi)
        faces.append((f[:, ::-1] if k in inward else f) + 8 * k)
        vertices.append(v)
    return np.vstack(vertices), np.vstack(faces)


# section


def test_section_of_a_box():
    mesh = meshvol.Mesh(*box((0, 0, 0), (2, 3, 4)))
    s = mesh.section("z=1")
    assert isinstance(s, meshvol.Section)
    assert (s.area, s.perimeter, s.polygons, s.holes) == (6.0, 10.0, 1, 0)
    assert s.centroid.tolist() == [1.0, 1.5] and s.centroid_3d.tolist() == [1.0, 1.5, 1.0]
    # ix = ∫(y - cy)² dA = 2·3³/12, iy = 3·2³/12.
    assert s.inertia["ix"] == pytest.approx(4.5) and s.inertia["iy"] == pytest.approx(2.0)
    assert np.allclose(s.principal_moments, [2.0, 4.5])
    assert np.isclose(abs(s.principal_axes[0] @ [0, 1]), 1.0)  # iy is about the y axis
    # The same plane in its other forms.
    for plane in ([[5, 5, 1], [0, 0, 2]], np.array([0, 0, 1, 1.0]), (0, 0, -3, -3)):
        assert mesh.section(plane).area == pytest.approx(6.0)
    (exterior, holes), = s.outlines
    x, y = exterior.T
    assert 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))) == 6.0 and holes == []
    assert s.to_wkt().startswith("MULTIPOLYGON") and s.to_geojson()["type"] == "Feature"


def test_section_by_a_tilted_plane():
    # The unit cube cut by z = 0.5 + 0.25 (x - 0.5): a 1 x sqrt(1 + 0.25²) rectangle.
    mesh = meshvol.Mesh(*box())
    s = mesh.section([[0.5, 0.5, 0.5], [-0.25, 0, 1]])
    assert s.area == pytest.approx(math.sqrt(1 + 0.25**2), rel=1e-14)
    assert np.allclose(s.centroid_3d, [0.5, 0.5, 0.5])


def test_section_with_a_cavity_has_a_hole():
    mesh = meshvol.Mesh(*boxes(((0, 0, 0), (3, 3, 3)), ((1, 1, 1), (2, 2, 2)), inward=(1,)))
    s = mesh.section("z=1.5")
    assert (s.area, s.polygons, s.holes) == (8.0, 1, 1)


def test_section_units_and_bad_planes():
    mesh = meshvol.Mesh(*box((0, 0, 0), (20, 30, 40)))
    s = mesh.section("z=10", units="mm:cm")
    assert s.area == pytest.approx(6.0) and s.units["length"] == "cm"
    # Every text form of `meshvol section --plane` (one parser): 20 × 30 mm at z = 10.
    for text in ["z=10", "0,0,1,10", "0,0,-2,-20", "5,5,10,0,0,1"]:
        assert mesh.section(text).area == pytest.approx(600.0, rel=1e-14), text
    with pytest.raises(ValueError, match="'w' is not an axis"):
        mesh.section("w=1")
    with pytest.raises(ValueError, match="found 3 number"):
        mesh.section("0,0,1")
    with pytest.raises(ValueError, match=r"plane must be \[point, normal\].*shape \(2, 3\); got shape \(3,\)"):
        mesh.section((0, 0, 1))
    with pytest.raises(ValueError, match="normal"):
        mesh.section([[0, 0, 0], [0, 0, 0]])
    with pytest.warns(meshvol.MeshWarning, match="does not cut"):
        empty = mesh.section("z=100")
    assert empty.area == 0.0 and empty.centroid is None


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
def test_section_is_the_commands(tmp_path):
    path = tmp_path / "two.obj"
    write_obj(path, *boxes(((0, 0, 0), (3, 3, 3)), ((1, 1, 1), (2, 2, 2)), inward=(1,)))
    for plane, ours in [("z=1.5", "z=1.5"), ("0.5,0.5,1.2,0.1,0.2,1", [[0.5, 0.5, 1.2], [0.1, 0.2, 1]])]:
        run = subprocess.run([COMMAND, "section", str(path), "--plane", plane, "--json"],
                             capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        assert meshvol.load(path).section(ours).to_dict() == json.loads(run.stdout)


# bodies


def test_bodies_have_their_own_mass_properties():
    # A 2-cube with a 1-cube cavity (wound like a solid: the check turns it), and a
    # 1 x 1 x 3 bar apart.
    mesh = meshvol.Mesh(*boxes(((0, 0, 0), (2, 2, 2)), ((0.5, 0.5, 0.5), (1.5, 1.5, 1.5)),
                               ((5, 0, 0), (6, 1, 3))))
    with pytest.warns(meshvol.MeshWarning):
        whole = mesh.mass_properties()
        bodies = mesh.bodies()
    assert len(bodies) == 2 and all(isinstance(b, meshvol.Mesh) for b in bodies)
    hollow, bar = (b.mass_properties(density=2.0) for b in bodies)
    assert hollow.volume == 7.0 and hollow.mass == 14.0
    assert np.allclose(hollow.centroid, [1, 1, 1]) and hollow.area == 24.0 + 6.0
    assert np.allclose(hollow.inertia, box_inertia((2, 2, 2), 2.0) - box_inertia((1, 1, 1), 2.0))
    assert bar.volume == 3.0 and np.allclose(bar.centroid, [5.5, 0.5, 1.5])
    assert np.allclose(bar.inertia, box_inertia((1, 1, 3), 2.0))
    assert hollow.volume + bar.volume == whole.volume
    assert hollow.closed and bar.closed and hollow.cavities == 1


def test_bodies_match_trimesh_on_each_part():
    trimesh = pytest.importorskip("trimesh")
    corners = (((0, 0, 0), (1, 2, 3)), ((4, 0, 0), (5, 1, 1)), ((0, 5, 0), (2, 7, 1)))
    bodies = meshvol.Mesh(*boxes(*corners)).bodies()
    for body, (lo, hi) in zip(bodies, corners):  # in shell order: the file's order here
        theirs = trimesh.Trimesh(*box(lo, hi), process=False)
        ours = body.mass_properties()
        assert ours.volume == pytest.approx(theirs.volume, rel=1e-14)
        assert np.allclose(ours.centroid, theirs.center_mass)
        assert np.allclose(ours.inertia, theirs.moment_inertia)


def test_unchecked_bodies_are_the_connected_parts():
    mesh = meshvol.Mesh(*boxes(((0, 0, 0), (2, 2, 2)), ((0.5, 0.5, 0.5), (1.5, 1.5, 1.5)), inward=(1,)))
    assert [b.mass_properties().volume for b in mesh.bodies()] == [7.0]
    parts = mesh.bodies(check=False)
    assert sorted(p.mass_properties(check=False).signed_volume for p in parts) == [-1.0, 8.0]


def test_an_open_body_is_capped():
    vertices, faces = box()
    mesh = meshvol.Mesh(vertices, faces[:-1])
    with pytest.warns(meshvol.MeshWarning, match="capped"):
        (body,) = mesh.bodies()
    assert body.check().closed and body.mass_properties().volume == 1.0


# saving a repaired solid


def test_a_repaired_solid_saves_and_reads_back(tmp_path):
    vertices, faces = box((0, 0, 0), (2, 3, 4))
    mesh = meshvol.Mesh(vertices, faces[:-1])  # a hole
    repaired = mesh.check().solid_mesh(caps=True)
    written = repaired.save(tmp_path / "repaired.ply")
    assert written["same_solid"] and written["closed"] and written["volume"] == 24.0
    again = meshvol.load(tmp_path / "repaired.ply")
    assert again.check().bounds_a_volume and again.mass_properties().volume == 24.0
