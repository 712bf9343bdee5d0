#!/usr/bin/env bash
# Installs what TilePattern needs on a fresh Debian/Ubuntu machine: the CBC solver library
# (and pkg-config, through which the build finds it). Run as root, or with sudo available;
# otherwise it prints the command to run.
set -euo pipefail

packages=(coinor-libcbc-dev pkg-config)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done

if ! command -v cargo >/dev/null 2>&1; then
  echo "TilePattern needs a Rust toolchain (cargo): install it with rustup (https://rustup.rs) and run this again." >&2
  exit 1
fi

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
if ! command -v apt-get >/dev/null 2>&1; then
  echo "Please install the CBC MILP solver library (C interface, e.g. 'coinor-cbc' from your package manager) and pkg-config." >&2
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
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}"
