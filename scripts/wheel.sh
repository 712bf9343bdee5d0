#!/usr/bin/env bash
# `make wheel`: a Python wheel of python/ that carries the native library, so that
# `pip install tilepattern-*.whl` works with no checkout and no TILEPATTERN_LIB (the package
# looks next to itself first: tilepattern/_native.py, library_candidates).
#
# The package is pure Python (ctypes), but the library in it is not: the wheel is tagged
# py3-none-<platform> (any Python 3, this platform's processor and system), not
# py3-none-any. Steps: copy python/ into target/wheel/src, put target/release's library
# into the copy's tilepattern/, and let setuptools (in target/wheel/venv) build the wheel
# into target/wheels/. Build the library first (`make wheel` does).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
work=target/wheel
out=target/wheels

case "$(uname -s)" in
  Darwin) name=libtilepattern.dylib ;;
  MINGW* | MSYS* | CYGWIN*) name=tilepattern.dll ;;
  *) name=libtilepattern.so ;;
esac
lib=target/release/$name
if [ ! -f "$lib" ]; then
  echo "wheel.sh: $lib is missing; run \`cargo build --release --lib\` first" >&2
  exit 1
fi

# The build environment: setuptools from PyPI, once.
venv=$work/venv
python=$venv/bin/python
[ -x "$python" ] || python=$venv/Scripts/python.exe
if [ ! -x "$python" ]; then
  python3 -m venv "$venv" || {
    echo "wheel.sh: python3 -m venv failed (on Debian/Ubuntu: apt-get install python3-venv)" >&2
    rm -rf "$venv"
    exit 1
  }
  python=$venv/bin/python
  [ -x "$python" ] || python=$venv/Scripts/python.exe
fi
"$python" -m pip install --quiet --disable-pip-version-check "setuptools>=70.1" "wheel>=0.40"

# The platform tag of this interpreter's platform (linux_x86_64, macosx_11_0_arm64,
# win_amd64, ...): setuptools tags a package without compiled extensions "any" unless told.
platform=$("$python" -c 'import sysconfig; print(sysconfig.get_platform().replace("-", "_").replace(".", "_"))')

src=$work/src
rm -rf "$src"
mkdir -p "$src" "$out"
cp python/pyproject.toml python/README.md "$src/"
cp -r python/tilepattern "$src/tilepattern"
find "$src" -name __pycache__ -type d -prune -exec rm -rf {} +
cp "$lib" "$src/tilepattern/$name"
# Without the debug information of the release profile (mostly COIN-OR's): 76 MB -> 7 MB.
if [ "$name" = libtilepattern.so ] && command -v strip >/dev/null 2>&1; then
  strip --strip-debug "$src/tilepattern/$name"
fi
cat > "$src/setup.cfg" <<EOF
[bdist_wheel]
python_tag = py3
plat_name = $platform
EOF

version=$(sed -n 's/^version = "\(.*\)"/\1/p' python/pyproject.toml | head -n 1)
rm -f "$out"/tilepattern-"$version"-*.whl
"$python" -m pip wheel --quiet --disable-pip-version-check --no-deps --no-build-isolation -w "$out" "$src"
wheel=$(ls "$out"/tilepattern-"$version"-py3-none-"$platform".whl)
# The wheel must hold the library inside the package.
"$python" - "$wheel" "tilepattern/$name" <<'EOF'
import sys, zipfile
wheel, member = sys.argv[1:]
names = zipfile.ZipFile(wheel).namelist()
if member not in names:
    sys.exit("wheel.sh: %s lacks %s (it has %s)" % (wheel, member, ", ".join(names)))
EOF
echo "wheel: $wheel"
