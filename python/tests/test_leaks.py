"""No memory grows over 1000 runs of the pipeline (RSS measured and printed).

Run on its own for the numbers: ``python tests/test_leaks.py``.
"""

import json
import os
import resource
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.dirname(HERE), HERE]  # the package of this checkout, meshes.py

import tilepattern as tp  # noqa: E402
from tilepattern.core import mesh_handle  # noqa: E402
from meshes import grid, triangulated  # noqa: E402

ROUNDS = 1000
WARM_UP = 100
LIMIT_MB = 20.0


def rss_mb():
    """Resident set size of this process in MB (/proc/self/statm; ru_maxrss elsewhere)."""
    try:
        with open("/proc/self/statm") as statm:
            return int(statm.read().split()[1]) * resource.getpagesize() / 2**20
    except OSError:  # not Linux: peak RSS, in kB on Linux/BSD, bytes on macOS
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        return peak / (2**20 if sys.platform == "darwin" else 2**10)


def measure(rounds=ROUNDS, warm_up=WARM_UP):
    """RSS before and after ``rounds`` runs of: mesh create (and read back), match with a
    small time limit, tiles cut to a surface, the report, and one refused mesh."""
    v, f = grid(3, 2)  # small, so that 1000 runs take seconds; the solve still goes to CBC
    surface = triangulated(*grid(6, 4, edge=0.0725))

    def once():
        with mesh_handle(v, f) as mesh:
            mesh.arrays()
        pattern = tp.match(v, f, time_limit=0.05)
        placed = tp.tiles(v, f, pattern, surface=surface)
        json.dumps(placed.report)
        pattern.close()
        try:
            tp.match([[0, 0, 0], [1, 0, 0], [0, 1, float("nan")]], [[0, 1, 2]])
        except tp.InvalidMeshError:
            pass

    for _ in range(warm_up):
        once()
    before = rss_mb()
    for _ in range(rounds):
        once()
    after = rss_mb()
    return before, after


def test_rss_is_flat_over_1000_runs(capsys):
    before, after = measure()
    with capsys.disabled():
        print("\nRSS after %d warm-up runs: %.1f MB; after %d more: %.1f MB (%+.2f MB)" % (WARM_UP, before, ROUNDS, after, after - before))
    assert after - before < LIMIT_MB


if __name__ == "__main__":
    before, after = measure()
    print("RSS after %d warm-up runs: %.1f MB; after %d more: %.1f MB (%+.2f MB)" % (WARM_UP, before, ROUNDS, after, after - before))
    sys.exit(0 if after - before < LIMIT_MB else 1)
