"""Compiled loops of the core (numba), imported only by the paths that need them.

``tilekit.tiling`` loads this module lazily, for patches large enough that the loop pays for
numba's import (a small patch keeps the NumPy path and its start-up).
"""

from __future__ import annotations

import numpy as np

from tilekit.jit import njit


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


@njit(cache=True, nogil=True)
def _trails(u, v, n, vertices, starts):  # pragma: no cover - compiled
    m = u.shape[0]
    degree = np.zeros(n + 1, dtype=np.int64)
    for e in range(m):
        degree[u[e] + 1] += 1
        degree[v[e] + 1] += 1
    first = np.cumsum(degree)  # first[x]: where vertex x's incident edges start
    cursor = first[:-1].copy()
    incident = np.empty(2 * m, dtype=np.int64)
    fill = first[:-1].copy()
    for e in range(m):
        incident[fill[u[e]]] = e
        fill[u[e]] += 1
        incident[fill[v[e]]] = e
        fill[v[e]] += 1
    used = np.zeros(m, dtype=np.bool_)
    left = degree[1:].copy()  # unused edges at each vertex
    nv = 0
    nt = 0
    # first from the vertices with an odd number of unused edges: a walk from one ends at
    # another, and the two become even; then every count left is even and the rest are
    # closed walks
    for sweep in range(2):
        for s in range(n):
            while left[s] > 0 and (sweep == 1 or left[s] % 2 == 1):
                while used[incident[cursor[s]]]:
                    cursor[s] += 1
                starts[nt] = nv
                nt += 1
                vertices[nv] = s
                nv += 1
                x = s
                while True:
                    while cursor[x] < first[x + 1] and used[incident[cursor[x]]]:
                        cursor[x] += 1
                    if cursor[x] == first[x + 1]:
                        break
                    e = incident[cursor[x]]
                    used[e] = True
                    left[u[e]] -= 1
                    left[v[e]] -= 1
                    x = v[e] if u[e] == x else u[e]
                    vertices[nv] = x
                    nv += 1
    starts[nt] = nv
    return nv, nt


def trails(u: np.ndarray, v: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The edges (u[e], v[e]) of a graph on vertices 0..n-1 as walks that use each edge once:
    ``(vertices, starts)``, walk t visiting ``vertices[starts[t]:starts[t + 1]]``. Walks start
    at odd-degree vertices first, so a connected graph with 2k odd vertices gives k open walks
    and then closed ones; a cutter's head lifts once per walk instead of once per edge."""
    u = np.ascontiguousarray(u, dtype=np.int64)
    v = np.ascontiguousarray(v, dtype=np.int64)
    m = len(u)
    vertices = np.empty(2 * m + 1, dtype=np.int64)
    starts = np.empty(m + 1, dtype=np.int64)
    nv, nt = _trails(u, v, int(n), vertices, starts)
    return vertices[:nv], starts[: nt + 1]
