"""step() releases the GIL.

1. While one thread is inside a long step(), the main thread keeps running Python: the longest
   pause between two of its loop iterations is far shorter than the step (with the GIL held it
   would be the whole step). This holds on one core too.
2. Two threads stepping two systems finish in less wall time than the same steps one after the
   other (loosely: < 0.9 x; the best of up to six tries). The machine is shared: each try also
   times two processes doing the same work, the speed-up the machine allows at that moment, and
   a try in which processes are not clearly faster either is inconclusive (skipped if all are).
   Needs two cores."""

import multiprocessing
import os
import threading
import time

import numpy as np
import pytest

import massspring as ms
from conftest import grid


def cloth(iterations):
    """A 40 x 40 cloth, two corners pinned, with a FastMassSpring solver ready to step."""
    points, springs = grid(40, 40, 0.025)
    s = ms.MassSpringSystem(points, springs, 0.01, 1000.0)
    s.pin([0, 39])
    s.add_force(ms.Gravity([0, -9.8, 0]))
    solver = ms.FastMassSpring()
    solver.options.iterations = iterations
    solver.precompute(s, 1 / 60)
    return s, solver


def test_python_runs_while_a_step_runs():
    s, solver = cloth(10)
    start = time.perf_counter()
    solver.step(s)
    one = time.perf_counter() - start
    solver.options.iterations = max(10, int(10 * 0.3 / one))  # one step of about 0.3 s
    done = threading.Event()
    took = []

    def work():
        t0 = time.perf_counter()
        assert solver.step(s).ok()
        took.append(time.perf_counter() - t0)
        done.set()

    thread = threading.Thread(target=work)
    longest, count = 0.0, 0
    thread.start()
    last = time.perf_counter()
    while not done.is_set():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
        count += 1
    thread.join()
    assert took[0] > 0.1
    assert longest < 0.5 * took[0], (longest, took[0], count)
    assert count > 1000


def _step_in_child(steps, go, times):
    """A forked process: its own cloth, stepped `steps` times after `go`; reports start and end."""
    s, solver = cloth(20)
    go.wait()
    t0 = time.perf_counter()  # CLOCK_MONOTONIC: comparable between processes
    for _ in range(steps):
        solver.step(s)
    times.put((t0, time.perf_counter()))


def _two_processes(steps):
    """Wall time of two processes stepping at once: what the machine allows two threads now."""
    ctx = multiprocessing.get_context("fork")
    go, times = ctx.Event(), ctx.Queue()
    children = [ctx.Process(target=_step_in_child, args=(steps, go, times)) for _ in range(2)]
    for c in children:
        c.start()
    time.sleep(0.2)  # both built their cloth
    go.set()
    spans = [times.get(timeout=120) for _ in children]
    for c in children:
        c.join()
    return max(e for _, e in spans) - min(b for b, _ in spans)


@pytest.mark.skipif(len(os.sched_getaffinity(0)) < 2, reason="needs two cores")
def test_two_threads_beat_one_after_the_other():
    """Two threads < 0.9 x one after the other. The machine is shared: when two processes doing
    the same work are not clearly faster (< 0.75 x), no second core is free and the try says
    nothing. The test passes on the first try that shows the threads' speed-up, fails when some
    try had a free core for processes but no try showed it for the threads, and is skipped when
    no try had a free core."""
    systems = [cloth(20), cloth(20)]

    def run(k, steps):
        s, solver = systems[k]
        for _ in range(steps):
            assert solver.step(s).ok()

    t0 = time.perf_counter()
    run(0, 10)
    steps = max(10, int(10 * 0.25 / (time.perf_counter() - t0)))  # about 0.25 s per system
    tries = []
    for _ in range(6):
        t0 = time.perf_counter()
        run(0, steps)
        run(1, steps)
        sequential = time.perf_counter() - t0
        threads = [threading.Thread(target=run, args=(k, steps)) for k in (0, 1)]
        t0 = time.perf_counter()
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        threaded = (time.perf_counter() - t0) / sequential
        processes = _two_processes(steps) / sequential
        tries.append((round(threaded, 3), round(processes, 3)))
        print(f"threaded / sequential {threaded:.3f}, processes / sequential {processes:.3f} "
              f"({steps} steps each)")
        if threaded < 0.9:
            break
    for s, _ in systems:
        assert np.isfinite(s.positions).all()
    if tries[-1][0] < 0.9:
        return
    if all(p >= 0.75 for _, p in tries):
        pytest.skip(f"no free second core on this machine now (two processes were not clearly "
                    f"faster either): (threads, processes) / sequential = {tries}")
    pytest.fail(f"two threads did not beat one after the other while two processes did: "
                f"(threads, processes) / sequential = {tries}")


def test_a_system_in_use_by_a_step_is_refused_elsewhere():
    """While a step runs without the GIL, the same system or solver used from another thread
    raises massspring.Error (instead of racing); other systems are free; afterwards all is free."""
    s, solver = cloth(10)
    start = time.perf_counter()
    solver.step(s)
    # About a second of step: far longer than the 50 ms sleep and the checks below, even on a
    # loaded machine (at 0.3 s, a step that ran alone on a core while the calibration shared one
    # ended before the checks).
    solver.options.iterations = max(10, int(10 * 1.0 / (time.perf_counter() - start)))
    other, other_solver = cloth(5)
    started, done = threading.Event(), threading.Event()

    def work():
        started.set()
        solver.step(s)
        done.set()

    thread = threading.Thread(target=work)
    thread.start()
    started.wait()
    time.sleep(0.05)  # inside the step
    refused = []
    for call in (lambda: solver.step(s), lambda: ms.FastMassSpring().step(s),
                 lambda: solver.step(other), lambda: s.positions, lambda: s.velocities,
                 lambda: s.set_positions(np.zeros((s.num_points, 3))),
                 lambda: s.pin(5), lambda: s.add_force(ms.LinearDrag(1.0)),
                 lambda: s.add_collider(ms.Collider.sphere([0, 0, 0], 1.0))):
        try:
            call()
        except ms.Error as e:
            refused.append("in use by a step in another thread" in str(e))
    busy = not done.is_set()
    assert other_solver.step(other).ok()  # another system and solver: free
    thread.join()
    print(f"busy {busy}, refused {refused}")
    if not busy:  # the step ended before the checks: the calls that changed s prove nothing
        pytest.skip(f"the step ended before the checks (refused {refused}): machine too loaded")
    assert refused == [True] * 9
    assert solver.step(s).ok() and s.positions.shape == (1600, 3)
    assert s.forces == ["gravity"] and s.num_colliders == 0 and s.pinned == [0, 39]
