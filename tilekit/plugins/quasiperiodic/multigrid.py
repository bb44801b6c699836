"""De Bruijn's multigrid (1981): the rhombs of a region from the grid lines crossing it.

Grid j is the family of lines {z : z . e_j - gamma_j = k}, k an integer. A point z off the
lines has the index vector K_j(z) = ceil(z . e_j - gamma_j); the mesh it lies in becomes the
tiling vertex sum_j K_j e_j, and the intersection of a line of grid r (index k_r) with one of
grid s (k_s) becomes the rhomb with vertices K + {0, e_r, e_r + e_s, e_s}, where K has
K_r = k_r, K_s = k_s and K_j = ceil(z . e_j - gamma_j) at the intersection z for the other j.
Three lines through one point (a *singular* gamma) leave that point's K undefined: such
offsets are refused, or perturbed (the tiling module's ``singular=perturb``).

Random access: every vertex of a mesh lies within the zonotope {sum u_j e_j, 0 <= u_j <= 1}
of (N / 2) z - sum_j gamma_j e_j, so the rhombs meeting a box come from the intersections in
one box of the grid plane (:func:`grid_window`), enumerated pair of grids by pair of grids,
line by line of one grid (no wasted candidates), in time proportional to the tiles: one
compiled pass over the window (:mod:`.kernels`).

Far from the origin the numbers z . e_j - gamma_j are large and their fractional parts would
lose precision, so each call anchors the grid at an integer point z_c of its window: the
integer parts I_j and fractions f_j of z_c . e_j - gamma_j are computed exactly (rational
arithmetic on the float directions and offsets, N numbers a call), and everything per tile is
computed from w = z - z_c, a few units long. Two calls with different windows therefore make
the same rhombs (up to the rounding of a few small numbers), wherever they are.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from tilekit.errors import ParameterError
from tilekit.plugins.quasiperiodic.star import Star

#: An intersection whose other grids' values z . e_j - gamma_j lie this close to an integer
#: has a third line through it (or within float noise of one): a singular point.
SINGULAR_TOL = 1e-9

__all__ = ["Rhombs", "SingularGrid", "grid_window", "rhombs"]


class SingularGrid(ParameterError):
    """Three grid lines meet in one point: the offsets gamma are singular (one line)."""

    def __init__(self, message: str, point: tuple[float, float], grids: tuple[int, int, int]) -> None:
        super().__init__(message)
        self.point = point
        self.grids = grids


@dataclass
class Rhombs:
    """The rhombs of a window, as columns: ``pair[i]`` indexes ``star.pairs`` (grids r < s),
    ``lower[i]`` is the rhomb's vertex with the lower indices K_r, K_s (absolute tiling
    coordinates), ``k[i]`` its whole index vector K (only when asked for), and ``candidates``
    the number of intersections computed (those in the grid window, before the final box test)."""

    pair: np.ndarray
    lower: np.ndarray
    k: np.ndarray | None
    candidates: int

    def __len__(self) -> int:
        return len(self.pair)


def grid_window(star: Star, gamma: np.ndarray, bounds: tuple[float, float, float, float]) -> tuple[float, ...]:
    """The box of the grid plane holding every intersection whose rhomb can meet ``bounds``.

    A rhomb at z lies in (N / 2) z - G + Z, G = sum_j gamma_j e_j and Z the zonotope of the
    star (its bounding box ``star.zonotope_bounds``), so z lies in (bounds + G - Z) / (N / 2);
    a margin of 1e-9 of the scale keeps an intersection on that box's edge inside it.
    """
    x0, y0, x1, y1 = bounds
    gx, gy = np.asarray(gamma, dtype=float) @ star.directions
    zx0, zy0, zx1, zy1 = star.zonotope_bounds
    s = star.scale
    pad = 1e-9 * (1 + max(abs(x0), abs(x1), abs(y0), abs(y1)))
    return ((x0 + gx - zx1) / s - pad, (y0 + gy - zy1) / s - pad, (x1 + gx - zx0) / s + pad, (y1 + gy - zy0) / s + pad)


def _anchor(star: Star, gamma: np.ndarray, z: tuple[int, int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(I, f, V): the integer parts I_j and fractions f_j in [0, 1) of z . e_j - gamma_j at
    the integer point z, and V = sum_j I_j e_j, computed exactly from the float directions
    and offsets (Fractions), then rounded once."""
    zx, zy = Fraction(z[0]), Fraction(z[1])
    ints, fracs = [], []
    vx = vy = Fraction(0)
    for (ex, ey), g in zip(star.directions.tolist(), np.asarray(gamma, dtype=float).tolist()):
        ex, ey = Fraction(ex), Fraction(ey)
        t = zx * ex + zy * ey - Fraction(g)
        i = math.floor(t)
        ints.append(i)
        fracs.append(float(t - i))
        vx += i * ex
        vy += i * ey
    return np.array(ints, dtype=np.int64), np.array(fracs), np.array([float(vx), float(vy)])


def rhombs(star: Star, gamma: np.ndarray, bounds: tuple[float, float, float, float], *,
           with_k: bool = False) -> Rhombs:
    """Every rhomb of the multigrid tiling with offsets ``gamma`` whose bounding box overlaps
    the box ``bounds`` by more than 1e-9 (boxes that only touch it do not count).

    Raises :class:`SingularGrid` (a one-line ParameterError) when three grid lines meet at
    one of the intersections computed. ``with_k`` adds each rhomb's index vector (int64).
    """
    # start-up cost: numba loads in ~0.3 s (the compiled loops are cached on disk); only
    # making tiles needs it, not naming or listing the family
    from tilekit.plugins.quasiperiodic import kernels

    gamma = np.asarray(gamma, dtype=float)
    qx0, qy0, qx1, qy1 = grid_window(star, gamma, bounds)
    z = (round((qx0 + qx1) / 2), round((qy0 + qy1) / 2))
    base, f, origin = _anchor(star, gamma, z)
    box = (qx0 - z[0], qy0 - z[1], qx1 - z[0], qy1 - z[1])
    x0, y0, x1, y1 = bounds
    region = (x0 - origin[0], y0 - origin[1], x1 - origin[0], y1 - origin[1])
    candidates, pair, lower, k, status = kernels.rhombs_in(
        star.directions, f, star.pairs, star.pair_inverse, star.pair_bounds, box, region,
        1e-9, SINGULAR_TOL, with_k)
    if status[0] >= 0:
        raise _singular(star, gamma, f, z, origin, *(int(v) for v in status))
    lower += origin
    if k is not None:
        k += base
    return Rhombs(pair, lower, k, candidates)


def _singular(star: Star, gamma: np.ndarray, f: np.ndarray, z: tuple[int, int], origin: np.ndarray,
              p: int, mr: int, ms: int, third: int) -> SingularGrid:
    """The one-line error for the intersection of line m_r of grid r and line m_s of grid s
    (the pair ``p``), through which a line of grid ``third`` passes."""
    r, s = (int(v) for v in star.pairs[p])
    e = star.directions
    w = star.pair_inverse[p] @ np.array([mr - f[r], ms - f[s]])
    point = (float(z[0] + w[0]), float(z[1] + w[1]))
    tile = star.scale * np.array(point) - np.asarray(gamma) @ e
    return SingularGrid(
        f"the offsets gamma={_fmt(gamma)} are singular for n={star.n}: lines of grids {r}, {s} and {third} meet "
        f"at the grid point ({point[0]:.6g}, {point[1]:.6g}) (tiling point near ({tile[0]:.6g}, {tile[1]:.6g})), "
        "where no rhomb is defined; choose other offsets, or --set singular=perturb", point, (r, s, third))


def _fmt(gamma: np.ndarray) -> str:
    return ",".join(f"{g:.6g}" for g in np.asarray(gamma).tolist())
