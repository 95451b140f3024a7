# Sourced by the quick start's two commands (scripts/meshvol, scripts/test-all.sh) and by
# .ci/run: what building meshvol needs on a fresh machine with only a shell and a
# network. The Rust toolchain (rustup's minimal profile, into ~/.cargo) when there is no
# `cargo`; and, as root on Debian or Ubuntu, a C compiler (mimalloc's C code), Python
# with venv (the Python tests), and curl with CA certificates (rustup's download) when
# they are missing. Elsewhere it says what is missing.

missing_system=()
command -v cc >/dev/null || missing_system+=(build-essential)
command -v python3 >/dev/null && python3 -c 'import venv, ensurepip' 2>/dev/null \
    || missing_system+=(python3 python3-venv)
command -v curl >/dev/null || missing_system+=(curl)
[ -e /etc/ssl/certs/ca-certificates.crt ] || missing_system+=(ca-certificates)
if [ ${#missing_system[@]} -gt 0 ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        apt-get update -qq && apt-get install -y -qq "${missing_system[@]}" >/dev/null
    else
        echo "meshvol: needs ${missing_system[*]} (a C compiler; Python 3 with venv; curl and CA certificates):" \
            "install them with your system's package manager" >&2
    fi
fi
if ! command -v cargo >/dev/null; then
    if [ ! -x "$HOME/.cargo/bin/cargo" ]; then
        echo "meshvol: installing the Rust toolchain (rustup, minimal profile) into ~/.cargo" >&2
        curl --proto '=https' --tlsv1.2 -sSf https://sh.rustup.rs \
            | sh -s -- -y --profile minimal >&2
    fi
    . "$HOME/.cargo/env"
fi
unset missing_system
