"""The bindings' reports are the command's: for every command they share, to_dict() has
the keys of the command's JSON, in its order, and the same values where the inputs are
the same (the command's report of a file, the bindings' of that file or its arrays)."""

import json
import os
import subprocess

import numpy as np
import pytest

import meshvol
from solids import box

COMMAND = os.environ.get("MESHVOL_BIN")
pytestmark = pytest.mark.skipif(
    not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with"
)


def command(*args):
    run = subprocess.run([COMMAND, *args, "--json"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


def write_obj(path, vertices, faces):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in faces.tolist()]
    path.write_text("\n".join(lines) + "\n")


@pytest.fixture
def two_boxes(tmp_path):
    va, fa = box((0, 0, 0), (2, 2, 2))
    vb, fb = box((1, 1, 1), (3, 2.5, 2.5))
    path = tmp_path / "two.obj"
    write_obj(path, np.vstack([va, vb]), np.vstack([fa, fb + len(va)]))
    return path


def test_profile(two_boxes):
    with pytest.warns(meshvol.MeshWarning):
        ours = meshvol.load(two_boxes).profile(levels=4).to_dict()
    assert ours == command("profile", str(two_boxes), "--levels", "4")


def test_union(two_boxes):
    with pytest.warns(meshvol.MeshWarning):
        ours = meshvol.union(meshvol.load(two_boxes)).to_dict()
    theirs = command("union", str(two_boxes))
    assert list(ours) == list(theirs)
    timing = {"seconds"}
    assert {k: v for k, v in ours.items() if k not in timing} == {
        k: v for k, v in theirs.items() if k not in timing
    }


def test_hull(tmp_path):
    points = np.random.default_rng(7).normal(size=(200, 3))
    path = tmp_path / "cloud.xyz"
    path.write_text("\n".join(" ".join(repr(x) for x in p) for p in points.tolist()) + "\n")
    ours = meshvol.convex_hull(points).to_dict()
    theirs = command("hull", str(path))
    assert list(ours) == list(theirs)
    source = {"file", "format"}
    assert {k: v for k, v in ours.items() if k not in source} == {
        k: v for k, v in theirs.items() if k not in source
    }


def test_area(tmp_path):
    outline = [(0.0, 0.0), (4.0, 0.0), (4.0, 3.0), (0.0, 3.0)]
    hole = [(1.0, 1.0), (1.0, 2.0), (2.0, 2.0), (2.0, 1.0)]
    path = tmp_path / "lot.wkt"
    ring = lambda r: "(" + ", ".join(f"{x!r} {y!r}" for x, y in r + r[:1]) + ")"
    path.write_text(f"POLYGON ({ring(outline)}, {ring(hole)})")
    ours = meshvol.polygon_area(np.array(outline), [np.array(hole)]).to_dict()
    theirs = command("area", str(path))
    assert list(ours) == list(theirs)
    source = {"file", "format"}
    assert {k: v for k, v in ours.items() if k not in source} == {
        k: v for k, v in theirs.items() if k not in source
    }
    assert ours["area"] == 11.0


def test_below(two_boxes):
    with pytest.warns(meshvol.MeshWarning):
        ours = meshvol.load(two_boxes).below(volume=5.0, heel=10.0).to_dict()
    assert ours == command("below", str(two_boxes), "--volume", "5", "--heel", "10")
