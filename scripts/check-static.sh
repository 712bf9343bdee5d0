#!/usr/bin/env bash
# Checks that a native library needs no shared COIN-OR library (CBC, Clp, CoinUtils, Cgl, Osi
# and their solver/interface libraries): with the default feature static-coin they are
# compiled from source and linked in (build.rs). Lists what ldd shows either way.
set -euo pipefail
lib=${1:?usage: check-static.sh LIBRARY}
deps=$(ldd "$lib")
echo "$deps" | sed 's/^/  /'
coin=$(echo "$deps" | grep -E 'lib(Cbc|CbcSolver|Clp|ClpSolver|CoinUtils|Cgl|Osi|OsiClp|OsiCbc)[.-]' || true)
if [ -n "$coin" ]; then
  echo "check-static: $lib needs shared COIN-OR libraries:" >&2
  echo "$coin" >&2
  echo "check-static: build with the default feature static-coin (not --no-default-features)" >&2
  exit 1
fi
# The solvers are in the library itself (local symbols: only tp_* is exported).
symbols=$(nm --defined-only "$lib" 2>/dev/null || true)
for symbol in Cbc_newModel Clp_newModel; do
  if ! grep -q " $symbol\$" <<<"$symbols"; then
    echo "check-static: $symbol is not defined in $lib" >&2
    exit 1
  fi
done
echo "check-static: $lib links no shared COIN-OR library (CBC and Clp are inside)"
