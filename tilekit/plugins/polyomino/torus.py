"""Periodic tilings by one polyform, found as exact covers of tori by SAT.

A tiling whose translations include a lattice ``L`` (of the grid's translations) is the same
thing as an exact cover of the torus ``cells / L`` by copies of the polyform. So a polyform has
a periodic tiling with ``m`` tiles per translational unit of some period lattice iff some
sublattice of index ``N`` (``N`` times the grid's cell types = ``m * n`` cells) admits one.
Every sublattice of index N has exactly one basis ``(a, b), (0, d)`` with ``a * d = N`` and
``0 <= b < d`` (Hermite normal form), so the search is complete for each m.

Each found tiling's symmetry group is computed exactly, on the torus: the maps ``x -> g x + t``
(g in the grid's point group) taking every tile onto a tile and the period lattice of the
tiling onto itself; the orbits of the tiles under that group are the tiling's transitivity
classes (its k as a k-isohedral tiling). The least k over the tilings found is what the
polyomino classification records for an anisohedral tile.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tilekit.budget import Budget
from tilekit.jit import njit
from tilekit.lattice import Grid
from tilekit.plugins.polyomino.isohedral import _hnf_add
from tilekit.plugins.polyomino.placements import Forms
from tilekit.sat import DEFAULT_SAT_SOLVER, IncrementalSolver, gc_paused, solve
from tilekit.symmetry.orbits import union_find

#: CPU seconds per clause of a torus formula, encoding and solving together, for the estimate
#: of :func:`torus_cost`: the 13-omino ``...x/.xxx/xxx./.xxx/.xxx`` took 582 CPU seconds for
#: its tori of 13..20 tiles per unit (docs/benchmarks.md, the n = 13 run), 5.1e7 clauses by
#: the estimate. Unsatisfiable tori dominate; a satisfiable one can be much quicker.
TORUS_CPU_PER_CLAUSE = 1.1e-5


def sublattice_count(N: int) -> int:
    """How many sublattices of Z^2 have index N: the sum of N's divisors, sigma(N) (one HNF
    basis (a, b), (0, d) per divisor a and residue b < d = N / a, :func:`sublattices`)."""
    total, a = 0, 1
    while a * a <= N:
        if N % a == 0:
            total += a + (N // a if a * a != N else 0)
        a += 1
    return total


@dataclass(frozen=True)
class TorusCost:
    """What the tori of one form up to ``tiles`` tiles per unit cost, estimated before any is
    built (:func:`torus_cost`)."""

    tiles: int
    sublattices: int  # every period lattice of the indices tried (exact)
    tori: int  # those left up to the grid's point group (an estimate: sublattices / (|G| / 2))
    clauses: int  # over all tori (at most: every orientation's every translate is a placement)
    largest_clauses: int  # of the largest torus formula
    largest_variables: int

    @property
    def cpu_seconds(self) -> float:
        """The CPU time it would take at :data:`TORUS_CPU_PER_CLAUSE`."""
        return self.clauses * TORUS_CPU_PER_CLAUSE


def formula_size(grid: Grid, cells: int, N: int, orientations: int | None = None) -> tuple[int, int]:
    """(variables, clauses) of the exact-cover formula of a torus of index N (N translational
    units) for a form of ``cells`` cells with ``orientations`` copies (default: as many as the
    grid's point group has elements): P = orientations * N placements of ``cells`` cells each on
    R * N torus cells (R cell types); one clause per cell that some copy covers, three for each
    further copy on it (the ladder) and the anchor — equal to :meth:`TorusSearch._formula`'s when
    no placement is dropped (an asymmetric form on a torus it does not wrap onto itself)."""
    J = len(grid.group) if orientations is None else orientations
    R = len(grid.roots)
    P = J * N
    return P + P * cells - R * N, 3 * P * cells - 3 * R * N + 1


def torus_cost(grid: Grid, cells: int, tiles: int, least: int = 2) -> TorusCost:
    """The estimated cost of searching the tori with ``least``..``tiles`` tiles per unit for a
    form of ``cells`` cells on ``grid``: the sublattices (exact), the tori up to the point group
    (``-1`` maps every lattice onto itself, so an orbit has at most |G| / 2 lattices) and the
    clauses (:func:`formula_size`, the most orientations). Arithmetic only: no lattice is built."""
    R = len(grid.roots)
    h = max(1, len(grid.group) // 2)
    subs = tori = clauses = big_c = big_v = 0
    for m in range(max(2, least), tiles + 1):
        if (m * cells) % R:
            continue
        N = m * cells // R
        s = sublattice_count(N)
        t = -(-s // h)
        v, c = formula_size(grid, cells, N)
        subs, tori, clauses = subs + s, tori + t, clauses + t * c
        big_c, big_v = max(big_c, c), max(big_v, v)
    return TorusCost(tiles, subs, tori, clauses, big_c, big_v)


def sublattices(N: int):
    """HNF triples ``(a, b, d)`` of every sublattice of Z^2 of index N (basis (a, b), (0, d))."""
    for a in range(1, N + 1):
        if N % a == 0:
            d = N // a
            for b in range(d):
                yield a, b, d


def _reduce(uv: np.ndarray, a: int, b: int, d: int) -> np.ndarray:
    """Residue index in [0, a*d) of unit vectors ``(..., 2)`` modulo the lattice (a, b), (0, d)."""
    u, v = uv[..., 0], uv[..., 1]
    i = np.floor_divide(u, a)
    return (u - i * a) * d + np.mod(v - i * b, d)


def _in_lattice(w: np.ndarray, basis: tuple[int, int, int]) -> bool:
    a, b, d = basis
    x, y = int(w[0]), int(w[1])
    if a == 0:
        return x == 0 and (y % d == 0 if d else y == 0)
    if x % a:
        return False
    y -= (x // a) * b
    return y % d == 0 if d else y == 0


@njit(cache=True)
def _tile_maps(plane, gidx, taus, group, types, roots, period, a, b, d, label, rep):  # pragma: no cover - compiled
    """For each candidate map ``x -> group[gidx[k]] x + taus[k]``: whether it takes every tile
    of ``plane`` (m, n, 2) onto a tile of the torus tiling, and the tile it takes each onto.
    ``label``/``rep`` give, per torus cell (type * a * d + residue), its tile and the unit
    offset of that tile's cell there (a map is a symmetry when each tile's cells land on one
    tile with one common offset)."""
    K, m, n = gidx.shape[0], plane.shape[0], plane.shape[1]
    perms = np.zeros((K, m), np.int64)
    ok = np.zeros(K, np.bool_)
    for k in range(K):
        g = group[gidx[k]]
        good = True
        for i in range(m):
            lab0 = -1
            ou = 0
            ov = 0
            for c in range(n):
                x = g[0, 0] * plane[i, c, 0] + g[0, 1] * plane[i, c, 1] + taus[k, 0]
                y = g[1, 0] * plane[i, c, 0] + g[1, 1] * plane[i, c, 1] + taus[k, 1]
                t = types[(y % period) * period + x % period]
                if t < 0:
                    good = False
                    break
                u = (x - roots[t, 0]) // period
                v = (y - roots[t, 1]) // period
                q = u // a
                cell = t * (a * d) + (u - q * a) * d + (v - q * b) % d
                lab = label[cell]
                du = u - rep[cell, 0]
                dv = v - rep[cell, 1]
                if c == 0:
                    lab0, ou, ov = lab, du, dv
                elif lab != lab0 or du != ou or dv != ov:
                    good = False
                    break
            if not good:
                break
            perms[k, i] = lab0
        ok[k] = good
    return perms, ok


@dataclass
class TorusTiling:
    """A periodic tiling: placements ``rows`` (j, tx, ty) of one translational unit of the
    lattice ``(a, b), (0, d)`` (in units of the grid's translations), the transitivity class of
    each tile, and the tiling's own translation lattice (HNF triple, possibly finer)."""

    lattice: tuple[int, int, int]
    rows: np.ndarray
    classes: np.ndarray
    translations: tuple[int, int, int]
    symmetries: int  # order of the symmetry group modulo the period lattice

    @property
    def m(self) -> int:
        return len(self.rows)

    @property
    def k(self) -> int:
        return int(self.classes.max()) + 1

    def vectors(self, grid: Grid) -> tuple[np.ndarray, np.ndarray]:
        """The two period vectors in Cartesian coordinates."""
        a, b, d = self.lattice
        p = grid.period
        return grid.xy(np.array([a * p, b * p])), grid.xy(np.array([0, d * p]))

    def to_json(self) -> dict:
        return {"kind": "torus", "lattice": list(self.lattice), "k": self.k,
                "tiles": [[int(j), int(x), int(y), int(c)] for (j, x, y), c in zip(self.rows.tolist(), self.classes.tolist())]}


class TorusSearch:
    """Exact covers of tori by the copies of one polyform."""

    def __init__(self, forms: Forms, *, solver: str = DEFAULT_SAT_SOLVER) -> None:
        self.forms = forms
        self.solver = solver
        g = forms.grid
        self.types = g.cell_type(forms.forms).reshape(forms.forms.shape[:2])  # (J, n)
        self.units = (forms.forms - g.roots[self.types]) // g.period  # (J, n, 2)
        self.R = len(g.roots)
        self.sat_calls = 0

    def _formula(self, lattice: tuple[int, int, int]):
        """(clauses, placement variables, placement rows (j, u0, v0)) of the exact cover of
        the torus, or False when some cell no copy can cover."""
        a, b, d = lattice
        N = a * d
        J, n = self.types.shape
        uu, vv = np.meshgrid(np.arange(a), np.arange(d), indexing="ij")
        t = np.column_stack([uu.ravel(), vv.ravel()])  # (N, 2) translations
        ids = self.types[:, None, :] * N + _reduce(self.units[:, None, :, :] + t[None, :, None, :], a, b, d)
        ids = ids.reshape(J * N, n)
        meta = np.column_stack([np.repeat(np.arange(J), N), np.tile(t, (J, 1))])
        srt = np.sort(ids, axis=1)
        ok = (srt[:, 1:] != srt[:, :-1]).all(axis=1) if n > 1 else np.ones(len(srt), bool)
        srt, meta, ids = srt[ok], meta[ok], ids[ok]
        _, first = np.unique(srt, axis=0, return_index=True)
        first = np.sort(first)
        srt, meta, ids = srt[first], meta[first], ids[first]
        P = len(srt)
        if P == 0:
            return False
        cells = self.R * N
        var = np.arange(1, P + 1)
        flat_c = srt.ravel()
        flat_v = np.repeat(var, n)
        order = np.argsort(flat_c, kind="stable")
        sc, sv = flat_c[order], flat_v[order]
        starts = np.flatnonzero(np.r_[True, sc[1:] != sc[:-1]])
        if len(starts) < cells:
            return False  # some cell no copy can cover
        clauses = [g.tolist() for g in np.split(sv, starts[1:])]
        gid = np.repeat(np.arange(len(starts)), np.diff(np.r_[starts, len(sc)]))
        idx = np.flatnonzero(np.r_[gid[1:] == gid[:-1], False])
        s = P + 1 + np.arange(len(idx))
        clauses += np.column_stack([-sv[idx], s]).tolist()
        clauses += np.column_stack([-s, -sv[idx + 1]]).tolist()
        chain = np.flatnonzero(np.r_[idx[1:] == idx[:-1] + 1, False])
        clauses += np.column_stack([-s[chain], s[chain + 1]]).tolist()
        # symmetry breaking: translate so that some tile's first cell is at unit (0, 0)
        anchor = (_reduce(meta[:, 1:3] + self.units[meta[:, 0], 0], a, b, d) == 0)
        clauses.append(var[anchor].tolist())
        return clauses, var, meta

    def cover(self, lattice: tuple[int, int, int], time_limit: Budget | float | None = None) -> np.ndarray | None | bool:
        """Placements (j, u0, v0) of one exact cover of the torus, False if none exists,
        None if the time limit (a :class:`Budget`, or CPU seconds) is spent."""
        with gc_paused():
            formula = self._formula(lattice)
        if formula is False:
            return False
        clauses, var, meta = self._last = formula
        ans = solve(clauses, solver=self.solver, time_limit=time_limit)
        self.sat_calls += 1
        if ans.satisfiable is None:
            return None
        if not ans.satisfiable:
            return False
        used = ans.values(var)
        return meta[used]

    def others(self, first: np.ndarray, limit: int, time_limit: Budget | float | None = None):
        """More covers of the torus of the last :meth:`cover` call (each differing from all
        before it), at most ``limit``, until ``time_limit`` (a budget, or CPU seconds) is spent;
        yields placement arrays like :meth:`cover`."""
        clauses, var, meta = self._last
        index = {tuple(r): int(v) for r, v in zip(meta.tolist(), var.tolist())}
        budget = Budget.of(time_limit)
        with IncrementalSolver(clauses, solver=self.solver) as s:
            chosen = first
            for _ in range(limit):
                s.add([-index[tuple(r)] for r in chosen.tolist()])
                if budget is not None and budget.spent():
                    return
                ans = s.solve(time_limit=budget)
                self.sat_calls += 1
                if not ans.satisfiable:
                    return
                used = ans.values(var)
                chosen = meta[used]
                yield chosen

    def classes(self, lattice: tuple[int, int, int], chosen: np.ndarray) -> TorusTiling:
        """The tiling's placements in the plane, its translation lattice and tile classes.

        The symmetries are the grid's maps ``x -> g x + tau`` taking every tile onto a tile:
        first the translations by the torus's residues (they give the tiling's own translation
        lattice), then each point-group element that keeps that lattice, with every
        translation taking tile 0's first cell onto a cell; each candidate is tested on all
        cells at once in one compiled call (:func:`_tile_maps`). The classes are the orbits of
        the tiles under the maps found."""
        grid = self.forms.grid
        a, b, d = lattice
        N = a * d
        p = grid.period
        rows = np.column_stack([chosen[:, 0], chosen[:, 1:3] * p])
        plane = np.ascontiguousarray(self.forms.forms[rows[:, 0]] + rows[:, None, 1:3])  # (m, n, 2) fine
        m, n = plane.shape[:2]
        flat = plane.reshape(-1, 2)
        ty = grid.cell_type(flat)
        uv = (flat - grid.roots[ty]) // p
        tid = ty * N + _reduce(uv, a, b, d)
        label = np.full(self.R * N, -1, dtype=np.int64)
        rep = np.zeros((self.R * N, 2), dtype=np.int64)
        label[tid] = np.repeat(np.arange(m), n)
        rep[tid] = uv
        group = grid.group.astype(np.int64)
        roots = grid.roots.astype(np.int64)
        tables = (group, grid.type_table, roots, np.int64(p), np.int64(a), np.int64(b), np.int64(d), label, rep)
        uu, vv = np.meshgrid(np.arange(a), np.arange(d), indexing="ij")
        trans = np.column_stack([uu.ravel(), vv.ravel()])
        # pure translations by the residues of the torus (those mapping tiles onto tiles)
        perms, ok = _tile_maps(plane, np.zeros(len(trans) - 1, dtype=np.int64), trans[1:] * p, *tables)
        lat = _hnf_add(_hnf_add((0, 0, 0), (a, b)), (0, d))
        for w in trans[1:][ok].tolist():
            lat = _hnf_add(lat, (w[0], w[1]))
        maps = [perms[ok]]
        # point-group elements with a translation: tile 0's first cell goes to some cell; only
        # symmetries of the grid (tau a grid translation, so each cell goes to a cell of the same
        # shape: on the octasquare grid, tau = (2, 2) maps octagons onto squares), and only those
        # sending the translation lattice onto itself
        la, lb, ld = lat
        keep = [gi for gi in range(1, len(group))
                if _in_lattice(group[gi] @ np.array([la, lb]), lat) and _in_lattice(group[gi] @ np.array([0, ld]), lat)]
        count = 1 + int(ok.sum())
        if keep:
            c0 = plane[0, 0]
            cand_cells = (roots[:, None, :] + p * trans[None, :, :]).reshape(-1, 2)
            g = np.asarray(keep, dtype=np.int64)
            taus = cand_cells[None, :, :] - (group[g] @ c0)[:, None, :]  # (G', C, 2)
            gidx = np.broadcast_to(g[:, None], taus.shape[:2])
            sel = grid.is_translation(taus)
            perms, ok = _tile_maps(plane, np.ascontiguousarray(gidx[sel]), np.ascontiguousarray(taus[sel]), *tables)
            maps.append(perms[ok])
            count += int(ok.sum())
        perms = np.concatenate(maps)  # tile i goes to tile perms[k, i]: the orbits are the classes
        classes = union_find(m, np.column_stack([np.tile(np.arange(m), len(perms)), perms.ravel()]))
        return TorusTiling(lattice, rows, classes, lat, count)

    def lattices(self, N: int) -> list[tuple[int, int, int]]:
        """The sublattices of index N up to the grid's point group: the polyform's copies come
        in every orientation, so the torus of g L has a cover iff the torus of L has one.
        One lattice per orbit (the least HNF triple), in increasing order."""
        group = self.forms.grid.group
        seen: set[tuple[int, int, int]] = set()
        out = []
        for lat in sublattices(N):
            if lat in seen:
                continue
            a, b, d = lat
            orbit = set()
            for g in group:
                h = (0, 0, 0)
                for v in (g @ np.array([a, b]), g @ np.array([0, d])):
                    h = _hnf_add(h, (int(v[0]), int(v[1])))
                orbit.add(h)
            seen |= orbit
            out.append(lat)
        return out

    def search(self, m_range, *, want_k: int = 2, time_limit: Budget | float | None = None, alternatives: int = 64):
        """Tilings with m tiles per unit for m in ``m_range``: yields (m, TorusTiling) for each
        lattice that has a cover (the least k among up to ``alternatives`` further covers of
        that torus); stops after a tiling with ``k <= want_k``. Yields (m, None) when the
        time limit (a :class:`Budget`, or CPU seconds) is spent."""
        budget = Budget.of(time_limit)
        n = self.forms.n
        for m in m_range:
            if (m * n) % self.R:
                continue
            N = m * n // self.R
            for lat in self.lattices(N):
                if budget is not None and budget.spent():
                    yield m, None
                    return
                got = self.cover(lat, budget)
                if got is None:
                    yield m, None
                    return
                if got is False:
                    continue
                tt = self.classes(lat, got)
                if tt.k > want_k and alternatives:
                    # another cover of the same torus may have fewer transitivity classes
                    for other in self.others(got, alternatives, budget):
                        t2 = self.classes(lat, other)
                        if t2.k < tt.k:
                            tt = t2
                        if tt.k <= want_k:
                            break
                yield m, tt
                if tt.k <= want_k:
                    return
