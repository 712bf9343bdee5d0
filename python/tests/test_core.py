"""The three stages on plain arrays: inputs in every form, results, frames and corners."""

import math

import numpy as np
import pytest

import tilepattern as tp
from tilepattern.core import face_arrays, mesh_arrays, mesh_handle

from meshes import grid, mixed, triangulated


def test_mesh_round_trip_keeps_order(quads):
    v, f = quads
    with mesh_handle(v, f) as handle:
        back_v, back_f = mesh_arrays(handle)
    assert np.array_equal(back_v, v)
    assert isinstance(back_f, np.ndarray) and back_f.tolist() == f


def test_polygon_faces_of_mixed_sizes():
    v, f = mixed()
    indices, sizes = face_arrays(f)
    assert sizes.tolist() == [3, 3, 4, 5, 4, 4, 4] and len(indices) == 27
    assert indices.dtype == np.uint32 and sizes.dtype == np.uint32
    with mesh_handle(v, f) as handle:
        assert handle.counts() == (len(v), 7, 27)
        back_v, back_f = mesh_arrays(handle)
    assert back_f == f  # a list of lists when the sizes differ
    pattern = tp.match(v, f, bond="stack", time_limit=5)
    assert pattern.non_quad == 3 and pattern.faces == 7
    assert 2 * len(pattern.pairs) + len(pattern.unpaired) == 4


@pytest.mark.parametrize(
    "convert",
    [
        lambda v, f: (v.tolist(), f),
        lambda v, f: (np.asfortranarray(v), np.array(f, dtype=np.uint32)),
        lambda v, f: (v.astype(np.float32), np.array(f, dtype=np.int64)),
        lambda v, f: (v[:, [0, 1, 2]], np.array(f, dtype=np.float64)),  # integral floats accepted
        lambda v, f: ([tuple(p) for p in v], [tuple(x) for x in f]),
        lambda v, f: (v, [np.array(x, dtype=np.int32) for x in f]),
    ],
)
def test_inputs_as_lists_or_arrays(quads, convert):
    v, f = quads
    cv, cf = convert(np.asarray(v), f)
    with mesh_handle(cv, cf) as handle:
        back_v, back_f = mesh_arrays(handle)
    assert np.allclose(back_v, v, atol=1e-6) and back_f.tolist() == f


def test_pipeline_on_a_curved_shell(curved):
    v, f = curved
    qv, qf = tp.remesh(v, f, target_edge=0.145)
    assert qv.dtype == np.float64 and qv.shape[1] == 3
    assert qf.shape[1] == 4 and len(qf) > 100
    pattern = tp.match(qv, qf, bond="staggered", time_limit=5)
    assert pattern.status in ("optimal", "time_limit", "feasible")
    assert pattern.bound >= pattern.objective - 1e-9 and 0 <= pattern.gap <= 1 and pattern.seconds >= 0
    assert pattern.pairs.shape[1] == 2 and pattern.pairs.dtype == np.int64
    assert np.all(pattern.pairs[:, 0] < pattern.pairs[:, 1])
    assert 2 * len(pattern.pairs) + len(pattern.unpaired) + pattern.excluded + pattern.non_quad == len(qf) == pattern.faces
    assert pattern.counts["pairs"] == len(pattern.pairs)
    assert pattern.to_dict()["pairs"] == pattern.pairs.tolist()
    assert pattern.bound_source in ("matching", "patches", "whole_program", "linear_relaxation")

    placed = tp.tiles(qv, qf, pattern, surface=(v, f))
    n = len(placed)
    assert placed.corners.shape == (n, 8, 3) and placed.frames.shape == (n, 4, 3) and placed.sizes.shape == (n, 3)
    assert placed.faces.shape == (n, 2) and len(placed.labels) == len(placed.outlines) == n
    assert sorted(placed.steps.tolist()) == list(range(n))
    assert sum(entry["count"] for entry in placed.cutlist) == n
    report = placed.report
    # Full and half tiles count the tiles laid on the quads; filler pieces close the courses
    # that end short of the surface's edge.
    fillers = report["cutting"]["filler_tiles"]
    assert report["full_tiles"] + report["half_tiles"] == n - fillers
    assert fillers == int(np.sum(placed.faces[:, 0] < 0))
    assert report["cutting"]["coverage"] > 0.9
    for kind, fraction, outline in zip(placed.kinds, placed.kept_fractions, placed.outlines):
        assert (kind in ("boundary", "fit_cut")) == (fraction < 1.0) == bool(outline)
    assert set(placed.kinds.tolist()) <= {"full", "half", "boundary", "fit_cut"}
    assert set(placed.blanks.tolist()) <= {"full", "half"}
    on_quads = placed.faces[:, 0] >= 0
    assert (placed.blanks[on_quads] == "full").sum() == report["full_tiles"]
    # The fit ran (default) and its figures are in the report.
    assert report["fit"]["status"] in ("converged", "iteration_limit", "time_limit")
    assert report["joints"]["before_fit"]["contacts"] > 0 and report["seconds"]["fit"] >= 0
    assert placed.joint_deviations.shape == (n,) and np.all(placed.joint_deviations >= 0)


def test_remesh_options_reach_the_library(curved):
    v, f = curved
    qv, qf = tp.remesh(v, f, target_edge=0.2, direction=[1, 0, 0], shapeup=True)
    edges = qv[qf[:, 1]] - qv[qf[:, 0]]
    mean = np.mean(np.linalg.norm(edges, axis=1))
    assert 0.15 < mean < 0.25
    qv2, qf2 = tp.remesh(v, f, target_edge=0.2, angle=45)
    assert len(qf2) > 20
    qv3, qf3 = tp.remesh(v, f, target_edge=0.2, direction="smooth")
    assert len(qf3) > 20


def test_frames_and_corners_agree():
    v, f = grid(5, 4, height=lambda x, y: 0.2 * x * y)
    placed = tp.tiles(v, f, tp.match(v, f, time_limit=5))
    for frame, size, corners in zip(placed.frames, placed.sizes, placed.corners):
        origin, x, y, z = frame
        assert np.allclose(frame[1:] @ frame[1:].T, np.eye(3))  # orthonormal
        assert np.isclose(np.dot(np.cross(x, y), z), 1.0)  # right-handed
        half = size / 2
        expected = [origin + sx * half[0] * x + sy * half[1] * y for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        assert np.allclose(corners[:4], expected)
        assert np.allclose(corners[4:], np.array(expected) + z * size[2])
        assert math.isclose(np.linalg.norm(corners[1] - corners[0]), size[0])
    assert np.allclose(placed.centres, placed.corners.mean(axis=1))


def test_half_tiles_have_one_face():
    v, f = grid(3, 1)
    placed = tp.tiles(v, f, tp.match(v, f, time_limit=5))
    assert sorted(placed.kinds.tolist()) == ["full", "half"]
    half = int(np.flatnonzero(placed.kinds == "half")[0])
    assert placed.faces[half, 1] == -1 and placed.faces[half, 0] >= 0
    assert placed.labels[half] == "H" and placed.blanks[half] == "half"
    assert np.isclose(placed.sizes[half, 0], 0.14)


def test_stack_bond_forced_pairs_and_excluded_faces(quads):
    v, f = quads
    pattern = tp.match(v, f, bond="stack", forced_pairs=[[0, 1]], excluded_faces=[79], time_limit=5)
    assert [0, 1] in pattern.pairs.tolist()
    assert 79 not in pattern.pairs and 79 not in pattern.unpaired and pattern.excluded == 1
    running = tp.match(*grid(6, 4), bond="running", weight=0.3, time_limit=5)
    assert running.optimal and running.shifted_pairs == 8
    paper = tp.match(v, f, method="mip", formulation="paper", time_limit=5)
    assert paper.optimal and len(paper.pairs) == 40


def test_a_gap_stops_the_search_once_close_enough():
    # The paper's plain program on CBC would prove 10 x 10 (w = 0.5) only by branching; with
    # a 5 % gap it stops at the first pattern that close to its bound.
    pattern = tp.match(*grid(10, 10), method="mip", formulation="paper", time_limit=60, gap=0.05)
    assert pattern.status == "feasible" and 0 < pattern.gap <= 0.05


def test_zero_time_limit_returns_the_greedy_start(quads):
    v, f = quads
    pattern = tp.match(v, f, time_limit=0)
    assert len(pattern.pairs) > 0 and pattern.status in ("optimal", "time_limit", "feasible")


def test_tile_options(quads):
    v, f = quads
    with tp.match(v, f, time_limit=5) as pattern:
        placed = tp.tiles(v, f, pattern, length=0.28, width=0.14, thickness=0.02, joint=0.01, up=(0, 1, 0), support_band=0.1)
    assert np.allclose(placed.sizes[placed.kinds == "full"], [0.28, 0.14, 0.02])
    assert placed.report["tile"]["thickness"] == 0.02


def test_tiles_cut_to_a_smaller_surface():
    v, f = grid(9, 7)
    surface = triangulated(*grid(24, 20, edge=0.05))  # 1.2 x 1.0 inside the 1.305 x 1.015 quads
    placed = tp.tiles(v, f, tp.match(v, f, time_limit=5), surface=surface)
    cut = placed.kinds == "boundary"
    assert cut.any() and all(len(loops) >= 1 for loops in np.array(placed.outlines, dtype=object)[cut])
    assert any(label.startswith("B") for label in placed.labels)
    assert np.all(placed.kept_fractions[cut] < 1) and np.all(placed.kept_fractions > 0)
    for loops, size in zip(placed.outlines, placed.sizes):
        for loop in loops:
            assert loop.shape[1] == 2 and len(loop) >= 3
            assert np.all(np.abs(loop) <= size[:2] / 2 + 1e-9)


def test_patch_relaxations_prove_the_paper_figure_5():
    # 10 x 10 grid, w = 2: 49 tiles and no joint, which no matching bound can prove; the
    # star rows' linear relaxation does.
    n = 10
    vertices = [(x, y, 0.0) for y in range(n + 1) for x in range(n + 1)]
    faces = [(y * (n + 1) + x, y * (n + 1) + x + 1, (y + 1) * (n + 1) + x + 1, (y + 1) * (n + 1) + x) for y in range(n) for x in range(n)]
    pattern = tp.match(vertices, faces, bond="staggered", weight=2.0, time_limit=30)
    assert (pattern.objective, pattern.status, pattern.bound_source) == (49.0, "optimal", "linear_relaxation")
    assert pattern.to_dict()["bound_source"] == "linear_relaxation"
    # The paper's route proves it by branch and bound on the whole program.
    paper = tp.match(vertices, faces, bond="staggered", weight=2.0, time_limit=30, method="mip")
    assert (paper.objective, paper.status, paper.bound_source) == (49.0, "optimal", "whole_program")


def test_herringbone_and_basket_weave():
    # Issue 20: the basket weave of an 8 x 8 grid is 16 squares of two parallel tiles,
    # alternating: every face paired, no pair penalised, proven.
    v, f = grid(8, 8)
    basket = tp.match(v, f, bond="basket-weave", time_limit=30)
    assert basket.optimal and len(basket.pairs) == 32 and basket.objective == 32.0
    a, b = basket.pairs[:, 0], basket.pairs[:, 1]
    along_x = b == a + 1
    assert np.all(np.where(along_x, a % 2 == 0, (a // 8) % 2 == 0))
    assert tp.match(v, f, bond="basket_weave", time_limit=30).pairs.tolist() == basket.pairs.tolist()
    herring = tp.match(v, f, bond="herringbone", time_limit=5)
    assert len(herring.pairs) > 0 and herring.bound >= herring.objective
    with pytest.raises(tp.InvalidArgumentError, match="courses free"):
        tp.match(v, f, bond="herringbone", courses="level")
