#!/usr/bin/env bash
# Fails when include/tilepattern.h differs from what the pinned cbindgen generates from
# src/ffi, or when a name without the tp_/Tp/TP_ prefix leaks into the header.
set -euo pipefail
cd "$(dirname "$0")/.."
want="cbindgen 0.29.2"
have=$(cbindgen --version 2>/dev/null || true)
if [ "$have" != "$want" ]; then
  echo "header check needs $want (found: ${have:-none}); run scripts/setup.sh" >&2
  exit 1
fi
fresh=$(mktemp)
trap 'rm -f "$fresh"' EXIT
cbindgen --quiet --config cbindgen.toml --crate tilepattern --output "$fresh"
if ! diff -u include/tilepattern.h "$fresh"; then
  echo "include/tilepattern.h is out of date: run 'make header' and commit it" >&2
  exit 1
fi
leaks=$(grep -E '^(#define|typedef|struct|enum) ' include/tilepattern.h | grep -vE '(TILEPATTERN_H|[ *(](tp_|Tp|TP_))' || true)
if [ -n "$leaks" ]; then
  echo "names without the tp_/Tp/TP_ prefix in the header:" >&2
  echo "$leaks" >&2
  exit 1
fi
echo "header: up to date"
