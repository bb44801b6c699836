"""The classification's cheap paths (issue 28: the per-form fixed cost on the grids with cells of
several shapes) give the answers of the paths they stand in for:

- ``first_corona_rows`` (one compiled call: orientations, the kernel's halo, the touching copies
  and the arc-consistency test of corona 1) returns exactly the first level that
  ``HeeschSolver`` grows through ``Forms``, row for row, on every hole-free form of a size;
- ``classify_form`` (corona 1's local test before the boundary-word test) gives every form the
  classification of ``classify`` after ``analyse``;
- ``heesch`` through one incremental solver (``HeeschSolver.ladder_at``) gives the Hc, Hh and
  proofs of one new formula per level.

The geometry of the witnesses is checked independently in tests/test_multigrid_classify.py.
"""

from __future__ import annotations

import numpy as np
import pytest

from tilekit.lattice import free_polyforms, get_grid
from tilekit.plugins.polyomino import heesch as heesch_module
from tilekit.plugins.polyomino.classify import classify, classify_form
from tilekit.plugins.polyomino.heesch import HeeschSolver, first_corona_rows, heesch
from tilekit.plugins.polyomino.isohedral import analyse


def _plain(name: str, n: int) -> tuple:
    grid = get_grid(name)
    polys, holes, _ = free_polyforms(grid, n, with_holes=True)
    return grid, [p for p, h in zip(polys, holes) if not h]


@pytest.mark.parametrize("name,n", [("bevelhex", 4), ("drafter", 5), ("octasquare", 5), ("trihex", 5),
                                    ("halfcairo", 5), ("abolo", 6), ("kite", 5), ("square", 6), ("hex", 5),
                                    ("iamond", 7)])
def test_first_corona_rows_equal_the_solver_first_level(name, n):
    grid, plain = _plain(name, n)
    settled = 0
    for cells in plain:
        hs = HeeschSolver(grid, cells)
        hs._grow()
        rows = first_corona_rows(grid, cells)
        assert np.array_equal(rows, hs.levels[1]), cells.tolist()
        settled += not len(rows)
    if name == "square":  # every polyomino of up to 6 cells tiles (A054360: the first non-tilers at n = 7)
        assert settled == 0


def test_a_single_dodecagon_is_a_non_tiler_with_no_solver():
    """A lone dodecagon of the 4.6.12 grid: its copies are dodecagons, none can cover the squares
    and hexagons around it, so no corona exists (Hc = Hh = 0) and no SAT call is made."""
    grid = get_grid("bevelhex")
    cell = np.array([[0, 0]])
    assert int(grid.cell_type(cell)[0]) == 0 and grid.degrees[0] == 12
    assert len(first_corona_rows(grid, cell)) == 0
    c = classify_form(grid, cell)
    assert (c.tiles, c.heesch, c.heesch_holes) == ("false", 0, 0)
    assert c.evidence["sat_calls"] == 0 and c.verdict.startswith("does not tile: Heesch number 0")


@pytest.mark.parametrize("name,n", [("bevelhex", 4), ("drafter", 5), ("trihex", 4), ("halfcairo", 5)])
def test_classify_form_equals_classify_after_analyse(name, n):
    grid, plain = _plain(name, n)
    for cells in plain:
        a = classify(grid, cells, analyse(grid, cells, construct=False), time_limit=60.0)
        b = classify_form(grid, cells, time_limit=60.0)
        keep = ("tiles", "isohedral", "anisohedral_k", "heesch", "heesch_holes", "verdict")
        assert {k: a.columns()[k] for k in keep} == {k: b.columns()[k] for k in keep}, cells.tolist()


def test_heesch_through_the_ladder_equals_one_formula_per_level(monkeypatch):
    """The first 12 hole-free 5-octasquares that reach the solver: (Hc, Hh, decided, surrounded) equal."""
    grid, plain = _plain("octasquare", 5)
    forms = [c for c in plain if len(first_corona_rows(grid, c)) and not analyse(grid, c, construct=False)["isohedral"]]
    assert len(forms) >= 12
    forms = forms[:12]
    ladder = [heesch(grid, c, max_level=2, solver="glucose4") for c in forms]
    monkeypatch.setattr(heesch_module.HeeschSolver, "ladder_at", lambda self, k: None)
    per_level = [heesch(grid, c, max_level=2, solver="glucose4") for c in forms]
    for a, b, c in zip(ladder, per_level, forms):
        assert (a.hc, a.hh, a.decided, a.surrounded) == (b.hc, b.hh, b.decided, b.surrounded), c.tolist()
