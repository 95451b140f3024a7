#!/usr/bin/env bash
# Builds meshvol's release artifacts, which install without a Rust toolchain, into
# target/dist/, and prints each one's size:
#
#   meshvol-VERSION-x86_64-unknown-linux-musl
#       the `meshvol` command, statically linked against musl (runs on any x86-64 Linux,
#       whatever its glibc), stripped. Install: copy it onto the PATH.
#   meshvol-VERSION-cp39-abi3-manylinux2014_x86_64.manylinux_2_17_x86_64.whl
#       the Python package: one wheel for CPython 3.9 and later (abi3), linked by zig
#       against glibc 2.17 (manylinux2014: any Linux from 2014 on). Install: pip install.
#
# Usage: scripts/dist.sh [binary|wheel]   (default both)
#
# Needs: rustup (the musl target is added), musl-gcc for mimalloc's C code (apt-get
# install musl-tools, done here when running as root on Debian/Ubuntu), python3 with
# venv. maturin and zig come from PyPI, pinned in crates/meshvol-py/requirements-dist.txt,
# into target/dist-venv (once). Cargo profile `release-dist`: the release profile's
# code (thin LTO, one codegen unit) without debug info (the 48 MB of a plain `cargo
# build --release`), stripped.
#
# Part of .ci/run, whose Python tests then run against this wheel (not a second, debug
# one). Measured with nothing of the profile built (target/dist-venv already made) on the
# shared 2-core machine, 2026-11-26 21:37 UTC, load average 2.5 to 7 from other builds:
# 6m00s wall, 5m32s user + 21 s system (binary 3m26s, wheel 2m30s); at 20:15 UTC with
# target/dist-venv made too, load 3 to 7: 8m50s. The Python suite took 15 to 26 s on this
# wheel against 100 s on the debug one.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
dist=$root/target/dist
what=${1:-all}
version=$(sed -n 's/^version = "\(.*\)"$/\1/p' Cargo.toml | head -n 1)
mkdir -p "$dist"

size() { printf '  %-72s %6s\n' "$(basename "$1")" "$(du -h "$1" | cut -f1)"; }

binary() {
    local target=x86_64-unknown-linux-musl
    if ! rustup target list --installed 2>/dev/null | grep -qx "$target"; then
        rustup target add "$target"
    fi
    if ! command -v musl-gcc >/dev/null; then
        if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
            apt-get install -y -qq musl-tools >/dev/null 2>&1 ||
                { apt-get update -qq && apt-get install -y -qq musl-tools >/dev/null; }
        else
            echo "dist.sh: musl-gcc not found: install musl-tools (Debian/Ubuntu) or musl-gcc" >&2
            exit 1
        fi
    fi
    cargo build --profile release-dist --locked -p meshvol-cli --target "$target"
    local out=$dist/meshvol-$version-$target
    cp "target/$target/release-dist/meshvol" "$out"
    strip "$out"
    # Static, and it runs: the README's first command.
    if ldd "$out" >/dev/null 2>&1 && ! ldd "$out" 2>&1 | grep -q "statically linked"; then
        echo "dist.sh: $out is dynamically linked" >&2
        exit 1
    fi
    "$out" --quiet samples/flanged-bushing.stl | grep -q "volume             26183.29623547"
}

wheel() {
    local venv=$root/target/dist-venv requirements=crates/meshvol-py/requirements-dist.txt
    if [ ! -x "$venv/bin/python" ]; then
        "${PYTHON:-python3}" -m venv "$venv"
    fi
    if ! cmp -s "$requirements" "$venv/requirements-installed.txt"; then
        "$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements"
        cp "$requirements" "$venv/requirements-installed.txt"
    fi
    rm -f "$dist"/meshvol-*.whl
    PATH=$venv/bin:$PATH "$venv/bin/maturin" build --profile release-dist --locked --strip --zig \
        --compatibility manylinux2014 --manifest-path crates/meshvol-py/Cargo.toml \
        --out "$dist"
    # It installs and measures (in target/dist-venv, with the pinned NumPy).
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-index --no-deps \
        --force-reinstall "$dist"/meshvol-*.whl
    "$venv/bin/python" -c 'import meshvol, sys
v = meshvol.load("samples/flanged-bushing.stl").mass_properties().volume
sys.exit(abs(v - 26183.29623547592) > 1e-9)'
}

case $what in
    binary) binary ;;
    wheel) wheel ;;
    all) binary; wheel ;;
    *) echo "usage: scripts/dist.sh [binary|wheel]" >&2; exit 2 ;;
esac

echo "target/dist:"
for f in "$dist"/meshvol-*; do size "$f"; done
