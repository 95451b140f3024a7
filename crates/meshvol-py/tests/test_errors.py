"""Bad input raises the MeshError family (or ValueError / TypeError for arguments) with
the command's messages, and never crashes the interpreter."""

import numpy as np
import pytest

import meshvol
from solids import box


def test_the_exception_family():
    assert issubclass(meshvol.MeshError, ValueError)
    assert issubclass(meshvol.ReadError, meshvol.MeshError)
    assert issubclass(meshvol.InvalidMeshError, meshvol.MeshError)
    assert meshvol.ReadError.__module__ == "meshvol"


@pytest.mark.parametrize(
    "vertices, faces, message",
    [
        (np.zeros((4, 2)), [[0, 1, 2]], r"^vertices must be an \(n, 3\) array of coordinates; got shape \(4, 2\)$"),
        (np.zeros(12), [[0, 1, 2]], r"got shape \(12,\)$"),
        (np.zeros((4, 3), dtype=complex), [[0, 1, 2]], "^vertices must be numbers .* got dtype complex128$"),
        (np.zeros((4, 3), dtype=bool), [[0, 1, 2]], "got dtype bool$"),
        (np.zeros((4, 3), dtype=np.longdouble), [[0, 1, 2]], "got dtype float(96|128)$"),
        ([[0, 0, 0], [1, 0]], [[0, 1, 2]], "^vertices cannot be read as an array"),
        (np.zeros((4, 3)), [[0, 1, 4]], "^face 0 uses vertex index 4, but there are only 4 vertices$"),
        (np.zeros((4, 3)), [[0, 1, 2], [0, -1, 2]], r"^face 1 uses vertex index -1, which is negative \(indices count from 0\)$"),
        (np.zeros((4, 3)), np.array([[0, 1, 2]], dtype=np.uint64) * 2**40, "^face 0 uses vertex index 1099511627776, but there are only 4 vertices$"),
        (np.zeros((4, 3)), np.array([[0.0, 1.0, 2.0]]), "^faces must be integer vertex indices; got dtype float64$"),
        (np.zeros((4, 3)), np.array([[0, 1]]), r"^faces must be an \(m, 3\) integer array .* got shape \(1, 2\)$"),
        (np.zeros((4, 3)), [[0, 1, 2], [0, 1]], "^face 1 has 2 vertices; a face needs at least 3$"),
        (np.zeros((4, 3)), [[0, 1, 2], [0, 1, 2.5, 3]], "^face 1 must be a sequence of integer vertex indices"),
        (np.zeros((4, 3)), [[0, 1, 2], "abc"], "^face 1 must be a sequence of integer vertex indices"),
        (np.zeros((4, 3)), 7, "^faces must be an"),
    ],
)
def test_invalid_arrays(vertices, faces, message):
    with pytest.raises(meshvol.InvalidMeshError, match=message):
        meshvol.Mesh(vertices, faces)


def test_non_finite_vertex_names_the_vertex():
    vertices, faces = box()
    vertices[5, 1] = np.nan
    with pytest.raises(meshvol.InvalidMeshError, match=r"^vertex 5 has a non-finite coordinate \(NaN\)$"):
        meshvol.Mesh(vertices, faces)
    vertices[5, 1] = -np.inf
    with pytest.raises(meshvol.InvalidMeshError, match=r"^vertex 5 has a non-finite coordinate \(-inf\)$"):
        meshvol.Mesh(vertices, faces)


def test_missing_file_names_the_path(tmp_path):
    path = tmp_path / "missing.stl"
    with pytest.raises(meshvol.ReadError) as caught:
        meshvol.load(path)
    e = caught.value
    assert e.path == str(path) and e.location is None
    assert str(e) == f"{path}: {e.reason}"


def test_malformed_obj_names_the_line(tmp_path):
    path = tmp_path / "bad.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1\nf 1 2 3\n")
    with pytest.raises(meshvol.ReadError) as caught:
        meshvol.load(str(path))
    e = caught.value
    assert (e.line, e.byte, e.face, e.location) == (3, None, None, "line 3")
    assert str(e) == f"{path}: line 3: {e.reason}"


def test_truncated_binary_stl_is_a_read_error(tmp_path):
    path = tmp_path / "short.stl"
    path.write_bytes(b"\0" * 80 + (5).to_bytes(4, "little") + b"\0" * 60)
    with pytest.raises(meshvol.ReadError) as caught:
        meshvol.load(path)
    assert caught.value.path == str(path)


@pytest.mark.parametrize(
    "call, error, message",
    [
        (lambda m: m.check(weld_tolerance=-1.0), ValueError, "weld_tolerance must be a non-negative number"),
        (lambda m: m.grid(cells=(0, 1, 1)), ValueError, r"cells must be three positive whole numbers; got \(0, 1, 1\)"),
        (lambda m: m.grid(), ValueError, r"give cells=\(nx, ny, nz\) or pitch=h"),
        (lambda m: m.grid(cells=(1, 1, 1), pitch=0.5), ValueError, "give cells or pitch, not both"),
        (lambda m: m.grid(pitch=-1.0), ValueError, "pitch must be positive"),
        (lambda m: m.grid(cells=(2, 2, 2), bounds=((0, 0, 0), (1, 0, 1))), meshvol.MeshError, "the bounds are empty along y"),
        (lambda m: m.profile(axis="w", levels=3), ValueError, "axis must be 'x', 'y' or 'z'; got 'w'"),
        (lambda m: m.profile(levels=0), ValueError, "levels must be at least 1; got 0"),
        (lambda m: m.profile(), ValueError, "give levels=n or step=h"),
        (lambda m: m.profile(step=float("nan")), ValueError, "step must be a positive number"),
        (lambda m: meshvol.union([m], tolerance=0.0), ValueError, "tolerance must be a positive number"),
        (lambda m: meshvol.union([]), meshvol.MeshError, "no bodies"),
        (lambda m: meshvol.union([m, 3]), TypeError, "expected a mesh"),
        (lambda m: meshvol.convex_hull([[0, 0, np.nan]]), meshvol.InvalidMeshError, "point 0 has a non-finite coordinate"),
        (lambda m: meshvol.polygon_area([[0, 0], [1, np.inf], [0, 1]]), meshvol.InvalidMeshError, "exterior: point 1 has a non-finite coordinate"),
        (lambda m: meshvol.polygon_area({"type": "LineString", "coordinates": [[0, 0], [1, 1]]}), meshvol.InvalidMeshError, "a LineString geometry has no area"),
    ],
)
def test_bad_arguments(call, error, message):
    with pytest.raises(error, match=message):
        call(meshvol.Mesh(*box()))


def test_garbage_never_crashes():
    """Random shapes, dtypes and values: every failure is an exception, never a crash."""
    rng = np.random.default_rng(11)
    good_v = [np.float64, np.float32, np.int64, np.float16]
    good_f = [np.int64, np.int8, np.uint16, np.uint64]
    bad = [object, complex, bool, np.float64]
    outcomes = set()
    for attempt in range(400):
        well_formed = attempt % 2 == 0
        if well_formed:
            n = int(rng.integers(3, 9))
            shape_v, shape_f = (n, 3), (int(rng.integers(1, 9)), 3)
            f = rng.integers(0, n, size=shape_f) + (rng.random(shape_f) < 0.02) * 9
        else:
            shape_v = tuple(rng.integers(0, 6, size=rng.integers(0, 4)))
            shape_f = tuple(rng.integers(0, 6, size=rng.integers(0, 4)))
            f = rng.integers(-1, 9, size=shape_f)
        v = np.asarray(rng.normal(size=shape_v) * 10.0 ** rng.integers(-3, 300))
        v[rng.random(shape_v) < 0.01] = np.nan
        with np.errstate(all="ignore"):
            v = v.astype((good_v if well_formed else good_v + bad)[rng.integers(4)])
            f = f.astype((good_f if well_formed else good_f + bad)[rng.integers(4)])
        try:
            mesh = meshvol.Mesh(v, f)
            mesh.mass_properties(exact=bool(rng.integers(2)))
            mesh.check()
            mesh.grid(cells=(2, 2, 2), bounds=((-1, -1, -1), (1, 1, 1)))
            outcomes.add("measured")
        except (meshvol.MeshError, ValueError, TypeError) as e:
            outcomes.add(type(e).__name__)
    assert outcomes == {"measured", "InvalidMeshError", "MeshError"}
