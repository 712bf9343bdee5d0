"""TilePattern on COMPAS meshes: ``Mesh`` in, ``Mesh`` and ``Box`` out.

COMPAS is imported here only, so the rest of the package works without it.
"""

from compas.datastructures import Mesh
from compas.geometry import Box, Frame

from . import core

__all__ = ["remesh", "match", "tiles", "boxes", "report"]


def _vertices_faces(mesh):
    vertices, faces = mesh.to_vertices_and_faces()
    return vertices, faces


def remesh(mesh, target_edge=0.145, **options):
    """Quadrangulate a COMPAS mesh (stage 1); see :func:`tilepattern.remesh`.

    Returns
    -------
    compas.datastructures.Mesh
        The quad mesh; face keys are 0..F-1 in the order the library returns them.
    """
    vertices, faces = core.remesh(*_vertices_faces(mesh), target_edge=target_edge, **options)
    return Mesh.from_vertices_and_faces(vertices.tolist(), faces.tolist())


def match(mesh, **options):
    """Match the faces of a COMPAS quad mesh into tiles (stage 2); see
    :func:`tilepattern.match`. Face indices refer to the mesh's faces in iteration order."""
    return core.match(*_vertices_faces(mesh), **options)


def tiles(mesh, pattern, surface=None, **options):
    """Place tiles on a COMPAS quad mesh (stage 3), optionally cut to the COMPAS mesh
    ``surface``; see :func:`tilepattern.tiles`."""
    reference = _vertices_faces(surface) if surface is not None else None
    return core.tiles(*_vertices_faces(mesh), pattern, surface=reference, **options)


def boxes(placed):
    """The tiles as COMPAS boxes.

    COMPAS frames sit at the box centre; TilePattern's sit at the centre of the bottom
    face, so each frame is moved half a thickness along its z axis.

    Parameters
    ----------
    placed : tilepattern.Tiles

    Returns
    -------
    list of compas.geometry.Box
        Named by cut-list label.
    """
    result = []
    for frame, size, label in zip(placed.frames, placed.sizes, placed.labels):
        origin, x, y, z = frame
        centre = origin + z * (size[2] / 2.0)
        box = Box(size[0], size[1], size[2], frame=Frame(centre.tolist(), x.tolist(), y.tolist()))
        box.name = label
        result.append(box)
    return result


def report(placed):
    """The tile report as a dict (the library's ``report.json``)."""
    return dict(placed.report)
