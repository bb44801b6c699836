"""Copies of one polyform on its grid: orientations, packed cell keys, touching copies, holes.

The Heesch (corona) and torus (periodic tiling) searches both reason about *placements*: a
placement ``(j, t)`` is orientation ``j`` of the polyform (its image under an element of the
grid's point group, in fixed form) moved by a translation ``t`` of the grid (a vector of
``period * Z^2`` in fine coordinates, see :mod:`tilekit.lattice`). Everything here is
grid-generic: it reads only the grid's tables.

Two copies *overlap* when they share a cell, and *touch* when they do not overlap but share a
point: for cells that is a shared vertex, so a copy touches ``F`` exactly when it covers a
cell of ``F``'s *halo* (the cells sharing a vertex with ``F`` and not in it). This is the
neighbourhood of Kaplan's "Heesch numbers of unmarked polyforms" (Contributions to Discrete
Mathematics 17(2), 2022), where a corona must cover the halo of the patch inside it.

Cells are packed into single int64 keys (:func:`tilekit.lattice.pack`; halos and holes are
:func:`tilekit.lattice.halo_of` and :func:`tilekit.lattice.holes_of`) so that sets of cells are sorted arrays
and membership is ``np.isin``/``searchsorted``, never a per-cell Python object.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from tilekit.jit import njit
from tilekit.lattice import _M, _OFF, Grid, pack, vertex_neighbour_table


@njit(cache=True)
def _adjacent(forms, halo, own, period):  # pragma: no cover - compiled
    """Rows ``(k, tx, ty)``: ``forms[k] + t`` covers a cell of ``halo`` and none of ``own``
    (sorted packed keys), each once, sorted by k and then by the packed translation (the
    translations taking a cell of ``forms[k]`` onto a halo cell, one loop)."""
    J, n = forms.shape[0], forms.shape[1]
    H = halo.shape[0]
    off, m = np.int64(_OFF), np.int64(_M)  # lattice.pack's offsets
    keys = np.empty(J * H * n, np.int64)
    c = 0
    for k in range(J):
        for h in range(H):
            for i in range(n):
                tx = halo[h, 0] - forms[k, i, 0]
                ty = halo[h, 1] - forms[k, i, 1]
                if tx % period == 0 and ty % period == 0:
                    keys[c] = (np.int64(k) << 42) | ((tx + off) * m + (ty + off))
                    c += 1
    keys = np.unique(keys[:c])
    out = np.empty((keys.shape[0], 3), np.int64)
    r = 0
    for q in range(keys.shape[0]):
        k = keys[q] >> 42
        t = keys[q] & ((np.int64(1) << 42) - 1)
        tx = t // m - off
        ty = t % m - off
        clash = False
        for i in range(n):
            v = (forms[k, i, 0] + tx + off) * m + (forms[k, i, 1] + ty + off)
            p = np.searchsorted(own, v)
            if p < own.shape[0] and own[p] == v:
                clash = True
                break
        if not clash:
            out[r, 0] = k
            out[r, 1] = tx
            out[r, 2] = ty
            r += 1
    return out[:r].copy()


@njit(cache=True)
def _halos(forms, table, types, period):  # pragma: no cover - compiled
    """Per orientation, its halo cells sorted by packed key (see :meth:`Forms.halos`)."""
    J, n, K = forms.shape[0], forms.shape[1], table.shape[1]
    off, m = np.int64(_OFF), np.int64(_M)  # lattice.pack's offsets
    out = np.empty((0, 0, 2), np.int64)
    for j in range(J):
        own = np.empty(n, np.int64)
        cand = np.empty(n * K, np.int64)
        for i in range(n):
            x, y = forms[j, i, 0], forms[j, i, 1]
            own[i] = (x + off) * m + (y + off)
            t = types[(y % period) * period + x % period]
            for k in range(K):
                cand[i * K + k] = (x + table[t, k, 0] + off) * m + (y + table[t, k, 1] + off)
        own = np.sort(own)
        cand = np.unique(cand)
        keep = np.ones(cand.shape[0], np.bool_)
        for q in range(cand.shape[0]):
            p = np.searchsorted(own, cand[q])
            if p < n and own[p] == cand[q]:
                keep[q] = False
        cand = cand[keep]
        if j == 0:
            out = np.empty((J, cand.shape[0], 2), np.int64)
        for q in range(cand.shape[0]):
            out[j, q, 0] = cand[q] // m - off
            out[j, q, 1] = cand[q] % m - off
    return out


@njit(cache=True)
def _orientations(cells, group, period):  # pragma: no cover - compiled
    """The distinct images of ``cells`` under ``group``, in group order, each in fixed form
    (sorted by (y, x), the least cell moved into [0, period)^2, as :func:`lattice.fixed_form`):
    (J, n, 2), their sorted packed keys (J, n), the group index of each and its shift (J, 2)
    (fixed form = image + shift); then, per group element g, the orientation its image is
    (G,) and its shift (G, 2). The polyform's own fixed form comes first."""
    G, n = group.shape[0], cells.shape[0]
    off, mm = np.int64(_OFF), np.int64(_M)  # lattice.pack's offsets
    out = np.empty((G, n, 2), np.int64)
    keys = np.empty((G, n), np.int64)
    gidx = np.empty(G, np.int64)
    shift = np.empty((G, 2), np.int64)
    owner = np.empty(G, np.int64)
    gshift = np.empty((G, 2), np.int64)
    J = 0
    for g in range(G):
        img = np.empty((n, 2), np.int64)
        yx = np.empty(n, np.int64)
        for i in range(n):
            img[i, 0] = group[g, 0, 0] * cells[i, 0] + group[g, 0, 1] * cells[i, 1]
            img[i, 1] = group[g, 1, 0] * cells[i, 0] + group[g, 1, 1] * cells[i, 1]
            yx[i] = (img[i, 1] + off) * mm + (img[i, 0] + off)
        img = img[np.argsort(yx)]
        sx = img[0, 0] % period - img[0, 0]
        sy = img[0, 1] % period - img[0, 1]
        k = np.empty(n, np.int64)
        for i in range(n):
            img[i, 0] += sx
            img[i, 1] += sy
            k[i] = (img[i, 0] + off) * mm + (img[i, 1] + off)
        k = np.sort(k)
        gshift[g, 0] = sx
        gshift[g, 1] = sy
        owner[g] = J
        for j in range(J):
            same = True
            for i in range(n):
                if keys[j, i] != k[i]:
                    same = False
                    break
            if same:
                owner[g] = j
                break
        if owner[g] == J:
            out[J] = img
            keys[J] = k
            gidx[J] = g
            shift[J, 0] = sx
            shift[J, 1] = sy
            J += 1
    return out[:J].copy(), keys[:J].copy(), gidx[:J].copy(), shift[:J].copy(), owner, gshift


@dataclass(eq=False)
class Forms:
    """The orientations of a polyform and which copies of one orientation touch another.

    ``forms[j]`` (fixed form) equals ``cells @ grid.group[g[j]].T + shift[j]`` as a set of
    cells; ``forms[0]`` is the polyform's own fixed form (the *kernel* of a corona search).
    """

    grid: Grid
    cells: np.ndarray

    def __post_init__(self) -> None:
        self.cells = np.ascontiguousarray(np.asarray(self.cells, dtype=np.int64).reshape(-1, 2))
        # the distinct images, each in fixed form, in group order (one compiled loop, shared
        # with heesch.first_corona_rows)
        # (and, per group element, which orientation it makes and with which shift)
        self.forms, _, self.g, self.shift, self.owner, self.gshift = _orientations(
            self.cells, self.grid.group.astype(np.int64), np.int64(self.grid.period))  # (J, n, 2)
        self.keys = pack(self.forms)  # (J, n)

    @property
    def n(self) -> int:
        return self.forms.shape[1]

    @property
    def J(self) -> int:
        return len(self.forms)

    @cached_property
    def halos(self) -> np.ndarray:
        """(J, H, 2): the halo of each orientation (all halos have the same size), one compiled
        loop: every cell's vertex neighbours (the grid's per-type table), deduplicated by a
        sort, less the orientation's own cells."""
        return _halos(self.forms, vertex_neighbour_table(self.grid), self.grid.type_table, np.int64(self.grid.period))

    @cached_property
    def adjacent(self) -> list[np.ndarray]:
        """Per orientation j, rows ``(k, tx, ty)``: ``forms[k] + t`` touches ``forms[j]``
        (sorted by k, then by the packed translation); :meth:`adjacent_to` for each j."""
        return [self.adjacent_to(j) for j in range(self.J)]

    def adjacent_to(self, j: int) -> np.ndarray:
        """``adjacent[j]``, computed (and kept) alone: corona 1 needs only the kernel's, j = 0.
        One array pass over every orientation k: the translations taking a cell of
        ``forms[k]`` onto a halo cell of ``forms[j]``, less the copies overlapping ``forms[j]``."""
        done = self.__dict__.setdefault("_adjacent_to", {})
        if j not in done:
            done[j] = _adjacent(self.forms, np.ascontiguousarray(self.halos[j]), np.sort(self.keys[j]),
                                np.int64(self.grid.period))
        return done[j]

    def placement_cells(self, rows: np.ndarray) -> np.ndarray:
        """(m, n) packed cell keys of placements ``rows`` = (j, tx, ty)."""
        rows = np.asarray(rows, dtype=np.int64).reshape(-1, 3)
        return pack(self.forms[rows[:, 0]] + rows[:, None, 1:3])

    def placement_halos(self, rows: np.ndarray) -> np.ndarray:
        rows = np.asarray(rows, dtype=np.int64).reshape(-1, 3)
        return pack(self.halos[rows[:, 0]] + rows[:, None, 1:3])

    def affine(self, rows: np.ndarray) -> np.ndarray:
        """(m, 3, 3) Cartesian transforms taking ``outline(cells)`` onto each placement."""
        rows = np.asarray(rows, dtype=np.int64).reshape(-1, 3)
        g = self.grid.group[self.g[rows[:, 0]]].astype(float)  # (m, 2, 2) in fine coordinates
        t = (self.shift[rows[:, 0]] + rows[:, 1:3]).astype(float)
        to = self.grid.to_xy
        inv = np.linalg.inv(to)
        out = np.zeros((len(rows), 3, 3))
        out[:, :2, :2] = to @ g @ inv
        out[:, :2, 2] = t @ to.T
        out[:, 2, 2] = 1.0
        return out
