"""tp.weld (tp_mesh_new_welded, ABI 10): a mesh as hosts give it, welded as the command line
reads a file, with where its vertices and faces came from."""

import numpy as np
import pytest

import tilepattern as tp

from meshes import round_dome

LEVEL = dict(courses="level", target_edge=0.15)


def soup(vertices, faces):
    """Every face with corners of its own, as an STL (numpy-stl) gives a mesh."""
    V = np.asarray(vertices, dtype=np.float64)
    F = np.asarray(faces)
    return V[F.reshape(-1)], np.arange(F.size).reshape(F.shape)


def test_a_soup_welded_is_the_mesh_it_came_from_and_is_tiled():
    V, F = round_dome()
    SV, SF = soup(V, F)
    # As given, a soup: refused, the message saying to weld.
    with pytest.raises(tp.InvalidMeshError, match="weld"):
        tp.run(SV, SF, tries=1, **LEVEL)
    welded = tp.weld(SV, SF)
    assert len(welded.vertices) == len(V) and len(welded.faces) == len(F)
    # Each face is its source's, on the same places; each vertex where its source is.
    assert np.array_equal(welded.face_source, np.arange(len(F)))
    assert np.array_equal(welded.vertices, SV[welded.vertex_source])
    assert np.allclose(np.asarray(welded.vertices)[np.asarray(welded.faces)], SV[SF])
    # Tiled as the dome itself.
    whole = tp.run(V, F, tries=1, **LEVEL)
    again = tp.run(welded.vertices, welded.faces, tries=1, **LEVEL)
    assert len(again.tiles) == len(whole.tiles)


def test_sources_carry_data_given_per_face_and_vertex_over():
    V, F = round_dome()
    SV, SF = soup(V, F)
    # A face given twice: the repeat is removed, so the faces after it move up.
    SF2 = np.vstack([SF[:3], SF[2:3], SF[3:]])
    welded = tp.weld(SV, SF2)
    assert len(welded.faces) == len(F)
    assert 3 not in welded.face_source.tolist()
    assert welded.face_source[3] == 4
    # A per-face list carried over: the faces of the surface's quarter x, y > 0, by face.
    centroids = np.asarray(SV)[SF2].mean(axis=1)
    quarter = (centroids[:, 0] > 0) & (centroids[:, 1] > 0)
    carried = np.flatnonzero(quarter[welded.face_source])
    left = tp.run(welded.vertices, welded.faces, tries=1, excluded_faces=carried, **LEVEL)
    centres = left.tiles.corners.mean(axis=1)
    assert not ((centres[:, 0] > 0.3) & (centres[:, 1] > 0.3)).any()


def test_zero_joins_nothing_and_a_bad_tolerance_is_refused():
    V, F = round_dome()
    SV, SF = soup(V, F)
    kept = tp.weld(SV, SF, tolerance=0)
    assert len(kept.vertices) == len(SV)
    for bad in (-1e-6, float("nan"), 1.0):
        with pytest.raises(tp.InvalidArgumentError, match="relative_tolerance"):
            tp.weld(SV, SF, tolerance=bad)
