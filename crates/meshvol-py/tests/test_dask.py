"""meshvol.dask on a two-process dask.distributed cluster: the chunked grid against the
single-process Mesh.grid (bit for bit), its Zarr copy read back with zarr-python, and
the sum of the cells against a tilted box's volume in closed form. Also the CLI's Zarr
output against its own .npy (where MESHVOL_BIN names the command)."""

import os
import pickle
import subprocess

import numpy as np
import pytest

import meshvol
from solids import box, uv_sphere

dask = pytest.importorskip("dask")
distributed = pytest.importorskip("distributed")
zarr = pytest.importorskip("zarr")
import meshvol.dask  # noqa: E402  (needs the optional dependencies above)


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


def write_obj(path, vertices, faces):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in faces.tolist()]
    path.write_text("\n".join(lines) + "\n")


def tilted_box(size):
    """A box with edges `size`, turned about two axes: its volume is the product of the
    edges, and no face lies on a grid plane."""
    vertices, faces = box((0, 0, 0), size)
    a, b = 0.4, 0.25
    rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    rx = np.array([[1, 0, 0], [0, np.cos(b), -np.sin(b)], [0, np.sin(b), np.cos(b)]])
    return vertices @ (rx @ rz).T + [0.3, -0.2, 0.1], faces


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, memory_limit="1GB", processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        yield client


@pytest.fixture(scope="module")
def sphere_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("dask") / "sphere.obj"
    write_obj(path, *uv_sphere(radius=1.0, rings=24, segments=48, centre=(0.1, -0.2, 0.3)))
    return path


def test_chunks_from_a_file_are_the_single_process_grid(client, sphere_file):
    whole = meshvol.load(str(sphere_file)).grid(cells=(20, 17, 23))
    cells = meshvol.dask.grid(sphere_file, cells=(20, 17, 23), chunks=(6, 5, -1))
    assert cells.numblocks == (4, 4, 1)
    assert same_bits(cells.compute(), whole)
    # Chunks split along z too, and fractions.
    split = meshvol.dask.grid(sphere_file, cells=(20, 17, 23), chunks=(7, 17, 8), fraction=True)
    expected = meshvol.load(str(sphere_file)).grid(cells=(20, 17, 23), fraction=True)
    assert same_bits(split.compute(), expected)


def test_chunks_from_a_mesh_with_given_bounds(client):
    mesh = meshvol.Mesh(*uv_sphere(radius=1.0, rings=16, segments=32))
    bounds = ((-1.2, -0.9, -1.1), (0.8, 1.3, 0.7))
    whole = mesh.grid(cells=(9, 12, 10), bounds=bounds, check=False)
    cells = meshvol.dask.grid(mesh, cells=(9, 12, 10), bounds=bounds, chunks=4, check=False)
    assert same_bits(cells.compute(), whole)


def test_zarr_copy_and_the_closed_form_volume(client, tmp_path):
    size = (1.3, 0.7, 0.9)
    mesh = meshvol.Mesh(*tilted_box(size))
    cells = meshvol.dask.grid(mesh, cells=(16, 14, 12), chunks=(5, 7, 12))
    target = tmp_path / "cells.zarr"
    cells.to_zarr(str(target))
    stored = zarr.open_array(str(target), mode="r")
    assert stored.shape == (16, 14, 12) and stored.chunks == (5, 7, 12)
    whole = mesh.grid(cells=(16, 14, 12))
    assert same_bits(stored[...], whole)
    assert float(cells.sum().compute()) == pytest.approx(np.prod(size), rel=1e-13)


def test_a_mesh_pickles_as_its_arrays():
    mesh = meshvol.Mesh(*box((0, 0, 0), (2, 1, 1)))
    again = pickle.loads(pickle.dumps(mesh))
    assert same_bits(again.vertices, mesh.vertices)
    assert np.array_equal(again.faces, mesh.faces)
    assert again.mass_properties().volume == 2.0


def test_a_changed_file_is_refused(tmp_path):
    path = tmp_path / "box.obj"
    write_obj(path, *box())
    cells = meshvol.dask.grid(path, cells=(2, 2, 2), chunks=1)
    write_obj(path, *box((0, 0, 0), (2, 2, 2)))
    os.utime(path, ns=(1, 1))
    with pytest.raises(meshvol.MeshError, match="box.obj: the file changed"):
        cells.compute(scheduler="sync")


COMMAND = os.environ.get("MESHVOL_BIN")


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
def test_the_commands_zarr_is_its_npy(sphere_file, tmp_path):
    npy, store = tmp_path / "cells.npy", tmp_path / "cells.zarr"
    for out, extra in ((npy, []), (store, ["--chunks", "4,5,6"])):
        run = subprocess.run(
            [COMMAND, "grid", str(sphere_file), "--cells", "9,10,11", "--out", str(out), *extra],
            capture_output=True,
            text=True,
        )
        assert run.returncode == 0, run.stderr
    stored = zarr.open_group(str(store), mode="r")["volume"]
    assert stored.shape == (9, 10, 11) and stored.chunks == (4, 5, 6)
    assert same_bits(stored[...], np.load(npy))


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
def test_the_commands_moments_zarr_is_its_npz(sphere_file, tmp_path):
    """grid --moments --out cells.zarr: a group of the .npz's arrays, the same bits, for
    chunks that divide the grid and chunks that do not; bounds through the sphere, so
    that the far faces' apertures are not zero."""
    grid = ["grid", str(sphere_file), "--cells", "8,10,11", "--moments",
            "--bounds", "-0.7,-1.3,-0.8,0.6,0.9,1.1"]
    npz = tmp_path / "cells.npz"
    run = subprocess.run([COMMAND, *grid, "--out", str(npz)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    arrays = np.load(npz)
    assert np.any(arrays["aperture_x"][-1] != 0) and np.any(arrays["aperture_z"][:, :, -1] != 0)
    for chunks in ((4, 5, 6), (3, 4, 11), (8, 10, 11), (1, 3, 2)):
        store = tmp_path / f"cells-{'-'.join(map(str, chunks))}.zarr"
        run = subprocess.run(
            [COMMAND, *grid, "--out", str(store), "--chunks", ",".join(map(str, chunks))],
            capture_output=True,
            text=True,
        )
        assert run.returncode == 0, run.stderr
        group = zarr.open_group(str(store), mode="r")
        assert same_bits(group.attrs["origin"], arrays["origin"])
        assert same_bits(group.attrs["cell_size"], arrays["cell_size"])
        names = sorted(set(arrays.files) - {"origin", "cell_size"})
        coordinates = {"x", "y", "z", "x_face", "y_face", "z_face"}
        assert sorted(set(group.array_keys()) - coordinates) == names
        for name in names:
            stored = group[name]
            assert stored.chunks[:3] == chunks, name
            assert same_bits(stored[...], arrays[name]), name
    # The dimension names make one xarray Dataset (apertures on x_face, y_face, z_face).
    xarray = pytest.importorskip("xarray")
    data = xarray.open_zarr(str(store), consolidated=True)
    assert dict(data.sizes) == {"x": 8, "y": 10, "z": 11, "x_face": 9, "y_face": 11,
                                "z_face": 12, "component": 3}
    assert same_bits(data["aperture_y"].values, arrays["aperture_y"])


def test_measure_many_files_on_the_cluster(client, tmp_path):
    pandas = pytest.importorskip("pandas")
    pytest.importorskip("dask.dataframe")
    volumes = {}
    for k in range(7):
        size = (1 + k, 2, 0.5 * (k + 1))
        write_obj(tmp_path / f"box{k}.obj", *box((k, 0, 0), np.add((k, 0, 0), size)))
        volumes[f"box{k}.obj"] = float(np.prod(size))
    (tmp_path / "broken.obj").write_text("v 0 0 0\nf 1 2 3\n")
    frame = meshvol.dask.measure(str(tmp_path / "*.obj"), files_per_partition=3)
    assert frame.npartitions == 3
    # Lazy and filterable before computing.
    big = frame[frame["volume"] > 5.0].compute()
    assert sorted(os.path.basename(f) for f in big["file"]) == sorted(n for n, v in volumes.items() if v > 5)
    result = frame.compute()
    names = [os.path.basename(f) for f in result["file"]]
    assert names == sorted(list(volumes) + ["broken.obj"])
    for name, volume, error in zip(names, result["volume"], result["error"]):
        if name == "broken.obj":
            assert np.isnan(volume) and "line 2" in error
        else:
            assert volume == pytest.approx(volumes[name], rel=1e-15) and pandas.isna(error)
    # The same rows as meshvol.measure on one machine, in the fixed columns.
    local = meshvol.measure(str(tmp_path / "*.obj"))
    assert set(local.columns) - {"units"} <= set(result.columns)
    for column in ["file", "volume", "area", "verdict", "error"]:
        assert local[column].astype(object).where(local[column].notna(), None).tolist() == \
            result[column].astype(object).where(result[column].notna(), None).tolist()
    assert str(result["vertices"].dtype) == "Int64" and str(result["closed"].dtype) == "boolean"
    frame.to_parquet(tmp_path / "table.parquet")
    back = pandas.read_parquet(tmp_path / "table.parquet")
    assert back["volume"].tolist()[:3] == result["volume"].tolist()[:3] and len(back) == 8


def test_measure_with_no_files_is_an_empty_frame(tmp_path):
    pytest.importorskip("dask.dataframe")
    with pytest.warns(meshvol.MeshWarning, match="no mesh files"):
        frame = meshvol.dask.measure([])
    assert len(frame.compute()) == 0 and "volume" in frame.columns
    # A pattern that matches nothing is a row naming it, as in meshvol.measure.
    unmatched = meshvol.dask.measure(str(tmp_path / "*.stl")).compute()
    assert unmatched["file"].tolist() == [str(tmp_path / "*.stl")]
    assert "no mesh files matching this pattern" in unmatched["error"][0]
