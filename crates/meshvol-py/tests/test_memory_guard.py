"""The memory guard (docs/security.md#memory): a file whose reading and checking would
not fit in the memory available is refused before it is read, as the command refuses it.
MESHVOL_MEMORY_LIMIT stands in for the machine's memory; the estimate is computed here
from the documented figures (a binary STL's header count times 120 bytes a triangle
checked, 8 read alone, plus the file's bytes)."""

import struct
from pathlib import Path

import numpy as np
import pytest

import meshvol

SAMPLE = Path(__file__).resolve().parents[3] / "samples" / "flanged-bushing.stl"
CHECKED, UNCHECKED = 120, 8


def triangles():
    return struct.unpack("<I", SAMPLE.read_bytes()[80:84])[0]


def estimate(per_triangle):
    return triangles() * per_triangle + SAMPLE.stat().st_size


def stl_volume():
    """The signed volume of the STL's triangles, from its bytes with NumPy."""
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    t = np.frombuffer(SAMPLE.read_bytes(), dtype=record, offset=84)["corners"].astype(float)
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0)


def test_load_refuses_what_does_not_fit_and_reads_what_does(monkeypatch):
    monkeypatch.setenv("MESHVOL_MEMORY_LIMIT", str(estimate(CHECKED) - 1))
    with pytest.raises(meshvol.ReadError) as caught:
        meshvol.load(SAMPLE)
    message = str(caught.value)
    assert "flanged-bushing.stl" in message
    assert f"reading and checking {triangles()} triangles needs about" in message
    monkeypatch.setenv("MESHVOL_MEMORY_LIMIT", str(estimate(CHECKED)))
    volume = meshvol.load(SAMPLE).mass_properties(check=False).volume
    assert volume == pytest.approx(stl_volume(), rel=1e-9)


def test_measure_counts_the_check_only_when_it_checks(monkeypatch):
    # Room to read, not to check: the unchecked row is measured, the checked one refused.
    monkeypatch.setenv("MESHVOL_MEMORY_LIMIT", str(estimate(UNCHECKED)))
    unchecked = meshvol.measure([SAMPLE], check=False)
    assert unchecked["volume"][0] == pytest.approx(stl_volume(), rel=1e-9)
    checked = meshvol.measure([SAMPLE])
    assert f"reading and checking {triangles()} triangles needs about" in checked["error"][0]
