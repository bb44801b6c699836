"""Heesch numbers of polyforms by SAT, after Kaplan, "Heesch numbers of unmarked polyforms"
(Contributions to Discrete Mathematics 17(2), 2022; arXiv:2105.09438).

A *k-corona patch* is the polyform (the kernel, corona 0) with coronas 1..k around it: corona
i is a set of copies, each touching a copy of corona i-1 (sharing at least a point) and none
touching coronas below i-1, such that every cell sharing a vertex with a copy of coronas 0..i-1
(its *halo*) is covered by coronas 0..i. A hole of the whole patch can then be bounded by
copies of the outermost corona only (a cell touching an inner copy is covered). The hole-free
Heesch number ``Hc`` is the largest k with a k-corona patch whose union has no hole; ``Hh``
allows holes (in the outermost corona), so ``Hc <= Hh <= Hc + 1``. As in Kaplan's
implementation, holes are looked for in the union of all k coronas: a hole of an inner patch
that the next corona fills is allowed (the coronas of a tiling can have such holes, and a
tile that tiles must not get a finite Heesch number).

**Encoding, for k levels.** A Boolean ``y[p, i]`` says placement ``p`` (orientation j moved
by t, see :mod:`placements`) is used in corona i; only placements reachable from the kernel by
i touching steps get a variable at level i. A cell variable ``c``, when true, says a used copy
covers the cell. Clauses:

1. ``c -> OR y`` over the copies covering the cell;
2. at most one used copy covers a cell (a ladder encoding per cell): copies do not overlap;
3. halo: ``y[p, i] -> c`` for every halo cell of p when i < k, and every halo cell of the
   kernel is covered;
4. touching: ``y[p, i] -> OR lev[h, i-1]`` over p's halo cells h, where ``lev[h, i-1]``
   (``-> OR y[q, i-1]`` over copies covering h) says a copy of corona i-1 covers h.

With 2 and 3, a copy that touches a copy of corona m < k has level at most m + 1, so the
levels of a model are exactly the corona numbers of its tiles, and a model is a k-corona
patch up to holes. Holes are found in each model by flood fill and forbidden by a clause
"not all of these tiles at these levels, or some copy of level <= i covering a cell of the
hole" (sound: any model with the same boundary tiles and none in the hole has the hole), and
the solver is asked again, as in Kaplan's implementation.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from tilekit import limits
from tilekit.budget import Budget
from tilekit.errors import ParameterError
from tilekit.jit import njit
from tilekit.lattice import (
    _M,
    _OFF,
    Grid,
    _empty_components,
    _vertex_neighbours,
    holes_of,
    pack,
    unique_keys,
    unpack,
    vertex_neighbour_table,
)
from tilekit.plugins.polyomino.placements import Forms, _adjacent, _halos, _orientations
from tilekit.sat import CNF, DEFAULT_SAT_SOLVER, NATIVE_ATMOST, IncrementalSolver, gc_paused

#: The most coronas a search will build (Kaplan's sat tool stops at 7 by default).
MAX_LEVEL_LIMIT = 12
#: The Hc-only search's solver: Glucose with native at-most-one constraints (Gluecard), which
#: spares the per-cell clausal ladders (measured on the non-tiling 10-ominoes: half the time of
#: Glucose with ladders, docs/benchmarks.md).
HC_SOLVER = "gluecard4"
#: The same solver with native at-most-one constraints: Gluecard is Glucose 4.1 and Minicard is
#: Minisat 2.2, each with cardinality constraints, so :class:`CoronaLadder` asked for Glucose or
#: Minisat runs them (the classification's coronas: 1.1-1.9x less CPU than Glucose with ladders
#: on the forms of five grids that need a solver, docs/benchmarks.md).
NATIVE_VARIANT = {"glucose4": "gluecard4", "minisat22": "minicard"}


#: Estimates below this many bytes skip the memory probe (it reads /proc, ~0.1 ms, more than
#: an easy shape's whole level-1 test); any machine holds them.
SMALL_BYTES = 1 << 24


def _refuse_over_memory(what: str, count: float, bytes_each: float, hint: str = "") -> None:
    """:func:`tilekit.limits.refuse_over_memory` for estimates of at least :data:`SMALL_BYTES`."""
    if count * bytes_each >= SMALL_BYTES:
        limits.refuse_over_memory(what, count, bytes_each, hint=hint)


@dataclass
class Corona:
    """A k-corona patch: rows ``(j, tx, ty)`` of placements with their corona numbers."""

    rows: np.ndarray  # (m, 3) including the kernel (level 0) first
    levels: np.ndarray  # (m,)
    holes: bool  # the union has a hole (only the outermost corona can cause one)

    @property
    def k(self) -> int:
        return int(self.levels.max()) if len(self.levels) else 0

    def to_json(self) -> dict:
        return {"kind": "coronas", "k": self.k, "holes": bool(self.holes),
                "tiles": [[int(j), int(x), int(y), int(lv)] for (j, x, y), lv in zip(self.rows.tolist(), self.levels.tolist())]}


@dataclass
class HeeschResult:
    """``hc`` and ``hh`` (None when undecided); witnesses; what the search did."""

    hc: int | None
    hh: int | None
    hc_witness: Corona | None
    hh_witness: Corona | None
    surrounded: int  # the most coronas found (hole-free), = hc when decided
    decided: bool
    reason: str
    sat_calls: int = 0
    seconds: float = 0.0


@njit(cache=True)
def _least_holes(pairs, at, nbr, period):  # pragma: no cover - compiled
    """Per row of ``pairs`` (cells of two copies), the size of its smallest hole (0: none)."""
    out = np.zeros(pairs.shape[0], np.int64)
    for i in range(pairs.shape[0]):
        lab, x0, y0, w, comps = _empty_components(pairs[i], at, nbr, period)
        if comps <= 1:
            continue
        size = np.zeros(comps, np.int64)
        for v in range(lab.shape[0]):
            if lab[v] > 0:
                size[lab[v]] += 1
        out[i] = size[1:].min()
    return out


def unfillable_pairs(grid: Grid, forms: Forms, j: int = 0) -> np.ndarray:
    """Which rows of ``forms.adjacent[j]`` make, with ``forms[j]``, a hole of fewer cells than
    the polyform: no copy fits in it (a copy covering a cell of the hole lies inside it), so a
    hole-free patch never uses the two copies together. Kaplan's heesch-sat drops every pair
    whose union is not simply connected; this keeps the pairs whose hole a copy could fill."""
    return unfillable_rows(grid, forms, forms.adjacent_to(j), j)


def unfillable_rows(grid: Grid, forms: Forms, rows: np.ndarray, j: int = 0) -> np.ndarray:
    """:func:`unfillable_pairs` for the given placement rows touching ``forms[j]``."""
    if not len(rows):
        return np.zeros(0, dtype=bool)
    cells = np.concatenate([np.broadcast_to(forms.forms[j], (len(rows), forms.n, 2)),
                            forms.forms[rows[:, 0]] + rows[:, None, 1:3]], axis=1)
    least = _least_holes(np.ascontiguousarray(cells), grid.type_table, grid.neighbours.astype(np.int64),
                         np.int64(grid.period))
    return (least > 0) & (least < forms.n)


@njit(cache=True)
def _support(col, hcol, ncells):  # pragma: no cover - compiled
    """Arc consistency of :func:`first_corona_support` over cell indices: ``col`` (m, n) the
    cells of each copy, ``hcol`` (H,) the halo's cells; the mask of copies kept."""
    m, n = col.shape
    H = hcol.shape[0]
    inc = np.zeros((m, ncells), np.bool_)
    for p in range(m):
        for k in range(n):
            inc[p, col[p, k]] = True
    # per cell, the copies covering it (CSR, in copy order): overlaps are read from these lists,
    # O(m n c) for c copies a cell, not O(m^2 n) over all pairs
    cstart = np.zeros(ncells + 1, np.int64)
    for p in range(m):
        for k in range(n):
            cstart[col[p, k] + 1] += 1
    for c in range(ncells):
        cstart[c + 1] += cstart[c]
    fill = cstart[:-1].copy()
    cov = np.empty(m * n, np.int64)
    for p in range(m):
        for k in range(n):
            c = col[p, k]
            cov[fill[c]] = p
            fill[c] += 1
    overlap = np.zeros((m, m), np.bool_)
    for p in range(m):
        for k in range(n):
            c = col[p, k]
            for i in range(cstart[c], cstart[c + 1]):
                overlap[p, cov[i]] = True
    # per halo cell, the copies covering it (CSR)
    start = np.zeros(H + 1, np.int64)
    for h in range(H):
        start[h + 1] = start[h] + cstart[hcol[h] + 1] - cstart[hcol[h]]
    cover = np.zeros(start[H], np.int64)
    for h in range(H):
        cover[start[h]:start[h + 1]] = cov[cstart[hcol[h]]:cstart[hcol[h] + 1]]
    alive = np.ones(m, np.bool_)
    changed = True
    while changed:
        changed = False
        for h in range(H):
            any_alive = False
            for c in range(start[h], start[h + 1]):
                if alive[cover[c]]:
                    any_alive = True
                    break
            if not any_alive:
                alive[:] = False
                return alive
        for p in range(m):
            if not alive[p]:
                continue
            for h in range(H):
                if inc[p, hcol[h]]:
                    continue
                ok = False
                for c in range(start[h], start[h + 1]):
                    q = cover[c]
                    if alive[q] and not overlap[p, q]:
                        ok = True
                        break
                if not ok:
                    alive[p] = False
                    changed = True
                    break
    return alive


def first_corona_support(cells: np.ndarray, halo: np.ndarray) -> np.ndarray:
    """The copies of corona 1 that can be in some corona patch, by a local test before any SAT.

    ``cells`` (m, n) are the packed cells of the candidate copies (each touching the kernel,
    none overlapping it), ``halo`` the kernel's halo. In every patch of k >= 1 coronas (holes
    allowed) each halo cell is covered by a copy of corona 1 (a copy covering it touches the
    kernel, and only corona 1 does), and the copies do not overlap. So a copy p can be used
    only if every halo cell h is covered by p or by some usable copy disjoint from p; removing
    the copies that fail this until none does (arc consistency, a compiled loop over all
    copies) keeps every copy of every patch. Returns the mask of the copies kept; all False
    when some halo cell is left with no copy: then no corona exists at all (Hc = Hh = 0, a
    proof that the polyform does not tile).
    """
    if not len(cells):
        return np.zeros(0, dtype=bool)
    return _support_keys(np.ascontiguousarray(cells, dtype=np.int64), np.ascontiguousarray(halo, dtype=np.int64))


@njit(cache=True)
def _support_keys(pk, hkeys):  # pragma: no cover - compiled
    """:func:`first_corona_support` on packed keys ``pk`` (m, n), m >= 1, and ``hkeys`` (H,):
    the cells numbered by their rank among the copies' cells, then :func:`_support`."""
    m = pk.shape[0]
    universe = np.unique(pk.ravel())
    H = hkeys.shape[0]
    hcol = np.empty(H, np.int64)
    for h in range(H):
        q = np.searchsorted(universe, hkeys[h])
        if q >= universe.shape[0] or universe[q] != hkeys[h]:
            return np.zeros(m, np.bool_)  # a halo cell no copy covers
        hcol[h] = q
    col = np.searchsorted(universe, pk.ravel()).reshape(pk.shape)
    return _support(col, hcol, universe.shape[0])


@njit(cache=True)
def _first_corona(cells, group, period, table, types):  # pragma: no cover - compiled
    """:func:`first_corona_rows` in one compiled call: the orientations, the kernel's halo, the
    copies touching the kernel (:func:`placements._adjacent`) and the local test
    (:func:`_support`)."""
    forms, keys, _g, _shift, _owner, _gshift = _orientations(cells, group, period)
    n = cells.shape[0]
    off, mm = np.int64(_OFF), np.int64(_M)
    halo = _halos(forms[:1], table, types, period)[0]
    rows = _adjacent(forms, halo, keys[0], period)
    m = rows.shape[0]
    if m == 0:
        return rows
    pk = np.empty((m, n), np.int64)
    for p in range(m):
        f = rows[p, 0]
        for i in range(n):
            pk[p, i] = (forms[f, i, 0] + rows[p, 1] + off) * mm + (forms[f, i, 1] + rows[p, 2] + off)
    H = halo.shape[0]
    hkeys = np.empty(H, np.int64)
    for h in range(H):
        hkeys[h] = (halo[h, 0] + off) * mm + (halo[h, 1] + off)
    return rows[_support_keys(pk, hkeys)]


def first_corona_rows(grid: Grid, cells: np.ndarray) -> np.ndarray:
    """The candidate copies of corona 1 that pass the local test of :func:`first_corona_support`,
    as placement rows ``(j, tx, ty)`` of :class:`Forms` (the same rows, in the same order, as
    :class:`HeeschSolver`'s first level), in one compiled call without building :class:`Forms`.
    Empty: no corona exists even with holes, so Hc = Hh = 0 and the polyform does not tile
    (most forms of the drafter and bevelhex grids end here, where setting up the solver was
    most of their cost)."""
    # the grid's tables are cached where they are defined (vertex_neighbour_table, Grid.type_table)
    return _first_corona(np.ascontiguousarray(cells, dtype=np.int64).reshape(-1, 2), grid.group.astype(np.int64),
                         np.int64(grid.period), vertex_neighbour_table(grid), grid.type_table)


def cover_index(cells: np.ndarray, ys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every cell of candidate copies ``cells`` (m, n packed keys) with the variable ``ys`` (m,)
    of its copy, sorted by key (then by variable): the index :func:`hole_clauses` looks holes up in."""
    flat = cells.ravel()
    y = np.repeat(ys, cells.shape[1])
    order = np.lexsort((y, flat))
    return flat[order], y[order]


def hole_clauses(grid: Grid, cells: np.ndarray, ys: np.ndarray, index: tuple[np.ndarray, np.ndarray]) -> list[list[int]]:
    """The clauses forbidding each hole of a model's patch: not all of the copies around the
    hole, or some candidate copy covering one of its cells. ``cells`` (m, n) are the packed
    cells of the model's copies and ``ys`` their variables (0 for the kernel, which is always
    there and left out); ``index`` is :func:`cover_index` over every candidate copy. Each
    clause lists the copies around in the model's order, then the copies inside by variable;
    empty when the patch has no hole. Copies of a model do not overlap, so a cell is one
    copy's: the lookups are sorted searches, not a set test per hole."""
    holes = holes_of(grid, cells.ravel())
    if not holes:
        return []
    flat = cells.ravel()
    order = np.argsort(flat, kind="stable")
    sk, row = flat[order], order // cells.shape[1]
    ck, cy = index
    out = []
    for hole in holes:
        hx = unpack(hole)
        ring = pack(hx[:, None, :] + grid.neighbours[grid.cell_type(hx)]).ravel()
        pos = np.minimum(np.searchsorted(sk, ring), len(sk) - 1)
        rows = np.unique(row[pos[sk[pos] == ring]])
        around = ys[rows]
        lo, hi = np.searchsorted(ck, hole, "left"), np.searchsorted(ck, hole, "right")
        inside = np.unique(np.concatenate([cy[a:b] for a, b in zip(lo.tolist(), hi.tolist())]))
        out.append([*(-around[around != 0]).tolist(), *inside.tolist()])
    return out


class HeeschSolver:
    """Coronas of one polyform, level by level (see the module docstring)."""

    def __init__(self, grid: Grid, cells: np.ndarray, *, solver: str = DEFAULT_SAT_SOLVER,
                 first: np.ndarray | None = None) -> None:
        """``first``: corona 1's rows from :func:`first_corona_rows`, when already computed."""
        self.grid = grid
        self.forms = Forms(grid, cells)
        self.solver = solver
        self.kernel_keys = np.sort(self.forms.keys[0])
        self.kernel_halo = unique_keys(self.forms.placement_halos(np.array([[0, 0, 0]]))[0])
        self.levels: list[np.ndarray] = [np.array([[0, 0, 0]], dtype=np.int64)]  # level 0: kernel
        if first is not None:
            self.levels.append(np.asarray(first, dtype=np.int64).reshape(-1, 3))
        self.sat_calls = 0
        self.solve_seconds = 0.0  # inside the solver (the rest is building the formulas)
        #: (Hc, Hh, hole-free witness, holey witness) once Kaplan's loop has stopped
        self.kaplan: tuple[int, int, Corona, Corona] | None = None
        self.ladder: CoronaLadder | None = None  # :func:`heesch`'s levels in one solver

    def ladder_at(self, k: int) -> CoronaLadder | None:
        """This polyform's :class:`CoronaLadder` (one incremental solver for every level, made on
        first use) holding exactly ``k`` coronas, or None when it already holds more."""
        if self.ladder is None:
            self.ladder = CoronaLadder(self)
        if self.ladder.k > k:
            return None
        while self.ladder.k < k:
            self.ladder.add_level()
        return self.ladder

    def close(self) -> None:
        """Free the ladder's solver (the per-level formulas free theirs as they go)."""
        if self.ladder is not None:
            self.ladder.close()
            self.ladder = None

    def drop_enclosing(self) -> int:
        """For hole-free questions only: leave out of corona 1 the copies that make an
        unfillable hole with the kernel (:func:`unfillable_rows`), then repeat the local test
        of :func:`first_corona_support` on what is left; corona 2 on is grown from what is
        left. Call before any level is grown; returns how many were left out."""
        if len(self.levels) > 1:
            raise ParameterError("drop_enclosing() must come before the coronas are grown")
        self._grow()
        rows = self.levels[1]
        bad = unfillable_rows(self.grid, self.forms, rows, 0)
        if bad.any():
            kept = rows[~bad]
            self.levels[1] = kept[first_corona_support(self.forms.placement_cells(kept), self.kernel_halo)]
        return int(len(rows) - len(self.levels[1]))

    # -- placements per level -------------------------------------------------------------
    def _row_keys(self, rows: np.ndarray) -> np.ndarray:
        """One int64 per placement row (orientation, translation)."""
        return pack(rows[:, 1:3]) * 64 + rows[:, 0]

    def _grow(self) -> None:
        """Add the placements of the next level: copies touching a copy of the last level."""
        last = self.levels[-1]
        if len(self.levels) == 1:  # corona 1: the copies touching the kernel, less the local test
            rows = self.forms.adjacent_to(0)
            self.levels.append(rows[first_corona_support(self.forms.placement_cells(rows), self.kernel_halo)])
            return
        used = np.unique(last[:, 0]).tolist()
        adj = {j: self.forms.adjacent_to(j) for j in used}
        # estimate first: every copy of the last level times the copies touching it, as
        # (orientation, tx, ty) rows plus their keys, before any is allocated
        candidates = sum(int((last[:, 0] == j).sum()) * len(adj[j]) for j in used)
        _refuse_over_memory(f"candidate placements for corona {len(self.levels)}", candidates, 72,
                            hint="ask for fewer coronas (--max-level)")
        parts = []
        for j in used:
            sel = last[last[:, 0] == j]
            if not len(sel) or not len(adj[j]):
                continue
            a = adj[j]
            rows = np.empty((len(sel), len(a), 3), dtype=np.int64)
            rows[..., 0] = a[None, :, 0]
            rows[..., 1:] = sel[:, None, 1:] + a[None, :, 1:]
            parts.append(rows.reshape(-1, 3))
        if not parts:
            self.levels.append(np.zeros((0, 3), dtype=np.int64))
            return
        rows = np.concatenate(parts)
        _, first = np.unique(self._row_keys(rows), return_index=True)
        rows = rows[np.sort(first)]
        clash = np.isin(self.forms.placement_cells(rows), self.kernel_keys).any(axis=1)
        if len(self.levels) >= 2:  # coronas 2, 3, ... do not touch the kernel
            clash |= np.isin(self.forms.placement_cells(rows), self.kernel_halo).any(axis=1)
        self.levels.append(rows[~clash])

    def starved(self, k: int) -> bool:
        """Whether some corona 1..k has no candidate copy at all, so that no k-corona patch
        exists (each corona must cover the nonempty halo of the one inside it). On grids with
        cells of several shapes this is common: a form of bevelhex hexagons and squares has no
        copy covering the dodecagons around it."""
        while len(self.levels) <= k:
            self._grow()
        return any(not len(self.levels[i]) for i in range(1, k + 1))

    # -- encoding ---------------------------------------------------------------------------
    def _encode(self, k: int):
        """Clauses for k coronas; returns (clauses, var tables) — see the module docstring."""
        while len(self.levels) <= k:
            self._grow()
        nv = sum(len(self.levels[i]) for i in range(1, k + 1))
        n, h = self.forms.n, self.forms.halos.shape[1]
        # estimate first (measured on 9-ominoes at 1-3 coronas: ~n + 2 variables and ~40 clauses
        # per placement variable, ~130 bytes per clause as Python lists)
        hint = "ask for fewer coronas (--max-level)"
        limits.refuse_over(f"SAT variables for {k} coronas", nv * (n + 2), limits.MAX_SAT_VARIABLES, hint=hint)
        limits.refuse_over_memory(f"clauses for {k} coronas", nv * (4 * n + h), 130, hint=hint)
        rows = np.concatenate(self.levels[1:k + 1])
        lvl = np.concatenate([np.full(len(self.levels[i]), i) for i in range(1, k + 1)])
        yvar = np.arange(1, nv + 1, dtype=np.int64)
        pcells = self.forms.placement_cells(rows)  # (nv, n)
        phalo = self.forms.placement_halos(rows)  # (nv, H)
        inner = lvl < k
        universe = unique_keys(np.concatenate([pcells.ravel(), phalo[inner].ravel(), self.kernel_halo]))
        universe = universe[~np.isin(universe, self.kernel_keys)]
        cvar = nv + 1 + np.arange(len(universe), dtype=np.int64)
        top = nv + len(universe)

        def cell_var(keys: np.ndarray) -> np.ndarray:
            pos = np.searchsorted(universe, keys)
            pos = np.minimum(pos, len(universe) - 1)
            hit = universe[pos] == keys
            return np.where(hit, cvar[pos], 0)  # 0: a kernel cell (always covered)

        clauses: list[list[int]] = []
        pc = cell_var(pcells)  # never 0: placements avoid the kernel
        # 1. c -> OR y. (y -> c is not needed: c occurs positively only in the halo clauses,
        # so a model with c false under a copy stays a model with c true.)
        flat_c = pc.ravel()
        flat_y = np.repeat(yvar, pcells.shape[1])
        order = np.argsort(flat_c, kind="stable")
        sc, sy = flat_c[order], flat_y[order]
        starts = np.flatnonzero(np.r_[True, sc[1:] != sc[:-1]])
        covered = sc[starts]
        groups = np.split(sy, starts[1:])
        uncovered = np.setdiff1d(cvar, covered)
        clauses += [[-int(c)] for c in uncovered]
        clauses += [[-int(c), *g.tolist()] for c, g in zip(covered.tolist(), groups)]
        # 2. at most one copy per cell: ladder s_i over each group (lits l_1..l_m)
        gid = np.repeat(np.arange(len(starts)), np.diff(np.r_[starts, len(sc)]))
        same_next = np.r_[gid[1:] == gid[:-1], False]
        idx = np.flatnonzero(same_next)  # positions i with l_{i+1} in the same group
        s = top + 1 + np.arange(len(idx), dtype=np.int64)
        top += len(idx)
        l_i, l_next = sy[idx], sy[idx + 1]
        clauses += np.column_stack([-l_i, s]).tolist()
        clauses += np.column_stack([-s, -l_next]).tolist()
        chain = np.flatnonzero(np.r_[idx[1:] == idx[:-1] + 1, False])
        clauses += np.column_stack([-s[chain], s[chain + 1]]).tolist()
        # 3. halos of inner copies and of the kernel
        hv = cell_var(phalo[inner])
        yi = np.repeat(yvar[inner], phalo.shape[1])
        hv = hv.ravel()
        keep = hv != 0
        clauses += np.column_stack([-yi[keep], hv[keep]]).tolist()
        kh = cell_var(self.kernel_halo)
        clauses += [[int(c)] for c in kh[kh != 0]]
        # 4. a copy of corona i >= 2 touches a copy of corona i-1: lev[h, i-1]
        false_var = top + 1
        top += 1
        clauses.append([-false_var])
        levs = {}
        for i in range(1, k):
            at = lvl == i
            cb = pcells[at].ravel()
            yb = np.repeat(yvar[at], pcells.shape[1])
            o = np.argsort(cb, kind="stable")
            cb, yb = cb[o], yb[o]
            st = np.flatnonzero(np.r_[True, cb[1:] != cb[:-1]])
            lev_keys = cb[st]
            lev = top + 1 + np.arange(len(lev_keys), dtype=np.int64)
            top += len(lev_keys)
            # lev[h, i] <-> some copy of corona i covers h
            clauses += [[-int(v), *g.tolist()] for v, g in zip(lev.tolist(), np.split(yb, st[1:]))]
            clauses += np.column_stack([-yb, np.repeat(lev, np.diff(np.r_[st, len(cb)]))]).tolist()
            levs[i] = (lev_keys, lev)

        def lev_lits(i: int, keys: np.ndarray) -> np.ndarray:
            lev_keys, lev = levs[i]
            pos = np.minimum(np.searchsorted(lev_keys, keys), len(lev_keys) - 1)
            return np.where(lev_keys[pos] == keys, lev[pos], false_var)

        for i in range(2, k + 1):
            here = lvl == i
            hk = phalo[here]
            # touches a copy of corona i-1 ...
            clauses += np.column_stack([-yvar[here], lev_lits(i - 1, hk)]).tolist()
            # ... and none of coronas 1..i-2 (the kernel is excluded when the levels are grown)
            for j in range(1, i - 1):
                lits = lev_lits(j, hk).ravel()
                yy = np.repeat(yvar[here], hk.shape[1])
                keep = lits != false_var
                clauses += np.column_stack([-yy[keep], -lits[keep]]).tolist()
        return clauses, {"rows": rows, "lvl": lvl, "yvar": yvar, "top": top, "cells": pcells}

    # -- solving ----------------------------------------------------------------------------
    def _holes(self, table: dict, used: np.ndarray) -> list[list[int]]:
        """The clauses forbidding each hole of the model's patch (``used``: which y are true),
        :func:`hole_clauses` over this formula's copies."""
        if "index" not in table:
            table["index"] = cover_index(table["cells"], table["yvar"])
        cells = np.concatenate([self.kernel_keys[None, :], table["cells"][used]])
        ys = np.concatenate([[0], table["yvar"][used]])
        return hole_clauses(self.grid, cells, ys, table["index"])

    def surrounds(self, k: int, *, time_limit: Budget | float | None = None) -> bool | None:
        """Whether k coronas exist with holes allowed (no hole checks: the coronas of any
        tiling satisfy this formula); None when the time limit (CPU seconds) is spent."""
        if self.starved(k):
            return False
        with gc_paused():
            clauses, _ = self._encode(k)
        with IncrementalSolver(clauses, solver=self.solver) as s:
            ans = s.solve(time_limit=time_limit)
        self.sat_calls += 1
        self.solve_seconds += ans.seconds
        return ans.satisfiable

    def corona(self, k: int, *, time_limit: Budget | float | None = None) -> tuple[Corona | None, Corona | None, bool | None]:
        """(hole-free k-corona patch or None, k-corona patch with holes allowed in its outer
        corona or None, decided) for exactly ``k`` coronas; undecided when ``time_limit`` (a
        budget, or CPU seconds) is spent."""
        if k == 0:
            kern = Corona(self.levels[0].copy(), np.zeros(1, dtype=np.int64), False)
            return kern, kern, True
        if self.starved(k):
            return None, None, True
        with gc_paused():
            clauses, table = self._encode(k)
        hf = table["top"] + 1  # selector: the outermost corona is hole-free too
        budget = Budget.of(time_limit)
        with IncrementalSolver(clauses, solver=self.solver) as s:
            with_holes: Corona | None = None
            assume: list[int] = []
            while True:
                ans = s.solve(assumptions=assume, time_limit=budget)
                self.sat_calls += 1
                self.solve_seconds += ans.seconds
                if ans.satisfiable is None:
                    return None, with_holes, None
                if not ans.satisfiable:
                    return None, with_holes, True
                used = ans.values(table["yvar"])
                rows = np.concatenate([self.levels[0], table["rows"][used]])
                lv = np.concatenate([[0], table["lvl"][used]])
                found = self._holes(table, used)
                if not found:
                    return Corona(rows, lv, False), with_holes or Corona(rows, lv, False), True
                for clause in found:
                    s.add([-hf, *clause])
                if with_holes is None:  # holes, all in the outermost corona: a witness for Hh >= k
                    with_holes = Corona(rows, lv, True)
                assume = [hf]


def heesch(grid: Grid, cells: np.ndarray, *, max_level: int = 6, solver: str = DEFAULT_SAT_SOLVER,
           time_limit: Budget | float | None = None, start: int = 1, hs: HeeschSolver | None = None,
           best: Corona | None = None) -> HeeschResult:
    """Hc and Hh of a hole-free polyform, trying 1..max_level coronas; ``decided`` only with a
    proof that it does not tile.

    Kaplan's numbers stop at the first level k with no hole-free patch (Hc = k - 1, and Hh = k
    when k coronas exist only with holes). That alone does not prove the tile cannot tile: the
    coronas of a tiling can enclose holes that the next corona fills. The proof is a level at
    which no patch exists even with holes (the formula without hole clauses, which the coronas
    of any tiling satisfy), so after a holey level the search goes on, without hole checks,
    until such a level or ``max_level``. Undecided (``decided=False``) when ``max_level``
    coronas exist or the time limit (a :class:`Budget`, or CPU seconds) is spent first; ``hc``/``hh`` then hold Kaplan's values if
    they were found (the polyform may still tile).
    """
    if not 0 <= max_level <= MAX_LEVEL_LIMIT:
        raise ParameterError(f"max_level must be between 0 and {MAX_LEVEL_LIMIT}, got {max_level}")
    budget = Budget.of(time_limit)
    if hs is not None:
        return _heesch(hs, max_level, budget, start, best)
    hs = HeeschSolver(grid, cells, solver=solver)
    try:
        return _heesch(hs, max_level, budget, start, best)
    finally:
        hs.close()


def _heesch(hs: HeeschSolver, max_level: int, budget: Budget | None, start: int, best: Corona | None) -> HeeschResult:
    """:func:`heesch` on a solver's levels (its ladder left open for the caller's next call)."""
    t0 = time.monotonic()
    best = best or Corona(hs.levels[0].copy(), np.zeros(1, dtype=np.int64), False)  # the kernel

    def result(decided: bool, reason: str, surrounded: int) -> HeeschResult:
        hc, hh, hcw, hhw = hs.kaplan if hs.kaplan else (None, None, best, None)
        return HeeschResult(hc, hh, hcw, hhw, surrounded, decided, reason, hs.sat_calls, time.monotonic() - t0)

    for k in range(start, max_level + 1):
        if budget is not None and budget.spent():
            return result(False, f"time limit ({budget}) spent after {k - 1} coronas", k - 1)
        answer = ok = None
        try:  # the proof question (holes allowed) once Kaplan's numbers are known, else coronas
            lad = hs.ladder_at(k)
            if lad is None:  # levels asked out of order: a formula of its own
                if hs.kaplan:
                    ok = hs.surrounds(k, time_limit=budget)
                else:
                    answer = hs.corona(k, time_limit=budget)
            elif hs.kaplan:
                ok = False if lad.empty else lad.solve([], budget).satisfiable
            else:
                answer = lad.corona(False, budget)
        except limits.LimitError as exc:  # a bound like the time limit: undecided, with the reason
            return result(False, f"{k} coronas: {exc}", k - 1)
        if answer is None:
            if ok is None:
                return result(False, f"time limit ({budget}) spent while looking for {k} coronas with holes", k - 1)
            if not ok:
                hc, hh = hs.kaplan[:2]
                return result(True, f"{hh} corona{'s' if hh != 1 else ''} only with a hole in the outermost corona; "
                                    f"no {k}-corona patch even with holes", k - 1)
            continue
        free, holey, decided = answer
        if decided is None:
            return result(False, f"time limit ({budget}) spent while looking for {k} coronas", k - 1)
        if free is not None:
            best = free
            continue
        if holey is not None:
            hs.kaplan = (k - 1, k, best, holey)
            continue
        hs.kaplan = (k - 1, k - 1, best, best)
        return result(True, f"no {k}-corona patch exists", k - 1)
    if hs.kaplan:
        hc, hh = hs.kaplan[:2]
        return result(False, f"Hc = {hc}, Hh = {hh} by Kaplan's reading, but {max_level} coronas exist with holes "
                             f"(not a proof that it cannot tile)", max_level)
    return result(False, f"surrounded by {max_level} coronas", max_level)



# --------------------------------------------------------------------------- one solver, all levels

def _groups(keys: np.ndarray, ids: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Sort ``ids`` by ``keys``: (distinct keys, group starts, ids in key order)."""
    o = np.argsort(keys, kind="stable")
    k, v = keys[o], ids[o]
    st = np.flatnonzero(np.r_[True, k[1:] != k[:-1]]) if len(k) else np.zeros(0, dtype=np.int64)
    return k[st], st, v


def _padded(first: np.ndarray, starts: np.ndarray, members: np.ndarray, pad: int) -> np.ndarray:
    """Rows ``[first[g], members of group g..., pad, ...]``: variable-length clauses as one
    rectangular block, short rows filled with the always-false literal ``pad``."""
    sizes = np.diff(np.r_[starts, len(members)])
    out = np.full((len(starts), 1 + int(sizes.max(initial=0))), pad, dtype=np.int64)
    out[:, 0] = first
    col = np.arange(len(members)) - np.repeat(starts, sizes)
    out[np.repeat(np.arange(len(starts)), sizes), 1 + col] = members
    return out



@njit(cache=True)
def _vertex_pairs(keys, table, period, offs, starts, kernel):  # pragma: no cover - compiled
    """:meth:`CoronaLadder._vertex_pairs`: for each cell type r in turn, each cell of ``keys``
    (packed) of that type and each of its vertex neighbours ``offs[starts[r]:starts[r + 1]]``
    not among the sorted ``kernel`` keys, the pair (cell, neighbour) of packed keys."""
    off, mm = np.int64(_OFF), np.int64(_M)
    n = keys.shape[0]
    types = np.empty(n, np.int64)
    for i in range(n):
        x, y = keys[i] // mm - off, keys[i] % mm - off
        types[i] = table[(y % period) * period + x % period]
    out_c = np.empty(n * (offs.shape[0] + 1), np.int64)
    out_d = np.empty(n * (offs.shape[0] + 1), np.int64)
    k = 0
    nk = kernel.shape[0]
    for r in range(starts.shape[0] - 1):
        for i in range(n):
            if types[i] != r:
                continue
            x, y = keys[i] // mm - off, keys[i] % mm - off
            for o in range(starts[r], starts[r + 1]):
                dk = (x + offs[o, 0] + off) * mm + (y + offs[o, 1] + off)
                q = np.searchsorted(kernel, dk)
                if q < nk and kernel[q] == dk:
                    continue
                out_c[k] = keys[i]
                out_d[k] = dk
                k += 1
    return out_c[:k].copy(), out_d[:k].copy()


class CoronaLadder:
    """The corona formulas of :class:`HeeschSolver` for k = 1, 2, ... in one incremental solver.

    Level i's variables and clauses never depend on how many levels are asked for, except for
    the halo clauses, which hold for inner coronas only: they are added for level i - 1 when
    level i is added, so the solver holding levels 1..k is exactly the k-corona formula
    (holes allowed). The clauses are the module docstring's, regrouped by level so that none
    has to be taken back:

    - ``lev[h, i]`` <-> some copy of corona i covers cell h (with at most one such copy: a
      ladder per cell and level), and at most one level covers a cell (pairwise);
    - halo of a copy p of corona i < k: each halo cell h is the kernel's or has
      ``lev[h, i-1] or lev[h, i] or lev[h, i+1]`` (a copy covering h touches p, so by the
      touching clauses its level is i - 1, i or i + 1);
    - the kernel's halo: ``lev[h, 1]`` for each halo cell h (a cell that no copy of corona 1
      can cover ends the search with Hc = Hh = 0 before any solver is made);
    - touching: ``y[p, i] -> OR lev[h, i-1]`` over p's halo, and ``y[p, i] -> not lev[h, j]``
      for j <= i - 2.

    Copies of levels two or more apart cannot overlap (an overlapping copy covers a halo cell),
    so the per-level ladders and the pairwise level exclusion forbid every overlap. Hole
    clauses found at level k are guarded by a selector assumed only for the hole-free question
    at level k. Variable-length clauses are padded with an always-false literal so that every
    group of clauses is one integer array (:meth:`tilekit.sat.CNF.add_block`).
    """

    def __init__(self, hs: HeeschSolver) -> None:
        self.hs = hs
        self.k = 0
        self.top = 1
        self.false = 1  # variable 1 is always false
        self.rows: list[np.ndarray] = [hs.levels[0]]
        self.cells: list[np.ndarray] = [hs.kernel_keys[None, :]]
        self.halos: list[np.ndarray] = [hs.kernel_halo[None, :]]
        self.y: list[np.ndarray] = [np.zeros(1, dtype=np.int64)]
        self.lev: list[tuple[np.ndarray, np.ndarray]] = [(hs.kernel_keys, np.zeros(len(hs.kernel_keys), dtype=np.int64))]
        self.solver: IncrementalSolver | None = None
        self.pending = CNF()
        self.pending.add([-self.false])
        self.empty = False  # a clause with no literal was met: no k-corona for any k >= self.k
        #: the solver, as its variant with native at-most-one constraints when it has one
        self.solver_name = NATIVE_VARIANT.get(hs.solver, hs.solver)
        self.native = self.solver_name in NATIVE_ATMOST  # at-most-one as native constraints
        self.pairs: list[tuple[np.ndarray, np.ndarray]] = [(np.zeros(0, dtype=np.int64),) * 2]
        grid = hs.grid
        #: per cell type, the offsets of the cells sharing a vertex with it
        self.around = _vertex_neighbours(grid)
        #: the same as one array of offsets and each type's start in it
        self.around_flat = (np.ascontiguousarray(np.concatenate(self.around), dtype=np.int64),
                            np.cumsum([0] + [len(o) for o in self.around]).astype(np.int64))
        #: (k, :func:`cover_index` of the candidate copies of levels 1..k), made on the first hole
        self.index: tuple[int, tuple[np.ndarray, np.ndarray]] | None = None

    def _vertex_pairs(self, keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(c, d) for every cell c of ``keys`` and every cell d sharing a vertex with it,
        d not a kernel cell (a kernel cell is covered): the cells of each type in turn, in the
        order of ``keys``, one compiled call (:func:`_vertex_pairs`)."""
        grid = self.hs.grid
        offs, starts = self.around_flat
        return _vertex_pairs(np.ascontiguousarray(keys, dtype=np.int64), grid.type_table, np.int64(grid.period),
                             offs, starts, self.hs.kernel_keys)

    def close(self) -> None:
        if self.solver is not None:
            self.solver.close()
            self.solver = None

    def _vars(self, m: int) -> np.ndarray:
        out = np.arange(self.top + 1, self.top + 1 + m, dtype=np.int64)
        self.top += m
        return out

    def _lev(self, i: int, keys: np.ndarray) -> np.ndarray:
        """``lev[keys, i]``, or the false literal where corona i covers no such cell."""
        lk, lv = self.lev[i]
        if not len(lk):
            return np.full(keys.shape, self.false, dtype=np.int64)
        pos = np.minimum(np.searchsorted(lk, keys), len(lk) - 1)
        return np.where(lk[pos] == keys, lv[pos], self.false)

    def add_level(self) -> None:
        """Add corona ``k + 1`` (and make corona k inner)."""
        hs = self.hs
        i = self.k + 1
        while len(hs.levels) <= i:
            hs._grow()
        rows = hs.levels[i]
        m, n = len(rows), hs.forms.n
        hint = "ask for fewer coronas (--max-level)"
        limits.refuse_over(f"SAT variables for {i} coronas", (self.top + m * (n + 2)), limits.MAX_SAT_VARIABLES, hint=hint)
        _refuse_over_memory(f"clauses for {i} coronas", m * (4 * n + hs.forms.halos.shape[1]), 24, hint=hint)
        cells = hs.forms.placement_cells(rows)
        halos = hs.forms.placement_halos(rows)
        y = self._vars(m)
        self.rows.append(rows)
        self.cells.append(cells)
        self.halos.append(halos)
        self.y.append(y)
        cnf, F = self.pending, self.false
        keys, st, yy = _groups(cells.ravel(), np.repeat(y, n))
        size = np.diff(np.r_[st, len(yy)])
        if self.native:
            # lev[h, i] = the number of copies of corona i covering h: at most one of the
            # group and not-lev (one native constraint), and lev -> OR of the group
            lev = self._vars(len(keys))
            self.lev.append((keys, lev))
            if len(keys):
                cnf.add_atmost_groups(yy, st, -lev, 1)
                cnf.add_block(_padded(-lev, st, yy, F))
        else:
            # lev[h, i] <-> some copy of corona i covers h, at most one of them: a ladder
            # s_1..s_g over the group's copies l_1..l_g (l_t -> s_t, s_t -> s_t+1,
            # s_t -> not l_t+1) whose last prefix s_g is lev[h, i] (so every l_t -> lev),
            # and lev -> OR l
            s = self._vars(len(yy))
            last = st + size - 1
            lev = s[last]
            self.lev.append((keys, lev))
            if len(keys):
                nxt = np.ones(len(yy), dtype=bool)
                nxt[last] = False
                t = np.flatnonzero(nxt)
                cnf.add_block(np.concatenate([np.column_stack([-yy, s]), np.column_stack([-s[t], s[t + 1]]),
                                              np.column_stack([-s[t], -yy[t + 1]])]))
                cnf.add_block(_padded(-lev, st, yy, F))
        # at most one level covers a cell
        for j in range(1, i):
            other = self._lev(j, keys)
            both = other != F
            if both.any():
                cnf.add_block(np.column_stack([-lev[both], -other[both]]))
        # cell pairs sharing a vertex: (cell of corona i, its vertex neighbour)
        ck, dk = self._vertex_pairs(keys)
        if i == 1:  # the kernel's halo is covered by corona 1
            need = self._lev(1, hs.kernel_halo)
            if (need == F).any():
                self.empty = True
            cnf.add_block(need[:, None])
        else:
            # touching corona i - 1 ...
            cnf.add_block(np.column_stack([-y, self._lev(i - 1, halos)]))
            # ... and none below it: no cell of corona i shares a vertex with one of corona j
            for j in range(1, i - 1):
                lits = self._lev(j, dk)
                hit = lits != F
                if hit.any():
                    cnf.add_block(np.column_stack([-self._lev(i, ck[hit]), -lits[hit]]))
            # corona i - 1 is inner now: every cell sharing a vertex with one of its cells is
            # covered (by corona i - 2, i - 1 or i: a copy covering it touches corona i - 1)
            pk, qk = self.pairs[i - 1]
            lits = np.column_stack([-self._lev(i - 1, pk), self._lev(i - 2, qk) if i >= 3 else np.full(len(qk), F),
                                    self._lev(i - 1, qk), self._lev(i, qk)])
            cnf.add_block(lits)
        self.pairs.append((ck, dk))
        self.k = i

    def _flush(self) -> IncrementalSolver:
        with gc_paused():
            if self.solver is None:
                self.solver = IncrementalSolver(self.pending, solver=self.solver_name)
            else:
                self.solver.extend(self.pending)
        self.pending = CNF()
        return self.solver

    def solve(self, assumptions: list[int], time_limit: Budget | float | None):
        s = self._flush()
        ans = s.solve(assumptions=assumptions, time_limit=time_limit)
        self.hs.sat_calls += 1
        self.hs.solve_seconds += ans.seconds
        return ans

    def model(self, ans) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(rows, levels, cells, y) of the copies a model uses, the kernel first."""
        rows, lv, cells, ys = [self.rows[0]], [np.zeros(1, dtype=np.int64)], [self.cells[0]], [self.y[0]]
        for i in range(1, self.k + 1):
            used = ans.values(self.y[i])
            rows.append(self.rows[i][used])
            lv.append(np.full(int(used.sum()), i, dtype=np.int64))
            cells.append(self.cells[i][used])
            ys.append(self.y[i][used])
        return np.concatenate(rows), np.concatenate(lv), np.concatenate(cells), np.concatenate(ys)

    def hole_clauses(self, cells: np.ndarray, ys: np.ndarray) -> list[list[int]]:
        """:func:`hole_clauses` over the copies of every level (the kernel, y = 0, is always
        there and left out of the clauses); the candidates' index is made once per ``k``."""
        if self.index is None or self.index[0] != self.k:
            self.index = (self.k, cover_index(np.concatenate(self.cells[1:self.k + 1]),
                                              np.concatenate(self.y[1:self.k + 1])))
        return hole_clauses(self.hs.grid, cells, ys, self.index[1])

    def corona(self, hole_free_only: bool, time_limit: Budget | float | None) -> tuple[Corona | None, Corona | None, bool | None]:
        """(hole-free patch, patch with holes, decided) for the current ``k`` (see
        :meth:`HeeschSolver.corona`); with ``hole_free_only`` the holey patch is not kept apart
        (the hole clauses are asserted for this level from the first model on)."""
        if self.empty:
            return None, None, True
        sel = self._vars(1)[0]
        budget = Budget.of(time_limit)
        with_holes: Corona | None = None
        assume: list[int] = [int(sel)] if hole_free_only else []
        while True:
            ans = self.solve(assume, budget)
            if ans.satisfiable is None:
                return None, with_holes, None
            if not ans.satisfiable:
                return None, with_holes, True
            rows, lv, cells, ys = self.model(ans)
            found = self.hole_clauses(cells, ys)
            if not found:
                c = Corona(rows, lv, False)
                return c, with_holes or c, True
            for clause in found:
                self.pending.add([-int(sel), *clause])
            if with_holes is None:
                with_holes = Corona(rows, lv, True)
            assume = [int(sel)]


def hole_free_heesch(grid: Grid, cells: np.ndarray, *, max_level: int = 6, solver: str = HC_SOLVER,
                     time_limit: Budget | float | None = None) -> HeeschResult:
    """Kaplan's hole-free Heesch number Hc alone (heesch-sat's default mode, without ``-hh``):
    coronas k = 1, 2, ... until a level with no hole-free k-corona patch, in one incremental
    solver (:class:`CoronaLadder`). ``hh`` is None (not asked) and ``decided`` stays False:
    Hc alone is no proof that the polyform cannot tile (:func:`heesch` gives the proof)."""
    if not 0 <= max_level <= MAX_LEVEL_LIMIT:
        raise ParameterError(f"max_level must be between 0 and {MAX_LEVEL_LIMIT}, got {max_level}")
    t0 = time.monotonic()
    budget = Budget.of(time_limit)
    hs = HeeschSolver(grid, cells, solver=solver)
    best = Corona(hs.levels[0].copy(), np.zeros(1, dtype=np.int64), False)
    hs.drop_enclosing()
    if max_level >= 1 and not len(hs.levels[1]):  # no copy can be in corona 1: no SAT needed
        return HeeschResult(0, None, best, None, 0, False,
                            "no hole-free 1-corona patch: a halo cell no copy of corona 1 can cover "
                            "(Hc only: not a proof that it cannot tile)", 0, time.monotonic() - t0)
    ladder = CoronaLadder(hs)
    try:
        for k in range(1, max_level + 1):
            if budget is not None and budget.spent():
                return HeeschResult(None, None, best, None, k - 1, False,
                                    f"time limit ({budget}) spent after {k - 1} coronas", hs.sat_calls,
                                    time.monotonic() - t0)
            try:
                ladder.add_level()
            except limits.LimitError as exc:
                return HeeschResult(None, None, best, None, k - 1, False, f"{k} coronas: {exc}", hs.sat_calls,
                                    time.monotonic() - t0)
            free, _, done = ladder.corona(True, budget)
            if done is None:
                return HeeschResult(None, None, best, None, k - 1, False,
                                    f"time limit ({budget}) spent while looking for {k} coronas", hs.sat_calls,
                                    time.monotonic() - t0)
            if free is None:
                return HeeschResult(k - 1, None, best, None, k - 1, False,
                                    f"no hole-free {k}-corona patch (Hc only: not a proof that it cannot tile)",
                                    hs.sat_calls, time.monotonic() - t0)
            best = free
    finally:
        ladder.close()
    return HeeschResult(None, None, best, None, max_level, False, f"surrounded by {max_level} hole-free coronas",
                        hs.sat_calls, time.monotonic() - t0)
