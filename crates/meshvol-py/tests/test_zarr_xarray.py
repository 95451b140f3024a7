"""The command's `.zarr` grids open in xarray (issue 52, item 3): `meshvol grid --out
cells.zarr` (volumes, fractions) and `--moments` open with xarray.open_zarr, with no
warning (the metadata consolidated), as Datasets with the cells' centres as the `x`, `y`,
`z` coordinates and the faces' planes as `x_face`, `y_face`, `z_face`; the coordinates
against origin + (i + 0.5)·cell_size computed here from the bounds asked for (in mm,
reported in cm: --units mm:cm), and the arrays and names against Grid.to_xarray() and
CutCells.to_xarray() of the same grid."""

import os
import subprocess
import warnings

import numpy as np
import pytest

import meshvol
from solids import uv_sphere

xarray = pytest.importorskip("xarray")
pytest.importorskip("zarr")

COMMAND = os.environ.get("MESHVOL_BIN")
pytestmark = pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")

CELLS = (7, 5, 6)
# The grid's box in mm (round the sphere: 10 mm about (0.5, -1, 1.5)), and in cm.
LO_MM, HI_MM = np.array([-10.0, -11.5, -9.0]), np.array([11.0, 9.5, 12.0])
LO, HI = LO_MM / 10.0, HI_MM / 10.0


@pytest.fixture(scope="module")
def sphere_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("zarr") / "sphere.obj"
    vertices, faces = uv_sphere(radius=10.0, rings=12, segments=24, centre=(0.5, -1.0, 1.5))
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in faces.tolist()]
    path.write_text("\n".join(lines) + "\n")
    return path


def grid_to_zarr(source, store, *flags):
    bounds = ",".join(repr(float(v)) for v in np.concatenate([LO_MM, HI_MM]))
    run = subprocess.run(
        [COMMAND, "grid", str(source), "--cells", ",".join(map(str, CELLS)), "--bounds", bounds,
         "--units", "mm:cm", "--chunks", "3,5,4", "--out", str(store), "--quiet", *flags],
        capture_output=True, text=True,
    )
    assert run.returncode == 0, run.stderr


def open_quietly(store):
    """xarray.open_zarr with every warning an error (a missing consolidated metadata
    warns), and again requiring the consolidated metadata."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        data = xarray.open_zarr(str(store))
    xarray.testing.assert_identical(data, xarray.open_zarr(str(store), consolidated=True))
    return data


def centres(axis):
    cell = (HI[axis] - LO[axis]) / CELLS[axis]
    return LO[axis] + (np.arange(CELLS[axis]) + 0.5) * cell


def planes(axis):
    cell = (HI[axis] - LO[axis]) / CELLS[axis]
    return LO[axis] + np.arange(CELLS[axis] + 1) * cell


@pytest.mark.parametrize("fraction", [False, True])
def test_the_volumes_zarr_is_a_dataset_with_cell_centres(sphere_file, tmp_path, fraction):
    store = tmp_path / "cells.zarr"
    grid_to_zarr(sphere_file, store, *(["--fraction"] if fraction else []))
    data = open_quietly(store)
    name = "fraction" if fraction else "volume"
    assert list(data.data_vars) == [name]
    assert data[name].dims == ("x", "y", "z") and set(data.coords) == {"x", "y", "z"}
    for axis, d in enumerate("xyz"):
        np.testing.assert_allclose(data[d].values, centres(axis), rtol=0, atol=1e-14)
    # The same grid in Python: the same values and coordinates, under the same names.
    mesh = meshvol.load(str(sphere_file))
    grid = mesh.grid(cells=CELLS, bounds=(LO_MM, HI_MM), fraction=fraction, units="mm:cm")
    python = grid.to_xarray()
    assert python.name == name and python.dims == data[name].dims
    np.testing.assert_array_equal(data[name].values, python.values)
    for d in "xyz":
        np.testing.assert_array_equal(data[d].values, python[d].values)
    # The sphere's volume in cm³, from the cells.
    if not fraction:
        assert float(data[name].sum()) == pytest.approx(mesh.mass_properties(units="mm:cm").volume, rel=1e-12)


def test_the_moments_zarr_is_cut_cells_to_xarray(sphere_file, tmp_path):
    store = tmp_path / "moments.zarr"
    grid_to_zarr(sphere_file, store, "--moments", "--face-centroids")
    data = open_quietly(store)
    cells = meshvol.load(str(sphere_file)).cells(cells=CELLS, bounds=(LO_MM, HI_MM), units="mm:cm",
                                                 face_centroids=True)
    python = cells.to_xarray()
    assert sorted(data.data_vars) == sorted(python.data_vars)
    for name in python.data_vars:
        assert data[name].dims == python[name].dims, name
        np.testing.assert_array_equal(data[name].values, python[name].values, err_msg=name)
    for axis, d in enumerate("xyz"):
        np.testing.assert_allclose(data[d].values, centres(axis), rtol=0, atol=1e-14)
        np.testing.assert_allclose(data[f"{d}_face"].values, planes(axis), rtol=0, atol=1e-14)
        for c in (d, f"{d}_face"):
            np.testing.assert_array_equal(data[c].values, python[c].values, err_msg=c)
    # The apertures sit on the faces: aperture_x on (x_face, y, z).
    assert data["aperture_x"].dims == ("x_face", "y", "z")
    assert data["aperture_x"].sizes["x_face"] == CELLS[0] + 1
