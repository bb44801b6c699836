"""Wang family: exact solvers (SAT, the shared patch builder, backtracking) and Wang's procedure.

Every tiling a solver returns is re-checked here with the independent grid checker; every
"no tiling" is cross-checked between solvers or against a fact proved in the test's comment.
Aperiodic sets (Jeandel–Rao arXiv:1506.06492; Culik and Kari, Discrete Math. 160, 1996)
tile every finite square but have no periodic tiling, hence no torus of any size.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from tilekit.errors import ParameterError, SolverLimit
from tilekit.plugins.wang import (
    backtrack_solve,
    builder_solve,
    from_tuples,
    get_tileset,
    grid_mismatches,
    sat_solve,
    solve,
    wang_procedure,
)

APERIODIC = ("jeandel-rao-11", "culik-13", "kari-14")


@pytest.mark.parametrize("name", APERIODIC)
def test_aperiodic_sets_tile_growing_squares(name):
    """An aperiodic set tiles the plane, so it tiles every square; checked up to 24 x 24."""
    ts = get_tileset(name)
    for n in (8, 16, 20, 24):
        result = sat_solve(ts, n, n)
        assert result.tiles and result.grid.shape == (n, n)
        assert grid_mismatches(result.grid, ts) == []


@pytest.mark.parametrize("name", APERIODIC)
def test_aperiodic_sets_have_no_small_torus(name):
    """A torus tiling would be a translational unit of a periodic tiling: none can exist."""
    ts = get_tileset(name)
    for rows, cols in itertools.product(range(1, 7), repeat=2):
        assert not sat_solve(ts, rows, cols, torus=True).tiles


def test_backtracking_tiles_jeandel_rao_20x20():
    ts = get_tileset("jeandel-rao-11")
    result = backtrack_solve(ts, 20, 20)
    assert result.tiles and grid_mismatches(result.grid, ts) == []


def test_builder_tiles_aperiodic_rectangles():
    """The shared patch builder, adapted with a colour-equality rule, finds rectangles too."""
    for name in APERIODIC:
        ts = get_tileset(name)
        result = builder_solve(ts, 4, 5)
        assert result.tiles and result.method == "builder"
        assert grid_mismatches(result.grid, ts) == []


# ---------------------------------------------------------------------- cross-checked answers


def _methods(torus: bool) -> tuple[str, ...]:
    """Every solver answers both questions (the builder's torus is its periodic mode)."""
    return ("sat", "backtrack", "builder")


def test_cycle_3_torus_exists_exactly_when_the_width_is_a_multiple_of_3():
    """cycle-3 (catalogue/wang/cycle-3.wang): columns repeat one tile and rows step i -> i+1
    mod 3, so an m x n torus exists iff 3 divides n, for every m."""
    ts = get_tileset("cycle-3")
    for rows, cols in itertools.product(range(1, 7), repeat=2):
        for method in _methods(True):
            result = solve(ts, rows, cols, torus=True, method=method)
            assert result.tiles == (cols % 3 == 0), (rows, cols, method)
            if result.tiles:
                assert grid_mismatches(result.grid, ts, torus=True) == []


def test_checkerboard_torus_needs_even_sides():
    """checkerboard-2 forces the two tiles to alternate both ways: a torus needs even sides."""
    ts = get_tileset("checkerboard-2")
    for rows, cols in itertools.product(range(1, 6), repeat=2):
        for method in _methods(True):
            assert solve(ts, rows, cols, torus=True, method=method).tiles == (rows % 2 == 0 and cols % 2 == 0)


def test_counter_4_rectangles_need_width_at_most_4():
    """counter-4 rows read 0, 1, 2, 3, 4 west to east with no way to continue, and columns
    repeat: an m x n rectangle tiles iff n <= 4. All three solvers agree, including the
    proofs of impossibility (exhausted searches and UNSAT)."""
    ts = get_tileset("counter-4")
    for rows, cols in itertools.product(range(1, 4), range(1, 7)):
        for method in _methods(False):
            assert solve(ts, rows, cols, method=method).tiles == (cols <= 4), (rows, cols, method)


def test_solvers_agree_on_random_small_sets():
    """Random 2-colour sets of 3-6 tiles: SAT, backtracking and the builder give the same
    answer on 3 x 3 rectangles and on 2 x 3 tori."""
    rng = np.random.default_rng(7)
    agreed = {True: 0, False: 0}
    for _ in range(25):
        k = int(rng.integers(3, 7))
        rows = {tuple(r) for r in rng.integers(0, 2, size=(k, 4)).tolist()}
        ts = from_tuples("random", sorted(rows))
        answers = {m: solve(ts, 3, 3, method=m).tiles for m in _methods(False)}
        assert len(set(answers.values())) == 1, answers
        agreed[answers["sat"]] += 1
        tori = {m: solve(ts, 2, 3, torus=True, method=m).tiles for m in _methods(True)}
        assert len(set(tori.values())) == 1, tori
    assert agreed[True] and agreed[False]  # both outcomes were exercised


# ---------------------------------------------------------------------- fixed tiles


def test_fixed_tiles_are_respected_by_every_method():
    ts = get_tileset("jeandel-rao-11")
    fixed = {(1, 2): "k", (3, 0): 6}
    for method in ("sat", "backtrack", "builder"):
        result = solve(ts, 5, 5, fixed=fixed, method=method)
        assert result.tiles
        assert result.grid[1, 2] == ts.tile_names.index("k") and result.grid[3, 0] == 6
        assert grid_mismatches(result.grid, ts) == []


def test_fixed_tiles_can_make_a_rectangle_impossible():
    """In any checkerboard-2 tiling cell (i, j) holds the tile at (0, 0) iff i + j is even:
    fixing a at (0, 0) and (1, 1) is consistent, fixing a at (0, 0) and (0, 3) is not (odd
    distance), which every method must prove."""
    ts = get_tileset("checkerboard-2")
    for method in ("sat", "backtrack", "builder"):
        assert solve(ts, 2, 4, fixed={(0, 0): "a", (1, 1): "a"}, method=method).tiles
        assert not solve(ts, 2, 4, fixed={(0, 0): "a", (0, 3): "a"}, method=method).tiles


def test_fixed_tile_errors_are_clear():
    ts = get_tileset("checkerboard-2")
    with pytest.raises(ParameterError, match=r"fixed tiles clash: a at \(0, 0\) has E='p' but a at \(0, 1\) has W='q'"):
        sat_solve(ts, 2, 2, fixed={(0, 0): "a", (0, 1): "a"})
    with pytest.raises(ParameterError, match="outside the 2 x 2 grid"):
        sat_solve(ts, 2, 2, fixed={(5, 0): 0})
    with pytest.raises(ParameterError, match="not in set 'checkerboard-2'; tiles: a, b"):
        backtrack_solve(ts, 2, 2, fixed={(0, 0): "zz"})
    with pytest.raises(ParameterError, match="out of range"):
        builder_solve(ts, 2, 2, fixed={(0, 0): 9})


def test_bad_solver_requests():
    ts = get_tileset("cycle-3")
    with pytest.raises(ParameterError, match="not one of sat, builder, backtrack"):
        solve(ts, 2, 2, method="guess")
    with pytest.raises(ParameterError, match="fixed tiles clash"):
        builder_solve(get_tileset("checkerboard-2"), 2, 2, torus=True, fixed={(0, 0): "a", (0, 1): "a"})
    with pytest.raises(ParameterError, match="at least 1 x 1"):
        sat_solve(ts, 0, 3)
    with pytest.raises(ParameterError, match="SAT solver 'nope'"):
        sat_solve(ts, 2, 2, solver="nope")


def test_limits_raise_solver_limit():
    ts = get_tileset("culik-13")
    with pytest.raises(SolverLimit, match="within 10 placements"):
        backtrack_solve(ts, 12, 12, max_nodes=10)
    with pytest.raises(SolverLimit, match="or max_nodes"):
        builder_solve(ts, 6, 6, max_nodes=5)
    # Kari 70 x 70 takes CaDiCaL many seconds: CaDiCaL runs in a child process that is
    # killed at the limit, Glucose is interrupted in process
    kari = get_tileset("kari-14")
    for solver in ("cadical195", "glucose4"):
        with pytest.raises(SolverLimit, match="within 0.3 CPU seconds"):
            sat_solve(kari, 70, 70, solver=solver, time_limit=0.3)


def test_time_limits_are_cpu_seconds_for_every_method():
    """The builder and the backtracking search count CPU seconds of the calling thread, as the
    SAT solver does (tilekit.budget): a budget that runs out ends the search with the one-line
    SolverLimit naming what was used and the limit, whatever the machine's load; a Budget
    given is the one spent. (Jeandel-Rao has no torus; 20 x 20 and 8 x 8 are far from
    exhausted in 0.3 s; Kari 70 x 70 as above.)"""
    from tilekit.budget import Budget

    jr, kari = get_tileset("jeandel-rao"), get_tileset("kari-14")
    for call, ts, n, torus in ((backtrack_solve, jr, 20, True), (backtrack_solve, kari, 70, False),
                               (builder_solve, jr, 8, True)):
        budget = Budget(0.3)
        with pytest.raises(SolverLimit, match=r"CPU seconds \(time limit: 0\.3 CPU seconds\); raise the time limit"):
            call(ts, n, n, torus=torus, max_nodes=None, time_limit=budget)
        assert budget.spent() and 0.3 <= budget.used() < 1.5
    with pytest.raises(SolverLimit, match=r"backtracking gave no answer .* within \d+ placements and 0\.\d+ CPU"):
        solve(jr, 20, 20, torus=True, method="backtrack", time_limit=0.2, max_nodes=None)


def test_wang_procedure_total_limit_is_cpu_seconds():
    """Wang's procedure's total limit is a CPU budget; each call gets a share of what is left
    (its CPU counts in the total), so the procedure ends in one line after about that much CPU
    (Jeandel-Rao, aperiodic, never answers)."""
    import time

    start = time.process_time()
    with pytest.raises(SolverLimit, match=r"CPU seconds"):
        wang_procedure(get_tileset("jeandel-rao"), 30, method="backtrack", time_limit=None, total_limit=0.2)
    assert 0.2 <= time.process_time() - start < 1.5


def test_other_sat_solvers_give_the_same_answers():
    ts = get_tileset("kari-14")
    for solver in ("glucose4", "minisat22"):
        assert sat_solve(ts, 10, 10, solver=solver).tiles
        assert not sat_solve(ts, 3, 4, torus=True, solver=solver).tiles


def test_builder_torus_answers_agree_with_sat_on_random_sets():
    """The builder's periodic mode against SAT on random 2- and 3-colour sets, on tori of
    shapes 1 x 4, 2 x 2, 3 x 3 and 2 x 4 (thin tori make a tile meet its own images);
    every builder tiling is re-checked with the torus checker."""
    rng = np.random.default_rng(11)
    agreed = {True: 0, False: 0}
    for trial in range(30):
        colours = 2 if trial % 2 == 0 else 3
        k = int(rng.integers(3, 8))
        rows = {tuple(r) for r in rng.integers(0, colours, size=(k, 4)).tolist()}
        ts = from_tuples("random", sorted(rows))
        for shape in ((1, 4), (2, 2), (3, 3), (2, 4)):
            built = builder_solve(ts, *shape, torus=True)
            assert built.tiles == sat_solve(ts, *shape, torus=True).tiles, (sorted(rows), shape)
            if built.tiles:
                assert built.torus and grid_mismatches(built.grid, ts, torus=True) == []
            agreed[built.tiles] += 1
    assert agreed[True] and agreed[False]


def test_builder_torus_with_fixed_tiles():
    """checkerboard-2 on a torus: a at (0, 0) forces a on every cell with i + j even, so
    fixing a at (1, 1) is consistent and fixing b there is not (on the 4 x 4 torus);
    every torus of the set needs even sides, whatever is fixed."""
    ts = get_tileset("checkerboard-2")
    ok = builder_solve(ts, 4, 4, torus=True, fixed={(0, 0): "a", (1, 1): "a"})
    assert ok.tiles and ok.grid[0, 0] == ok.grid[1, 1] == ts.tile_names.index("a")
    assert grid_mismatches(ok.grid, ts, torus=True) == []
    assert not builder_solve(ts, 4, 4, torus=True, fixed={(0, 0): "a", (1, 1): "b"}).tiles
    assert not builder_solve(ts, 3, 4, torus=True, fixed={(2, 3): "b"}).tiles


@pytest.mark.parametrize("name", APERIODIC)
def test_builder_finds_no_small_torus_for_aperiodic_sets(name):
    """As for SAT above: no torus exists for an aperiodic set; the builder's exhausted
    periodic searches prove it for the small tori."""
    ts = get_tileset(name)
    for rows, cols in ((1, 1), (1, 3), (2, 2), (2, 3)):
        assert not builder_solve(ts, rows, cols, torus=True).tiles, (rows, cols)


# ---------------------------------------------------------------------- Wang's procedure


def test_wang_procedure_finds_the_periodic_units():
    """cycle-3's smallest square torus is 3 x 3, checkerboard-2's 2 x 2, and a set with a
    tile whose N = S and E = W (Figure 6.9's (R, Y, R, Y)) has a 1 x 1 unit."""
    for name, m in (("cycle-3", 3), ("checkerboard-2", 2), ("stochastic-2colour", 1), ("corner-2colour", 1)):
        ts = get_tileset(name)
        result = wang_procedure(ts, 6)
        assert result.outcome == "periodic" and result.m == m
        built = wang_procedure(ts, 6, method="builder")  # the builder answers the tori too
        assert (built.outcome, built.m) == ("periodic", m)
        assert grid_mismatches(built.unit, ts, torus=True) == []
        assert result.unit.shape == (m, m) and grid_mismatches(result.unit, ts, torus=True) == []
        assert "tiles the plane periodically" in result.statement()


def test_wang_procedure_proves_non_tiling_sets_do_not_tile():
    """counter-4 tiles 4 x 4 but not 5 x 5; mismatch-1 (N != S) cannot fill a 2 x 2 square."""
    for name, m in (("counter-4", 5), ("mismatch-1", 2)):
        for method in ("sat", "backtrack", "builder"):
            result = wang_procedure(get_tileset(name), 8, method=method)
            assert (result.outcome, result.m) == ("does_not_tile", m), method
            assert [s["m"] for s in result.steps] == list(range(1, m + 1))
            assert f"no {m} x {m} square can be tiled" in result.statement()


@pytest.mark.parametrize("name", APERIODIC)
def test_wang_procedure_gives_no_answer_for_aperiodic_sets(name):
    """A bounded search says only what it showed; it never claims aperiodicity."""
    result = wang_procedure(get_tileset(name), 6)
    assert result.outcome == "no_answer" and result.m is None and result.unit is None
    text = result.statement()
    assert "no answer up to m = 6" in text and "does not show aperiodicity" in text
    assert all(step["torus"] is False and step["square"] is True for step in result.steps)
    assert result.to_json()["outcome"] == "no_answer"


def test_wang_procedure_parameters():
    with pytest.raises(ParameterError, match="1 <= start_m <= max_m"):
        wang_procedure(get_tileset("cycle-3"), 0)
    with pytest.raises(ParameterError, match="must be an integer"):
        wang_procedure(get_tileset("cycle-3"), "many")
