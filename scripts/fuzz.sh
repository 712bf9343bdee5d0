#!/usr/bin/env bash
# Runs each cargo-fuzz target for N seconds (default 60), one process each, one after the
# other, and fails on a crash, a timeout, a leak or an out-of-memory input.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]     targets: obj_reader mesh_validation ffi_pipeline
#
# cargo-fuzz needs nightly features (-Zsanitizer=address); with the stable toolchain
# RUSTC_BOOTSTRAP=1 enables them, which is what this script does. Inputs start from the
# growing corpus fuzz/corpus/<target>/ (not committed) and the kept inputs
# fuzz/regressions/<target>/ (committed; `cargo test --test fuzz_regressions` replays them).
# A failing input lands in fuzz/artifacts/<target>/: fix the bug, then move the input to
# fuzz/regressions/<target>/. Prints the executions per target.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(obj_reader mesh_validation ffi_pipeline)
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "installing cargo-fuzz ..."
  cargo install --quiet --locked cargo-fuzz
fi
export RUSTC_BOOTSTRAP=1
(cd fuzz && cargo fuzz build --release)
failed=0
total=0
for target in "${targets[@]}"; do
  mkdir -p "fuzz/corpus/$target" "fuzz/artifacts/$target"
  log="fuzz/artifacts/$target/last-run.log"
  before=$(ls "fuzz/artifacts/$target" | grep -cE '^(crash|timeout|leak|oom)-' || true)
  status=0
  (cd fuzz && cargo fuzz run --release "$target" "corpus/$target" "regressions/$target" -- \
    -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=20 -print_final_stats=1) >"$log" 2>&1 || status=$?
  runs=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$log" | grep -oE '[0-9]+$' | tail -1 || true)
  after=$(ls "fuzz/artifacts/$target" | grep -cE '^(crash|timeout|leak|oom)-' || true)
  echo "$target: ${runs:-?} executions in $seconds s (exit $status)"
  total=$((total + ${runs:-0}))
  if [ "$status" -ne 0 ] || [ "$after" -gt "$before" ]; then
    echo "$target found a failing input (see $log):" >&2
    grep -E "^(==[0-9]+==ERROR|SUMMARY|thread .* panicked|Test unit written|artifact_prefix)" "$log" | head -20 >&2 || true
    failed=1
  fi
done
echo "all targets: $total executions"
exit "$failed"
