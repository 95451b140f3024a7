"""The stubs under mypy --strict: typing_sample.py (user code over the API added by
issue 31) type-checks, and runs; and mypy's stubtest finds the stubs (__init__.pyi,
_meshvol.pyi, and the typed Python modules) complete and true to the runtime: every
public name, signature, default and property (issue 52, item 2)."""

import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).parent
PACKAGE = HERE.parent


def test_sample_runs(tmp_path):
    sys.path.insert(0, str(HERE))
    try:
        import typing_sample
    finally:
        sys.path.remove(str(HERE))
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        typing_sample.main(tmp_path)


def test_stubs_pass_mypy_strict():
    pytest.importorskip("mypy")
    run = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--no-incremental", "--cache-dir=/dev/null",
         str(HERE / "typing_sample.py")],
        capture_output=True, text=True,
    )
    assert run.returncode == 0, run.stdout + run.stderr


def test_stubtest_finds_the_stubs_true_to_the_runtime(tmp_path):
    # mypy is pinned in requirements-test.txt: no skip here.
    run = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "meshvol",
         "--mypy-config-file", str(PACKAGE / "pyproject.toml"),
         "--allowlist", str(PACKAGE / "stubtest-allowlist.txt")],
        capture_output=True, text=True, cwd=tmp_path,
    )
    assert run.returncode == 0, run.stdout + run.stderr
    # Every module of the package was checked, the extension's stub among them.
    assert "no issues found in 6 modules" in run.stdout, run.stdout
