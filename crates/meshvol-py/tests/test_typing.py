"""The stubs under mypy --strict: typing_sample.py (user code over the API added by
issue 31) type-checks, and runs."""

import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).parent


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
