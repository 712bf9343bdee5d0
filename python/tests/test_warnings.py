"""Warnings on odd input (issue 19): each with a stable code and a message saying what to do,
in ``Tiles.warnings``, in the report and issued as :class:`tilepattern.TilePatternWarning`."""

import warnings

import numpy as np
import pytest

import tilepattern as tp

from meshes import grid


def cube(n=2, edge=0.145):
    """A closed cube of n x n quads a side, normals out, shared corners."""
    size = n * edge
    index, vertices, faces = {}, [], []

    def vertex(p):
        key = tuple(np.round(p, 9))
        if key not in index:
            index[key] = len(vertices)
            vertices.append(p)
        return index[key]

    for k in range(3):
        for sign in (-1.0, 1.0):
            a, b = (k + 1) % 3, (k + 2) % 3
            if sign < 0:
                a, b = b, a
            at = {}
            for j in range(n + 1):
                for i in range(n + 1):
                    p = np.zeros(3)
                    p[k], p[a], p[b] = sign * size / 2, i * edge - size / 2, j * edge - size / 2
                    at[i, j] = vertex(p)
            for j in range(n):
                for i in range(n):
                    faces.append([at[i, j], at[i + 1, j], at[i + 1, j + 1], at[i, j + 1]])
    return np.array(vertices), np.array(faces)


def test_a_closed_surface_warns_with_codes_and_messages():
    v, f = cube()
    with tp.match(v, f, time_limit=5) as pattern:
        with pytest.warns(tp.TilePatternWarning, match="closed_surface"):
            placed = tp.tiles(v, f, pattern)
    codes = [w["code"] for w in placed.warnings]
    assert "closed_surface" in codes and "no_support" in codes
    assert all(len(w["message"]) > 30 for w in placed.warnings)
    assert [w["code"] for w in placed.report["warnings"]] == codes
    assert placed.report["sequence"]["support"] == "no_boundary"
    assert placed.report["sequence"]["support_tiles"] == 0


def test_tiles_off_the_half_tile_model_warn():
    v, f = grid(8, 6)
    with tp.match(v, f, time_limit=5) as pattern:
        with pytest.warns(tp.TilePatternWarning, match="tile_shape"):
            tp.tiles(v, f, pattern, length=0.30, width=0.10, thickness=0.02, joint=0.01)


def test_a_plain_tiling_is_quiet():
    v, f = grid(8, 6)
    # Stood up along y so the grid is a wall on its bottom edge, not a floor.
    v = np.column_stack([v[:, 0], np.zeros(len(v)), v[:, 1]])
    with tp.match(v, f, time_limit=5) as pattern:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            placed = tp.tiles(v, f, pattern, up=(0, 0, 1))
    assert placed.warnings == [] and placed.report["warnings"] == []


def test_a_level_floor_and_normals_down():
    v, f = grid(8, 6)
    with tp.match(v, f, time_limit=5) as pattern:
        with pytest.warns(tp.TilePatternWarning, match="no_support"):
            floor = tp.tiles(v, f, pattern)
    assert floor.report["sequence"]["support"] == "level"
    assert floor.report["sequence"]["unsupported"] == 0
    # The same grid seen from below: normals point down.
    with tp.match(v, f, time_limit=5) as pattern:
        with pytest.warns(tp.TilePatternWarning, match="normals_down"):
            tp.tiles(v, f, pattern, up=(0, 0, -1))
