#!/usr/bin/env bash
# Tests of the Python package (python/): a venv at target/py-venv with pytest, numpy,
# compas and rhino3dm from PyPI, the library from target/release (build it first with
# `cargo build --release --lib`; `make python-test` does both), then pytest over
# python/tests and the package's docstring examples.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/target/py-venv"
lib="$root/target/release/libtilepattern.so"
case "$(uname -s)" in
  Darwin) lib="$root/target/release/libtilepattern.dylib" ;;
  MINGW* | MSYS* | CYGWIN*) lib="$root/target/release/tilepattern.dll" ;;
esac

if [ ! -f "$lib" ]; then
  echo "test-python.sh: $lib is missing; run \`cargo build --release --lib\` first" >&2
  exit 1
fi

python="$venv/bin/python"
[ -x "$python" ] || python="$venv/Scripts/python.exe"
if [ ! -x "$python" ]; then
  echo "test-python.sh: creating $venv"
  if ! python3 -m venv "$venv"; then
    echo "test-python.sh: python3 -m venv failed (on Debian/Ubuntu: apt-get install python3-venv)" >&2
    rm -rf "$venv"
    exit 1
  fi
  python="$venv/bin/python"
  [ -x "$python" ] || python="$venv/Scripts/python.exe"
fi
"$python" -m pip install --quiet --disable-pip-version-check \
  "pytest>=7.0" "numpy>=1.21" "compas>=2.0" "rhino3dm>=8.0"

export TILEPATTERN_LIB="$lib"
cd "$root/python"
exec "$python" -m pytest -q -p no:cacheprovider tests tilepattern "$@"
