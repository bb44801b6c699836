"""Does a Wang set tile an m x n rectangle or torus (with some tiles fixed)? A SAT encoding.

Variables: ``x[c, t]`` (cell c holds tile t) and, per edge of the grid, ``y[e, k]`` (edge e
has colour k). Clauses, all linear in the grid size:

- each cell holds at least one tile;
- a tile forces the colours of its four edges: ``x[c, t] -> y[side(c), colour(t, side)]``;
- each edge has exactly one colour (at-least-one is implied but helps the solver; at-most-one
  pairwise, as colours per orientation are few), which with the previous clauses also makes
  the tile of a cell unique (no two tiles share all four colours);
- support: an edge colour needs a tile carrying it on each side of the edge, so the solver
  propagates through edges as well as through tiles.

Compared with the plain encoding of FACTS.md (pairwise at-most-one over tiles, adjacency as
pairs of incompatible tiles), the number of clauses per cell drops from O(T^2) to O(T + k^2).
The default solver is CaDiCaL 1.9.5 through python-sat; solving, solver choice and time
limits are the core's :mod:`tilekit.sat`.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tilekit.budget import Budget
from tilekit.errors import ParameterError, SolverLimit
from tilekit.limits import (
    DEFAULT_SOLVER_SECONDS,
    MAX_SAT_VARIABLES,
    refuse_over,
    refuse_over_memory,
    sat_bytes,
)
from tilekit.plugins.wang.check import check_grid, grid_size
from tilekit.plugins.wang.tileset import E, N, S, W, WangTileSet
from tilekit.sat import (  # re-exported: the names this module had before tilekit.sat
    CNF,
    DEFAULT_SAT_SOLVER,
    INTERRUPTIBLE,  # noqa: F401
    SAT_SOLVERS,  # noqa: F401
    check_solver,
    solve,
)


@dataclass
class SolveResult:
    """The answer to one rectangle/torus question.

    ``tiles`` is True with a verified ``grid``, or False when the solver proved that no
    tiling of the asked size (with the fixed tiles) exists.
    """

    tiles: bool
    grid: np.ndarray | None
    rows: int
    cols: int
    torus: bool
    method: str
    seconds: float
    stats: dict[str, Any] = field(default_factory=dict)

    def __bool__(self) -> bool:
        return self.tiles

    def describe(self) -> str:
        shape = f"{self.rows} x {self.cols} {'torus' if self.torus else 'rectangle'}"
        verdict = "tiles" if self.tiles else "proved untileable"
        return f"{shape}: {verdict} ({self.method}, {self.seconds:.3g} s)"


def normalise_fixed(
    tileset: WangTileSet, rows: int, cols: int, fixed: Mapping[Any, Any] | None
) -> dict[tuple[int, int], int]:
    """Fixed tiles as {(i, j): tile index}; tiles may be given by index or by name."""
    out: dict[tuple[int, int], int] = {}
    for key, tile in (fixed or {}).items():
        try:
            i, j = (int(v) for v in key)
        except (TypeError, ValueError):
            raise ParameterError(f"fixed tile position {key!r} must be a pair (row, column)") from None
        if not (0 <= i < rows and 0 <= j < cols):
            raise ParameterError(f"fixed tile position ({i}, {j}) lies outside the {rows} x {cols} grid")
        if isinstance(tile, str):
            if tile not in tileset.tile_names:
                raise ParameterError(
                    f"fixed tile {tile!r} at ({i}, {j}) is not in set {tileset.name!r}; "
                    f"tiles: {', '.join(tileset.tile_names)}"
                )
            t = tileset.tile_names.index(tile)
        else:
            t = int(tile)
            if not 0 <= t < len(tileset):
                raise ParameterError(
                    f"fixed tile {t} at ({i}, {j}) is out of range; set {tileset.name!r} has tiles 0..{len(tileset) - 1}"
                )
        out[(i, j)] = t
    return out


def fixed_conflict(
    tileset: WangTileSet, rows: int, cols: int, fixed: Mapping[tuple[int, int], int], torus: bool
) -> str | None:
    """A message naming two adjacent fixed tiles whose colours clash, or None."""
    for (i, j), t in fixed.items():
        for di, dj, mine, theirs, side in ((0, 1, E, W, "E"), (1, 0, S, N, "S")):
            ii, jj = i + di, j + dj
            if torus:
                ii, jj = ii % rows, jj % cols
            u = fixed.get((ii, jj))
            if u is None:
                continue
            a, b = tileset.tiles[t, mine], tileset.tiles[u, theirs]
            if a != b:
                opp = {"E": "W", "S": "N"}[side]
                return (
                    f"fixed tiles clash: {tileset.tile_names[t]} at ({i}, {j}) has {side}="
                    f"{tileset.colours[a]!r} but {tileset.tile_names[u]} at ({ii}, {jj}) has {opp}={tileset.colours[b]!r}"
                )
    return None


#: Colours per edge orientation up to which "at most one colour per edge" is pairwise
#: (p(p-1)/2 binary clauses); above it a sequential counter (p-1 auxiliary variables and
#: 3p-4 clauses), so a set with thousands of colours costs linear, not quadratic, clauses.
PAIRWISE_AMO_MAX = 6


class _Encoding:
    """Variable numbering and clause generation for one rows x cols grid; the clauses come
    as blocks of equal-width rows (:meth:`tilekit.sat.CNF.add_block`), and :meth:`size`
    counts variables, clauses and literals without making them."""

    def __init__(self, tileset: WangTileSet, rows: int, cols: int, torus: bool) -> None:
        self.ts = tileset
        self.rows, self.cols, self.torus = rows, cols, torus
        t = len(tileset)
        c = len(tileset.colours)
        self.n_tiles, self.n_colours = t, c
        cells = rows * cols
        self.x_base = 1
        # horizontal edges: line r (0..rows) above row r; the torus identifies line rows with 0
        self.h_lines = rows if torus else rows + 1
        self.v_lines = cols if torus else cols + 1
        self.h_base = self.x_base + cells * t
        self.v_base = self.h_base + self.h_lines * cols * c
        self.top = self.v_base + rows * self.v_lines * c - 1
        self.palettes = (tileset.horizontal_colours, tileset.vertical_colours)
        self.edges = (self.h_lines * cols, rows * self.v_lines)

    def x(self, i: np.ndarray, j: np.ndarray, t: np.ndarray) -> np.ndarray:
        return self.x_base + (i * self.cols + j) * self.n_tiles + t

    def h(self, line: np.ndarray, j: np.ndarray, k: np.ndarray) -> np.ndarray:
        line = line % self.rows if self.torus else line
        return self.h_base + (line * self.cols + j) * self.n_colours + k

    def v(self, i: np.ndarray, line: np.ndarray, k: np.ndarray) -> np.ndarray:
        line = line % self.cols if self.torus else line
        return self.v_base + (i * self.v_lines + line) * self.n_colours + k

    def size(self) -> tuple[int, int, int]:
        """(variables, clauses, literals) of the encoding, counted without making it."""
        cells, t = self.rows * self.cols, self.n_tiles
        variables, clauses, literals = self.top, cells + 4 * cells * t, cells * t + 8 * cells * t
        for palette, edges in zip(self.palettes, self.edges):
            p = len(palette)
            clauses += edges
            literals += edges * p
            if p <= PAIRWISE_AMO_MAX:
                clauses += edges * (p * (p - 1) // 2)
                literals += edges * p * (p - 1)
            else:
                variables += edges * (p - 1)
                clauses += edges * (3 * p - 4)
                literals += edges * 2 * (3 * p - 4)
        for palette in (*self.palettes, *self.palettes):  # support: N and S, W and E
            clauses += cells * len(palette)
            literals += cells * (len(palette) + t)  # each tile carries one colour per side
        return variables, clauses, literals

    def blocks(self, cnf: CNF) -> None:
        """Add the encoding's clauses to ``cnf`` as blocks (and its auxiliary variables)."""
        ts, rows, cols, t = self.ts, self.rows, self.cols, self.n_tiles
        cnf.reserve(self.top)
        ii, jj = np.divmod(np.arange(rows * cols), cols)
        tt = np.arange(t)
        # at least one tile per cell
        xs = self.x(ii[:, None], jj[:, None], tt[None, :])
        cnf.add_block(xs)
        # tile -> its four edge colours
        xvar = xs.ravel()
        ci = np.repeat(ii, t)
        cj = np.repeat(jj, t)
        cols4 = ts.tiles[np.tile(tt, rows * cols)]
        for lits in (
            self.h(ci, cj, cols4[:, N]),
            self.h(ci + 1, cj, cols4[:, S]),
            self.v(ci, cj, cols4[:, W]),
            self.v(ci, cj + 1, cols4[:, E]),
        ):
            cnf.add_block(np.column_stack([-xvar, lits]))
        # exactly one colour per edge, over the colours that can appear on that orientation
        hl, hj = np.divmod(np.arange(self.h_lines * cols), cols)
        vi, vl = np.divmod(np.arange(rows * self.v_lines), self.v_lines)
        for palette, var, a, b in ((self.palettes[0], self.h, hl, hj), (self.palettes[1], self.v, vi, vl)):
            lits = var(a[:, None], b[:, None], palette[None, :])  # (edges, p)
            # at least one colour per edge: implied by the tile clauses, but stated it helps
            # the solver (Jeandel-Rao 80 x 80: 5.5 s -> 2.4 s with CaDiCaL 1.9.5)
            cnf.add_block(lits)
            _at_most_one(cnf, lits)
        # support: colour k on an edge needs a matching tile on each side that exists
        self._support(cnf)

    def _support(self, cnf: CNF) -> None:
        ts, rows, cols = self.ts, self.rows, self.cols
        ii, jj = np.divmod(np.arange(rows * cols), cols)
        for side, colours_of in ((N, ts.horizontal_colours), (S, ts.horizontal_colours), (W, ts.vertical_colours), (E, ts.vertical_colours)):
            order = np.argsort(ts.tiles[:, side], kind="stable")
            bounds = np.searchsorted(ts.tiles[order, side], colours_of, side="left")
            ends = np.searchsorted(ts.tiles[order, side], colours_of, side="right")
            for k, lo, hi in zip(colours_of.tolist(), bounds.tolist(), ends.tolist()):
                carriers = order[lo:hi]
                # edges whose this-side cell exists: every cell supports its own edge
                if side == N:
                    ev = self.h(ii, jj, k)
                elif side == S:
                    ev = self.h(ii + 1, jj, k)
                elif side == W:
                    ev = self.v(ii, jj, k)
                else:
                    ev = self.v(ii, jj + 1, k)
                xs = self.x(ii[:, None], jj[:, None], carriers[None, :])
                cnf.add_block(np.column_stack([-ev, xs]))

    def decode(self, model: list[int]) -> np.ndarray:
        rows, cols, t = self.rows, self.cols, self.n_tiles
        vals = np.asarray(model[: rows * cols * t]) > 0
        return vals.reshape(rows, cols, t).argmax(axis=2)


def _at_most_one(cnf: CNF, lits: np.ndarray) -> None:
    """At most one literal true in each row of ``lits`` (n, p): pairwise for small p, else
    Sinz's sequential counter with p-1 fresh variables s_1..s_{p-1} per row:
    x_1 -> s_1; x_i -> s_i, s_{i-1} -> s_i, x_i -> not s_{i-1} (1 < i < p); x_p -> not s_{p-1}."""
    n, p = lits.shape
    if p < 2 or n == 0:
        return
    if p <= PAIRWISE_AMO_MAX:
        pa, pb = np.triu_indices(p, 1)
        cnf.add_block(np.column_stack([-lits[:, pa].ravel(), -lits[:, pb].ravel()]))
        return
    s = np.asarray(cnf.new_vars(n * (p - 1)), dtype=np.int64).reshape(n, p - 1)
    pairs = [np.column_stack([-lits[:, : p - 1].ravel(), s.ravel()]),          # x_i -> s_i, i < p
             np.column_stack([-s[:, :-1].ravel(), s[:, 1:].ravel()]),           # s_{i-1} -> s_i
             np.column_stack([-lits[:, 1:].ravel(), -s.ravel()])]               # x_i -> not s_{i-1}, i > 1
    for block in pairs:
        cnf.add_block(block)


def sat_solve(
    tileset: WangTileSet,
    rows: int,
    cols: int,
    torus: bool = False,
    fixed: Mapping[Any, Any] | None = None,
    solver: str = DEFAULT_SAT_SOLVER,
    time_limit: Budget | float | None = DEFAULT_SOLVER_SECONDS,
    max_variables: float = MAX_SAT_VARIABLES,
) -> SolveResult:
    """Decide whether ``tileset`` tiles a rows x cols rectangle (or torus) with ``fixed`` tiles.

    The question is refused before its clauses are made when it has more than
    ``max_variables`` variables or would not fit in memory (:func:`check_sat_size`).
    A tiling found is checked by the independent :func:`check_grid` before it is returned.
    After ``time_limit`` CPU seconds (a :class:`tilekit.budget.Budget` or a number; default
    ``limits.DEFAULT_SOLVER_SECONDS``; None: no limit) the solver is interrupted (or, for CaDiCaL, which python-sat cannot interrupt, run in a
    child process that is killed) and :class:`SolverLimit` raised.
    """
    check_solver(solver)
    rows, cols, fixed_n = prepare_question(tileset, rows, cols, fixed, torus)
    start = time.perf_counter()
    enc = _Encoding(tileset, rows, cols, torus)
    check_sat_size(enc, tileset, max_variables)
    cnf = CNF(top=enc.top)
    enc.blocks(cnf)
    assumptions = [int(enc.x(i, j, t)) for (i, j), t in fixed_n.items()]
    budget = Budget.of(time_limit)
    answer = solve(cnf, assumptions, solver=solver, time_limit=budget)
    stats = {"variables": cnf.top, "clauses": len(cnf), "literals": cnf.literals(), "solver": solver, **answer.stats}
    seconds = time.perf_counter() - start
    if answer.satisfiable is None:
        raise no_answer(solver, tileset, rows, cols, torus, str(budget), "raise the time limit (--time-limit S)")
    grid = None
    if answer.satisfiable:
        grid = enc.decode(answer.model)
        check_grid(grid, tileset, torus=torus, fixed=fixed_n)
    return SolveResult(bool(answer.satisfiable), grid, rows, cols, torus, f"sat:{solver}", seconds, stats)


def sat_size(tileset: WangTileSet, rows: int, cols: int, torus: bool = False) -> tuple[int, int, int]:
    """(variables, clauses, literals) of the SAT question, counted without making it."""
    return _Encoding(tileset, rows, cols, torus).size()


def check_sat_size(enc: _Encoding, tileset: WangTileSet, max_variables: float = MAX_SAT_VARIABLES) -> None:
    """Refuse (LimitError, one line) a question over ``max_variables`` variables or whose
    measured cost (``limits.sat_bytes``) would not fit in the memory available."""
    variables, clauses, _ = enc.size()
    hint = f"{enc.rows} x {enc.cols} cells x {len(tileset)} tiles, {clauses:,} clauses"
    refuse_over("SAT variables", variables, max_variables, "--max-variables", hint=hint)
    refuse_over_memory("SAT clauses", clauses, sat_bytes(variables, clauses) / max(clauses, 1), hint=hint)


def prepare_question(
    tileset: WangTileSet, rows: Any, cols: Any, fixed: Mapping[Any, Any] | None, torus: bool
) -> tuple[int, int, dict[tuple[int, int], int]]:
    """What every solver checks first: the size, the fixed tiles, and that they agree."""
    rows, cols = grid_size(rows, cols)
    fixed_n = normalise_fixed(tileset, rows, cols, fixed)
    clash = fixed_conflict(tileset, rows, cols, fixed_n, torus)
    if clash:
        raise ParameterError(clash)
    return rows, cols, fixed_n


def no_answer(who: str, tileset: WangTileSet, rows: int, cols: int, torus: bool, spent: str, advice: str) -> SolverLimit:
    """The SolverLimit every solver raises when its budget ran out."""
    shape = "torus" if torus else "rectangle"
    return SolverLimit(
        f"{who} gave no answer for set {tileset.name!r} on a {rows} x {cols} {shape} within {spent}; {advice}"
    )
