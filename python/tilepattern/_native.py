"""The C library through ctypes: loading, struct mirrors, every export, status checks.

Everything here mirrors ``include/tilepattern.h`` (ABI 2). The rest of the package calls
the library only through this module.
"""

import ctypes
import os
import sys
from ctypes import POINTER, c_char, c_char_p, c_double, c_int32, c_size_t, c_uint32, c_void_p
from pathlib import Path

ABI_VERSION = 2

STATUS_NAMES = {
    0: "TP_OK",
    1: "TP_NULL_POINTER",
    2: "TP_INVALID_ARGUMENT",
    3: "TP_BUFFER_TOO_SMALL",
    4: "TP_INVALID_MESH",
    5: "TP_INVALID_PATTERN",
    6: "TP_SOLVER_FAILED",
    7: "TP_TIME_LIMIT",
    8: "TP_CANCELLED",
    9: "TP_NOT_AVAILABLE",
    10: "TP_PANIC",
}

TP_STAGE_REMESH = 1
TP_STAGE_PATTERN = 2
BONDS = {"stack": 0, "staggered": 1, "running": 2, "running-bond": 2}
METHODS = {"auto": 0, "mip": 1}
FORMULATIONS = {"strengthened": 0, "paper": 1}
SOLVE_STATUS = {0: "optimal", 1: "time_limit", 2: "feasible"}
DIRECTIONS = {"curvature": 0, "vector": 1, "angle": 2}
TILE_KINDS = {0: "full", 1: "half", 2: "boundary"}
NO_FACE = 0xFFFFFFFF


class TilePatternError(Exception):
    """A call into the TilePattern library failed.

    Attributes
    ----------
    status : int
        The library's stable status code (``TP_*``).
    name : str
        The code's name, e.g. ``"TP_INVALID_MESH"``.
    message : str
        The library's explanation, naming the face or vertex at fault.
    """

    def __init__(self, status, message):
        self.status = status
        self.name = STATUS_NAMES.get(status, "TP_UNKNOWN_%d" % status)
        self.message = message
        super().__init__("%s: %s" % (self.name, message))


class _Mesh(ctypes.Structure):
    pass


class _Pattern(ctypes.Structure):
    pass


class _Tiles(ctypes.Structure):
    pass


class PatternOptions(ctypes.Structure):
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
    ]


class PatternSummary(ctypes.Structure):
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


class RemeshOptions(ctypes.Structure):
    _fields_ = [
        ("struct_size", c_uint32),
        ("target_edge", c_double),
        ("direction", c_int32),
        ("direction_vector", c_double * 3),
        ("angle_degrees", c_double),
        ("shapeup", c_int32),
    ]


class TileOptions(ctypes.Structure):
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
    ]


PROGRESS = ctypes.CFUNCTYPE(c_int32, c_void_p, c_uint32, c_double)

# name: (restype, argtypes). Every export of the header but tp_test_panic (test builds only).
_EXPORTS = {
    "tp_version": (c_char_p, []),
    "tp_abi_version": (c_uint32, []),
    "tp_last_error_message": (c_size_t, [POINTER(c_char), c_size_t]),
    "tp_mesh_new": (c_int32, [POINTER(c_double), c_size_t, POINTER(c_uint32), c_size_t, POINTER(c_uint32), c_size_t, POINTER(POINTER(_Mesh))]),
    "tp_mesh_free": (None, [POINTER(_Mesh)]),
    "tp_mesh_counts": (c_int32, [POINTER(_Mesh), POINTER(c_size_t), POINTER(c_size_t), POINTER(c_size_t)]),
    "tp_mesh_copy_vertices": (c_int32, [POINTER(_Mesh), POINTER(c_double), c_size_t]),
    "tp_mesh_copy_faces": (c_int32, [POINTER(_Mesh), POINTER(c_uint32), c_size_t, POINTER(c_uint32), c_size_t]),
    "tp_pattern_options_default": (PatternOptions, []),
    "tp_pattern_options_init": (c_int32, [POINTER(PatternOptions), c_size_t]),
    "tp_pattern_solve": (c_int32, [POINTER(_Mesh), POINTER(PatternOptions), PROGRESS, c_void_p, POINTER(POINTER(_Pattern))]),
    "tp_pattern_free": (None, [POINTER(_Pattern)]),
    "tp_pattern_summary": (c_int32, [POINTER(_Pattern), POINTER(PatternSummary)]),
    "tp_pattern_copy_pairs": (c_int32, [POINTER(_Pattern), POINTER(c_uint32), c_size_t]),
    "tp_pattern_copy_unpaired": (c_int32, [POINTER(_Pattern), POINTER(c_uint32), c_size_t]),
    "tp_remesh_options_default": (RemeshOptions, []),
    "tp_remesh_options_init": (c_int32, [POINTER(RemeshOptions), c_size_t]),
    "tp_remesh": (c_int32, [POINTER(_Mesh), POINTER(RemeshOptions), PROGRESS, c_void_p, POINTER(POINTER(_Mesh))]),
    "tp_tile_options_default": (TileOptions, []),
    "tp_tile_options_init": (c_int32, [POINTER(TileOptions), c_size_t]),
    "tp_tiles_build": (c_int32, [POINTER(_Mesh), POINTER(_Pattern), POINTER(TileOptions), POINTER(POINTER(_Tiles))]),
    "tp_tiles_build_on_surface": (c_int32, [POINTER(_Mesh), POINTER(_Pattern), POINTER(_Mesh), POINTER(TileOptions), POINTER(POINTER(_Tiles))]),
    "tp_tiles_free": (None, [POINTER(_Tiles)]),
    "tp_tiles_count": (c_int32, [POINTER(_Tiles), POINTER(c_size_t)]),
    "tp_tiles_copy_kinds": (c_int32, [POINTER(_Tiles), POINTER(c_int32), c_size_t]),
    "tp_tiles_copy_corners": (c_int32, [POINTER(_Tiles), POINTER(c_double), c_size_t]),
    "tp_tiles_copy_frames": (c_int32, [POINTER(_Tiles), POINTER(c_double), c_size_t]),
    "tp_tiles_copy_sizes": (c_int32, [POINTER(_Tiles), POINTER(c_double), c_size_t]),
    "tp_tiles_copy_faces": (c_int32, [POINTER(_Tiles), POINTER(c_uint32), c_size_t]),
    "tp_tiles_copy_steps": (c_int32, [POINTER(_Tiles), POINTER(c_uint32), c_size_t]),
    "tp_tiles_copy_kept_fractions": (c_int32, [POINTER(_Tiles), POINTER(c_double), c_size_t]),
    "tp_tiles_outline_counts": (c_int32, [POINTER(_Tiles), POINTER(c_size_t), POINTER(c_size_t)]),
    "tp_tiles_copy_loop_counts": (c_int32, [POINTER(_Tiles), POINTER(c_uint32), c_size_t]),
    "tp_tiles_copy_loop_sizes": (c_int32, [POINTER(_Tiles), POINTER(c_uint32), c_size_t]),
    "tp_tiles_copy_loop_points": (c_int32, [POINTER(_Tiles), POINTER(c_double), c_size_t]),
    "tp_tiles_labels": (c_int32, [POINTER(_Tiles), POINTER(c_char), c_size_t, POINTER(c_size_t)]),
    "tp_tiles_cutlist_json": (c_int32, [POINTER(_Tiles), POINTER(c_char), c_size_t, POINTER(c_size_t)]),
    "tp_tiles_report_json": (c_int32, [POINTER(_Tiles), POINTER(c_char), c_size_t, POINTER(c_size_t)]),
}


def _library_names():
    if sys.platform == "win32":
        return ["tilepattern.dll"]
    if sys.platform == "darwin":
        return ["libtilepattern.dylib"]
    return ["libtilepattern.so"]


def library_path():
    """Where the native library is found.

    In order: the ``TILEPATTERN_LIB`` environment variable (a full path), next to this
    package, the cargo target folder of a source checkout (``target/release``).

    Raises
    ------
    TilePatternError
        With status ``TP_NOT_AVAILABLE`` when it is nowhere.
    """
    explicit = os.environ.get("TILEPATTERN_LIB")
    if explicit:
        return Path(explicit)
    here = Path(__file__).resolve().parent
    candidates = [here / n for n in _library_names()]
    candidates += [here.parent.parent / "target" / "release" / n for n in _library_names()]
    for candidate in candidates:
        if candidate.is_file():
            return candidate
    raise TilePatternError(9, "the TilePattern library was not found; build it with `cargo build --release` or set TILEPATTERN_LIB (looked at %s)" % ", ".join(str(c) for c in candidates))


def _load():
    lib = ctypes.CDLL(str(library_path()))
    for name, (restype, argtypes) in _EXPORTS.items():
        function = getattr(lib, name)
        function.restype = restype
        function.argtypes = argtypes
    loaded = lib.tp_abi_version()
    if loaded != ABI_VERSION:
        raise TilePatternError(9, "the library has ABI version %d, this package needs %d" % (loaded, ABI_VERSION))
    return lib


_lib = None


def lib():
    """The loaded library (loaded on first use)."""
    global _lib
    if _lib is None:
        _lib = _load()
    return _lib


def last_error():
    """This thread's last error message from the library."""
    size = lib().tp_last_error_message(None, 0)
    buffer = ctypes.create_string_buffer(size + 1)
    lib().tp_last_error_message(buffer, size + 1)
    return buffer.value.decode("utf-8", "replace")


def check(status):
    """Raises :class:`TilePatternError` for a non-zero status."""
    if status != 0:
        raise TilePatternError(status, last_error())


def init(struct_type, init_name):
    """A options struct filled with the library's defaults."""
    options = struct_type()
    check(getattr(lib(), init_name)(ctypes.byref(options), ctypes.sizeof(options)))
    return options


def text(function, handle):
    """A string returned by one of the size-then-copy text functions."""
    needed = c_size_t(0)
    function(handle, None, 0, ctypes.byref(needed))
    buffer = ctypes.create_string_buffer(needed.value + 1)
    check(function(handle, buffer, needed.value + 1, None))
    return buffer.value.decode("utf-8")


class Handle:
    """Owns one native handle and frees it exactly once (``close``, ``with`` or garbage
    collection)."""

    _free = None

    def __init__(self, pointer):
        self._pointer = pointer

    @property
    def pointer(self):
        if self._pointer is None:
            raise ValueError("the handle was closed")
        return self._pointer

    def close(self):
        pointer, self._pointer = self._pointer, None
        if pointer is not None and _lib is not None:
            getattr(_lib, self._free)(pointer)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        self.close()


class MeshHandle(Handle):
    _free = "tp_mesh_free"


class PatternHandle(Handle):
    _free = "tp_pattern_free"


class TilesHandle(Handle):
    _free = "tp_tiles_free"


def new_handle(kind):
    """A NULL out-pointer for a handle of ``kind`` (``_Mesh``, ``_Pattern`` or ``_Tiles``)."""
    return POINTER(kind)()
