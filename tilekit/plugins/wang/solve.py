"""Exact answers to "does this Wang set tile an m x n rectangle / torus?" and Wang's procedure.

Three solvers, one question, one independent checker (:func:`check_grid`) on every answer:

- ``sat``: the encoding of :mod:`tilekit.plugins.wang.sat` (CaDiCaL through python-sat);
- ``builder``: the shared backtracking patch builder (:mod:`tilekit.builder`) with Wang tiles
  as unit squares whose edge labels are (side, colour) and a colour-equality compatibility
  rule; the builder's fill goal is "every open edge inside the rectangle is filled", a
  vertex rule keeps tiles inside the rectangle and on their fixed cells, and the frontier
  order is scanline order. For a torus the builder runs with ``period=((cols, 0), (0,
  rows))``: every tile stands for its lattice orbit, the goal is a closed torus, and the
  rule reads cells modulo the torus;
- ``backtrack``: a Wang-specific scanline backtracking search with an explicit stack, for
  rectangles and tori (a second opinion).

:func:`wang_procedure` is the algorithm of §6.2: for m = 1, 2, ... look for an m x m torus
(a translational unit, so the set tiles periodically) and for an m x m square that cannot be
tiled (so the set does not tile); it reports which came first or that neither did up to the
bound, and never more than that.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tilekit.budget import Budget
from tilekit.builder import PatchBuilder
from tilekit.errors import ParameterError, SolverLimit
from tilekit.limits import (
    BUILDER_BYTES_PER_TILE,
    BUILDER_BYTES_PER_TORUS_TILE,
    DEFAULT_SOLVER_SECONDS,
    refuse_over_memory,
)
from tilekit.plugins.wang.check import check_grid
from tilekit.plugins.wang.sat import (
    DEFAULT_SAT_SOLVER,
    SolveResult,
    no_answer,
    prepare_question,
    sat_solve,
)
from tilekit.plugins.wang.tileset import E, N, S, W, WangTileSet
from tilekit.tiling import Prototile

METHODS = ("sat", "builder", "backtrack")


# ---------------------------------------------------------------------- scanline backtracking


def backtrack_solve(
    tileset: WangTileSet,
    rows: int,
    cols: int,
    torus: bool = False,
    fixed: Mapping[Any, Any] | None = None,
    max_nodes: int | None = 10_000_000,
    time_limit: Budget | float | None = DEFAULT_SOLVER_SECONDS,
) -> SolveResult:
    """Depth-first search in scanline order with an explicit stack (no recursion limit).

    Cell k = i * cols + j takes the tiles whose N and W colours match the tiles above and to
    the left (on a torus, the last column must also match the first and the last row the
    first row). Exhausting the stack proves that no tiling exists. Raises
    :class:`SolverLimit` at ``max_nodes`` tile placements or ``time_limit`` CPU seconds of the
    calling thread (a number or a :class:`tilekit.budget.Budget`).
    """
    rows, cols, fixed_n = prepare_question(tileset, rows, cols, fixed, torus)
    start = time.perf_counter()
    budget = Budget.of(time_limit)
    tiles = tileset.tiles.tolist()
    T = len(tiles)
    # candidates by (north colour or None, west colour or None)
    by_nw: dict[tuple[int | None, int | None], list[int]] = {}
    for t, (n, _e, _s, w) in enumerate(tiles):
        for key in ((n, w), (None, w), (n, None), (None, None)):
            by_nw.setdefault(key, []).append(t)
    cells = rows * cols
    grid = [-1] * cells
    fixed_flat = {i * cols + j: t for (i, j), t in fixed_n.items()}

    def candidates(k: int) -> list[int]:
        i, j = divmod(k, cols)
        n = tiles[grid[k - cols]][S] if i > 0 else None
        w = tiles[grid[k - 1]][E] if j > 0 else None
        cand = by_nw.get((n, w), [])
        f = fixed_flat.get(k)
        if f is not None:
            cand = [f] if f in cand else []
        if torus:
            if j == cols - 1:
                first = grid[k - cols + 1] if cols > 1 else None
                if first is not None:
                    want = tiles[first][W]
                    cand = [t for t in cand if tiles[t][E] == want]
                else:  # a single column wraps onto itself
                    cand = [t for t in cand if tiles[t][E] == tiles[t][W]]
            if i == rows - 1:
                if rows > 1:
                    want = tiles[grid[j]][N]
                    cand = [t for t in cand if tiles[t][S] == want]
                else:
                    cand = [t for t in cand if tiles[t][S] == tiles[t][N]]
        return cand

    nodes = 0
    stack: list[tuple[list[int], int]] = [(candidates(0), 0)]
    k = 0
    found = False
    while stack:
        cand, pos = stack[-1]
        if pos >= len(cand):
            stack.pop()
            k -= 1
            continue
        stack[-1] = (cand, pos + 1)
        grid[k] = cand[pos]
        nodes += 1
        if max_nodes is not None and nodes > max_nodes or (
            budget is not None and (nodes & 1023) == 0 and budget.spent()
        ):
            spent = _spent(f"{nodes - 1} placements", budget)
            raise no_answer("backtracking", tileset, rows, cols, torus, spent, _ADVICE)
        if k == cells - 1:
            found = True
            break
        k += 1
        stack.append((candidates(k), 0))
    seconds = time.perf_counter() - start
    stats = {"nodes": nodes, "tiles": T}
    if not found:
        return SolveResult(False, None, rows, cols, torus, "backtrack", seconds, stats)
    out = np.array(grid, dtype=np.int64).reshape(rows, cols)
    check_grid(out, tileset, torus=torus, fixed=fixed_n)
    return SolveResult(True, out, rows, cols, torus, "backtrack", seconds, stats)


# ---------------------------------------------------------------------- the shared builder


_OPPOSITE = {"N": "S", "S": "N", "E": "W", "W": "E"}
#: Prototile outline vertex k of a unit square sits at this offset from its SW corner.
_CORNER_OFFSET = ((0, 0), (1, 0), (1, 1), (0, 1))


def builder_prototiles(tileset: WangTileSet) -> list:
    """Unit squares with edge labels ('S', c), ('E', c), ('N', c), ('W', c) (outline order)."""

    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    return [
        Prototile(square, edge_labels=tuple((side, int(row[k])) for side, k in (("S", S), ("E", E), ("N", N), ("W", W))), name=nm)
        for row, nm in zip(tileset.tiles, tileset.tile_names)
    ]


def wang_compatible(a: Any, b: Any) -> bool:
    """Grid adjacency rule: a north edge meets a south edge (east meets west) of one colour."""
    return a is not None and b is not None and _OPPOSITE[a[0]] == b[0] and a[1] == b[1]


class _GridRule:
    """Vertex rule for the builder: every tile lies in the rows x cols rectangle (its SW
    corner at (j, rows - 1 - i) for cell (i, j)) and fixed cells hold their fixed tile. On a
    torus the cell is read modulo (rows, cols) and every position is allowed."""

    def __init__(self, rows: int, cols: int, fixed: Mapping[tuple[int, int], int], torus: bool = False) -> None:
        self.rows, self.cols, self.fixed, self.torus = rows, cols, dict(fixed), torus

    def _ok(self, view: Any) -> bool:
        px, py = view.point
        for c in view.corners:
            dx, dy = _CORNER_OFFSET[c.index]
            x, y = round(px - dx), round(py - dy)
            i, j = self.rows - 1 - y, x
            if self.torus:
                i, j = i % self.rows, j % self.cols
            elif not (0 <= i < self.rows and 0 <= j < self.cols):
                return False
            f = self.fixed.get((i, j))
            if f is not None and f != c.prototile:
                return False
        return True

    def open(self, view: Any) -> bool:
        return self._ok(view)

    def closed(self, view: Any) -> bool:
        return self._ok(view)

    def describe(self) -> str:
        if self.torus:
            return f"cells read modulo the {self.rows} x {self.cols} torus, fixed tiles in place"
        return f"inside the {self.rows} x {self.cols} rectangle, fixed tiles in place"


def builder_solve(
    tileset: WangTileSet,
    rows: int,
    cols: int,
    torus: bool = False,
    fixed: Mapping[Any, Any] | None = None,
    max_nodes: int | None = 2_000_000,
    time_limit: Budget | float | None = DEFAULT_SOLVER_SECONDS,
) -> SolveResult:
    """Decide the rectangle or torus question with :class:`tilekit.builder.PatchBuilder`.

    The seed is the north-west cell; the builder is run once per candidate seed tile (the
    fixed one if that cell is fixed), and "no tiling" is claimed only when every run is
    exhausted. A rectangle is the builder's fill goal "every open edge inside the rectangle";
    a torus is the builder's periodic mode with lattice ((cols, 0), (0, rows)) and its goal
    of a closed torus. The patch found is converted back to a grid and checked independently.
    ``time_limit``: CPU seconds of the calling thread for all the runs together (a number or a
    :class:`tilekit.budget.Budget`).
    """

    rows, cols, fixed_n = prepare_question(tileset, rows, cols, fixed, torus)
    refuse_over_memory("tiles placed by the patch builder", rows * cols,
                       BUILDER_BYTES_PER_TORUS_TILE if torus else BUILDER_BYTES_PER_TILE,
                       hint="use method='sat' or a smaller grid")
    start = time.perf_counter()
    budget = Budget.of(time_limit)
    top = float(rows)

    def inside(edge: Mapping[str, Any]) -> bool:
        """An open edge whose midpoint is strictly inside the rectangle still needs a tile."""
        x, y = edge["midpoint"]  # midpoints are 1/2 off the lattice; 1e-6 absorbs float noise
        return 1e-6 < x < cols - 1e-6 and 1e-6 < y < top - 1e-6

    def scanline(edge: Mapping[str, Any]) -> tuple[float, float]:
        x, y = edge["midpoint"]
        return (-round(y, 6), round(x, 6))

    builder = PatchBuilder(
        builder_prototiles(tileset), compatible=wang_compatible, rule=_GridRule(rows, cols, fixed_n, torus),
        order=scanline, period=((cols, 0), (0, rows)) if torus else None,
    )
    seeds = [fixed_n[(0, 0)]] if (0, 0) in fixed_n else list(range(len(tileset)))
    corner = np.eye(3)
    corner[1, 2] = rows - 1
    nodes = 0
    for seed in seeds:
        left = None if max_nodes is None else max_nodes - nodes
        if (left is not None and left < 1) or (budget is not None and budget.spent()):
            raise _limit_message(tileset, rows, cols, torus, nodes, budget)
        result = builder.build(
            fill=None if torus else inside, seed=seed, seed_transform=corner,
            max_nodes=left if left is not None else 10**12, max_seconds=budget,
        )
        nodes += result.stats.nodes
        if result.status == "limit":
            raise _limit_message(tileset, rows, cols, torus, nodes, budget)
        if result.status == "complete":
            grid = patch_to_grid(result.patch, rows, cols, torus)
            check_grid(grid, tileset, torus=torus, fixed=fixed_n)
            stats = {"nodes": nodes, "seed_runs": seeds.index(seed) + 1}
            return SolveResult(True, grid, rows, cols, torus, "builder", time.perf_counter() - start, stats)
    stats = {"nodes": nodes, "seed_runs": len(seeds)}
    return SolveResult(False, None, rows, cols, torus, "builder", time.perf_counter() - start, stats)


_ADVICE = "raise the time limit (--time-limit S) or max_nodes, or use method='sat'"


def _spent(work: str, budget: Budget | None) -> str:
    """What a search used when it gave up: its work and, with a budget, the CPU seconds."""
    return work if budget is None else f"{work} and {budget.used():.3g} CPU seconds (time limit: {budget})"


def _limit_message(tileset: WangTileSet, rows: int, cols: int, torus: bool, nodes: int,
                   budget: Budget | None) -> SolverLimit:
    return no_answer("the patch builder", tileset, rows, cols, torus, _spent(f"{nodes} nodes", budget), _ADVICE)


def patch_to_grid(patch: Any, rows: int, cols: int, torus: bool = False) -> np.ndarray:
    """The grid of a patch of unit squares covering [0, cols] x [0, rows] (row 0 north); on
    a torus, of one tile per orbit of the lattice ((cols, 0), (0, rows)), anywhere."""
    pos = np.rint(patch.transform[:, :2, 2]).astype(np.int64)
    i = rows - 1 - pos[:, 1]
    j = pos[:, 0]
    if torus:
        i, j = i % rows, j % cols
    if len(patch) != rows * cols or i.min() < 0 or i.max() >= rows or j.min() < 0 or j.max() >= cols:
        raise ParameterError(f"patch of {len(patch)} tiles does not fill the {rows} x {cols} rectangle")
    grid = np.full((rows, cols), -1, dtype=np.int64)
    grid[i, j] = patch.prototile
    if (grid < 0).any():
        raise ParameterError(f"patch leaves a cell of the {rows} x {cols} rectangle empty")
    return grid


# ---------------------------------------------------------------------- one entry point


def solve(
    tileset: WangTileSet,
    rows: int,
    cols: int,
    torus: bool = False,
    fixed: Mapping[Any, Any] | None = None,
    method: str = "sat",
    time_limit: Budget | float | None = DEFAULT_SOLVER_SECONDS,
    **options: Any,
) -> SolveResult:
    """Does ``tileset`` tile a rows x cols rectangle (or torus) with the ``fixed`` tiles?

    ``fixed`` maps (row, column) to a tile index or name. ``method`` is 'sat' (default),
    'builder' or 'backtrack'. Every tiling returned has passed the independent
    checker; "does not tile" is a proof (exhausted search or an UNSAT answer). The call
    ends with a one-line :class:`SolverLimit` after ``time_limit`` CPU seconds (a number or a
    :class:`tilekit.budget.Budget`; default ``limits.DEFAULT_SOLVER_SECONDS``; None: no limit),
    for every method: the calling thread's, and a SAT solver's forked process's.
    """
    if method == "sat":
        return sat_solve(tileset, rows, cols, torus, fixed, time_limit=time_limit, solver=options.pop("solver", DEFAULT_SAT_SOLVER), **options)
    if method == "builder":
        return builder_solve(tileset, rows, cols, torus, fixed, time_limit=time_limit, **options)
    if method == "backtrack":
        return backtrack_solve(tileset, rows, cols, torus, fixed, time_limit=time_limit, **options)
    raise ParameterError(f"solver method {method!r} is not one of {', '.join(METHODS)}")


# ---------------------------------------------------------------------- Wang's procedure


@dataclass
class WangProcedureResult:
    """What Wang's procedure showed, up to ``max_m``.

    ``outcome`` is 'periodic' (an m x m torus exists: the set tiles the plane periodically,
    ``unit`` holds it), 'does_not_tile' (no m x m square can be tiled, hence no tiling of the
    plane) or 'no_answer' (neither happened for m <= max_m: nothing is claimed, in particular
    not aperiodicity). ``steps`` records each m tried.
    """

    set_name: str
    max_m: int
    outcome: str
    m: int | None
    unit: np.ndarray | None
    steps: list[dict[str, Any]] = field(default_factory=list)
    seconds: float = 0.0

    def statement(self) -> str:
        if self.outcome == "periodic":
            return (
                f"set {self.set_name!r} tiles the plane periodically: a torus tiling of size {self.m} x {self.m} "
                f"(translational unit) exists"
            )
        if self.outcome == "does_not_tile":
            return (
                f"set {self.set_name!r} does not tile the plane: no {self.m} x {self.m} square can be tiled"
                + (f" (the {self.m - 1} x {self.m - 1} square can)" if self.m and self.m > 1 else "")
            )
        return (
            f"no answer up to m = {self.max_m}: set {self.set_name!r} tiles every m x m square and "
            f"has no m x m torus for m <= {self.max_m} (this does not show aperiodicity)"
        )

    def to_json(self) -> dict[str, Any]:
        return {
            "set": self.set_name,
            "max_m": self.max_m,
            "outcome": self.outcome,
            "m": self.m,
            "unit": None if self.unit is None else self.unit.tolist(),
            "statement": self.statement(),
            "steps": self.steps,
            "seconds": round(self.seconds, 6),
        }


def wang_procedure(
    tileset: WangTileSet,
    max_m: int,
    method: str = "sat",
    time_limit: float | None = DEFAULT_SOLVER_SECONDS,
    start_m: int = 1,
    total_limit: float | None = None,
) -> WangProcedureResult:
    """Wang's procedure (§6.2) for m = start_m .. max_m.

    For each m, first an m x m torus (found: periodic, stop), then the m x m square (no
    tiling: does not tile, stop). ``time_limit`` bounds each single solver call (default
    ``limits.DEFAULT_SOLVER_SECONDS``), ``total_limit`` the whole procedure: past it, the
    calls left end in a SolverLimit. Both are CPU seconds (:mod:`tilekit.budget`): each call's
    budget is a share of the total's, so a forked solver's CPU counts in both.
    """
    try:
        max_m = int(max_m)
        start_m = int(start_m)
    except (TypeError, ValueError):
        raise ParameterError(f"max_m must be an integer, got {max_m!r}") from None
    if max_m < 1 or start_m < 1 or start_m > max_m:
        raise ParameterError(f"Wang's procedure needs 1 <= start_m <= max_m, got start_m={start_m}, max_m={max_m}")
    began = time.perf_counter()
    steps: list[dict[str, Any]] = []

    total = Budget.of(total_limit)

    def budget() -> Budget | float | None:
        if total is None:
            return time_limit
        left = total.remaining()
        if left <= 0:
            raise SolverLimit(f"Wang's procedure for set {tileset.name!r} ran out of its {total} before m = {m}")
        return total.share(1.0 if time_limit is None or time_limit >= left else time_limit / left)

    for m in range(start_m, max_m + 1):
        tor = solve(tileset, m, m, torus=True, method=method, time_limit=budget())
        step: dict[str, Any] = {"m": m, "torus": tor.tiles, "torus_seconds": round(tor.seconds, 6)}
        if tor.tiles:
            steps.append(step)
            return WangProcedureResult(tileset.name, max_m, "periodic", m, tor.grid, steps, time.perf_counter() - began)
        sq = solve(tileset, m, m, torus=False, method=method, time_limit=budget())
        step.update({"square": sq.tiles, "square_seconds": round(sq.seconds, 6)})
        steps.append(step)
        if not sq.tiles:
            return WangProcedureResult(tileset.name, max_m, "does_not_tile", m, None, steps, time.perf_counter() - began)
    return WangProcedureResult(tileset.name, max_m, "no_answer", None, None, steps, time.perf_counter() - began)
