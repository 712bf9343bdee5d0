"""TilePattern for Python: laying patterns of standard rectangular tiles on free-form shells.

Wraps the TilePattern C library through ctypes. The three stages take ``(vertices, faces)``
like COMPAS's ``Mesh.to_vertices_and_faces()``::

    from tilepattern import remesh, match, tiles
    QV, QF = remesh(V, F, target_edge=0.145)         # triangles -> quads of 145 mm
    pattern = match(QV, QF, bond="staggered")        # quads -> pairs
    placed = tiles(QV, QF, pattern, surface=(V, F))  # pairs -> boxes cut to the surface

``tilepattern.compas`` works on COMPAS meshes and returns COMPAS boxes;
``tilepattern.rhino.export_3dm`` writes the tiles to a Rhino file.
"""

from ._native import TilePatternError, library_path
from .core import Pattern, Tiles, match, remesh, tiles

__all__ = ["TilePatternError", "Pattern", "Tiles", "remesh", "match", "tiles", "library_path", "version"]


def version():
    """The native library's version, e.g. ``"0.1.0"``."""
    from . import _native

    return _native.lib().tp_version().decode()
