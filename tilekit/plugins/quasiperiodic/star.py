"""The n-fold star of a multigrid: grid directions, rhomb kinds and how each pair of grids
places its rhomb (one copy, read by the multigrid, the cut-and-project check and the tiling).

De Bruijn's multigrid for rotational order n uses the directions e_j = (cos 2πj/n, sin 2πj/n):
all n of them for odd n, the first n/2 for even n (the others are their negatives, whose
grids would be the same lines). With N grids, the edges of the tiles take the 2N directions
±e_j, two grids r < s meet in rhombs with edges e_r and e_s, and the rhombs come in N // 2
kinds, the acute (or right) angles kπ/N for k = 1 .. N // 2: thin and thick for n = 5, the
45° rhomb and the square for n = 8. (For odd n that is n // 2 kinds; for even n it is n // 4.)

Every prototile is the rhomb with unit edges ``(0, 0), (1, 0), (1 + cos a, sin a), (cos a, sin a)``;
a pair of grids places it by a fixed rotation at a fixed corner of its rhomb
(:attr:`Star.pair_turn`, :attr:`Star.pair_offset`), so a tile's map is that rotation plus a
translation.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from tilekit.errors import ParameterError
from tilekit.tiling import Prototile

#: The smallest rotational order: n = 4 is the square grid (two grids); below it no rhombs.
MIN_N = 4
#: The largest rotational order accepted (a typo guard, not a limit of the method): n = 49
#: has 49 grids, 24 rhomb kinds down to 3.7 degrees and 1,176 grid pairs, each a loop over
#: the intersections of a region; the cost per tile grows with the number of grids.
MAX_N = 50

__all__ = ["MAX_N", "MIN_N", "Star", "check_order", "star"]


def check_order(n: object) -> int:
    """``n`` as an int in MIN_N..MAX_N, or a one-line ParameterError."""
    if isinstance(n, bool):
        raise ParameterError(f"n={n!r} is not a whole number; valid: {MIN_N}..{MAX_N}")
    if isinstance(n, str):
        text = n.strip()
        try:
            if len(text) > 6 or not text.isascii():
                raise ValueError(text)
            n = int(text)
        except ValueError:
            raise ParameterError(f"n={n[:20]!r} is not a whole number; valid: {MIN_N}..{MAX_N}") from None
    if isinstance(n, float) and n.is_integer():
        n = int(n)
    if not isinstance(n, int | np.integer):
        raise ParameterError(f"n={n!r} is not a whole number; valid: {MIN_N}..{MAX_N}")
    n = int(n)
    if not MIN_N <= n <= MAX_N:
        raise ParameterError(
            f"n={n} is outside {MIN_N}..{MAX_N} (the rotational order of the star: n = 5 Penrose, 8 Ammann-Beenker)"
        )
    return n


class Star:
    """The directions, pairs and rhomb kinds of the n-fold multigrid (see the module text)."""

    def __init__(self, n: int) -> None:
        self.n = check_order(n)
        #: Number of grids N: n for odd n, n / 2 for even n.
        self.grids = self.n if self.n % 2 else self.n // 2
        angles = 2 * math.pi * np.arange(self.grids) / self.n
        #: (N, 2) unit vectors e_j.
        dirs = np.column_stack([np.cos(angles), np.sin(angles)])
        dirs[np.abs(dirs) < 1e-15] = 0.0  # cos(pi / 2) is 6e-17 in floats: the exact 0
        self.directions = dirs
        self.directions.setflags(write=False)
        #: The multigrid's scale: a grid-plane point z lies near the tiling point (N / 2) z,
        #: because sum_j (z . e_j) e_j = (N / 2) z for these directions (a tight frame).
        self.scale = self.grids / 2

    def __repr__(self) -> str:
        return f"Star(n={self.n}, grids={self.grids}, kinds={self.kinds})"

    @property
    def kinds(self) -> int:
        """Rhomb kinds: N // 2."""
        return self.grids // 2

    @cached_property
    def kind_angles(self) -> np.ndarray:
        """(kinds,) acute angle of each kind, kπ/N for k = 1 .. N // 2 (radians)."""
        return math.pi * np.arange(1, self.kinds + 1) / self.grids

    @cached_property
    def prototiles(self) -> list[Prototile]:
        """One unit rhomb per kind, the acute (or right) angle at the origin."""
        out = []
        for a in self.kind_angles:
            c, s = math.cos(a), math.sin(a)
            deg = math.degrees(a)
            name = "square" if abs(deg - 90) < 1e-9 else f"rhomb-{round(deg, 3):g}"
            out.append(Prototile(np.array([[0.0, 0.0], [1.0, 0.0], [1 + c, s], [c, s]]), name=name))
        return out

    # ------------------------------------------------------------------ pairs of grids
    @cached_property
    def pairs(self) -> np.ndarray:
        """(P, 2) the grid pairs r < s, P = N (N - 1) / 2."""
        r, s = np.triu_indices(self.grids, 1)
        return np.column_stack([r, s]).astype(np.int64)

    @cached_property
    def _placement(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Per pair: rhomb kind, the rotation (cos, sin) of the prototile, and the corner it
        is placed at (0: the vertex with the lower indices K_r, K_s; 1: that vertex + e_r
        or + e_s). With u, v the pair's edges ordered counter-clockwise (angle phi < pi from
        u to v): phi <= pi/2 puts the prototile's acute corner at the lower vertex, turned to u;
        otherwise its acute corner is at lower + u, turned to v."""
        e = self.directions
        kind = np.empty(len(self.pairs), dtype=np.int64)
        turn = np.empty((len(self.pairs), 2))
        offset = np.empty((len(self.pairs), 2))
        for p, (r, s) in enumerate(self.pairs.tolist()):
            u, v = e[r], e[s]
            if u[0] * v[1] - u[1] * v[0] < 0:
                u, v = v, u
            phi = math.atan2(u[0] * v[1] - u[1] * v[0], float(u @ v))
            if phi <= math.pi / 2 + 1e-12:
                alpha, axis, corner = phi, u, np.zeros(2)
            else:
                alpha, axis, corner = math.pi - phi, v, u
            k = round(alpha * self.grids / math.pi)
            if abs(k * math.pi / self.grids - alpha) > 1e-9 or not 1 <= k <= self.kinds:
                raise AssertionError(f"pair {r},{s} of n={self.n}: angle {alpha} is not a kind")  # pragma: no cover
            kind[p] = k - 1
            turn[p] = axis
            offset[p] = corner
        return kind, turn, offset

    @property
    def pair_kind(self) -> np.ndarray:
        """(P,) the rhomb kind (prototile index) of each pair's tiles."""
        return self._placement[0]

    @property
    def pair_turn(self) -> np.ndarray:
        """(P, 2) cos and sin of the rotation placing each pair's prototile."""
        return self._placement[1]

    @property
    def pair_offset(self) -> np.ndarray:
        """(P, 2) where the prototile's origin goes, relative to the rhomb's lower vertex."""
        return self._placement[2]

    @cached_property
    def pair_corners(self) -> np.ndarray:
        """(P, 4, 2) each pair's rhomb relative to its lower vertex: 0, e_r, e_r + e_s, e_s."""
        e = self.directions
        r, s = self.pairs[:, 0], self.pairs[:, 1]
        zero = np.zeros((len(r), 2))
        return np.stack([zero, e[r], e[r] + e[s], e[s]], axis=1)

    @cached_property
    def pair_bounds(self) -> np.ndarray:
        """(P, 4) each pair's rhomb's bounding box x0, y0, x1, y1 relative to its lower vertex."""
        c = self.pair_corners
        return np.column_stack([c[:, :, 0].min(1), c[:, :, 1].min(1), c[:, :, 0].max(1), c[:, :, 1].max(1)])

    @cached_property
    def pair_inverse(self) -> np.ndarray:
        """(P, 2, 2) the inverse of each pair's [e_r; e_s]: where lines of the two grids meet."""
        e = self.directions
        return np.linalg.inv(np.stack([e[self.pairs[:, 0]], e[self.pairs[:, 1]]], axis=1))

    @cached_property
    def pair_sines(self) -> np.ndarray:
        """(P,) |sin| of the angle between each pair's grids: intersections per unit area of
        the grid plane (lines of each grid are one apart), and the rhomb's area."""
        e = self.directions
        r, s = self.pairs[:, 0], self.pairs[:, 1]
        return np.abs(e[r, 0] * e[s, 1] - e[r, 1] * e[s, 0])

    # ------------------------------------------------------------------ sizes
    @cached_property
    def density(self) -> float:
        """Tiles per unit area of the tiling: the intersections per unit grid area, sum of
        the pairs' |sin|, over scale² (the tiling is the grid plane scaled by N / 2)."""
        return float(self.pair_sines.sum()) / self.scale**2

    @cached_property
    def zonotope_bounds(self) -> np.ndarray:
        """(x0, y0, x1, y1) of {sum_j u_j e_j : 0 <= u_j <= 1}: how far a vertex lies from
        scale z - sum_j gamma_j e_j, z any point of its mesh."""
        e = self.directions
        lo, hi = np.minimum(e, 0).sum(0), np.maximum(e, 0).sum(0)
        return np.array([lo[0], lo[1], hi[0], hi[1]])

    @property
    def diameter(self) -> float:
        """The largest tile diameter (the long diagonal of the thinnest rhomb, < 2)."""
        return float(2 * math.cos(self.kind_angles[0] / 2))


def star(n: int) -> Star:
    """The star of rotational order ``n`` (cached per n)."""
    n = check_order(n)
    cached = _STARS.get(n)
    if cached is None:
        cached = _STARS[n] = Star(n)
    return cached


_STARS: dict[int, Star] = {}
