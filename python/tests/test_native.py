"""The ctypes layer against the C header: every export, struct, constant and status code;
library loading; handles."""

import copy
import ctypes
import gc
import os
import pickle
import re
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import tilepattern as tp
from tilepattern import _native as nat

from conftest import HEADER

needs_header = pytest.mark.skipif(not HEADER.is_file(), reason="not in a source checkout")


def _header_text():
    return HEADER.read_text()


def _strip_comments(text):
    return re.sub(r"/\*.*?\*/", "", re.sub(r"//[^\n]*", "", text), flags=re.S)


def _c_type(decl):
    """The ctypes type of a C declaration's type part, e.g. 'const struct TpMesh *'."""
    decl = " ".join(decl.replace("*", " * ").split())
    stars = decl.count("*")
    base = decl.replace("*", "").replace("const", "").replace("struct", "").split()
    base = " ".join(base)
    table = {
        "double": ctypes.c_double,
        "uint32_t": ctypes.c_uint32,
        "int32_t": ctypes.c_int32,
        "size_t": ctypes.c_size_t,
        "TpStatus": ctypes.c_int32,
        "TpWarning": ctypes.c_int32,
        "TpMesh": nat.TpMesh,
        "TpPattern": nat.TpPattern,
        "TpTiles": nat.TpTiles,
        "TpPatternOptions": nat.TpPatternOptions,
        "TpPatternSummary": nat.TpPatternSummary,
        "TpRemeshOptions": nat.TpRemeshOptions,
        "TpTileOptions": nat.TpTileOptions,
        "TpRunOptions": nat.TpRunOptions,
        "TpProgressCallback": nat.TpProgressCallback,
    }
    if base == "void":
        return {0: None, 1: ctypes.c_void_p}[stars]
    if base == "char":
        return {1: ctypes.c_char_p if decl.startswith("const") else ctypes.POINTER(ctypes.c_char)}[stars]
    t = table[base]
    for _ in range(stars):
        t = ctypes.POINTER(t)
    return t


def _prototypes():
    """{name: (return decl, [argument decls])} of the header's functions."""
    text = _strip_comments(_header_text())
    found = {}
    for ret, name, args in re.findall(r"^([A-Za-z_][\w ]*?\**)\s*\b(tp_\w+)\(([^)]*)\);", text, flags=re.M):
        parts = [a.strip() for a in args.split(",") if a.strip() and a.strip() != "void"]
        # drop the parameter name: the last identifier
        types = [re.sub(r"\b\w+$", "", p).strip() for p in parts]
        found[name] = (ret.strip(), types)
    return found


@needs_header
def test_every_export_is_bound_with_the_header_types():
    prototypes = _prototypes()
    assert len(prototypes) > 30
    assert set(prototypes) == set(nat.PROTOTYPES) | set(nat.OPTIONAL_PROTOTYPES)
    library = nat.lib()
    for name, (ret, args) in prototypes.items():
        restype, argtypes = (nat.PROTOTYPES.get(name) or nat.OPTIONAL_PROTOTYPES[name])
        expected = [_c_type(a) for a in args]
        assert argtypes == expected, name
        want = _c_type(ret)
        if want in (nat.TpPatternOptions, nat.TpRemeshOptions, nat.TpTileOptions):
            assert issubclass(restype, want) and restype is not want, name  # padded return
        else:
            assert restype == want, name
        if name in nat.PROTOTYPES:
            function = getattr(library, name)
            assert function.argtypes == argtypes and function.restype == restype, name


@needs_header
def test_struct_mirrors_match_the_header():
    text = _strip_comments(_header_text())
    structs = dict(re.findall(r"typedef struct (Tp\w+) \{(.*?)\} \1;", text, flags=re.S))
    assert set(structs) == {"TpPatternOptions", "TpPatternSummary", "TpRemeshOptions", "TpTileOptions", "TpRunOptions"}
    for name, body in structs.items():
        mirror = getattr(nat, name)
        fields = []
        for line in body.split(";"):
            line = " ".join(line.split())
            if not line:
                continue
            m = re.match(r"(.*?)(\w+)(\[(\d+)\])?$", line)
            ctype = _c_type(m.group(1))
            if m.group(4):
                ctype = ctype * int(m.group(4))
            fields.append((m.group(2), ctype))
        got = [(n, t) for n, t in mirror._fields_]
        assert [n for n, _ in got] == [n for n, _ in fields], name
        for (n, t), (_, want) in zip(got, fields):
            assert ctypes.sizeof(t) == ctypes.sizeof(want) and getattr(t, "_type_", t) == getattr(want, "_type_", want), (name, n)


@needs_header
def test_constants_and_status_codes_match_the_header():
    text = _header_text()
    defines = dict(re.findall(r"^#define (\w+) (\S+)$", text, flags=re.M))
    defines.pop("TILEPATTERN_H", None)
    assert defines, "no #define found"
    for name, value in defines.items():
        mine = nat.ABI_VERSION if name == "TP_ABI_VERSION" else getattr(nat, name)
        assert mine == (0xFFFFFFFF if value == "UINT32_MAX" else int(value)), name
    enums = dict(re.findall(r"^\s+(TP_\w+) = (\d+),$", text, flags=re.M))
    enum = {k: v for k, v in enums.items() if not k.startswith("TP_WARNING_")}
    assert len(enum) == 11
    assert {int(v): k for k, v in enum.items()} == nat.STATUS_NAMES
    warnings = {k: v for k, v in enums.items() if k.startswith("TP_WARNING_")}
    assert {int(v): k[len("TP_WARNING_"):].lower() for k, v in warnings.items()} == nat.WARNING_NAMES
    for name, value in enums.items():
        assert getattr(nat, name) == int(value)


def test_the_loaded_library_has_the_struct_sizes_of_the_mirrors():
    for default, struct in [
        ("tp_pattern_options_default", nat.TpPatternOptions),
        ("tp_remesh_options_default", nat.TpRemeshOptions),
        ("tp_tile_options_default", nat.TpTileOptions),
        ("tp_run_options_default", nat.TpRunOptions),
    ]:
        assert nat.native_struct_size(default) == ctypes.sizeof(struct), default
    assert nat.pattern_options().struct_size == ctypes.sizeof(nat.TpPatternOptions)
    assert nat.pattern_options().zone_count == 0 and not nat.pattern_options().zones
    assert nat.remesh_options().time_limit_seconds == 60.0
    assert nat.remesh_options().field_weight == 1.0 and nat.remesh_options().field_count == 0
    assert nat.remesh_options().guide_weight == 1.0 and nat.remesh_options().guide_count == 0
    assert nat.tile_options().length == 0.28
    assert nat.remesh_options().creases == 1 and nat.tile_options().creases == 1
    assert nat.remesh_options().renormalisation == 0.5
    assert nat.run_options().tries == 0 and nat.run_options().struct_size == ctypes.sizeof(nat.TpRunOptions) == 8
    # Returned by value in registers (8 bytes): bound unpadded, and it reads back right.
    assert nat.lib().tp_run_options_default().tries == 0
    assert tp.abi_version() == tp.ABI_VERSION == 10
    assert re.match(r"\d+\.\d+", tp.version())


@pytest.mark.parametrize("status", sorted(nat.STATUS_NAMES))
def test_every_status_code_maps_to_an_exception(status):
    if status == nat.TP_OK:
        assert nat.check(status) is None
        return
    cls = nat.error_class(status)
    assert issubclass(cls, tp.TilePatternError) and cls is not tp.TilePatternError and cls.code == status
    error = nat.error(status, "why")
    assert error.status == status and error.name == nat.STATUS_NAMES[status] and error.message == "why"
    assert nat.STATUS_NAMES[status] in str(error) and "why" in str(error)
    back = pickle.loads(pickle.dumps(error))
    assert type(back) is cls and back.status == status and back.message == "why"


def test_unknown_status_codes_still_raise():
    error = nat.error(99, "new")
    assert type(error) is tp.TilePatternError and error.name == "TP_UNKNOWN_99"
    with pytest.raises(tp.TilePatternError):
        nat.check(99)


def test_value_errors_are_value_errors():
    assert issubclass(tp.InvalidMeshError, ValueError)
    assert issubclass(tp.InvalidArgumentError, ValueError)
    assert issubclass(tp.LibraryNotFoundError, OSError) and issubclass(tp.LibraryNotFoundError, tp.NotAvailableError)


def _run(code, env, cwd):
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], env=env, cwd=str(cwd), capture_output=True, text=True, timeout=60)


def test_library_search_order(tmp_path):
    package = Path(tp.__file__).parent
    copy_dir = tmp_path / "site"
    shutil.copytree(package, copy_dir / "tilepattern", ignore=shutil.ignore_patterns("__pycache__", "*.so", "*.dylib", "*.dll"))
    env = {k: v for k, v in os.environ.items() if k not in ("TILEPATTERN_LIB", "CARGO_TARGET_DIR")}
    env["PYTHONPATH"] = str(copy_dir)
    probe = """
        import tilepattern as tp
        try:
            print(tp.library_path())
            print(tp.version())
        except tp.LibraryNotFoundError as e:
            print("ERROR", e.status, e.name, e)
    """
    # Nowhere: a clear error naming the places it looked at and the environment variable.
    out = _run(probe, env, tmp_path).stdout
    assert out.startswith("ERROR 9 TP_NOT_AVAILABLE") and "TILEPATTERN_LIB" in out and "target/release" in out, out
    # TILEPATTERN_LIB naming a missing file.
    out = _run(probe, dict(env, TILEPATTERN_LIB=str(tmp_path / "missing.so")), tmp_path).stdout
    assert out.startswith("ERROR 9") and "missing.so" in out, out
    # Next to the package.
    native = nat.library_path()
    shutil.copy(native, copy_dir / "tilepattern" / nat.library_file_names()[0])
    out = _run(probe, env, tmp_path).stdout.split()
    assert out[0] == str(copy_dir / "tilepattern" / nat.library_file_names()[0]) and out[1] == tp.version()
    # TILEPATTERN_LIB first.
    out = _run(probe, dict(env, TILEPATTERN_LIB=str(native)), tmp_path).stdout.split()
    assert out[0] == str(native)


def test_the_checkout_target_folder_is_a_candidate():
    assert Path(tp.__file__).resolve().parent.parent.parent / "target" / "release" / nat.library_file_names()[0] in nat.library_candidates()


class _CountingFree:
    def __init__(self, real=None):
        self.calls = 0
        self.real = real

    def __call__(self, pointer):
        self.calls += 1
        if self.real is not None:
            self.real(pointer)


def test_a_handle_is_freed_exactly_once():
    free = _CountingFree()
    handle = nat.Handle(object(), free)
    handle.close()
    handle.close()
    del handle
    gc.collect()
    assert free.calls == 1

    free = _CountingFree()
    with nat.Handle(object(), free) as handle:
        assert not handle.closed
    assert handle.closed and free.calls == 1
    with pytest.raises(ValueError, match="closed"):
        handle.pointer
    del handle
    gc.collect()
    assert free.calls == 1

    free = _CountingFree()
    nat.Handle(object(), free)  # dropped at once: freed by garbage collection
    gc.collect()
    assert free.calls == 1
    with pytest.raises(ValueError):
        nat.Handle(None, free)


def test_native_handles_free_once_and_refuse_use_after_close(quads):
    from tilepattern.core import mesh_handle

    handle = mesh_handle(*quads)
    counting = _CountingFree(handle._free)
    handle._free = counting
    assert handle.counts() == (99, 80, 320)
    handle.close()
    handle.close()
    assert counting.calls == 1
    with pytest.raises(ValueError):
        handle.counts()
    assert "closed" in repr(handle)
    assert copy.copy(handle) is handle and copy.deepcopy(handle) is handle
    with pytest.raises(TypeError):
        pickle.dumps(handle)


def test_null_pointers_and_small_buffers_raise_their_codes(quads):
    from tilepattern.core import mesh_handle

    library = nat.lib()
    with pytest.raises(tp.NullPointerError) as caught:
        nat.check(library.tp_mesh_counts(None, None, None, None))
    assert caught.value.name == "TP_NULL_POINTER"
    with mesh_handle(*quads) as mesh:
        buffer = (ctypes.c_double * 10)()
        with pytest.raises(tp.BufferTooSmallError) as caught:
            nat.check(library.tp_mesh_copy_vertices(mesh.pointer, buffer, 10))
        assert caught.value.status == 3 and "10" in caught.value.message
        options = nat.pattern_options()
        options.struct_size = 0
        out = nat.TpPatternP()
        with pytest.raises(tp.InvalidArgumentError, match="struct_size"):
            nat.check(library.tp_pattern_solve(mesh.pointer, ctypes.byref(options), nat.TpProgressCallback(), None, ctypes.byref(out)))
        assert not out


def test_a_panic_becomes_panic_error():
    library = nat.lib()
    if getattr(library, "tp_test_panic", None) is None:
        pytest.skip("tp_test_panic exists only in a test build of the library")
    with pytest.raises(tp.PanicError):
        nat.check(library.tp_test_panic())


def test_errors_are_per_thread(quads):
    import threading

    v, f = quads
    results = {}

    def worker(name, faces, expected):
        got = []
        for _ in range(50):
            try:
                tp.match(v, faces, time_limit=0)
            except tp.TilePatternError as error:
                got.append(expected in error.message)
        results[name] = all(got) and len(got) == 50

    bad_index = [list(face) for face in f]
    bad_index[3][1] = 5000
    repeated = [list(face) for face in f]
    repeated[7][1] = repeated[7][0]
    threads = [
        threading.Thread(target=worker, args=("index", bad_index, "5000")),
        threading.Thread(target=worker, args=("repeat", repeated, "more than once")),
    ]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == {"index": True, "repeat": True}
