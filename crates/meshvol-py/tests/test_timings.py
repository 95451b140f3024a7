"""timings=True (issue 28, item 1): the stages of a call, with wall and CPU seconds, as
the command's --timings lists them; they add up to (at most) the call's own time."""

import json
import os
import resource
import subprocess
import time

import numpy as np
import pytest

import meshvol
from solids import uv_sphere

COMMAND = os.environ.get("MESHVOL_BIN")


def sphere():
    return meshvol.Mesh(*uv_sphere(rings=24, segments=48))


@pytest.mark.parametrize(
    "call",
    [
        lambda m, t: m.mass_properties(timings=t),
        lambda m, t: m.check(timings=t),
        lambda m, t: m.profile(levels=4, timings=t),
        lambda m, t: m.below(volume=1.0, timings=t),
        lambda m, t: m.section("z=0.1", timings=t),
        lambda m, t: meshvol.union([m], timings=t),
        lambda m, t: meshvol.intersection(m, m, timings=t),
    ],
)
def test_stages_add_up_to_the_call(call):
    mesh = sphere()
    assert "timings" not in call(mesh, False).to_dict()
    start = time.perf_counter()
    peak_before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 / 1e6
    report = call(mesh, True)
    peak_after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 / 1e6
    elapsed = time.perf_counter() - start
    stages = report.timings
    # Each stage's peak is the process's high-water mark at its end, as the system
    # reports it to Python: never falling, and between the marks before and after.
    peaks = [s["peak_mb"] for s in stages]
    assert peaks == sorted(peaks) and peak_before <= peaks[0] and peaks[-1] <= peak_after
    assert stages == report.to_dict()["timings"] and list(report.to_dict())[-1] == "timings"
    assert [set(s) for s in stages] == [{"stage", "wall_s", "cpu_s", "peak_mb"}] * len(stages)
    names = [s["stage"] for s in stages]
    assert names[0] == "checking" and "welding" in names and "finding edges" in names
    assert all(s["wall_s"] >= 0 and s["cpu_s"] >= 0 for s in stages)
    assert sum(s["wall_s"] for s in stages) <= elapsed


def terrain(n=24):
    """A height field z = sin x cos y over n x n squares, two triangles each."""
    x, y = np.meshgrid(np.linspace(0, 3, n + 1), np.linspace(0, 3, n + 1), indexing="ij")
    vertices = np.column_stack([x.ravel(), y.ravel(), (np.sin(x) * np.cos(y)).ravel()])
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    a = (i * (n + 1) + j).ravel()
    faces = np.concatenate([np.column_stack([a, a + n + 1, a + n + 2]),
                            np.column_stack([a, a + n + 2, a + 1])])
    return meshvol.Mesh(vertices, faces)


@pytest.mark.parametrize(
    "call",
    [
        lambda t: meshvol.convex_hull(sphere().vertices, timings=t),
        lambda t: meshvol.cutfill(terrain(), level=0.0, timings=t),
    ],
)
def test_the_kernels_stages(call):
    # No check: the stages are the kernel's, after the arguments are read ("measuring").
    assert "timings" not in call(False).to_dict()
    start = time.perf_counter()
    report = call(True)
    elapsed = time.perf_counter() - start
    stages = report.timings
    assert stages == report.to_dict()["timings"] and list(report.to_dict())[-1] == "timings"
    assert [set(s) for s in stages] == [{"stage", "wall_s", "cpu_s", "peak_mb"}] * len(stages)
    assert stages[0]["stage"] == "measuring" and len(stages) >= 2
    assert all(s["wall_s"] >= 0 and s["cpu_s"] >= 0 for s in stages)
    assert sum(s["wall_s"] for s in stages) <= elapsed


def test_grid_stages():
    mesh = sphere()
    assert not hasattr(mesh.grid(cells=(4, 4, 4)), "timings")
    start = time.perf_counter()
    grid = mesh.grid(cells=(4, 4, 4), timings=True)
    elapsed = time.perf_counter() - start
    names = [s["stage"] for s in grid.timings]
    assert names[0] == "checking" and "welding" in names and "measuring" in names
    assert names[-1] != "measuring"  # the kernel's stages follow
    assert sum(s["wall_s"] for s in grid.timings) <= elapsed
    # The same cells as without timings.
    assert np.array_equal(grid.values, mesh.grid(cells=(4, 4, 4)).values)


def test_unchecked_is_one_stage():
    (stage,) = sphere().mass_properties(check=False, timings=True).timings
    assert stage["stage"] == "measuring"
    # A check's mass properties: the check is done, measuring is all that is left.
    (stage,) = sphere().check().mass_properties(timings=True).timings
    assert stage["stage"] == "measuring"
    (stage,) = meshvol.polygon_area([[0, 0], [1, 0], [1, 1]], timings=True).timings
    assert stage["stage"] == "measuring" and stage["wall_s"] >= 0 and stage["cpu_s"] >= 0


@pytest.mark.skipif(not COMMAND, reason="MESHVOL_BIN names no meshvol command to compare with")
def test_the_stages_are_the_commands(tmp_path):
    vertices, faces = uv_sphere(rings=8, segments=16)
    path = tmp_path / "s.obj"
    path.write_text("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in vertices.tolist())
                    + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces.tolist()))
    run = subprocess.run([COMMAND, "volume", str(path), "--json", "--timings"], capture_output=True, text=True)
    theirs = [s["stage"] for s in json.loads(run.stdout)["timings"]]
    ours = [s["stage"] for s in meshvol.load(path).mass_properties(timings=True).timings]
    assert theirs[0] == "reading" and ours == theirs[1:]
