"""COMPAS sample meshes through the pipeline; COMPAS boxes against the C ABI's frames."""

import compas
import numpy as np
import pytest
from compas.datastructures import Mesh

import tilepattern.compas as tpc


def tile_for(mesh, scale=1.0):
    """A tile whose (L + joint) / 2 is `scale` times the mesh's mean edge, joint a fifteenth
    of L."""
    edge = scale * np.mean([mesh.edge_length(e) for e in mesh.edges()])
    length = 2 * edge / (1 + 1 / 15)
    return dict(length=length, width=length / 2, thickness=length / 20, joint=length / 15)


@pytest.mark.parametrize("name", ["tubemesh.obj", "hypar.obj", "quadmesh.obj"])
def test_sample_quad_meshes(name):
    mesh = Mesh.from_obj(compas.get(name))
    pattern = tpc.match(mesh, time_limit=3)
    placed = tpc.tiles(mesh, pattern, **tile_for(mesh))
    assert len(placed) >= len(pattern.pairs)
    boxes = tpc.boxes(placed)
    assert len(boxes) == len(placed)
    # COMPAS frames sit at the box centre, ours at the bottom face's centre.
    for box, frame, size, corners in zip(boxes, placed.frames, placed.sizes, placed.corners):
        assert np.allclose(box.frame.point, frame[0] + frame[3] * size[2] / 2)
        assert np.allclose(sorted(map(tuple, np.round(box.points, 9))), sorted(map(tuple, np.round(corners, 9))))
    assert tpc.report(placed)["faces"] == mesh.number_of_faces()


def test_remesh_a_triangulated_sample_and_tile_it():
    mesh = Mesh.from_obj(compas.get("hypar.obj"))
    triangles = mesh.copy()
    triangles.quads_to_triangles()
    tile = tile_for(mesh, scale=0.4)
    quads = tpc.remesh(triangles, target_edge=(tile["length"] + tile["joint"]) / 2)
    assert all(len(quads.face_vertices(f)) == 4 for f in quads.faces())
    pattern = tpc.match(quads, time_limit=3)
    placed = tpc.tiles(quads, pattern, surface=triangles, **tile)
    assert placed.report["cutting"]["coverage"] > 0.95
