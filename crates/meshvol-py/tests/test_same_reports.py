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


def test_cutfill(tmp_path):
    # A bumpy terrain against a tilted design of another triangulation, in cells.
    def sheet(path, n, z):
        xs = np.linspace(0.0, 2.0, n + 1)
        vertices = np.array([[x, y, z(x, y)] for x in xs for y in xs])
        at = lambda i, j: i * (n + 1) + j
        faces = np.array(
            [f for i in range(n) for j in range(n)
             for f in ([at(i, j), at(i + 1, j), at(i + 1, j + 1)],
                       [at(i, j), at(i + 1, j + 1), at(i, j + 1)])]
        )
        write_obj(path, vertices, faces)
    existing, design = tmp_path / "land.obj", tmp_path / "road.obj"
    sheet(existing, 9, lambda x, y: np.sin(3 * x) * np.cos(2 * y))
    sheet(design, 4, lambda x, y: 0.1 * x - 0.2 * y)
    ours = meshvol.cutfill(str(existing), design=str(design), cells=(3, 2))
    assert ours.to_dict() == command("cutfill", str(existing), "--design", str(design), "--cells", "3,2")
    assert abs(ours.cut_cells.sum() - ours.cut) < 1e-12
    ours = meshvol.cutfill(meshvol.load(existing), level=0.1)
    theirs = command("cutfill", str(existing), "--level", "0.1")
    assert ours.to_dict() == theirs


def test_intersect(tmp_path):
    paths = [tmp_path / "a.obj", tmp_path / "b.obj"]
    write_obj(paths[0], *box((0, 0, 0), (2, 2, 2)))
    write_obj(paths[1], *box((1, 0.5, 1), (3, 2.5, 2.5)))
    ours = meshvol.intersection(*(meshvol.load(p) for p in paths)).to_dict()
    theirs = command("intersect", *map(str, paths))
    assert list(ours) == list(theirs)
    timing = {"seconds"}
    assert {k: v for k, v in ours.items() if k not in timing} == {
        k: v for k, v in theirs.items() if k not in timing
    }
