"""The three stages on plain arrays, errors, cancellation and handle lifetime."""

import math

import numpy as np
import pytest

import tilepattern as tp
from tilepattern import _native
from tilepattern.core import _mesh, mesh_arrays

from meshes import grid


def test_every_export_of_the_header_is_declared():
    header = open(_native.library_path().parents[2] / "include" / "tilepattern.h").read()
    import re

    exports = set(re.findall(r"\b(tp_[a-z0-9_]+)\(", header)) - {"tp_test_panic"}
    declared = set(_native._EXPORTS)
    assert exports - declared == set(), "exports without a declaration"
    assert declared - exports == set(), "declarations of functions the header does not have"


def test_option_structs_match_the_library_sizes():
    for struct, init in [
        (_native.PatternOptions, "tp_pattern_options_init"),
        (_native.RemeshOptions, "tp_remesh_options_init"),
        (_native.TileOptions, "tp_tile_options_init"),
    ]:
        assert _native.init(struct, init).struct_size == __import__("ctypes").sizeof(struct)
        default = getattr(_native.lib(), init.replace("_init", "_default"))()
        assert default.struct_size == __import__("ctypes").sizeof(struct)


def test_mesh_round_trip_keeps_order(quads):
    v, f = quads
    with _mesh(v, f) as handle:
        back_v, back_f = mesh_arrays(handle)
    assert np.array_equal(back_v, v)
    assert [list(x) for x in back_f] == f


def test_pipeline_on_a_curved_shell(shell):
    v, f = shell
    qv, qf = tp.remesh(v, f, target_edge=0.145)
    assert qf.shape[1] == 4 and len(qf) > 100
    pattern = tp.match(qv, qf, bond="staggered", time_limit=5)
    assert pattern.status in ("optimal", "time_limit", "feasible")
    assert pattern.bound >= pattern.objective
    assert 2 * len(pattern.pairs) + len(pattern.unpaired) + pattern.excluded + pattern.non_quad == len(qf)
    placed = tp.tiles(qv, qf, pattern, surface=(v, f))
    assert len(placed) == len(placed.labels) == len(placed.steps) == len(placed.outlines)
    assert sorted(placed.steps) == list(range(len(placed)))
    assert sum(g["count"] for g in placed.cut_list) == len(placed)
    assert placed.report["cutting"]["coverage"] > 0.9
    for kind, fraction, outline in zip(placed.kinds, placed.kept_fractions, placed.outlines):
        assert (kind == "boundary") == (fraction < 1.0) == bool(outline)


def test_frames_and_corners_agree(quads):
    v, f = quads
    placed = tp.tiles(v, f, tp.match(v, f, time_limit=5))
    for frame, size, corners in zip(placed.frames, placed.sizes, placed.corners):
        origin, x, y, z = frame
        expected = origin + x * (-size[0] / 2) + y * (-size[1] / 2)
        assert np.allclose(corners[0], expected)
        assert np.allclose(corners[4], expected + z * size[2])
        assert math.isclose(np.linalg.norm(corners[1] - corners[0]), size[0])


def test_half_tiles_have_one_face(quads):
    v, f = grid(3, 1)
    placed = tp.tiles(v, f, tp.match(v, f, time_limit=5))
    half = [k for k, kind in enumerate(placed.kinds) if kind == "half"]
    assert len(half) == 1 and placed.faces[half[0], 1] == -1


def test_stack_bond_and_forced_and_excluded(quads):
    v, f = quads
    p = tp.match(v, f, bond="stack", forced_pairs=[[0, 1]], excluded_faces=[79], time_limit=5)
    assert [0, 1] in p.pairs.tolist()
    assert 79 not in p.pairs and p.excluded == 1


@pytest.mark.parametrize(
    "vertices, faces, code",
    [
        ([[0, 0, 0], [1, 0, 0], [1, 1, float("nan")], [0, 1, 0]], [[0, 1, 2, 3]], "TP_INVALID_MESH"),
        ([[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 1, 5]], "TP_INVALID_MESH"),
        ([[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 1, -1]], "TP_INVALID_MESH"),
        ([], [], "TP_INVALID_MESH"),
        ([[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 1, 1]], "TP_INVALID_MESH"),
    ],
)
def test_bad_meshes_raise_with_the_native_status(vertices, faces, code):
    with pytest.raises(tp.TilePatternError) as caught:
        tp.match(vertices, faces, time_limit=1)
    assert caught.value.name == code
    assert caught.value.message


def test_bad_options_raise(quads):
    v, f = quads
    for kwargs in [dict(weight=float("nan")), dict(time_limit=-1), dict(bond="herringbone"), dict(forced_pairs=[[0, 55]])]:
        with pytest.raises(tp.TilePatternError) as caught:
            tp.match(v, f, **kwargs)
        assert caught.value.status in (2, 5), kwargs
    with pytest.raises(tp.TilePatternError) as caught:
        tp.tiles(v, f, tp.match(v, f, time_limit=1), length=0)
    assert caught.value.name == "TP_INVALID_ARGUMENT"


def test_progress_can_cancel_and_errors_in_it_surface():
    v, f = grid(60, 60)
    seen = []

    def stop(stage, fraction):
        seen.append((stage, fraction))
        return True

    with pytest.raises(tp.TilePatternError) as caught:
        tp.match(v, f, bond="running", time_limit=30, progress=stop)
    assert caught.value.name == "TP_CANCELLED" and seen[0][0] == "pattern"

    def broken(stage, fraction):
        raise KeyError("from the callback")

    with pytest.raises(KeyError):
        tp.match(v, f, bond="running", time_limit=30, progress=broken)


def test_handles_close_once(quads):
    v, f = quads
    p = tp.match(v, f, time_limit=1)
    p.close()
    p.close()
    with pytest.raises(ValueError):
        tp.tiles(v, f, p)
