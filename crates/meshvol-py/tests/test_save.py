"""Mesh.save(): the file written is read back and must be the solid meant, as `meshvol
repair -o` requires. Volumes are compared with trimesh's (a peer tool) on the same
sphere at the origin, where float64 sums are accurate, and with boxes' closed forms."""

import os
import warnings

import numpy as np
import pytest
import trimesh

import meshvol
from solids import box, uv_sphere

FAR = (5e6, 1e7, 0.0)


def open_far_sphere():
    """A UV sphere of radius 1 at FAR without its first triangle (a polar fan triangle,
    so the cap, a fan in that triangle's plane, restores the closed sphere)."""
    vertices, faces = uv_sphere(rings=16, segments=32, centre=FAR)
    return meshvol.Mesh(vertices, faces[1:])


def sphere_volume():
    """The closed sphere's polyhedral volume, by trimesh at the origin."""
    vertices, faces = uv_sphere(rings=16, segments=32)
    return trimesh.Trimesh(vertices, faces, process=False).volume


def files(folder):
    return sorted(os.listdir(folder))


def test_far_solid_to_stl_is_refused_and_nothing_is_left(tmp_path):
    solid = open_far_sphere().check().solid_mesh(caps=True)
    path = tmp_path / "far.stl"
    with pytest.raises(meshvol.LossyWriteError) as raised:
        solid.save(path)
    message = str(raised.value)
    for word in ["far.stl", "float32", ".ply", ".obj", "allow_lossy=True", "volume"]:
        assert word in message, (word, message)
    assert isinstance(raised.value, meshvol.MeshError)
    assert files(tmp_path) == []
    # A file already there stays as it was.
    path.write_bytes(b"earlier")
    with pytest.raises(meshvol.LossyWriteError):
        solid.save(str(path))
    assert path.read_bytes() == b"earlier" and files(tmp_path) == ["far.stl"]


def test_far_solid_with_allow_lossy_is_written_warned_and_reports_both(tmp_path):
    solid = open_far_sphere().check().solid_mesh(caps=True)
    path = tmp_path / "far.stl"
    with pytest.warns(meshvol.MeshWarning, match="not the solid reported"):
        written = solid.save(path, allow_lossy=True)
    expected = sphere_volume()
    assert written["same_solid"] is False and written["coordinates"] == "float32"
    assert written["intended_volume"] == pytest.approx(expected, rel=1e-9)
    # What was written is what meshvol reads back, and float32 moved it.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", meshvol.MeshWarning)
        read_back = meshvol.load(path).mass_properties().volume
    assert written["volume"] == read_back
    assert abs(read_back / expected - 1) > 1e-3
    assert written["collapsed_faces"] + written["duplicate_faces"] > 0


@pytest.mark.parametrize("name", ["far.ply", "far.obj"])
def test_far_solid_round_trips_through_float64_formats(tmp_path, name):
    solid = open_far_sphere().check().solid_mesh(caps=True)
    path = tmp_path / name
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        written = solid.save(path)
    assert written["same_solid"] is True and written["coordinates"] == "float64"
    assert abs(written["volume"] - written["intended_volume"]) <= written["tolerance"]
    assert written["volume"] == pytest.approx(sphere_volume(), rel=1e-9)
    again = meshvol.load(path)
    assert again.check().bounds_a_volume
    assert again.mass_properties().volume == written["volume"]


def test_near_origin_box_to_stl_is_silent(tmp_path):
    mesh = meshvol.Mesh(*box((0, 0, 0), (2, 3, 4)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        written = mesh.save(tmp_path / "box.stl")
    assert written["same_solid"] is True and written["format"] == "stl-binary"
    assert written["volume"] == written["intended_volume"] == 24.0
    assert meshvol.load(tmp_path / "box.stl").mass_properties().volume == 24.0


def test_far_hull_mesh_is_refused_as_stl(tmp_path):
    vertices, _ = uv_sphere(rings=16, segments=32, centre=FAR)
    hull = meshvol.convex_hull(vertices)
    with pytest.raises(meshvol.LossyWriteError, match="float32"):
        hull.mesh.save(tmp_path / "hull.stl")
    assert files(tmp_path) == []
    assert hull.mesh.save(tmp_path / "hull.ply")["volume"] == pytest.approx(hull.volume, rel=1e-12)


def test_unknown_extension_and_unwritable_folder(tmp_path):
    mesh = meshvol.Mesh(*box())
    with pytest.raises(meshvol.MeshError, match="cannot write this format"):
        mesh.save(tmp_path / "box.xyz")
    with pytest.raises(OSError):
        mesh.save(tmp_path / "missing" / "box.ply")
    assert files(tmp_path) == []
