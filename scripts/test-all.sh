#!/usr/bin/env bash
# Every test meshvol has: the Rust workspace (unit, integration and doc tests; the
# corpus tests run when ../shared/corpus is there and skip, saying so, when it is not),
# then the Python bindings' pytest suite (in a virtualenv under target/py-venv).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --locked
scripts/test-python.sh
