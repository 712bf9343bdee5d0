"""tilepattern.run (tp_run, ABI 9): the whole pipeline in one call, on up to three quad
meshes, keeping the tiles that fit best. One try is the stages called one by one; three
tries are listed in the report with the one kept; the progress callback hears the whole run
and can cancel it; bad tries, quads named before they exist and zones not one per surface
face are refused by name."""

import json
import warnings

import numpy as np
import pytest

import tilepattern as tp
from tilepattern import _native as nat
from tilepattern.core import mesh_handle

from meshes import grid, round_dome, triangulated

#: As the C test: 280 x 140 mm tiles in level courses, quads of a course's height.
LEVEL = dict(courses="level", target_edge=0.15)


@pytest.fixture(scope="module")
def dome():
    """A spherical cap of radius 2 over a disk of radius 1.3 in 1104 triangles (268 quads of
    0.15): round, so its field's cones are free and other tries give other quads."""
    return round_dome()


@pytest.fixture(scope="module")
def stages(dome):
    """remesh -> match -> tiles called one by one, with the options of LEVEL."""
    V, F = dome
    QV, QF = tp.remesh(V, F, target_edge=0.15)
    pattern = tp.match(QV, QF, courses="level")
    placed = tp.tiles(QV, QF, pattern, surface=(V, F))
    return QV, QF, pattern, placed


def test_one_try_is_the_stages_one_by_one(dome, stages):
    V, F = dome
    QV, QF, pattern, placed = stages
    heard = []
    result = tp.run(V, F, tries=1, progress=lambda stage, fraction: heard.append((stage, fraction)), **LEVEL)
    assert isinstance(result, tp.RunResult)
    # The same quads ...
    assert np.array_equal(result.vertices, QV) and np.array_equal(result.faces, QF)
    # ... the same pattern ...
    assert isinstance(result.pattern, tp.Pattern) and pattern.optimal and result.pattern.optimal
    assert np.array_equal(result.pattern.pairs, pattern.pairs) and result.pattern.objective == pattern.objective
    # ... and the same tiles, to the bit.
    assert isinstance(result.tiles, tp.Tiles) and len(placed) > 100
    assert np.array_equal(result.tiles.corners, placed.corners)
    assert result.tiles.labels == placed.labels and result.tiles.kinds.tolist() == placed.kinds.tolist()
    # One try lists no tries.
    assert result.tries == [] and result.chosen_try is None and "tries" not in result.report
    # Progress: the whole run's, from 0 to 1 without going back.
    assert len(heard) > 2 and {stage for stage, _ in heard} == {"run"}
    fractions = [f for _, f in heard]
    assert fractions == sorted(fractions) and 0.0 <= fractions[0] and fractions[-1] <= 1.0
    # It unpacks as the four results.
    qv, qf, p, t = result
    assert qv is result.vertices and qf is result.faces and p is result.pattern and t is result.tiles
    # The whole tiles on the dome's flanks (up to 40 degrees), counted again from the frames:
    # on a slope of over 20 degrees, a tile climbs when its length lies within 45 degrees of
    # the fall line.
    tiles = result.tiles
    up = np.array([0.0, 0.0, 1.0])
    sloped = climbing = 0
    for frame, size, outline in zip(tiles.frames, tiles.sizes, tiles.outlines):
        if outline or size[0] < 1.5 * size[1]:
            continue
        slope = up - frame[3] * frame[3].dot(up)
        if np.linalg.norm(slope) < np.sin(np.radians(20.0)):
            continue
        sloped += 1
        climbing += abs(frame[1].dot(slope)) > np.linalg.norm(slope) * np.sqrt(0.5)
    sequence = tiles.report["sequence"]
    assert sloped > 0 and (sequence["sloped_tiles"], sequence["climbing_tiles"]) == (sloped, climbing)


def test_the_default_target_edge_is_the_quad_edge_of_the_tile(dome):
    V, F = dome
    # Level courses: quad_edge(0.28, 0.14, 0.01, "level"), a course's height (0.14 + 0.01).
    edge = tp.quad_edge(courses="level")
    assert edge == pytest.approx(0.15)
    result = tp.run(V, F, tries=1, courses="level", time_limit=0)
    QV, QF = tp.remesh(V, F, target_edge=edge)
    assert np.array_equal(result.vertices, QV) and np.array_equal(result.faces, QF)
    # Level courses are the default, as the command line's run.
    default = tp.run(V, F, tries=1, time_limit=0)
    assert np.array_equal(default.vertices, result.vertices) and np.array_equal(default.faces, result.faces)
    assert np.array_equal(default.tiles.corners, result.tiles.corners)
    # Free courses: (0.28 + 0.01) / 2, remesh's default 0.145 as computed in floating point
    # (one unit in the last place above the literal); herringbone is laid in them by default.
    assert tp.quad_edge() == pytest.approx(0.145)
    free = tp.run(V, F, tries=1, courses="free", time_limit=0)
    QV, QF = tp.remesh(V, F, target_edge=tp.quad_edge())
    assert np.array_equal(free.vertices, QV) and np.array_equal(free.faces, QF)
    herringbone = tp.run(V, F, tries=1, bond="herringbone", time_limit=0)
    assert np.array_equal(herringbone.vertices, QV) and np.array_equal(herringbone.faces, QF)
    # Given, it is used as given.
    given = tp.run(V, F, tries=1, target_edge=0.2, time_limit=0)
    QV, QF = tp.remesh(V, F, target_edge=0.2)
    assert np.array_equal(given.vertices, QV) and np.array_equal(given.faces, QF)


def test_the_pattern_and_quads_handed_out_are_those_of_the_kept_tiles(dome):
    V, F = dome
    with tp.run(V, F, tries=3, **LEVEL) as result:
        # The pattern handed out makes the kept tiles again on the quads handed out.
        again = tp.tiles(result.vertices, result.faces, result.pattern, surface=(V, F))
        assert np.array_equal(again.corners, result.tiles.corners)
        assert result.tiles.faces.max() < len(result.faces) and result.pattern.pairs.max() < len(result.faces)
    assert result.pattern.closed  # the with block released the native pattern
    with pytest.raises(ValueError):
        tp.tiles(result.vertices, result.faces, result.pattern, surface=(V, F))


def test_three_tries_are_listed_and_the_best_is_kept(dome, stages):
    V, F = dome
    QV = stages[0]
    result = tp.run(V, F, tries=3, **LEVEL)
    tries, chosen = result.tries, result.chosen_try
    assert len(tries) == 3 and chosen in (0, 1, 2)
    assert [t["renormalisation"] for t in tries] == pytest.approx([0.5, 0.5, 1.0])
    assert [t["field"] for t in tries] == ["curvature", "smooth", "curvature"]
    # The kept try is the best by the run's rank: joints not flagged first, then cuts not
    # flagged, then the score (the first of equals).
    ranks = [(t["wide_joints"], t["fit_cuts"], t["score"]) for t in tries]
    assert all(t["score"] is not None and "limit_reached" not in t for t in tries)
    assert chosen == ranks.index(min(ranks))
    assert tries[chosen]["quads"] == len(result.faces)
    # The kept quads are the first try's (the stages' with the default strength) exactly
    # when the first was kept.
    assert (result.vertices.shape == QV.shape and np.array_equal(result.vertices, QV)) == (chosen == 0)
    # The report as plain data and as JSON says the same.
    report = json.loads(json.dumps(result.tiles.to_dict()))["report"]
    assert len(report["tries"]) == 3 and report["chosen_try"] == chosen
    # 0 (automatic) makes 5 tries on this surface (268 quads, at most 10,000): the same three,
    # the curvature field at half the strength and, in level courses with quads of a course's
    # pitch (0.15, against 0.145 for half a tile and a joint), the smooth field's quads laid
    # out for the courses; and keeps the best of the five. Its rim is round: no try follows
    # it, so none is made free of it (the sixth try).
    auto = tp.run(V, F, **LEVEL)
    assert len(auto.tries) == 5 and auto.tries[3]["renormalisation"] == pytest.approx(0.25)
    assert [t.get("quads_along_courses", False) for t in auto.tries] == [False] * 4 + [True]
    assert not any(t.get("boundary_free", False) for t in auto.tries)
    assert auto.tries[4]["field"] == "smooth"
    assert [t["score"] for t in auto.tries[:3]] == [t["score"] for t in tries]
    ranks = [(t["wide_joints"], t["fit_cuts"], t["score"]) for t in auto.tries]
    assert auto.chosen_try == ranks.index(min(ranks))
    if auto.chosen_try == chosen:
        assert np.array_equal(auto.tiles.corners, result.tiles.corners)


def test_cancel_from_the_progress_callback(dome):
    V, F = dome
    calls = []

    def stop_at_the_second_call(stage, fraction):
        calls.append((stage, fraction))
        return len(calls) >= 2

    with pytest.raises(tp.CancelledError) as caught:
        tp.run(V, F, tries=3, progress=stop_at_the_second_call, **LEVEL)
    assert caught.value.status == nat.TP_CANCELLED and "cancel" in caught.value.message
    assert len(calls) == 2

    class Stop(Exception):
        pass

    def raising(stage, fraction):
        raise Stop(stage)

    # An exception raised in the callback cancels the run and is raised again.
    with pytest.raises(Stop, match="run"):
        tp.run(V, F, tries=1, progress=raising, **LEVEL)
    # The next run in the process is unaffected.
    assert len(tp.run(V, F, tries=1, **LEVEL).tiles) > 100


def test_a_cancel_in_the_last_try_cancels_the_run(dome):
    """Cancelled in the last try's fit, the run is cancelled: not an earlier try's tiles."""
    V, F = dome
    heard = []

    def stop_at_the_end(stage, fraction):
        heard.append(fraction)
        return fraction >= 0.999

    with pytest.raises(tp.CancelledError):
        tp.run(V, F, tries=3, progress=stop_at_the_end, **LEVEL)
    assert heard[-1] >= 0.999 and heard[0] < 1.0 / 3


@pytest.mark.parametrize("tries", [7, -1, 2.0, "2", True, None])
def test_bad_tries_are_refused_by_name(dome, tries):
    V, F = dome
    with pytest.raises(tp.InvalidArgumentError, match=r"^TP_INVALID_ARGUMENT \(2\): tries is .*0 \(automatic\) or 1 to 6"):
        tp.run(V, F, tries=tries, **LEVEL)


def test_the_library_refuses_bad_tries_and_named_quads_too(dome):
    """Past the Python checks, tp_run itself refuses them (the binding passes them on)."""
    V, F = dome
    remesh, pattern, tiles, run = nat.remesh_options(), nat.pattern_options(), nat.tile_options(), nat.run_options()
    with mesh_handle(V, F) as surface:
        run.tries = 7
        with pytest.raises(tp.InvalidArgumentError, match="tries is 7"):
            surface.run(remesh, pattern, tiles, run)
        run.tries = 1
        pair = np.array([0, 1], dtype=np.uint32)
        pattern.forced_pairs = nat.as_pointer(pair, nat.c_uint32)
        pattern.forced_pair_count = 1
        with pytest.raises(tp.InvalidArgumentError, match="forced_pair_count"):
            surface.run(remesh, pattern, tiles, run)


def test_forced_pairs_are_refused(dome):
    V, F = dome
    with pytest.raises(tp.InvalidArgumentError, match="forced_pairs names 1 pair of quads.*remesh\\(\\), match\\(\\) and tiles\\(\\)"):
        tp.run(V, F, tries=1, forced_pairs=[[0, 1]], **LEVEL)
    # Empty is no pair: accepted.
    assert len(tp.run(V, F, tries=1, forced_pairs=[], excluded_faces=[], **LEVEL).tiles) > 100


def test_excluded_faces_are_faces_of_the_surface_and_are_neither_tiled_nor_counted(dome):
    V, F = dome
    whole = tp.run(V, F, tries=1, **LEVEL)
    centroids = np.asarray(V)[np.asarray(F)].mean(axis=1)
    quarter = np.flatnonzero((centroids[:, 0] > 0) & (centroids[:, 1] > 0))
    kept = tp.run(V, F, tries=1, excluded_faces=quarter, **LEVEL)
    centres = kept.tiles.corners.mean(axis=1)
    # No tile well inside the quarter left out (a tile is 0.29 long), about a quarter fewer.
    assert not ((centres[:, 0] > 0.3) & (centres[:, 1] > 0.3)).any()
    assert 0.5 * len(whole.tiles) < len(kept.tiles) < 0.85 * len(whole.tiles)
    # The area left out is not counted as uncovered.
    assert kept.tiles.report["cutting"]["coverage"] > 0.9
    with pytest.raises(tp.InvalidArgumentError, match="face 1104"):
        tp.run(V, F, tries=1, excluded_faces=[len(F)], **LEVEL)


def test_zones_are_per_surface_face(dome):
    V, F = dome
    stack = tp.run(V, F, tries=1, bond="stack", **LEVEL)
    staggered = tp.run(V, F, tries=1, **LEVEL)
    # Every surface face (1104 triangles, not the 268 quads) in stack: the stack bond's pattern.
    zoned = tp.run(V, F, tries=1, zones=["stack"] * len(F), **LEVEL)
    assert np.array_equal(zoned.pattern.pairs, stack.pattern.pairs)
    assert zoned.pattern.objective == stack.pattern.objective != staggered.pattern.objective
    with pytest.raises(tp.InvalidArgumentError, match="zones give 268 bonds for a mesh of 1104 faces"):
        tp.run(V, F, tries=1, zones=["stack"] * 268, **LEVEL)


def test_a_zone_laying_tiles_both_ways_makes_the_default_courses_free(dome):
    V, F = dome
    zones = ["herringbone"] * 100 + [None] * (len(F) - 100)
    # As the command line: free courses by default (level ones refuse herringbone).
    default = tp.run(V, F, tries=1, zones=zones, time_limit=5)
    free = tp.run(V, F, tries=1, zones=zones, courses="free", time_limit=5)
    assert np.array_equal(default.tiles.corners, free.tiles.corners)
    with pytest.raises(tp.InvalidArgumentError, match="herringbone"):
        tp.run(V, F, tries=1, zones=zones, courses="level", time_limit=5)


def test_warnings_are_issued_at_the_caller():
    V, F = triangulated(*grid(8, 6))  # level: no tile needs a prop
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = tp.run(V, F, tries=1, time_limit=10)
    codes = [w["code"] for w in result.tiles.warnings]
    assert "no_support" in codes
    issued = [w for w in caught if issubclass(w.category, tp.TilePatternWarning)]
    assert len(issued) == len(codes) and all(w.filename == __file__ for w in issued)
