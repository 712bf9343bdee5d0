#!/usr/bin/env bash
# The Python package's tests: a venv under target/ with numpy, compas, rhino3dm and pytest
# from PyPI, the library from target/release, pytest over python/tests and the package's
# docstring examples.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "pytest>=7" "numpy>=1.20" "compas>=2.0" "rhino3dm>=8.0"
export TILEPATTERN_LIB="$PWD/target/release/libtilepattern.so"
cd python
"../$venv/bin/python" -m pytest -q -s tests tilepattern
