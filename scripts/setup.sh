#!/usr/bin/env bash
# Installs what TilePattern needs on a fresh Debian/Ubuntu machine: a C/C++ compiler (the build
# compiles COIN-OR's CBC and Clp from source and links them statically; C tests), the system's
# CBC and Clp libraries and pkg-config (for `--no-default-features` builds, which link them
# dynamically, and the package check's counter-example), valgrind (C tests), mono with NUnit (C#
# wrapper tests), Python's venv (Python package tests, which install numpy, compas,
# rhino3dm and pytest from PyPI into target/py-venv; the Grasshopper compile check, which installs
# the published RhinoCommon/Grasshopper type stubs into target/gh-venv), and cbindgen 0.29.2 (header check). System packages need root or sudo;
# otherwise it prints the command to run.
set -euo pipefail

if ! command -v cargo >/dev/null 2>&1; then
  echo "TilePattern needs a Rust toolchain (cargo): install it with rustup (https://rustup.rs) and run this again." >&2
  exit 1
fi

# System.Drawing and System.Windows.Forms: the Grasshopper components compile against them (make gh-compile).
packages=(coinor-libcbc-dev coinor-libclp-dev pkg-config g++ valgrind mono-mcs mono-runtime nunit-console libnunit-cil-dev
  libmono-system-drawing4.0-cil libmono-system-windows-forms4.0-cil)
# The Python tests make a venv; Debian's own python3 needs python3-venv for that.
python3 -c "import ensurepip, venv" >/dev/null 2>&1 || packages+=(python3-venv)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if ! command -v apt-get >/dev/null 2>&1; then
    echo "Please install: the CBC MILP solver library (C interface), pkg-config, a C++ compiler, valgrind, mono (mcs, runtime, NUnit 2.6 console)." >&2
    exit 1
  fi
  if [ "$(id -u)" -eq 0 ]; then
    sudo=()
  elif command -v sudo >/dev/null 2>&1; then
    sudo=(sudo)
  else
    echo "Missing packages: ${missing[*]}. Run as root: apt-get update && apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
  echo "installing ${missing[*]} ..."
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# make lint: rustfmt and clippy come with rustup's default profile, not its minimal one.
if command -v rustup >/dev/null 2>&1; then
  for component in rustfmt clippy; do
    rustup component list --installed 2>/dev/null | grep -q "^$component" ||
      rustup component add "$component"
  done
fi

cbindgen_version="0.29.2"
if [ "$(cbindgen --version 2>/dev/null || true)" != "cbindgen $cbindgen_version" ]; then
  echo "installing cbindgen $cbindgen_version ..."
  cargo install --quiet --locked cbindgen --version "$cbindgen_version"
fi
