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
