"""TilePattern for Python: laying patterns of standard rectangular tiles on free-form shells.

A pure-Python (ctypes) wrapper of the TilePattern C library. The three stages take
``(vertices, faces)`` like COMPAS's ``Mesh.to_vertices_and_faces()`` and return numpy
arrays and small result objects::

    import tilepattern as tp

    QV, QF = tp.remesh(V, F, target_edge=0.145)            # triangles -> quads of 145 mm
    pattern = tp.match(QV, QF, bond="staggered")            # quads -> pairs (Pattern)
    placed = tp.tiles(QV, QF, pattern, surface=(V, F))      # pairs -> boxes (Tiles)
    placed.report["full_tiles"], placed.corners.shape      # (N, 8, 3)

    QV, QF, pattern, placed = tp.run(V, F, courses="level")   # all three on up to 5 quad meshes, best tiles kept
    V, F, _, _ = tp.weld(V, F)                              # a soup (numpy-stl) or patches joined, as the CLI reads files

:mod:`tilepattern.compas` works on COMPAS meshes and returns COMPAS boxes;
:func:`tilepattern.rhino.export_3dm` writes tiles to a Rhino file. Failures raise
:class:`TilePatternError` (one subclass per status code of the C library).

The native library is found through ``TILEPATTERN_LIB``, next to the package, or in
``target/release`` of a source checkout; see :func:`library_path`.
"""

from ._native import (
    ABI_VERSION,
    BufferTooSmallError,
    CancelledError,
    InvalidArgumentError,
    InvalidMeshError,
    InvalidPatternError,
    LibraryNotFoundError,
    NotAvailableError,
    NullPointerError,
    PanicError,
    SolverFailedError,
    TilePatternError,
    TimeLimitError,
    abi_version,
    library_path,
    version,
)
from .core import Pattern, RunResult, TilePatternWarning, Tiles, Welded, match, quad_edge, remesh, run, tiles, weld

__version__ = "0.1.0"

__all__ = [
    "remesh",
    "match",
    "tiles",
    "run",
    "quad_edge",
    "weld",
    "Welded",
    "Pattern",
    "Tiles",
    "RunResult",
    "TilePatternWarning",
    "TilePatternError",
    "NullPointerError",
    "InvalidArgumentError",
    "BufferTooSmallError",
    "InvalidMeshError",
    "InvalidPatternError",
    "SolverFailedError",
    "TimeLimitError",
    "CancelledError",
    "NotAvailableError",
    "PanicError",
    "LibraryNotFoundError",
    "library_path",
    "version",
    "abi_version",
    "ABI_VERSION",
]
