#!/usr/bin/env bash
# The C# wrapper's tests under mono (make dotnet-test, after cargo build --release --lib):
# compiles dotnet/TilePattern and dotnet/TilePattern.Tests with mcs into target/dotnet/,
# checks that a program finds the native library in the runtimes/<rid>/native/ layout, then
# runs the NUnit 2.6 tests with TILEPATTERN_LIB pointing at target/release/libtilepattern.so.
# Needs Debian's mono-mcs, mono-runtime, nunit-console and libnunit-cil-dev.
set -euo pipefail

cd "$(dirname "$0")/.."
root=$PWD
out=target/dotnet
lib=$root/target/release/libtilepattern.so

for tool in mcs mono nunit-console; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "test-dotnet: $tool not found; on Debian/Ubuntu: sudo apt-get install mono-mcs mono-runtime nunit-console libnunit-cil-dev" >&2
    exit 1
  fi
done
if [ ! -f "$lib" ]; then
  echo "test-dotnet: $lib is missing; run: cargo build --release --lib" >&2
  exit 1
fi
nunit=""
for candidate in /usr/lib/cli/nunit.framework-2.6*/nunit.framework.dll /usr/lib/mono/gac/nunit.framework/2.6*/nunit.framework.dll; do
  if [ -f "$candidate" ]; then nunit=$candidate; break; fi
done
if [ -z "$nunit" ]; then
  nunit=$(find /usr/lib /usr/share -name nunit.framework.dll 2>/dev/null | head -n 1)
fi
if [ -z "$nunit" ]; then
  echo "test-dotnet: nunit.framework.dll not found; on Debian/Ubuntu: sudo apt-get install libnunit-cil-dev" >&2
  exit 1
fi

case "$(uname -m)" in
  x86_64 | amd64) rid=linux-x64 ;;
  aarch64 | arm64) rid=linux-arm64 ;;
  *) rid=linux-$(uname -m) ;;
esac

rm -rf "$out"
mkdir -p "$out/runtimes/$rid/native"

# C# 7.2 is mcs's newest level; the SDK build uses 7.3. Warnings are errors (CS1591: missing
# XML comments on self-explanatory members, is not).
mcs_flags=(-langversion:7.2 -debug -warn:4 -warnaserror+ -nowarn:1591 -nologo)
mcs "${mcs_flags[@]}" -target:library -doc:"$out/TilePattern.xml" -out:"$out/TilePattern.dll" dotnet/TilePattern/*.cs
mcs "${mcs_flags[@]}" -target:library -out:"$out/TilePattern.Tests.dll" \
  -r:"$out/TilePattern.dll" -r:"$nunit" -r:System.Core.dll dotnet/TilePattern.Tests/*.cs
mcs "${mcs_flags[@]}" -target:exe -out:"$out/TilePattern.Smoke.exe" -r:"$out/TilePattern.dll" dotnet/Smoke/*.cs

# The layout an application ships: the native library under runtimes/<rid>/native/.
cp "$lib" "$out/runtimes/$rid/native/"
echo "== smoke: native library from $out/runtimes/$rid/native/"
env -u TILEPATTERN_LIB -u LD_LIBRARY_PATH mono --debug "$out/TilePattern.Smoke.exe"

echo "== NUnit"
TILEPATTERN_LIB=$lib TILEPATTERN_HEADER=$root/include/tilepattern.h RUST_BACKTRACE=0 \
  nunit-console -nologo -noshadow -xml="$out/TestResult.xml" "$out/TilePattern.Tests.dll"
