#!/usr/bin/env bash
# Runs each cargo-fuzz target for N seconds (default 60) and fails on a crash. cargo-fuzz
# needs nightly features; with the stable toolchain RUSTC_BOOTSTRAP=1 enables them.
# Crash inputs land in fuzz/artifacts/<target>/; add them to fuzz/regressions/ when fixed.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "installing cargo-fuzz ..."
  cargo install --quiet --locked cargo-fuzz
fi
export RUSTC_BOOTSTRAP=1
for target in obj_reader mesh_validation ffi_pipeline; do
  mkdir -p "fuzz/corpus/$target"
  echo "fuzzing $target for $seconds s"
  (cd fuzz && cargo fuzz run --release "$target" "corpus/$target" -- -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=20 2>&1) \
    | grep -E "^(#[0-9]+.*DONE|Done|==[0-9]+==|SUMMARY|Test unit written|INFO: Running with|thread .* panicked)" || true
  if ls "fuzz/artifacts/$target"/crash-* "fuzz/artifacts/$target"/timeout-* >/dev/null 2>&1; then
    echo "$target found a failing input: fuzz/artifacts/$target/" >&2
    exit 1
  fi
done
