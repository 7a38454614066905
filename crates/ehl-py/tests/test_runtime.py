"""What Python users expect at run time: no memory growth, the GIL released (threads solve in
parallel), Ctrl-C stops a long solve promptly."""

import ctypes
import gc
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
import weakref
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import ehl
from conftest import example


def rss_bytes() -> int:
    """The resident memory, after handing the allocator's free memory back to the system
    (glibc's malloc_trim: without it the free memory of the solver threads' arenas makes the
    figure wander by +-5 MB from one loop to the next; with it, by about 1 MB)."""
    gc.collect()
    try:
        ctypes.CDLL(None).malloc_trim(0)
    except (OSError, AttributeError):
        pass  # not glibc
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def tiny() -> ehl.Case:
    c = ehl.Case.from_file(example("ehl_ball_on_glass.toml"))
    c.set("grid.nx", 32)
    c.set("grid.ny", 32)
    return c


def test_a_solution_is_freed_with_its_last_reference():
    """The Solution (and the library's solution it owns) goes when the last reference to it
    goes: the Solution itself, its array views, the frames' and snapshots' views. A view keeps
    its Solution alive while it exists."""
    sol = ehl.solve(tiny(), progress=False)
    views = [sol.pressure, sol.film, sol.deformation, sol.viscosity, sol.density]
    summary, text = sol.summary, repr(sol)
    assert summary["converged"] and "converged" in text
    ref = weakref.ref(sol)
    del sol
    gc.collect()
    assert ref() is not None, "the views keep the solution alive"
    assert all(np.isfinite(v).all() for v in views)
    del views
    gc.collect()
    assert ref() is None, "the solution outlived every reference to it"

    case = ehl.Case.from_file(example("ehl_thesis_ch3_single_pit.toml"))
    for k, v in (("grid.nx", 32), ("grid.ny", 32), ("output.animation", False),
                 ("output.snapshots", [0.0]), ("output.frames_every", 2),
                 ("motion.travel", {"from": -0.5e-3, "to": 0.5e-3, "steps": 6})):
        case.set(k, v)
    sol = ehl.solve(case, progress=False)
    frames, snapshots, timeline = sol.frames, sol.snapshots, sol.timeline
    assert len(frames) == 4 and len(snapshots) == 1 and len(timeline["step"]) == 7
    ref = weakref.ref(sol)
    del sol
    gc.collect()
    assert ref() is not None, "the frames' views keep the solution alive"
    del frames
    gc.collect()
    assert ref() is not None, "the snapshots' views keep the solution alive"
    del snapshots
    gc.collect()
    assert ref() is None, "the solution outlived its frames and snapshots"
    assert timeline["x_p_m"][0] == pytest.approx(-0.5e-3)  # copies: independent of it


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="needs /proc")
def test_repeated_solves_do_not_grow_memory():
    # Grids large enough for a leak to show: a dry 128 x 128 case (its Solution owns three
    # (ny, nx) float64 fields: pressure, film, deformation, 393 kB) and an EHL 64 x 64 one (five
    # fields, with viscosity and density, 164 kB). Measured: keeping the Solutions costs
    # 0.53-0.64 MiB a pair, the fields and little else. Three batches of 30 pairs: a leak of one
    # Solution per solve (a reference cycle, a view that never lets go of it) keeps at least
    # 30 * 557 kB = 16 MiB in *every* batch, and the test fails when even the batch that grew
    # least grew by half of that. The allocator's noise is not a leak: it comes once, not in
    # every batch. On this machine a batch grows by 0-3 MiB (`rss_bytes` trims the allocator's
    # free memory; the first solves add ~20 MB of per-thread arenas, hence the warm-up), but
    # one CI run saw a single batch of 50 pairs grow by 12.7 MiB, which a one-batch bound at a
    # third of the leak failed on. ~0.04 s a solve, ~8 s in all.
    dry = ehl.Case.from_file(example("dry_ball_on_flat.toml"))
    dry.set("grid.nx", 128)
    dry.set("grid.ny", 128)
    wet = tiny()
    wet.set("grid.nx", 64)
    wet.set("grid.ny", 64)
    fields = 3 * 128 * 128 * 8 + 5 * 64 * 64 * 8

    def once(case):
        sol = ehl.solve(case, progress=False)
        # touch everything a user would: views, the summary, the repr
        assert sol.pressure.sum() > 0 and sol.film.min() >= 0 and sol.deformation.max() > 0
        assert sol.summary["converged"]
        repr(sol)
        return weakref.ref(sol)

    for _ in range(20):  # warm up: allocator arenas, thread stacks, numpy
        once(dry), once(wet)
    pairs = 30
    leak = pairs * fields
    growths = []
    for _ in range(3):
        before = rss_bytes()
        refs = [once(case) for _ in range(pairs) for case in (dry, wet)]
        growths.append(rss_bytes() - before)
        assert all(r() is None for r in refs), "a Solution outlived the loop"
    mib = ", ".join(f"{g / 2**20:.2f}" for g in growths)
    print(f"resident memory grew by {mib} MiB in three batches of {2 * pairs} solves")
    assert min(growths) < leak / 2, (
        f"resident memory grew in every batch of {2 * pairs} solves ({mib} MiB; a leaked "
        f"Solution per solve: >= {leak / 2**20:.0f} MiB a batch)"
    )


def test_the_gil_is_released_while_solving():
    """A Python thread keeps running while another thread solves."""
    case = ehl.Case.from_file(example("ehl_thesis_ch3_single_pit.toml"))
    # 48 x 48: ~0.4 s here (32 x 32 took 0.19-0.2 s on this machine and on CI, under the
    # 0.2 s this test needs to see the other thread tick, so it skipped itself)
    case.set("grid.nx", 48)
    case.set("grid.ny", 48)
    case.set("output.animation", False)
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.005)

    t = threading.Thread(target=tick)
    start = time.perf_counter()
    t.start()
    try:
        ehl.solve(case, progress=False)
    finally:
        stop.set()
        t.join()
    took = time.perf_counter() - start
    if took < 0.2:
        # (a fast machine: the gaps of a 5 ms ticker could not tell a held GIL from a free one)
        pytest.skip(f"the solve took {took:.3f} s, too short to see the other thread tick")
    # with the GIL held by the solve the other thread would not tick at all: it ticks
    # throughout (largest gap well under the solve time)
    gaps = [b - a for a, b in zip(ticks, ticks[1:])]
    assert len(ticks) > 10 and max(gaps) < took / 2, (len(ticks), max(gaps), took)


# Run in a child with RAYON_NUM_THREADS=1: each solve then uses one core, as a user running
# solves from a thread pool would want, and two threads on the 2-core CI machine should take
# about half the time of one thread doing both. With the default (a rayon pool as wide as the
# machine in every solve) one solve already spreads its parallel loops over both cores, so two
# threads gain only the serial part of each solve, which would make the comparison depend on
# the machine rather than on the GIL.
PARALLEL = textwrap.dedent(
    """
    import sys, time, ehl
    from concurrent.futures import ThreadPoolExecutor
    def case(load):
        c = ehl.Case.from_file(sys.argv[1])
        for k, v in (("grid.nx", 32), ("grid.ny", 32), ("output.animation", False),
                     ("load.force", load)):
            c.set(k, v)
        return c
    cases = [case(8519.0), case(8000.0)]
    solve = lambda c: ehl.solve(c, progress=False)
    solve(cases[0])  # warm up
    best_serial, best_parallel = 1e9, 1e9
    for _ in range(3):  # interleaved, best of three: robust to a burst of other work
        t = time.perf_counter(); [solve(c) for c in cases]
        best_serial = min(best_serial, time.perf_counter() - t)
        t = time.perf_counter()
        with ThreadPoolExecutor(2) as ex:
            list(ex.map(solve, cases))
        best_parallel = min(best_parallel, time.perf_counter() - t)
    print(best_serial, best_parallel)
    """
)


def _spin(seconds: float) -> int:
    n, end = 0, time.perf_counter() + seconds
    while time.perf_counter() < end:
        n += 1
    return n


def free_cores_for_two() -> float:
    """How much of a second core two busy processes get: the work two processes do side by
    side over what one does alone (2.0 on an idle 2-core machine, 1.0 when another program
    keeps one core busy)."""
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(2) as ex:
        list(ex.map(_spin, [0.05, 0.05]))  # start both workers
        alone = ex.submit(_spin, 0.3).result()
        both = sum(ex.map(_spin, [0.3, 0.3]))
    return both / alone


# The least share of a second core at which the comparison still means something (see the
# bound in the test).
LEAST_CAPACITY = 1.25


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="needs two cores")
def test_two_threads_solve_two_cases_faster_than_one():
    before = free_cores_for_two()
    if before < LEAST_CAPACITY:
        pytest.skip(
            f"two processes get only {before:.2f} cores here (other programs keep the "
            f"machine busy; {LEAST_CAPACITY} needed): two threads could not gain enough over "
            "one to tell a released GIL from a held one"
        )
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    r = subprocess.run(
        [sys.executable, "-c", PARALLEL, str(example("ehl_thesis_ch3_single_pit.toml"))],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    assert r.returncode == 0, r.stderr
    serial, parallel = map(float, r.stdout.split())
    # the load of the other programs drifts: measure again, and take the smaller of the two
    capacity = min(before, free_cores_for_two())
    # The bound. With the GIL released two threads on `capacity` free cores take serial /
    # capacity at best; with it held they take turns and need at least `serial`. The bound
    # asks for half of the ideal gain, serial * (1 + 1/capacity) / 2 (0.75 serial on two
    # free cores), times 1.15 for what best-of-three runs do not absorb: the capacity is
    # measured before and after the solves, not during them, and the other sessions' load
    # changes within seconds. It never exceeds 0.95 serial: at or above `serial` the test
    # could not fail with the GIL held (on 1.25 to 1.35 free cores the cap applies, and a
    # released GIL still gives ~0.8 serial there).
    bound = serial * min(1.15 * (1 + 1 / capacity) / 2, 0.95)
    print(
        f"{capacity:.2f} free cores: one thread {serial:.3f} s, two threads {parallel:.3f} s "
        f"(bound {bound:.3f} s)"
    )
    if capacity < LEAST_CAPACITY:
        pytest.skip(
            f"the machine got busier during the test ({capacity:.2f} free cores after it; "
            f"{LEAST_CAPACITY} needed): one thread {serial:.3f} s, two {parallel:.3f} s"
        )
    assert parallel < bound, (capacity, serial, parallel, bound)


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals")
def test_sigint_stops_a_long_solve_promptly():
    case = ehl.Case.from_file(example("ehl_thesis_ch3_single_pit.toml"))
    case.set("grid.nx", 64)
    case.set("grid.ny", 64)
    case.set("motion.travel", {"from": -1.0e-3, "to": 1.0e-3, "steps": 2000})  # ~20 s
    sent = []
    main = threading.main_thread().ident

    def interrupt():
        sent.append(time.perf_counter())
        signal.pthread_kill(main, signal.SIGINT)  # as Ctrl-C: SIGINT to the main thread

    # Python raises KeyboardInterrupt on SIGINT only when SIGINT was not ignored at its start;
    # a shell ignores it in background jobs (`./test.sh &`, some CI runners): put the handler
    # of an interactive Python (a terminal, Jupyter) in place for this test
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, interrupt)
    start = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            sol = ehl.solve(case, progress=False)
            pytest.fail(f"the solve ended after {time.perf_counter() - start:.2f} s without an "
                        f"interrupt (SIGINT sent at {[t - start for t in sent]} s): {sol!r}")
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    late = time.perf_counter() - sent[0]
    assert late < 1.0, f"KeyboardInterrupt came {late:.2f} s after SIGINT"
    # the next solve works
    assert ehl.solve(tiny(), progress=False).converged


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals")
def test_sigint_during_write_leaves_the_folder_complete_or_absent(tmp_path):
    """`Solution.write` is not interruptible (documented): Ctrl-C during it raises
    KeyboardInterrupt once it has ended. Either way the folder is complete or absent, and
    nothing else (no temporary folder) is left beside it."""
    case = ehl.Case.from_file(example("ehl_thesis_ch3_single_pit.toml"))
    for k, v in (("grid.nx", 48), ("grid.ny", 48),
                 ("motion.travel", {"from": -1.0e-3, "to": 1.0e-3, "steps": 20})):
        case.set(k, v)
    sol = ehl.solve(case, progress=False)
    start = time.perf_counter()
    whole = sol.write(tmp_path / "whole")  # an uninterrupted write, to compare with
    took = time.perf_counter() - start
    if took < 0.2:
        pytest.skip(f"a write takes {took:.3f} s here, too short to interrupt")
    expected = sorted(p.name for p in whole.iterdir())
    sent = []
    main = threading.main_thread().ident

    def interrupt():
        sent.append(time.perf_counter())
        signal.pthread_kill(main, signal.SIGINT)

    out = tmp_path / "out"
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(took / 4, interrupt)
    caught = None
    start = time.perf_counter()
    timer.start()
    try:
        sol.write(out)
        time.sleep(5)  # the interrupt lands in the write or, at the latest, here
        pytest.fail("no KeyboardInterrupt")
    except KeyboardInterrupt:
        caught = time.perf_counter()
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert sent, "no SIGINT was sent"
    print(f"write {took:.2f} s; SIGINT at {sent[0] - start:.2f} s, "
          f"KeyboardInterrupt at {caught - start:.2f} s")
    if out.exists():
        assert sorted(p.name for p in out.iterdir()) == expected, "a half-written folder"
    assert sorted(p.name for p in tmp_path.iterdir()) in (["out", "whole"], ["whole"]), (
        "something was left beside the output folder"
    )


def test_cancel_all_stops_a_solve_in_a_worker_thread():
    """Ctrl-C reaches the main thread only: `ehl.cancel_all()` stops the solves of worker
    threads (the pattern `except KeyboardInterrupt: ehl.cancel_all(); raise`)."""
    case = ehl.Case.from_file(example("ehl_thesis_ch3_single_pit.toml"))
    case.set("grid.nx", 64)
    case.set("grid.ny", 64)
    case.set("motion.travel", {"from": -1.0e-3, "to": 1.0e-3, "steps": 2000})  # ~20 s
    running = [threading.Event(), threading.Event()]
    with ThreadPoolExecutor(2) as ex:
        futures = [
            ex.submit(ehl.solve, case, progress=lambda f, m, e=e: e.set()) for e in running
        ]
        assert all(e.wait(60) for e in running), "the solves did not start"
        time.sleep(0.2)
        start = time.perf_counter()
        n = ehl.cancel_all()
        for f in futures:
            with pytest.raises(KeyboardInterrupt):
                f.result(timeout=30)
        late = time.perf_counter() - start
    assert n == 2, f"cancel_all found {n} running solves"
    assert late < 1.0, f"the solves stopped {late:.2f} s after cancel_all"
    assert ehl.cancel_all() == 0, "a finished solve stayed in the registry"
    # solves started later are not affected
    assert ehl.solve(tiny(), progress=False).converged
