"""Matching tiles: the congruences of one outline onto another, and locating the images of
tiles among the cell's tiles modulo the lattice (grid hash, then point sets both ways)."""

from __future__ import annotations

import math

import numpy as np

from tilekit.geometry import Affine
from tilekit.symmetry.cell import _Cell
from tilekit.symmetry.lattice import _inv2

#: Point-to-point distances computed per block when comparing located tiles.
_BLOCK_PAIRS = 2_000_000


def _candidate_pairs(cell: _Cell, centre: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(image, cell tile) pairs whose centres may agree modulo the lattice: a grid hash.

    Cell centres are reduced to fractional coordinates in [0, 1) and binned on a G x G
    grid (about one tile per bin); an image centre is compared only with the tiles in its
    own bin and the eight around it (wrapping round the cell), so the work grows with
    the number of images, not images x tiles.
    """
    m = len(cell)
    grid = max(1, int(math.isqrt(m)))
    inv = _inv2(cell.basis)
    fc = cell.centre @ inv
    cb = np.floor((fc - np.floor(fc)) * grid).astype(np.int64) % grid
    cid = cb[:, 0] * grid + cb[:, 1]
    order = np.argsort(cid, kind="stable")
    sorted_cid = cid[order]
    fi = centre @ inv
    ib = np.floor((fi - np.floor(fi)) * grid).astype(np.int64) % grid
    steps = sorted({d % grid for d in (-1, 0, 1)})
    ii_all, jj_all = [], []
    n = len(centre)
    for dx in steps:
        for dy in steps:
            nb = ((ib[:, 0] + dx) % grid) * grid + (ib[:, 1] + dy) % grid
            start = np.searchsorted(sorted_cid, nb, side="left")
            end = np.searchsorted(sorted_cid, nb, side="right")
            counts = end - start
            total = int(counts.sum())
            if not total:
                continue
            ii = np.repeat(np.arange(n), counts)
            pos = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts) + np.repeat(start, counts)
            ii_all.append(ii)
            jj_all.append(order[pos])
    if not ii_all:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(ii_all), np.concatenate(jj_all)


def _locate(cell: _Cell, pts: np.ndarray, centre: np.ndarray, label: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For image tiles (points (N, K, 2), centres (N, 2), labels (N,)) find the cell tile.

    Returns (j, shift): j[n] is the index of the cell tile that image n equals after
    translating it by the lattice vector shift[n], or -1 when image n is no tile. Centres
    are matched through a grid hash modulo the lattice; the point sets of matching pairs
    are then compared both ways, in blocks of bounded size.
    """
    n = len(pts)
    found = np.full(n, -1, dtype=np.int64)
    shift = np.zeros((n, 2))
    if n == 0:
        return found, shift
    tol = cell.tol
    ii, jj = _candidate_pairs(cell, centre)
    f = (centre[ii] - cell.centre[jj]) @ _inv2(cell.basis)
    r = np.rint(f)
    hit = (np.linalg.norm((f - r) @ cell.basis, axis=1) < tol) & (label[ii] == cell.label[jj])
    ii, jj, sh = ii[hit], jj[hit], r[hit] @ cell.basis
    k = pts.shape[1]
    block = max(1, _BLOCK_PAIRS // (k * k))
    same = np.zeros(len(ii), dtype=bool)
    for s in range(0, len(ii), block):
        sl = slice(s, s + block)
        a = pts[ii[sl]]  # (P, K, 2)
        b = cell.points[jj[sl]] + sh[sl, None, :]
        d = np.linalg.norm(a[:, :, None, :] - b[:, None, :, :], axis=3)  # (P, K, K)
        same[sl] = (d.min(axis=2).max(axis=1) < tol) & (d.min(axis=1).max(axis=1) < tol)
    ii, jj, sh = ii[same], jj[same], sh[same]
    # one match per image (a tile equals at most one tile of the cell): keep the first
    order = np.lexsort((jj, ii))
    ii, jj, sh = ii[order], jj[order], sh[order]
    first = np.ones(len(ii), dtype=bool)
    first[1:] = ii[1:] != ii[:-1]
    found[ii[first]] = jj[first]
    shift[ii[first]] = sh[first]
    return found, shift


def _images(
    cell: _Cell, maps: np.ndarray, idx: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cell tiles (all, or those at ``idx``) moved by every map: points (C*m, K, 2), centres, labels."""
    points, centre, label = cell.points, cell.centre, cell.label
    if idx is not None:
        points, centre, label = points[idx], centre[idx], label[idx]
    c, m, k = len(maps), len(label), points.shape[1]
    pts = Affine.apply(maps, points.reshape(-1, 2)).reshape(c * m, k, 2)
    cen = Affine.apply(maps, centre).reshape(c * m, 2)
    lab = np.tile(label, c)
    return pts, cen, lab
