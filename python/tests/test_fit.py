"""The fit stage (stage 3b) and level courses through the Python package: options reach the
library, the report's new figures, joint deviations, progress and cancellation of the fit,
and callers whose option structs predate ABI 3."""

import ctypes
import math

import numpy as np
import pytest

import tilepattern as tp
from tilepattern import _native as nat
from tilepattern.core import mesh_handle

from meshes import grid, shell, triangulated

JOINT_FIGURES = {
    "contacts", "joint", "min_gap", "max_gap", "mean_gap", "p95_gap", "p95_deviation",
    "max_overlap", "overlaps", "within_2mm", "within_5mm", "fit_cuts",
}


@pytest.fixture(scope="module")
def shell_quads():
    """A doubly curved surface, its quads and a staggered pattern on them."""
    v, f = shell()
    qv, qf = tp.remesh(v, f, target_edge=0.145)
    return (v, f), qv, qf, tp.match(qv, qf, time_limit=2)


def test_the_fit_runs_by_default_and_its_figures_are_reported(shell_quads):
    surface, qv, qf, pattern = shell_quads
    placed = tp.tiles(qv, qf, pattern, surface=surface)
    report = placed.report
    # The report embeds the pattern it tiled, bound_source included.
    assert report["pattern"]["pairs"] == len(pattern.pairs)
    assert report["pattern"]["bound_source"] == pattern.bound_source
    assert report["pattern"]["objective"] == report["objective"] == pattern.objective
    fit = report["fit"]
    assert fit["status"] in ("converged", "iteration_limit", "time_limit")
    assert fit["iterations"] >= 1 and fit["objective_after"] <= fit["objective_before"]
    assert 0 <= fit["mean_move"] <= fit["max_move"]
    # Pieces laid in rooms are tiles with no faces, counted in neither full nor half tiles.
    whole = (placed.faces[:, 0] == -1) & np.isin(placed.kinds, ("full", "half"))
    faceless = int(whole.sum())
    assert 0 <= fit["room_pieces"] <= faceless
    joints = report["joints"]
    assert JOINT_FIGURES <= set(joints) and JOINT_FIGURES <= set(joints["before_fit"])
    assert "before_fit" not in joints["before_fit"]
    # The fit brings the joints closer to the nominal joint.
    assert joints["p95_deviation"] < joints["before_fit"]["p95_deviation"]
    assert joints["within_2mm"] >= joints["before_fit"]["within_2mm"]
    assert 0.0 <= joints["within_2mm"] <= joints["within_5mm"] <= 1.0
    assert report["seconds"]["fit"] >= 0.0
    # What the fit cut carries the C labels, like boundary cuts carry B labels.
    for kind, label in zip(placed.kinds, placed.labels):
        assert (kind == "fit_cut") == label.startswith("C")


def test_fit_false_keeps_the_papers_placement(shell_quads):
    surface, qv, qf, pattern = shell_quads
    paper = tp.tiles(qv, qf, pattern, surface=surface, fit=False)
    assert "fit" not in paper.report and "before_fit" not in paper.report["joints"]
    assert paper.report["seconds"]["fit"] == 0.0
    assert "fit_cut" not in paper.kinds.tolist()
    fitted = tp.tiles(qv, qf, pattern, surface=surface)
    # The paper's placement is what the fit started from.
    before = dict(fitted.report["joints"]["before_fit"])
    after_paper = {k: paper.report["joints"][k] for k in before}
    assert before["contacts"] > 0
    for key in ("min_gap", "max_gap", "p95_deviation"):
        assert math.isclose(before[key], after_paper[key], rel_tol=0.05, abs_tol=1e-3), key


def test_joint_deviations_are_each_tiles_worst_joint(shell_quads):
    surface, qv, qf, pattern = shell_quads
    for fit in (True, False):
        placed = tp.tiles(qv, qf, pattern, surface=surface, fit=fit)
        deviations = placed.joint_deviations
        assert deviations.shape == (len(placed),) and deviations.dtype == np.float64
        assert len(placed.to_dict()["joint_deviations"]) == len(placed)
        assert np.all(deviations >= 0) and np.all(np.isfinite(deviations))
        joints = placed.report["joints"]
        worst = max(abs(joints["min_gap"] - joints["joint"]), abs(joints["max_gap"] - joints["joint"]))
        assert math.isclose(deviations.max(), worst, rel_tol=1e-12, abs_tol=1e-15)


def test_fit_options_reach_the_library(shell_quads):
    surface, qv, qf, pattern = shell_quads
    # units_per_mm: a model in metres read as millimetres puts every joint within "2 mm".
    metres = tp.tiles(qv, qf, pattern, surface=surface)
    as_mm = tp.tiles(qv, qf, pattern, surface=surface, units_per_mm=1.0)
    assert metres.report["joints"]["within_2mm"] < 1.0 and as_mm.report["joints"]["within_2mm"] == 1.0
    # No time at all: the best placement after the first step, and an honest status.
    hurried = tp.tiles(qv, qf, pattern, surface=surface, fit_time_limit=0)
    assert hurried.report["fit"]["status"] == "time_limit"
    # Tolerances are accepted (negative means automatic in the C struct; None here).
    loose = tp.tiles(qv, qf, pattern, surface=surface, overlap_tolerance=0.05, bond_tolerance=0.0)
    assert loose.report["fit"]["iterations"] >= 1
    assert loose.report["joints"]["max_overlap"] <= 0.05 + 1e-12


@pytest.mark.parametrize(
    "options, fragment",
    [
        (dict(fit_time_limit=-1), "time_limit"),
        (dict(fit_time_limit=float("nan")), "time_limit"),
        (dict(fit_time_limit=float("inf")), "time_limit"),
        (dict(overlap_tolerance=float("nan")), "overlap_tolerance"),
        (dict(bond_tolerance=float("inf")), "bond_tolerance"),
        (dict(units_per_mm=0), ""),
        (dict(units_per_mm=-1), ""),
    ],
)
def test_bad_fit_options(quads, options, fragment):
    v, f = quads
    pattern = tp.match(v, f, time_limit=1)
    with pytest.raises(tp.InvalidArgumentError) as caught:
        tp.tiles(v, f, pattern, **options)
    assert caught.value.status == nat.TP_INVALID_ARGUMENT and fragment in caught.value.message


def test_level_courses_on_a_sloped_grid_run_one_way():
    # Rising along y: level courses run along x, so every tile pairs face f with f + 1.
    v, f = grid(8, 6, height=lambda x, y: 0.3 * y)
    free = tp.match(v, f, time_limit=5)
    assert any(b != a + 1 for a, b in free.pairs.tolist()), "free tiles lie both ways on a grid"
    level = tp.match(v, f, courses="level", time_limit=5)
    assert len(level.pairs) > 0 and all(b == a + 1 for a, b in level.pairs.tolist())
    # The same grid with x as up: courses along y, tiles pair f with f + 8.
    across = tp.match(v, f, courses="level", up=(1, 0, 0), time_limit=5)
    assert len(across.pairs) > 0 and all(b == a + 8 for a, b in across.pairs.tolist())
    # The C code works too.
    assert tp.match(v, f, courses=nat.TP_COURSES_LEVEL, time_limit=5).pairs.tolist() == level.pairs.tolist()
    placed = tp.tiles(v, f, level)
    assert placed.report["fit"]["status"] in ("converged", "iteration_limit", "time_limit")


@pytest.mark.parametrize(
    "options, error, fragment",
    [
        (dict(courses="diagonal"), tp.InvalidArgumentError, "diagonal"),
        (dict(courses=7), tp.InvalidArgumentError, "courses 7"),
        (dict(courses="level", up=(0, 0, 0)), tp.InvalidArgumentError, "up"),
        (dict(courses="level", up=(0, float("nan"), 1)), tp.InvalidArgumentError, "up"),
        (dict(up=(0, 1)), tp.InvalidArgumentError, "up"),
    ],
)
def test_bad_courses(quads, options, error, fragment):
    v, f = quads
    with pytest.raises(error) as caught:
        tp.match(v, f, time_limit=1, **options)
    assert caught.value.status == nat.TP_INVALID_ARGUMENT and fragment in caught.value.message


def test_quad_edge():
    assert tp.quad_edge() == pytest.approx(0.145)
    assert tp.quad_edge(courses="level") == pytest.approx(0.15)
    # Where the course pitch is below (L + joint) / 2 the square quad stays.
    assert tp.quad_edge(280, 100, 10, courses="level") == pytest.approx(145)
    with pytest.raises(tp.InvalidArgumentError):
        tp.quad_edge(courses="sideways")


def test_progress_reports_the_tiles_stage(shell_quads):
    surface, qv, qf, pattern = shell_quads
    seen = []
    tp.tiles(qv, qf, pattern, surface=surface, progress=lambda stage, fraction: seen.append((stage, fraction)))
    assert seen and {stage for stage, _ in seen} == {"tiles"}
    fractions = [x for _, x in seen]
    assert all(0.0 <= x <= 1.0 for x in fractions) and fractions == sorted(fractions)
    # Without the fit there is nothing to report.
    seen.clear()
    tp.tiles(qv, qf, pattern, surface=surface, fit=False, progress=lambda stage, fraction: seen.append(stage))
    assert seen == []


def test_cancelling_the_fit_raises_cancelled_error(shell_quads):
    surface, qv, qf, pattern = shell_quads
    calls = []

    def stop(stage, fraction):
        calls.append(stage)
        return len(calls) >= 2

    with pytest.raises(tp.CancelledError) as caught:
        tp.tiles(qv, qf, pattern, surface=surface, progress=stop)
    assert caught.value.status == nat.TP_CANCELLED and caught.value.name == "TP_CANCELLED"
    assert "fit" in caught.value.message
    assert len(calls) == 2  # no further calls reach Python once cancelled
    # The pattern is unharmed and tiles again.
    assert len(tp.tiles(qv, qf, pattern, surface=surface)) > 0


class Boom(Exception):
    pass


def test_an_exception_in_the_fit_progress_is_raised_after(shell_quads):
    surface, qv, qf, pattern = shell_quads

    def broken(stage, fraction):
        raise Boom("during the fit")

    with pytest.raises(Boom, match="during the fit"):
        tp.tiles(qv, qf, pattern, surface=surface, progress=broken)


def _build(mesh, pattern, options):
    out = nat.TpTilesP()
    status = nat.lib().tp_tiles_build_with_progress(
        mesh.pointer, pattern.handle.pointer, None, ctypes.byref(options), nat.TpProgressCallback(), None, ctypes.byref(out)
    )
    nat.check(status)
    return nat.TilesHandle(out)


def test_an_abi_2_tile_options_struct_keeps_the_fit_on(quads):
    """A caller built against the ABI 2 header knows TpTileOptions up to support_band."""
    import json

    v, f = quads
    pattern = tp.match(v, f, time_limit=2)
    old_size = nat.TpTileOptions.fit.offset
    assert old_size == nat.TpTileOptions.support_band.offset + ctypes.sizeof(ctypes.c_double)
    options = nat.TpTileOptions()
    ctypes.memset(ctypes.byref(options), 0xAB, ctypes.sizeof(options))
    nat.check(nat.lib().tp_tile_options_init(ctypes.byref(options), old_size))
    raw = bytes(memoryview(options).cast("B"))
    assert raw[old_size:] == b"\xab" * (ctypes.sizeof(options) - old_size), "init wrote past the old struct"
    assert options.struct_size == old_size and options.length == 0.28
    options.fit = 0  # beyond the old struct: the library must not read it
    with mesh_handle(v, f) as mesh, _build(mesh, pattern, options) as built:
        report = json.loads(built.report_json())
    assert report["fit"]["status"] in ("converged", "iteration_limit", "time_limit")
    assert "before_fit" in report["joints"]
    # The same with the full struct and fit = 0: the field is read.
    full = nat.tile_options()
    full.fit = 0
    with mesh_handle(v, f) as mesh, _build(mesh, pattern, full) as built:
        assert "fit" not in json.loads(built.report_json())


def test_an_abi_2_pattern_options_struct_lays_tiles_either_way():
    v, f = grid(8, 6, height=lambda x, y: 0.3 * y)
    old_size = nat.TpPatternOptions.courses.offset
    options = nat.TpPatternOptions()
    nat.check(nat.lib().tp_pattern_options_init(ctypes.byref(options), old_size))
    assert options.struct_size == old_size
    options.courses = nat.TP_COURSES_LEVEL  # beyond the old struct: ignored
    options.time_limit_seconds = 5
    with mesh_handle(v, f) as mesh, mesh.solve(options) as pattern:
        pairs = pattern.pairs().tolist()
    assert any(b != a + 1 for a, b in pairs)


def test_tiles_of_a_fit_cut_read_like_boundary_tiles():
    """A strongly curved surface leaves tiles the fit cannot fit: they are cut, and cut
    tiles carry outlines and kept fractions below 1 whatever their kind (13 on this wave; on
    the gentler 0.8 sin(2x) sin(3y) none since joints that cannot close gather into tears)."""
    v, f = triangulated(*grid(40, 32, edge=0.05, height=lambda x, y: 0.8 * np.sin(3 * x) * np.sin(4 * y)))
    qv, qf = tp.remesh(v, f, target_edge=0.145)
    placed = tp.tiles(qv, qf, tp.match(qv, qf, time_limit=2), surface=(v, f))
    report = placed.report
    assert report["joints"]["fit_cuts"] > 0
    cut = np.isin(placed.kinds, ["boundary", "fit_cut"])
    assert np.all(placed.kept_fractions[cut] < 1.0) and np.all(placed.kept_fractions[~cut] == 1.0)
    assert all(bool(loops) == c for loops, c in zip(placed.outlines, cut))
    assert "fit_cut" in placed.kinds.tolist()
    assert any(entry["kind"] == "fit_cut" and entry["label"].startswith("C") for entry in placed.cutlist)
    # No two tiles overlap by more than the tolerance (a twentieth of the joint).
    assert report["joints"]["max_overlap"] <= 0.01 / 20 + 1e-12
    # The holes the fit leaves are filled with pieces on no face, counted among the fillers.
    cutting = report["cutting"]
    assert 0 < cutting["tear_pieces"] <= cutting["filler_tiles"]
    assert 0 <= cutting["tear_cuts"] <= cutting["tear_pieces"]
    assert 0 <= cutting["tear_cuts"] + cutting["tear_halves"] <= cutting["tear_pieces"]
    assert cutting["filler_tiles"] == int(np.sum(np.all(placed.faces == -1, axis=1)))
