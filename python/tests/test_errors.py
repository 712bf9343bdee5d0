"""Bad input raises TilePatternError with the library's status code and message."""

import numpy as np
import pytest

import tilepattern as tp

from meshes import grid, shell

NAN = float("nan")
TRIANGLE = [[0, 0, 0], [1, 0, 0], [1, 1, 0]]


@pytest.mark.parametrize(
    "vertices, faces, fragment",
    [
        ([[0, 0, 0], [1, 0, 0], [1, 1, NAN], [0, 1, 0]], [[0, 1, 2, 3]], "vertex 2"),
        ([[0, 0, 0], [1, 0, 0], [1, 1, float("inf")], [0, 1, 0]], [[0, 1, 2, 3]], "vertex 2"),
        (TRIANGLE, [[0, 1, 5]], "face 0"),
        (TRIANGLE, [[0, 1, 2], [0, 2, 2**40]], "face 1"),
        (TRIANGLE, [[0, 1, -1]], "face 0"),
        ([], [], "empty"),
        (np.zeros((0, 3)), np.zeros((0, 3), dtype=np.uint32), "empty"),
        (TRIANGLE, [[0, 1, 1]], "more than once"),
        (TRIANGLE, [[0, 1]], "at least 3"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], [[0, 1, 2], [1, 0, 3], [0, 1, 4]], "shared by 3"),
        ([[0, 0], [1, 0], [1, 1]], [[0, 1, 2]], "shape"),
        (TRIANGLE, [[0, 1, 1.5]], "integers"),
        ([["a", "b", "c"]], [[0, 1, 2]], "numbers"),
    ],
)
def test_bad_meshes(vertices, faces, fragment):
    for stage in (
        lambda: tp.match(vertices, faces, time_limit=1),
        lambda: tp.remesh(vertices, faces),
    ):
        with pytest.raises(tp.TilePatternError) as caught:
            stage()
        error = caught.value
        assert isinstance(error, tp.InvalidMeshError) and isinstance(error, ValueError)
        assert error.status == 4 and error.name == "TP_INVALID_MESH"
        assert fragment in error.message, error.message


@pytest.mark.parametrize(
    "options, status, fragment",
    [
        (dict(weight=NAN), 2, "weight"),
        (dict(time_limit=-1), 2, "time limit"),
        (dict(time_limit=NAN), 2, ""),
        (dict(gap=-0.01), 2, "relative gap"),
        (dict(gap=1.5), 2, "relative gap"),
        (dict(gap=NAN), 2, "relative gap"),
        (dict(bond="flemish"), 2, "flemish"),
        (dict(bond=7), 2, "bond 7"),
        (dict(method="magic"), 2, "magic"),
        (dict(formulation=5), 2, ""),
        (dict(forced_pairs=[[0, 55]]), 2, "[0, 55]"),
        (dict(forced_pairs=[[0, 1, 2]]), 2, "pairs"),
        (dict(forced_pairs=[[0, -1]]), 2, "-1"),
        (dict(excluded_faces=[80]), 2, "face 80"),
        (dict(excluded_faces=[0.5]), 2, "integers"),
        (dict(progress="not callable"), 2, "callable"),
    ],
)
def test_bad_pattern_options(quads, options, status, fragment):
    v, f = quads
    with pytest.raises(tp.TilePatternError) as caught:
        tp.match(v, f, **options)
    assert caught.value.status == status and caught.value.name == "TP_INVALID_ARGUMENT", caught.value
    assert isinstance(caught.value, tp.InvalidArgumentError)
    assert fragment in caught.value.message


@pytest.mark.parametrize(
    "options, fragment",
    [
        (dict(length=0), "length"),
        # The library derives the default cut tolerance (1 % of the width) before it checks
        # the width, so the message names the tolerance: "tile tolerance -0.01 must be ...".
        (dict(width=-1), ""),
        (dict(thickness=NAN), ""),
        (dict(joint=-0.5), "joint"),
        (dict(up=(0, 0, 0)), ""),
        (dict(up=(0, 1)), "up"),
    ],
)
def test_bad_tile_options(quads, options, fragment):
    v, f = quads
    pattern = tp.match(v, f, time_limit=1)
    with pytest.raises(tp.InvalidArgumentError) as caught:
        tp.tiles(v, f, pattern, **options)
    assert caught.value.status == 2 and fragment in caught.value.message


def test_a_pattern_on_another_mesh(quads):
    v, f = quads
    pattern = tp.match(v, f, time_limit=1)
    with pytest.raises(tp.InvalidPatternError) as caught:
        tp.tiles(*grid(3, 3), pattern)
    assert caught.value.status == 5 and caught.value.name == "TP_INVALID_PATTERN"
    with pytest.raises(tp.InvalidArgumentError):
        tp.tiles(v, f, "not a pattern")


@pytest.mark.parametrize(
    "options, error, status",
    [
        (dict(target_edge=0), tp.InvalidArgumentError, 2),
        (dict(target_edge=-0.1), tp.InvalidArgumentError, 2),
        (dict(time_limit=-1), tp.InvalidArgumentError, 2),
        (dict(direction=(0, 0, 0, 1)), tp.InvalidArgumentError, 2),
        (dict(direction=(1, 0, 0), angle=45), tp.InvalidArgumentError, 2),
        (dict(direction="smoooth"), tp.InvalidArgumentError, 2),
        (dict(direction="smooth", angle=45), tp.InvalidArgumentError, 2),
        (dict(time_limit=0), tp.TimeLimitError, 7),
    ],
)
def test_bad_remesh_options(options, error, status):
    v, f = shell(10, 8, edge=0.1)
    with pytest.raises(error) as caught:
        tp.remesh(v, f, **options)
    assert caught.value.status == status and caught.value.name == tp._native.STATUS_NAMES[status]
    assert caught.value.message
