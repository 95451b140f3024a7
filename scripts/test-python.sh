#!/usr/bin/env bash
# Builds meshvol's Python bindings (crates/meshvol-py) and runs their pytest suite, in a
# virtual environment under target/py-venv.
#
# Idempotent and quick on re-runs: the venv and the pinned tools of
# crates/meshvol-py/requirements-test.txt are installed once (again when that file
# changes); the extension is built by cargo incrementally, in the debug profile and in
# CARGO_TARGET_DIR (default target/, so the dependencies `cargo test` built are reused),
# packed as a wheel and reinstalled from the local file (no network after the first run).
#
# MESHVOL_WHEEL, when set, names a wheel to test instead (CI: the release wheel
# scripts/dist.sh built from the same sources), so that no second wheel is built.
# MESHVOL_BIN, when set (or when $CARGO_TARGET_DIR/debug/meshvol is newer than the
# sources), names a meshvol command the tests compare the bindings' facts with.
# Arguments are passed to pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
venv=$root/target/py-venv
requirements=crates/meshvol-py/requirements-test.txt
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$root/target}

if [ ! -x "$venv/bin/python" ]; then
    "${PYTHON:-python3}" -m venv "$venv"
fi
if ! cmp -s "$requirements" "$venv/requirements-installed.txt"; then
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements"
    cp "$requirements" "$venv/requirements-installed.txt"
fi

wheel=${MESHVOL_WHEEL:-}
if [ -z "$wheel" ]; then
    wheels=$CARGO_TARGET_DIR/py-wheels
    rm -rf "$wheels"
    "$venv/bin/maturin" build --quiet --profile dev --strip --interpreter "$venv/bin/python" \
        --manifest-path crates/meshvol-py/Cargo.toml --out "$wheels"
    wheel=$(echo "$wheels"/meshvol-*.whl)
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-index --no-deps \
    --force-reinstall "$wheel"

if [ -z "${MESHVOL_BIN:-}" ]; then
    command=$CARGO_TARGET_DIR/debug/meshvol
    if [ -x "$command" ] && [ -z "$(find crates/meshvol/src crates/meshvol-io/src \
        crates/meshvol-report/src crates/meshvol-cli/src -newer "$command" -print -quit)" ]; then
        export MESHVOL_BIN=$command
    fi
fi
exec "$venv/bin/python" -m pytest crates/meshvol-py/tests -q "$@"
