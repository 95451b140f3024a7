#!/usr/bin/env bash
# Every test meshvol has: the Rust workspace (unit, integration and doc tests; the
# corpus tests run when ../shared/corpus is there and skip, saying so, when it is not),
# then the Python bindings' pytest suite (in a virtualenv under target/py-venv).
#
# MESHVOL_BIN, when set, names the `meshvol` command that the command's tests
# (crates/meshvol-cli/tests) and the Python suite run, instead of the debug one cargo
# builds: CI names the release binary scripts/dist.sh has just built from the same tree,
# which takes the command's suites from about 3.5 minutes to under one (2-core machine,
# 2026-11-27). They refuse a binary older than the sources.
set -euo pipefail
if [ -n "${MESHVOL_BIN:-}" ]; then
    # Absolute: cargo runs each crate's tests in that crate's folder.
    MESHVOL_BIN=$(realpath "$MESHVOL_BIN")
    export MESHVOL_BIN
fi
cd "$(dirname "$0")/.."
# On a fresh machine: the Rust toolchain, a C compiler and Python's venv first.
. scripts/toolchain.sh
cargo test --locked
scripts/test-python.sh
