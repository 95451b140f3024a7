"""backend= of Mesh.grid, Mesh.cells and meshvol.dask.grid, as the command's --backend:
on an OpenCL device (PoCL's CPU device in CI) the cells, and the cut cells, are the
CPU's bit for bit."""

import re

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


def opencl_cells(mesh, **kwargs):
    """Mesh.cells on an OpenCL device, or a skip saying why there is none."""
    try:
        return mesh.cells(backend="opencl", **kwargs)
    except (meshvol.MeshError, ValueError) as e:
        if "OpenCL" in str(e):
            pytest.skip(f"no OpenCL device with f64 here: {e}")
        raise


def same_arrays(cpu, gpu, what):
    """Every array of two meshvol.CutCells, bit for bit."""
    assert sorted(cpu) == sorted(gpu), what
    for name in cpu:
        a, b = np.asarray(cpu[name]), np.asarray(gpu[name])
        assert a.shape == b.shape, (what, name)
        assert np.array_equal(a.view(np.uint64), b.view(np.uint64)), (what, name)


def test_opencl_cut_cells_are_the_cpus_bit_for_bit():
    mesh = sphere()
    for kwargs in [dict(cells=(9, 7, 11)), dict(cells=(9, 7, 11), region=((2, 7), (0, 7), (3, 9))),
                   dict(pitch=0.3, check=False), dict(cells=(4, 5, 6), units="mm:cm")]:
        same_arrays(mesh.cells(backend="cpu", **kwargs), opencl_cells(mesh, **kwargs), kwargs)
    # auto: a GPU when there is one, else the CPU: the same bits either way.
    same_arrays(mesh.cells(cells=(9, 7, 11), backend="cpu"), mesh.cells(cells=(9, 7, 11)), "auto")
    pytest.importorskip("dask")
    import meshvol.dask

    lazy = meshvol.dask.grid(mesh, cells=(6, 6, 6), chunks=(3, 3, 6), moments=True, backend="opencl")
    same_arrays(mesh.cells(cells=(6, 6, 6), backend="cpu"),
                {name: a.compute() for name, a in lazy.items()}, "dask")


def test_backends_that_cannot_be_are_refused():
    mesh = sphere()
    with pytest.raises(ValueError, match="one of cpu, opencl, auto"):
        mesh.grid(cells=(2, 2, 2), backend="gpu")
    for extra in ["second_moments", "face_centroids"]:
        with pytest.raises(ValueError, match="CPU only"):
            mesh.cells(cells=(2, 2, 2), backend="opencl", **{extra: True})
        # auto takes the CPU for them.
        assert mesh.cells(cells=(2, 2, 2), **{extra: True})["volume"].shape == (2, 2, 2)
    with pytest.raises((meshvol.MeshError, ValueError), match="OpenCL"):
        mesh.grid(cells=(2, 2, 2), backend="opencl", opencl_device=999)


def test_dask_grid_takes_the_backend():
    pytest.importorskip("dask")
    import meshvol.dask

    mesh = sphere()
    lazy = meshvol.dask.grid(mesh, cells=(6, 6, 6), chunks=(3, 3, 6), backend="cpu")
    assert np.array_equal(lazy.compute(), np.asarray(mesh.grid(cells=(6, 6, 6), backend="cpu")))
    with pytest.raises(ValueError, match="CPU only"):
        meshvol.dask.grid(mesh, cells=(6, 6, 6), moments=True, second_moments=True, backend="opencl")


def test_a_failing_device_is_an_error_and_auto_warns_and_takes_the_cpu(monkeypatch):
    """A kernel build or an allocation the driver refuses (provoked through
    MESHVOL_OPENCL_FAULT, read when the device opens): backend="opencl" raises naming the
    device; backend="auto" on that device warns and gives the CPU's cells, bit for bit."""
    mesh = sphere()
    opencl_grid(mesh, cells=(2, 2, 2))  # skips where there is no device
    cpu = np.asarray(mesh.grid(cells=(9, 7, 11), backend="cpu"))
    cut = mesh.cells(cells=(5, 6, 7), backend="cpu")
    # The number of the device backend="opencl" took (the first with f64), for auto,
    # which takes a CPU device only when named.
    device = None
    for n in range(64):
        try:
            mesh.grid(cells=(2, 2, 2), backend="opencl", opencl_device=n)
            device = n
            break
        except (meshvol.MeshError, ValueError):
            continue
    assert device is not None, "backend='opencl' ran, yet no device number runs it"
    for fault, says in [("build", "did not build"), ("alloc", "clCreateBuffer (cells)")]:
        monkeypatch.setenv("MESHVOL_OPENCL_FAULT", fault)
        with pytest.raises((meshvol.MeshError, ValueError), match=re.escape(says)):
            mesh.grid(cells=(9, 7, 11), backend="opencl", opencl_device=device)
        with pytest.warns(meshvol.MeshWarning, match=re.escape(says)):
            auto = np.asarray(mesh.grid(cells=(9, 7, 11), backend="auto", opencl_device=device))
        assert np.array_equal(auto.view(np.uint64), cpu.view(np.uint64)), fault
        # The cut cells alike.
        with pytest.raises((meshvol.MeshError, ValueError), match=re.escape(says)):
            mesh.cells(cells=(5, 6, 7), backend="opencl", opencl_device=device)
        with pytest.warns(meshvol.MeshWarning, match=re.escape(says)):
            auto = mesh.cells(cells=(5, 6, 7), backend="auto", opencl_device=device)
        same_arrays(cut, auto, fault)
