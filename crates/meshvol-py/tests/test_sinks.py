"""Python's side of the path test matrix (crates/meshvol-cli/tests/sinks.rs): the robot
formats in SI from any units and density, and the grid arrays in the units asked for,
against the closed form converted by hand and, where MESHVOL_BIN names the command, the
same bits as the files the command writes."""

import os
import subprocess

import numpy as np
import pytest

import meshvol
from solids import box

COMMAND = os.environ.get("MESHVOL_BIN")

# A 10 x 20 x 30 box from (1, 2, 3), in the file's units.
LO, HI = (1.0, 2.0, 3.0), (11.0, 22.0, 33.0)
VOLUME = 6000.0

# (units, metres per file length, reported lengths per file length)
UNITS = [("mm:cm", 1e-3, 0.1), ("in:mL", 0.0254, 2.54), ("mm:m", 1e-3, 1e-3)]
# (density, kg/m³)
DENSITIES = [("7850kg/m3", 7850.0), ("7.85g/cm3", 7850.0), ("490lb/ft3", 490 * 0.45359237 / 0.3048**3)]


def attribute(text, key):
    return [float(x) for x in text.split(f' {key}="')[1].split('"')[0].split()]


@pytest.mark.parametrize("units,metres,length", UNITS)
@pytest.mark.parametrize("density,kg_per_m3", DENSITIES)
def test_to_urdf_is_si_whatever_the_units(units, metres, length, density, kg_per_m3):
    mp = meshvol.Mesh(*box(LO, HI)).mass_properties(units=units, density=density)
    urdf = mp.to_urdf()
    kilograms = kg_per_m3 * VOLUME * metres**3
    assert attribute(urdf, "value")[0] == pytest.approx(kilograms, rel=1e-12)
    assert attribute(urdf, "xyz") == pytest.approx([6 * metres, 12 * metres, 18 * metres], rel=1e-12)
    b, c = 20 * metres, 30 * metres
    assert attribute(urdf, "ixx")[0] == pytest.approx(kilograms * (b * b + c * c) / 12, rel=1e-12)


def test_to_urdf_refuses_a_mass_of_no_known_unit():
    mp = meshvol.Mesh(*box(LO, HI)).mass_properties(units="mm:cm", density=7.85)
    with pytest.raises(ValueError, match="kilograms"):
        mp.to_urdf()


@pytest.mark.parametrize("units,metres,length", UNITS)
def test_grid_and_cells_in_the_units_asked_for(units, metres, length):
    mesh = meshvol.Mesh(*box(LO, HI))
    grid = mesh.grid(pitch=2.5, units=units)
    assert grid.sum() == pytest.approx(VOLUME * length**3, rel=1e-12)
    assert grid.origin == pytest.approx([x * length for x in LO], rel=1e-12)
    assert grid.spacing == pytest.approx([2.5 * length] * 3, rel=1e-12)
    masses = mesh.grid(pitch=2.5, units=units, density="7.85g/cm3")
    # 7.85 g/cm³ = 7.85e6 g/m³.
    assert masses.sum() == pytest.approx(7.85e6 * VOLUME * metres**3, rel=1e-12)
    cells = mesh.cells(pitch=2.5, units=units)
    assert cells["volume"].sum() == pytest.approx(VOLUME * length**3, rel=1e-12)
    assert cells["boundary_area"].sum() == pytest.approx(2200 * length**2, rel=1e-12)
    assert cells["centroid"][0, 0, 0] == pytest.approx([(x + 1.25) * length for x in LO], rel=1e-12)


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
@pytest.mark.parametrize("units", [u for u, _, _ in UNITS])
def test_the_commands_grid_files_hold_pythons_arrays(tmp_path, units):
    vertices, faces = box(LO, HI)
    mesh = meshvol.Mesh(vertices, faces)
    path = tmp_path / "box.obj"
    mesh.save(str(path))
    npy, npz = tmp_path / "cells.npy", tmp_path / "cut.npz"
    flags = ["--pitch", "2.5", "--units", units]
    subprocess.run([COMMAND, "grid", str(path), *flags, "--density", "2.7g/cm3", "--out", str(npy)], check=True, capture_output=True)
    subprocess.run([COMMAND, "grid", str(path), *flags, "--moments", "--out", str(npz)], check=True, capture_output=True)
    # One conversion behind both: the same bits.
    assert np.array_equal(np.load(npy), mesh.grid(pitch=2.5, units=units, density="2.7g/cm3"))
    written, cells = np.load(npz), mesh.cells(pitch=2.5, units=units)
    for name in ["volume", "fraction", "centroid", "boundary_area", "boundary_vector", "aperture_x"]:
        assert np.array_equal(written[name], cells[name]), name
    assert np.array_equal(written["origin"], cells.origin)
    assert np.array_equal(written["cell_size"], cells.spacing)
