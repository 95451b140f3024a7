"""Python takes what the command takes (issue 52, item 5): paths wherever meshes are
(meshvol.union, meshvol.intersection, meshvol.intersections, as meshvol.cutfill), a
compressed form in file_type ('stl.gz', 'gz', 'zip'), density= on section and cutfill,
and timings= on the batch calls (meshvol.measure, meshvol.dask.measure,
meshvol.intersections). Each compared
with the command's JSON for the same files and options."""

import ast
import gzip
import io
import json
import os
import subprocess
import zipfile
from pathlib import Path

import numpy as np
import pytest

import meshvol
from solids import box

COMMAND = os.environ.get("MESHVOL_BIN")
needs_command = pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")

# Keys that time the run: never the same twice.
TIMED = {"seconds", "timings"}


def write_obj(path, vertices, faces):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices).tolist()]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in np.asarray(faces).tolist()]
    path.write_text("\n".join(lines) + "\n")


def command_lines(*args):
    run = subprocess.run([COMMAND, *map(str, args)], capture_output=True, text=True)
    assert run.returncode in (0, 1), run.stderr
    return [json.loads(line) for line in run.stdout.splitlines()]


def untimed(report):
    return {k: v for k, v in report.items() if k not in TIMED}


@pytest.fixture()
def two_boxes(tmp_path):
    """Two overlapping boxes, 2 × 3 × 4 and 3 × 3 × 3, sharing a 1 × 3 × 3 block; the
    second's file has a line element, which the reader passes over with a warning."""
    a, b = tmp_path / "a.obj", tmp_path / "b.obj"
    write_obj(a, *box((0, 0, 0), (2, 3, 4)))
    write_obj(b, *box((1, 0, 0), (4, 3, 3)))
    b.write_text(b.read_text() + "l 1 2\n")
    return a, b


@needs_command
def test_union_and_intersection_take_paths_as_the_command_reads_them(two_boxes):
    a, b = two_boxes
    (union,) = command_lines("union", a, b, "--json")
    for given in ([str(a), str(b)], [a, b], [os.fsencode(a), b]):
        assert untimed(meshvol.union(given).to_dict()) == untimed(union)
    # |A ∪ B| = 24 + 27 - 9, in closed form too.
    assert union["lower"] <= 42.0 <= union["upper"]
    (inter,) = command_lines("intersect", a, b, "--json")
    assert untimed(meshvol.intersection(str(a), b).to_dict()) == untimed(inter)
    assert inter["lower"] <= 9.0 <= inter["upper"]
    # Paths and meshes mixed, and the pose batch: the same report for the pose None.
    (posed,) = meshvol.intersections(a, meshvol.load(str(b)))
    assert (posed.lower, posed.upper) == (inter["lower"], inter["upper"])
    # One path stands for its bodies, as one file does for the command.
    both = a.parent / "both.obj"
    (va, fa), (vb, fb) = box((0, 0, 0), (2, 3, 4)), box((1, 0, 0), (4, 3, 3))
    write_obj(both, np.vstack([va, vb]), np.vstack([fa, fb + len(va)]))
    (single,) = command_lines("union", both, "--json")
    assert untimed(meshvol.union(str(both)).to_dict()) == untimed(single)
    assert single["bodies"] == 2


def test_a_missing_path_is_the_error_load_gives(tmp_path):
    missing = tmp_path / "missing.obj"
    with pytest.raises(meshvol.MeshFileNotFoundError, match="missing.obj"):
        meshvol.union([missing])
    with pytest.raises(FileNotFoundError, match="missing.obj"):
        meshvol.intersection(meshvol.Mesh(*box()), missing)
    with pytest.raises(TypeError, match="expected a mesh"):
        meshvol.intersection(meshvol.Mesh(*box()), 3)


@needs_command
def test_the_reader_warnings_of_a_path_are_the_commands(two_boxes):
    a, b = two_boxes
    (inter,) = command_lines("intersect", a, b, "--json")
    assert inter["warnings"] == [f"{b}: ignored 1 line elements (l)"]
    with pytest.warns(meshvol.MeshWarning) as caught:
        meshvol.intersection(a, b)
    assert [str(w.message) for w in caught] == inter["warnings"]


def compressed_forms(obj_bytes):
    """The OBJ as gzip bytes and as a zip holding part.obj."""
    zipped = io.BytesIO()
    with zipfile.ZipFile(zipped, "w") as z:
        z.writestr("part.obj", obj_bytes)
    return gzip.compress(obj_bytes), zipped.getvalue()


@needs_command
def test_file_type_names_compressed_forms(tmp_path):
    plain = tmp_path / "part.obj"
    write_obj(plain, *box((0, 0, 0), (2, 3, 4)))
    gz, zipped = compressed_forms(plain.read_bytes())
    (tmp_path / "part.obj.gz").write_bytes(gz)
    (want,) = command_lines("volume", tmp_path / "part.obj.gz", "--json")
    assert want["volume"] == 24.0
    blob = tmp_path / "blob.bin"
    blob.write_bytes(gz)
    cases = [(io.BytesIO(gz), "obj.gz"), (io.BytesIO(gz), "gz"), (io.BytesIO(gz), ".OBJ.GZ"),
             (blob, "obj.gz"), (blob, "gz"), (io.BytesIO(zipped), "zip")]
    for source, file_type in cases:
        got = meshvol.load(source, file_type=file_type).mass_properties()
        assert (got.volume, got.area, got.centroid.tolist()) == (want["volume"], want["area"], want["centroid"])
    with pytest.raises(ValueError, match=r"file_type must be one of stl, .*got 'stl\.zip'"):
        meshvol.load(io.BytesIO(gz), file_type="stl.zip")
    with pytest.raises(ValueError, match="got 'tar'"):
        meshvol.load(io.BytesIO(gz), file_type="tar")


@needs_command
def test_density_on_section_and_cutfill_is_the_commands(tmp_path):
    part = tmp_path / "part.obj"
    write_obj(part, *box((0, 0, 0), (20, 30, 40)))
    (section,) = command_lines("section", part, "--plane", "z=10", "--units", "mm:cm",
                               "--density", "62.8kg/m2", "--json")
    got = meshvol.load(str(part)).section("z=10", units="mm:cm", density="62.8kg/m2").to_dict()
    assert untimed(got) == untimed(section)
    assert section["mass"] == pytest.approx(62.8 * 6e-4)
    ground = tmp_path / "ground.obj"
    vertices = np.array([[0, 0, 1], [10, 0, 1], [10, 10, 1], [0, 10, 1]], dtype=float)
    write_obj(ground, vertices, [[0, 1, 2], [0, 2, 3]])
    (fill,) = command_lines("cutfill", ground, "--level", "2", "--units", "m",
                            "--density", "1.8t/m3", "--json")
    got = meshvol.cutfill(str(ground), level=2.0, units="m", density="1.8t/m3").to_dict()
    assert untimed(got) == untimed(fill)
    assert fill["fill"] == 100.0 and fill["mass"] == pytest.approx(180.0)


def stage_names(timings):
    return [t["stage"] for t in timings]


@needs_command
def test_timings_on_measure_are_the_commands_stages(two_boxes):
    a, b = two_boxes
    missing = a.parent / "missing.obj"
    lines = command_lines("volume", a, b, missing, "--json", "--timings")
    frame = meshvol.measure([a, b, missing], timings=True)
    assert list(frame["file"]) == [line["file"] for line in lines]
    for row, line in zip(frame.to_dict("records"), lines):
        if "error" in line:
            # The command's error line has no timings; the row's cell is empty.
            assert "timings" not in line and not isinstance(row["timings"], list)
            continue
        assert stage_names(row["timings"]) == stage_names(line["timings"])
        assert {"reading", "checking", "measuring"} <= set(stage_names(line["timings"]))
        assert all(t["wall_s"] >= 0 and t["cpu_s"] >= 0 for t in row["timings"])
    assert "timings" not in meshvol.measure([a]).columns
    pytest.importorskip("dask")
    from meshvol import dask as meshvol_dask

    lazy = meshvol_dask.measure([a, b, missing], files_per_partition=2, timings=True)
    computed = lazy.compute(scheduler="sync")
    assert list(computed.columns) == list(lazy.columns)
    # Dask keeps object columns as text (its `dataframe.convert-string`): a list cell
    # arrives as the list's repr.
    cells = [ast.literal_eval(t) if isinstance(t, str) else None for t in computed["timings"]]
    assert [stage_names(t) if t else None for t in cells] == [
        stage_names(line["timings"]) if "timings" in line else None for line in lines
    ]


@needs_command
def test_timings_on_intersections_are_the_commands_stages(two_boxes):
    a, b = two_boxes
    (line,) = command_lines("intersect", a, b, "--json", "--timings")
    results = meshvol.intersections(a, b, poses_b=np.stack([np.eye(4)] * 3), timings=True)
    assert len(results) == 3
    # The command's checks (after reading each file, which Python did before the call),
    # then measuring, as meshvol.intersection times them.
    command = stage_names(line["timings"])
    checks = [s for s in command[: command.index("measuring")] if s not in ("reading", "preparing the bodies")]
    one = stage_names(meshvol.intersection(a, b, timings=True).timings)
    for r in results:
        assert stage_names(r.timings) == checks + ["measuring"] == one
        assert untimed(r.to_dict()) == untimed(line)
    assert "timings" not in meshvol.intersections(a, b)[0].to_dict()
