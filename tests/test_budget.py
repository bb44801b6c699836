"""tilekit.budget: CPU-time budgets, and the SAT layer and the polyform classification under them."""

import contextlib
import doctest
import math
import multiprocessing
import threading
import time

import pytest
from test_sat import _hard_cnf  # the pigeonhole formula, unsatisfiable and hard for CDCL

import tilekit.budget
from tilekit.budget import WALL_FACTOR, Budget, thread_cpu_clock
from tilekit.errors import ParameterError
from tilekit.sat import IncrementalSolver, solve


def _busy(seconds: float) -> None:
    """Use about ``seconds`` of this thread's CPU."""
    clock = thread_cpu_clock()
    start = clock()
    while clock() - start < seconds:
        sum(range(1000))


def _spin() -> None:
    while True:
        pass


@contextlib.contextmanager
def cpu_hogs(n: int):
    """``n`` processes spinning on the CPU while the block runs (killed after it, by their pids)."""
    ctx = multiprocessing.get_context("fork")
    procs = [ctx.Process(target=_spin, daemon=True) for _ in range(n)]
    for p in procs:
        p.start()
    try:
        yield
    finally:
        for p in procs:
            p.kill()
            p.join()


def test_doctests():
    assert doctest.testmod(tilekit.budget).failed == 0


def test_a_busy_loop_charges_cpu_and_a_sleep_does_not():
    b = Budget(10)
    _busy(0.2)
    assert 0.2 <= b.used() <= b.elapsed() + 0.02
    before = b.used()
    time.sleep(0.3)
    assert b.used() - before < 0.05
    assert b.remaining() == pytest.approx(10 - b.used(), abs=0.01)


def test_another_threads_work_is_not_charged():
    """The budget counts the thread that made it: a busy thread beside it costs it nothing."""
    b = Budget(10)
    worker = threading.Thread(target=_busy, args=(0.3,))
    worker.start()
    worker.join()
    assert b.used() < 0.05


def test_a_budget_is_read_from_another_thread():
    """The watchdog reads the solving thread's clock from its own thread."""
    b = Budget(10)
    _busy(0.2)
    seen = []
    t = threading.Thread(target=lambda: seen.append(b.used()))
    t.start()
    t.join()
    assert 0.2 <= seen[0] <= b.used()


def test_the_wall_clock_cap_ends_a_sleeping_budget():
    b = Budget(0.05)
    assert b.wall == pytest.approx(0.05 * WALL_FACTOR)
    start = time.monotonic()
    while not b.spent():
        time.sleep(0.01)
        assert time.monotonic() - start < 5, "the wall-clock cap did not end the budget"
    assert b.used() < 0.05 <= b.wall <= time.monotonic() - start
    assert str(b) == "0.05 CPU seconds, stopped by its wall-clock cap of 0.5 s"
    assert str(Budget(120)) == "120 CPU seconds"


def test_share_splits_and_charges_reach_the_parent():
    b = Budget(10)
    s = b.share(0.25)
    assert 2.4 < s.cpu <= 2.5 and s.wall <= 0.25 * b.wall
    s.charge(3.0)  # a forked solver's CPU, charged to the share
    assert s.spent() and not b.spent()
    assert b.used() >= 3.0 and b.remaining() <= 7.0
    b.charge(10.0)
    rest = b.share(1.0)
    assert b.spent() and rest.spent() and rest.cpu == 0.0
    fresh = Budget(10)
    half = fresh.share(0.5)
    fresh.charge(9.9)  # the parent spent elsewhere: the share has at most what the parent has left
    assert half.remaining() <= 0.1 + 1e-9


@pytest.mark.parametrize("bad", [-1, math.nan, math.inf, "soon", None])
def test_a_bad_budget_is_one_line(bad):
    with pytest.raises(ParameterError, match="a CPU budget must be a") as e:
        Budget(bad)
    assert "\n" not in str(e.value)


@pytest.mark.parametrize("fraction", [0, -0.5, 1.5, math.nan])
def test_a_bad_share_is_one_line(fraction):
    with pytest.raises(ParameterError, match=r"share must be a fraction in \(0, 1\]"):
        Budget(1).share(fraction)


def test_of_takes_a_budget_a_number_or_none():
    b = Budget(3)
    assert Budget.of(b) is b and Budget.of(None) is None
    assert Budget.of(2.5).cpu == 2.5


@pytest.mark.parametrize("solver", ["minisat22", "cadical195"])
def test_a_solver_stops_when_its_budget_is_spent(solver):
    """MiniSat is interrupted in this thread; CaDiCaL solves in a forked child, killed when the
    budget charged with the child's own CPU seconds (read in clock ticks) is spent. (Glucose 4.1
    is left out: on this formula it checks for an interrupt only after a stretch of about
    1.4 CPU seconds that starts 0.4 CPU seconds in, measured.)"""
    b = Budget(0.4)
    answer = solve(_hard_cnf(), solver=solver, time_limit=b)
    assert answer.satisfiable is None
    assert 0.35 <= b.used() < 0.8, b  # the solve ran up to the budget, not past it
    assert answer.seconds < b.wall + 1


def test_a_spent_budget_answers_at_once_and_the_solver_stays_usable():
    spent = Budget(0.0)
    with IncrementalSolver(_hard_cnf(), solver="minisat22") as s:
        ans = s.solve(time_limit=spent)
        assert ans.satisfiable is None and ans.seconds < 0.1
        assert s.solve(assumptions=[1, -1]).satisfiable is False  # contradictory assumptions


def test_a_solver_budget_is_cpu_not_wall_under_load():
    """Beside two CPU hogs (on top of whatever else the machine runs) a 0.4 CPU-second budget
    still lets the solver use about 0.4 CPU seconds before it is interrupted."""
    with cpu_hogs(2):
        b = Budget(0.4)
        assert solve(_hard_cnf(), solver="minisat22", time_limit=b).satisfiable is None
    assert 0.35 <= b.used() < 0.8, b


def test_a_classification_verdict_is_the_same_under_load():
    """The 6-hex with Hc = Hh = 2 (Kaplan, arXiv:2105.09438, Table 3; tests/test_polyform_heesch.py)
    takes well under a CPU second to prove a non-tiler. Under a 2.5 CPU-second budget it is
    decided alone and beside three CPU hogs alike: on a 2-core machine the hogs stretch its wall
    time past what a wall-clock limit of that size allowed, but not its CPU time."""
    from tilekit.lattice import HEXAGONAL
    from tilekit.plugins.polyomino.classify import classify_form
    from tilekit.plugins.polyomino.model import Polyomino

    cells = Polyomino.parse("hex:0,0;3,0;6,0;-3,3;6,3;-6,6").cells
    classify_form(HEXAGONAL, cells, time_limit=None)  # warm-up: the compiled kernels load once
    alone = classify_form(HEXAGONAL, cells, time_limit=2.5)
    with cpu_hogs(3):
        b = Budget(2.5)
        loaded = classify_form(HEXAGONAL, cells, time_limit=b)
        used = b.used()
    assert (alone.tiles, alone.heesch, alone.heesch_holes) == ("false", 2, 2), alone.verdict
    assert (loaded.tiles, loaded.heesch, loaded.heesch_holes, loaded.verdict) == \
        (alone.tiles, alone.heesch, alone.heesch_holes, alone.verdict)
    assert used < 2.5
