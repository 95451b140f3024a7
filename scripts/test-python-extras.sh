#!/usr/bin/env bash
# The `dask` extra as a user gets it from the package index: a fresh virtualenv (made
# again on every run, under target/py-extras-venv), the wheel installed with `[dask]`
# from the index (pip's resolver choosing dask, distributed and zarr, as for
# `pip install "meshvol[dask]"`), then scripts/test-python-extras.py: meshvol.dask.measure
# and meshvol.dask.grid on a two-process LocalCluster, checked against the command
# (MESHVOL_BIN) and the non-Dask Python path. The pinned test venv (target/py-venv)
# cannot catch a broken pair: its versions are pinned by hand.
#
# MESHVOL_WHEEL names the wheel (CI: target/dist/meshvol-*.whl, from scripts/dist.sh);
# unset, the one scripts/test-python.sh last built (target/py-wheels). MESHVOL_BIN, when
# set, names the command the results are compared with.
#
# Needs the package index on every run: pip resolves the extra against it. What it
# downloads is kept in ${XDG_CACHE_HOME:-~/.cache}/meshvol/py-extras-wheels, outside the
# checkout so that CI's clean clones share it (pip's own HTTP cache keeps nothing from
# an index or mirror that sends no caching headers), so a rerun downloads only what
# changed there (a new dask release) and installs the rest from that folder. Measured
# on the shared 2-core machine, 2026-12-07, load average 5 to 7 from other builds: 83 s
# with nothing downloaded (64 s resolving, downloading 96 MB and installing), 43 s on
# rerun (22 s resolving and installing, 20 s the checks).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
venv=$root/target/py-extras-venv
wheels=${XDG_CACHE_HOME:-$HOME/.cache}/meshvol/py-extras-wheels
wheel=${MESHVOL_WHEEL:-$(echo "$root"/target/py-wheels/meshvol-*.whl)}
if [ ! -f "$wheel" ]; then
    echo "test-python-extras.sh: no wheel at $wheel: run scripts/test-python.sh or scripts/dist.sh wheel first" >&2
    exit 1
fi
if [ -n "${MESHVOL_BIN:-}" ]; then
    MESHVOL_BIN=$(realpath "$MESHVOL_BIN")
    export MESHVOL_BIN
fi

start=$SECONDS
rm -rf "$venv"
"${PYTHON:-python3}" -m venv "$venv"
pip=("$venv/bin/python" -m pip --quiet --disable-pip-version-check)
# The resolver's choice from the index (files already in $wheels are not fetched
# again), then the install from those files.
"${pip[@]}" download --dest "$wheels" --find-links "$wheels" "$wheel[dask]"
rm -f "$wheels"/meshvol-*.whl
"${pip[@]}" install --no-compile --no-index --find-links "$wheels" "$wheel[dask]"
installed=$SECONDS
"${pip[@]}" check
"$venv/bin/python" scripts/test-python-extras.py
echo "test-python-extras.sh: passed in $((SECONDS - start)) s (install $((installed - start)) s)"
