"""Mesh.check(): the facts of `meshvol check` for solids whose topology is known."""

import json
import warnings
import os
import subprocess

import numpy as np
import pytest

import meshvol
from solids import BOX_TRIANGLES, OPENSCAD_CUBE_FACES, OPENSCAD_CUBE_POINTS, box

CHECK_KEYS = [
    "bounds_a_volume", "verdict", "closed", "weld_tolerance", "welded_vertices", "edges",
    "boundary_edges", "boundary_loops", "non_manifold_edges", "unpaired_at_non_manifold_edges",
    "non_manifold_vertices",
    "degenerate_faces", "flat_faces", "duplicate_faces", "double_wall_faces",
    "consistently_oriented", "orientation", "winding",
    "shells", "cavities", "shell_details", "overlapping_shells", "overlapping_objects",
    "self_intersections",
    "intersection_examples", "euler_characteristic", "solid_volume", "volume_uncertainty",
    "units",
]


def two_boxes(lo_a, hi_a, lo_b, hi_b, inward_b=False):
    va, fa = box(lo_a, hi_a)
    vb, fb = box(lo_b, hi_b)
    if inward_b:
        fb = fb[:, ::-1]
    return np.vstack([va, vb]), np.vstack([fa, fb + 8])


def test_boxes_touching_along_an_edge_are_two_closed_bodies():
    # The second box wound inward: the faces around the shared edge pair by body, so
    # each box is a closed shell turned outward, and every measure gives 2.
    v, f = two_boxes((0, 0, 0), (1, 1, 1), (1, 1, 0), (2, 2, 1), inward_b=True)
    m = meshvol.Mesh(v, f)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", meshvol.MeshWarning)
        c = m.check()
        assert (c.non_manifold_edges, c.unpaired_at_non_manifold_edges, c.shells) == (1, 0, 2)
        assert all(s.closed and s.volume == 1.0 for s in c.shell_details)
        assert m.mass_properties().volume == 2.0
        assert abs(m.grid(cells=(4, 4, 2)).sum() - 2.0) < 1e-12


def test_closed_box():
    c = meshvol.Mesh(*box((0, 0, 0), (2, 3, 4))).check()
    assert c.bounds_a_volume and c.closed and c.consistently_oriented
    assert c.verdict == "closed, 1 shell: volume is exact"
    assert (c.welded_vertices, c.edges, c.boundary_edges, c.boundary_loops) == (8, 18, 0, 0)
    assert (c.non_manifold_edges, c.non_manifold_vertices) == (0, 0)
    assert (c.orientation, c.winding) == ("outward", "ccw")
    assert (c.shells, c.cavities, c.euler_characteristic) == (1, 0, 2)
    assert (c.self_intersections, c.overlapping_shells, c.weld_tolerance) == (0, [], None)
    assert c.solid_volume == 24.0 and c.volume_uncertainty == 0.0
    (shell,) = c.shell_details
    assert (shell.face_count, shell.closed, shell.genus, shell.cavity, shell.parent) == (12, True, 0, False, None)
    assert c.repairs == (0, 0, 0)


def test_openscad_cube_is_wound_inward():
    mesh = meshvol.Mesh(OPENSCAD_CUBE_POINTS, OPENSCAD_CUBE_FACES)
    c = mesh.check()
    assert (c.orientation, c.winding) == ("inward", "cw")
    assert c.verdict == "closed, 1 shell: volume is exact (wound inward)"
    assert c.solid_volume == 1.0
    solid = c.mass_properties()
    # The solid's volume; signed_volume is the file's surface's, as the command's key.
    assert solid.volume == 1.0 and solid.signed_volume == -1.0
    assert any("wound inward" in w for w in solid.warnings)
    assert c.repairs == (12, 0, 0)
    assert c.solid_mesh().mass_properties().signed_volume == 1.0


def test_open_box_is_capped():
    vertices, faces = box((0, 0, 0), (2, 3, 4))
    open_box = np.delete(faces, [1, 7], axis=0)  # the two triangles of the top
    c = meshvol.Mesh(vertices, open_box).check()
    assert not c.closed and not c.bounds_a_volume
    assert (c.boundary_edges, c.boundary_loops) == (4, 1)
    assert c.verdict == "does not bound a volume: open (1 hole, flat, capped exactly); 1 shell"
    # A flat hole is capped exactly.
    assert c.solid_volume == pytest.approx(24.0, rel=1e-15)
    assert c.volume_uncertainty == 0.0
    assert c.mass_properties().volume == pytest.approx(24.0, rel=1e-15)
    assert c.solid_mesh(caps=True).check().closed
    assert not c.solid_mesh().check().closed


@pytest.mark.parametrize("inward", [True, False])
def test_cavity_is_subtracted_whatever_its_winding(inward):
    vertices, faces = two_boxes((0, 0, 0), (3, 3, 3), (1, 1, 1), (2, 2, 2), inward_b=inward)
    c = meshvol.Mesh(vertices, faces).check()
    assert (c.shells, c.cavities) == (2, 1)
    assert c.solid_volume == 26.0
    assert c.bounds_a_volume
    assert c.orientation == ("outward" if inward else "mixed")
    inner = c.shell_details[1]
    assert inner.cavity and inner.parent == 0 and inner.wound_outward == inward
    assert c.mass_properties().volume == 26.0
    np.testing.assert_allclose(c.mass_properties().centroid, [1.5] * 3, atol=1e-14)


def test_overlapping_boxes_point_to_union():
    vertices, faces = two_boxes((0, 0, 0), (2, 2, 2), (1, 0.75, 0.5), (3, 2.5, 3))
    c = meshvol.Mesh(vertices, faces).check()
    assert c.overlapping_shells == [(0, 1)]
    assert not c.bounds_a_volume
    assert c.verdict == (
        "does not bound a volume: 1 pair of shells overlap (their common volume is counted "
        "twice: use `meshvol union`); 2 shells"
    )
    assert c.solid_volume == 8.0 + 2 * 1.75 * 2.5
    assert c.intersection_examples  # face pairs that cross
    unchecked = meshvol.Mesh(vertices, faces).check(intersections=False)
    assert unchecked.self_intersections is None


def test_duplicate_and_degenerate_faces_are_dropped():
    vertices, faces = box()
    extra = np.vstack([faces, faces[:1], [[0, 0, 1]]])
    c = meshvol.Mesh(vertices, extra).check()
    assert (c.duplicate_faces, c.degenerate_faces) == (1, 1)
    assert c.closed and c.solid_volume == 1.0
    assert c.repairs == (0, 2, 0)
    assert c.mass_properties().volume == 1.0


def test_weld_tolerance():
    vertices, faces = box()
    # Vertex 7 again, a hair away, used by the faces of the top.
    near = vertices[7] + 1e-12
    vertices = np.vstack([vertices, near])
    faces = faces.copy()
    faces[[1, 7]] = np.where(faces[[1, 7]] == 7, 8, faces[[1, 7]])
    mesh = meshvol.Mesh(vertices, faces)
    exact = mesh.check(weld_tolerance=0.0)
    assert not exact.closed and exact.weld_tolerance is None
    auto = mesh.check()
    assert auto.closed and auto.weld_tolerance == pytest.approx(1e-9 * np.sqrt(3))
    given = mesh.check(weld_tolerance=1e-6)
    assert given.closed and given.weld_tolerance == 1e-6


def test_to_dict_has_the_check_report_keys():
    d = meshvol.Mesh(*box()).check().to_dict()
    assert list(d) == ["file", "format", *CHECK_KEYS, "warnings"]
    assert (d["file"], d["format"], d["warnings"]) == (None, None, [])
    assert d["shell_details"] == [
        {
            "faces": 12, "closed": True, "orientable": True, "volume": 1.0, "cavity": False,
            "parent": None, "wound_outward": True, "boundary_loops": 0,
            "euler_characteristic": 2, "genus": 0,
        }
    ]
    json.dumps(d)  # plain values only


def write_obj(path, vertices, faces):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in faces.tolist()]
    path.write_text("\n".join(lines) + "\n")


COMMAND = os.environ.get("MESHVOL_BIN")


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
@pytest.mark.parametrize(
    "name, solid",
    [
        ("box", box((0.5, 1, 2), (2, 3, 7))),
        ("openscad", (OPENSCAD_CUBE_POINTS, OPENSCAD_CUBE_FACES)),
        ("open", (box()[0], np.delete(BOX_TRIANGLES, [1, 7], axis=0))),
        ("cavity", two_boxes((0, 0, 0), (3, 3, 3), (1, 1, 1), (2, 2, 2))),
        ("overlap", two_boxes((0, 0, 0), (2, 2, 2), (1, 1, 1), (3, 3, 3))),
    ],
)
def test_same_facts_as_the_command(tmp_path, name, solid):
    path = tmp_path / f"{name}.obj"
    write_obj(path, *solid)
    mesh = meshvol.load(path)

    def command(*args):
        run = subprocess.run([COMMAND, *args, "--json", str(path)], capture_output=True, text=True)
        return json.loads(run.stdout)

    # The same report: every key and value (the file as given to both).
    assert command("check") == mesh.check().to_dict()
    as_wound = mesh.mass_properties(density=2.0, check=False).to_dict()
    assert command("volume", "--no-check", "--density", "2") == as_wound
    # By default both measure the checked solid, with the same warnings.
    checked = command("volume", "--density", "2")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", meshvol.MeshWarning)
        solid = mesh.mass_properties(density=2.0).to_dict()
        assert mesh.check().mass_properties(density=2.0).to_dict() == solid
    assert checked == solid


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
def test_same_read_error_as_the_command(tmp_path):
    path = tmp_path / "bad.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n")
    with pytest.raises(meshvol.ReadError) as caught:
        meshvol.load(path)
    run = subprocess.run([COMMAND, "volume", str(path)], capture_output=True, text=True)
    assert run.returncode != 0
    assert run.stderr.strip() == f"meshvol: error: {caught.value}"
