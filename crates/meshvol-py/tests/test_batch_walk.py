"""meshvol.measure and meshvol.dask.measure read a folder as the command does (issue 48,
item 3): the command's own walk (compressed files, extensions in any case, hidden files
and .git/ passed over, --glob), so meshvol.measure(folder) gives the rows that
`meshvol volume -r folder --json` prints, in the same order. Compared with the file
list and the boxes' volumes written out by hand, and with the command's JSON lines."""

import ast
import bz2
import gzip
import json
import os
import struct
import subprocess
import zipfile
from pathlib import Path

import numpy as np
import pytest

import meshvol
from solids import box

pandas = pytest.importorskip("pandas")
COMMAND = os.environ.get("MESHVOL_BIN")
CORPUS = Path(__file__).resolve().parents[4] / "shared" / "corpus" / "trimesh-models"
needs_command = pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")


def stl_bytes(length):
    """A binary STL of the box [0, length] x [0, 1] x [0, 1] (volume `length`)."""
    vertices, faces = box((0, 0, 0), (length, 1, 1))
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    data = np.zeros(len(faces), dtype=record)
    data["corners"] = vertices[faces]
    return b"\0" * 80 + struct.pack("<I", len(faces)) + data.tobytes()


# What the walk reads of the folder below, in the command's order (sorted by path,
# upper case first), and each file's volume.
READ = {
    "B_BOX.STL": 2.0,
    "a_cube.stl": 1.0,
    "c.stl.gz": 3.0,
    "d.zip": 4.0,
    "e.stl.bz2": 5.0,
    "sub/f.stl": 6.0,
}


@pytest.fixture
def folder(tmp_path):
    """Boxes in every case and compressed form, beside boxes in hidden places (a hidden
    file, a hidden folder, .git/) and files that are not meshes, and an empty folder."""
    root = tmp_path / "parts"
    for sub in ["sub", ".hidden", ".git/objects", "sub/empty"]:
        (root / sub).mkdir(parents=True)
    (root / "a_cube.stl").write_bytes(stl_bytes(1))
    (root / "B_BOX.STL").write_bytes(stl_bytes(2))
    (root / "c.stl.gz").write_bytes(gzip.compress(stl_bytes(3)))
    with zipfile.ZipFile(root / "d.zip", "w") as archive:
        archive.writestr("inside.stl", stl_bytes(4))
    (root / "e.stl.bz2").write_bytes(bz2.compress(stl_bytes(5)))
    (root / "sub" / "f.stl").write_bytes(stl_bytes(6))
    for hidden in [".g.stl", ".hidden/h.stl", ".git/objects/i.stl", "sub/.j.stl"]:
        (root / hidden).write_bytes(stl_bytes(7))
    (root / "notes.txt").write_text("not a mesh")
    (root / "k.gz").write_bytes(gzip.compress(b"not a mesh either"))
    return root


def command_rows(*args):
    """The command's JSON lines, as meshvol.measure's frame, and its exit status."""
    run = subprocess.run([COMMAND, "volume", *map(str, args), "--json"], capture_output=True, text=True)
    lines = [json.loads(line) for line in run.stdout.splitlines()]
    return pandas.json_normalize(lines, sep="."), run.returncode


def below(root, files):
    return [Path(f).relative_to(root).as_posix() for f in files]


def test_a_folder_gives_the_files_the_command_reads(folder):
    assert below(folder, meshvol._batch.mesh_files(folder)) == list(READ)
    assert below(folder, meshvol._batch.mesh_files(folder, recursive=False)) == list(READ)[:-1]
    frame = meshvol.measure(folder)
    assert below(folder, frame["file"]) == list(READ)
    assert frame["volume"].tolist() == list(READ.values())
    assert "error" not in frame.columns
    # MESH_EXTENSIONS is the same rule, as name endings, for the files not hidden.
    shown = [p for p in folder.rglob("*") if p.is_file() and not any(
        part.startswith(".") for part in p.relative_to(folder).parts)]
    by_ending = sorted(p.name.lower() for p in shown if p.name.lower().endswith(meshvol._batch.MESH_EXTENSIONS))
    assert by_ending == sorted(Path(n).name.lower() for n in READ)


def test_patterns_are_chosen_as_a_folders_files(folder):
    everything = meshvol.measure(str(folder / "**" / "*"))
    assert below(folder, everything["file"]) == list(READ)
    stl = meshvol.measure(str(folder / "**" / "*.stl"))
    assert below(folder, stl["file"]) == ["a_cube.stl", "sub/f.stl"]
    # glob= matches in any case (as the extensions do); a pattern as a path is Python's glob.
    kept = meshvol.measure(folder, glob=["*.stl*", "!a*"])
    assert below(folder, kept["file"]) == ["B_BOX.STL", "c.stl.gz", "e.stl.bz2", "sub/f.stl"]
    with pytest.raises(ValueError, match="glob"):
        meshvol.measure(folder, glob="a[")


def test_nothing_found_is_a_row_naming_it(folder):
    empty = folder / "sub" / "empty"
    frame = meshvol.measure([empty, folder / "a_cube.stl", str(folder / "*.3mf")])
    assert frame["file"].tolist() == [str(empty), str(folder / "*.3mf"), str(folder / "a_cube.stl")]
    assert frame["error"][0].startswith(f"{empty}: no mesh files in this folder (.stl,")
    assert frame["error"][1].startswith(f"{folder / '*.3mf'}: no mesh files matching this pattern")
    assert frame["volume"][2] == 1.0
    with pytest.warns(meshvol.MeshWarning, match="no mesh files in this folder"):
        assert meshvol._batch.mesh_files(empty) == []
    with pytest.warns(meshvol.MeshWarning, match="the DataFrame is empty"):
        assert meshvol.measure([]).empty


@needs_command
@pytest.mark.parametrize(
    "options",
    [{}, {"recursive": False}, {"glob": ["*.stl*", "!a*"]}, {"glob": "sub/*"}, {"check": False}],
    ids=["recursive", "flat", "globs", "path-glob", "no-check"],
)
def test_rows_are_the_commands_for_a_folder(folder, options):
    flags = [] if options.get("recursive") is False else ["-r"]
    globs = options.get("glob", [])
    for pattern in [globs] if isinstance(globs, str) else globs:
        flags += ["--glob", pattern]
    if options.get("check") is False:
        flags.append("--no-check")
    theirs, status = command_rows(folder, *flags)
    assert status == 0
    pandas.testing.assert_frame_equal(meshvol.measure(folder, **options), theirs)


@needs_command
def test_failed_folders_are_the_commands_rows_in_its_order(folder):
    empty = folder / "sub" / "empty"
    paths = [folder / "sub", empty, folder / "a_cube.stl", folder / "missing.stl"]
    theirs, status = command_rows("-r", *paths)
    assert status == 1
    ours = meshvol.measure(paths)
    pandas.testing.assert_frame_equal(ours, theirs)
    assert ours["file"][0] == str(empty) and ours["error"].notna().tolist() == [True, False, False, True]


@needs_command
def test_dask_gives_the_commands_rows(folder):
    pytest.importorskip("dask.dataframe")
    import meshvol.dask

    empty = folder / "sub" / "empty"
    theirs, _ = command_rows("-r", folder, empty)
    frame = meshvol.dask.measure([folder, empty], files_per_partition=4).compute()
    assert frame["file"].tolist() == theirs["file"].tolist()
    assert below(folder, frame["file"][1:]) == list(READ)
    # The dask frame's columns are fixed; 'units' (null without units=) is left out.
    assert set(theirs.columns) - set(frame.columns) <= {"units"}
    for column in set(theirs.columns) & set(frame.columns):
        mine = frame[column].astype(object).where(frame[column].notna(), None).tolist()
        command = theirs[column].astype(object).where(theirs[column].notna(), None).tolist()
        # Dask keeps object columns as text (its `dataframe.convert-string`, which lets
        # to_parquet infer one schema): a list cell arrives as the list's repr.
        mine = [ast.literal_eval(m) if isinstance(c, list) else m for m, c in zip(mine, command)]
        assert mine == command, column


@needs_command
@pytest.mark.skipif(not CORPUS.is_dir(), reason=f"no corpus at {CORPUS}")
def test_the_corpus_gives_the_commands_rows():
    # Unchecked: the corpus is read whole, and reading is what is compared (the check
    # of every file in a debug build would take minutes).
    theirs, _ = command_rows("-r", "--no-check", CORPUS)
    ours = meshvol.measure(CORPUS, check=False)
    assert len(ours) == len(theirs) > 100
    assert any(f.lower().endswith(".zip") for f in ours["file"])
    pandas.testing.assert_frame_equal(ours, theirs)
