"""One argument convention and Python's conventions (issue 31, items 1 and 2): vector
and box arguments from any array-like, errors naming the argument and the shape, every
default shown by help(), bounds as (2, 3) arrays, principal moments ascending with their
axes in 2D as in 3D, counts named *_count, warnings at the caller's line, missing files
as FileNotFoundError, load() from paths of every kind and file objects, Grid."""

import inspect
import io
import math
import os
import pathlib
import sys
import warnings

import numpy as np
import pytest

import meshvol
from solids import BOX_TRIANGLES, TETRA_FACES, box, box_inertia

BOX_OBJ = "".join(f"v {x} {y} {z}\n" for x, y, z in box((0, 0, 0), (2, 3, 4))[0]) + "".join(
    "f " + " ".join(str(i + 1) for i in t) + "\n" for t in BOX_TRIANGLES
)


def box_mesh(lo=(0, 0, 0), hi=(2, 3, 4)):
    return meshvol.Mesh(*box(lo, hi))


# 31.1: arguments


@pytest.mark.parametrize(
    "bounds",
    [
        ((0, 0, 0), (2, 3, 4)),
        [[0, 0, 0], [2, 3, 4]],
        np.array([[0, 0, 0], [2, 3, 4]], dtype=np.float32),
        np.array([[0, 0, 0], [2, 3, 4]], dtype=np.int64),
        np.asfortranarray([[0.0, 0, 0], [2, 3, 4]]),
    ],
)
def test_bounds_from_any_array_like(bounds):
    grid = box_mesh().grid(cells=np.array([2, 3, 4]), bounds=bounds)
    # Each cell of the 2 x 3 x 4 box on a grid of unit cells is full.
    assert np.array_equal(np.asarray(grid), np.ones((2, 3, 4)))


def test_trimesh_bounds_are_accepted():
    trimesh = pytest.importorskip("trimesh")
    tm = trimesh.creation.box(extents=(2, 3, 4))
    mesh = meshvol.Mesh(tm)
    grid = mesh.grid(cells=(2, 3, 4), bounds=tm.bounds)
    assert np.allclose(grid.values, 1.0) and np.allclose(grid.bounds, tm.bounds)


def test_vectors_from_any_array_like():
    mesh = box_mesh()
    by_tuple = mesh.below(volume=6.0, direction=(0, 0, 1))
    for direction in ([0, 0, 1], np.array([0.0, 0.0, 1.0]), np.array([0, 0, 2], dtype=np.int32)):
        assert mesh.below(volume=6.0, direction=direction).level == by_tuple.level == 1.0
    plane = mesh.below(plane=np.array([0.0, 0.0, 1.0, 2.0]))
    assert plane.volume == 12.0  # half of 2 x 3 x 4
    # Every form the command's --plane takes names the same plane z = 2.
    for form in ("z=2", "0,0,1,2", "0,0,2,0,0,1", [[0, 0, 2], [0, 0, 1]], (0, 0, 1, 2)):
        assert mesh.below(plane=form).volume == 12.0, form
    # A tilted plane through the box's centre (1, 1.5, 2) halves it too.
    assert mesh.below(plane="1,1.5,2,1,1,1").volume == pytest.approx(12.0, rel=1e-15)
    region = mesh.grid(cells=(2, 3, 4), region=np.array([[0, 1], [0, 3], [0, 4]]))
    assert region.shape == (1, 3, 4)
    assert mesh.grid(pitch=np.array([1.0, 1.0, 2.0])).shape == (2, 3, 2)


@pytest.mark.parametrize(
    "call, exception, message",
    [
        (lambda m: m.grid(cells=(2, 2, 2), bounds=(0, 0, 0)), ValueError,
         r"bounds must be .*shape \(2, 3\); got shape \(3,\)"),
        (lambda m: m.grid(cells=(2, 2, 2), bounds=[[0, 0], [1, 1]]), ValueError,
         r"bounds must be .*shape \(2, 3\); got shape \(2, 2\)"),
        (lambda m: m.grid(cells=(2, 2, 2), bounds=[["a", "b", "c"], ["d", "e", "f"]]), TypeError,
         r"bounds must be numbers.*\(2, 3\); got dtype <U1"),
        (lambda m: m.grid(cells=(2, 2)), ValueError, r"cells must be \(nx, ny, nz\).*shape \(3,\); got shape \(2,\)"),
        (lambda m: m.grid(cells=(2.5, 2, 2)), TypeError, r"cells must be whole numbers"),
        (lambda m: m.grid(cells=(2, 2, 2), region=(0, 1)), ValueError, r"region must be .*shape \(3, 2\)"),
        (lambda m: m.below(volume=1.0, direction=(0, 1)), ValueError,
         r"direction must be \(x, y, z\), an array-like of shape \(3,\); got shape \(2,\)"),
        (lambda m: m.below(plane=np.eye(3)), ValueError, r"plane must be .*got shape \(3, 3\)"),
        (lambda m: m.below(plane="z=two"), ValueError, r"z=H"),
        (lambda m: m.below(volume=1.0, direction=[1j, 0, 1]), TypeError, r"direction must be numbers.*complex128"),
    ],
)
def test_wrong_shapes_and_dtypes_name_the_argument(call, exception, message):
    with pytest.raises(exception, match=message):
        call(box_mesh())


def public_callables():
    for name in meshvol.__all__:
        obj = getattr(meshvol, name)
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for attr, member in vars(obj).items():
                if callable(member) and not attr.startswith("_"):
                    yield f"{name}.{attr}", getattr(obj, attr)
        elif callable(obj) and not inspect.isclass(obj):
            yield name, obj


@pytest.mark.parametrize("name, function", list(public_callables()))
def test_every_default_shows_in_help(name, function):
    signature = inspect.signature(function)
    text = str(signature)
    assert "Ellipsis" not in text and "..." not in text, f"{name}{text}"
    for p in signature.parameters.values():
        assert p.default is not Ellipsis, f"{name}: {p.name}"


def test_below_shows_its_direction():
    assert "direction=(0.0, 0.0, 1.0)" in str(inspect.signature(meshvol.Mesh.below))


def test_bounds_is_a_2_by_3_array():
    vertices, faces = box((1, 2, 3), (4, 6, 8))
    mp = meshvol.Mesh(vertices, faces).mass_properties()
    assert isinstance(mp.bounds, np.ndarray) and mp.bounds.shape == (2, 3)
    assert np.array_equal(mp.bounds, [vertices.min(axis=0), vertices.max(axis=0)])
    lo, hi = mp.bounds  # unpacks as the (min, max) pair it was
    assert lo.tolist() == [1, 2, 3] and hi.tolist() == [4, 6, 8]
    assert mp.to_dict()["bounds"] == {"min": [1.0, 2.0, 3.0], "max": [4.0, 6.0, 8.0]}


def test_principal_moments_ascend_with_their_axes_in_3d():
    mp = box_mesh().mass_properties()
    expected = np.sort(np.diag(box_inertia((2, 3, 4))))
    assert np.allclose(mp.principal_moments, expected)
    for k in range(3):  # I a = λ a for each row
        axis = mp.principal_axes[k]
        assert np.allclose(mp.inertia @ axis, mp.principal_moments[k] * axis)


@pytest.mark.parametrize("degrees", [0.0, 30.0, 100.0])
def test_principal_moments_ascend_with_their_axes_in_2d(degrees):
    # A 4 x 2 rectangle turned by `degrees`: b h³ / 12 about its long axis (the smaller
    # moment, 4·8/12) and about its short axis (the larger, 2·64/12).
    t = math.radians(degrees)
    rotation = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
    corners = np.array([[-2, -1], [2, -1], [2, 1], [-2, 1]], dtype=float) @ rotation.T + [5, 7]
    a = meshvol.polygon_area(corners)
    assert np.allclose(a.principal_moments, [4 * 8 / 12, 2 * 64 / 12])
    long_axis = rotation @ [1.0, 0.0]
    assert np.isclose(abs(a.principal_axes[0] @ long_axis), 1.0)
    assert np.isclose(abs(a.principal_axes[1] @ long_axis), 0.0)
    assert np.isclose(np.linalg.det(a.principal_axes), 1.0)
    # The moment about the line through the centroid along unit u = (c, s) is
    # ∫ (c·y − s·x)² dA = c²·ix + s²·iy − 2cs·ixy.
    for k in range(2):
        c, s = a.principal_axes[k]
        moment = c * c * a.ix + s * s * a.iy - 2 * c * s * a.ixy
        assert np.isclose(moment, a.principal_moments[k])


def test_counts_are_named_count():
    mp = meshvol.Mesh(*box()).mass_properties()
    assert (mp.vertex_count, mp.face_count, mp.triangle_count) == (8, 12, 12)
    assert "vertex_count" in dir(mp) and "vertices" not in dir(mp)
    with pytest.warns(DeprecationWarning, match=r"MassProperties.vertices is a count.*vertex_count"):
        assert mp.vertices == 8
    with pytest.warns(DeprecationWarning, match=r"face_count"):
        assert mp.faces == 12
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert mp.triangles == 12  # no array of that name: kept as it is
    assert mp.to_dict()["vertices"] == 8  # the command's keys stay
    (shell,) = mp.shell_details
    assert isinstance(shell, meshvol.Shell) and shell.face_count == 12
    assert shell["volume"] == 1.0  # shell_details were dicts
    hull = meshvol.convex_hull(box()[0])
    assert (hull.point_count, hull.hull_vertex_count, hull.hull_face_count) == (8, 8, 12)


# 31.2: warnings at the caller's line


def open_box():
    vertices, faces = box()
    return meshvol.Mesh(vertices, faces[:-1])  # one triangle missing: capped, warned


@pytest.mark.parametrize(
    "measure",
    [
        lambda m: m.mass_properties(),
        lambda m: m.grid(cells=(2, 2, 2)),
        lambda m: m.profile(levels=2),
        lambda m: m.below(plane=(0, 0, 1, 0.5)),
        lambda m: m.section("z=0.5"),
        lambda m: meshvol.union([m]),
        lambda m: m.check().mass_properties(),
    ],
)
def test_warnings_point_at_the_callers_line(measure):
    mesh = open_box()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        measure(mesh)
    line = measure.__code__.co_firstlineno  # the lambda's line calls meshvol
    ours = [w for w in caught if issubclass(w.category, meshvol.MeshWarning)]
    assert ours, "no MeshWarning"
    for w in ours:
        assert (w.filename, w.lineno) == (__file__, line), (w.filename, w.lineno, line)


def helper_in_user_code(mesh):
    return mesh.mass_properties()  # the line warned about


def test_warnings_point_at_the_line_in_the_users_function():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        helper_in_user_code(open_box())
    (w,) = [w for w in caught if issubclass(w.category, meshvol.MeshWarning)]
    first = helper_in_user_code.__code__.co_firstlineno
    assert (w.filename, w.lineno) == (__file__, first + 1)


# 31.2: files


def test_a_missing_file_is_file_not_found_and_mesh_error(tmp_path):
    path = tmp_path / "missing.stl"
    with pytest.raises(FileNotFoundError) as caught:
        meshvol.load(path)
    e = caught.value
    assert isinstance(e, OSError) and isinstance(e, meshvol.MeshError)
    assert isinstance(e, meshvol.ReadError) and isinstance(e, meshvol.MeshFileNotFoundError)
    assert e.errno == 2 and e.filename == str(path) and e.path == str(path)
    assert str(path) in str(e) and "os error" not in str(e)
    # Caught as before: ReadError, MeshError, ValueError.
    for kind in (meshvol.ReadError, meshvol.MeshError, ValueError, OSError):
        with pytest.raises(kind):
            meshvol.load(str(path))


def test_a_directory_is_is_a_directory_error(tmp_path):
    with pytest.raises(IsADirectoryError) as caught:
        meshvol.load(tmp_path)
    assert isinstance(caught.value, meshvol.ReadError)


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="root reads any file")
def test_an_unreadable_file_is_permission_error(tmp_path):
    path = tmp_path / "locked.obj"
    path.write_text(BOX_OBJ)
    path.chmod(0)
    with pytest.raises(PermissionError) as caught:
        meshvol.load(path)
    assert isinstance(caught.value, meshvol.MeshError) and caught.value.filename == str(path)


def test_load_takes_every_kind_of_path_and_file_objects(tmp_path):
    path = tmp_path / "box.obj"
    path.write_text(BOX_OBJ)
    volumes = set()
    for given in (str(path), os.fsencode(path), path, pathlib.PurePath(path)):
        volumes.add(meshvol.load(given).mass_properties().volume)
    with open(path, "rb") as f:
        from_file = meshvol.load(f)
    assert from_file.file == str(path) and from_file.format == "obj"
    volumes.add(from_file.mass_properties().volume)
    stream = meshvol.load(io.BytesIO(BOX_OBJ.encode()), file_type="obj")
    assert stream.format == "obj"
    volumes.add(stream.mass_properties().volume)
    assert volumes == {24.0}


def test_load_file_objects_by_content_and_errors(tmp_path):
    # Binary STL recognised by its content without a name or file_type.
    trimesh = pytest.importorskip("trimesh")
    data = trimesh.Trimesh(*box((0, 0, 0), (2, 3, 4))).export(file_type="stl")
    assert meshvol.load(io.BytesIO(data)).mass_properties().volume == pytest.approx(24.0)
    assert meshvol.load(io.BytesIO(data), file_type=".STL").format == "stl-binary"
    with pytest.raises(ValueError, match="file_type must be one of stl, obj"):
        meshvol.load(io.BytesIO(data), file_type="dwg")
    with pytest.raises(TypeError, match="binary mode"):
        meshvol.load(io.StringIO(BOX_OBJ))
    with pytest.raises(TypeError, match="load\\(\\) takes a path"):
        meshvol.load(42)
    with pytest.raises(meshvol.ReadError, match="<file object>"):
        meshvol.load(io.BytesIO(b"v 0 0\n"), file_type="obj")


# 31.2: Grid


def test_grid_is_an_object_with_its_cells_place():
    mesh = box_mesh((1, 1, 1), (3, 4, 5))
    grid = mesh.grid(pitch=0.75)  # the 2 x 3 x 4 box: 3 x 4 x 6 cells of 0.75 from (1, 1, 1)
    assert isinstance(grid, meshvol.Grid)
    assert grid.values.shape == grid.shape == (3, 4, 6)
    assert grid.origin.tolist() == [1, 1, 1] and grid.spacing.tolist() == [0.75] * 3
    assert np.allclose(grid.bounds, [[1, 1, 1], [1 + 3 * 0.75, 1 + 4 * 0.75, 1 + 6 * 0.75]])
    # The cells' volumes: each the overlap of its cell with the box, computed here.
    x, y, z = grid.centers()
    lo = grid.origin + np.stack(np.meshgrid(*[np.arange(n) for n in grid.shape], indexing="ij"), -1) * 0.75
    overlap = np.prod(np.clip(np.minimum(lo + 0.75, [3, 4, 5]) - np.maximum(lo, [1, 1, 1]), 0, None), axis=-1)
    assert np.allclose(grid.values, overlap)
    assert np.allclose(x, 1 + 0.375 + 0.75 * np.arange(3))
    # NumPy code written for the bare array keeps working.
    assert np.asarray(grid) is grid.values
    assert float(grid.sum()) == pytest.approx(24.0) and float(np.sum(grid)) == pytest.approx(24.0)
    assert (grid == grid.values).all() and grid[0].shape == (4, 6) and len(grid) == 3
    assert np.array_equal(grid.ravel(), grid.values.ravel()) and grid.dtype == np.float64
    assert isinstance(grid * 2, np.ndarray)


def test_a_blocks_origin_is_its_first_corner():
    mesh = box_mesh()
    whole = mesh.grid(cells=(4, 6, 8))
    block = mesh.grid(cells=(4, 6, 8), region=((1, 3), (2, 6), (0, 8)))
    assert np.array_equal(block.values, whole.values[1:3, 2:6, 0:8])
    assert block.origin.tolist() == [0.5, 1.0, 0.0]
    assert np.allclose(block.bounds, [[0.5, 1, 0], [1.5, 3, 4]])


def test_grid_to_xarray():
    grid = box_mesh().grid(cells=(2, 3, 4), fraction=True)
    try:
        import xarray  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pip install xarray"):
            grid.to_xarray()
        return
    array = grid.to_xarray()
    assert array.dims == ("x", "y", "z") and array.name == "fraction"
    assert array.x.values.tolist() == [0.5, 1.5]
    assert float(array.sel(x=1.5, y=2.5, z=3.5)) == 1.0


def test_attributes_are_to_dicts_bits():
    from solids import uv_sphere

    mp = meshvol.Mesh(*uv_sphere(rings=9, segments=13, centre=(1000.1, 2.3, -3.7))).mass_properties(
        density=7.3, timings=True
    )
    d = mp.to_dict()
    floats = {k: v for k, v in d.items() if isinstance(v, float)}
    assert len(floats) >= 5
    for key, value in floats.items():
        assert np.float64(getattr(mp, key)).view(np.uint64) == np.float64(value).view(np.uint64), key
    assert np.array_equal(mp.principal_moments, d["principal_moments"])
    assert np.array_equal(mp.centroid, d["centroid"]) and mp.timings == d["timings"]
