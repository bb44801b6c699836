"""Compiled loops of the multigrid (numba): the intersections of a window, pair by pair of
grids and line by line, and each one's rhomb, in one pass with no temporaries.

Per intersection the work is a loop over the other N - 2 grids (a ceiling and a product
each); in NumPy that is N - 2 passes over memory per block and, for regions of a few hundred
tiles, thousands of small array calls (N(N - 1)/2 pairs times N - 2 grids: 0.9 s for n = 49).
Here one call does a whole region. Coordinates are about the anchor (see multigrid.py):
grid j's lines are w . e_j = m - f_j, m an integer.
"""

from __future__ import annotations

import math

import numpy as np

from tilekit.jit import njit


@njit(cache=True, nogil=True)
def _rows(er0, er1, fr, box):  # pragma: no cover - compiled
    """The lines m of a grid (direction er, fraction fr) crossing the box: (first, last)."""
    lo = math.inf
    hi = -math.inf
    for cx in (box[0], box[2]):
        for cy in (box[1], box[3]):
            p = cx * er0 + cy * er1
            lo = min(lo, p)
            hi = max(hi, p)
    return math.ceil(lo + fr), math.floor(hi + fr)


@njit(cache=True, nogil=True)
def _chord(er0, er1, es0, es1, fr, fs, box, m):  # pragma: no cover - compiled
    """The lines of grid s crossing line m of grid r inside the box: (first, last), last <
    first when none. The line is w = c er + t n (n = er turned by 90 degrees), t bounded by
    the box's sides; on it w . es = c (er . es) + t (n . es)."""
    c = m - fr
    n0, n1 = -er1, er0
    tlo = -math.inf
    thi = math.inf
    for axis in range(2):
        na = n0 if axis == 0 else n1
        ea = er0 if axis == 0 else er1
        low = box[0] if axis == 0 else box[1]
        high = box[2] if axis == 0 else box[3]
        if abs(na) > 1e-15:
            t0 = (low - c * ea) / na
            t1 = (high - c * ea) / na
            tlo = max(tlo, min(t0, t1))
            thi = min(thi, max(t0, t1))
        elif c * ea < low or c * ea > high:
            return 1, 0
    if thi < tlo:
        return 1, 0
    cos = er0 * es0 + er1 * es1
    sin = n0 * es0 + n1 * es1
    a = c * cos + tlo * sin + fs
    b = c * cos + thi * sin + fs
    return math.ceil(min(a, b)), math.floor(max(a, b))


@njit(cache=True, nogil=True)
def count(e, f, pairs, box):  # pragma: no cover - compiled
    """The intersections of every pair of grids inside the box (the fill's candidates)."""
    total = 0
    for p in range(pairs.shape[0]):
        r, s = pairs[p, 0], pairs[p, 1]
        first, last = _rows(e[r, 0], e[r, 1], f[r], box)
        for m in range(first, last + 1):
            a, b = _chord(e[r, 0], e[r, 1], e[s, 0], e[s, 1], f[r], f[s], box, m)
            if b >= a:
                total += b - a + 1
    return total


@njit(cache=True, nogil=True)
def fill(e, f, pairs, inv, pair_bounds, box, region, margin, tol, out_pair, out_lower, out_k, with_k, status):  # pragma: no cover - compiled
    """Every intersection in the box whose rhomb's bounding box overlaps ``region`` (by more
    than ``margin``): its pair, its lower vertex (sum of K_j e_j, about the anchor) and, with
    ``with_k``, its index vector less the anchor's. Returns the count; on an intersection with
    a third line within ``tol`` it stops and writes (pair, m_r, m_s, grid) to ``status``."""
    grids = e.shape[0]
    at = 0
    for p in range(pairs.shape[0]):
        r, s = pairs[p, 0], pairs[p, 1]
        i00, i01, i10, i11 = inv[p, 0, 0], inv[p, 0, 1], inv[p, 1, 0], inv[p, 1, 1]
        bx0, by0, bx1, by1 = pair_bounds[p, 0], pair_bounds[p, 1], pair_bounds[p, 2], pair_bounds[p, 3]
        first, last = _rows(e[r, 0], e[r, 1], f[r], box)
        for mr in range(first, last + 1):
            a, b = _chord(e[r, 0], e[r, 1], e[s, 0], e[s, 1], f[r], f[s], box, mr)
            cr = mr - f[r]
            for ms in range(a, b + 1):
                cs = ms - f[s]
                wx = i00 * cr + i01 * cs
                wy = i10 * cr + i11 * cs
                vx = mr * e[r, 0] + ms * e[s, 0]
                vy = mr * e[r, 1] + ms * e[s, 1]
                for j in range(grids):
                    if j == r or j == s:
                        continue
                    x = f[j] + wx * e[j, 0] + wy * e[j, 1]
                    k = math.ceil(x)
                    gap = k - x  # in [0, 1): a line of grid j within tol of the point at 0 or 1
                    if gap < tol or gap > 1 - tol:
                        status[0] = p
                        status[1] = mr
                        status[2] = ms
                        status[3] = j
                        return at
                    vx += k * e[j, 0]
                    vy += k * e[j, 1]
                    if with_k:
                        out_k[at, j] = k
                if (vx + bx1 > region[0] + margin and vx + bx0 < region[2] - margin
                        and vy + by1 > region[1] + margin and vy + by0 < region[3] - margin):
                    out_pair[at] = p
                    out_lower[at, 0] = vx
                    out_lower[at, 1] = vy
                    if with_k:
                        out_k[at, r] = mr
                        out_k[at, s] = ms
                    at += 1
    return at


@njit(cache=True, nogil=True)
def place(pair, lower, turn, offset, kind, out_maps, out_kind):  # pragma: no cover - compiled
    """Each rhomb's map (its pair's rotation, translated to its lower vertex plus the pair's
    offset) and prototile, written in one pass."""
    for i in range(pair.shape[0]):
        p = pair[i]
        c, s = turn[p, 0], turn[p, 1]
        out_maps[i, 0, 0] = c
        out_maps[i, 0, 1] = -s
        out_maps[i, 0, 2] = lower[i, 0] + offset[p, 0]
        out_maps[i, 1, 0] = s
        out_maps[i, 1, 1] = c
        out_maps[i, 1, 2] = lower[i, 1] + offset[p, 1]
        out_maps[i, 2, 0] = 0.0
        out_maps[i, 2, 1] = 0.0
        out_maps[i, 2, 2] = 1.0
        out_kind[i] = kind[p]


def rhombs_in(e: np.ndarray, f: np.ndarray, pairs: np.ndarray, inv: np.ndarray, pair_bounds: np.ndarray,
              box: tuple[float, ...], region: tuple[float, ...], margin: float, tol: float, with_k: bool
              ) -> tuple[int, np.ndarray, np.ndarray, np.ndarray | None, np.ndarray]:
    """(candidates, pair, lower, K less the anchor's or None, status) of one window: the
    arrays are the rhombs kept; ``status[0] >= 0`` names a singular intersection (pair, m_r,
    m_s, third grid), where the fill stopped."""
    box_a = np.asarray(box, dtype=np.float64)
    region_a = np.asarray(region, dtype=np.float64)
    total = int(count(e, f, pairs, box_a))
    out_pair = np.empty(total, dtype=np.int64)
    out_lower = np.empty((total, 2))
    out_k = np.empty((total if with_k else 0, e.shape[0]), dtype=np.int64)
    status = np.full(4, -1, dtype=np.int64)
    kept = int(fill(e, f, pairs, inv, pair_bounds, box_a, region_a, margin, tol, out_pair, out_lower,
                    out_k if with_k else np.empty((1, e.shape[0]), dtype=np.int64), with_k, status))
    # views of the kept rows: the region's box test drops about a perimeter's worth of the
    # candidates (0.5 % at 10^6 tiles), less than a copy would cost
    return total, out_pair[:kept], out_lower[:kept], out_k[:kept] if with_k else None, status
