"""Mesh.cells: the cut-cell geometry, against a box's closed forms, trimesh's whole-mesh
properties, the command's .npz, and unit conversions."""

import os
import pickle
import subprocess

import meshvol
import meshvol.dask
import numpy as np
import pytest
import trimesh
from solids import BOX_QUADS, box_vertices

COMMAND = os.environ.get("MESHVOL_BIN")
LO, HI = np.array([0.25, 0.5, -0.3]), np.array([1.5, 1.25, 0.9])
BOUNDS = [[0.0, 0.0, -0.5], [2.0, 1.5, 1.0]]


def box_mesh():
    return meshvol.Mesh(box_vertices(LO, HI), BOX_QUADS)


def test_a_box_by_closed_forms():
    c = box_mesh().cells(cells=(4, 3, 5), bounds=BOUNDS)
    assert isinstance(c, dict) and c.shape == (4, 3, 5)
    assert sorted(c) == sorted(
        ["volume", "fraction", "centroid", "boundary_area", "boundary_vector",
         "boundary_centroid", "aperture_x", "aperture_y", "aperture_z"]
    )
    lower = c.origin + np.indices((4, 3, 5)).transpose(1, 2, 3, 0) * c.spacing
    lo, hi = np.maximum(lower, LO), np.minimum(lower + c.spacing, HI)
    lengths = np.clip(hi - lo, 0, None)
    volume = lengths.prod(axis=-1)
    np.testing.assert_allclose(c["volume"], volume, atol=1e-14)
    np.testing.assert_allclose(c["fraction"], volume / c.spacing.prod(), atol=1e-13)
    partial = volume > 1e-9
    np.testing.assert_allclose(c["centroid"][partial], ((lo + hi) / 2)[partial], atol=1e-12)
    # Σ over the box's surface; the x apertures: the box's section on each x plane.
    area = 2 * (1.25 * 0.75 + 1.25 * 1.2 + 0.75 * 1.2)
    assert c["boundary_area"].sum() == pytest.approx(area, rel=1e-14)
    np.testing.assert_allclose(c["boundary_vector"].sum(axis=(0, 1, 2)), 0, atol=1e-14)
    x_planes = c.origin[0] + np.arange(5) * c.spacing[0]
    # A face of the box on a plane: the section just below it, as `section` takes it.
    inside = (x_planes > LO[0]) & (x_planes <= HI[0])
    section = c["aperture_x"].sum(axis=(1, 2)) * c.spacing[1] * c.spacing[2]
    np.testing.assert_allclose(section, np.where(inside, 0.75 * 1.2, 0.0), atol=1e-13)


def test_sums_match_trimesh_on_a_sphere():
    sphere = trimesh.creation.icosphere(subdivisions=4, radius=1.0)
    mesh = meshvol.Mesh(sphere.vertices, sphere.faces)
    c = mesh.cells(cells=(9, 8, 7), bounds=[[-1.1] * 3, [1.1] * 3])
    assert c["boundary_area"].sum() == pytest.approx(sphere.area, rel=1e-12)
    moment = (c["volume"][..., None] * c["centroid"]).sum(axis=(0, 1, 2))
    np.testing.assert_allclose(moment, sphere.center_mass * sphere.volume, atol=1e-12)
    assert c["volume"].sum() == pytest.approx(sphere.volume, rel=1e-12)
    # The divergence theorem on every cut cell.
    h = c.spacing
    div = np.stack(
        [
            np.diff(c["aperture_x"], axis=0) * h[1] * h[2],
            np.diff(c["aperture_y"], axis=1) * h[0] * h[2],
            np.diff(c["aperture_z"], axis=2) * h[0] * h[1],
        ],
        axis=-1,
    ) + c["boundary_vector"]
    assert np.abs(div).max() < 1e-12


def test_units_scale_each_quantity_by_its_dimension():
    mm = box_mesh().cells(cells=(4, 3, 5), bounds=BOUNDS)
    cm = box_mesh().cells(cells=(4, 3, 5), bounds=BOUNDS, units="mm:cm")
    np.testing.assert_allclose(cm["volume"], mm["volume"] * 1e-3, rtol=1e-15)
    np.testing.assert_allclose(cm["centroid"], mm["centroid"] * 0.1, rtol=1e-15)
    np.testing.assert_allclose(cm["boundary_area"], mm["boundary_area"] * 1e-2, rtol=1e-15)
    np.testing.assert_allclose(cm["boundary_vector"], mm["boundary_vector"] * 1e-2, rtol=1e-15)
    np.testing.assert_array_equal(cm["aperture_z"], mm["aperture_z"])
    np.testing.assert_allclose(cm.spacing, mm.spacing * 0.1, rtol=1e-15)


def test_to_xarray_pickle_and_bad_arguments():
    c = box_mesh().cells(cells=(4, 3, 5), bounds=BOUNDS)
    ds = c.to_xarray()
    assert ds["aperture_x"].dims == ("x_face", "y", "z")
    assert ds["centroid"].dims == ("x", "y", "z", "component")
    np.testing.assert_array_equal(ds["volume"].values, c["volume"])
    back = pickle.loads(pickle.dumps(c))
    assert isinstance(back, meshvol.CutCells) and back.shape == c.shape
    with pytest.raises(ValueError, match="give cells"):
        box_mesh().cells()
    with pytest.raises(ValueError, match="positive"):
        box_mesh().cells(cells=(0, 1, 1))


def test_moments_true_is_the_cut_cells_and_false_points_to_grid():
    """The issue's spelling, Mesh.cells(cells=..., moments=True), is the default call;
    its volumes are Mesh.grid's bit for bit; moments=False is an error naming Mesh.grid."""
    c = box_mesh().cells(cells=(4, 3, 5), bounds=BOUNDS, moments=True)
    d = box_mesh().cells(cells=(4, 3, 5), bounds=BOUNDS)
    assert sorted(c) == sorted(d)
    for name in c:
        np.testing.assert_array_equal(c[name], d[name])
    g = box_mesh().grid(cells=(4, 3, 5), bounds=BOUNDS)
    np.testing.assert_array_equal(c["volume"], np.asarray(g))
    with pytest.raises(ValueError, match="Mesh.grid"):
        box_mesh().cells(cells=(4, 3, 5), bounds=BOUNDS, moments=False)


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
def test_the_same_arrays_as_the_command(tmp_path):
    sample = os.path.join(os.path.dirname(__file__), "../../../samples/flanged-bushing.stl")
    out = tmp_path / "c.npz"
    subprocess.run(
        [COMMAND, "grid", sample, "--cells", "12,11,10", "--moments", "--second-moments",
         "--face-centroids", "--out", str(out)],
        check=True,
        capture_output=True,
    )
    written = np.load(out)
    c = meshvol.load(sample).cells(cells=(12, 11, 10), second_moments=True, face_centroids=True)
    for name, values in c.items():
        np.testing.assert_array_equal(written[name], values, err_msg=name)
    np.testing.assert_array_equal(written["origin"], c.origin)


def test_blocks_and_dask_chunks_are_the_whole_grid_bit_for_bit():
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    mesh = meshvol.Mesh(sphere.vertices, sphere.faces)
    bounds = [[-1.1, -1.1, -1.1], [0.6, 0.7, 0.5]]  # the grid cuts the sphere
    whole = mesh.cells(cells=(7, 6, 5), bounds=bounds)
    block = mesh.cells(cells=(7, 6, 5), bounds=bounds, region=((2, 5), (1, 6), (0, 3)))
    np.testing.assert_array_equal(block["centroid"], whole["centroid"][2:5, 1:6, 0:3])
    np.testing.assert_array_equal(block["aperture_x"], whole["aperture_x"][2:6, 1:6, 0:3])
    np.testing.assert_array_equal(block["aperture_z"], whole["aperture_z"][2:5, 1:6, 0:4])
    np.testing.assert_allclose(block.origin, whole.origin + np.array([2, 1, 0]) * whole.spacing)
    lazy = meshvol.dask.grid(mesh, cells=(7, 6, 5), bounds=bounds, chunks=(3, 4, 2), moments=True)
    assert sorted(lazy) == sorted(whole)
    for name, values in lazy.items():
        np.testing.assert_array_equal(values.compute(scheduler="threads"), whole[name], err_msg=name)


def summed_inertia(c, about):
    """Σ over the cells of their inertia moved to `about` (parallel axis theorem: the
    covariance there is Σ C_cell + V (c − about)(c − about)ᵀ), as an inertia tensor."""
    eye = np.eye(3)
    inertia = c["inertia"].reshape(-1, 3, 3)
    cov = np.trace(inertia, axis1=1, axis2=2)[:, None, None] / 2 * eye - inertia
    r = c["centroid"].reshape(-1, 3) - about
    total = cov.sum(axis=0) + np.einsum("n,ni,nj->ij", c["volume"].reshape(-1), r, r)
    return np.trace(total) * eye - total


def test_second_moments_sum_to_trimeshs_inertia():
    # An ellipsoid turned and moved: every product of inertia is non-zero.
    solid = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    solid.apply_scale([1.3, 0.8, 0.6])
    solid.apply_transform(trimesh.transformations.rotation_matrix(0.7, [1, 2, 3], [0, 0, 0]))
    solid.apply_translation([2.0, -1.0, 0.5])
    mesh = meshvol.Mesh(solid.vertices, solid.faces)
    for cells in [(5, 4, 6), (13, 11, 9)]:
        c = mesh.cells(cells=cells, second_moments=True)
        assert c["inertia"].shape == cells + (3, 3)
        np.testing.assert_allclose(c["inertia"], np.swapaxes(c["inertia"], -1, -2), atol=0)
        got = summed_inertia(c, solid.center_mass)
        np.testing.assert_allclose(got, solid.moment_inertia, atol=1e-12 * solid.moment_inertia.max())


def test_a_boxs_inertia_and_face_centroids_by_closed_forms():
    c = box_mesh().cells(cells=(4, 3, 5), bounds=BOUNDS, second_moments=True, face_centroids=True)
    lower = c.origin + np.indices((4, 3, 5)).transpose(1, 2, 3, 0) * c.spacing
    lo, hi = np.maximum(lower, LO), np.minimum(lower + c.spacing, HI)
    l = np.clip(hi - lo, 0, None)
    v = l.prod(axis=-1)
    diagonal = v[..., None] * (l[..., [1, 0, 0]] ** 2 + l[..., [2, 2, 1]] ** 2) / 12
    np.testing.assert_allclose(c["inertia"], diagonal[..., None] * np.eye(3), atol=1e-15)
    # The z faces: the box's rectangle in each, its middle; NaN where the face is dry.
    z = c["aperture_z_centroid"]
    assert z.shape == (4, 3, 6, 3)
    planes = c.origin[2] + np.arange(6) * c.spacing[2]
    wet = c["aperture_z"] > 0
    assert np.isnan(z[~wet]).all() and not np.isnan(z[wet]).any()
    middle = ((lo + hi) / 2)[:, :, :1, :2]
    expected_xy = np.broadcast_to(middle, (4, 3, 6, 2))
    np.testing.assert_allclose(z[..., :2][wet], expected_xy[wet], atol=1e-14)
    np.testing.assert_allclose(z[..., 2][wet], np.broadcast_to(planes, (4, 3, 6))[wet], atol=1e-14)
    ds = c.to_xarray()
    assert ds["inertia"].dims == ("x", "y", "z", "row", "column")
    assert ds["aperture_y_centroid"].dims == ("x", "y_face", "z", "component")
    # Units: the inertia is a volume times a length squared.
    cm = box_mesh().cells(cells=(4, 3, 5), bounds=BOUNDS, second_moments=True, units="mm:cm")
    np.testing.assert_allclose(cm["inertia"], c["inertia"] * 1e-5, rtol=1e-15, atol=1e-300)


def test_extras_by_blocks_and_dask_chunks_are_the_whole_grid_bit_for_bit():
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    mesh = meshvol.Mesh(sphere.vertices, sphere.faces)
    bounds = [[-1.1, -1.1, -1.1], [0.6, 0.7, 0.5]]
    extras = dict(second_moments=True, face_centroids=True)
    whole = mesh.cells(cells=(7, 6, 5), bounds=bounds, **extras)
    block = mesh.cells(cells=(7, 6, 5), bounds=bounds, region=((2, 5), (1, 6), (0, 3)), **extras)
    np.testing.assert_array_equal(block["inertia"], whole["inertia"][2:5, 1:6, 0:3])
    np.testing.assert_array_equal(
        block["aperture_x_centroid"], whole["aperture_x_centroid"][2:6, 1:6, 0:3]
    )
    lazy = meshvol.dask.grid(
        mesh, cells=(7, 6, 5), bounds=bounds, chunks=(3, 4, 2), moments=True, **extras
    )
    assert sorted(lazy) == sorted(whole)
    for name, values in lazy.items():
        np.testing.assert_array_equal(values.compute(scheduler="threads"), whole[name], err_msg=name)
    with pytest.raises(ValueError, match="moments=True"):
        meshvol.dask.grid(mesh, cells=(7, 6, 5), bounds=bounds, second_moments=True)
