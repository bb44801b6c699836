"""tilekit.sat: the shared SAT layer (CNF, cardinality, incremental solving, time limits)."""

import doctest
import itertools

import pytest

import tilekit.sat
from tilekit.errors import ParameterError
from tilekit.sat import CNF, IncrementalSolver, solve


def test_doctests():
    assert doctest.testmod(tilekit.sat).failed == 0


@pytest.mark.parametrize(("encoding", "k"), [
    *((e, k) for e in ("seqcounter", "totalizer", "sortnetwrk") for k in (0, 1, 2, 4)),
    ("pairwise", 1),  # the pairwise encoding exists for at-most-one only
])
def test_cardinality_counts_match_binomials(encoding, k):
    # exactly k of 5 variables: C(5, k) models over the original variables
    cnf = CNF()
    xs = list(cnf.new_vars(5))
    cnf.exactly(xs, k, encoding=encoding)
    count = 0
    for bits in itertools.product((False, True), repeat=5):
        assumptions = [x if b else -x for x, b in zip(xs, bits)]
        count += bool(solve(cnf, assumptions).satisfiable)
    assert count == len(list(itertools.combinations(range(5), k)))


def test_pigeonhole_is_unsatisfiable_with_every_solver():
    # 4 pigeons, 3 holes
    cnf = CNF()
    p = {(i, h): cnf.new_var() for i in range(4) for h in range(3)}
    for i in range(4):
        cnf.add([p[i, h] for h in range(3)])
    for h in range(3):
        cnf.at_most([p[i, h] for i in range(4)], 1)
    for solver in ("cadical195", "glucose4", "minisat22"):
        assert solve(cnf, solver=solver).satisfiable is False


def test_incremental_solver_keeps_clauses_between_questions():
    cnf = CNF()
    a, b = cnf.new_vars(2)
    cnf.add([a, b])
    with IncrementalSolver(cnf) as s:
        assert s.solve([-a]).value(b)
        s.add([-b])
        assert s.solve([-a]).satisfiable is False
        assert s.solve().value(a)
        assert s.calls == 3


def _hard_cnf(n=11):
    # pigeonhole n+1 into n: exponential for resolution-based solvers
    cnf = CNF()
    p = {(i, h): cnf.new_var() for i in range(n + 1) for h in range(n)}
    for i in range(n + 1):
        cnf.add([p[i, h] for h in range(n)])
    for h in range(n):
        for i, j in itertools.combinations(range(n + 1), 2):
            cnf.add([-p[i, h], -p[j, h]])
    return cnf


@pytest.mark.parametrize("solver", ["cadical195", "glucose4"])
def test_time_limit_gives_no_answer(solver):
    answer = solve(_hard_cnf(), solver=solver, time_limit=0.3)
    assert answer.satisfiable is None
    assert answer.seconds < 5


def test_incremental_time_limit_in_a_child_leaves_the_solver_usable():
    cnf = _hard_cnf()
    with IncrementalSolver(cnf, solver="cadical195") as s:
        assert s.solve(time_limit=0.3).satisfiable is None
        assert s.solve([-1, 1]).satisfiable is False


def test_bad_inputs_name_what_is_valid():
    with pytest.raises(ParameterError, match="not supported; choose one of"):
        solve(CNF(), solver="nope")
    with pytest.raises(ParameterError, match="cardinality encoding"):
        CNF().at_most([1, 2], 1, encoding="nope")
    with pytest.raises(ParameterError, match="non-zero"):
        CNF().add([1, 0])


def test_gc_paused_restores_the_collector_and_nests():
    import gc

    from tilekit.sat import gc_paused

    assert gc.isenabled()
    with gc_paused():
        assert not gc.isenabled()
        with gc_paused():
            assert not gc.isenabled()
        assert not gc.isenabled()  # the inner exit keeps the outer pause
    assert gc.isenabled()
    try:
        with gc_paused():
            raise KeyError("x")
    except KeyError:
        pass
    assert gc.isenabled()  # restored on an exception too
    gc.disable()
    try:
        with gc_paused():
            pass
        assert not gc.isenabled()  # a collector that was off stays off
    finally:
        gc.enable()


def test_cryptominisat_takes_blocks_and_answers_like_the_others():
    """CryptoMiniSat 5 (pycryptosat, the ``cms`` extra) gets a CNF's blocks as flat buffers:
    the pigeonhole formula (4 into 3) is unsatisfiable, the 3-into-3 one has exactly the 3! =
    6 permutation models, and an incremental solver keeps its clauses."""
    pytest.importorskip("pycryptosat")
    import numpy as np

    def pigeons(m, n):
        cnf = CNF()
        p = np.arange(1, m * n + 1).reshape(m, n)
        cnf.reserve(m * n)
        cnf.add_block(p)  # each pigeon in some hole, as one block
        pairs = np.array([(-p[i, h], -p[j, h]) for h in range(n) for i, j in itertools.combinations(range(m), 2)])
        cnf.add_block(pairs)
        return cnf, p

    cnf, _ = pigeons(4, 3)
    assert solve(cnf, solver="cryptominisat5").satisfiable is False
    cnf, p = pigeons(3, 3)
    cnf.add_block(np.array([[-p[i, h], -p[i, g]] for i in range(3) for h, g in itertools.combinations(range(3), 2)]))
    models = 0
    with IncrementalSolver(cnf, solver="cryptominisat5") as s:
        while True:
            ans = s.solve()
            if not ans.satisfiable:
                break
            truth = ans.values(p.ravel())
            assert truth.reshape(3, 3).sum(axis=0).tolist() == [1, 1, 1]  # a permutation
            models += 1
            s.add([-int(v) for v in p.ravel()[truth]])
        # an assumption on a variable no clause mentions is no obstacle
        assert s.solve(assumptions=[1000]).satisfiable is False
    assert models == 6


def test_time_limited_solves_share_one_watchdog_thread():
    """A time limit interrupts a hard formula, and 50 time-limited solves start no thread each
    (one shared watchdog); a solve after an interrupted one answers normally."""
    import threading

    with IncrementalSolver(_hard_cnf(), solver="gluecard4") as hard, \
            IncrementalSolver([[1, 2], [-1]], solver="gluecard4") as easy:
        assert hard.solve(time_limit=0.3).satisfiable is None
        before = threading.active_count()
        for _ in range(50):
            assert easy.solve(time_limit=60).satisfiable is True
        assert threading.active_count() <= before
        assert hard.solve(time_limit=0.2).satisfiable is None
        assert easy.solve(time_limit=60).satisfiable is True


def test_atmost_groups_equal_one_at_a_time():
    """``CNF.add_atmost_groups`` gives the constraints ``add_atmost`` gives one by one; zero
    literals are refused."""
    import numpy as np

    flat, starts, extra = np.array([1, 2, 3, 4, 5, -6]), np.array([0, 2, 3]), np.array([-7, 8, 9])
    a, b = CNF(), CNF()
    a.add_atmost_groups(flat, starts, extra, 1)
    for lits in ([1, 2, -7], [3, 8], [4, 5, -6, 9]):
        b.add_atmost(lits, 1)
    assert a.atmosts == b.atmosts and a.top == b.top == 9
    with pytest.raises(ParameterError, match="non-zero"):
        CNF().add_atmost_groups(np.array([1, 0]), np.array([0]), np.array([3]))
