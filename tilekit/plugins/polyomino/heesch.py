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
from tilekit.errors import ParameterError
from tilekit.lattice import Grid, holes_of, pack, unique_keys, unpack
from tilekit.plugins.polyomino.placements import Forms
from tilekit.sat import DEFAULT_SAT_SOLVER, IncrementalSolver, gc_paused

#: The most coronas a search will build (Kaplan's sat tool stops at 7 by default).
MAX_LEVEL_LIMIT = 12


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


class HeeschSolver:
    """Coronas of one polyform, level by level (see the module docstring)."""

    def __init__(self, grid: Grid, cells: np.ndarray, *, solver: str = DEFAULT_SAT_SOLVER) -> None:
        self.grid = grid
        self.forms = Forms(grid, cells)
        self.solver = solver
        self.kernel_keys = np.sort(self.forms.keys[0])
        self.kernel_halo = unique_keys(self.forms.placement_halos(np.array([[0, 0, 0]]))[0])
        self.levels: list[np.ndarray] = [np.array([[0, 0, 0]], dtype=np.int64)]  # level 0: kernel
        self.sat_calls = 0
        self.solve_seconds = 0.0  # inside the solver (the rest is building the formulas)
        #: (Hc, Hh, hole-free witness, holey witness) once Kaplan's loop has stopped
        self.kaplan: tuple[int, int, Corona, Corona] | None = None

    # -- placements per level -------------------------------------------------------------
    def _row_keys(self, rows: np.ndarray) -> np.ndarray:
        """One int64 per placement row (orientation, translation)."""
        return pack(rows[:, 1:3]) * 64 + rows[:, 0]

    def _grow(self) -> None:
        """Add the placements of the next level: copies touching a copy of the last level."""
        last = self.levels[-1]
        adj = self.forms.adjacent
        # estimate first: every copy of the last level times the copies touching it, as
        # (orientation, tx, ty) rows plus their keys, before any is allocated
        candidates = sum(int((last[:, 0] == j).sum()) * len(adj[j]) for j in range(self.forms.J))
        limits.refuse_over_memory(f"candidate placements for corona {len(self.levels)}", candidates, 72,
                                  hint="ask for fewer coronas (--max-level)")
        parts = []
        for j in range(self.forms.J):
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
        """The clauses forbidding each hole of the model's patch (``used``: which y are true):
        not all of the copies around the hole (at their levels), or some copy covering one of
        its cells. Empty when the patch has no hole."""
        cells = table["cells"][used]
        keys = np.concatenate([self.kernel_keys, cells.ravel()])
        out = []
        for hole in holes_of(self.grid, keys):
            hx = unpack(hole)
            ring = pack(hx[:, None, :] + self.grid.neighbours[self.grid.cell_type(hx)]).ravel()
            around = table["yvar"][used][np.isin(cells, ring).any(axis=1)]  # the kernel is always there
            inside = table["yvar"][np.isin(table["cells"], hole).any(axis=1)]
            out.append([*(-around).tolist(), *inside.tolist()])
        return out

    def surrounds(self, k: int, *, time_limit: float | None = None) -> bool | None:
        """Whether k coronas exist with holes allowed (no hole checks: the coronas of any
        tiling satisfy this formula); None when the time limit expires."""
        with gc_paused():
            clauses, _ = self._encode(k)
        with IncrementalSolver(clauses, solver=self.solver) as s:
            ans = s.solve(time_limit=time_limit)
        self.sat_calls += 1
        self.solve_seconds += ans.seconds
        return ans.satisfiable

    def corona(self, k: int, *, time_limit: float | None = None) -> tuple[Corona | None, Corona | None, bool | None]:
        """(hole-free k-corona patch or None, k-corona patch with holes allowed in its outer
        corona or None, decided) for exactly ``k`` coronas."""
        if k == 0:
            kern = Corona(self.levels[0].copy(), np.zeros(1, dtype=np.int64), False)
            return kern, kern, True
        with gc_paused():
            clauses, table = self._encode(k)
        hf = table["top"] + 1  # selector: the outermost corona is hole-free too
        deadline = None if time_limit is None else time.monotonic() + time_limit
        with IncrementalSolver(clauses, solver=self.solver) as s:
            with_holes: Corona | None = None
            assume: list[int] = []
            while True:
                left = None if deadline is None else max(0.01, deadline - time.monotonic())
                ans = s.solve(assumptions=assume, time_limit=left)
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
           time_limit: float | None = None, start: int = 1, hs: HeeschSolver | None = None,
           best: Corona | None = None) -> HeeschResult:
    """Hc and Hh of a hole-free polyform, trying 1..max_level coronas; ``decided`` only with a
    proof that it does not tile.

    Kaplan's numbers stop at the first level k with no hole-free patch (Hc = k - 1, and Hh = k
    when k coronas exist only with holes). That alone does not prove the tile cannot tile: the
    coronas of a tiling can enclose holes that the next corona fills. The proof is a level at
    which no patch exists even with holes (the formula without hole clauses, which the coronas
    of any tiling satisfy), so after a holey level the search goes on, without hole checks,
    until such a level or ``max_level``. Undecided (``decided=False``) when ``max_level``
    coronas exist or the time limit expires first; ``hc``/``hh`` then hold Kaplan's values if
    they were found (the polyform may still tile).
    """
    if not 0 <= max_level <= MAX_LEVEL_LIMIT:
        raise ParameterError(f"max_level must be between 0 and {MAX_LEVEL_LIMIT}, got {max_level}")
    t0 = time.monotonic()
    hs = hs or HeeschSolver(grid, cells, solver=solver)
    best = best or Corona(hs.levels[0].copy(), np.zeros(1, dtype=np.int64), False)  # the kernel

    def result(decided: bool, reason: str, surrounded: int) -> HeeschResult:
        hc, hh, hcw, hhw = hs.kaplan if hs.kaplan else (None, None, best, None)
        return HeeschResult(hc, hh, hcw, hhw, surrounded, decided, reason, hs.sat_calls, time.monotonic() - t0)

    for k in range(start, max_level + 1):
        left = None if time_limit is None else time_limit - (time.monotonic() - t0)
        if left is not None and left <= 0:
            return result(False, f"time limit after {k - 1} coronas", k - 1)
        answer = ok = None
        try:  # the proof question (holes allowed) once Kaplan's numbers are known, else coronas
            if hs.kaplan:
                ok = hs.surrounds(k, time_limit=left)
            else:
                answer = hs.corona(k, time_limit=left)
        except limits.LimitError as exc:  # a bound like the time limit: undecided, with the reason
            return result(False, f"{k} coronas: {exc}", k - 1)
        if answer is None:
            if ok is None:
                return result(False, f"time limit while looking for {k} coronas with holes", k - 1)
            if not ok:
                hc, hh = hs.kaplan[:2]
                return result(True, f"{hh} corona{'s' if hh != 1 else ''} only with a hole in the outermost corona; "
                                    f"no {k}-corona patch even with holes", k - 1)
            continue
        free, holey, decided = answer
        if decided is None:
            return result(False, f"time limit while looking for {k} coronas", k - 1)
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

