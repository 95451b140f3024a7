"""units= and density= on every measuring method (issue 30, item 1): one solid in mm,
in and m gives the same physical answers through every method, the closed forms of a
20 x 30 x 40 mm box, and the command's JSON for the same options."""

import json
import os
import subprocess

import numpy as np
import pytest

import meshvol
from solids import box

COMMAND = os.environ.get("MESHVOL_BIN")
MM = {"mm": 1.0, "in": 25.4, "m": 1000.0}


def part(unit):
    """The 20 x 30 x 40 mm box, its coordinates in `unit`."""
    return meshvol.Mesh(*box((0, 0, 0), np.array([20.0, 30.0, 40.0]) / MM[unit]))


@pytest.mark.parametrize("unit", ["mm", "in", "m"])
def test_every_method_reports_cm(unit):
    mesh, to = part(unit), f"{unit}:cm"
    half = 20.0 / MM[unit]  # z = 20 mm in the file's units
    assert mesh.mass_properties(units=to).volume == pytest.approx(24.0)
    assert mesh.mass_properties(units=unit, density="7.85g/cm3").mass == pytest.approx(24.0 * 7.85)
    assert mesh.check(units=to).solid_volume == pytest.approx(24.0)
    below = mesh.below(plane=(0, 0, 1, half), units=to, density="1g/cm3")
    assert below.volume == pytest.approx(12.0) and below.mass == pytest.approx(12.0)
    assert below.mass_unit == "g"
    profile = mesh.profile(levels=4, units=f"{unit}:L")
    assert profile.volume_below[-1] == pytest.approx(0.024) and profile.units["volume"] == "L"
    assert mesh.section(f"z={half}", units=to).area == pytest.approx(6.0)
    grid = mesh.grid(cells=(2, 3, 4), units=to)
    assert np.allclose(grid.values, 1.0) and np.allclose(grid.spacing, 1.0)
    assert np.allclose(grid.bounds, [[0, 0, 0], [2, 3, 4]])
    masses = mesh.grid(cells=(2, 3, 4), units=unit, density="2g/cm3")
    assert float(masses.sum()) == pytest.approx(48.0)
    u = meshvol.union([mesh], units=to)
    assert u.lower <= 24.0 * (1 + 1e-9) and u.upper >= 24.0 * (1 - 1e-9)
    i = meshvol.intersection(mesh, mesh, units=to)
    assert i.volume == pytest.approx(24.0)
    assert meshvol.convex_hull(mesh.vertices, units=to).volume == pytest.approx(24.0)
    rectangle = np.array([[0, 0], [20, 0], [20, 30], [0, 30]]) / MM[unit]
    assert meshvol.polygon_area(rectangle, units=to).area == pytest.approx(6.0)


def test_cutfill_in_cubic_yards():
    # A 10 x 10 m plane 1 m above z = 0: 100 m³ of cut against level 0.
    vertices = np.array([[0, 0, 1], [10, 0, 1], [10, 10, 1], [0, 10, 1]], dtype=float)
    sheet = meshvol.Mesh(vertices, [[0, 1, 2], [0, 2, 3]])
    cubic_yard = 0.9144**3
    r = meshvol.cutfill(sheet, level=0.0, cells=(2, 2), units="m:yd")
    assert r.cut == pytest.approx(100.0 / cubic_yard)
    assert float(r.cut_cells.sum()) == pytest.approx(100.0 / cubic_yard)


@pytest.mark.parametrize("unit", ["mm", "in", "m"])
def test_masses_of_sections_polygons_and_fill(unit):
    # The section at half height and the 20 x 30 mm rectangle: 6 cm² = 6e-4 m²; a sheet
    # of 62.8 kg/m² (8 mm of steel) with that outline weighs 62.8 * 6e-4 kg.
    mesh, half = part(unit), 20.0 / MM[unit]
    section = mesh.section(f"z={half}", units=f"{unit}:cm", density="62.8kg/m2")
    assert section.area == pytest.approx(6.0)
    assert section.mass == pytest.approx(62.8 * 6e-4) and section.mass_unit == "kg"
    assert section.density_unit == "kg/m^2" and section.to_dict()["mass"] == section.mass
    rectangle = np.array([[0, 0], [20, 0], [20, 30], [0, 30]]) / MM[unit]
    plate = meshvol.polygon_area(rectangle, units=unit, density="62.8kg/m2")
    assert plate.mass == pytest.approx(62.8 * 6e-4) and plate.mass_unit == "kg"
    # A bare number is mass per reported area unit.
    assert mesh.section(f"z={half}", units=f"{unit}:cm", density=2.0).mass == pytest.approx(12.0)
    # 10 x 10 m of ground at z = 1 m filled to the level z = 2 m: 100 m³ of fill, at
    # 1.8 t/m³ 180 t, whatever unit the coordinates are in.
    m = 1000.0 / MM[unit]
    vertices = np.array([[0, 0, 1], [10, 0, 1], [10, 10, 1], [0, 10, 1]], dtype=float) * m
    ground = meshvol.Mesh(vertices, [[0, 1, 2], [0, 2, 3]])
    r = meshvol.cutfill(ground, level=2.0 * m, units=f"{unit}:m3", density="1.8t/m3")
    assert (r.cut, r.fill) == (0.0, pytest.approx(100.0))
    assert r.mass == pytest.approx(180.0) and r.mass_unit == "t"


def test_a_density_of_the_wrong_kind_is_refused():
    mesh = part("mm")
    with pytest.raises(ValueError, match="mass per volume; this command measures areas"):
        mesh.section("z=20", units="mm", density="7.85g/cm3")
    with pytest.raises(ValueError, match="mass per area; this command measures volumes"):
        mesh.mass_properties(units="mm", density="62.8kg/m2")
    with pytest.raises(ValueError, match="mass per area"):
        meshvol.cutfill(mesh, level=0.0, units="mm", density="62.8kg/m2")
    with pytest.raises(ValueError, match="density must be a positive number"):
        meshvol.polygon_area([[0, 0], [1, 0], [1, 1]], density=-1.0)
    for bad in (0.0, float("nan"), float("inf"), "0kg/m2", "-2kg/m3"):
        with pytest.raises(ValueError, match="positive number"):
            mesh.section("z=20", density=bad)


def test_bad_units_and_densities():
    mesh = part("mm")
    with pytest.raises(ValueError, match="furlong|unknown|known"):
        mesh.below(plane=(0, 0, 1, 1), units="furlong")
    with pytest.raises(ValueError, match="density must be a positive number"):
        mesh.profile(levels=2, density=0)
    with pytest.raises(ValueError, match="unit"):
        mesh.mass_properties(density="7.85g/cm3")  # a unit needs the file's length unit
    with pytest.raises(ValueError, match="density or fraction"):
        mesh.grid(cells=(1, 1, 1), fraction=True, density=2.0)


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
def test_the_commands_reports(tmp_path):
    path = tmp_path / "part.obj"
    vertices, faces = box((0, 0, 0), (20, 30, 40))
    path.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in vertices)
                    + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces))

    def command(*args):
        run = subprocess.run([COMMAND, *args, "--json"], capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        return json.loads(run.stdout)

    mesh = meshvol.load(path)
    assert mesh.profile(levels=4, units="mm:L", density="1kg/L").to_dict() == command(
        "profile", str(path), "--levels", "4", "--units", "mm:L", "--density", "1kg/L")
    assert mesh.below(plane=(0, 0, 1, 20), units="mm:m", density="1025kg/m3").to_dict() == command(
        "below", str(path), "--plane", "0,0,1,20", "--units", "mm:m", "--density", "1025kg/m3")
    assert mesh.check(units="mm:cm").to_dict() == command("check", str(path), "--units", "mm:cm")
    assert mesh.section("z=20", units="mm:cm", density="62.8kg/m2").to_dict() == command(
        "section", str(path), "--plane", "z=20", "--units", "mm:cm", "--density", "62.8kg/m2")
