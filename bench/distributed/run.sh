#!/usr/bin/env bash
# A grid larger than memory, written chunk by chunk: `meshvol grid --out cells.zarr` on a
# 1M-triangle sphere at 1024³ cells (8 GiB of float64 if every chunk were stored), with its
# time and peak memory (/usr/bin/time -v), and the in-memory throughput of a 512³ grid of
# the same sphere, in cells per second. Writes bench/distributed/RESULTS.md.
#
# Needs: cargo, /usr/bin/time, a Python with NumPy (PYTHON, else target/py-venv/bin/python
# from scripts/test-python.sh, else python3), and free disk for the store (about 5 GB:
# chunks that are all zeros are not stored). WORK (default target/bench-distributed)
# holds the mesh and the store; the store is deleted at the end unless KEEP=1.
# CELLS (default 1024) and CHUNKS (default 32,128,128) change the large run.
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$root/target}
work=${WORK:-$root/target/bench-distributed}
cells=${CELLS:-1024}
chunks=${CHUNKS:-32,128,128}
python=${PYTHON:-}
if [ -z "$python" ]; then
    if [ -x target/py-venv/bin/python ]; then python=target/py-venv/bin/python; else python=python3; fi
fi
mkdir -p "$work"

cargo build --release --locked --quiet -p meshvol-cli
meshvol=$CARGO_TARGET_DIR/release/meshvol

mesh=$work/sphere_1M.stl
if [ ! -f "$mesh" ]; then
    PYTHONPATH=bench/compare "$python" -c "
import meshgen
v, f, _ = meshgen.uv_sphere(1_000_000)
meshgen.write_stl_binary('$mesh', v, f)
print(len(f), 'triangles')"
fi

# One run: its JSON summary to $1.json, /usr/bin/time's report to $1.time.
timed() {
    local name=$1
    shift
    /usr/bin/time -v "$meshvol" "$@" --json >"$work/$name.json" 2>"$work/$name.time"
}
field() { grep -F "$2" "$work/$1.time" | sed 's/.*: //'; }
key() { "$python" -c "import json,sys; print(json.load(open('$work/$1.json'))['$2'])"; }

df -h "$work" | tail -1
load=$(cut -d' ' -f1-3 /proc/loadavg)
store=$work/cells.zarr
rm -rf "$store"
sync
# In memory first: the Zarr run leaves gigabytes of dirty pages that the kernel writes
# back for a while after it ends.
timed memory grid "$mesh" --cells 512,512,512
timed zarr grid "$mesh" --cells "$cells,$cells,$cells" --chunks "$chunks" --out "$store"
stored=$(du -sb "$store" | cut -f1)
chunk_files=$(find "$store/c" -type f | wc -l)
[ "${KEEP:-0}" = 1 ] || rm -rf "$store"

cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')
threads=$(nproc)
"$python" - "$work" "$cells" "$chunks" "$stored" "$chunk_files" "$cpu" "$threads" "$load" <<'EOF' | tee bench/distributed/RESULTS.md
import json, re, sys
work, cells, chunks, stored, chunk_files, cpu, threads, load = sys.argv[1:]
cells, stored, chunk_files = int(cells), int(stored), int(chunk_files)

def run(name):
    summary = json.load(open(f"{work}/{name}.json"))
    time = open(f"{work}/{name}.time").read()
    wall = re.search(r"Elapsed \(wall clock\) time.*: (.*)", time).group(1)
    parts = [float(p) for p in wall.split(":")]
    seconds = sum(p * 60 ** i for i, p in enumerate(reversed(parts)))
    peak = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", time).group(1))
    return summary, seconds, peak / 1024

z, z_wall, z_peak = run("zarr")
m, m_wall, m_peak = run("memory")
n = cells**3
cx, cy, cz = (int(c) for c in chunks.split(","))
total_chunks = -(-cells // cx) * -(-cells // cy) * -(-cells // cz)
print(f"""# A grid larger than memory: `meshvol grid --out cells.zarr`

Made by `bench/distributed/run.sh` on {cpu}, {threads} threads (load average {load} when
it started: other work shared the machine). The mesh: a UV sphere of radius 100 with 1M
triangles (binary STL), its bounding box as the grid's bounds.

| run | cells | wall time | cell volumes computed in | peak memory (RSS) | cells/s (computing) |
|---|---|---|---|---|---|
| Zarr, chunks {cx}×{cy}×{cz} | {cells}³ = {n:,} | {z_wall:.1f} s | {z['seconds']:.1f} s | {z_peak:,.0f} MiB | {n / z['seconds']:.3g} |
| in memory (no output) | 512³ = {512**3:,} | {m_wall:.1f} s | {m['seconds']:.1f} s | {m_peak:,.0f} MiB | {512**3 / m['seconds']:.3g} |

- The Zarr array would hold {n * 8 / 2**30:.1f} GiB of float64; {chunk_files:,} of its {total_chunks:,} chunks
  were stored ({stored / 2**30:.2f} GiB on disk): a chunk whose cells are all +0.0 (outside the
  sphere) is left to the fill value.
- Memory holds one chunk row ({cx} × {cells} × {cells} cells, {cx * cells * cells * 8 / 2**20:,.0f} MiB) plus the mesh,
  not the grid: the in-memory 512³ run, an eighth of the cells, needs its whole
  {512**3 * 8 / 2**20:,.0f} MiB array.
- Wall time includes reading and checking the mesh; for the Zarr run, also writing the
  chunks, uncompressed, which is most of it here (`seconds` in the JSON counts the cell
  volumes only).
- Σ cells: {z['total']!r} (1024³) and {m['total']!r} (512³) against the mesh's volume
  {z['mesh_volume']!r}.
""")
EOF
