"""scripts/check-joints.py, the independent joint measure (when run from a source checkout)."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "check-joints.py"

pytestmark = pytest.mark.skipif(not SCRIPT.is_file(), reason="not in a source checkout")


def box(name, corners, thickness):
    """An OBJ object: the bottom face `corners` (counter-clockwise) and the top, `thickness` up."""
    lines = ["o " + name]
    for x, y, z in corners:
        lines.append("v %r %r %r" % (x, y, z))
    for x, y, z in corners:
        lines.append("v %r %r %r" % (x, y, z + thickness))
    return lines


def measure(tmp_path, tiles, surface=True):
    obj = tmp_path / "tiles.obj"
    obj.write_text("\n".join(tiles) + "\n")
    args = [sys.executable, str(SCRIPT), str(obj), "--joint", "0.01"]
    if surface:
        # A plate 1 x 1 m at z = 0, two triangles.
        plate = tmp_path / "plate.obj"
        plate.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n")
        args += ["--surface", str(plate)]
    out = subprocess.run(args, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def test_joints_between_two_tiles_a_joint_apart(tmp_path):
    a = box("full_0", [(0.1, 0.1, 0), (0.38, 0.1, 0), (0.38, 0.24, 0), (0.1, 0.24, 0)], 0.015)
    b = box("full_1", [(0.39, 0.1, 0), (0.67, 0.1, 0), (0.67, 0.24, 0), (0.39, 0.24, 0)], 0.015)
    figures = measure(tmp_path, a + b, surface=False)
    assert figures["pairs"] == 1
    assert figures["p95_deviation_mm"] == pytest.approx(0.0, abs=1e-6)
    assert "tiles_lifted" not in figures


def test_a_tile_standing_off_the_surface_is_counted(tmp_path):
    flat = box("full_0", [(0.1, 0.1, 0), (0.38, 0.1, 0), (0.38, 0.24, 0), (0.1, 0.24, 0)], 0.015)
    # Tilted about its short side: one end 30 mm up, as a tile bridging a crease stands.
    tilted = box("full_1", [(0.5, 0.5, 0), (0.78, 0.5, 0.03), (0.78, 0.64, 0.03), (0.5, 0.64, 0)], 0.015)
    figures = measure(tmp_path, flat + tilted)
    assert figures["tiles_lifted"] == 1
    assert figures["largest_lift_mm"] == pytest.approx(30.0, abs=0.5)
