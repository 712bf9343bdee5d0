"""The three stages on plain arrays, in the style of compas_cgal and compas_libigl:
``(vertices, faces)`` in, numpy arrays and small result objects out; :func:`run` makes all
three in one call, on up to three quad meshes, keeping the tiles that fit best.

``vertices`` is anything ``numpy.asarray`` turns into a ``(V, 3)`` float array (a list of
``[x, y, z]``, COMPAS points, an array). ``faces`` is a list of vertex-index lists, which
may mix triangles, quads and n-gons (COMPAS's ``Mesh.to_vertices_and_faces()``), or an
``(F, k)`` integer array. Face and vertex indices are 0-based and keep their order, so the
face indices in results refer to the faces as given.
"""

from __future__ import annotations

import ctypes
import itertools
import json
import warnings
from dataclasses import dataclass, field
from typing import Callable, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native as nat
from ._native import InvalidArgumentError, InvalidMeshError

__all__ = [
    "Pattern",
    "Tiles",
    "RunResult",
    "remesh",
    "match",
    "tiles",
    "run",
    "mesh_handle",
    "mesh_arrays",
    "quad_edge",
    "BONDS",
    "METHODS",
    "FORMULATIONS",
    "COURSES",
]

#: ``bond`` names of :func:`match` and their ``TP_BOND_*`` codes.
BONDS = {
    "stack": nat.TP_BOND_STACK,
    "staggered": nat.TP_BOND_STAGGERED,
    "running": nat.TP_BOND_RUNNING,
    "running-bond": nat.TP_BOND_RUNNING,
    "herringbone": nat.TP_BOND_HERRINGBONE,
    "basket-weave": nat.TP_BOND_BASKET_WEAVE,
    "basket_weave": nat.TP_BOND_BASKET_WEAVE,
}
#: ``method`` names of :func:`match`.
METHODS = {"auto": nat.TP_METHOD_AUTO, "mip": nat.TP_METHOD_MIP}
#: ``formulation`` names of :func:`match`.
FORMULATIONS = {"strengthened": nat.TP_FORMULATION_STRENGTHENED, "paper": nat.TP_FORMULATION_PAPER}
#: ``courses`` names of :func:`match` and their ``TP_COURSES_*`` codes.
COURSES = {"free": nat.TP_COURSES_FREE, "level": nat.TP_COURSES_LEVEL}

Progress = Callable[[str, float], Optional[bool]]

# ---------------------------------------------------------------------------------------
# Meshes
# ---------------------------------------------------------------------------------------


def _vertex_array(vertices):
    try:
        v = np.asarray(vertices, dtype=np.float64, order="C")
    except (TypeError, ValueError) as why:
        raise InvalidMeshError(nat.TP_INVALID_MESH, "vertices are not an array of (x, y, z) numbers: %s" % why) from None
    if v.size == 0:
        return np.zeros((0, 3), dtype=np.float64)
    if v.ndim != 2 or v.shape[1] != 3:
        raise InvalidMeshError(nat.TP_INVALID_MESH, "vertices must have shape (V, 3), got %s" % (v.shape,))
    return np.ascontiguousarray(v)


def _integer_array(values, what):
    a = np.asarray(values)
    if a.size == 0:
        return np.zeros(a.shape, dtype=np.int64)
    if a.dtype.kind in "iu":
        return a.astype(np.int64, copy=False)
    if a.dtype.kind == "f" and np.all(np.isfinite(a)) and np.all(a == np.round(a)):
        return a.astype(np.int64)
    raise InvalidMeshError(nat.TP_INVALID_MESH, "%s must be integers, got %s" % (what, a.dtype))


def _uniform_faces(faces):
    """``faces`` as an ``(F, k)`` array when all faces have the same size (the fast path),
    else unchanged."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # numpy < 1.24 only warns about ragged lists
            array = np.asarray(faces)
    except (ValueError, TypeError, Warning):
        return faces
    return array if array.ndim == 2 and array.dtype.kind in "iuf" else faces


def face_arrays(faces):
    """Flat vertex indices and face sizes in the layout of ``tp_mesh_new``.

    Parameters
    ----------
    faces : list of list of int or array_like (F, k)
        Faces of any sizes (triangles, quads, n-gons may be mixed).

    Returns
    -------
    indices : ndarray (I,) uint32
        All faces' vertex indices, face after face.
    sizes : ndarray (F,) uint32
        Each face's number of vertices.

    Raises
    ------
    InvalidMeshError
        For indices that are not integers or are negative or beyond ``uint32``.

    Examples
    --------
    >>> indices, sizes = face_arrays([[0, 1, 2], [0, 2, 3, 4]])
    >>> indices.tolist(), sizes.tolist()
    ([0, 1, 2, 0, 2, 3, 4], [3, 4])
    """
    if not isinstance(faces, np.ndarray):
        faces = _uniform_faces(faces)
    if isinstance(faces, np.ndarray) and faces.ndim == 2:
        flat = _integer_array(faces, "face indices").reshape(-1)
        sizes = np.full(faces.shape[0], faces.shape[1], dtype=np.int64)
    else:
        rows = [face if hasattr(face, "__len__") else list(face) for face in faces]
        sizes = np.fromiter(map(len, rows), dtype=np.int64, count=len(rows))
        try:
            flat = np.fromiter(itertools.chain.from_iterable(rows), dtype=np.float64, count=int(sizes.sum()))
        except (TypeError, ValueError):
            flat = np.concatenate([np.asarray(row).reshape(-1) for row in rows]) if rows else np.zeros(0)
        flat = _integer_array(flat, "face indices")
    bad = np.flatnonzero((flat < 0) | (flat > 0xFFFFFFFE))
    if bad.size:
        face = int(np.searchsorted(np.cumsum(sizes), bad[0], side="right"))
        raise InvalidMeshError(nat.TP_INVALID_MESH, "face %d refers to vertex %d, which is out of range" % (face, flat[bad[0]]))
    return np.asarray(flat, dtype=np.uint32, order="C"), np.asarray(sizes, dtype=np.uint32, order="C")


def mesh_handle(vertices, faces):
    """A validated native mesh from ``(vertices, faces)``.

    Parameters
    ----------
    vertices : array_like (V, 3)
    faces : list of list of int or array_like (F, k)

    Returns
    -------
    tilepattern._native.MeshHandle
        Close it (or use it in a ``with`` block) when done.

    Raises
    ------
    InvalidMeshError
        NaN or infinite coordinates, bad indices, non-manifold edges, an empty mesh.

    Examples
    --------
    >>> with mesh_handle([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]]) as mesh:
    ...     mesh.counts()
    (4, 1, 4)
    """
    v = _vertex_array(vertices)
    indices, sizes = face_arrays(faces)
    return nat.MeshHandle.new(v, indices, sizes)


class Welded(NamedTuple):
    """A mesh as :func:`weld` makes it, with where its vertices and faces came from.

    Attributes
    ----------
    vertices : ndarray (V, 3) float64
    faces : ndarray (F, k) int64 or list of list of int
    vertex_source : ndarray (V,) int64
        Each vertex's first given vertex: ``field[vertex_source]`` carries a field given per
        vertex over.
    face_source : ndarray (F,) int64
        Each face's given face (triangles split where cracks were zipped keep their face's):
        ``zones[face_source]`` carries data given per face over; a given face in no entry
        was removed (collapsed, or a repeat).
    """

    vertices: np.ndarray
    faces: Union[np.ndarray, List[List[int]]]
    vertex_source: np.ndarray
    face_source: np.ndarray


def weld(vertices, faces, tolerance: float = 1e-6) -> Welded:
    """A mesh as the command line reads a file: vertices closer than ``tolerance`` times the
    mesh's size (its used vertices' bounding-box diagonal) joined, the faces this collapses
    or repeats removed, the cracks of a triangle mesh zipped where patches meshed apart meet,
    and faces turned to agree with their neighbours (``tp_mesh_new_welded``).

    For a triangle soup (an STL read with numpy-stl, every triangle with its own corners), a
    polysurface meshed face by face, or patches joined without welding, which the stages take
    as pieces (a soup is refused by :func:`remesh` and :func:`run`).

    Parameters
    ----------
    vertices : array_like (V, 3)
    faces : list of list of int or array_like (F, k)
    tolerance : float
        Share of the mesh's size within which vertices are joined: 0 joins none (faces are
        still turned), the command line's default 1e-6.

    Returns
    -------
    Welded
        ``vertices``, ``faces``, ``vertex_source`` and ``face_source`` (how many vertices were
        joined and faces removed follows from them; the library reports no other summary).

    Raises
    ------
    InvalidArgumentError
        A tolerance that is not a number from 0 up to below 1.
    InvalidMeshError
        A mesh that is still not valid once welded (faces and vertices named as given).

    Examples
    --------
    >>> soup = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 0, 0], [1, 1, 0], [0, 1, 0]]
    >>> welded = weld(soup, [[0, 1, 2], [3, 4, 5]])
    >>> len(welded.vertices), welded.faces.tolist(), welded.vertex_source.tolist()
    (4, [[0, 1, 2], [0, 2, 3]], [0, 1, 2, 5])
    """
    v = _vertex_array(vertices)
    indices, sizes = face_arrays(faces)
    with nat.MeshHandle.new_welded(v, indices, sizes, float(tolerance)) as handle:
        out_vertices, out_faces = mesh_arrays(handle)
        vertex_source, face_source = handle.sources()
    return Welded(out_vertices, out_faces, vertex_source, face_source)


def _faces_out(indices, sizes):
    """An ``(F, k)`` int64 array when all faces have k vertices, else a list of lists."""
    if len(sizes) == 0:
        return np.zeros((0, 4), dtype=np.int64)
    if np.all(sizes == sizes[0]):
        return indices.astype(np.int64).reshape(-1, int(sizes[0]))
    ends = np.cumsum(sizes, dtype=np.int64)
    flat = indices.tolist()
    return [flat[e - s : e] for s, e in zip(sizes.tolist(), ends.tolist())]


def mesh_arrays(handle):
    """``(vertices, faces)`` of a native mesh.

    Returns
    -------
    vertices : ndarray (V, 3) float64
    faces : ndarray (F, k) int64 or list of list of int
        An array when all faces have the same size, else a list of lists.
    """
    vertices, indices, sizes = handle.arrays()
    return vertices, _faces_out(indices, sizes)


# ---------------------------------------------------------------------------------------
# Stage 1: remesh
# ---------------------------------------------------------------------------------------


def remesh(
    vertices,
    faces,
    target_edge: float = 0.145,
    direction: Union[Sequence[float], str, None] = None,
    angle: Optional[float] = None,
    shapeup: bool = False,
    time_limit: float = 60.0,
    progress: Optional[Progress] = None,
    field=None,
    field_weight: float = 1.0,
    guides=None,
    guide_weight: float = 1.0,
    creases: bool = True,
    renormalisation: float = 0.5,
) -> Tuple[np.ndarray, np.ndarray]:
    """Quadrangulate a surface into near-square quads (stage 1).

    The quads follow the principal curvature (the paper's choice), a direction projected
    onto the surface, the curvature field rotated by an angle, or the designer's own field
    (``field``, e.g. principal stress or thrust directions) blended with it; near guide
    curves (``guides``) they follow the curves.

    Parameters
    ----------
    vertices : array_like (V, 3)
        The surface's vertices.
    faces : list of list of int or array_like (F, k)
        Its faces: triangles, quads or n-gons, mixed if need be.
    target_edge : float, optional
        Quad edge in model units; ``(L + joint) / 2`` for tiles of length ``L``.
        Default 0.145, i.e. 280 mm tiles and 10 mm joints in metres.
    direction : array_like (3,) or "smooth", optional
        Align the quads with this direction (projected onto the surface); ``"smooth"``
        follows neither the curvature nor a direction: the boundary and smoothness alone
        orient the quads (:func:`run`'s second try), which ends fewer rows where the
        curvature lines converge (a cone, a funnel, a bend).
    angle : float, optional
        Rotate the curvature-aligned field by this many degrees.
    shapeup : bool, optional
        Pull the faces towards squares without leaving the surface.
    time_limit : float, optional
        Wall-clock seconds for the stage (default 60): when they pass, the quad mesh as it
        stands is returned if there is one, else :class:`~tilepattern.TimeLimitError`.
    progress : callable, optional
        ``progress(stage, fraction)`` with ``stage == "remesh"``, called about every 10 ms;
        return True to cancel (:class:`~tilepattern.CancelledError`).
    field : array_like (V, 3) or (F, 3), optional
        The designer's direction field: one vector per vertex or one per face of the surface
        (told apart by the count), a numpy array or a sequence of 3-sequences. Signs and
        lengths do not matter; NaN, infinite or zero vectors are refused with their index.
    field_weight : float, optional
        Share of ``field`` against the curvature field (or ``direction`` / ``angle``),
        from 0 to 1 (default 1: the field alone).
    guides : sequence of array_like (n, 3), optional
        Guide curves the quad rows follow near them (within 2 target edges, falling off):
        polylines in model units, each a numpy array or a sequence of at least 2 xyz points,
        on or near the surface. Curves with too few points, NaN or infinite coordinates, no
        length or nowhere near the surface are refused with their index.
    guide_weight : float, optional
        Share of ``guides`` on the curves against every other source (curvature,
        ``direction``, ``field``), from 0 to 1 (default 1: the guides alone on them).
    creases : bool, optional
        Give each sheet between the creases that part the surface (a groin vault's webs,
        split where the faces turn sharply) quads of its own, their field never aligned to
        the crease (default True); False runs one field over the whole surface. Pass the
        same to :func:`tiles`.
    renormalisation : float, optional
        Strength of the field's renormalising steps, which place its cones and with them
        where rows end (any number from 0, default 0.5). Other strengths give other, equally
        valid quads whose tiles may fit better: the command line's ``run`` tries 0.5, 1 and
        0.25 (and a smooth field) and keeps the tiles with the fewest cuts and the closest joints; do the same by
        calling :func:`remesh`, :func:`match` and :func:`tiles` for each and comparing the
        reports.

    Returns
    -------
    vertices : ndarray (V, 3) float64
        The quad mesh's vertices.
    faces : ndarray (F, 4) int64
        Its faces (a list of lists in the unlikely case that not all are quads).

    Raises
    ------
    TilePatternError
        ``InvalidMeshError`` for a bad surface, ``InvalidArgumentError`` for bad options,
        ``CancelledError``, ``TimeLimitError``.

    Examples
    --------
    A gently curved 2 x 2 square of 800 triangles, remeshed into quads of edge 0.25:

    >>> import numpy as np
    >>> from tilepattern import remesh
    >>> n = 21
    >>> x, y = np.meshgrid(np.linspace(0, 2, n), np.linspace(0, 2, n))
    >>> V = np.c_[x.ravel(), y.ravel(), 0.1 * x.ravel() * y.ravel()]
    >>> at = lambda i, j: i + n * j
    >>> F = [[at(i, j), at(i + 1, j), at(i + 1, j + 1)] for j in range(n - 1) for i in range(n - 1)]
    >>> F += [[at(i, j), at(i + 1, j + 1), at(i, j + 1)] for j in range(n - 1) for i in range(n - 1)]
    >>> QV, QF = remesh(V, F, target_edge=0.25)
    >>> QF.shape[1], 40 < len(QF) < 90
    (4, True)
    """
    # `keep`: the arrays the options point into, referenced until the native call returns.
    options, keep = _remesh_options(
        target_edge, direction, angle, shapeup, time_limit, field, field_weight, guides, guide_weight, creases, renormalisation
    )
    with mesh_handle(vertices, faces) as surface:
        with surface.remesh(options, progress) as quads:
            return mesh_arrays(quads)


def _remesh_options(target_edge, direction, angle, shapeup, time_limit, field, field_weight, guides, guide_weight, creases, renormalisation):
    """The ``TpRemeshOptions`` of :func:`remesh` (and :func:`run`) from its arguments, and the
    arrays they point into: keep those referenced until the native call returns."""
    if direction is not None and angle is not None:
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "give either direction or angle, not both")
    options = nat.remesh_options()
    options.target_edge = float(target_edge)
    if isinstance(direction, str):
        if direction != "smooth":
            raise InvalidArgumentError(
                nat.TP_INVALID_ARGUMENT, "direction must be 3 numbers or \"smooth\", got %r" % (direction,)
            )
        options.direction = nat.TP_DIRECTION_SMOOTH
    elif direction is not None:
        d = np.asarray(direction, dtype=np.float64).reshape(-1)
        if d.shape != (3,):
            raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "direction must be 3 numbers, got %r" % (direction,))
        options.direction = nat.TP_DIRECTION_VECTOR
        options.direction_vector[:] = d.tolist()
    elif angle is not None:
        options.direction = nat.TP_DIRECTION_ANGLE
        options.angle_degrees = float(angle)
    options.shapeup = 1 if shapeup else 0
    options.creases = 1 if creases else 0
    options.renormalisation = float(renormalisation)
    options.time_limit_seconds = float(time_limit)
    keep = None
    if field is not None:
        try:
            keep = np.ascontiguousarray(np.asarray(field, dtype=np.float64))
        except (TypeError, ValueError) as error:
            raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "field must be an (n, 3) array of numbers: %s" % error)
        if keep.ndim != 2 or keep.shape[1] != 3 or len(keep) == 0:
            raise InvalidArgumentError(
                nat.TP_INVALID_ARGUMENT,
                "field must be an (n, 3) array, one vector per vertex or per face; got shape %r" % (keep.shape,),
            )
        options.field_vectors = keep.ctypes.data_as(ctypes.POINTER(ctypes.c_double))
        options.field_count = len(keep)
    options.field_weight = float(field_weight)
    keep_guides = None
    if guides is not None:
        keep_guides = _guides_in(guides)
        points, sizes = keep_guides
        options.guide_points = points.ctypes.data_as(ctypes.POINTER(ctypes.c_double))
        options.guide_point_count = len(points)
        options.guide_curve_sizes = sizes.ctypes.data_as(ctypes.POINTER(ctypes.c_uint32))
        options.guide_count = len(sizes)
    options.guide_weight = float(guide_weight)
    return options, (keep, keep_guides)


def _guides_in(guides) -> Tuple[np.ndarray, np.ndarray]:
    """Guide polylines as one contiguous (n, 3) float64 array of all their points and the
    uint32 point count of each curve."""
    if isinstance(guides, np.ndarray) and guides.ndim == 2:
        raise InvalidArgumentError(
            nat.TP_INVALID_ARGUMENT, "guides must be a list of polylines (each an (n, 3) array); got one (n, 3) array: wrap it in a list"
        )
    curves = []
    for k, curve in enumerate(guides):
        try:
            points = np.asarray(curve, dtype=np.float64)
        except (TypeError, ValueError) as error:
            raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "guide curve %d must be an (n, 3) array of numbers: %s" % (k, error))
        if points.ndim != 2 or points.shape[1] != 3:
            raise InvalidArgumentError(
                nat.TP_INVALID_ARGUMENT, "guide curve %d must be an (n, 3) array of xyz points; got shape %r" % (k, points.shape)
            )
        curves.append(points)
    sizes = np.ascontiguousarray([len(c) for c in curves], dtype=np.uint32)
    points = np.ascontiguousarray(np.concatenate(curves) if curves else np.zeros((0, 3)), dtype=np.float64)
    return points, sizes


# ---------------------------------------------------------------------------------------
# Stage 2: match
# ---------------------------------------------------------------------------------------


@dataclass(eq=False)
class Pattern:
    """A matching of quads into tiles: the result of :func:`match`.

    It keeps the native pattern that :func:`tiles` needs; ``close()`` (or a ``with``
    block) releases it early, garbage collection does otherwise.

    Attributes
    ----------
    pairs : ndarray (P, 2) int64
        Matched faces ``[a, b]``, ``a < b``, sorted: each pair becomes a full tile.
    unpaired : ndarray (U,) int64
        Quads in no pair: each becomes a half tile, which needs a cut.
    faces : int
        Faces of the mesh.
    excluded : int
        Faces excluded with ``excluded_faces``.
    non_quad : int
        Faces that are not quads (never paired, no tile).
    continuous_joints : int
        Continuous joints in the pattern (the paper's eq. 2, y).
    shifted_pairs : int
        Tiles side by side shifted by one face (eq. 3, z).
    objective : float
        Objective of this pattern.
    bound : float
        Proven upper bound on the objective.
    gap : float
        ``(bound - objective) / max(bound, 1)``.
    status : str
        ``"optimal"`` only when proven; ``"time_limit"`` when the limit stopped the
        search with a gap; ``"feasible"`` when it ended with a gap for another reason.
    seconds : float
        Wall-clock time of the solve.
    status_code : int
        ``TP_SOLVE_*``.
    bound_source : str
        Which argument proved ``bound`` (with an optimal status: which closed the gap):
        ``"matching"`` (a maximum matching), ``"patches"`` (a decomposition's patch
        relaxations, linear or integer), ``"whole_program"`` (branch and bound on the whole program)
        or ``"linear_relaxation"`` (the whole program's linear relaxation, from its row prices).
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
    status_code: int = 0
    bound_source: str = "matching"
    handle: Optional[nat.PatternHandle] = field(default=None, repr=False)

    @property
    def optimal(self) -> bool:
        """True when the pattern is proven optimal."""
        return self.status_code == nat.TP_SOLVE_OPTIMAL

    @property
    def counts(self) -> dict:
        """The face and tile counts as a dict."""
        return {
            "faces": self.faces,
            "pairs": len(self.pairs),
            "unpaired": len(self.unpaired),
            "excluded": self.excluded,
            "non_quad": self.non_quad,
            "continuous_joints": self.continuous_joints,
            "shifted_pairs": self.shifted_pairs,
        }

    def to_dict(self) -> dict:
        """The pattern as plain data, with the field names of ``tilepattern match --json``."""
        return dict(
            self.counts,
            pairs=self.pairs.tolist(),
            unpaired=self.unpaired.tolist(),
            objective=self.objective,
            bound=self.bound,
            gap=self.gap,
            status=self.status,
            bound_source=self.bound_source,
            seconds=self.seconds,
        )

    @property
    def closed(self) -> bool:
        """True once the native pattern was released (it can no longer make tiles)."""
        return self.handle is None or self.handle.closed

    def close(self):
        """Releases the native pattern; the arrays stay. Safe to call more than once."""
        if self.handle is not None:
            self.handle.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    @classmethod
    def _from_handle(cls, handle):
        s = handle.summary()
        return cls(
            pairs=handle.pairs(s.pairs).astype(np.int64),
            unpaired=handle.unpaired(s.unpaired).astype(np.int64),
            faces=int(s.faces),
            excluded=int(s.excluded),
            non_quad=int(s.non_quad),
            continuous_joints=int(s.continuous_joints),
            shifted_pairs=int(s.shifted_pairs),
            objective=float(s.objective),
            bound=float(s.bound),
            gap=float(s.gap),
            status=nat.SOLVE_STATUS_NAMES.get(s.status, str(s.status)),
            seconds=float(s.seconds),
            status_code=int(s.status),
            bound_source=nat.BOUND_SOURCE_NAMES.get(handle.bound_source(), "unknown"),
            handle=handle,
        )


def _choice(value, choices, what):
    if isinstance(value, str) and value in choices:
        return choices[value]
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        return int(value)  # a TP_* code: the library checks its range
    raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "%s %r: choose one of %s" % (what, value, ", ".join(repr(c) for c in choices)))


def _three(values, what):
    """Three floats from an (x, y, z) sequence (``InvalidArgumentError`` otherwise)."""
    try:
        a = np.asarray(values, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        a = None
    if a is None or a.shape != (3,):
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "%s must be 3 numbers, got %r" % (what, values))
    return a.tolist()


def _index_array(values, what, shape_last=None):
    if values is None:
        return np.zeros(0, dtype=np.uint32)
    try:
        a = _integer_array(values, what)
    except InvalidMeshError as why:
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, why.message) from None
    if shape_last is not None and a.size and a.shape[-1] != shape_last:
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "%s must be pairs of face indices, got shape %s" % (what, a.shape))
    a = a.reshape(-1)
    if a.size and (a.min() < 0 or a.max() > 0xFFFFFFFF):
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "%s: face %d is out of range" % (what, a[(a < 0) | (a > 0xFFFFFFFF)][0]))
    return np.asarray(a, dtype=np.uint32, order="C")


def _zone_codes(zones):
    """``zones`` of :func:`match` as ``TP_BOND_*`` codes (-1 for the options' bond), or None."""
    if zones is None:
        return None
    if isinstance(zones, (str, bytes)):
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "zones must be one bond per face (a sequence), not the string %r" % (zones,))
    items = np.asarray(zones, dtype=object) if not isinstance(zones, np.ndarray) else zones
    if items.ndim != 1 or items.size == 0:
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "zones must be one bond per face (or None for none), got shape %s" % (items.shape,))
    if items.dtype.kind in "iu":
        if items.size and (items.min() < -(2**31) or items.max() >= 2**31):
            raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "zones: a code is out of range; give TP_BOND_* codes or -1")
        return np.ascontiguousarray(items, dtype=np.int32)
    codes = np.empty(items.size, dtype=np.int32)
    for face, zone in enumerate(items.tolist()):
        if zone is None:
            codes[face] = nat.TP_ZONE_DEFAULT
        elif isinstance(zone, str) and zone in BONDS:
            codes[face] = BONDS[zone]
        elif isinstance(zone, (int, np.integer)) and not isinstance(zone, bool) and -(2**31) <= zone < 2**31:
            codes[face] = int(zone)  # a TP_BOND_* code: the library checks it
        else:
            raise InvalidArgumentError(
                nat.TP_INVALID_ARGUMENT,
                "zones[%d] is %r: give a bond (%s), a TP_BOND_* code, or None for bond" % (face, zone, ", ".join(repr(c) for c in BONDS)),
            )
    return codes


def match(
    vertices,
    faces,
    bond: str = "staggered",
    weight: float = 0.5,
    time_limit: float = 60.0,
    method: str = "auto",
    formulation: str = "strengthened",
    forced_pairs=None,
    excluded_faces=None,
    progress: Optional[Progress] = None,
    courses: str = "free",
    up: Sequence[float] = (0.0, 0.0, 1.0),
    gap: float = 0.0,
    zones=None,
) -> Pattern:
    """Match adjacent quads into tiles with the paper's integer programs (stage 2).

    Parameters
    ----------
    vertices : array_like (V, 3)
        Vertices of the quad mesh.
    faces : list of list of int or array_like (F, k)
        Its faces; faces that are not quads take part in no tile.
    bond : {"staggered", "stack", "running", "herringbone", "basket-weave"}, optional
        ``"staggered"`` (eq. 2, default): as many tiles as possible with few continuous
        joints; ``"stack"`` (eq. 1): maximum matching; ``"running"`` (eq. 3): running bond;
        ``"herringbone"``: the 90-degree zig-zag; ``"basket-weave"`` (or
        ``"basket_weave"``): 2 x 2 squares of parallel tiles, alternating. The last two lay
        tiles both ways and need ``courses="free"``.
    weight : float, optional
        Penalty per continuous joint (staggered), reward per shifted pair (running),
        penalty per continuous joint or end-to-end pair (herringbone), penalty per
        shifted, end-to-end or one-course-apart pair (basket weave); default 0.5.
    time_limit : float, optional
        Wall-clock seconds (default 60); 0 returns the greedy start at once. A solve
        stopped by the limit still returns a valid pattern with ``status="time_limit"``.
    method : {"auto", "mip"}, optional
        ``"auto"``: whole program on CBC up to 600 faces, a decomposition above;
        ``"mip"``: the paper's whole program.
    formulation : {"strengthened", "paper"}, optional
        ``"strengthened"`` adds valid rows to eq. 2 (same optimum, proven sooner).
    forced_pairs : array_like (K, 2) of int, optional
        Pairs of adjacent faces that must form a tile.
    excluded_faces : array_like (E,) of int, optional
        Faces that take part in no tile (openings, areas laid by hand).
    progress : callable, optional
        ``progress(stage, fraction)`` with ``stage == "pattern"`` and the share of the time
        limit used; return True to cancel (:class:`~tilepattern.CancelledError`). An
        exception raised in it cancels the solve and is raised again by ``match``.
    courses : {"free", "level"}, optional
        ``"free"`` (default, the paper's model): tiles may lie either way across any quad;
        ``"level"``: every tile runs along level courses (horizontal with respect to
        ``up``), which the fit stage of :func:`tiles` can close far better. Remesh for
        level courses with :func:`quad_edge` ``(..., courses="level")``.
    up : array_like (3,), optional
        Up direction of level courses; default ``(0, 0, 1)``.
    gap : float, optional
        Relative gap at which the search stops, like a MIP solver's: once
        ``(bound - objective) / bound`` is at most this (from 0 to 1). Default 0: prove
        optimality or reach the time limit. A solve stopped by the gap has
        ``status="feasible"`` (or ``"optimal"`` when proven).
    zones : sequence (F,) of str, int or None, optional
        Zones: a bond per face, in face order (e.g. a band of ``"herringbone"`` in a
        staggered vault): a ``bond`` name, a ``TP_BOND_*`` code, or ``None`` (or -1) for
        ``bond``; every zone at ``weight``. A list or a numpy array (of integer codes, or of
        objects). A herringbone or basket-weave zone needs ``courses="free"``. Default
        ``None``: every face in ``bond``.

    Returns
    -------
    Pattern
        Pairs, unpaired quads, objective, bound, gap and status.

    Raises
    ------
    TilePatternError
        ``InvalidMeshError``, ``InvalidArgumentError`` (a weight, a time limit, a face in
        the options), ``SolverFailedError``, ``CancelledError``.

    Examples
    --------
    A 4 x 4 grid of quads takes 8 tiles:

    >>> from tilepattern import match
    >>> V = [[i, j, 0.0] for j in range(5) for i in range(5)]
    >>> F = [[i + 5 * j, i + 1 + 5 * j, i + 6 + 5 * j, i + 5 + 5 * j] for j in range(4) for i in range(4)]
    >>> pattern = match(V, F, time_limit=5)
    >>> len(pattern.pairs), len(pattern.unpaired), pattern.status
    (8, 0, 'optimal')

    Keep face 0 out of the tiles and force faces 1 and 2 into one:

    >>> pattern = match(V, F, bond="stack", excluded_faces=[0], forced_pairs=[[1, 2]], time_limit=5)
    >>> pattern.excluded, [1, 2] in pattern.pairs.tolist()
    (1, True)

    A herringbone band (the two middle rows) in a staggered field:

    >>> zones = ["herringbone" if 4 <= face < 12 else None for face in range(16)]
    >>> pattern = match(V, F, zones=zones, time_limit=5)
    >>> len(pattern.pairs) > 0
    True

    In level courses every tile runs along x here (faces ``f`` and ``f + 1``):

    >>> pattern = match(V, F, courses="level", up=(0, 1, 0), time_limit=5)
    >>> all(b == a + 1 for a, b in pattern.pairs.tolist())
    True
    """
    # `keep`: the arrays the options point into, referenced until the native call returns.
    options, keep = _pattern_options(bond, weight, time_limit, method, formulation, forced_pairs, excluded_faces, courses, up, gap, zones)
    with mesh_handle(vertices, faces) as mesh:
        handle = mesh.solve(options, progress)
    return _pattern_from(handle)


def _pattern_options(bond, weight, time_limit, method, formulation, forced_pairs, excluded_faces, courses, up, gap, zones):
    """The ``TpPatternOptions`` of :func:`match` (and :func:`run`) from its arguments, and the
    arrays they point into: keep those referenced until the native call returns."""
    options = nat.pattern_options()
    options.bond = _choice(bond, BONDS, "bond")
    options.method = _choice(method, METHODS, "method")
    options.formulation = _choice(formulation, FORMULATIONS, "formulation")
    options.courses = _choice(courses, COURSES, "courses")
    options.up[:] = _three(up, "up")
    options.weight = float(weight)
    options.time_limit_seconds = float(time_limit)
    options.gap = float(gap)
    forced = _index_array(forced_pairs, "forced_pairs", shape_last=2)
    if forced.size % 2:
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "forced_pairs must be pairs of face indices")
    excluded = _index_array(excluded_faces, "excluded_faces")
    zone_codes = _zone_codes(zones)
    options.forced_pairs = nat.as_pointer(forced, nat.c_uint32)
    options.forced_pair_count = forced.size // 2
    options.excluded_faces = nat.as_pointer(excluded, nat.c_uint32)
    options.excluded_face_count = excluded.size
    options.zones = nat.as_pointer(zone_codes, nat.c_int32)
    options.zone_count = 0 if zone_codes is None else zone_codes.size
    return options, (forced, excluded, zone_codes)


def _pattern_from(handle) -> Pattern:
    """A :class:`Pattern` owning ``handle`` (closed if reading it fails)."""
    try:
        return Pattern._from_handle(handle)
    except BaseException:
        handle.close()
        raise


# ---------------------------------------------------------------------------------------
# Stage 3: tiles
# ---------------------------------------------------------------------------------------


@dataclass(eq=False)
class Tiles:
    """Placed tiles: the result of :func:`tiles`. All arrays have one row per tile.

    Tiles are full tiles in pair order, then half tiles in face order, then filler pieces
    on no quad (where the quad mesh, or a course the fit left short, ends before the
    surface's edge; counted in ``report["cutting"]["filler_tiles"]``, not in
    ``full_tiles`` or ``half_tiles``); tiles dropped as slivers or outside the surface are
    left out. ``steps`` is their laying order.

    Attributes
    ----------
    kinds : ndarray (N,) str
        ``"full"`` (over two faces), ``"half"`` (over one unmatched quad),
        ``"boundary"`` (a full or half tile cut to the surface's boundary) or
        ``"fit_cut"`` (a full or half tile cut where the fit could not make it fit its
        neighbours; its outline is read like a boundary tile's).
    corners : ndarray (N, 8, 3) float64
        Box corners: the bottom face counter-clockwise from (-x, -y), then the top face in
        the same order.
    frames : ndarray (N, 4, 3) float64
        Per tile: origin, length axis x, width axis y, thickness axis z (orthonormal,
        right-handed). The box spans ``[-L/2, L/2] x [-W/2, W/2] x [0, T]`` in its frame:
        the origin is the centre of the bottom face, not of the box (see ``centres``).
    sizes : ndarray (N, 3) float64
        Length, width, thickness of each box (the blank: a cut tile keeps its blank's).
    faces : ndarray (N, 2) int64
        Faces under each tile; -1 in the second slot of a half tile and in both slots of a
        filler piece beyond the quad mesh's boundary, of a piece filling the fit's tears and
        of a whole piece laid in a room of a course (``report["fit"]["room_pieces"]``).
    steps : ndarray (N,) int64
        Step of each tile in the laying order, from 0.
    kept_fractions : ndarray (N,) float64
        Kept area over face area: 1 for uncut tiles.
    outlines : list of list of ndarray (k, 2)
        Per tile, the loops of the part to keep, as (x, y) in the tile's frame (outer
        loops counter-clockwise, holes clockwise); empty for uncut tiles.
    labels : list of str
        Cut-list label of each tile: ``"F"`` full, ``"H"`` half, ``"B1"``, ``"B2"``, ...
        boundary shapes and ``"C1"``, ``"C2"``, ... fit cuts, by falling count.
    cutlist : list of dict
        One entry per cut shape: ``label``, ``kind``, ``count``, ``blank``, ``area``,
        ``outline`` (``cutlist.json``).
    joint_deviations : ndarray (N,) float64
        Each tile's worst joint: the largest ``|gap - joint|`` of the joints it takes part
        in (0 for a tile with none), in model units; for a colour preview of the joints.
    report : dict
        Counts, proof status, tile size, joint gaps (``joints``, with the figures before
        the fit under ``joints["before_fit"]``), the fit (``fit``: status, iterations,
        objective before and after, mean and largest move; absent with ``fit=False``),
        cutting, sequence and warnings (``report.json`` of the command line, without
        ``units``).
    warnings : list of dict
        Odd input or results to look at twice, each ``{"code": ..., "message": ...}``:
        ``closed_surface``, ``several_pieces``, ``normals_down``, ``tile_shape``,
        ``tile_vs_curvature``, ``low_coverage``, ``tiles_dropped``, ``no_support``,
        ``vertices_welded`` (the message says what to do). :func:`tiles` also issues each
        as a :class:`TilePatternWarning`.
    """

    kinds: np.ndarray
    corners: np.ndarray
    frames: np.ndarray
    sizes: np.ndarray
    faces: np.ndarray
    steps: np.ndarray
    kept_fractions: np.ndarray
    outlines: List[List[np.ndarray]]
    labels: List[str]
    cutlist: List[dict]
    report: dict
    joint_deviations: np.ndarray = field(default_factory=lambda: np.zeros(0))
    warnings: List[dict] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.kinds)

    @property
    def centres(self) -> np.ndarray:
        """``(N, 3)`` box centres: frame origin plus half the thickness along z."""
        return self.frames[:, 0] + self.frames[:, 3] * (self.sizes[:, 2:3] / 2.0)

    @property
    def blanks(self) -> np.ndarray:
        """``(N,) str``: the blank each tile is cut from, ``"full"`` or ``"half"``."""
        length = self.report.get("tile", {}).get("length")
        if not length:
            length = float(self.sizes[:, 0].max()) if len(self) else 1.0
        return np.where(self.sizes[:, 0] > 0.75 * length, "full", "half")

    @property
    def tries(self) -> List[dict]:
        """The tries of :func:`run` (the report's ``tries``), in order: ``renormalisation``,
        ``quads``, ``p95_deviation``, ``cut_share``, ``coverage``, ``wide_joints``,
        ``fit_cuts`` (more than 1 % of the tiles cut by the fit), ``score``,
        ``seconds``, ``field`` (``"curvature"``, or ``"smooth"`` for the tries whose field
        follows nothing), ``quads_along_courses`` and ``boundary_free`` (the fifth and sixth
        automatic tries, written only for them), and ``limit_reached`` or ``failed`` where
        they apply. Empty for
        :func:`tiles` and when one try was asked for (when more were and one reached a time
        limit that ended the tries, it lists those made)."""
        return list(self.report.get("tries", []))

    @property
    def chosen_try(self) -> Optional[int]:
        """Which of :attr:`tries` these tiles are, from 0; ``None`` when :attr:`tries` is
        empty."""
        return self.report.get("chosen_try")

    def to_dict(self) -> dict:
        """The tiles as plain (JSON-ready) data."""
        return {
            "kinds": self.kinds.tolist(),
            "labels": list(self.labels),
            "frames": self.frames.tolist(),
            "sizes": self.sizes.tolist(),
            "corners": self.corners.tolist(),
            "faces": self.faces.tolist(),
            "steps": self.steps.tolist(),
            "kept_fractions": self.kept_fractions.tolist(),
            "outlines": [[loop.tolist() for loop in loops] for loops in self.outlines],
            "cutlist": self.cutlist,
            "joint_deviations": self.joint_deviations.tolist(),
            "report": self.report,
            "warnings": list(self.warnings),
        }


class TilePatternWarning(UserWarning):
    """Odd input or a result to look at twice (see :attr:`Tiles.warnings`)."""


def _read_tiles(handle) -> Tiles:
    n = handle.count()
    kinds = handle.kinds(n)
    faces = handle.faces(n).astype(np.int64)
    faces[faces == nat.TP_NO_FACE] = -1
    return Tiles(
        kinds=np.array([nat.TILE_KIND_NAMES.get(int(k), str(int(k))) for k in kinds], dtype="<U8").reshape(n),
        corners=handle.corners(n),
        frames=handle.frames(n),
        sizes=handle.sizes(n),
        faces=faces,
        steps=handle.steps(n).astype(np.int64),
        kept_fractions=handle.kept_fractions(n),
        outlines=handle.outlines(n),
        labels=handle.labels(),
        cutlist=json.loads(handle.cutlist_json()),
        report=json.loads(handle.report_json()),
        joint_deviations=handle.joint_deviations(n),
        warnings=[{"code": code, "message": message} for code, message in handle.warnings()],
    )


def _optional(value):
    return -1.0 if value is None else float(value)


def tiles(
    vertices,
    faces,
    pattern: Pattern,
    length: float = 0.28,
    width: float = 0.14,
    thickness: float = 0.015,
    joint: float = 0.01,
    surface=None,
    cut_tolerance: Optional[float] = None,
    min_kept_width: Optional[float] = None,
    up: Sequence[float] = (0.0, 0.0, 1.0),
    support_band: Optional[float] = None,
    fit: bool = True,
    fit_time_limit: float = 10.0,
    overlap_tolerance: Optional[float] = None,
    bond_tolerance: Optional[float] = None,
    units_per_mm: float = 0.001,
    progress: Optional[Progress] = None,
    creases: bool = True,
) -> Tiles:
    """Place a box per matched pair and a half tile per unpaired quad (stage 3).

    Each box is first placed as in the paper's section 3.5: its origin at the midpoint of
    the two face centroids, its length along the line between them, its thickness along
    the normal of the least-squares plane of the pair's vertices, its bottom on that plane
    and the box on the side the face normals point to. The fit stage (``fit=True``,
    default) then moves every tile on the surface so that its joints come close to
    ``joint``, keeping the bond; what still cannot fit is cut (kind ``"fit_cut"``, labels
    ``C1``, ``C2``...) so that no two tiles overlap, and filler pieces close the courses
    that end short of the edge. Tiles crossing the boundary (of ``surface``, or of the
    quad mesh) are cut to it; the tiles are labelled and numbered in laying order.

    Parameters
    ----------
    vertices : array_like (V, 3)
        Vertices of the quad mesh the pattern was solved on.
    faces : list of list of int or array_like (F, k)
        Its faces, in the same order as for :func:`match`.
    pattern : Pattern
        The result of :func:`match` on this mesh (not closed).
    length, width, thickness, joint : float, optional
        Tile size and mortar joint in model units; default 280 x 140 x 15 mm tiles with
        10 mm joints, in metres.
    surface : tuple (vertices, faces), optional
        The input surface the quads were made from: tiles are cut to its outer edge and
        openings, and pieces fill the strip between the quads and its edge.
    cut_tolerance : float, optional
        Tiles the boundary enters by no more than this stay whole (default 1 % of width).
    min_kept_width : float, optional
        Narrower pieces are slivers: reported, not placed (default a fifth of the width).
    up : array_like (3,), optional
        Up direction for the laying order; default ``(0, 0, 1)``.
    support_band : float, optional
        Tiles with a boundary edge this close above the lowest boundary point stand on the
        supports (default one tile width).
    fit : bool, optional
        Run the fit stage (default True); False keeps the paper's placement, and the
        report has no ``fit`` entry.
    fit_time_limit : float, optional
        Wall-clock seconds of the fit (default 10); when they pass, the best placement so
        far is kept and ``report["fit"]["status"]`` is ``"time_limit"``. The same limit
        holds again for filling the fit's tears with pieces (those laid so far are kept).
    overlap_tolerance : float, optional
        Overlaps the fit may leave; deeper ones are cut (default a twentieth of the joint, at least a three-hundredth of the tile's width).
    bond_tolerance : float, optional
        How far the fit may move a running bond's half offset or an aligned joint
        (default a tenth of the tile length).
    units_per_mm : float, optional
        Model units per millimetre (default 0.001: a model in metres; 1 for millimetres),
        for the report's shares of joints within 2 and 5 mm.
    progress : callable, optional
        ``progress(stage, fraction)`` with ``stage == "tiles"`` and the share of the fit's
        step limit used; return True to cancel (:class:`~tilepattern.CancelledError`, no
        tiles). An exception raised in it cancels and is raised again by ``tiles``.
    creases : bool, optional
        Cut the tiles to the creases that part ``surface`` into sheets, half a joint short
        on each side, and keep tiles and filler pieces on their own sheet (default True);
        False takes the surface as one sheet. Pass the same as to :func:`remesh`.

    Returns
    -------
    Tiles
        Kinds, corners ``(N, 8, 3)``, frames ``(N, 4, 3)``, sizes, faces, laying steps,
        outlines of cut tiles, labels, cut list, joint deviations and the report.

    Raises
    ------
    TilePatternError
        ``InvalidArgumentError`` for a bad tile size or fit option,
        ``InvalidPatternError`` when the pattern was solved on another mesh,
        ``InvalidMeshError``, ``CancelledError``.
    ValueError
        When ``pattern`` was closed.

    Examples
    --------
    >>> from tilepattern import match, tiles
    >>> V = [[0.145 * i, 0.145 * j, 0.0] for j in range(5) for i in range(4)]
    >>> F = [[i + 4 * j, i + 1 + 4 * j, i + 5 + 4 * j, i + 4 + 4 * j] for j in range(4) for i in range(3)]
    >>> placed = tiles(V, F, match(V, F, time_limit=5))
    >>> len(placed), placed.corners.shape, placed.report["full_tiles"]
    (6, (6, 8, 3), 6)
    >>> placed.sizes[0].tolist()
    [0.28, 0.14, 0.015]
    """
    if not isinstance(pattern, Pattern):
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "pattern must be the Pattern returned by match(), got %s" % type(pattern).__name__)
    if pattern.handle is None:
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "this Pattern has no native pattern; pass the result of match()")
    options = _tile_options(
        length, width, thickness, joint, cut_tolerance, min_kept_width, up, support_band, fit, fit_time_limit,
        overlap_tolerance, bond_tolerance, units_per_mm, creases,
    )
    pattern_pointer = pattern.handle  # raises ValueError below if closed
    with mesh_handle(vertices, faces) as quads:
        if surface is None:
            built = pattern_pointer.build_tiles(quads, options, progress=progress)
        else:
            with mesh_handle(*surface) as reference:
                built = pattern_pointer.build_tiles(quads, options, reference, progress=progress)
    return _tiles_from(built, stacklevel=3)


def _tile_options(
    length, width, thickness, joint, cut_tolerance, min_kept_width, up, support_band, fit, fit_time_limit,
    overlap_tolerance, bond_tolerance, units_per_mm, creases,
):
    """The ``TpTileOptions`` of :func:`tiles` (and :func:`run`) from its arguments."""
    options = nat.tile_options()
    options.length = float(length)
    options.width = float(width)
    options.thickness = float(thickness)
    options.joint = float(joint)
    options.cut_tolerance = _optional(cut_tolerance)
    options.min_kept_width = _optional(min_kept_width)
    options.support_band = _optional(support_band)
    options.up[:] = _three(up, "up")
    options.fit = 1 if fit else 0
    options.fit_time_limit_seconds = float(fit_time_limit)
    options.fit_overlap_tolerance = _optional(overlap_tolerance)
    options.fit_bond_tolerance = _optional(bond_tolerance)
    options.units_per_mm = float(units_per_mm)
    options.creases = 1 if creases else 0
    return options


def _tiles_from(handle, stacklevel) -> Tiles:
    """The :class:`Tiles` of a native tiles handle, which is closed; each warning is issued
    as a :class:`TilePatternWarning` pointing ``stacklevel`` frames up (at the caller of the
    public function that calls this)."""
    with handle:
        placed = _read_tiles(handle)
    for w in placed.warnings:
        warnings.warn(f"[{w['code']}] {w['message']}", TilePatternWarning, stacklevel=stacklevel)
    return placed


def quad_edge(length=0.28, width=0.14, joint=0.01, courses="free"):
    """The quad edge to remesh with for a tile (the command line's choice).

    Tiles laid either way sit best on square quads of ``(length + joint) / 2`` (the
    paper's choice). In level courses the quads' height across the courses is what no
    placement can change, so they are made as high as a course, ``width + joint``, where
    that is larger; the fit then closes the head joints along each course.

    Parameters
    ----------
    length, width, joint : float, optional
        Tile size and joint in model units (default 280 x 140 mm, 10 mm, in metres).
    courses : {"free", "level"}, optional
        As for :func:`match`.

    Returns
    -------
    float

    Examples
    --------
    >>> round(quad_edge(), 4), round(quad_edge(courses="level"), 4)
    (0.145, 0.15)
    """
    code = _choice(courses, COURSES, "courses")
    edge = (float(length) + float(joint)) / 2.0
    return max(edge, float(width) + float(joint)) if code == nat.TP_COURSES_LEVEL else edge


# ---------------------------------------------------------------------------------------
# The whole pipeline, with tries
# ---------------------------------------------------------------------------------------


@dataclass(eq=False)
class RunResult:
    """What :func:`run` keeps: the quad mesh, its pattern and its tiles.

    It unpacks as a tuple, ``QV, QF, pattern, placed = run(V, F)``. ``close()`` (or a
    ``with`` block) releases the pattern's native object early, as :meth:`Pattern.close`.

    Attributes
    ----------
    vertices : ndarray (V, 3) float64
        The kept quad mesh's vertices, as :func:`remesh` returns them.
    faces : ndarray (F, 4) int64
        Its faces (a list of lists in the unlikely case that not all are quads).
    pattern : Pattern
        The pattern solved on that quad mesh, as :func:`match` returns it: pairs and
        unpaired faces index ``faces``.
    tiles : Tiles
        The tiles, as :func:`tiles` returns them; faces index ``faces``, and the report
        lists the tries (``report["tries"]``) and the one kept (``report["chosen_try"]``)
        when more than one was made.
    """

    vertices: np.ndarray
    faces: np.ndarray
    pattern: Pattern
    tiles: Tiles

    def __iter__(self):
        return iter((self.vertices, self.faces, self.pattern, self.tiles))

    @property
    def report(self) -> dict:
        """The kept tiles' report (``tiles.report``)."""
        return self.tiles.report

    @property
    def tries(self) -> List[dict]:
        """Each try's figures (:attr:`Tiles.tries`)."""
        return self.tiles.tries

    @property
    def chosen_try(self) -> Optional[int]:
        """Which try was kept (:attr:`Tiles.chosen_try`)."""
        return self.tiles.chosen_try

    def close(self):
        """Releases the pattern's native object; the arrays stay."""
        self.pattern.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()


#: Most quad meshes :func:`run` tries (the library's ``pipeline::MAX_TRIES``).
MAX_TRIES = 6


def _tries(tries) -> int:
    """``tries`` of :func:`run`, checked: 0 (automatic) or 1 to :data:`MAX_TRIES`."""
    if isinstance(tries, bool) or not isinstance(tries, (int, np.integer)) or not 0 <= tries <= MAX_TRIES:
        raise InvalidArgumentError(nat.TP_INVALID_ARGUMENT, "tries is %r: give 0 (automatic) or 1 to %d" % (tries, MAX_TRIES))
    return int(tries)


def _no_forced_pairs(options):
    """Refuses forced pairs, which name quads, which :func:`run` makes itself."""
    count = options.forced_pair_count
    if count:
        raise InvalidArgumentError(
            nat.TP_INVALID_ARGUMENT,
            "forced_pairs names %d pair%s of quads, but run() makes the quads itself, so none can be named before it: "
            "leave forced_pairs None, or call remesh(), match() and tiles() one by one (excluded_faces, as zones, "
            "name faces of the surface and are taken)" % (count, "" if count == 1 else "s"),
        )


def run(
    vertices,
    faces,
    *,
    tries: int = 0,
    progress: Optional[Progress] = None,
    # remesh
    target_edge: Optional[float] = None,
    direction: Union[Sequence[float], str, None] = None,
    angle: Optional[float] = None,
    shapeup: bool = False,
    remesh_time_limit: float = 60.0,
    field=None,
    field_weight: float = 1.0,
    guides=None,
    guide_weight: float = 1.0,
    creases: bool = True,
    renormalisation: float = 0.5,
    # match
    bond: str = "staggered",
    weight: float = 0.5,
    time_limit: float = 60.0,
    method: str = "auto",
    formulation: str = "strengthened",
    forced_pairs=None,
    excluded_faces=None,
    courses: Optional[str] = None,
    up: Sequence[float] = (0.0, 0.0, 1.0),
    gap: float = 0.0,
    zones=None,
    # tiles
    length: float = 0.28,
    width: float = 0.14,
    thickness: float = 0.015,
    joint: float = 0.01,
    cut_tolerance: Optional[float] = None,
    min_kept_width: Optional[float] = None,
    support_band: Optional[float] = None,
    fit: bool = True,
    fit_time_limit: float = 10.0,
    overlap_tolerance: Optional[float] = None,
    bond_tolerance: Optional[float] = None,
    units_per_mm: float = 0.001,
) -> RunResult:
    """Tile a surface in one call, keeping the best of a few quad meshes (all three stages).

    As the command line's ``tilepattern run``: the surface is quadrangulated (:func:`remesh`),
    the quads matched (:func:`match`) and the tiles placed, fitted and cut to the surface
    (:func:`tiles`), on up to six quad meshes, the field's cones placed by a
    renormalisation at ``renormalisation``, then a smooth field, then at twice and half the
    strength, then the smooth field's quads laid out for level courses, then the smooth field
    free of the boundary (other strengths and fields give other, equally valid quads, which
    decide where courses end). The tiles that fit best are kept: joints the report does not
    flag (``wide_joints``) first, then cuts it does not flag (``fit_cuts``), then the fewest
    tiles cut to fit, joints closest to ``joint``, most of the surface covered and fewest
    pieces cut at the edge. One try
    gives exactly what :func:`remesh`, :func:`match` and :func:`tiles` give called one by one
    with the same options and ``surface=(vertices, faces)``.

    Every option of the three stages is taken under its own name (all keyword-only), with
    the same meaning and default, except these:

    Parameters
    ----------
    vertices : array_like (V, 3)
        The surface's vertices.
    faces : list of list of int or array_like (F, k)
        Its faces: triangles, quads or n-gons, mixed if need be.
    tries : int, optional
        How many quad meshes to carry through to tiles: 0 (default) for the command line's
        choice, all of them when the surface needs at most 10,000 quads of ``target_edge``
        (its area over ``target_edge`` squared) and 1 otherwise; or 1 to 6: the
        renormalisation strength given, a smooth field that follows neither the curvature nor
        anything else (made only without a direction, angle, designer's field or guides),
        then twice and half the strength, then the smooth field's quads laid out for level
        courses, half a tile and a joint along them and a course's pitch across (made only
        in level courses with quads of a course's pitch: a course closed on itself, a
        tower's or a drum's ring, then holds whole tiles at the nominal joint), then the smooth
        field free of the boundary, its rows cut to curved edges instead of following them
        (made only where the first try follows an edge with corners: on a developable shell
        with curved edges, a conical vault, its courses are then straight on the
        development and fit to a fraction of a millimetre). Anything else raises
        :class:`~tilepattern.InvalidArgumentError` naming ``tries``. Each try has the
        stages' own time limits (a later try's pattern stage at most 10 s, but the smooth
        field's try the caller's where the first try's quads end rows all over the
        surface). A try whose
        pattern stage or fit reaches its limit has tiles that depend on the machine's
        speed: a later one is listed but not kept. A later one's limit ends the tries, and
        so does the first try's fit, or its pattern stage when that limit is 10 s or less
        (the try's ``ended_tries``).
    progress : callable, optional
        ``progress(stage, fraction)`` with ``stage == "run"`` and the share of the whole run
        done (each try an equal share), about every 10 ms; return True to cancel
        (:class:`~tilepattern.CancelledError`, nothing returned). An exception raised in it
        cancels the run and is raised again by ``run``.
    target_edge : float, optional
        Quad edge in model units. Default ``quad_edge(length, width, joint, courses)``, the
        command line's choice for the tile given: ``(length + joint) / 2`` in free courses
        and ``max((length + joint) / 2, width + joint)`` in level courses; for the default
        tile in metres 0.145 (:func:`remesh`'s default, but as computed in floating point,
        one unit in the last place above the literal: pass ``target_edge=0.145`` for
        :func:`remesh`'s default quads bit for bit) and 0.15.
    remesh_time_limit : float, optional
        Wall-clock seconds of each remesh (default 60), :func:`remesh`'s ``time_limit``.
    time_limit : float, optional
        Wall-clock seconds of each pattern stage (default 60), :func:`match`'s.
    up : array_like (3,), optional
        Up direction of level courses (:func:`match`) and of the laying order
        (:func:`tiles`), one for both as on the command line; default ``(0, 0, 1)``.
    creases : bool, optional
        Quads of their own on each sheet between the surface's creases (:func:`remesh`) and
        tiles cut to them (:func:`tiles`); default True.
    zones : sequence (F,) of str, int or None, optional
        A bond per face of the surface (``faces``, not of the quads), spelt as for
        :func:`match`; each quad takes the zone of the surface face closest to its
        centroid. A wrong count raises :class:`~tilepattern.InvalidArgumentError` before
        any work.
    excluded_faces : array_like (E,) of int, optional
        Faces of the surface (``faces``, not of the quads) to leave out: openings, areas
        laid by hand. Each quad whose closest surface face is one is neither tiled nor
        filled, and its area is left out of the coverage. An index beyond ``faces`` raises
        :class:`~tilepattern.InvalidArgumentError` before any work.
    forced_pairs : optional
        Refused unless None or empty (:class:`~tilepattern.InvalidArgumentError` naming
        it): pairs name quads, which do not exist before the call. Call :func:`remesh`,
        :func:`match` and :func:`tiles` one by one to use them.
    direction, angle, shapeup, field, field_weight, guides, guide_weight, renormalisation
        As for :func:`remesh` (``field`` one vector per vertex or face of the surface).
    courses : {"level", "free"}, optional
        As for :func:`match`, but by default the command line's ``run``'s choice: level
        courses, which fit far better, or free courses when ``bond`` or a zone is
        ``"herringbone"`` or ``"basket-weave"``, which lay tiles both ways (level ones refuse
        them).
    bond, weight, method, formulation, gap
        As for :func:`match`.
    length, width, thickness, joint, cut_tolerance, min_kept_width, support_band, fit, fit_time_limit, overlap_tolerance, bond_tolerance, units_per_mm
        As for :func:`tiles`. Lengths are in model units throughout (default 280 x 140 x 15
        mm tiles with 10 mm joints, in metres; ``units_per_mm`` only scales the report's
        millimetre figures): give the tile in the surface's units.

    Returns
    -------
    RunResult
        ``vertices``, ``faces`` (the kept quad mesh, as :func:`remesh` returns it),
        ``pattern`` (a :class:`Pattern`) and ``tiles`` (a :class:`Tiles`, whose
        ``report["tries"]`` lists every try and ``report["chosen_try"]`` the one kept when
        more than one was made); it unpacks as ``QV, QF, pattern, placed``. Each warning of
        the kept tiles is also issued as a :class:`TilePatternWarning`.

    Raises
    ------
    TilePatternError
        ``InvalidMeshError`` for a bad surface, ``InvalidArgumentError`` for bad options
        (``tries``, zones, forced pairs, excluded faces, ...), ``CancelledError``,
        ``TimeLimitError`` (the first remesh had no quads in its time limit).

    Examples
    --------
    A gently curved 2 x 2 square of 800 triangles, tiled in level courses:

    >>> import numpy as np
    >>> from tilepattern import run
    >>> n = 21
    >>> x, y = np.meshgrid(np.linspace(0, 2, n), np.linspace(0, 2, n))
    >>> V = np.c_[x.ravel(), y.ravel(), 0.1 * x.ravel() * y.ravel()]
    >>> at = lambda i, j: i + n * j
    >>> F = [[at(i, j), at(i + 1, j), at(i + 1, j + 1)] for j in range(n - 1) for i in range(n - 1)]
    >>> F += [[at(i, j), at(i + 1, j + 1), at(i, j + 1)] for j in range(n - 1) for i in range(n - 1)]
    >>> result = run(V, F, courses="level", up=(0, 1, 0), tries=2, time_limit=10)
    >>> QV, QF, pattern, placed = result
    >>> QF.shape[1], len(result.tries), result.chosen_try in (0, 1)
    (4, 2, True)
    >>> placed.report["full_tiles"] == len(pattern.pairs)
    True
    """
    run_options = nat.run_options()
    run_options.tries = _tries(tries)
    if courses is None:
        # As the command line: free courses when the bond or any zone lays tiles both ways.
        both = (nat.TP_BOND_HERRINGBONE, nat.TP_BOND_BASKET_WEAVE)
        codes = _zone_codes(zones)
        both_ways = _choice(bond, BONDS, "bond") in both or (codes is not None and bool(np.isin(codes, both).any()))
        courses = "free" if both_ways else "level"
    if target_edge is None:
        target_edge = quad_edge(length, width, joint, courses)
    # `keep_*`: the arrays the options point into, referenced until the native call returns.
    remesh_options, keep_remesh = _remesh_options(
        target_edge, direction, angle, shapeup, remesh_time_limit, field, field_weight, guides, guide_weight, creases, renormalisation
    )
    pattern_options, keep_pattern = _pattern_options(
        bond, weight, time_limit, method, formulation, forced_pairs, excluded_faces, courses, up, gap, zones
    )
    _no_forced_pairs(pattern_options)
    tile_options = _tile_options(
        length, width, thickness, joint, cut_tolerance, min_kept_width, up, support_band, fit, fit_time_limit,
        overlap_tolerance, bond_tolerance, units_per_mm, creases,
    )
    with mesh_handle(vertices, faces) as surface:
        quads, solved, placed = surface.run(remesh_options, pattern_options, tile_options, run_options, progress)
    try:
        with quads:
            quad_vertices, quad_faces = mesh_arrays(quads)
        tiles_kept = _tiles_from(placed, stacklevel=3)
    except BaseException:
        solved.close()
        placed.close()
        raise
    return RunResult(quad_vertices, quad_faces, _pattern_from(solved), tiles_kept)
