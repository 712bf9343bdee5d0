"""Low-level ctypes binding of ``include/tilepattern.h`` (ABI 9).

This module mirrors the C header one to one: the constants, the status codes (as
exception classes), the option and summary structs, the progress callback type and the
``argtypes``/``restype`` of every exported function (``tp_test_panic`` only exists in test
builds of the library and is bound only when present). It also owns the three kinds of
native handle (:class:`MeshHandle`, :class:`PatternHandle`, :class:`TilesHandle`), each
freed exactly once by ``close()``, a ``with`` block or garbage collection.

The rest of the package calls the library only through this module. The library is
loaded on first use (:func:`lib`), so ``import tilepattern`` works without it.

Notes
-----
Options structs are filled with the ``tp_*_options_init`` functions, never with the
``tp_*_options_default`` functions that return a struct by value: a library whose struct
grew (the ``struct_size`` scheme allows that without a new ABI version) would write past
the end of a shorter return buffer. The ``_default`` functions are still bound, with a
return type padded by :data:`RETURN_PADDING` bytes so that calling them stays safe; all but
``tp_run_options_default``, whose 8-byte ``TpRunOptions`` is returned in registers and is
bound with its exact type (the package never calls it; the tests compare its size).
"""

from __future__ import annotations

import ctypes
import os
import sys
import threading
from ctypes import (
    CFUNCTYPE,
    POINTER,
    Structure,
    c_char,
    c_char_p,
    c_double,
    c_int32,
    c_size_t,
    c_ubyte,
    c_uint32,
    c_void_p,
)
from pathlib import Path

import numpy as np

# ---------------------------------------------------------------------------------------
# Constants of the header
# ---------------------------------------------------------------------------------------

#: ``TP_ABI_VERSION`` of the header this module mirrors.
ABI_VERSION = 10

TP_STAGE_REMESH = 1
TP_STAGE_PATTERN = 2
TP_STAGE_TILES = 3
#: The whole pipeline of ``tp_run``: every stage of every try (since ABI 9).
TP_STAGE_RUN = 4

TP_BOND_STACK = 0
TP_BOND_STAGGERED = 1
TP_BOND_RUNNING = 2
TP_BOND_HERRINGBONE = 3
TP_BOND_BASKET_WEAVE = 4
#: A zone laid in the options' ``bond`` (``TpPatternOptions.zones``).
TP_ZONE_DEFAULT = -1

TP_METHOD_AUTO = 0
TP_METHOD_MIP = 1

TP_FORMULATION_STRENGTHENED = 0
TP_FORMULATION_PAPER = 1

TP_SOLVE_OPTIMAL = 0
TP_SOLVE_TIME_LIMIT = 1
TP_SOLVE_FEASIBLE = 2

TP_BOUND_MATCHING = 0
TP_BOUND_PATCHES = 1
TP_BOUND_WHOLE_PROGRAM = 2
TP_BOUND_LINEAR_RELAXATION = 3

TP_COURSES_FREE = 0
TP_COURSES_LEVEL = 1

TP_DIRECTION_CURVATURE = 0
TP_DIRECTION_VECTOR = 1
TP_DIRECTION_ANGLE = 2
TP_DIRECTION_SMOOTH = 3

TP_TILE_FULL = 0
TP_TILE_HALF = 1
TP_TILE_BOUNDARY = 2
TP_TILE_FIT_CUT = 3

TP_NO_FACE = 0xFFFFFFFF

# Warning codes (enum TpWarning): report.json's warnings[].code by number.
TP_WARNING_CLOSED_SURFACE = 1
TP_WARNING_SEVERAL_PIECES = 2
TP_WARNING_NORMALS_DOWN = 3
TP_WARNING_TILE_SHAPE = 4
TP_WARNING_TILE_VS_CURVATURE = 5
TP_WARNING_LOW_COVERAGE = 6
TP_WARNING_TILES_DROPPED = 7
TP_WARNING_NO_SUPPORT = 8
TP_WARNING_VERTICES_WELDED = 9
TP_WARNING_FIT_CUTS = 10
TP_WARNING_WIDE_JOINTS = 11
TP_WARNING_FOLDED_SURFACE = 12
TP_WARNING_NORMALS_UNIFIED = 13
TP_WARNING_QUAD_SIZE = 14
TP_WARNING_TILES_OFF_SURFACE = 15
TP_WARNING_SMALL_OPENINGS = 16
TP_WARNING_UP_AXIS = 17
TP_WARNING_QUADS_OFF_SURFACE = 18
TP_WARNING_CURVED_POLYGONS = 19

#: Warning code -> its name in report.json, for every code of ``enum TpWarning``.
WARNING_NAMES = {
    TP_WARNING_CLOSED_SURFACE: "closed_surface",
    TP_WARNING_SEVERAL_PIECES: "several_pieces",
    TP_WARNING_NORMALS_DOWN: "normals_down",
    TP_WARNING_TILE_SHAPE: "tile_shape",
    TP_WARNING_TILE_VS_CURVATURE: "tile_vs_curvature",
    TP_WARNING_LOW_COVERAGE: "low_coverage",
    TP_WARNING_TILES_DROPPED: "tiles_dropped",
    TP_WARNING_NO_SUPPORT: "no_support",
    TP_WARNING_VERTICES_WELDED: "vertices_welded",
    TP_WARNING_FIT_CUTS: "fit_cuts",
    TP_WARNING_WIDE_JOINTS: "wide_joints",
    TP_WARNING_FOLDED_SURFACE: "folded_surface",
    TP_WARNING_NORMALS_UNIFIED: "normals_unified",
    TP_WARNING_QUAD_SIZE: "quad_size",
    TP_WARNING_TILES_OFF_SURFACE: "tiles_off_surface",
    TP_WARNING_SMALL_OPENINGS: "small_openings",
    TP_WARNING_UP_AXIS: "up_axis",
    TP_WARNING_QUADS_OFF_SURFACE: "quads_off_surface",
    TP_WARNING_CURVED_POLYGONS: "curved_polygons",
}

MAX_VERTICES = 4_000_000
MAX_FACES = 4_000_000
MAX_INDICES = 16_000_000

# Status codes (enum TpStatus).
TP_OK = 0
TP_NULL_POINTER = 1
TP_INVALID_ARGUMENT = 2
TP_BUFFER_TOO_SMALL = 3
TP_INVALID_MESH = 4
TP_INVALID_PATTERN = 5
TP_SOLVER_FAILED = 6
TP_TIME_LIMIT = 7
TP_CANCELLED = 8
TP_NOT_AVAILABLE = 9
TP_PANIC = 10

#: Status code -> name, for every code of ``enum TpStatus``.
STATUS_NAMES = {
    TP_OK: "TP_OK",
    TP_NULL_POINTER: "TP_NULL_POINTER",
    TP_INVALID_ARGUMENT: "TP_INVALID_ARGUMENT",
    TP_BUFFER_TOO_SMALL: "TP_BUFFER_TOO_SMALL",
    TP_INVALID_MESH: "TP_INVALID_MESH",
    TP_INVALID_PATTERN: "TP_INVALID_PATTERN",
    TP_SOLVER_FAILED: "TP_SOLVER_FAILED",
    TP_TIME_LIMIT: "TP_TIME_LIMIT",
    TP_CANCELLED: "TP_CANCELLED",
    TP_NOT_AVAILABLE: "TP_NOT_AVAILABLE",
    TP_PANIC: "TP_PANIC",
}

STAGE_NAMES = {TP_STAGE_REMESH: "remesh", TP_STAGE_PATTERN: "pattern", TP_STAGE_TILES: "tiles", TP_STAGE_RUN: "run"}
SOLVE_STATUS_NAMES = {TP_SOLVE_OPTIMAL: "optimal", TP_SOLVE_TIME_LIMIT: "time_limit", TP_SOLVE_FEASIBLE: "feasible"}
BOUND_SOURCE_NAMES = {TP_BOUND_MATCHING: "matching", TP_BOUND_PATCHES: "patches", TP_BOUND_WHOLE_PROGRAM: "whole_program", TP_BOUND_LINEAR_RELAXATION: "linear_relaxation"}
TILE_KIND_NAMES = {TP_TILE_FULL: "full", TP_TILE_HALF: "half", TP_TILE_BOUNDARY: "boundary", TP_TILE_FIT_CUT: "fit_cut"}
COURSES_NAMES = {TP_COURSES_FREE: "free", TP_COURSES_LEVEL: "level"}

# ---------------------------------------------------------------------------------------
# Errors
# ---------------------------------------------------------------------------------------


class TilePatternError(Exception):
    """A call into the TilePattern library failed.

    Every non-zero ``TpStatus`` raises a subclass of this exception, chosen by
    :func:`error_class`; catch ``TilePatternError`` to catch them all.

    Parameters
    ----------
    status : int
        The status code returned by the library.
    message : str
        Why the call failed (the library's ``tp_last_error_message``).

    Attributes
    ----------
    status : int
        The library's stable status code, e.g. ``4``.
    name : str
        The code's name in the header, e.g. ``"TP_INVALID_MESH"``.
    message : str
        The native message; it names the face, vertex or option at fault.

    Examples
    --------
    >>> from tilepattern import TilePatternError, match
    >>> try:
    ...     match([[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 1, 7]])
    ... except TilePatternError as error:
    ...     print(error.status, error.name)
    4 TP_INVALID_MESH
    """

    #: The status code this class stands for (``None``: any).
    code = None

    def __init__(self, status, message=""):
        self.status = int(status)
        self.name = STATUS_NAMES.get(self.status, "TP_UNKNOWN_%d" % self.status)
        self.message = message
        super().__init__("%s (%d): %s" % (self.name, self.status, message) if message else "%s (%d)" % (self.name, self.status))

    def __reduce__(self):
        return (_rebuild_error, (self.status, self.message))


def _rebuild_error(status, message):
    return error_class(status)(status, message)


class NullPointerError(TilePatternError):
    """``TP_NULL_POINTER``: a required pointer was NULL."""

    code = TP_NULL_POINTER


class InvalidArgumentError(TilePatternError, ValueError):
    """``TP_INVALID_ARGUMENT``: an argument or option is out of range."""

    code = TP_INVALID_ARGUMENT


class BufferTooSmallError(TilePatternError):
    """``TP_BUFFER_TOO_SMALL``: a copy buffer was smaller than the data."""

    code = TP_BUFFER_TOO_SMALL


class InvalidMeshError(TilePatternError, ValueError):
    """``TP_INVALID_MESH``: the mesh was refused (NaN, bad indices, non-manifold, empty)."""

    code = TP_INVALID_MESH


class InvalidPatternError(TilePatternError, ValueError):
    """``TP_INVALID_PATTERN``: the pattern does not fit the mesh."""

    code = TP_INVALID_PATTERN


class SolverFailedError(TilePatternError):
    """``TP_SOLVER_FAILED``: the MIP solver failed."""

    code = TP_SOLVER_FAILED


class TimeLimitError(TilePatternError):
    """``TP_TIME_LIMIT``: the stage hit its time limit before it had any result."""

    code = TP_TIME_LIMIT


class CancelledError(TilePatternError):
    """``TP_CANCELLED``: the progress callback asked to stop."""

    code = TP_CANCELLED


class NotAvailableError(TilePatternError):
    """``TP_NOT_AVAILABLE``: the stage (or the library itself) is not available."""

    code = TP_NOT_AVAILABLE


class PanicError(TilePatternError):
    """``TP_PANIC``: a bug in the library; the panic was caught and the handle discarded."""

    code = TP_PANIC


class LibraryNotFoundError(NotAvailableError, OSError):
    """The native library could not be found or loaded (status ``TP_NOT_AVAILABLE``)."""

    def __init__(self, message):
        super().__init__(TP_NOT_AVAILABLE, message)

    def __reduce__(self):
        return (LibraryNotFoundError, (self.message,))


_ERROR_CLASSES = {
    cls.code: cls
    for cls in (
        NullPointerError,
        InvalidArgumentError,
        BufferTooSmallError,
        InvalidMeshError,
        InvalidPatternError,
        SolverFailedError,
        TimeLimitError,
        CancelledError,
        NotAvailableError,
        PanicError,
    )
}


def error_class(status):
    """The exception class for a status code (``TilePatternError`` for unknown codes).

    Parameters
    ----------
    status : int
        A non-zero ``TpStatus``.

    Returns
    -------
    type
        A subclass of :class:`TilePatternError`.

    Examples
    --------
    >>> error_class(4).__name__, error_class(99).__name__
    ('InvalidMeshError', 'TilePatternError')
    """
    return _ERROR_CLASSES.get(int(status), TilePatternError)


def error(status, message):
    """A ready-to-raise exception for ``status`` with ``message``."""
    return error_class(status)(status, message)


# ---------------------------------------------------------------------------------------
# Structs and types
# ---------------------------------------------------------------------------------------


class TpMesh(Structure):
    """Opaque ``TpMesh``."""


class TpPattern(Structure):
    """Opaque ``TpPattern``."""


class TpTiles(Structure):
    """Opaque ``TpTiles``."""


TpMeshP = POINTER(TpMesh)
TpPatternP = POINTER(TpPattern)
TpTilesP = POINTER(TpTiles)


class TpPatternOptions(Structure):
    """``TpPatternOptions``; create filled with defaults by :func:`pattern_options`."""

    _fields_ = [
        ("struct_size", c_uint32),
        ("bond", c_int32),
        ("weight", c_double),
        ("time_limit_seconds", c_double),
        ("method", c_int32),
        ("formulation", c_int32),
        ("forced_pairs", POINTER(c_uint32)),
        ("forced_pair_count", c_size_t),
        ("excluded_faces", POINTER(c_uint32)),
        ("excluded_face_count", c_size_t),
        # Since ABI 3.
        ("courses", c_int32),
        ("up", c_double * 3),
        # Since ABI 4.
        ("gap", c_double),
        # Since ABI 6.
        ("zones", POINTER(c_int32)),
        ("zone_count", c_size_t),
    ]


class TpPatternSummary(Structure):
    """``TpPatternSummary``."""

    _fields_ = [
        ("faces", c_size_t),
        ("pairs", c_size_t),
        ("unpaired", c_size_t),
        ("excluded", c_size_t),
        ("non_quad", c_size_t),
        ("continuous_joints", c_size_t),
        ("shifted_pairs", c_size_t),
        ("objective", c_double),
        ("bound", c_double),
        ("gap", c_double),
        ("seconds", c_double),
        ("status", c_int32),
    ]


class TpRemeshOptions(Structure):
    """``TpRemeshOptions``; create filled with defaults by :func:`remesh_options`."""

    _fields_ = [
        ("struct_size", c_uint32),
        ("target_edge", c_double),
        ("direction", c_int32),
        ("direction_vector", c_double * 3),
        ("angle_degrees", c_double),
        ("shapeup", c_int32),
        ("time_limit_seconds", c_double),
        ("field_vectors", POINTER(c_double)),
        ("field_count", c_size_t),
        ("field_weight", c_double),
        ("guide_points", POINTER(c_double)),
        ("guide_point_count", c_size_t),
        ("guide_curve_sizes", POINTER(c_uint32)),
        ("guide_count", c_size_t),
        ("guide_weight", c_double),
        # Since ABI 7: split at the creases.
        ("creases", c_int32),
        # Since ABI 8: the strength that places the field's cones.
        ("renormalisation", c_double),
    ]


class TpTileOptions(Structure):
    """``TpTileOptions``; create filled with defaults by :func:`tile_options`."""

    _fields_ = [
        ("struct_size", c_uint32),
        ("length", c_double),
        ("width", c_double),
        ("thickness", c_double),
        ("joint", c_double),
        ("cut_tolerance", c_double),
        ("min_kept_width", c_double),
        ("up", c_double * 3),
        ("support_band", c_double),
        # Since ABI 3: the fit stage.
        ("fit", c_int32),
        ("fit_time_limit_seconds", c_double),
        ("fit_overlap_tolerance", c_double),
        ("fit_bond_tolerance", c_double),
        ("units_per_mm", c_double),
        # Since ABI 7: cut to the creases.
        ("creases", c_int32),
    ]


class TpRunOptions(Structure):
    """``TpRunOptions`` (since ABI 9); create filled with defaults by :func:`run_options`."""

    _fields_ = [
        ("struct_size", c_uint32),
        ("tries", c_uint32),
    ]


#: Spare bytes after the return value of the ``tp_*_options_default`` functions.
RETURN_PADDING = 256


def _padded(struct):
    """``struct`` followed by :data:`RETURN_PADDING` spare bytes, as a return type: every
    options struct is far larger than 16 bytes, so on x86-64, AArch64 and Windows x64
    it is returned through a caller-provided buffer either way, and the padding keeps a
    newer library with a longer struct inside that buffer."""
    return type(struct.__name__ + "Return", (struct,), {"_fields_": [("_reserved", c_ubyte * RETURN_PADDING)]})


TpPatternOptionsReturn = _padded(TpPatternOptions)
TpRemeshOptionsReturn = _padded(TpRemeshOptions)
TpTileOptionsReturn = _padded(TpTileOptions)
# Not TpRunOptions: at 8 bytes it comes back in registers (x86-64, AArch64, Windows x64), and
# a padded return type would make ctypes expect it through a caller's buffer instead.
# ``tp_run_options_default`` is bound with its exact type; the package fills run options with
# ``tp_run_options_init`` like the others (:func:`run_options`).

#: ``TpProgressCallback``: ``int32_t (*)(void *user, uint32_t stage, double fraction)``.
TpProgressCallback = CFUNCTYPE(c_int32, c_void_p, c_uint32, c_double)

TpStatus = c_int32
_u32p = POINTER(c_uint32)
_f64p = POINTER(c_double)
_i32p = POINTER(c_int32)
_sizep = POINTER(c_size_t)
_charp = POINTER(c_char)

#: ``name: (restype, argtypes)`` for every export of the header.
PROTOTYPES = {
    "tp_version": (c_char_p, []),
    "tp_abi_version": (c_uint32, []),
    "tp_mesh_new": (TpStatus, [_f64p, c_size_t, _u32p, c_size_t, _u32p, c_size_t, POINTER(TpMeshP)]),
    "tp_mesh_new_welded": (TpStatus, [_f64p, c_size_t, _u32p, c_size_t, _u32p, c_size_t, c_double, POINTER(TpMeshP)]),
    "tp_mesh_copy_sources": (TpStatus, [TpMeshP, _u32p, c_size_t, _u32p, c_size_t]),
    "tp_mesh_free": (None, [TpMeshP]),
    "tp_mesh_counts": (TpStatus, [TpMeshP, _sizep, _sizep, _sizep]),
    "tp_mesh_copy_vertices": (TpStatus, [TpMeshP, _f64p, c_size_t]),
    "tp_mesh_copy_faces": (TpStatus, [TpMeshP, _u32p, c_size_t, _u32p, c_size_t]),
    "tp_pattern_options_default": (TpPatternOptionsReturn, []),
    "tp_pattern_options_init": (TpStatus, [POINTER(TpPatternOptions), c_size_t]),
    "tp_pattern_solve": (TpStatus, [TpMeshP, POINTER(TpPatternOptions), TpProgressCallback, c_void_p, POINTER(TpPatternP)]),
    "tp_pattern_free": (None, [TpPatternP]),
    "tp_pattern_summary": (TpStatus, [TpPatternP, POINTER(TpPatternSummary)]),
    "tp_pattern_bound_source": (TpStatus, [TpPatternP, POINTER(c_int32)]),
    "tp_pattern_copy_pairs": (TpStatus, [TpPatternP, _u32p, c_size_t]),
    "tp_pattern_copy_unpaired": (TpStatus, [TpPatternP, _u32p, c_size_t]),
    "tp_remesh_options_default": (TpRemeshOptionsReturn, []),
    "tp_remesh_options_init": (TpStatus, [POINTER(TpRemeshOptions), c_size_t]),
    "tp_remesh": (TpStatus, [TpMeshP, POINTER(TpRemeshOptions), TpProgressCallback, c_void_p, POINTER(TpMeshP)]),
    "tp_run_options_default": (TpRunOptions, []),
    "tp_run_options_init": (TpStatus, [POINTER(TpRunOptions), c_size_t]),
    "tp_run": (
        TpStatus,
        [
            TpMeshP,
            POINTER(TpRemeshOptions),
            POINTER(TpPatternOptions),
            POINTER(TpTileOptions),
            POINTER(TpRunOptions),
            TpProgressCallback,
            c_void_p,
            POINTER(TpMeshP),
            POINTER(TpPatternP),
            POINTER(TpTilesP),
        ],
    ),
    "tp_last_error_message": (c_size_t, [_charp, c_size_t]),
    "tp_tile_options_default": (TpTileOptionsReturn, []),
    "tp_tile_options_init": (TpStatus, [POINTER(TpTileOptions), c_size_t]),
    "tp_tiles_build": (TpStatus, [TpMeshP, TpPatternP, POINTER(TpTileOptions), POINTER(TpTilesP)]),
    "tp_tiles_build_on_surface": (TpStatus, [TpMeshP, TpPatternP, TpMeshP, POINTER(TpTileOptions), POINTER(TpTilesP)]),
    "tp_tiles_build_with_progress": (
        TpStatus,
        [TpMeshP, TpPatternP, TpMeshP, POINTER(TpTileOptions), TpProgressCallback, c_void_p, POINTER(TpTilesP)],
    ),
    "tp_tiles_copy_joint_deviations": (TpStatus, [TpTilesP, _f64p, c_size_t]),
    "tp_tiles_free": (None, [TpTilesP]),
    "tp_tiles_count": (TpStatus, [TpTilesP, _sizep]),
    "tp_tiles_copy_kinds": (TpStatus, [TpTilesP, _i32p, c_size_t]),
    "tp_tiles_copy_corners": (TpStatus, [TpTilesP, _f64p, c_size_t]),
    "tp_tiles_copy_frames": (TpStatus, [TpTilesP, _f64p, c_size_t]),
    "tp_tiles_copy_sizes": (TpStatus, [TpTilesP, _f64p, c_size_t]),
    "tp_tiles_copy_faces": (TpStatus, [TpTilesP, _u32p, c_size_t]),
    "tp_tiles_report_json": (TpStatus, [TpTilesP, _charp, c_size_t, _sizep]),
    "tp_tiles_copy_steps": (TpStatus, [TpTilesP, _u32p, c_size_t]),
    "tp_tiles_copy_kept_fractions": (TpStatus, [TpTilesP, _f64p, c_size_t]),
    "tp_tiles_outline_counts": (TpStatus, [TpTilesP, _sizep, _sizep]),
    "tp_tiles_copy_loop_counts": (TpStatus, [TpTilesP, _u32p, c_size_t]),
    "tp_tiles_copy_loop_sizes": (TpStatus, [TpTilesP, _u32p, c_size_t]),
    "tp_tiles_copy_loop_points": (TpStatus, [TpTilesP, _f64p, c_size_t]),
    "tp_tiles_labels": (TpStatus, [TpTilesP, _charp, c_size_t, _sizep]),
    "tp_tiles_cutlist_json": (TpStatus, [TpTilesP, _charp, c_size_t, _sizep]),
    "tp_tiles_warning_count": (TpStatus, [TpTilesP, _sizep]),
    "tp_tiles_copy_warning_codes": (TpStatus, [TpTilesP, _i32p, c_size_t]),
    "tp_tiles_warnings": (TpStatus, [TpTilesP, _charp, c_size_t, _sizep]),
}

#: Exports that exist only in some builds: bound when present.
OPTIONAL_PROTOTYPES = {
    "tp_test_panic": (TpStatus, []),
}

# ---------------------------------------------------------------------------------------
# Loading
# ---------------------------------------------------------------------------------------

_PACKAGE_DIR = Path(__file__).resolve().parent


def library_file_names():
    """The library's file names on this platform, most likely first."""
    if sys.platform == "win32":
        return ["tilepattern.dll", "libtilepattern.dll"]
    if sys.platform == "darwin":
        return ["libtilepattern.dylib", "libtilepattern.so"]
    return ["libtilepattern.so"]


def library_candidates():
    """Where the library is looked for, in order (the environment variable aside).

    Returns
    -------
    list of pathlib.Path
        Next to the package, then ``target/release`` of a source checkout (the package
        lives in ``python/tilepattern`` of it) and of ``$CARGO_TARGET_DIR``.
    """
    folders = [_PACKAGE_DIR, _PACKAGE_DIR.parent.parent / "target" / "release"]
    if os.environ.get("CARGO_TARGET_DIR"):
        folders.append(Path(os.environ["CARGO_TARGET_DIR"]) / "release")
    return [folder / name for folder in folders for name in library_file_names()]


def library_path():
    """The path of the native library that :func:`lib` loads.

    Looked for in order: the ``TILEPATTERN_LIB`` environment variable (a full path), next
    to the package (``tilepattern/libtilepattern.so``, ``.dylib`` or ``tilepattern.dll``),
    and the cargo target folder of a source checkout (``../target/release`` relative to
    ``python/``).

    Returns
    -------
    pathlib.Path

    Raises
    ------
    LibraryNotFoundError
        When ``TILEPATTERN_LIB`` names a missing file, or the library is nowhere.
    """
    explicit = os.environ.get("TILEPATTERN_LIB")
    if explicit:
        path = Path(explicit).expanduser()
        if not path.is_file():
            raise LibraryNotFoundError("TILEPATTERN_LIB is set to %s, which is not a file" % explicit)
        return path
    candidates = library_candidates()
    for candidate in candidates:
        if candidate.is_file():
            return candidate
    raise LibraryNotFoundError(
        "the TilePattern library was not found. Build it with `cargo build --release --lib` in the "
        "repository, copy it next to the package, or set TILEPATTERN_LIB to its full path. Looked at: "
        + ", ".join(str(c) for c in candidates)
    )


def bind(library):
    """Declares ``argtypes`` and ``restype`` of every export on a loaded ``ctypes.CDLL``.

    Parameters
    ----------
    library : ctypes.CDLL

    Raises
    ------
    LibraryNotFoundError
        When an export of the header is missing (a library older than the header).
    """
    for name, (restype, argtypes) in PROTOTYPES.items():
        try:
            function = getattr(library, name)
        except AttributeError:
            raise LibraryNotFoundError("%s does not export %s: it is older than this package" % (library._name, name)) from None
        function.restype = restype
        function.argtypes = argtypes
    for name, (restype, argtypes) in OPTIONAL_PROTOTYPES.items():
        function = getattr(library, name, None)
        if function is not None:
            function.restype = restype
            function.argtypes = argtypes
    return library


_lib = None
_lib_lock = threading.Lock()


def load(path=None):
    """Loads and binds the library at ``path`` (default :func:`library_path`) and checks
    its ABI version. Does not make it the library :func:`lib` returns.

    Returns
    -------
    ctypes.CDLL
    """
    path = library_path() if path is None else Path(path)
    try:
        library = ctypes.CDLL(str(path))
    except OSError as why:
        raise LibraryNotFoundError("could not load %s: %s" % (path, why)) from None
    bind(library)
    loaded = library.tp_abi_version()
    if loaded != ABI_VERSION:
        raise LibraryNotFoundError("%s has ABI version %d; this package needs %d" % (path, loaded, ABI_VERSION))
    return library


def lib():
    """The loaded, bound library (loaded on first use, then cached).

    Returns
    -------
    ctypes.CDLL
    """
    global _lib
    if _lib is None:
        with _lib_lock:
            if _lib is None:
                _lib = load()
    return _lib


# ---------------------------------------------------------------------------------------
# Calls
# ---------------------------------------------------------------------------------------


def last_error_message():
    """This thread's last error message from the library (empty after a success)."""
    library = lib()
    size = library.tp_last_error_message(None, 0)
    buffer = ctypes.create_string_buffer(size + 1)
    library.tp_last_error_message(buffer, size + 1)
    return buffer.value.decode("utf-8", "replace")


def check(status):
    """Raises the :class:`TilePatternError` subclass for a non-zero status, with the
    library's message; returns ``None`` for ``TP_OK``."""
    if status != TP_OK:
        raise error(status, last_error_message())


def as_pointer(array, ctype):
    """A ``POINTER(ctype)`` to the data of a C-contiguous numpy array (``None`` for ``None``)."""
    if array is None:
        return None
    if not array.flags.c_contiguous:
        raise ValueError("array must be C-contiguous")
    return array.ctypes.data_as(POINTER(ctype))


def _options(struct, init_name):
    options = struct()
    check(getattr(lib(), init_name)(ctypes.byref(options), ctypes.sizeof(options)))
    return options


def pattern_options():
    """A :class:`TpPatternOptions` filled with the library's defaults (``_init``)."""
    return _options(TpPatternOptions, "tp_pattern_options_init")


def remesh_options():
    """A :class:`TpRemeshOptions` filled with the library's defaults (``_init``)."""
    return _options(TpRemeshOptions, "tp_remesh_options_init")


def tile_options():
    """A :class:`TpTileOptions` filled with the library's defaults (``_init``)."""
    return _options(TpTileOptions, "tp_tile_options_init")


def run_options():
    """A :class:`TpRunOptions` filled with the library's defaults (``_init``)."""
    return _options(TpRunOptions, "tp_run_options_init")


def native_struct_size(default_name):
    """The ``struct_size`` the library puts in its own defaults, e.g. for
    ``"tp_remesh_options_default"``: ``sizeof`` the struct as the library was compiled.

    Compare it with ``ctypes.sizeof`` of the mirror to find a header/library mismatch.
    """
    return getattr(lib(), default_name)().struct_size


def _text(function, pointer):
    """A string from one of the ask-the-size-then-copy text functions."""
    needed = c_size_t(0)
    status = function(pointer, None, 0, ctypes.byref(needed))
    if status not in (TP_OK, TP_BUFFER_TOO_SMALL):
        check(status)
    while True:
        buffer = ctypes.create_string_buffer(needed.value + 1)
        length = needed.value
        status = function(pointer, buffer, length + 1, ctypes.byref(needed))
        if status == TP_BUFFER_TOO_SMALL and needed.value > length:
            continue  # cannot happen for an immutable handle; be safe anyway
        check(status)
        return buffer.raw[: needed.value].decode("utf-8")


# ---------------------------------------------------------------------------------------
# Progress callbacks
# ---------------------------------------------------------------------------------------


class ProgressBridge:
    """A Python callable as a ``TpProgressCallback``.

    ``progress(stage, fraction)`` gets the stage name (``"remesh"``, ``"pattern"``,
    ``"tiles"``, or ``"run"`` for the whole pipeline of ``tp_run``) and the fraction done; a
    true return value cancels the stage. An
    exception raised by ``progress`` (``KeyboardInterrupt`` included) never reaches C: it
    is stored, the stage is cancelled, and :meth:`finish` raises it again once the native
    call returned. The bridge is installed even without ``progress``, so that Ctrl-C
    cancels a long solve.

    Keep the bridge referenced for as long as the native call runs (the ctypes callback
    object must outlive it).

    Parameters
    ----------
    progress : callable or None
    """

    def __init__(self, progress=None):
        if progress is not None and not callable(progress):
            raise InvalidArgumentError(TP_INVALID_ARGUMENT, "progress must be callable, got %r" % (progress,))
        self.progress = progress
        self.exception = None
        self.calls = 0
        self.callback = TpProgressCallback(self._call)

    def _call(self, _user, stage, fraction):
        if self.exception is not None:
            return 1
        try:
            self.calls += 1
            if self.progress is None:
                return 0
            return 1 if self.progress(STAGE_NAMES.get(stage, str(stage)), float(fraction)) else 0
        except BaseException as caught:  # noqa: BLE001 - raised again by finish()
            self.exception = caught
            return 1

    def finish(self, status):
        """Raises the callback's exception, if any, else checks ``status``."""
        if self.exception is not None:
            caught, self.exception = self.exception, None
            try:
                raise caught
            finally:
                caught = None
        check(status)


# ---------------------------------------------------------------------------------------
# Handles
# ---------------------------------------------------------------------------------------


class Handle:
    """Owns one native pointer and releases it exactly once.

    ``close()`` (safe to call any number of times), the end of a ``with`` block and
    garbage collection all release it; the handle keeps the library's free function, so
    the library outlives it. Copies share the handle (``copy.copy`` returns the handle
    itself) and pickling is refused: a native pointer cannot cross processes.

    Parameters
    ----------
    pointer : ctypes pointer
        A non-NULL pointer returned by the library.
    free : callable
        The ``tp_*_free`` function to release it with.
    """

    kind = "handle"

    def __init__(self, pointer, free):
        if not pointer:
            raise ValueError("a %s handle needs a non-NULL pointer" % self.kind)
        self._pointer = pointer
        self._free = free
        self._lock = threading.Lock()

    @property
    def pointer(self):
        """The native pointer; ``ValueError`` once the handle was closed."""
        pointer = getattr(self, "_pointer", None)
        if pointer is None:
            raise ValueError("operation on a closed %s handle" % self.kind)
        return pointer

    @property
    def closed(self):
        """True once the native object was released."""
        return getattr(self, "_pointer", None) is None

    def close(self):
        """Releases the native object; further calls do nothing."""
        lock = getattr(self, "_lock", None)
        if lock is None:
            return
        with lock:
            pointer, self._pointer = self._pointer, None
        if pointer is not None:
            self._free(pointer)

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:  # noqa: BLE001 - nothing sensible to do at collection time
            pass

    def __copy__(self):
        return self

    def __deepcopy__(self, memo):
        return self

    def __reduce__(self):
        raise TypeError("a native %s handle cannot be pickled" % self.kind)

    def __repr__(self):
        state = "closed" if self.closed else "0x%x" % ctypes.cast(self._pointer, c_void_p).value
        return "<%s %s>" % (type(self).__name__, state)


class MeshHandle(Handle):
    """A validated native mesh (``TpMesh``)."""

    kind = "mesh"

    def __init__(self, pointer):
        super().__init__(pointer, lib().tp_mesh_free)

    @classmethod
    def new(cls, vertices, indices, sizes):
        """``tp_mesh_new`` on prepared arrays.

        Parameters
        ----------
        vertices : ndarray (V, 3) float64, C-contiguous
        indices : ndarray (I,) uint32, C-contiguous
            All faces' vertex indices, face after face.
        sizes : ndarray (F,) uint32, C-contiguous
            Each face's number of vertices.
        """
        return cls._made(lib().tp_mesh_new, vertices, indices, sizes)

    @classmethod
    def new_welded(cls, vertices, indices, sizes, relative_tolerance):
        """``tp_mesh_new_welded`` on prepared arrays (as :meth:`new`): vertices within
        ``relative_tolerance`` of the mesh's size joined, cracks zipped, faces turned."""
        return cls._made(lib().tp_mesh_new_welded, vertices, indices, sizes, c_double(relative_tolerance))

    @classmethod
    def _made(cls, make, vertices, indices, sizes, *options):
        """A mesh from ``make`` (``tp_mesh_new`` or ``tp_mesh_new_welded``) on the arrays,
        with ``options`` between them and the out pointer."""
        out = TpMeshP()
        check(
            make(
                as_pointer(vertices, c_double), len(vertices),
                as_pointer(indices, c_uint32), len(indices),
                as_pointer(sizes, c_uint32), len(sizes),
                *options,
                ctypes.byref(out),
            )
        )
        return cls(out)

    def sources(self):
        """``(vertex_source (V,) int64, face_source (F,) int64)``: each vertex's first given
        vertex and each face's given face (``tp_mesh_copy_sources``)."""
        nv, nf, _ = self.counts()
        vertex_source = np.empty(nv, dtype=np.uint32)
        face_source = np.empty(nf, dtype=np.uint32)
        check(lib().tp_mesh_copy_sources(self.pointer, as_pointer(vertex_source, c_uint32), nv, as_pointer(face_source, c_uint32), nf))
        return vertex_source.astype(np.int64), face_source.astype(np.int64)

    def counts(self):
        """``(vertex_count, face_count, index_count)``."""
        nv, nf, ni = c_size_t(), c_size_t(), c_size_t()
        check(lib().tp_mesh_counts(self.pointer, ctypes.byref(nv), ctypes.byref(nf), ctypes.byref(ni)))
        return nv.value, nf.value, ni.value

    def arrays(self):
        """``(vertices (V, 3) float64, indices (I,) uint32, sizes (F,) uint32)``."""
        nv, nf, ni = self.counts()
        vertices = np.empty((nv, 3), dtype=np.float64)
        indices = np.empty(ni, dtype=np.uint32)
        sizes = np.empty(nf, dtype=np.uint32)
        check(lib().tp_mesh_copy_vertices(self.pointer, as_pointer(vertices, c_double), vertices.size))
        check(lib().tp_mesh_copy_faces(self.pointer, as_pointer(indices, c_uint32), ni, as_pointer(sizes, c_uint32), nf))
        return vertices, indices, sizes

    def remesh(self, options, progress=None):
        """``tp_remesh``: the quad mesh as a new :class:`MeshHandle`."""
        out = TpMeshP()
        bridge = ProgressBridge(progress)
        status = lib().tp_remesh(self.pointer, ctypes.byref(options), bridge.callback, None, ctypes.byref(out))
        if status == TP_OK and out:
            result = MeshHandle(out)
        else:
            result = None
            if out:  # never expected: the library leaves *out alone on failure
                lib().tp_mesh_free(out)
        bridge.finish(status)
        return result

    def solve(self, options, progress=None):
        """``tp_pattern_solve``: a new :class:`PatternHandle`."""
        out = TpPatternP()
        bridge = ProgressBridge(progress)
        status = lib().tp_pattern_solve(self.pointer, ctypes.byref(options), bridge.callback, None, ctypes.byref(out))
        if status == TP_OK and out:
            result = PatternHandle(out)
        else:
            result = None
            if out:
                lib().tp_pattern_free(out)
        bridge.finish(status)
        return result


    def run(self, remesh, pattern, tiles, run, progress=None):
        """``tp_run`` on this surface: the whole pipeline on up to three quad meshes,
        keeping the tiles that fit best.

        Parameters
        ----------
        remesh, pattern, tiles, run : TpRemeshOptions, TpPatternOptions, TpTileOptions, TpRunOptions
        progress : callable, optional
            Hears ``"run"`` and the share of the whole run; may cancel it
            (:class:`CancelledError`, nothing handed out).

        Returns
        -------
        tuple of (MeshHandle, PatternHandle, TilesHandle)
            The kept quad mesh, its pattern and the tiles.
        """
        quads, solved, placed = TpMeshP(), TpPatternP(), TpTilesP()
        bridge = ProgressBridge(progress)
        status = lib().tp_run(
            self.pointer,
            ctypes.byref(remesh),
            ctypes.byref(pattern),
            ctypes.byref(tiles),
            ctypes.byref(run),
            bridge.callback,
            None,
            ctypes.byref(quads),
            ctypes.byref(solved),
            ctypes.byref(placed),
        )
        # Own whatever was handed out (all three on success, nothing on failure) before
        # anything can raise, so that each is freed exactly once.
        handles = [
            cls(pointer) if pointer else None
            for cls, pointer in ((MeshHandle, quads), (PatternHandle, solved), (TilesHandle, placed))
        ]
        try:
            bridge.finish(status)
            if None in handles:  # never expected: TP_OK hands out all three
                raise error(TP_PANIC, "tp_run returned TP_OK without its results")
        except BaseException:
            for handle in handles:
                if handle is not None:
                    handle.close()
            raise
        return tuple(handles)


class PatternHandle(Handle):
    """A solved native pattern (``TpPattern``)."""

    kind = "pattern"

    def __init__(self, pointer):
        super().__init__(pointer, lib().tp_pattern_free)

    def summary(self):
        """The :class:`TpPatternSummary`."""
        summary = TpPatternSummary()
        check(lib().tp_pattern_summary(self.pointer, ctypes.byref(summary)))
        return summary

    def bound_source(self):
        """Which argument proved the bound (``TP_BOUND_*``)."""
        source = c_int32()
        check(lib().tp_pattern_bound_source(self.pointer, ctypes.byref(source)))
        return source.value

    def pairs(self, count=None):
        """Matched pairs as an ``(P, 2)`` uint32 array."""
        count = self.summary().pairs if count is None else count
        out = np.empty((count, 2), dtype=np.uint32)
        check(lib().tp_pattern_copy_pairs(self.pointer, as_pointer(out, c_uint32), out.size))
        return out

    def unpaired(self, count=None):
        """Unpaired quads as a ``(U,)`` uint32 array."""
        count = self.summary().unpaired if count is None else count
        out = np.empty(count, dtype=np.uint32)
        check(lib().tp_pattern_copy_unpaired(self.pointer, as_pointer(out, c_uint32), out.size))
        return out

    def build_tiles(self, mesh, options, surface=None, progress=None):
        """``tp_tiles_build_with_progress``: a new :class:`TilesHandle`.

        ``surface`` (a :class:`MeshHandle` or ``None``: the quad mesh's own boundary) is
        what the tiles are cut to; ``progress`` hears the fit stage (``"tiles"``) and may
        cancel it (:class:`CancelledError`, no tiles).
        """
        out = TpTilesP()
        bridge = ProgressBridge(progress)
        status = lib().tp_tiles_build_with_progress(
            mesh.pointer,
            self.pointer,
            None if surface is None else surface.pointer,
            ctypes.byref(options),
            bridge.callback,
            None,
            ctypes.byref(out),
        )
        if status == TP_OK and out:
            result = TilesHandle(out)
        else:
            result = None
            if out:  # never expected: the library leaves *out alone on failure
                lib().tp_tiles_free(out)
        bridge.finish(status)
        return result


class TilesHandle(Handle):
    """Placed native tiles (``TpTiles``)."""

    kind = "tiles"

    def __init__(self, pointer):
        super().__init__(pointer, lib().tp_tiles_free)

    def count(self):
        """The number of tiles."""
        n = c_size_t()
        check(lib().tp_tiles_count(self.pointer, ctypes.byref(n)))
        return n.value

    def _copy(self, name, shape, dtype, ctype):
        out = np.empty(shape, dtype=dtype)
        check(getattr(lib(), name)(self.pointer, as_pointer(out, ctype), out.size))
        return out

    def kinds(self, n):
        """``TP_TILE_*`` per tile, ``(n,)`` int32."""
        return self._copy("tp_tiles_copy_kinds", n, np.int32, c_int32)

    def corners(self, n):
        """``(n, 8, 3)`` box corners."""
        return self._copy("tp_tiles_copy_corners", (n, 8, 3), np.float64, c_double)

    def frames(self, n):
        """``(n, 4, 3)``: origin, x (length), y (width), z (thickness) axes."""
        return self._copy("tp_tiles_copy_frames", (n, 4, 3), np.float64, c_double)

    def sizes(self, n):
        """``(n, 3)``: length, width, thickness."""
        return self._copy("tp_tiles_copy_sizes", (n, 3), np.float64, c_double)

    def faces(self, n):
        """``(n, 2)`` uint32 faces under each tile, ``TP_NO_FACE`` where none."""
        return self._copy("tp_tiles_copy_faces", (n, 2), np.uint32, c_uint32)

    def steps(self, n):
        """``(n,)`` uint32 laying steps."""
        return self._copy("tp_tiles_copy_steps", n, np.uint32, c_uint32)

    def kept_fractions(self, n):
        """``(n,)`` kept area over face area."""
        return self._copy("tp_tiles_copy_kept_fractions", n, np.float64, c_double)

    def joint_deviations(self, n):
        """``(n,)``: each tile's worst joint, the largest ``|gap - joint|`` of the joints it
        takes part in (0 for a tile with none), in model units."""
        return self._copy("tp_tiles_copy_joint_deviations", n, np.float64, c_double)

    def outline_counts(self):
        """``(loops, points)`` over all tiles."""
        loops, points = c_size_t(), c_size_t()
        check(lib().tp_tiles_outline_counts(self.pointer, ctypes.byref(loops), ctypes.byref(points)))
        return loops.value, points.value

    def outlines(self, n):
        """Per tile, the list of its outline loops as ``(k, 2)`` arrays in its frame."""
        loops, points = self.outline_counts()
        loop_counts = self._copy("tp_tiles_copy_loop_counts", n, np.uint32, c_uint32)
        loop_sizes = self._copy("tp_tiles_copy_loop_sizes", loops, np.uint32, c_uint32)
        xy = self._copy("tp_tiles_copy_loop_points", (points, 2), np.float64, c_double)
        ends = np.cumsum(loop_sizes, dtype=np.int64)
        loop_arrays = [xy[e - s : e] for s, e in zip(loop_sizes.astype(np.int64), ends)]
        result, at = [], 0
        for c in loop_counts.astype(np.int64):
            result.append(loop_arrays[at : at + c])
            at += c
        return result

    def report_json(self):
        """The report as a JSON string."""
        return _text(lib().tp_tiles_report_json, self.pointer)

    def labels(self):
        """The cut-list label of every tile, as a list of str."""
        return _text(lib().tp_tiles_labels, self.pointer).splitlines()

    def cutlist_json(self):
        """The cut list as a JSON string."""
        return _text(lib().tp_tiles_cutlist_json, self.pointer)

    def warnings(self):
        """The warnings as a list of ``(code name, message)``."""
        count = c_size_t()
        check(lib().tp_tiles_warning_count(self.pointer, ctypes.byref(count)))
        codes = self._copy("tp_tiles_copy_warning_codes", count.value, np.int32, c_int32)
        messages = _text(lib().tp_tiles_warnings, self.pointer).splitlines()
        return [(WARNING_NAMES.get(int(c), str(int(c))), m) for c, m in zip(codes, messages)]


def version():
    """The native library's version string, e.g. ``"0.1.0"``."""
    return lib().tp_version().decode("ascii")


def abi_version():
    """The ABI version of the loaded library (:data:`ABI_VERSION` when it loaded)."""
    return lib().tp_abi_version()
