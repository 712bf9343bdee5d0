"""COMPAS sample meshes through the pipeline; COMPAS boxes against the C ABI's frames.

``compas.get`` returns the path of a sample that ships inside the compas wheel
(``compas/data/samples``), so these tests need no network.
"""

import os

import numpy as np
import pytest

compas = pytest.importorskip("compas")
from compas.datastructures import Mesh  # noqa: E402
from compas.geometry import Box  # noqa: E402

import tilepattern as tp  # noqa: E402
import tilepattern.compas as tpc  # noqa: E402


def sample(name):
    path = compas.get(name)
    if not os.path.isfile(path):
        pytest.skip("%s is not shipped with this compas (%s) and the tests stay offline" % (name, path))
    return Mesh.from_obj(path)


def tile_for(mesh, scale=1.0):
    """A tile whose (L + joint) / 2 is ``scale`` times the mesh's mean edge; joint L / 30."""
    edge = scale * np.mean([mesh.edge_length(e) for e in mesh.edges()])
    length = 2 * edge / (1 + 1 / 30)
    return dict(length=length, width=length / 2, thickness=length / 20, joint=length / 30)


def assert_boxes_match_tiles(boxes, placed):
    assert len(boxes) == len(placed)
    for box, frame, size, corners, label in zip(boxes, placed.frames, placed.sizes, placed.corners, placed.labels):
        assert isinstance(box, Box) and box.name == label
        assert np.allclose([box.xsize, box.ysize, box.zsize], size)
        # COMPAS frames sit at the box centre, TilePattern's at the centre of its bottom face.
        assert np.allclose(box.frame.point, frame[0] + frame[3] * size[2] / 2)
        assert np.allclose(box.frame.xaxis, frame[1]) and np.allclose(box.frame.yaxis, frame[2])
        assert np.allclose(box.frame.zaxis, frame[3])
        # Same 8 corners (COMPAS lists them in another order).
        points = np.array([list(p) for p in box.points])
        distance = np.linalg.norm(points[:, None, :] - corners[None, :, :], axis=2)
        assert np.all(distance.min(axis=1) < 1e-9) and np.all(distance.min(axis=0) < 1e-9)


@pytest.mark.parametrize("name", ["tubemesh.obj", "hypar.obj", "quadmesh.obj"])
def test_sample_quad_meshes(name):
    mesh = sample(name)
    pattern = tpc.match(mesh, time_limit=1)
    assert pattern.faces == mesh.number_of_faces()
    boxes = tpc.tiles(mesh, pattern, **tile_for(mesh))
    assert isinstance(boxes, list) and isinstance(boxes, tpc.TileBoxes)
    assert_boxes_match_tiles(boxes, boxes.tiles)
    report = tpc.report(boxes)
    assert report["faces"] == mesh.number_of_faces() and report == tpc.report(boxes.tiles)
    # Pairs become full tiles unless they fall off the surface or the fit leaves a sliver.
    cutting = report["cutting"]
    assert report["full_tiles"] >= len(pattern.pairs) - cutting["outside_tiles"] - len(cutting["slivers"])
    assert report["full_tiles"] + report["half_tiles"] == len(boxes) - cutting["filler_tiles"]
    assert set(boxes.tiles.kinds.tolist()) <= {"full", "half", "boundary", "fit_cut"}
    fit_cut = boxes.tiles.kinds == "fit_cut"
    assert all(label.startswith("C") for label in np.array(boxes.tiles.labels)[fit_cut])
    assert int(fit_cut.sum()) <= report["joints"]["fit_cuts"]


def test_boxes_agree_with_the_c_abi():
    """The same mesh through the array API (the C ABI's frames and corners as they come)
    and through tilepattern.compas."""
    mesh = sample("hypar.obj")
    tile = tile_for(mesh)
    vertices, faces = mesh.to_vertices_and_faces()
    placed = tp.tiles(vertices, faces, tp.match(vertices, faces, time_limit=5), **tile)
    boxes = tpc.tiles(mesh, tpc.match(mesh, time_limit=5), **tile)
    assert_boxes_match_tiles(boxes, placed)
    assert_boxes_match_tiles(tpc.boxes(placed), placed)


def test_remesh_a_triangulated_sample_and_tile_it():
    surface = sample("hypar.obj")
    tile = tile_for(surface, scale=0.5)
    surface.quads_to_triangles()
    assert all(len(surface.face_vertices(f)) == 3 for f in surface.faces())
    quads = tpc.remesh(surface, target_edge=(tile["length"] + tile["joint"]) / 2)
    assert isinstance(quads, Mesh) and quads.number_of_faces() > 150
    assert all(len(quads.face_vertices(f)) == 4 for f in quads.faces())
    pattern = tpc.match(quads, time_limit=2)
    boxes = tpc.tiles(quads, pattern, surface=surface, **tile)
    report = tpc.report(boxes)
    assert report["cutting"]["coverage"] > 0.9
    assert report["full_tiles"] + report["half_tiles"] == len(boxes) - report["cutting"]["filler_tiles"]


def test_face_keys_are_translated():
    mesh = sample("quadmesh.obj")
    removed = 5
    mesh.delete_face(removed)
    mesh.remove_unused_vertices()
    keys = list(mesh.faces())
    assert keys != list(range(len(keys)))
    last = keys[-1]
    pattern = tpc.match(mesh, bond="stack", excluded_faces=[last], time_limit=2)
    used = set(pattern.pairs.ravel().tolist()) | set(pattern.unpaired.tolist())
    assert used <= set(keys) and last not in used and removed not in used
    boxes = tpc.tiles(mesh, pattern, **tile_for(mesh))
    faces = boxes.tiles.faces
    assert set(faces[faces >= 0].tolist()) <= set(keys)
    with pytest.raises(tp.InvalidArgumentError, match="no face 5"):
        tpc.match(mesh, excluded_faces=[removed])
    # Zones by face key: a herringbone zone reaches the solve (level courses refuse it).
    with pytest.raises(tp.InvalidArgumentError, match="courses free"):
        tpc.match(mesh, zones={last: "herringbone"}, courses="level")
    with pytest.raises(tp.InvalidArgumentError, match="zones: the mesh has no face 5"):
        tpc.match(mesh, zones={removed: "stack"})
    zoned = tpc.match(mesh, zones={k: "herringbone" for k in keys[:10]}, time_limit=2)
    assert set(zoned.pairs.ravel().tolist()) | set(zoned.unpaired.tolist()) <= set(keys)


def test_run_on_a_compas_surface():
    """tpc.run: the array API's run on the same surface, as a COMPAS quad mesh, the pattern
    and boxes; zones keyed by the surface's face keys."""
    surface = sample("hypar.obj")
    tile = tile_for(surface, scale=0.5)
    surface.quads_to_triangles()
    result = tpc.run(surface, courses="level", tries=3, time_limit=10, **tile)
    quads, pattern, boxes = result
    assert isinstance(quads, Mesh) and isinstance(pattern, tp.Pattern) and isinstance(boxes, tpc.TileBoxes)
    assert all(len(quads.face_vertices(f)) == 4 for f in quads.faces())
    assert len(result.tries) == 3 and result.chosen_try in (0, 1, 2) and tpc.report(result) == boxes.report
    # The same as tilepattern.run on the surface's arrays.
    vertices, faces = surface.to_vertices_and_faces()
    arrays = tp.run(vertices, faces, courses="level", tries=3, time_limit=10, **tile)
    qv, qf = quads.to_vertices_and_faces()
    assert np.array_equal(np.array(qv), arrays.vertices) and np.array_equal(np.array(qf), arrays.faces)
    assert np.array_equal(pattern.pairs, arrays.pattern.pairs) and arrays.chosen_try == result.chosen_try
    assert_boxes_match_tiles(boxes, arrays.tiles)


def test_run_takes_zones_by_surface_face_key():
    surface = sample("hypar.obj")
    tile = tile_for(surface, scale=0.5)
    surface.quads_to_triangles()
    removed = next(iter(surface.faces()))  # a corner triangle; keys then run from 65, not 0
    surface.delete_face(removed)
    surface.remove_unused_vertices()
    keys = list(surface.faces())
    assert keys != list(range(len(keys)))
    options = dict(courses="level", tries=1, time_limit=10, **tile)
    stack = tpc.run(surface, bond="stack", **options)
    zoned = tpc.run(surface, zones={k: "stack" for k in keys}, **options)
    assert np.array_equal(zoned.pattern.pairs, stack.pattern.pairs)
    assert zoned.pattern.objective == stack.pattern.objective
    # Half the surface by key (a dict) = the same zones in mesh.faces() order (a sequence),
    # and not the other half.
    half = len(keys) // 2
    by_key = tpc.run(surface, zones={k: "stack" for k in keys[:half]}, **options)
    in_order = tpc.run(surface, zones=["stack"] * half + [None] * (len(keys) - half), **options)
    other = tpc.run(surface, zones=[None] * half + ["stack"] * (len(keys) - half), **options)
    assert np.array_equal(by_key.pattern.pairs, in_order.pattern.pairs)
    assert not np.array_equal(by_key.pattern.pairs, other.pattern.pairs)
    # A herringbone zone reaches the library (level courses refuse it); an unknown key is refused.
    with pytest.raises(tp.InvalidArgumentError, match="courses free"):
        tpc.run(surface, zones={keys[-1]: "herringbone"}, **options)
    with pytest.raises(tp.InvalidArgumentError, match="zones: the mesh has no face %d" % removed):
        tpc.run(surface, zones={removed: "stack"}, **options)


def test_run_takes_excluded_faces_by_surface_face_key():
    surface = sample("hypar.obj")
    tile = tile_for(surface, scale=0.5)
    surface.quads_to_triangles()
    removed = next(iter(surface.faces()))  # keys then run from 65, not 0
    surface.delete_face(removed)
    surface.remove_unused_vertices()
    keys = list(surface.faces())
    options = dict(courses="level", tries=1, time_limit=10, **tile)
    # Half the surface by key = the same faces by position; the last key is beyond the
    # positions, so it is translated, not read as a position.
    half = keys[len(keys) // 2:]
    by_key = tpc.run(surface, excluded_faces=half, **options)
    by_position = tp.run(*tpc.mesh_vertices_faces(surface)[:2], excluded_faces=range(len(keys) // 2, len(keys)), **options)
    whole = tpc.run(surface, **options)
    assert len(by_key.boxes) == len(by_position.tiles) < len(whole.boxes)
    with pytest.raises(tp.InvalidArgumentError, match="excluded_faces: the mesh has no face %d" % removed):
        tpc.run(surface, excluded_faces=[removed], **options)
