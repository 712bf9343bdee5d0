"""No memory grows over 1000 calls through every stage (RSS measured and printed)."""

import resource

import tilepattern as tp

from meshes import grid, triangulated


def rss_mb():
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * resource.getpagesize() / 2**20


def test_rss_is_flat_over_1000_calls():
    v, f = grid(6, 5)
    surface = triangulated(*grid(12, 10, edge=0.0725))

    def once():
        pattern = tp.match(v, f, time_limit=0.2)
        tp.tiles(v, f, pattern, surface=surface)
        try:
            tp.match([[0, 0, 0]], [[0, 0, 0]])
        except tp.TilePatternError:
            pass

    for _ in range(100):
        once()
    before = rss_mb()
    for _ in range(1000):
        once()
    after = rss_mb()
    print("RSS after warm-up %.1f MB, after 1000 more calls %.1f MB (+%.2f MB)" % (before, after, after - before))
    assert after - before < 20
