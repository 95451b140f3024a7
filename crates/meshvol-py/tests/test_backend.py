"""backend= of Mesh.grid, Mesh.cells and meshvol.dask.grid, as the command's --backend:
on an OpenCL device (PoCL's CPU device in CI) the cells are the CPU's bit for bit."""

import numpy as np
import pytest

import meshvol
from solids import uv_sphere


def sphere():
    return meshvol.Mesh(*uv_sphere(radius=1.0, rings=16, segments=32))


def opencl_grid(mesh, **kwargs):
    """Mesh.grid on an OpenCL device, or a skip saying why there is none."""
    try:
        return mesh.grid(backend="opencl", **kwargs)
    except (meshvol.MeshError, ValueError) as e:
        if "OpenCL" in str(e):
            pytest.skip(f"no OpenCL device with f64 here: {e}")
        raise


def test_opencl_cells_are_the_cpus_bit_for_bit():
    mesh = sphere()
    for kwargs in [dict(cells=(9, 7, 11)), dict(cells=(9, 7, 11), fraction=True),
                   dict(cells=(9, 7, 11), region=((2, 7), (0, 7), (3, 9))),
                   dict(pitch=0.3, check=False), dict(cells=(4, 4, 4), units="mm:cm", density="7.85g/cm3")]:
        cpu = np.asarray(mesh.grid(backend="cpu", **kwargs))
        gpu = np.asarray(opencl_grid(mesh, **kwargs))
        assert cpu.shape == gpu.shape
        assert np.array_equal(cpu.view(np.uint64), gpu.view(np.uint64)), kwargs
    # auto: a GPU when there is one, else the CPU: the same bits either way.
    auto = np.asarray(mesh.grid(cells=(9, 7, 11)))
    assert np.array_equal(auto, np.asarray(mesh.grid(cells=(9, 7, 11), backend="cpu")))


def test_backends_that_cannot_be_are_refused():
    mesh = sphere()
    with pytest.raises(ValueError, match="one of cpu, opencl, auto"):
        mesh.grid(cells=(2, 2, 2), backend="gpu")
    with pytest.raises(ValueError, match="CPU only"):
        mesh.cells(cells=(2, 2, 2), backend="opencl")
    # auto takes the CPU for the cut cells.
    assert mesh.cells(cells=(2, 2, 2))["volume"].shape == (2, 2, 2)
    with pytest.raises((meshvol.MeshError, ValueError), match="OpenCL"):
        mesh.grid(cells=(2, 2, 2), backend="opencl", opencl_device=999)


def test_dask_grid_takes_the_backend():
    pytest.importorskip("dask")
    import meshvol.dask

    mesh = sphere()
    lazy = meshvol.dask.grid(mesh, cells=(6, 6, 6), chunks=(3, 3, 6), backend="cpu")
    assert np.array_equal(lazy.compute(), np.asarray(mesh.grid(cells=(6, 6, 6), backend="cpu")))
    with pytest.raises(ValueError, match="CPU only"):
        meshvol.dask.grid(mesh, cells=(6, 6, 6), moments=True, backend="opencl")
