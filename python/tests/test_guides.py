"""Guide curves (issue 20): ``remesh(..., guides=, guide_weight=)`` with polylines as numpy
arrays or sequences; bad curves name the curve and point at fault."""

import math

import numpy as np
import pytest

import tilepattern as tp
from meshes import grid, triangulated

ANGLE = math.radians(30.0)
DIRECTION = np.array([math.cos(ANGLE), math.sin(ANGLE), 0.0])
CENTRE = np.array([0.87, 0.87, 0.0])


def plate():
    """A flat 1.74 x 1.74 m plate of 24 x 24 squares, each split into two triangles."""
    return triangulated(*grid(24, 24, edge=0.0725))


def guides():
    """A line through the plate's centre at 30 degrees (three points, a numpy array) and a
    short one near a corner along the same direction (a list of lists)."""
    line = CENTRE + np.outer([-0.9, 0.0, 0.9], DIRECTION)
    corner = [[0.1, 0.1, 0.0], list(np.array([0.1, 0.1, 0.0]) + 0.3 * DIRECTION)]
    return [line, corner]


def alignment(qv, qf):
    """Mean |cos 4 theta| of the quad edges against DIRECTION (1: every edge on it or
    across it)."""
    qf = np.asarray(qf)
    a, b = qv[qf], qv[np.roll(qf, -1, axis=1)]
    theta = np.arctan2(b[..., 1] - a[..., 1], b[..., 0] - a[..., 0]) - ANGLE
    return float(np.abs(np.cos(4.0 * theta)).mean())


def test_guides_turn_the_quads():
    v, f = plate()
    plain = alignment(*tp.remesh(v, f, target_edge=0.145))
    guided = tp.remesh(v, f, target_edge=0.145, guides=guides())
    turned = alignment(*guided)
    none = alignment(*tp.remesh(v, f, target_edge=0.145, guides=guides(), guide_weight=0.0))
    assert turned > plain + 0.2, (plain, turned)
    assert none < turned - 0.2, (none, turned)
    # Deterministic.
    again = tp.remesh(v, f, target_edge=0.145, guides=guides())
    assert np.array_equal(again[0], guided[0]) and np.array_equal(again[1], guided[1])


def _short(g):
    g[1] = g[1][:1]
    return g


def _nan(g):
    g[0] = g[0].copy()
    g[0][2, 0] = np.nan
    return g


def _lifted(g):
    g[1] = [[0.0, 0.0, 3.0], [1.0, 0.0, 3.0]]
    return g


def _flat(g):
    g[0] = g[0][:, :2]
    return g


@pytest.mark.parametrize(
    "change, message",
    [
        (_short, "guide curve 1 has 1 point"),
        (_nan, "point 2 of guide curve 0"),
        (_lifted, "guide curve 1 is nowhere near"),
        (_flat, "guide curve 0 must be an (n, 3) array"),
        (lambda g: g[0], "list of polylines"),
    ],
)
def test_bad_guides_are_refused_with_the_index(change, message):
    v, f = plate()
    with pytest.raises(tp.InvalidArgumentError) as error:
        tp.remesh(v, f, target_edge=0.145, guides=change(guides()))
    assert message in str(error.value)
    assert error.value.status == 2


def test_a_guide_weight_outside_0_to_1_is_refused():
    v, f = plate()
    with pytest.raises(tp.InvalidArgumentError, match="guide weight"):
        tp.remesh(v, f, target_edge=0.145, guides=guides(), guide_weight=1.5)
