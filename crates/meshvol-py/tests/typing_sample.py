"""Code a user writes against meshvol's public API, checked by mypy --strict against the
stubs (test_typing.py); it also runs (test_typing.py runs it), so the stubs and the
runtime agree on what it does."""

from __future__ import annotations

import io
import pathlib
from typing import Optional

import numpy as np
import numpy.typing as npt

import meshvol


def main(folder: pathlib.Path) -> None:
    corners = np.array([[x, y, z] for z in (0, 4) for y in (0, 3) for x in (0, 2)], dtype=float)
    quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    box = meshvol.Mesh(corners, quads)
    mp: meshvol.MassProperties = box.mass_properties(density="2g/cm3", units="mm", timings=True)
    bounds: Optional[npt.NDArray[np.float64]] = mp.bounds
    assert bounds is not None and bounds.shape == (2, 3)
    count: int = mp.vertex_count + mp.face_count + mp.triangle_count
    shells: list[meshvol.Shell] = mp.shell_details
    assert count == 8 + 6 + 12 and shells[0].face_count == 6
    assert mp.timings[0]["stage"] == "checking"
    grid: meshvol.Grid = box.grid(cells=np.array([2, 3, 4]), bounds=bounds, units="mm:cm")
    values: npt.NDArray[np.float64] = np.asarray(grid)
    origin: npt.NDArray[np.float64] = grid.origin
    assert values.shape == grid.shape and origin.shape == (3,)
    below: meshvol.Below = box.below(volume=6.0, direction=[0, 0, 1], density=1.0)
    section: meshvol.Section = box.section([[0, 0, 1], [0, 0, 1]])
    axes: npt.NDArray[np.float64] = section.principal_axes
    bodies: list[meshvol.Mesh] = box.bodies()
    assert below.level == 1.0 and axes.shape == (2, 2) and len(bodies) == 1
    path = folder / "box.obj"
    box.save(path)
    with open(path, "rb") as f:
        again = meshvol.load(f, file_type="obj")
    again = meshvol.load(io.BytesIO(path.read_bytes()), file_type="obj")
    assert again.mass_properties().volume == 24.0
    try:
        meshvol.load(folder / "missing.stl")
    except FileNotFoundError as e:
        assert isinstance(e, meshvol.MeshError)
    frame = meshvol.measure([path, folder / "missing.stl"], workers=1)
    assert len(frame) == 2
    assert len(meshvol.measure(folder, recursive=False, glob=["*.obj", "!missing*"])) >= 1
    area: meshvol.AreaProperties = meshvol.polygon_area([[0, 0], [2, 0], [2, 1], [0, 1]], units="m:cm")
    assert area.area == 20000.0 and area.principal_moments[0] <= area.principal_moments[1]


if __name__ == "__main__":
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        main(pathlib.Path(d))
