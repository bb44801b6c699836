"""The compiled layer step of the hyperbolic boundary automaton (numba; see layers.py).

One pass over the boundary finds the runs of edges joined at vertices with q − 1 tiles (one
new tile each, its matrix the parent's times the run's first half-turn: 27 products, no
temporaries), then walks the new tiles' free edges with a stack: a vertex the two tiles on
either side fill (q tiles) cancels against the edge before it, its count carried to the next
vertex, so cascades cost nothing extra. The NumPy formulation (runs by repeat/cumsum and
cancellations in passes, ``layers._cancel``) is kept as the tests' independent check.
"""

from __future__ import annotations

import numpy as np

from tilekit.jit import njit


@njit(cache=True, nogil=True)
def grow(count, owner, slot, layer, half, p, q, out):  # pragma: no cover - compiled
    """One layer: its G transforms written to out[:G] (out has room for the G vertices of
    count other than q − 1), and the
    new boundary (count, owner, slot). Returns (G, count, owner, slot), or (status, ...) with
    a negative status when the boundary does not grow as a disc's (-1: no open vertex, -2: a
    tile enclosed, -3: a cancellation past the start, -4: a vertex over q tiles)."""
    n = count.shape[0]
    bad = np.empty(0, np.int32)
    G = 0
    s0 = -1
    for i in range(n):
        if count[i] != q - 1:
            G += 1
            if s0 < 0:
                s0 = i
    if G == 0:
        return -1, bad, bad, bad
    parent = np.empty(G, np.int32)
    pslot = np.empty(G, np.int32)
    jcount = np.empty(G, np.int32)
    run = np.zeros(G, np.int32)
    g = -1
    for t in range(n):
        i = s0 + t
        if i >= n:
            i -= n
        if count[i] != q - 1:
            g += 1
            parent[g] = owner[i]
            pslot[g] = slot[i]
            jcount[g] = count[i]
        run[g] += 1
    cap = 0
    g0 = -1
    for g in range(G):
        free = p - run[g]
        if free < 1:
            return -2, bad, bad, bad
        cap += free
        if g0 < 0 and free >= 2:
            g0 = g
        a = layer[parent[g]]
        b = half[pslot[g]]
        for r in range(3):
            a0, a1, a2 = a[r, 0], a[r, 1], a[r, 2]
            for c in range(3):
                out[g, r, c] = a0 * b[0, c] + a1 * b[1, c] + a2 * b[2, c]
    if g0 < 0:
        return -2, bad, bad, bad
    sc = np.empty(cap, np.int32)
    so = np.empty(cap, np.int32)
    ss = np.empty(cap, np.int32)
    top = 0
    carry = 0
    # the walk starts at a vertex of one new tile alone (count 1), g0's second vertex, and
    # ends with g0's first (a junction), so no cancellation needs a vertex not yet seen
    for t in range(G + 1):
        g = g0 + t
        if g >= G:
            g -= G
        free = p - run[g]
        k0 = 1 if t == 0 else 0
        k1 = 1 if t == G else free
        for k in range(k0, k1):
            c = (jcount[g] + 2 if k == 0 else 1) + carry
            carry = 0
            if c == q:
                if top == 0:
                    return -3, bad, bad, bad
                top -= 1
                carry = sc[top]
            elif c > q:
                return -4, bad, bad, bad
            else:
                sc[top] = c
                so[top] = g
                s = pslot[g] + 1 + k
                ss[top] = s % p
                top += 1
    lo = 0
    if carry:
        sc[0] += carry
    while top - lo > 3 and sc[lo] == q:
        top -= 1
        sc[lo + 1] += sc[top]
        lo += 1
    for i in range(lo, top):
        if sc[i] >= q:
            return -4, bad, bad, bad
    return G, sc[lo:top], so[lo:top], ss[lo:top]


@njit(cache=True, nogil=True)
def poincare_points(transforms, points):  # pragma: no cover - compiled
    """(n, k, 2) Poincaré-disc coordinates of hyperboloid points (k, 3) moved by each of the
    (n, 3, 3) Lorentz transforms: nine products and one division a point, no temporaries."""
    n = transforms.shape[0]
    k = points.shape[0]
    out = np.empty((n, k, 2))
    for i in range(n):
        m = transforms[i]
        for j in range(k):
            px, py, pt = points[j, 0], points[j, 1], points[j, 2]
            x = m[0, 0] * px + m[0, 1] * py + m[0, 2] * pt
            y = m[1, 0] * px + m[1, 1] * py + m[1, 2] * pt
            t = m[2, 0] * px + m[2, 1] * py + m[2, 2] * pt
            s = 1.0 / (1.0 + t)
            out[i, j, 0] = x * s
            out[i, j, 1] = y * s
    return out
