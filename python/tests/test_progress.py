"""Progress callbacks: values, cancellation, exceptions raised inside them."""

import gc
import os
import time

import pytest

import tilepattern as tp

from meshes import grid, shell


@pytest.fixture(scope="module")
def big():
    """A 40 x 40 grid: large enough that a staggered solve takes its whole time limit."""
    return grid(40, 40)


@pytest.fixture(scope="module")
def surface():
    return shell(40, 32, edge=0.05)


def solver_threads():
    """Live solver worker threads of the library in this process (Linux; else 0)."""
    try:
        tasks = os.listdir("/proc/self/task")
    except OSError:
        return 0
    count = 0
    for task in tasks:
        try:
            with open("/proc/self/task/%s/comm" % task) as comm:
                # The worker's name, "tilepattern-solver", cut to Linux's 15 characters.
                count += comm.read().strip() == "tilepattern-sol"
        except OSError:
            pass
    return count


def solver_threads_once_exited(within=0.2):
    """Live solver worker threads once those the library has joined are gone from /proc.

    The library joins a stopped worker before it returns, but Linux wakes the joining thread
    when the worker's thread id is cleared, a moment before the exiting thread leaves
    /proc/self/task; counted at once, a worker already joined may still be listed (seen once
    in CI). A solver left running lasts seconds, far beyond `within`.
    """
    deadline = time.monotonic() + within
    while solver_threads() and time.monotonic() < deadline:
        time.sleep(0.005)
    return solver_threads()


@pytest.fixture(autouse=True)
def solver_idle():
    """After a test, wait for solver threads that a cancellation left running.

    A cancel stops CBC and Clp inside their solves and the library waits for them (see
    test_a_cancel_inside_cbc_returns_at_once_and_leaves_cbc_free); this only keeps a test
    that fails from holding up the next.
    """
    yield
    deadline = time.monotonic() + 10
    while solver_threads() and time.monotonic() < deadline:
        time.sleep(0.05)


def test_progress_is_reported(surface):
    v, f = surface
    seen = []
    tp.remesh(v, f, target_edge=0.145, progress=lambda stage, fraction: seen.append((stage, fraction)))
    assert len(seen) >= 3 and {s for s, _ in seen} == {"remesh"}
    fractions = [x for _, x in seen]
    assert fractions[0] == 0.0 and fractions[-1] == 1.0 and fractions == sorted(fractions)

    seen.clear()
    q = grid(6, 6)
    tp.match(*q, time_limit=5, progress=lambda stage, fraction: seen.append((stage, fraction)))
    assert seen and {s for s, _ in seen} == {"pattern"} and all(0.0 <= x <= 1.0 for _, x in seen)


def test_a_true_return_cancels_the_pattern_solve(big):
    seen = []

    def stop(stage, fraction):
        seen.append(fraction)
        return len(seen) >= 3

    start = time.perf_counter()
    with pytest.raises(tp.CancelledError) as caught:
        tp.match(*big, time_limit=1, progress=stop)
    assert caught.value.status == 8 and caught.value.name == "TP_CANCELLED"
    assert time.perf_counter() - start < 5  # "within about a second" of the request
    assert len(seen) == 3  # no further calls reach Python once cancelled


def test_a_true_return_cancels_the_remesh_midway(surface):
    v, f = surface
    seen = []

    def stop(stage, fraction):
        seen.append(fraction)
        return fraction >= 0.2

    with pytest.raises(tp.CancelledError):
        tp.remesh(v, f, target_edge=0.145, progress=stop)
    assert seen[-1] >= 0.2 and seen[-1] < 1.0


class Boom(Exception):
    pass


def test_an_exception_in_the_callback_cancels_and_is_raised_after(big):
    calls = []

    def broken(stage, fraction):
        calls.append(fraction)
        if len(calls) == 2:
            raise Boom("from the callback")

    start = time.perf_counter()
    with pytest.raises(Boom, match="from the callback") as caught:
        tp.match(*big, time_limit=1, progress=broken)
    assert time.perf_counter() - start < 5 and len(calls) == 2
    assert any(frame.name == "broken" for frame in caught.traceback)  # the original traceback

    def broken_remesh(stage, fraction):
        raise Boom("remesh")

    with pytest.raises(Boom):
        tp.remesh(*shell(20, 16, edge=0.1), progress=broken_remesh)


def test_keyboard_interrupt_in_the_callback_is_raised_after(big):
    def interrupted(stage, fraction):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        tp.match(*big, time_limit=1, progress=interrupted)


def test_the_callback_survives_garbage_collection_during_the_call(big):
    calls = []

    def collecting(stage, fraction):
        gc.collect()  # the ctypes callback object must stay alive meanwhile
        calls.append(fraction)
        return len(calls) >= 3

    with pytest.raises(tp.CancelledError):
        tp.match(*big, time_limit=1, progress=collecting)


def test_the_library_works_after_a_cancellation(big):
    with pytest.raises(tp.CancelledError):
        tp.match(*big, time_limit=1, progress=lambda stage, fraction: True)
    pattern = tp.match(*grid(4, 4), time_limit=5)
    assert len(pattern.pairs) == 8 and pattern.optimal


def small_mip():
    """The paper's whole program on CBC for a 12 x 12 grid; its time in seconds."""
    start = time.perf_counter()
    pattern = tp.match(*grid(12, 12), method="mip", time_limit=60)
    took = time.perf_counter() - start
    assert pattern.optimal, "status %s after %.2f s" % (pattern.status, took)
    return took


def test_a_cancel_inside_cbc_returns_at_once_and_leaves_cbc_free():
    """Cancel from the callback in the middle of the whole program on CBC (the paper's route;
    45 x 45 grid, 2025 faces, whose root linear program alone takes CBC seconds) returns within
    0.2 s, no solver thread is left running, and the next CBC solve takes as long as the same
    solve did before the cancel."""
    before = small_mip()
    start = time.perf_counter()
    asked = []

    def cancel_after_a_second(stage, fraction):
        # The callbacks of this solve come only while CBC runs.
        if time.perf_counter() - start < 1.0:
            return False
        asked.append(time.perf_counter())
        return True

    with pytest.raises(tp.CancelledError):
        tp.match(*grid(45, 45), method="mip", time_limit=60, progress=cancel_after_a_second)
    returned = time.perf_counter() - asked[0]
    assert len(asked) == 1
    assert returned < 0.2, "returned %.3f s after the callback asked" % returned
    assert solver_threads_once_exited() == 0
    after = small_mip()
    # Generous for a loaded machine; a CBC still busy with the cancelled solve would hold the
    # next one up for seconds.
    assert after < 2.0 * before + 0.25, "%.3f s after the cancel, %.3f s before" % (after, before)


def test_a_time_limit_inside_cbc_stops_it_and_leaves_cbc_free():
    """The same whole program on CBC with a 2 s limit, which falls in its root linear program
    (which CBC's own clock does not reach): the call keeps its limit, no solver thread is left
    running, and the next CBC solve takes as long as before."""
    before = small_mip()
    start = time.perf_counter()
    pattern = tp.match(*grid(45, 45), method="mip", time_limit=2)
    took = time.perf_counter() - start
    assert pattern.status == "time_limit" and took < 3.0, "%s after %.3f s" % (pattern.status, took)
    assert solver_threads_once_exited() == 0
    after = small_mip()
    assert after < 2.0 * before + 0.25, "%.3f s after the limit, %.3f s before" % (after, before)
