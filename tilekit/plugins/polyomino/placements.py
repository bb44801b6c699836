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

from tilekit.lattice import Grid, fixed_form, halo_of, pack, unique_keys, unpack


@dataclass(eq=False)
class Forms:
    """The orientations of a polyform and which copies of one orientation touch another.

    ``forms[j]`` (fixed form) equals ``cells @ grid.group[g[j]].T + shift[j]`` as a set of
    cells; ``forms[0]`` is the polyform's own fixed form (the *kernel* of a corona search).
    """

    grid: Grid
    cells: np.ndarray

    def __post_init__(self) -> None:
        self.cells = np.asarray(self.cells, dtype=np.int64).reshape(-1, 2)
        forms, gs, shifts, seen = [], [], [], set()
        for g, m in enumerate(self.grid.group):
            img = self.cells @ m.T
            f = fixed_form(self.grid, img)
            key = tuple(np.sort(pack(f)).tolist())
            if key in seen:
                continue
            seen.add(key)
            # fixed_form sorts and translates; recover the translation from the first cell
            order = np.lexsort((img[:, 0], img[:, 1]))
            forms.append(f)
            gs.append(g)
            shifts.append(f[0] - img[order][0])
        self.forms = np.array(forms, dtype=np.int64)  # (J, n, 2)
        self.g = np.array(gs, dtype=np.int64)
        self.shift = np.array(shifts, dtype=np.int64)
        self.keys = pack(self.forms)  # (J, n)

    @property
    def n(self) -> int:
        return self.forms.shape[1]

    @property
    def J(self) -> int:
        return len(self.forms)

    @cached_property
    def halos(self) -> np.ndarray:
        """(J, H, 2): the halo of each orientation (all halos have the same size)."""
        return np.array([halo_of(self.grid, f) for f in self.forms], dtype=np.int64)

    @cached_property
    def adjacent(self) -> list[np.ndarray]:
        """Per orientation j, rows ``(k, tx, ty)``: ``forms[k] + t`` touches ``forms[j]``
        (sorted by k, then by the packed translation). One array pass over every (j, k) pair:
        the translations taking a cell of ``forms[k]`` onto a halo cell of ``forms[j]``."""
        p, J = self.grid.period, self.J
        t = self.halos[:, None, :, None, :] - self.forms[None, :, None, :, :]  # (J, J, H, n, 2)
        jj = np.broadcast_to(np.arange(J)[:, None, None, None], t.shape[:-1]).ravel()
        kk = np.broadcast_to(np.arange(J)[None, :, None, None], t.shape[:-1]).ravel()
        t = t.reshape(-1, 2)
        ok = (t % p == 0).all(axis=1)
        # distinct (j, k, t) as one sorted int64 key (packed translations are < 2^42)
        key = unique_keys(((jj[ok] * J + kk[ok]) << 42) | pack(t[ok]))
        jk = key >> 42
        jj, kk = jk // J, jk % J
        tt = unpack(key & ((np.int64(1) << 42) - 1))
        moved = pack(self.forms[kk] + tt[:, None, :])  # (R, n)
        # a copy overlapping forms[j] does not touch it: (j, cell) pairs as one sorted key
        own = np.sort(((np.arange(J)[:, None] << 42) | self.keys).ravel())
        probe = (jj[:, None] << 42) | moved
        pos = np.minimum(np.searchsorted(own, probe), len(own) - 1)
        clash = (own[pos] == probe).any(axis=1)
        rows = np.column_stack([kk, tt]).astype(np.int64)[~clash]
        cut = np.searchsorted(jj[~clash], np.arange(1, J))
        return np.split(rows, cut)

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
