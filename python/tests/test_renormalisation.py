"""The field's renormalisation strength: on a round dome (no corner, so where its field's
cones sit is free) other strengths give other, equally valid quads; the default is 0.5, and a
negative strength is refused by name."""

import numpy as np
import pytest

from tilepattern import InvalidArgumentError, remesh

from meshes import round_dome


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
