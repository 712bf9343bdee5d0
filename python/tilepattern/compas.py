"""TilePattern on COMPAS meshes: ``compas.datastructures.Mesh`` in, ``Mesh`` and
``compas.geometry.Box`` out.

COMPAS is imported when these functions are called, not when :mod:`tilepattern` is, so the
core package works without it.

Face indices in the results are COMPAS face keys: for a mesh whose keys are not
``0 .. F-1`` in order (after faces were deleted, say), pairs, unpaired faces and tile faces
are translated, and ``forced_pairs`` and ``excluded_faces`` are taken as face keys too.

Examples
--------
>>> import compas
>>> from compas.datastructures import Mesh
>>> import tilepattern.compas as tpc
>>> surface = Mesh.from_obj(compas.get("hypar.obj"))          # 64 quads, ~0.67 units each
>>> pattern = tpc.match(surface, time_limit=5)
>>> boxes = tpc.tiles(surface, pattern, length=1.2, width=0.6, thickness=0.05, joint=0.04)
>>> report = tpc.report(boxes)
>>> len(boxes), report["full_tiles"], report["cutting"]["filler_tiles"]
(44, 32, 12)
>>> boxes[0].name, round(boxes[0].xsize, 2)
('F', 1.2)

The fit stage moved the tiles so that the joints come close to the 0.04 joint (filler pieces
close the courses it left short of the edge and the tears where joints could not close);
``fit=False`` keeps the paper's placement:

>>> report["fit"]["status"], report["joints"]["p95_deviation"] < report["joints"]["before_fit"]["p95_deviation"]
('converged', True)
>>> placed = tpc.tiles(surface, pattern, fit=False, length=1.2, width=0.6, thickness=0.05, joint=0.04)
>>> len(placed), "fit" in tpc.report(placed)
(32, False)
"""

from __future__ import annotations

import dataclasses

import numpy as np

from . import core
from ._native import TP_INVALID_ARGUMENT, InvalidArgumentError

__all__ = ["remesh", "match", "tiles", "run", "boxes", "report", "TileBoxes", "RunResult", "mesh_vertices_faces", "box_from_frame"]


def _compas():
    try:
        from compas.datastructures import Mesh
        from compas.geometry import Box, Frame
    except ImportError as why:  # pragma: no cover - depends on the environment
        raise ImportError("tilepattern.compas needs COMPAS 2: pip install 'compas>=2'") from why
    return Mesh, Box, Frame


def mesh_vertices_faces(mesh):
    """The vertices, faces and face keys of a COMPAS mesh.

    Parameters
    ----------
    mesh : compas.datastructures.Mesh

    Returns
    -------
    vertices : list of list of float
    faces : list of list of int
        Vertex indices (positions in ``vertices``), any face sizes.
    face_keys : ndarray (F,) int64
        The COMPAS key of each face, in the order of ``faces``.
    """
    vertices, faces = mesh.to_vertices_and_faces()
    return vertices, faces, np.fromiter(mesh.faces(), dtype=np.int64, count=len(faces))


def _keys_are_positions(keys):
    return bool(np.array_equal(keys, np.arange(len(keys))))


def _positions(values, keys, what):
    """Face keys -> positions (as given when keys are positions)."""
    if values is None or _keys_are_positions(keys):
        return values
    index = {int(k): i for i, k in enumerate(keys)}
    a = np.asarray(values, dtype=np.int64)
    try:
        return np.vectorize(lambda k: index[int(k)], otypes=[np.int64])(a) if a.size else a
    except KeyError as missing:
        raise InvalidArgumentError(TP_INVALID_ARGUMENT, "%s: the mesh has no face %s" % (what, missing.args[0])) from None


def _keys(positions, keys):
    """Positions -> face keys; -1 stays -1."""
    if _keys_are_positions(keys):
        return positions
    positions = np.asarray(positions, dtype=np.int64)
    return np.where(positions >= 0, keys[np.clip(positions, 0, max(len(keys) - 1, 0))], -1)


def remesh(mesh, target_edge=0.145, **options):
    """Quadrangulate a COMPAS mesh (triangles or polygons) into near-square quads.

    Parameters
    ----------
    mesh : compas.datastructures.Mesh
        The surface.
    target_edge : float, optional
        Quad edge in model units: ``(L + joint) / 2`` for tiles of length ``L``.
    **options
        ``direction``, ``angle``, ``shapeup``, ``time_limit``, ``progress``, ``field``,
        ``field_weight``, ``guides``, ``guide_weight``, ``creases``, ``renormalisation``:
        see :func:`tilepattern.remesh`.

    Returns
    -------
    compas.datastructures.Mesh
        The quad mesh; its face keys are ``0 .. F-1``.

    Examples
    --------
    >>> import compas
    >>> from compas.datastructures import Mesh
    >>> import tilepattern.compas as tpc
    >>> surface = Mesh.from_obj(compas.get("hypar.obj"))
    >>> surface.quads_to_triangles()
    >>> quads = tpc.remesh(surface, target_edge=0.4)
    >>> all(len(quads.face_vertices(f)) == 4 for f in quads.faces())
    True
    """
    vertices, faces, _ = mesh_vertices_faces(mesh)
    return _quad_mesh(*core.remesh(vertices, faces, target_edge=target_edge, **options))


def _quad_mesh(vertices, faces):
    """A COMPAS mesh of the quads :func:`tilepattern.remesh` returns (face keys ``0 .. F-1``)."""
    Mesh, _, _ = _compas()
    return Mesh.from_vertices_and_faces(vertices.tolist(), faces.tolist() if isinstance(faces, np.ndarray) else faces)


def _zones(zones, keys):
    """``zones`` of :func:`match` by face position: a dict {face key: bond} spread over the
    faces (None for those it does not name); a sequence as given (in face order)."""
    if not isinstance(zones, dict):
        return zones
    index = {int(k): i for i, k in enumerate(keys)}
    spread = [None] * len(keys)
    for key, bond in zones.items():
        if int(key) not in index:
            raise InvalidArgumentError(TP_INVALID_ARGUMENT, "zones: the mesh has no face %s" % (key,))
        spread[index[int(key)]] = bond
    return spread


def match(mesh, forced_pairs=None, excluded_faces=None, zones=None, **options):
    """Match the faces of a COMPAS quad mesh into tiles.

    Parameters
    ----------
    mesh : compas.datastructures.Mesh
        The quad mesh.
    forced_pairs : list of [int, int], optional
        Pairs of face keys that must form a tile.
    excluded_faces : list of int, optional
        Face keys that take part in no tile.
    zones : dict or sequence, optional
        A bond per face: a dict ``{face key: bond}`` (faces it does not name take ``bond``)
        or one bond per face in ``mesh.faces()`` order; bonds as :func:`tilepattern.match`'s
        ``zones`` take them (names, ``TP_BOND_*`` codes, ``None``).
    **options
        ``bond``, ``weight``, ``time_limit``, ``method``, ``formulation``, ``courses``
        (``"free"`` or ``"level"``), ``up``, ``progress``: see :func:`tilepattern.match`.

    Returns
    -------
    tilepattern.Pattern
        ``pairs`` and ``unpaired`` hold face keys of ``mesh``.

    Examples
    --------
    >>> import compas
    >>> from compas.datastructures import Mesh
    >>> import tilepattern.compas as tpc
    >>> pattern = tpc.match(Mesh.from_obj(compas.get("hypar.obj")), bond="stack", time_limit=5)
    >>> pattern.pairs.shape, pattern.status
    ((32, 2), 'optimal')
    """
    vertices, faces, keys = mesh_vertices_faces(mesh)
    pattern = core.match(
        vertices,
        faces,
        forced_pairs=_positions(forced_pairs, keys, "forced_pairs"),
        excluded_faces=_positions(excluded_faces, keys, "excluded_faces"),
        zones=_zones(zones, keys),
        **options,
    )
    if _keys_are_positions(keys):
        return pattern
    return dataclasses.replace(pattern, pairs=np.sort(_keys(pattern.pairs, keys), axis=1), unpaired=_keys(pattern.unpaired, keys))


class TileBoxes(list):
    """The list of COMPAS boxes returned by :func:`tiles`, one per tile, in tile order.

    Attributes
    ----------
    tiles : tilepattern.Tiles
        Everything else about the tiles: kinds, frames, corners, faces (face keys), laying
        steps, outlines of cut tiles, labels, cut list, joint deviations.
    report : dict
        The tile report (``report.json``).
    """

    def __init__(self, boxes, tiles):
        super().__init__(boxes)
        self.tiles = tiles

    @property
    def report(self):
        return self.tiles.report


def box_from_frame(frame, size, name=None):
    """A COMPAS box from a TilePattern tile frame and size.

    TilePattern's frame sits at the centre of the box's bottom face (the box spans
    ``[-L/2, L/2] x [-W/2, W/2] x [0, T]``); a COMPAS box's frame sits at its centre, so
    the origin moves half the thickness along z. The axes stay.

    Parameters
    ----------
    frame : array_like (4, 3)
        Origin, x (length), y (width), z (thickness) axes.
    size : array_like (3,)
        Length, width, thickness.
    name : str, optional

    Returns
    -------
    compas.geometry.Box

    Examples
    --------
    >>> box = box_from_frame([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [0.28, 0.14, 0.015])
    >>> box.frame.point.z, box.zmin, box.zmax
    (0.0075, 0.0, 0.015)
    """
    _, Box, Frame = _compas()
    origin, x, y, z = (np.asarray(v, dtype=np.float64) for v in np.asarray(frame, dtype=np.float64))
    length, width, thickness = (float(s) for s in size)
    centre = origin + z * (thickness / 2.0)
    box = Box(length, width, thickness, frame=Frame(centre.tolist(), x.tolist(), y.tolist()))
    if name is not None:
        box.name = name
    return box


def boxes(placed):
    """The tiles of :func:`tilepattern.tiles` as COMPAS boxes, named by cut-list label.

    Parameters
    ----------
    placed : tilepattern.Tiles

    Returns
    -------
    TileBoxes
        A list of :class:`compas.geometry.Box`, with the tiles under ``.tiles``.
    """
    return TileBoxes(
        [box_from_frame(frame, size, label) for frame, size, label in zip(placed.frames, placed.sizes, placed.labels)],
        placed,
    )


def tiles(mesh, pattern, surface=None, **options):
    """Place tiles on a COMPAS quad mesh and return them as COMPAS boxes.

    Parameters
    ----------
    mesh : compas.datastructures.Mesh
        The quad mesh the pattern was solved on.
    pattern : tilepattern.Pattern
        From :func:`match` on this mesh.
    surface : compas.datastructures.Mesh, optional
        The surface the quads were made from: tiles are cut to its boundary.
    **options
        ``length``, ``width``, ``thickness``, ``joint``, ``cut_tolerance``,
        ``min_kept_width``, ``up``, ``support_band``, ``fit``, ``fit_time_limit``,
        ``overlap_tolerance``, ``bond_tolerance``, ``units_per_mm``, ``progress``,
        ``creases``: see :func:`tilepattern.tiles`.

    Returns
    -------
    TileBoxes
        A list of :class:`compas.geometry.Box` (frames at the box centres, named by
        cut-list label ``F``, ``H``, ``B1``..., ``C1``...), with ``.tiles`` (including
        ``joint_deviations``, parallel to the boxes) and ``.report``.

    Examples
    --------
    >>> import compas
    >>> from compas.datastructures import Mesh
    >>> import tilepattern.compas as tpc
    >>> quads = Mesh.from_obj(compas.get("hypar.obj"))
    >>> boxes = tpc.tiles(quads, tpc.match(quads, time_limit=5), length=1.2, width=0.6, thickness=0.05, joint=0.04)
    >>> boxes.tiles.kinds[:2].tolist(), boxes.report["half_tiles"]
    (['full', 'boundary'], 0)
    """
    vertices, faces, keys = mesh_vertices_faces(mesh)
    reference = None
    if surface is not None:
        sv, sf, _ = mesh_vertices_faces(surface)
        reference = (sv, sf)
    placed = core.tiles(vertices, faces, pattern, surface=reference, **options)
    if not _keys_are_positions(keys):
        placed = dataclasses.replace(placed, faces=_keys(placed.faces, keys))
    return boxes(placed)


@dataclasses.dataclass(eq=False)
class RunResult:
    """What :func:`run` keeps, on COMPAS: it unpacks as ``quads, pattern, boxes = run(mesh)``.

    Attributes
    ----------
    quads : compas.datastructures.Mesh
        The kept quad mesh; its face keys are ``0 .. F-1``.
    pattern : tilepattern.Pattern
        Its pattern; ``pairs`` and ``unpaired`` hold face keys of ``quads``.
    boxes : TileBoxes
        The tiles as COMPAS boxes, with ``.tiles`` and ``.report`` (which lists the tries
        and the one kept when more than one was made).
    """

    quads: object
    pattern: core.Pattern
    boxes: TileBoxes

    def __iter__(self):
        return iter((self.quads, self.pattern, self.boxes))

    @property
    def tiles(self):
        """The kept :class:`tilepattern.Tiles` (``boxes.tiles``)."""
        return self.boxes.tiles

    @property
    def report(self):
        """The kept tiles' report."""
        return self.boxes.report

    @property
    def tries(self):
        """Each try's figures (:attr:`tilepattern.Tiles.tries`)."""
        return self.tiles.tries

    @property
    def chosen_try(self):
        """Which try was kept (:attr:`tilepattern.Tiles.chosen_try`)."""
        return self.tiles.chosen_try

    def close(self):
        """Releases the pattern's native object."""
        self.pattern.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()


def run(mesh, zones=None, excluded_faces=None, **options):
    """Tile a COMPAS surface in one call, keeping the best of a few quad meshes.

    :func:`tilepattern.run` on a COMPAS mesh: remesh, match and tiles (fitted, cut to the
    surface), on up to six quad meshes (``tries``), the tiles that fit best kept.

    Parameters
    ----------
    mesh : compas.datastructures.Mesh
        The surface (triangles or polygons).
    zones : dict or sequence, optional
        A bond per face of ``mesh`` (the surface): a dict ``{face key: bond}`` (faces it does
        not name take ``bond``) or one bond per face in ``mesh.faces()`` order, bonds as
        :func:`match` takes them; each quad takes the zone of the surface face closest to it.
    excluded_faces : list of int, optional
        Face keys of ``mesh`` (the surface) to leave out: each quad whose closest surface
        face is one gets no tile, and its area is left out of the coverage.
    **options
        ``tries``, ``progress``, ``target_edge`` (default ``quad_edge`` of the tile and
        courses), ``remesh_time_limit``, ``time_limit`` (the pattern stage's), ``bond``,
        ``courses``, ``length``, ``width``, ``thickness``, ``joint``, ``fit``,
        ``units_per_mm``...: see :func:`tilepattern.run`. Lengths are in the mesh's units.

    Returns
    -------
    RunResult
        ``quads`` (a COMPAS quad mesh), ``pattern`` (:class:`tilepattern.Pattern`, face keys
        of ``quads``) and ``boxes`` (:class:`TileBoxes`, as :func:`tiles` returns them).

    Examples
    --------
    >>> import compas
    >>> from compas.datastructures import Mesh
    >>> import tilepattern.compas as tpc
    >>> surface = Mesh.from_obj(compas.get("hypar.obj"))
    >>> surface.quads_to_triangles()
    >>> result = tpc.run(surface, length=0.58, width=0.29, thickness=0.04, joint=0.02, courses="level", time_limit=10)
    >>> quads, pattern, boxes = result
    >>> all(len(quads.face_vertices(f)) == 4 for f in quads.faces()), len(result.tries), boxes[0].name
    (True, 6, 'F')
    """
    vertices, faces, keys = mesh_vertices_faces(mesh)
    result = core.run(
        vertices,
        faces,
        zones=_zones(zones, keys),
        excluded_faces=_positions(excluded_faces, keys, "excluded_faces"),
        **options,
    )
    return RunResult(_quad_mesh(result.vertices, result.faces), result.pattern, boxes(result.tiles))


def report(result):
    """The tile report as a dict.

    Parameters
    ----------
    result : TileBoxes, tilepattern.Tiles or a run's result
        What :func:`tiles`, :func:`tilepattern.tiles`, :func:`run` or
        :func:`tilepattern.run` returned.

    Returns
    -------
    dict
        ``faces``, ``full_tiles``, ``half_tiles``, ``boundary_tiles``, ``objective``,
        ``bound``, ``gap``, ``status``, ``tile``, ``joints`` (with ``before_fit``),
        ``fit``, ``cutting``, ``sequence``, ``seconds``... (``report.json`` of the command
        line).
    """
    placed = getattr(result, "tiles", result)
    if not isinstance(placed, core.Tiles):
        raise TypeError("report() takes what tiles() or run() returned, got %s" % type(result).__name__)
    return dict(placed.report)
