"""meshvol.measure (issue 31, item 4): many files at once, one DataFrame row a file in
the input's order, the columns `meshvol volume --json`'s keys flattened as
pandas.json_normalize(sep='.') flattens them, a failed file a row with 'error'.
Compared with closed forms and with the command's JSON lines."""

import json
import os
import subprocess
import warnings

import numpy as np
import pytest

import meshvol
from solids import box, uv_sphere

pandas = pytest.importorskip("pandas")
COMMAND = os.environ.get("MESHVOL_BIN")


def write_obj(path, vertices, faces):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices).tolist()]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in np.asarray(faces).tolist()]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def folder(tmp_path):
    """Boxes of known volumes, an open box, a broken file and a text file."""
    (tmp_path / "sub").mkdir()
    write_obj(tmp_path / "a_box.obj", *box((0, 0, 0), (2, 3, 4)))
    write_obj(tmp_path / "sub" / "b_cube.obj", *box((1, 1, 1), (2, 2, 2)))
    v, f = box()
    write_obj(tmp_path / "c_open.obj", v, f[:-1])
    (tmp_path / "d_broken.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n")
    (tmp_path / "notes.txt").write_text("not a mesh")
    return tmp_path


def test_one_row_a_file_in_order(folder):
    paths = [folder / "sub" / "b_cube.obj", folder / "d_broken.obj", folder / "a_box.obj",
             folder / "missing.stl", folder / "c_open.obj"]
    df = meshvol.measure(paths)
    assert isinstance(df, pandas.DataFrame) and len(df) == 5
    assert df["file"].tolist() == [str(p) for p in paths]
    assert df["volume"].tolist()[0] == 1.0 and df["volume"].tolist()[2] == 24.0
    assert df["volume"].tolist()[4] == 1.0  # capped
    assert np.isnan(df["volume"][1]) and np.isnan(df["volume"][3])
    assert df["error"][1].startswith(f"{paths[1]}: line 3:")
    assert "No such file" in df["error"][3]
    assert df["error"].isna().tolist() == [True, False, True, False, True]
    # Nested objects become a.b columns; lists stay one cell.
    assert df["bounds.min"][2] == [0.0, 0.0, 0.0] and df["bounds.max"][2] == [2.0, 3.0, 4.0]
    assert df["centroid"][2] == [1.0, 1.5, 2.0]
    assert df["closed"].tolist()[0] is True and df["warnings"][4] != []
    assert df["verdict"][2] == "closed, 1 shell: volume is exact"


def test_the_columns_are_the_reports_flattened(folder):
    path = folder / "a_box.obj"
    df = meshvol.measure([path], density=2.0, units="mm:cm")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        report = meshvol.load(path).mass_properties(density=2.0, units="mm:cm").to_dict()
    report["file"] = str(path)
    expected = pandas.json_normalize([report], sep=".")
    assert list(df.columns) == list(expected.columns)
    assert "units.volume" in df.columns and df["units.volume"][0] == "cm^3"
    assert df["volume"][0] == pytest.approx(0.024) and df["mass"][0] == pytest.approx(0.048)


def test_directories_globs_and_nothing(folder):
    by_folder = meshvol.measure(folder)
    names = [os.path.relpath(f, folder) for f in by_folder["file"]]
    assert names == ["a_box.obj", "c_open.obj", "d_broken.obj", os.path.join("sub", "b_cube.obj")]
    by_glob = meshvol.measure(str(folder / "**" / "*_c*.obj"))
    assert [os.path.basename(f) for f in by_glob["file"]] == ["b_cube.obj"]
    # A pattern or a folder that gives no file is a row naming it, as the command's
    # failed input; only an empty list of paths is an empty frame.
    unmatched = meshvol.measure(str(folder / "*.stl"))
    assert unmatched["file"].tolist() == [str(folder / "*.stl")]
    assert "no mesh files matching this pattern" in unmatched["error"][0]
    (folder / "empty").mkdir()
    empty = meshvol.measure(folder / "empty")
    assert empty["file"].tolist() == [str(folder / "empty")]
    assert "no mesh files in this folder" in empty["error"][0]
    with pytest.warns(meshvol.MeshWarning, match="no mesh files"):
        nothing = meshvol.measure([])
    assert isinstance(nothing, pandas.DataFrame) and nothing.empty


def test_any_worker_count_gives_the_same_frame(folder, tmp_path):
    for k in range(12):
        write_obj(folder / f"sphere{k:02}.obj", *uv_sphere(radius=1 + k, rings=8, segments=12))
    one = meshvol.measure(folder, workers=1)
    many = meshvol.measure(folder, workers=3)
    default = meshvol.measure(folder)
    pandas.testing.assert_frame_equal(one, many)
    pandas.testing.assert_frame_equal(one, default)
    with pytest.raises(ValueError, match="workers"):
        meshvol.measure(folder, workers=0)
    # Threads are capped (one a file, 8 a core): a huge count starts no million threads.
    assert len(meshvol.measure([folder / "a_box.obj"], workers=10**6)) == 1


def test_unchecked(folder):
    df = meshvol.measure([folder / "a_box.obj"], check=False)
    assert df["volume"][0] == 24.0 and "closed" not in df.columns


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
def test_rows_are_the_commands_json_lines(folder):
    files = sorted(str(p) for p in folder.rglob("*.obj"))
    run = subprocess.run([COMMAND, "volume", *files, "--json"], capture_output=True, text=True)
    lines = [json.loads(line) for line in run.stdout.splitlines()]
    theirs = pandas.json_normalize(lines, sep=".")
    ours = meshvol.measure(files)
    pandas.testing.assert_frame_equal(ours, theirs)
