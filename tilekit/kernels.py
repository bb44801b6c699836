"""Compiled loops of the core (numba), imported only by the paths that need them.

``tilekit.tiling`` loads this module lazily, for patches large enough that the loop pays for
numba's import (a small patch keeps the NumPy path and its start-up).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def _bounds(prototile, transform, corners, counts, out):  # pragma: no cover - compiled
    for i in range(prototile.shape[0]):
        p = prototile[i]
        a, b, c = transform[i, 0, 0], transform[i, 0, 1], transform[i, 0, 2]
        d, e, f = transform[i, 1, 0], transform[i, 1, 1], transform[i, 1, 2]
        x0 = y0 = np.inf
        x1 = y1 = -np.inf
        for k in range(counts[p]):
            vx, vy = corners[p, k, 0], corners[p, k, 1]
            x = a * vx + b * vy + c
            y = d * vx + e * vy + f
            x0 = min(x0, x)
            x1 = max(x1, x)
            y0 = min(y0, y)
            y1 = max(y1, y)
        out[i, 0] = x0
        out[i, 1] = y0
        out[i, 2] = x1
        out[i, 3] = y1


def tile_bounds(prototile: np.ndarray, transform: np.ndarray, outlines: list[np.ndarray]) -> np.ndarray:
    """(n, 4) bounding boxes x0, y0, x1, y1 of affine-placed outlines, in one pass over the
    transforms (no per-corner temporary arrays)."""
    k = max(len(o) for o in outlines)
    corners = np.zeros((len(outlines), k, 2))
    for p, o in enumerate(outlines):
        corners[p, :len(o)] = o
    counts = np.array([len(o) for o in outlines], dtype=np.int64)
    out = np.empty((len(prototile), 4))
    _bounds(np.ascontiguousarray(prototile, dtype=np.int64), np.ascontiguousarray(transform, dtype=np.float64),
            corners, counts, out)
    return out
