"""The three stages on plain arrays: ``(vertices, faces)`` in, numpy arrays and small result
objects out, in the style of compas_cgal and compas_libigl."""

import ctypes
import json
from ctypes import c_double, c_int32, c_size_t, c_uint32
from dataclasses import dataclass, field

import numpy as np

from . import _native as nat
from ._native import TilePatternError

__all__ = ["Pattern", "Tiles", "mesh_arrays", "remesh", "match", "tiles"]


def _faces_arrays(faces):
    """Flat indices and sizes of ``faces`` (a list of index lists, or an ``(F, k)`` array)."""
    if isinstance(faces, np.ndarray) and faces.ndim == 2:
        rows = faces
        sizes = np.full(len(rows), rows.shape[1], dtype=np.int64)
        flat = np.asarray(rows, dtype=np.int64).reshape(-1)
    else:
        rows = [np.asarray(f, dtype=np.int64).reshape(-1) for f in faces]
        sizes = np.array([len(r) for r in rows], dtype=np.int64)
        flat = np.concatenate(rows) if rows else np.zeros(0, dtype=np.int64)
    if flat.size and (flat.min() < 0 or flat.max() > 0xFFFFFFFE):
        bad = int(np.flatnonzero((flat < 0) | (flat > 0xFFFFFFFE))[0])
        face = int(np.searchsorted(np.cumsum(sizes), bad, side="right"))
        raise TilePatternError(4, "face %d: vertex index %d is out of range" % (face, int(flat[bad])))
    return np.ascontiguousarray(flat, dtype=np.uint32), np.ascontiguousarray(sizes, dtype=np.uint32)


def _mesh(vertices, faces):
    """A native mesh from ``(vertices, faces)``, validated by the library."""
    v = np.ascontiguousarray(np.asarray(vertices, dtype=np.float64).reshape(-1, 3))
    indices, sizes = _faces_arrays(faces)
    out = nat.new_handle(nat._Mesh)
    nat.check(
        nat.lib().tp_mesh_new(
            v.ctypes.data_as(ctypes.POINTER(c_double)), len(v),
            indices.ctypes.data_as(ctypes.POINTER(c_uint32)), len(indices),
            sizes.ctypes.data_as(ctypes.POINTER(c_uint32)), len(sizes),
            ctypes.byref(out),
        )
    )
    return nat.MeshHandle(out)


def mesh_arrays(handle):
    """``(vertices (V, 3) float64, faces list of index arrays)`` of a native mesh."""
    counts = [c_size_t(), c_size_t(), c_size_t()]
    nat.check(nat.lib().tp_mesh_counts(handle.pointer, *[ctypes.byref(c) for c in counts]))
    nv, nf, ni = (c.value for c in counts)
    vertices = np.zeros((nv, 3), dtype=np.float64)
    indices = np.zeros(ni, dtype=np.uint32)
    sizes = np.zeros(nf, dtype=np.uint32)
    nat.check(nat.lib().tp_mesh_copy_vertices(handle.pointer, vertices.ctypes.data_as(ctypes.POINTER(c_double)), 3 * nv))
    nat.check(
        nat.lib().tp_mesh_copy_faces(
            handle.pointer, indices.ctypes.data_as(ctypes.POINTER(c_uint32)), ni, sizes.ctypes.data_as(ctypes.POINTER(c_uint32)), nf
        )
    )
    return vertices, np.split(indices.astype(np.int64), np.cumsum(sizes)[:-1]) if nf else []


class _Progress:
    """A Python callable as a native progress callback: ``progress(stage, fraction)``
    returning True cancels. Exceptions in it cancel the call and are raised after it."""

    STAGES = {nat.TP_STAGE_REMESH: "remesh", nat.TP_STAGE_PATTERN: "pattern"}

    def __init__(self, progress):
        self.progress = progress
        self.error = None
        self.callback = nat.PROGRESS(self._call) if progress else nat.PROGRESS()

    def _call(self, _user, stage, fraction):
        try:
            return 1 if self.progress(self.STAGES.get(stage, str(stage)), fraction) else 0
        except BaseException as error:  # noqa: BLE001 - re-raised after the native call
            self.error = error
            return 1

    def finish(self, status):
        if self.error is not None:
            raise self.error
        nat.check(status)


def remesh(vertices, faces, target_edge=0.145, direction=None, angle=None, shapeup=False, progress=None):
    """Quadrangulate a triangle (or polygon) surface into near-square quads (stage 1).

    Parameters
    ----------
    vertices : array_like (V, 3)
    faces : list of index lists or array_like (F, k)
    target_edge : float
        Quad edge in model units; ``(L + joint) / 2`` for tiles of length L.
    direction : array_like (3,), optional
        Align the quads with this direction instead of the principal curvature.
    angle : float, optional
        Rotate the curvature-aligned field by this many degrees.
    shapeup : bool
        Pull faces towards squares without leaving the surface.
    progress : callable, optional
        ``progress(stage, fraction)``; return True to cancel.

    Returns
    -------
    tuple
        ``(vertices (V, 3) float64, faces (F, 4) int64)`` of the quad mesh.

    Examples
    --------
    >>> import numpy as np
    >>> from tilepattern import remesh
    >>> x, y = np.meshgrid(np.linspace(0, 2, 21), np.linspace(0, 2, 21))
    >>> V = np.c_[x.ravel(), y.ravel(), 0.1 * x.ravel() * y.ravel()]
    >>> F = [[i + 21 * j, i + 1 + 21 * j, i + 1 + 21 * (j + 1)] for j in range(20) for i in range(20)]
    >>> F += [[i + 21 * j, i + 1 + 21 * (j + 1), i + 21 * (j + 1)] for j in range(20) for i in range(20)]
    >>> QV, QF = remesh(V, F, target_edge=0.25)
    >>> QF.shape[1]
    4
    """
    options = nat.init(nat.RemeshOptions, "tp_remesh_options_init")
    options.target_edge = target_edge
    if direction is not None:
        options.direction = nat.DIRECTIONS["vector"]
        options.direction_vector[:] = [float(c) for c in direction]
    elif angle is not None:
        options.direction = nat.DIRECTIONS["angle"]
        options.angle_degrees = angle
    options.shapeup = 1 if shapeup else 0
    with _mesh(vertices, faces) as surface:
        out = nat.new_handle(nat._Mesh)
        bridge = _Progress(progress)
        status = nat.lib().tp_remesh(surface.pointer, ctypes.byref(options), bridge.callback, None, ctypes.byref(out))
        bridge.finish(status)
        with nat.MeshHandle(out) as quads:
            qv, qf = mesh_arrays(quads)
    return qv, np.array(qf, dtype=np.int64).reshape(-1, 4)


@dataclass
class Pattern:
    """A matching of quads into tiles (stage 2).

    Attributes
    ----------
    pairs : ndarray (P, 2) int64
        Matched faces: each row becomes a full tile.
    unpaired : ndarray (U,) int64
        Quads left alone: each becomes a half tile.
    objective, bound, gap : float
        The objective, a proven upper bound on it, and their relative gap.
    status : str
        ``"optimal"`` (proven), ``"time_limit"`` or ``"feasible"``.
    """

    pairs: np.ndarray
    unpaired: np.ndarray
    faces: int
    excluded: int
    non_quad: int
    continuous_joints: int
    shifted_pairs: int
    objective: float
    bound: float
    gap: float
    status: str
    seconds: float
    _handle: nat.PatternHandle = field(repr=False, default=None)

    def close(self):
        """Releases the native pattern (also done when the object is collected)."""
        if self._handle is not None:
            self._handle.close()


def match(
    vertices,
    faces,
    bond="staggered",
    weight=0.5,
    time_limit=60.0,
    method="auto",
    formulation="strengthened",
    forced_pairs=(),
    excluded_faces=(),
    progress=None,
):
    """Match adjacent quads into tiles with the paper's integer programs (stage 2).

    Parameters
    ----------
    vertices, faces
        The quad mesh.
    bond : {"staggered", "stack", "running"}
        Eq. (2) staggered bond, eq. (1) maximum matching, eq. (3) running bond.
    weight : float
        Penalty per continuous joint (staggered) or reward per shifted pair (running).
    time_limit : float
        Wall-clock seconds; the result states whether it is proven optimal.
    forced_pairs : array_like (K, 2)
        Pairs of faces that must become tiles.
    excluded_faces : array_like (E,)
        Faces that take part in no tile.
    progress : callable, optional
        ``progress(stage, fraction)``; return True to cancel (raises ``TP_CANCELLED``).

    Returns
    -------
    Pattern

    Examples
    --------
    >>> from tilepattern import match
    >>> V = [[i, j, 0.0] for j in range(5) for i in range(5)]
    >>> F = [[i + 5 * j, i + 1 + 5 * j, i + 6 + 5 * j, i + 5 + 5 * j] for j in range(4) for i in range(4)]
    >>> p = match(V, F, time_limit=5)
    >>> len(p.pairs), p.status
    (8, 'optimal')
    """
    if bond not in nat.BONDS:
        raise TilePatternError(2, "bond %r: choose one of %s" % (bond, ", ".join(sorted(nat.BONDS))))
    options = nat.init(nat.PatternOptions, "tp_pattern_options_init")
    options.bond = nat.BONDS[bond]
    options.weight = weight
    options.time_limit_seconds = time_limit
    options.method = nat.METHODS[method]
    options.formulation = nat.FORMULATIONS[formulation]
    forced = np.ascontiguousarray(np.asarray(forced_pairs, dtype=np.int64).reshape(-1), dtype=np.uint32)
    excluded = np.ascontiguousarray(np.asarray(excluded_faces, dtype=np.int64).reshape(-1), dtype=np.uint32)
    options.forced_pairs = forced.ctypes.data_as(ctypes.POINTER(c_uint32))
    options.forced_pair_count = len(forced) // 2
    options.excluded_faces = excluded.ctypes.data_as(ctypes.POINTER(c_uint32))
    options.excluded_face_count = len(excluded)
    with _mesh(vertices, faces) as mesh:
        out = nat.new_handle(nat._Pattern)
        bridge = _Progress(progress)
        status = nat.lib().tp_pattern_solve(mesh.pointer, ctypes.byref(options), bridge.callback, None, ctypes.byref(out))
        bridge.finish(status)
    handle = nat.PatternHandle(out)
    summary = nat.PatternSummary()
    nat.check(nat.lib().tp_pattern_summary(handle.pointer, ctypes.byref(summary)))
    pairs = np.zeros(2 * summary.pairs, dtype=np.uint32)
    unpaired = np.zeros(summary.unpaired, dtype=np.uint32)
    nat.check(nat.lib().tp_pattern_copy_pairs(handle.pointer, pairs.ctypes.data_as(ctypes.POINTER(c_uint32)), len(pairs)))
    nat.check(nat.lib().tp_pattern_copy_unpaired(handle.pointer, unpaired.ctypes.data_as(ctypes.POINTER(c_uint32)), len(unpaired)))
    return Pattern(
        pairs=pairs.astype(np.int64).reshape(-1, 2),
        unpaired=unpaired.astype(np.int64),
        faces=summary.faces,
        excluded=summary.excluded,
        non_quad=summary.non_quad,
        continuous_joints=summary.continuous_joints,
        shifted_pairs=summary.shifted_pairs,
        objective=summary.objective,
        bound=summary.bound,
        gap=summary.gap,
        status=nat.SOLVE_STATUS.get(summary.status, str(summary.status)),
        seconds=summary.seconds,
        _handle=handle,
    )


@dataclass
class Tiles:
    """Placed tiles (stage 3).

    Attributes
    ----------
    kinds : list of str
        ``"full"``, ``"half"`` or ``"boundary"`` (cut to the surface's edge).
    corners : ndarray (N, 8, 3)
        Box corners: the bottom face counter-clockwise from (-x, -y), then the top face.
    frames : ndarray (N, 4, 3)
        Origin, length axis x, height axis y, thickness axis z. The box spans
        ``[-L/2, L/2] x [-W/2, W/2] x [0, T]`` in this frame (origin at the bottom face's
        centre, not the box centre).
    sizes : ndarray (N, 3)
        Length, width, thickness of each box.
    faces : ndarray (N, 2) int64
        Faces under each tile; -1 where there is none (half tiles, filler pieces).
    steps : ndarray (N,) int64
        Laying order, from 0.
    kept_fractions : ndarray (N,)
        Kept share of each tile's face (1 when uncut).
    outlines : list of list of ndarray (k, 2)
        For each tile, the loops of its kept part in its frame (empty when uncut).
    labels : list of str
        Cut-list labels: ``F``, ``H``, ``B1``, ...
    cut_list : list of dict
        Cut shapes with counts (``cutlist.json``).
    report : dict
        The report (``report.json``).
    """

    kinds: list
    corners: np.ndarray
    frames: np.ndarray
    sizes: np.ndarray
    faces: np.ndarray
    steps: np.ndarray
    kept_fractions: np.ndarray
    outlines: list
    labels: list
    cut_list: list
    report: dict

    def __len__(self):
        return len(self.kinds)


def _copy(function, handle, count, dtype, ctype):
    values = np.zeros(count, dtype=dtype)
    nat.check(function(handle.pointer, values.ctypes.data_as(ctypes.POINTER(ctype)), count))
    return values


def tiles(vertices, faces, pattern, length=0.28, width=0.14, thickness=0.015, joint=0.01, surface=None, cut_tolerance=None, min_kept_width=None, up=(0.0, 0.0, 1.0), support_band=None):
    """Place a box per matched pair and a half tile per unpaired quad (stage 3), cut to the
    boundary of ``surface`` and numbered in laying order.

    Parameters
    ----------
    vertices, faces
        The quad mesh the pattern was solved on.
    pattern : Pattern
        From :func:`match`.
    length, width, thickness, joint : float
        Tile size and mortar joint in model units.
    surface : tuple (vertices, faces), optional
        The input surface the quads were made from: tiles are cut to its boundary and the
        strip between the quads and its edge is filled (default: the quads' own boundary).
    cut_tolerance, min_kept_width, support_band : float, optional
        Cutting tolerance, sliver width and support band (default: derived from the tile).
    up : array_like (3,)
        Up direction for the laying order.

    Returns
    -------
    Tiles

    Examples
    --------
    >>> from tilepattern import match, tiles
    >>> V = [[0.145 * i, 0.145 * j, 0.0] for j in range(5) for i in range(5)]
    >>> F = [[i + 5 * j, i + 1 + 5 * j, i + 6 + 5 * j, i + 5 + 5 * j] for j in range(4) for i in range(4)]
    >>> t = tiles(V, F, match(V, F, time_limit=5))
    >>> len(t), t.kinds[0]
    (8, 'full')
    """
    if pattern._handle is None:
        raise TilePatternError(2, "pattern has no native handle: pass the result of match()")
    options = nat.init(nat.TileOptions, "tp_tile_options_init")
    options.length, options.width, options.thickness, options.joint = length, width, thickness, joint
    options.cut_tolerance = -1.0 if cut_tolerance is None else cut_tolerance
    options.min_kept_width = -1.0 if min_kept_width is None else min_kept_width
    options.support_band = -1.0 if support_band is None else support_band
    options.up[:] = [float(c) for c in up]
    with _mesh(vertices, faces) as quads:
        out = nat.new_handle(nat._Tiles)
        if surface is None:
            status = nat.lib().tp_tiles_build(quads.pointer, pattern._handle.pointer, ctypes.byref(options), ctypes.byref(out))
        else:
            with _mesh(*surface) as reference:
                status = nat.lib().tp_tiles_build_on_surface(
                    quads.pointer, pattern._handle.pointer, reference.pointer, ctypes.byref(options), ctypes.byref(out)
                )
        nat.check(status)
    with nat.TilesHandle(out) as handle:
        return _read_tiles(handle)


def _read_tiles(handle):
    lib = nat.lib()
    count = c_size_t()
    nat.check(lib.tp_tiles_count(handle.pointer, ctypes.byref(count)))
    n = count.value
    kinds = _copy(lib.tp_tiles_copy_kinds, handle, n, np.int32, c_int32)
    faces = _copy(lib.tp_tiles_copy_faces, handle, 2 * n, np.uint32, c_uint32).astype(np.int64).reshape(-1, 2)
    faces[faces == nat.NO_FACE] = -1
    loops, points = c_size_t(), c_size_t()
    nat.check(lib.tp_tiles_outline_counts(handle.pointer, ctypes.byref(loops), ctypes.byref(points)))
    loop_counts = _copy(lib.tp_tiles_copy_loop_counts, handle, n, np.uint32, c_uint32)
    loop_sizes = _copy(lib.tp_tiles_copy_loop_sizes, handle, loops.value, np.uint32, c_uint32)
    xy = _copy(lib.tp_tiles_copy_loop_points, handle, 2 * points.value, np.float64, c_double).reshape(-1, 2)
    loop_arrays = np.split(xy, np.cumsum(loop_sizes)[:-1]) if loops.value else []
    outlines, at = [], 0
    for c in loop_counts:
        outlines.append(loop_arrays[at : at + c])
        at += c
    return Tiles(
        kinds=[nat.TILE_KINDS.get(int(k), str(k)) for k in kinds],
        corners=_copy(lib.tp_tiles_copy_corners, handle, 24 * n, np.float64, c_double).reshape(-1, 8, 3),
        frames=_copy(lib.tp_tiles_copy_frames, handle, 12 * n, np.float64, c_double).reshape(-1, 4, 3),
        sizes=_copy(lib.tp_tiles_copy_sizes, handle, 3 * n, np.float64, c_double).reshape(-1, 3),
        faces=faces,
        steps=_copy(lib.tp_tiles_copy_steps, handle, n, np.uint32, c_uint32).astype(np.int64),
        kept_fractions=_copy(lib.tp_tiles_copy_kept_fractions, handle, n, np.float64, c_double),
        outlines=outlines,
        labels=nat.text(lib.tp_tiles_labels, handle.pointer).splitlines(),
        cut_list=json.loads(nat.text(lib.tp_tiles_cutlist_json, handle.pointer)),
        report=json.loads(nat.text(lib.tp_tiles_report_json, handle.pointer)),
    )
