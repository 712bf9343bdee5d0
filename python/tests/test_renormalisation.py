"""The field's renormalisation strength: on a round dome (no corner, so where its field's
cones sit is free) other strengths give other, equally valid quads; the default is 0.5, and a
negative strength is refused by name."""

import numpy as np
import pytest

from tilepattern import InvalidArgumentError, remesh


def round_dome(rings=12, sectors=48):
    """A spherical cap of radius 2 over a disk of radius 1.3: a centre, rings of triangles."""
    V = [[0.0, 0.0, 2.0]]
    for i in range(1, rings + 1):
        r = 1.3 * i / rings
        for j in range(sectors):
            a = 2 * np.pi * j / sectors
            V.append([r * np.cos(a), r * np.sin(a), np.sqrt(4.0 - r * r)])

    def at(i, j):
        return 0 if i == 0 else 1 + (i - 1) * sectors + j % sectors

    F = [[0, at(1, j), at(1, j + 1)] for j in range(sectors)]
    for i in range(1, rings):
        for j in range(sectors):
            F += [[at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]]
    return np.array(V), F


def test_other_strengths_give_other_quads_and_the_default_is_half():
    V, F = round_dome()
    default = remesh(V, F, target_edge=0.145)
    half = remesh(V, F, target_edge=0.145, renormalisation=0.5)
    twice = remesh(V, F, target_edge=0.145, renormalisation=1.0)
    assert np.array_equal(default[0], half[0])
    assert default[0].shape != twice[0].shape or not np.array_equal(default[0], twice[0])
    none = remesh(V, F, target_edge=0.145, renormalisation=0.0)
    assert none[1].shape[1] == 4


def test_a_negative_strength_is_refused_by_name():
    V, F = round_dome()
    with pytest.raises(InvalidArgumentError, match="renormalisation"):
        remesh(V, F, target_edge=0.145, renormalisation=-1.0)
