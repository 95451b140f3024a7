#!/usr/bin/env bash
# The thread-scaling table: every checked command (and the unchecked volume, the grid
# kernel and the union) on UV spheres, at 1, 2, 4, ... threads, wall time of the whole
# command, each run with --timings so the stages that do not scale show.
#
#   bench/scaling/run.sh OUT_DIR [THREADS...]      (default threads: 1 2 4 8 16)
#
# MESHVOL and SPHERE name the binaries (default: target/release/meshvol and
# target/release/examples/sphere, built by `cargo build --release -p meshvol-cli` and
# `cargo build --release -p meshvol-io --example sphere`); SIZE (default 5000000) and
# SMALL (default 1000000) the spheres' triangle counts; RUNS (default 2) the runs of
# each cell. Writes OUT_DIR/runs.tsv (command, threads, run, wall s) and every run's JSON
# report (with its stage timings) as one line of OUT_DIR/reports.jsonl, in the same
# order; `bench/scaling/table.py OUT_DIR` prints the tables. Needs bash only.
set -euo pipefail
out=${1:?usage: run.sh OUT_DIR [THREADS...]}
shift
threads=("${@:-1 2 4 8 16}")
read -r -a threads <<<"${threads[*]}"
root=$(cd "$(dirname "$0")/../.." && pwd)
meshvol=${MESHVOL:-$root/target/release/meshvol}
sphere=${SPHERE:-$root/target/release/examples/sphere}
size=${SIZE:-5000000}
small=${SMALL:-1000000}
runs=${RUNS:-2}
mkdir -p "$out/data"
big=$out/data/big.stl
one=$out/data/small.stl
two=$out/data/small-shifted.stl
[ -s "$big" ] || "$sphere" "$size" "$big"
[ -s "$one" ] || "$sphere" "$small" "$one"
[ -s "$two" ] || "$sphere" "$small" "$two" 50
echo "machine: $(nproc) cores, $(uname -m); $("$meshvol" --version)" >"$out/machine.txt"

# name|arguments (FILE is the big sphere)
commands=(
    "volume --no-check|volume $big --no-check"
    "volume|volume $big"
    "check|check $big"
    "check --no-intersections|check $big --no-intersections"
    "profile|profile $big --levels 256"
    "below|below $big --plane 0,0,1,10"
    "section|section $big --plane z=10"
    "grid 256^3|grid $big --cells 256,256,256"
    "grid --no-check 512^3 (small)|grid $one --cells 512,512,512 --no-check"
    "union --no-check (small + small)|union $one $two --no-check"
)
printf 'command\tthreads\trun\twall_s\n' >"$out/runs.tsv"
: >"$out/reports.jsonl"
for entry in "${commands[@]}"; do
    name=${entry%%|*}
    read -r -a args <<<"${entry#*|}"
    for t in "${threads[@]}"; do
        for r in $(seq 1 "$runs"); do
            start=${EPOCHREALTIME/./}
            report=$("$meshvol" --threads "$t" -q --timings "${args[@]}" --json | tail -n 1) || true
            us=$((${EPOCHREALTIME/./} - start))
            echo "${report:-null}" >>"$out/reports.jsonl"
            printf '%s\t%s\t%s\t%d.%06d\n' "$name" "$t" "$r" $((us / 1000000)) $((us % 1000000)) |
                tee -a "$out/runs.tsv"
        done
    done
done
