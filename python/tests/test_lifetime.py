"""Native handles behind results: closing, context managers, garbage collection."""

import copy
import gc
import pickle
import weakref

import pytest

import tilepattern as tp


def test_close_twice_is_safe(quads):
    v, f = quads
    pattern = tp.match(v, f, time_limit=1)
    assert not pattern.closed
    free_calls = []
    real = pattern.handle._free
    pattern.handle._free = lambda pointer: (free_calls.append(1), real(pointer))
    pattern.close()
    pattern.close()
    assert pattern.closed and len(free_calls) == 1
    assert len(pattern.pairs) == 40  # the arrays stay
    with pytest.raises(ValueError, match="closed"):
        tp.tiles(v, f, pattern)
    del pattern
    gc.collect()
    assert len(free_calls) == 1


def test_with_block_closes(quads):
    v, f = quads
    with tp.match(v, f, time_limit=1) as pattern:
        placed = tp.tiles(v, f, pattern)
    assert pattern.closed and len(placed) == 40


def test_a_pattern_makes_tiles_any_number_of_times(quads):
    v, f = quads
    pattern = tp.match(v, f, time_limit=1)
    first = tp.tiles(v, f, pattern)
    second = tp.tiles(v, f, pattern, thickness=0.03)
    assert len(first) == len(second) and (first.faces == second.faces).all()


def test_dropped_patterns_are_collected(quads):
    v, f = quads
    pattern = tp.match(v, f, time_limit=1)
    handle = weakref.ref(pattern.handle)
    del pattern
    gc.collect()
    assert handle() is None


def test_copies_share_the_handle_and_pickling_is_refused(quads):
    v, f = quads
    pattern = tp.match(v, f, time_limit=1)
    shallow, deep = copy.copy(pattern), copy.deepcopy(pattern)
    assert shallow.handle is pattern.handle and deep.handle is pattern.handle
    assert deep.pairs is not pattern.pairs
    pattern.close()
    assert shallow.closed and deep.closed
    with pytest.raises(TypeError):
        pickle.dumps(pattern)
    # Tiles hold no native handle: they pickle.
    placed = tp.tiles(v, f, tp.match(v, f, time_limit=1))
    assert pickle.loads(pickle.dumps(placed)).labels == placed.labels
