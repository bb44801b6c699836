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

from tilekit.lattice import Grid, pack, unique_keys, unpack, vertex_neighbour_table


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
        # every image at once, each in fixed form (sorted by (y, x), the least cell moved into
        # [0, period)^2, as lattice.fixed_form): (G, n, 2)
        img = np.einsum("gab,nb->gna", self.grid.group.astype(np.int64), self.cells)
        order = np.argsort(pack(img[..., ::-1]), axis=1, kind="stable")
        img = np.take_along_axis(img, order[..., None], axis=1)
        c0 = img[:, 0, :]
        shift = np.mod(c0, self.grid.period) - c0  # fixed form = image + shift
        fixed = img + shift[:, None, :]
        keys = np.sort(pack(fixed), axis=1)
        seen: set[bytes] = set()
        first = []
        for g in range(len(fixed)):  # distinct orientations, in group order
            b = keys[g].tobytes()
            if b not in seen:
                seen.add(b)
                first.append(g)
        self.forms = fixed[first]  # (J, n, 2)
        self.g = np.array(first, dtype=np.int64)
        self.shift = shift[first]
        self.keys = pack(self.forms)  # (J, n)

    @property
    def n(self) -> int:
        return self.forms.shape[1]

    @property
    def J(self) -> int:
        return len(self.forms)

    @cached_property
    def halos(self) -> np.ndarray:
        """(J, H, 2): the halo of each orientation (all halos have the same size), in one array
        pass: every cell's vertex neighbours (the grid's per-type table), keyed by orientation,
        deduplicated by one sort, less the orientation's own cells."""
        J, n = self.J, self.n
        tab = vertex_neighbour_table(self.grid)
        cand = self.forms[:, :, None, :] + tab[self.grid.cell_type(self.forms.reshape(-1, 2))].reshape(J, n, -1, 2)
        jj = np.arange(J, dtype=np.int64)[:, None] << 42
        key = unique_keys(jj | pack(cand).reshape(J, -1))
        own = np.sort((jj | self.keys).ravel())
        pos = np.minimum(np.searchsorted(own, key), len(own) - 1)
        key = key[own[pos] != key]
        return unpack(key & ((np.int64(1) << 42) - 1)).reshape(J, -1, 2)

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
        if j in done:
            return done[j]
        p, J = self.grid.period, self.J
        t = self.halos[j][None, :, None, :] - self.forms[:, None, :, :]  # (J, H, n, 2)
        kk = np.broadcast_to(np.arange(J)[:, None, None], t.shape[:-1]).ravel()
        t = t.reshape(-1, 2)
        ok = (t % p == 0).all(axis=1)
        # distinct (k, t) as one sorted int64 key (packed translations are < 2^42)
        key = unique_keys((kk[ok] << 42) | pack(t[ok]))
        kk = key >> 42
        tt = unpack(key & ((np.int64(1) << 42) - 1))
        moved = pack(self.forms[kk] + tt[:, None, :])  # (R, n)
        own = np.sort(self.keys[j])
        pos = np.minimum(np.searchsorted(own, moved), len(own) - 1)
        clash = (own[pos] == moved).any(axis=1)
        done[j] = np.column_stack([kk, tt]).astype(np.int64)[~clash]
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
