#!/usr/bin/env bash
# `make package`: lays out the Yak package folder of the Grasshopper plug-in in target/yak/:
#
#   manifest.yml                      name, version (Cargo.toml's), authors, description,
#                                     url (Cargo.toml's homepage or repository, if set),
#                                     keywords, icon: grasshopper/manifest.yml completed
#   TilePattern.Grasshopper.gha       the components
#   TilePattern.dll                   the C# wrapper (dotnet/TilePattern)
#   icon.png                          grasshopper/Icons/TilePatternPlugin.png
#   runtimes/<rid>/native/<library>   the native library of each platform shipped
#
# then checks it (scripts/check-package.py). `yak build` in that folder makes the .yak; yak
# comes with Rhino (Windows, macOS), not here, so it is not run.
#
# Inputs (make variables or environment):
#   GHA     the .gha (default: target/gh/TilePattern.Grasshopper.gha from `make gh-compile`,
#           built against the checked stubs: fine for checking the layout; ship the one
#           `dotnet build` makes against the real RhinoCommon/Grasshopper, see grasshopper/README.md)
#   WRAPPER the wrapper dll (default: target/gh/TilePattern.dll, the one the .gha was compiled with)
#   NATIVE  space-separated <rid>=<file> pairs (default: this machine's rid=target/release's
#           library), e.g. "win-x64=tilepattern.dll win-arm64=arm64/tilepattern.dll
#           osx-arm64=libtilepattern.dylib osx-x64=libtilepattern.dylib" (one universal dylib twice)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out=target/yak

gha=${GHA:-target/gh/TilePattern.Grasshopper.gha}
wrapper=${WRAPPER:-target/gh/TilePattern.dll}
if [ -z "${NATIVE:-}" ]; then
  case "$(uname -s)-$(uname -m)" in
    Linux-x86_64) NATIVE="linux-x64=target/release/libtilepattern.so" ;;
    Linux-aarch64) NATIVE="linux-arm64=target/release/libtilepattern.so" ;;
    Darwin-arm64) NATIVE="osx-arm64=target/release/libtilepattern.dylib" ;;
    Darwin-x86_64) NATIVE="osx-x64=target/release/libtilepattern.dylib" ;;
    *) echo "package.sh: unknown platform $(uname -s)-$(uname -m); set NATIVE=<rid>=<file>" >&2; exit 1 ;;
  esac
fi
for file in "$gha" "$wrapper"; do
  if [ ! -f "$file" ]; then
    echo "package.sh: $file is missing (run make gh-compile, or set GHA/WRAPPER)" >&2
    exit 1
  fi
done

rm -rf "$out"
mkdir -p "$out"
cp "$gha" "$out/TilePattern.Grasshopper.gha"
cp "$wrapper" "$out/TilePattern.dll"
cp grasshopper/Icons/TilePatternPlugin.png "$out/icon.png"
rids=()
for pair in $NATIVE; do
  rid=${pair%%=*}
  file=${pair#*=}
  if [ "$rid" = "$pair" ] || [ ! -f "$file" ]; then
    echo "package.sh: NATIVE entry '$pair' is not <rid>=<existing file> (build the library: cargo build --release --lib)" >&2
    exit 1
  fi
  mkdir -p "$out/runtimes/$rid/native"
  cp "$file" "$out/runtimes/$rid/native/"
  # Without the release profile's debug information (mostly COIN-OR's): 76 MB -> 7 MB.
  case "$file" in
    *.so) if command -v strip >/dev/null 2>&1; then strip --strip-debug "$out/runtimes/$rid/native/$(basename "$file")"; fi ;;
  esac
  rids+=("$rid")
done

# The manifest: grasshopper/manifest.yml with Cargo.toml's version and url.
python3 - Cargo.toml grasshopper/manifest.yml "$out/manifest.yml" <<'EOF'
import re, sys
cargo, template, out = sys.argv[1:]
package = re.search(r"^\[package\]\n(.*?)(?=^\[|\Z)", open(cargo, encoding="utf-8").read(), re.S | re.M).group(1)
def field(name):
    m = re.search(r'^%s\s*=\s*"([^"]*)"' % name, package, re.M)
    return m.group(1) if m else None
version = field("version")
url = field("homepage") or field("repository")
lines = []
for line in open(template, encoding="utf-8").read().splitlines():
    if line.startswith("#"):
        continue
    if line.startswith("version:"):
        line = "version: " + version
    lines.append(line)
if url:
    lines.append("url: " + url)
else:
    print("package.sh: Cargo.toml has no homepage or repository: the manifest has no url (Yak's url is optional)", file=sys.stderr)
open(out, "w", encoding="utf-8").write("\n".join(lines) + "\n")
EOF

python3 scripts/check-package.py "$out"
echo "package: $out (runtimes: ${rids[*]}); next, with Rhino's yak: cd $out && yak build"
