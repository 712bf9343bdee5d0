#!/usr/bin/env bash
# `make package-test`: lays out the Yak folder (scripts/package.sh, which checks it with
# scripts/check-package.py), then proves the check bites: copies of the folder with one
# thing wrong must each fail it with the expected words.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/package.sh
good=target/yak
broken=target/yak-broken
passed=0
failed=0

# expect_failure NAME WORDS COMMAND...: COMMAND breaks the copy in $broken.
expect_failure() {
  local name=$1 words=$2
  shift 2
  rm -rf "$broken"
  cp -r "$good" "$broken"
  "$@"
  local log
  if log=$(python3 scripts/check-package.py "$broken" 2>&1); then
    echo "package self-test $name: FAILED: the broken package passed" >&2
    failed=$((failed + 1))
  elif ! grep -qF -- "$words" <<<"$log"; then
    echo "package self-test $name: FAILED: it failed without '$words': $log" >&2
    failed=$((failed + 1))
  else
    echo "package self-test $name: caught ($(grep -F -m1 -- "$words" <<<"$log"))"
    passed=$((passed + 1))
  fi
}

rid=$(ls "$good/runtimes")
lib=$(ls "$good/runtimes/$rid/native")
expect_failure no-native "holds no native library" rm -rf "$broken/runtimes"
expect_failure no-wrapper "TilePattern.dll is missing" rm "$broken/TilePattern.dll"
expect_failure no-gha "TilePattern.Grasshopper.gha is missing" rm "$broken/TilePattern.Grasshopper.gha"
expect_failure wrong-rid "expected exactly tilepattern.dll" mv "$broken/runtimes/$rid" "$broken/runtimes/win-x64"
expect_failure wrong-arch "is not a" mv "$broken/runtimes/$rid" "$broken/runtimes/${rid%-*}-arm64"
expect_failure not-an-assembly "is not a .NET assembly" cp "$good/runtimes/$rid/native/$lib" "$broken/TilePattern.dll"
expect_failure stale-version "version 0.0.1, Cargo.toml has" sed -i 's/^version: .*/version: 0.0.1/' "$broken/manifest.yml"
expect_failure placeholder-url "is a placeholder" sed -i '$a url: https://github.com/' "$broken/manifest.yml"
expect_failure no-icon "icon.png is missing" rm "$broken/icon.png"
expect_failure stray-file "does not belong" touch "$broken/notes.txt"
coin=$(ldconfig -p 2>/dev/null | grep -o '/[^ ]*libCbcSolver\.so[^ ]*' | head -n 1 || true)
if [ -n "$coin" ]; then
  # A library that needs a shared COIN-OR library (the system's own) must be refused.
  expect_failure dynamic-coin "needs COIN-OR libraries" cp "$coin" "$broken/runtimes/$rid/native/$lib"
fi
rm -rf "$broken"
echo "package self-test: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
