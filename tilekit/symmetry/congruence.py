"""Congruence of two periodic tilings: an isometry that maps one tiling onto the other, found
with the group search's own test, so that tilings can be told apart by geometry alone."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from tilekit.polygon import congruences
from tilekit.symmetry.cell import DEFAULT_TOL, _abs_tol, _base_cell, _Cell, _check
from tilekit.symmetry.group import _accepts
from tilekit.symmetry.lattice import _cell_area


def _joint_labels(a: _Cell, b: _Cell) -> tuple[_Cell, _Cell]:
    """The two cells with tile labels (signature point count, outline point count) numbered
    alike, so a tile of one is matched only with a tile of the other of the same kind."""
    rows = [np.column_stack([c.count, [len(o) for o in c.outlines]]) for c in (a, b)]
    _, label = np.unique(np.vstack(rows), axis=0, return_inverse=True)
    label = label.reshape(-1)
    return replace(a, label=label[: len(a)]), replace(b, label=label[len(a):])


def congruence(a: Any, b: Any, tol: float = DEFAULT_TOL) -> np.ndarray | None:
    """An isometry (3, 3) that maps tiling ``a`` onto tiling ``b``, or None when there is none.

    Tiles are matched by geometry (outlines and markings), as :func:`symmetries` matches
    them. A congruence maps a's least common tile onto some tile, and modulo b's lattice onto
    a tile of b's unit, so the candidates are the congruences of that tile onto each unit tile
    of b. A candidate g is accepted when it maps every tile of a's unit onto a tile of b and
    maps a's two lattice vectors to translations of b; then g(a) is a tiling inside b, so
    g(a) = b. Before any candidate, the number of tiles of each kind per unit area must agree.
    ``tol`` is relative to the tile size, the smaller of the two tilings' scales.
    """
    a, b = _check(a), _check(b)
    abs_tol = min(_abs_tol(a, tol), _abs_tol(b, tol))
    ca, cb = _joint_labels(_base_cell(a, abs_tol, False), _base_cell(b, abs_tol, False))
    n = int(max(ca.label.max(), cb.label.max())) + 1
    counts_a, counts_b = np.bincount(ca.label, minlength=n), np.bincount(cb.label, minlength=n)
    if not np.allclose(counts_a / _cell_area(ca.basis), counts_b / _cell_area(cb.basis), rtol=1e-6, atol=0):
        return None
    anchor = int(np.argmin(counts_a[ca.label] * (len(ca) + 1) + np.arange(len(ca))))
    cands = [congruences(ca.outlines[anchor], cb.outlines[j], abs_tol)
             for j in np.flatnonzero(cb.label == ca.label[anchor])]
    maps = np.concatenate([np.zeros((0, 3, 3)), *cands])
    maps = maps[_accepts(ca, maps, anchor, target=cb)]
    if not len(maps):
        return None
    # the images of a's lattice vectors must be translations of b
    moved = np.einsum("cij,kj->cki", maps[:, :2, :2], ca.basis).reshape(-1, 2)
    shifts = np.tile(np.eye(3), (len(moved), 1, 1))
    shifts[:, :2, 2] = moved
    good = _accepts(cb, shifts, 0).reshape(len(maps), 2).all(axis=1)
    return maps[int(np.argmax(good))] if good.any() else None


def congruent(a: Any, b: Any, tol: float = DEFAULT_TOL) -> bool:
    """Whether some isometry (direct or opposite) maps tiling ``a`` onto tiling ``b``."""
    return congruence(a, b, tol) is not None
