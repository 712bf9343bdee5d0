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


def measure(tmp_path, tiles, surface=True, extra=()):
    obj = tmp_path / "tiles.obj"
    obj.write_text("\n".join(tiles) + "\n")
    args = [sys.executable, str(SCRIPT), str(obj), "--joint", "0.01", *extra]
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


def test_tiles_running_up_a_slope_are_told_from_level_ones(tmp_path):
    # A roof plane rising 30 degrees along y: one tile lies level (its length along x), one
    # climbs (its length up the slope), one lies on a level floor beside them (not counted).
    c, s = 0.8660254037844387, 0.5

    def on_roof(x, v):
        return (x, v * c, v * s)

    level = box("full_0", [on_roof(0.1, 0.1), on_roof(0.38, 0.1), on_roof(0.38, 0.24), on_roof(0.1, 0.24)], 0.015)
    climbs = box("full_1", [on_roof(0.6, 0.1), on_roof(0.74, 0.1), on_roof(0.74, 0.38), on_roof(0.6, 0.38)], 0.015)
    floor = box("full_2", [(2.0, 0.1, 0), (2.28, 0.1, 0), (2.28, 0.24, 0), (2.0, 0.24, 0)], 0.015)
    figures = measure(tmp_path, level + climbs + floor, surface=False, extra=["--up", "0,0,1"])
    assert figures["sloped_tiles"] == 2
    assert figures["climbing_tiles"] == 1
    assert figures["climbing_share"] == pytest.approx(0.5)
    # Without --up nothing of the kind is measured.
    assert "climbing_share" not in measure(tmp_path, level, surface=False)
