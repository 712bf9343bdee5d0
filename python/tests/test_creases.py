"""Creases: a surface that turns sharply along a line is split there by default (each sheet
gets quads of its own and tiles are cut to the crease); ``creases=False`` runs one field over
it."""

import numpy as np

from meshes import grid
from tilepattern import match, remesh, tiles


def folded_plate():
    """A 2.4 x 1.2 m plate folded along x = 1.2 (the halves turn by 44 degrees)."""
    return grid(24, 12, edge=0.1, height=lambda x, y: 0.4 * np.abs(x - 1.2))


def over_the_fold(vertices, faces):
    """Quads with corners on both sides of the fold."""
    x = np.asarray(vertices)[:, 0] - 1.2
    return sum(1 for f in faces if (x[list(f)] < -0.01).any() and (x[list(f)] > 0.01).any())


def test_a_folded_plate_is_split_at_its_fold_unless_asked_not_to():
    V, F = folded_plate()
    split = remesh(V, F, target_edge=0.145)
    joined = remesh(V, F, target_edge=0.145, creases=False)
    assert over_the_fold(*split) == 0
    assert over_the_fold(*joined) > 0


def test_tiles_are_cut_to_the_fold_unless_asked_not_to():
    V, F = folded_plate()
    QV, QF = remesh(V, F, target_edge=0.145)
    pattern = match(QV, QF, time_limit=5)
    cut = [
        sum(1 for kind in tiles(QV, QF, pattern, surface=(V, F), creases=creases).kinds if kind == "boundary")
        for creases in (True, False)
    ]
    assert cut[0] > cut[1]
