"""The direct isohedral test on any grid: a first corona closed under its own transforms, by SAT.

A tiling by copies of a tile K is isohedral when a group Γ of grid symmetries permutes the
tiles transitively; then the tiles are the images γK (γ in Γ), and the tiles touching K are γK
for γ in ``E = {γ in Γ : γK touches K}``. That set obeys three local rules:

1. ``E`` is closed under inverses (γK touches K exactly when K touches γ⁻¹K);
2. if αK and βK (α, β in E) touch each other, then α⁻¹β is in E (it is in Γ, and α⁻¹βK
   touches α⁻¹αK = K);
3. if αK = βK with α ≠ β, then s = α⁻¹β fixes K and is in Γ's stabiliser H of K, and then
   αs and sα are in E too (and H is a group).

Kaplan's heesch-sat decides isohedral tilers with the first of these rules and a form of the
second added to its 1-corona formula (``HeeschSolver::checkIsohedralTiling``); this module
states them over group *elements* rather than placements, so that a tile with symmetries is
handled exactly (a placement of a symmetric tile is reached by several elements, only some of
which need be in Γ). The variables are the 1-corona formula's (:class:`heesch.CoronaLadder`,
holes allowed: the corona of a tiling need not be hole-free), one per element for a symmetric
tile, and one per non-trivial symmetry of K for H; the clauses of the rules are guarded by a
selector, so the same incremental solver goes on to the coronas afterwards.

**Complete.** The E and H of every isohedral tiling satisfy the formula (its copies touching K
survive the local test of :func:`heesch.first_corona_support`), so *unsatisfiable* proves the
tile has no isohedral tiling on the grid. **Sound by construction.** A model gives E and H;
the group they generate is built here (a transversal of its point group and its translation
lattice by Schreier's generators), its tiles are placed on the torus of that lattice and
checked to cover it exactly once, and the symmetry classes of that tiling are computed
(:meth:`torus.TorusSearch.classes`): one class, or the model is blocked and the solver asked
again (at most :data:`MAX_MODELS` times). The tests check every tiling found again with
``Patch.validate`` and :mod:`tilekit.symmetry`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from tilekit.budget import Budget
from tilekit.jit import njit
from tilekit.lattice import _M, _OFF
from tilekit.plugins.polyomino.heesch import HeeschSolver
from tilekit.plugins.polyomino.isohedral import _group_closure, _inv_array, _mul_array
from tilekit.plugins.polyomino.placements import Forms
from tilekit.plugins.polyomino.torus import TorusSearch, TorusTiling, _reduce

#: Most models of the closed-corona formula tried before the test gives up (each one that does
#: not build a one-class tiling is blocked). None has been met: on every hole-free form with a
#: corona of drafter and abolo to 7, half-Cairo, kite, bevelhex and octasquare to 6 and trihex
#: to 7 cells (513 isohedral, 316 not), the first model built a one-class tiling.
MAX_MODELS = 16


@dataclass
class SurroundResult:
    """``isohedral`` True with the tiling found, False when proved impossible, None when the
    time limit or :data:`MAX_MODELS` ended the test first."""

    isohedral: bool | None
    tiling: TorusTiling | None
    models: int
    seconds: float


def element_maps(forms: Forms) -> tuple[np.ndarray, np.ndarray]:
    """Per point-group element g: the orientation ``o[g]`` (row of ``forms``) of g's image of the
    polyform and ``c[g]`` such that the grid symmetry ``x -> G x + t`` takes the kernel
    (orientation 0) onto orientation ``o[g]`` moved by ``t + c[g]``. Fixed forms and shifts are
    :func:`placements._orientations`'s; the kernel is ``cells + s[0]`` (element 0 is the
    identity), so ``c[g] = G_g s[0] - s[g]``."""
    group = forms.grid.group.astype(np.int64)
    s = forms.gshift
    return forms.owner, group @ s[0] - s


@njit(cache=True)
def _row_key(j, tx, ty):  # pragma: no cover - compiled
    return ((tx + np.int64(_OFF)) * np.int64(_M) + (ty + np.int64(_OFF))) * 64 + j


@njit(cache=True)
def _find(sorted_keys, order, key):  # pragma: no cover - compiled
    p = np.searchsorted(sorted_keys, key)
    if p < sorted_keys.shape[0] and sorted_keys[p] == key:
        return order[p]
    return -1


@njit(cache=True)
def _closure(rows, touching, o, c, gl, pos, group, mul, inv):  # pragma: no cover - compiled
    """The rules of the module docstring over the elements of corona 1.

    Element ``e = r * S + k`` (S = |Sym K|) is ``x -> G_g x + t`` with ``g = gl[rows[r, 0], k]``
    and ``t = T_r - c[g]``: it takes the kernel onto placement row r = (j, T). Symmetry k of
    the kernel is ``(gl[0, k], -c[gl[0, k]])`` (k = 0 the identity). Returns
    ``inverse`` (M,): the element α⁻¹ (-1: not a candidate copy, so α is not used);
    ``pairs`` (P, 3): (α, β, γ) with αK, βK touching and γ = α⁻¹β (-1: γK touches K but was
    ruled out by the local test, so α and β are not used together);
    ``same`` (Q, 3): (α, β, k), α ≠ β with one placement, α⁻¹β = symmetry k;
    ``stab`` (Z, 4): (k, α, αs, sα) for symmetry k = s (sα -1: not a candidate)."""
    m, S = rows.shape[0], gl.shape[1]
    M = m * S
    rk = np.empty(m, np.int64)
    for r in range(m):
        rk[r] = _row_key(rows[r, 0], rows[r, 1], rows[r, 2])
    rorder = np.argsort(rk)
    rsorted = rk[rorder]
    A = touching.shape[0]
    ak = np.empty(A, np.int64)
    for r in range(A):
        ak[r] = _row_key(touching[r, 0], touching[r, 1], touching[r, 2])
    aorder = np.argsort(ak)
    asorted = ak[aorder]
    eg = np.empty(M, np.int64)
    et = np.empty((M, 2), np.int64)
    for r in range(m):
        for k in range(S):
            g = gl[rows[r, 0], k]
            eg[r * S + k] = g
            et[r * S + k, 0] = rows[r, 1] - c[g, 0]
            et[r * S + k, 1] = rows[r, 2] - c[g, 1]
    inverse = np.full(M, -1, np.int64)
    pairs = np.empty((16, 3), np.int64)
    npairs = 0
    same = np.empty((16, 3), np.int64)
    nsame = 0
    for a in range(M):
        gi = inv[eg[a]]
        # α⁻¹ = (G⁻¹, -G⁻¹ t)
        ix = -(group[gi, 0, 0] * et[a, 0] + group[gi, 0, 1] * et[a, 1])
        iy = -(group[gi, 1, 0] * et[a, 0] + group[gi, 1, 1] * et[a, 1])
        r = _find(rsorted, rorder, _row_key(o[gi], ix + c[gi, 0], iy + c[gi, 1]))
        if r >= 0:
            inverse[a] = r * S + pos[gi]
        for b in range(M):
            if b == a:
                continue
            # α⁻¹β = (G_a⁻¹ G_b, G_a⁻¹ (t_b - t_a))
            g = mul[gi, eg[b]]
            dx = et[b, 0] - et[a, 0]
            dy = et[b, 1] - et[a, 1]
            tx = group[gi, 0, 0] * dx + group[gi, 0, 1] * dy
            ty = group[gi, 1, 0] * dx + group[gi, 1, 1] * dy
            px, py = tx + c[g, 0], ty + c[g, 1]
            if a // S == b // S:  # one placement: α⁻¹β fixes the kernel
                if nsame == same.shape[0]:
                    same = np.concatenate((same, np.empty_like(same)))
                same[nsame, 0] = a
                same[nsame, 1] = b
                same[nsame, 2] = pos[g]
                nsame += 1
                continue
            key = _row_key(o[g], px, py)
            r = _find(rsorted, rorder, key)
            hit = -1
            if r >= 0:
                hit = r * S + pos[g]
            elif _find(asorted, aorder, key) < 0:
                continue  # αK and βK overlap or do not touch
            if npairs == pairs.shape[0]:
                pairs = np.concatenate((pairs, np.empty_like(pairs)))
            pairs[npairs, 0] = a
            pairs[npairs, 1] = b
            pairs[npairs, 2] = hit
            npairs += 1
    stab = np.empty((M * (S - 1), 4), np.int64)
    z = 0
    for k in range(1, S):
        gs = gl[0, k]
        tsx, tsy = -c[gs, 0], -c[gs, 1]
        for a in range(M):
            ga = eg[a]
            # αs = (G_a G_s, G_a t_s + t_a): the same placement as α
            g1 = mul[ga, gs]
            # sα = (G_s G_a, G_s t_a + t_s)
            g2 = mul[gs, ga]
            x2 = group[gs, 0, 0] * et[a, 0] + group[gs, 0, 1] * et[a, 1] + tsx
            y2 = group[gs, 1, 0] * et[a, 0] + group[gs, 1, 1] * et[a, 1] + tsy
            r2 = _find(rsorted, rorder, _row_key(o[g2], x2 + c[g2, 0], y2 + c[g2, 1]))
            stab[z, 0] = k
            stab[z, 1] = a
            stab[z, 2] = (a // S) * S + pos[g1]
            stab[z, 3] = r2 * S + pos[g2] if r2 >= 0 else -1
            z += 1
    return inverse, pairs[:npairs].copy(), same[:nsame].copy(), stab


@njit(cache=True)
def _elements(rows, c, gl):  # pragma: no cover - compiled
    """(g, tx, ty) of every element (numbered as in :func:`_closure`)."""
    m, S = rows.shape[0], gl.shape[1]
    out = np.empty((m * S, 3), np.int64)
    for r in range(m):
        for k in range(S):
            g = gl[rows[r, 0], k]
            out[r * S + k, 0] = g
            out[r * S + k, 1] = rows[r, 1] - c[g, 0]
            out[r * S + k, 2] = rows[r, 2] - c[g, 1]
    return out


class SurroundTest:
    """The closed-corona formula of one polyform, added to its :class:`HeeschSolver`'s ladder."""

    def __init__(self, hs: HeeschSolver) -> None:
        self.hs = hs
        forms, grid = hs.forms, hs.grid
        self.group = grid.group.astype(np.int64)
        self.mul, self.inv = _mul_array(grid), _inv_array(grid)  # shared, read only
        self.o, self.c = element_maps(forms)
        # the elements taking the kernel onto each orientation, in group order (S of each)
        G = len(self.group)
        order = np.argsort(self.o, kind="stable")
        self.S = G // forms.J
        self.gl = np.ascontiguousarray(order.reshape(forms.J, self.S))
        self.pos = np.empty(G, dtype=np.int64)
        self.pos[self.gl.ravel()] = np.tile(np.arange(self.S), forms.J)

    def run(self, time_limit: Budget | float | None = None) -> SurroundResult:
        """Decide whether the polyform tiles isohedrally (see the module docstring); undecided
        when ``time_limit`` (a :class:`Budget`, or CPU seconds) is spent."""
        t0 = time.monotonic()
        budget = Budget.of(time_limit)
        hs = self.hs
        lad = hs.ladder_at(1)
        if lad is None or lad.k != 1:
            raise RuntimeError("the direct isohedral test runs on corona 1's formula, before the coronas grow")
        if lad.empty:
            return SurroundResult(False, None, 0, time.monotonic() - t0)
        rows, y = lad.rows[1], lad.y[1]
        S, F = self.S, lad.false
        inverse, pairs, same, stab = _closure(rows, hs.forms.adjacent_to(0), self.o, self.c, self.gl, self.pos,
                                              self.group, self.mul, self.inv)
        M = len(rows) * S
        sel = int(lad._vars(1)[0])
        cnf = lad.pending
        if S == 1:
            x = y
        else:
            x = lad._vars(M)
            # y[r] <-> some element onto row r
            cnf.add_block(np.column_stack([np.full(len(y), -sel), -y, x.reshape(-1, S)]))
            cnf.add_block(np.column_stack([np.full(M, -sel), -x, np.repeat(y, S)]))
        h = np.concatenate([[F], lad._vars(S - 1)]) if S > 1 else np.array([F])
        xs = np.concatenate([x, [F]])  # index -1: the false literal
        neg = np.full(M, -sel)
        # 1. inverses
        cnf.add_block(np.column_stack([neg, -x, xs[inverse]]))
        # 2. touching pairs: α, β -> α⁻¹β
        if len(pairs):
            cnf.add_block(np.column_stack([np.full(len(pairs), -sel), -x[pairs[:, 0]], -x[pairs[:, 1]],
                                           xs[pairs[:, 2]]]))
        # 3. the stabiliser: α, β on one placement -> h[α⁻¹β]; h[s], α -> αs, sα; H a group
        if len(same):
            cnf.add_block(np.column_stack([np.full(len(same), -sel), -x[same[:, 0]], -x[same[:, 1]], h[same[:, 2]]]))
        if len(stab):
            lits = np.column_stack([np.full(len(stab), -sel), -h[stab[:, 0]], -x[stab[:, 1]]])
            cnf.add_block(np.column_stack([lits, x[stab[:, 2]]]))
            cnf.add_block(np.column_stack([lits, xs[stab[:, 3]]]))
            gs = self.gl[0]
            for k in range(1, S):
                for q in range(1, S):
                    r = self.pos[self.mul[gs[k], gs[q]]]
                    if r:  # (s t = identity needs no clause)
                        cnf.add([-sel, -int(h[k]), -int(h[q]), int(h[r])])
        models = 0
        while True:
            if models >= MAX_MODELS or (budget is not None and budget.spent()):
                cnf.add([-sel])
                return SurroundResult(None, None, models, time.monotonic() - t0)
            ans = lad.solve([sel], budget)
            if ans.satisfiable is None:
                cnf.add([-sel])
                return SurroundResult(None, None, models, time.monotonic() - t0)
            if not ans.satisfiable:
                cnf.add([-sel])  # the guarded clauses are void from now on
                return SurroundResult(False, None, models, time.monotonic() - t0)
            models += 1
            used = ans.values(x)
            held = ans.values(h[1:]) if S > 1 else np.zeros(0, dtype=bool)
            tt = self.build(rows, used, held)
            if tt is not None:
                cnf.add([-sel])
                return SurroundResult(True, tt, models, time.monotonic() - t0)
            # not a one-class tiling: block exactly this choice of elements
            cnf.add([-sel, *(-x[used]).tolist(), *x[~used].tolist()])

    def build(self, rows: np.ndarray, used: np.ndarray, held: np.ndarray) -> TorusTiling | None:
        """The tiling of the group generated by the used elements and symmetries, checked: an
        exact cover of the torus of its translation lattice with one transitivity class, or None."""
        grid = self.hs.grid
        p = int(grid.period)
        elems = _elements(rows, self.c, self.gl)[used]
        gs = self.gl[0]
        syms = [(int(gs[k]), -int(self.c[gs[k], 0]), -int(self.c[gs[k], 1])) for k in range(1, self.S) if held[k - 1]]
        gens = np.array(elems.tolist() + syms, dtype=np.int64).reshape(-1, 3)
        if not len(gens):
            return None
        # a transversal of the point group of the generated group (taken depth first) and its
        # translation lattice, by Schreier's generators
        reps, a, b, d = _group_closure(gens, self.group, self.mul, True)
        if a == 0 or d == 0:
            return None  # no lattice of translations: not a tiling of the plane
        if a % p or b % p or d % p:
            return None  # a translation off the grid
        a, b, d = a // p, b // p, d // p
        lat = (a, b, d)
        ts = TorusSearch(self.hs.forms)
        N = a * d
        placed = np.array([[self.o[g], (tx + self.c[g, 0]) // p, (ty + self.c[g, 1]) // p] for g, tx, ty in reps.tolist()],
                          dtype=np.int64)
        key = placed[:, 0] * N + _reduce(placed[:, 1:3], a, b, d)
        _, first = np.unique(key, return_index=True)
        placed = placed[np.sort(first)]
        n = self.hs.forms.n
        if len(placed) * n != ts.R * N:
            return None
        ids = ts.types[placed[:, 0]] * N + _reduce(ts.units[placed[:, 0]] + placed[:, None, 1:3], a, b, d)
        if len(np.unique(ids)) != ids.size:
            return None  # copies overlap on the torus
        tt = ts.classes(lat, placed)
        return tt if tt.k == 1 else None


def isohedral_surround(hs: HeeschSolver, time_limit: Budget | float | None = None) -> SurroundResult:
    """:meth:`SurroundTest.run` on a polyform's :class:`HeeschSolver` before its coronas grow."""
    return SurroundTest(hs).run(time_limit)
