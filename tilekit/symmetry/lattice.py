"""2D lattice algebra: reduced bases, lattice coordinates, membership, and the lattice that a
set of translations spans together with a given basis."""

from __future__ import annotations

import math
from functools import cache

import numpy as np

from tilekit.errors import GeometryError


def _reduce(b1: np.ndarray, b2: np.ndarray) -> np.ndarray:
    """Lagrange-Gauss reduction of a 2D lattice basis; rows, positively oriented."""
    b1, b2 = np.array(b1, dtype=float), np.array(b2, dtype=float)
    for _ in range(200):
        if b1 @ b1 > b2 @ b2:
            b1, b2 = b2, b1
        mu = round(float(b1 @ b2) / float(b1 @ b1))
        if mu == 0:
            break
        b2 = b2 - mu * b1
    if b1[0] * b2[1] - b1[1] * b2[0] < 0:
        b2 = -b2
    return np.array([b1, b2])


def _inv2(basis: np.ndarray) -> np.ndarray:
    """Inverse of a 2x2 matrix in closed form (for the lattice-coordinate map)."""
    (a, b), (c, d) = basis
    det = a * d - b * c
    return np.array([[d, -b], [-c, a]]) / det


def _frac(vectors: np.ndarray, basis: np.ndarray) -> np.ndarray:
    """Coordinates of vectors (..., 2) in the basis whose rows are the lattice vectors."""
    return np.asarray(vectors) @ _inv2(basis)


def _lattice_residual(v: np.ndarray, basis: np.ndarray) -> np.ndarray:
    """Distance of each vector (..., 2) from the nearest lattice point."""
    f = _frac(v, basis)
    return np.linalg.norm((f - np.rint(f)) @ basis, axis=-1)


def _in_lattice(v: np.ndarray, basis: np.ndarray, tol: float) -> bool:
    return bool(np.all(_lattice_residual(v, basis) < tol))


@cache
def _grid(r: int) -> np.ndarray:
    """Integer pairs (a, b) with |a|, |b| <= r, as a read-only (n, 2) float array."""
    rng = np.arange(-r, r + 1, dtype=float)
    a, b = np.meshgrid(rng, rng, indexing="ij")
    out = np.column_stack([a.ravel(), b.ravel()])
    out.setflags(write=False)
    return out


def _small_combos(basis: np.ndarray, r: int) -> np.ndarray:
    return _grid(r) @ basis


def _lattice_from(translations: np.ndarray, given: np.ndarray, index: int, tol: float) -> np.ndarray:
    """Reduced basis of the lattice spanned by ``given`` (rows) and ``translations``."""
    g = _reduce(given[0], given[1])
    if index == 1:
        return g
    f = _frac(translations, g)
    reps = (f - np.floor(f + 1e-9)) @ g  # representatives in the given cell
    cand = (reps[:, None, :] + _small_combos(g, 2)[None, :, :]).reshape(-1, 2)
    lengths = np.hypot(cand[:, 0], cand[:, 1])
    order = np.argsort(lengths, kind="stable")
    cand, lengths = cand[order], lengths[order]
    nz = lengths > tol
    cand, lengths = cand[nz], lengths[nz]
    w1 = cand[0]
    area = abs(g[0, 0] * g[1, 1] - g[0, 1] * g[1, 0]) / index
    cross = np.abs(w1[0] * cand[:, 1] - w1[1] * cand[:, 0])
    ok = np.flatnonzero(np.abs(cross - area) < tol * max(1.0, lengths[0]))
    if not len(ok):
        raise GeometryError(
            f"the {index} translations found do not form a lattice refining v1, v2 (tolerance {tol:g})"
        )
    basis = _reduce(w1, cand[ok[0]])
    bad = _lattice_residual(np.vstack([translations, given]), basis) >= tol * 10
    if bad.any():
        t = np.vstack([translations, given])[np.argmax(bad)]
        raise GeometryError(f"translation {t.tolist()} is not in the lattice found; raise the tolerance")
    return basis


def reduce_basis(b1: np.ndarray, b2: np.ndarray) -> np.ndarray:
    """Lagrange-Gauss reduction of the 2D lattice basis ``b1, b2``: rows (w1, w2) with
    |w1| <= |w2| <= |w2 ± w1|, positively oriented.

    >>> reduce_basis([1.0, 0.0], [5.0, 1.0]).tolist()
    [[1.0, 0.0], [0.0, 1.0]]
    """
    return _reduce(np.asarray(b1, dtype=float), np.asarray(b2, dtype=float))


def canonical_basis(g1: np.ndarray, g2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A deterministic reduced basis of the lattice spanned by g1, g2: v1 a shortest vector
    with the least direction angle in [0, 2π); v2 a shortest vector completing a
    positively oriented basis, least angle from v1 on ties (float noise cannot flip ties).

    >>> [v.tolist() for v in canonical_basis([0.0, 1.0], [-1.0, 3.0])]
    [[1.0, 0.0], [0.0, 1.0]]
    """
    two_pi = 2 * math.pi
    g1, g2 = _reduce(np.asarray(g1, float), np.asarray(g2, float))
    det = abs(g1[0] * g2[1] - g1[1] * g2[0])
    combos = np.array([a * g1 + b * g2 for a in range(-2, 3) for b in range(-2, 3) if (a, b) != (0, 0)])
    lengths = np.hypot(combos[:, 0], combos[:, 1])
    ang = np.round(np.mod(np.arctan2(combos[:, 1], combos[:, 0]), two_pi), 6) % round(two_pi, 6)
    shortest = np.flatnonzero(lengths <= lengths.min() + 1e-6)
    i1 = shortest[np.lexsort((ang[shortest],))[0]]
    v1 = combos[i1]
    best = None
    for j in np.argsort(np.round(lengths, 6), kind="stable"):
        w = combos[j]
        d = v1[0] * w[1] - v1[1] * w[0]
        if abs(abs(d) - det) > 1e-6 * max(1.0, det) or d <= 0:
            continue
        key = (round(float(lengths[j]), 6), round(float(np.mod(np.arctan2(w[1], w[0]) - np.arctan2(v1[1], v1[0]), two_pi)), 6))
        if best is None or key < best[0]:
            best = (key, w)
    assert best is not None
    return v1, best[1]


def successive_minima(vectors: np.ndarray, tol: float = 1e-7) -> tuple[np.ndarray, np.ndarray]:
    """The two successive minima of a set of lattice vectors (a shortest one, then the
    shortest independent one), positively oriented; in the plane they form a basis of the
    lattice the vectors generate when the set holds every lattice vector up to that length.

    >>> [v.tolist() for v in successive_minima(np.array([[2.0, 0.0], [0.0, 3.0], [1.0, 0.0]]))]
    [[1.0, 0.0], [0.0, 3.0]]
    """
    vecs = np.asarray(vectors, dtype=float)
    vecs = vecs[np.hypot(vecs[:, 0], vecs[:, 1]) > tol]
    if len(vecs) < 2:
        raise GeometryError("fewer than two non-zero translations: no lattice basis")
    order = np.argsort(np.hypot(vecs[:, 0], vecs[:, 1]))
    v1 = vecs[order[0]]
    v2 = next((vecs[i] for i in order[1:] if abs(v1[0] * vecs[i][1] - v1[1] * vecs[i][0]) > tol), None)
    if v2 is None:
        raise GeometryError("the translations are all parallel: no lattice basis")
    if v1[0] * v2[1] - v1[1] * v2[0] < 0:
        v2 = -v2
    return v1, v2


def _cell_area(lattice: np.ndarray) -> float:
    return abs(float(lattice[0, 0] * lattice[1, 1] - lattice[0, 1] * lattice[1, 0]))
