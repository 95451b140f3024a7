#!/usr/bin/env bash
# Runs every fuzz target for SECONDS each (default 300), one after another, one job:
#   fuzz/run.sh [SECONDS] [TARGET...]
# Builds with cargo-fuzz on the stable toolchain (RUSTC_BOOTSTRAP=1 lets it pass the
# sanitizer flag), keeps the growing corpora in $FUZZ_WORK (default /tmp/meshvol-fuzz)
# with the committed seeds/ as read-only extra corpora, and prints libFuzzer's final
# stats for each target. Crashes land in $FUZZ_WORK/artifacts/TARGET/.
set -euo pipefail
cd "$(dirname "$0")"
seconds=${1:-300}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(stl obj off ply threemf threemf_model gltf glb sniff)
fi
work=${FUZZ_WORK:-/tmp/meshvol-fuzz}
target_dir=${FUZZ_TARGET_DIR:-$work/target}
RUSTC_BOOTSTRAP=1 CARGO_BUILD_JOBS=1 cargo fuzz build -O --target-dir "$target_dir"
for t in "${targets[@]}"; do
    mkdir -p "$work/corpus/$t" "$work/artifacts/$t"
    echo "== $t: ${seconds}s"
    "$target_dir/x86_64-unknown-linux-gnu/release/$t" "$work/corpus/$t" "seeds/$t" \
        -max_total_time="$seconds" -print_final_stats=1 -rss_limit_mb=2048 -timeout=10 \
        -artifact_prefix="$work/artifacts/$t/" 2>&1 |
        grep -E "^(stat::|Done|==|SUMMARY|INFO: (Loaded|seed))|panicked|ERROR|crash-|leak-|timeout-|oom-" || true
done
# Every crash or timeout becomes a regression input, read by every test run
# (crates/meshvol-io/tests/regressions.rs): commit it with the fix.
for t in "${targets[@]}"; do
    for f in "$work/artifacts/$t"/crash-* "$work/artifacts/$t"/timeout-* "$work/artifacts/$t"/oom-*; do
        [ -e "$f" ] || continue
        mkdir -p "regressions/$t"
        cp -n "$f" "regressions/$t/"
        echo "kept $f as regressions/$t/$(basename "$f")"
    done
done
