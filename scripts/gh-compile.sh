#!/usr/bin/env bash
# `make gh-compile`: compiles the Grasshopper components (grasshopper/*.cs) with mcs, warnings
# as errors, against reference stubs of RhinoCommon and Grasshopper (grasshopper/stubs/) and
# the C# wrapper (dotnet/TilePattern), after checking the stubs member by member against the
# type stubs McNeel published on PyPI for Rhino/Grasshopper 7 and 8
# (scripts/check-gh-stubs.py). Then proves that the check bites: broken copies of the stubs (a
# misspelt, retyped, made-static, given-a-setter or renumbered member, a removed member) must
# each fail the check or the compile. Output in target/gh/. Needs mcs, mono, python3 (venv)
# and PyPI for the first run (the pinned stub packages go into target/gh-venv).
set -euo pipefail

cd "$(dirname "$0")/.."
out=target/gh
venv=target/gh-venv
packages=(rhino-stubs-typed==8.20.25157 grasshopper-stubs-typed==8.20.25157 Rhino-stubs==7.7.21140 Grasshopper-stubs==7.7.21140)
export CHECK_GH_STUBS_CACHE=$out/pyi-cache

for tool in mcs mono python3; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "gh-compile: $tool not found; run scripts/setup.sh (Debian: mono-mcs mono-runtime python3-venv)" >&2
    exit 1
  fi
done

# The published stubs, pinned; installed once (the stamp names the versions).
stamp=$venv/.stubs-installed
if [ "$(cat "$stamp" 2>/dev/null || true)" != "${packages[*]}" ]; then
  echo "== installing ${packages[*]} into $venv"
  rm -rf "$venv"
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check --no-deps "${packages[@]}"
  echo "${packages[*]}" > "$stamp"
fi
site=$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')

mkdir -p "$out"
flags=(-langversion:7.2 -warn:4 -warnaserror+ -nowarn:1591 -nologo)
winforms=(-r:System.Drawing.dll -r:System.Windows.Forms.dll)

# Compiles stub sources from $1 into $2/RhinoCommon.dll and $2/Grasshopper.dll.
compile_stubs() {
  local src=$1 dst=$2
  mcs "${flags[@]}" -target:library -out:"$dst/RhinoCommon.dll" "${winforms[@]}" "$src"/RhinoCommon/*.cs &&
    mcs "${flags[@]}" -target:library -out:"$dst/Grasshopper.dll" -r:"$dst/RhinoCommon.dll" "${winforms[@]}" "$src"/Grasshopper/*.cs
}

# Checks the stubs compiled in $1 against the published ones.
check_stubs() {
  mono "$out/DumpApi.exe" "$1/RhinoCommon.dll" "$1/Grasshopper.dll" > "$1/api.jsonl" &&
    python3 scripts/check-gh-stubs.py "$1/api.jsonl" "$site" grasshopper/stubs/ledger.txt
}

# Compiles the components against the stubs in $1.
compile_components() {
  local resources=()
  for icon in grasshopper/Icons/*.png; do
    resources+=("-resource:$icon,TilePattern.Gh.Icons.$(basename "$icon")")
  done
  mcs "${flags[@]}" -target:library -out:"$1/TilePattern.Grasshopper.gha" -r:"$1/RhinoCommon.dll" -r:"$1/Grasshopper.dll" \
    -r:"$out/TilePattern.dll" -r:System.Core.dll "${winforms[@]}" "${resources[@]}" grasshopper/*.cs
}

echo "== stubs: compile and check against $(IFS=,; echo "${packages[*]}")"
mcs "${flags[@]}" -target:exe -out:"$out/DumpApi.exe" -r:System.Core.dll grasshopper/stubs/tools/DumpApi.cs
compile_stubs grasshopper/stubs "$out"
check_stubs "$out"

echo "== components: compile against the stubs (warnings as errors)"
mcs "${flags[@]}" -target:library -doc:"$out/TilePattern.xml" -out:"$out/TilePattern.dll" dotnet/TilePattern/*.cs
compile_components "$out"
echo "gh-compile: $out/TilePattern.Grasshopper.gha built"

# ---- the check must bite ------------------------------------------------------------------
# Each case edits one line of a copy of the stubs; the edit must change the file, and then the
# stub check or the component compile must fail, with the expected words in the output.
selftest=$out/selftest
passed=0
failed=0
expect_failure() {
  local name=$1 file=$2 from=$3 to=$4 words=$5
  rm -rf "$selftest"
  mkdir -p "$selftest"
  cp -r grasshopper/stubs/RhinoCommon grasshopper/stubs/Grasshopper "$selftest/"
  local target=$selftest/$file
  if ! grep -qF -- "$from" "$target"; then
    echo "self-test $name: '$from' not found in $file (the stubs changed: update the case)" >&2
    failed=$((failed + 1))
    return
  fi
  python3 - "$target" "$from" "$to" <<'EOF'
import sys
path, old, new = sys.argv[1:]
text = open(path, encoding="utf-8").read()
open(path, "w", encoding="utf-8").write(text.replace(old, new, 1))
EOF
  local log=$selftest/log
  if compile_stubs "$selftest" "$selftest" >"$log" 2>&1 && check_stubs "$selftest" >>"$log" 2>&1 \
    && compile_components "$selftest" >>"$log" 2>&1; then
    echo "self-test $name: FAILED: a broken stub passed the check and the compile" >&2
    failed=$((failed + 1))
  elif ! grep -qF -- "$words" "$log"; then
    echo "self-test $name: FAILED: it failed, but without '$words':" >&2
    cat "$log" >&2
    failed=$((failed + 1))
  else
    echo "self-test $name: caught ($(grep -F -m1 -- "$words" "$log" | cut -c1-150))"
    passed=$((passed + 1))
  fi
}

echo "== self-test: broken stubs must fail"
expect_failure misspelt-member Grasshopper/Grasshopper.Kernel.cs \
  "public void AddRuntimeMessage(" "public void AddRuntimeMesage(" "AddRuntimeMesage not in the"
expect_failure wrong-parameter-type RhinoCommon/Rhino.Geometry.cs \
  "public Point3d Point3dAt(int index)" "public Point3d Point3dAt(long index)" "no published overload matches"
expect_failure wrong-return-type RhinoCommon/Rhino.Geometry.cs \
  "public bool Compact()" "public int Compact()" "no published overload matches"
expect_failure made-static Grasshopper/Grasshopper.Kernel.cs \
  "public void ScheduleSolution(" "public static void ScheduleSolution(" "no published overload matches"
expect_failure invented-setter RhinoCommon/Rhino.Geometry.cs \
  "public bool IsQuad { get { throw null; } }" "public bool IsQuad { get { throw null; } set { } }" "the 8.20 typed stubs have none"
expect_failure wrong-enum-value Grasshopper/Grasshopper.Kernel.cs \
  "Remark = 255," "Remark = 254," "Remark is 255 in the"
expect_failure modifier-not-in-ledger Grasshopper/Grasshopper.Kernel.cs \
  "protected virtual void BeforeSolveInstance()" "protected void BeforeSolveInstance()" "ledger line"
expect_failure removed-member RhinoCommon/Rhino.Geometry.cs \
  "public bool Compact() { throw null; }" "" "error CS1061"
rm -rf "$selftest"
echo "gh-compile self-test: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
