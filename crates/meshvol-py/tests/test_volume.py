"""meshvol.volume: the volume alone, arrays read in place when they can be."""

import doctest

import numpy as np
import pytest

import meshvol
from solids import box, uv_sphere


def same_bits(a, b):
    return np.float64(a).tobytes() == np.float64(b).tobytes()


def test_docstring_examples_run():
    runner = doctest.DocTestRunner()
    finder = doctest.DocTestFinder()
    tests = finder.find(meshvol.volume, "volume", globs={})
    assert tests and tests[0].examples
    for test in tests:
        runner.run(test)
    assert runner.failures == 0


@pytest.mark.parametrize("dtype", [np.int32, np.int64, np.uint32, np.uint64, np.int16])
@pytest.mark.parametrize("layout", ["c", "fortran", "strided"])
def test_unchecked_volume_is_mass_properties_bits(dtype, layout):
    v, f = uv_sphere(radius=3.0, rings=40, segments=77, centre=(10.0, -2.0, 0.5))
    f = np.asarray(f, dtype=dtype)
    if layout == "fortran":
        v, f = np.asfortranarray(v), np.asfortranarray(f)
    elif layout == "strided":
        v = np.repeat(v, 2, axis=0)[::2]
        f = np.repeat(f, 2, axis=0)[::2]
    mp = meshvol.Mesh(v, f).mass_properties(check=False)
    value, bound = meshvol.volume(v, f, check=False)
    assert same_bits(value, mp.signed_volume) and same_bits(bound, mp.volume_error_bound)


def test_checked_volume_is_the_checked_mass_properties():
    v, f = box((0.0, 0.0, 0.0), (1.0, 2.0, 3.0))
    inward = np.asarray(f)[:, ::-1].copy()
    assert meshvol.volume(v, inward, check=False)[0] == -6.0
    with pytest.warns(meshvol.MeshWarning, match="wound inward"):
        value, bound = meshvol.volume(v, inward)
    with pytest.warns(meshvol.MeshWarning):
        mp = meshvol.Mesh(v, inward).mass_properties()
    assert (value, bound) == (mp.volume, mp.volume_error_bound) == (6.0, mp.volume_error_bound)
    # Two boxes, one inside the other: the checked solid has a cavity.
    v2, f2 = box((0.25, 0.25, 0.25), (0.75, 0.75, 0.75))
    vv = np.concatenate([v, v2])
    ff = np.concatenate([np.asarray(f), np.asarray(f2) + len(v)])
    assert meshvol.volume(vv, ff, check=False)[0] == 6.125
    with pytest.warns(meshvol.MeshWarning, match="wound against its role"):
        assert meshvol.volume(vv, ff)[0] == 5.875


def test_float32_and_lists_are_copied_and_measured_the_same():
    v, f = box((0.0, 0.0, 0.0), (2.0, 2.0, 2.0))
    expected = meshvol.volume(np.asarray(v, float), np.asarray(f, np.int64), check=False)
    assert meshvol.volume(np.asarray(v, np.float32), f, check=False) == expected
    assert meshvol.volume(np.asarray(v).tolist(), np.asarray(f).tolist(), check=False) == expected


def test_borrowed_arrays_are_not_copied_or_changed():
    v, f = uv_sphere()
    v, f = np.ascontiguousarray(v, float), np.ascontiguousarray(f, np.int32)
    v.flags.writeable = False
    before = (v.copy(), f.copy())
    meshvol.volume(v, f, check=False)
    assert np.array_equal(v, before[0]) and np.array_equal(f, before[1])


def test_bad_indices_and_coordinates_raise():
    v, f = box()
    f = np.asarray(f, np.int64).copy()
    f[5, 1] = 8
    with pytest.raises(meshvol.InvalidMeshError, match="face 5 uses vertex index 8"):
        meshvol.volume(np.asarray(v, float), f, check=False)
    f[5, 1] = -1
    with pytest.raises(meshvol.InvalidMeshError, match="face 5 uses vertex index -1, which is negative"):
        meshvol.volume(np.asarray(v, float), f, check=False)
    v = np.asarray(v, float).copy()
    v[3, 2] = np.nan
    with pytest.raises(meshvol.InvalidMeshError, match="non-finite"):
        meshvol.volume(v, np.asarray(box()[1]), check=False)
