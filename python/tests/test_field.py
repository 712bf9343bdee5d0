"""The designer's field (issue 20): ``remesh(..., field=, field_weight=)`` with one vector
per vertex or per face, as a numpy array or a sequence; bad fields name the index at fault."""

import math

import numpy as np
import pytest

import tilepattern as tp
from meshes import grid, triangulated

ANGLE = math.radians(30.0)
DIRECTION = (math.cos(ANGLE), math.sin(ANGLE), 0.0)


def plate():
    """A flat 1.74 x 1.74 m plate of 24 x 24 squares, each split into two triangles."""
    return triangulated(*grid(24, 24, edge=0.0725))


def alignment(qv, qf):
    """Mean |cos 4 theta| of the quad edges against DIRECTION (1: every edge on it or
    across it)."""
    qf = np.asarray(qf)
    a, b = qv[qf], qv[np.roll(qf, -1, axis=1)]
    theta = np.arctan2(b[..., 1] - a[..., 1], b[..., 0] - a[..., 0]) - ANGLE
    return float(np.abs(np.cos(4.0 * theta)).mean())


def test_a_field_per_face_or_per_vertex_turns_the_quads():
    v, f = plate()
    plain = alignment(*tp.remesh(v, f, target_edge=0.145))
    per_face = np.tile(DIRECTION, (len(f), 1))
    per_face[::2] *= -3.0  # signs and lengths do not matter
    turned = alignment(*tp.remesh(v, f, target_edge=0.145, field=per_face))
    as_lists = [list(DIRECTION)] * len(v)
    by_vertex = alignment(*tp.remesh(v, f, target_edge=0.145, field=as_lists, field_weight=1.0))
    none = alignment(*tp.remesh(v, f, target_edge=0.145, field=per_face, field_weight=0.0))
    assert turned > plain + 0.2, (plain, turned)
    assert by_vertex > plain + 0.2, (plain, by_vertex)
    assert none < turned - 0.2, (none, turned)
    # Deterministic.
    again = tp.remesh(v, f, target_edge=0.145, field=per_face)
    first = tp.remesh(v, f, target_edge=0.145, field=per_face)
    assert np.array_equal(again[0], first[0]) and np.array_equal(again[1], first[1])


@pytest.mark.parametrize(
    "change, message",
    [
        (lambda x: x[:-1], "vertices"),
        (lambda x: np.vstack([x[:7], [[0.0, 0.0, 0.0]], x[8:]]), "face 7"),
        (lambda x: np.vstack([x[:3], [[np.nan, 1.0, 0.0]], x[4:]]), "face 3"),
        (lambda x: x[:, :2], "(n, 3)"),
        (lambda x: [["a", "b", "c"]] * len(x), "(n, 3)"),
    ],
)
def test_bad_fields_are_refused_with_the_index(change, message):
    v, f = plate()
    per_face = np.tile(DIRECTION, (len(f), 1))
    with pytest.raises(tp.InvalidArgumentError) as error:
        tp.remesh(v, f, target_edge=0.145, field=change(per_face))
    assert message in str(error.value)
    assert error.value.status == 2


def test_a_weight_outside_0_to_1_is_refused():
    v, f = plate()
    with pytest.raises(tp.InvalidArgumentError, match="weight"):
        tp.remesh(v, f, target_edge=0.145, field=np.tile(DIRECTION, (len(v), 1)), field_weight=1.5)
