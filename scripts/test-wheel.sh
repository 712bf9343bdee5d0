#!/usr/bin/env bash
# `make wheel-test` (part of `make python-test`): the wheel from `make wheel` installed into a
# fresh venv in a temporary folder outside the repository, with TILEPATTERN_LIB,
# CARGO_TARGET_DIR and PYTHONPATH unset, run from that folder: the package must load the
# library it carries (not the checkout's), and the Python example of python/README.md
# ("With COMPAS"), extracted from the README as it stands, must run and write tiles.3dm.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
version=$(sed -n 's/^version = "\(.*\)"/\1/p' "$root/python/pyproject.toml" | head -n 1)
shopt -s nullglob
wheels=("$root"/target/wheels/tilepattern-"$version"-py3-none-*.whl)
shopt -u nullglob
if [ ${#wheels[@]} -ne 1 ]; then
  echo "test-wheel.sh: expected one wheel of $version in target/wheels (run make wheel), found ${#wheels[@]}" >&2
  exit 1
fi
wheel=${wheels[0]}

scratch=$(mktemp -d "${TMPDIR:-/tmp}/tilepattern-wheel.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
case "$scratch" in
  "$root"/*) echo "test-wheel.sh: the scratch folder $scratch is inside the repository" >&2; exit 1 ;;
esac

echo "== fresh venv in $scratch, pip install $(basename "$wheel")[compas,rhino]"
python3 -m venv "$scratch/venv"
python=$scratch/venv/bin/python
[ -x "$python" ] || python=$scratch/venv/Scripts/python.exe
"$python" -m pip install --quiet --disable-pip-version-check "$wheel[compas,rhino]"

# The README's example: the first ```python block after "## With COMPAS".
python3 - "$root/python/README.md" "$scratch/example.py" <<'EOF'
import re, sys
readme, out = sys.argv[1:]
text = open(readme, encoding="utf-8").read()
section = text.split("## With COMPAS", 1)
if len(section) != 2:
    sys.exit("test-wheel.sh: python/README.md has no '## With COMPAS' section")
block = re.search(r"```python\n(.*?)```", section[1], re.S)
if not block:
    sys.exit("test-wheel.sh: no python block under '## With COMPAS'")
open(out, "w", encoding="utf-8").write(block.group(1))
EOF

cd "$scratch"
run=(env -u TILEPATTERN_LIB -u CARGO_TARGET_DIR -u PYTHONPATH -u LD_LIBRARY_PATH "$python")
echo "== the package loads the library it carries"
"${run[@]}" - <<'EOF'
import pathlib, tilepattern
package = pathlib.Path(tilepattern.__file__).resolve().parent
library = pathlib.Path(tilepattern.library_path()).resolve()
assert library.parent == package, "loaded %s, not the wheel's copy in %s" % (library, package)
print("library:", library, "version:", tilepattern.version())
EOF
echo "== python/README.md's example"
"${run[@]}" example.py
if [ ! -s tiles.3dm ]; then
  echo "test-wheel.sh: the example wrote no tiles.3dm" >&2
  exit 1
fi
# The .3dm holds one object per tile.
"${run[@]}" - <<'EOF'
import rhino3dm
model = rhino3dm.File3dm.Read("tiles.3dm")
assert model is not None and len(model.Objects) > 100, "tiles.3dm has %s objects" % (None if model is None else len(model.Objects))
print("tiles.3dm:", len(model.Objects), "objects")
EOF
echo "wheel test: 1 passed, 0 failed"
