"""The two curved geometries of §3.6.2 as 3x3 matrices: the sphere (points on S², the group
O(3)) and the hyperbolic plane (points on the hyperboloid x² + y² − t² = −1, t > 0, the
Lorentz group O(2,1)); the regular p-gon of the tiling {p, q} and its edge half-turns; the
projections a picture needs (Poincaré disc, Klein disc, orthographic and stereographic views of
the sphere).

A {p, q} tile is centred at the pole (0, 0, 1) of either model with vertex k at angle
2πk/p. Its circumradius ρ comes from the right triangle of the (p, q, 2) triangle group
(angles π/p at the centre, π/q at the vertex, π/2 at the edge midpoint): cos ρ = cot(π/p)
cot(π/q) on the sphere, cosh ρ = cot(π/p) cot(π/q) in the hyperbolic plane; the inradius r
has cos r (cosh r) = cos(π/q) / sin(π/p). The neighbour across edge j is the tile turned by
a half-turn about that edge's midpoint: the p matrices ``half_turns`` generate the
orientation-preserving symmetry group's action on the tiles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tilekit.errors import ParameterError

#: Largest p or q accepted (a 10^6-tile patch of {p, q} needs few layers for large p, q;
#: this bounds the per-tile outline a user can ask for).
MAX_PQ = 60

SPHERE, EUCLIDEAN, HYPERBOLIC = "spherical", "euclidean", "hyperbolic"


def kind_of(p: int, q: int) -> str:
    """The geometry {p, q} lives in: (p − 2)(q − 2) < 4 sphere, = 4 plane, > 4 hyperbolic."""
    d = (p - 2) * (q - 2)
    return SPHERE if d < 4 else EUCLIDEAN if d == 4 else HYPERBOLIC


def check_pq(p: object, q: object, want: str | None = None) -> tuple[int, int]:
    """p and q as ints in 3..MAX_PQ, living in geometry ``want`` (when given); one-line errors."""
    out = []
    for name, v in (("p", p), ("q", q)):
        if isinstance(v, bool) or not isinstance(v, (int, float, str)):
            raise ParameterError(f"{name} must be an integer 3..{MAX_PQ}, got {type(v).__name__}")
        try:
            f = float(v)
        except (ValueError, OverflowError):
            raise ParameterError(f"{name} must be an integer 3..{MAX_PQ}, got {str(v)[:40]!r}") from None
        if not math.isfinite(f) or f != int(f) or not 3 <= f <= MAX_PQ:
            raise ParameterError(f"{name} must be an integer 3..{MAX_PQ}, got {str(v)[:40]}")
        out.append(int(f))
    p_, q_ = out
    kind = kind_of(p_, q_)
    if kind == EUCLIDEAN:
        raise ParameterError(
            f"{{{p_},{q_}}} tiles the Euclidean plane ((p-2)(q-2) = 4): see the archimedean family "
            "(4.4.4.4, 3.3.3.3.3.3, 6.6.6)")
    if want is not None and kind != want:
        need = "(p-2)(q-2) < 4: {3,3} {3,4} {4,3} {3,5} {5,3}" if want == SPHERE else "(p-2)(q-2) > 4, e.g. {7,3} {5,4}"
        raise ParameterError(f"{{{p_},{q_}}} is {kind}, not {want}: {want} tilings need {need}")
    return p_, q_


@dataclass(frozen=True)
class Geometry:
    """Curvature sign and the model's matrices: ``sign`` +1 on the sphere, −1 hyperbolic."""

    sign: int

    @property
    def name(self) -> str:
        return SPHERE if self.sign > 0 else HYPERBOLIC

    def cos(self, x: float | np.ndarray) -> float | np.ndarray:
        return np.cos(x) if self.sign > 0 else np.cosh(x)

    def sin(self, x: float | np.ndarray) -> float | np.ndarray:
        return np.sin(x) if self.sign > 0 else np.sinh(x)

    def acos(self, x: float | np.ndarray) -> float | np.ndarray:
        if self.sign > 0:
            return np.arccos(np.clip(x, -1.0, 1.0))
        return np.arccosh(np.maximum(x, 1.0))

    def form(self) -> np.ndarray:
        """The bilinear form J: <u, v> = uᵀ J v (identity on the sphere, diag(1, 1, −1) hyperbolic)."""
        return np.diag([1.0, 1.0, float(self.sign)])

    def inner(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """<u, v> over the last axis."""
        return u[..., 0] * v[..., 0] + u[..., 1] * v[..., 1] + self.sign * u[..., 2] * v[..., 2]

    def distance_from_pole(self, points: np.ndarray) -> np.ndarray:
        """Distance of model points (..., 3) from the pole (0, 0, 1)."""
        return self.acos(points[..., 2])

    def point(self, r: float | np.ndarray, theta: float | np.ndarray) -> np.ndarray:
        """The point at distance r from the pole in direction theta (..., 3)."""
        s = self.sin(r)
        return np.stack(np.broadcast_arrays(s * np.cos(theta), s * np.sin(theta), self.cos(r)), axis=-1)

    def rotation(self, theta: float) -> np.ndarray:
        """Rotation by theta about the pole."""
        c, s = math.cos(theta), math.sin(theta)
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    def translation(self, d: float) -> np.ndarray:
        """The motion along the x axis taking the pole to distance d (a rotation about the y
        axis on the sphere, a Lorentz boost in the hyperbolic plane)."""
        c, s = float(self.cos(d)), float(self.sin(d))
        return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-self.sign * s, 0.0, c]])


SPHERICAL_GEOMETRY = Geometry(+1)
HYPERBOLIC_GEOMETRY = Geometry(-1)


def geometry_of(p: int, q: int) -> Geometry:
    return SPHERICAL_GEOMETRY if kind_of(p, q) == SPHERE else HYPERBOLIC_GEOMETRY


@dataclass(frozen=True)
class RegularPolygon:
    """The central tile of {p, q}: radii, vertices on the model, the p edge half-turns."""

    p: int
    q: int

    @property
    def geometry(self) -> Geometry:
        return geometry_of(self.p, self.q)

    @property
    def circumradius(self) -> float:
        g = self.geometry
        return float(g.acos(1.0 / (math.tan(math.pi / self.p) * math.tan(math.pi / self.q))))

    @property
    def inradius(self) -> float:
        g = self.geometry
        return float(g.acos(math.cos(math.pi / self.q) / math.sin(math.pi / self.p)))

    @property
    def edge_length(self) -> float:
        g = self.geometry
        return 2.0 * float(g.acos(math.cos(math.pi / self.p) / math.sin(math.pi / self.q)))

    @property
    def area(self) -> float:
        """Gauss–Bonnet: |2π − p(π − 2π/q)| (the angle excess or defect of the p-gon)."""
        return abs(2 * math.pi - self.p * (math.pi - 2 * math.pi / self.q))

    def vertex_angles(self) -> np.ndarray:
        return 2 * np.pi * np.arange(self.p) / self.p

    def vertices(self) -> np.ndarray:
        """(p, 3) model points of the central tile, counter-clockwise seen from outside."""
        return self.geometry.point(self.circumradius, self.vertex_angles())

    def outline(self, per_edge: int = 1) -> np.ndarray:
        """(p * per_edge, 3) points along the boundary (:func:`sample_edges`)."""
        return sample_edges(self.geometry, self.vertices(), self.edge_length, per_edge)

    def half_turns(self) -> np.ndarray:
        """(p, 3, 3): H[j] turns the central tile by π about the midpoint of its edge j; the
        image is the neighbour across edge j, whose own edge j is the same edge reversed."""
        g = self.geometry
        out = np.empty((self.p, 3, 3))
        flip = np.diag([-1.0, -1.0, 1.0])
        t, t_inv = g.translation(self.inradius), g.translation(-self.inradius)
        for j in range(self.p):
            phi = (2 * j + 1) * math.pi / self.p
            r, r_inv = g.rotation(phi), g.rotation(-phi)
            out[j] = r @ t @ flip @ t_inv @ r_inv
        return out


def sample_edges(g: Geometry, v: np.ndarray, d: float, per_edge: int) -> np.ndarray:
    """(k * per_edge, 3): the closed polygon v (k, 3) with edges of length d, per edge its
    start and per_edge − 1 points along the geodesic (spaced evenly in the model's parameter,
    symmetric about the midpoint, so neighbours sample a shared edge at the same points)."""
    if per_edge <= 1:
        return v
    a, b = v, np.roll(v, -1, axis=0)
    s = np.linspace(0.0, 1.0, per_edge, endpoint=False)
    # slerp on the sphere / along the hyperbola: sin((1-s)d)/sin d a + sin(sd)/sin d b
    w0 = g.sin((1 - s) * d) / g.sin(d)
    w1 = g.sin(s * d) / g.sin(d)
    pts = w0[None, :, None] * a[:, None, :] + w1[None, :, None] * b[:, None, :]
    return pts.reshape(-1, 3)


# --------------------------------------------------------------------------- projections


def poincare(points: np.ndarray) -> np.ndarray:
    """Hyperboloid points (..., 3) to the Poincaré disc (..., 2): (x, y) / (1 + t)."""
    return points[..., :2] / (1.0 + points[..., 2:3])


def klein(points: np.ndarray) -> np.ndarray:
    """Hyperboloid points (..., 3) to the Klein disc (..., 2): (x, y) / t (geodesics are chords)."""
    return points[..., :2] / points[..., 2:3]


def from_poincare(xy: np.ndarray) -> np.ndarray:
    """Poincaré disc points (..., 2), |z| < 1, back to the hyperboloid (..., 3)."""
    r2 = np.sum(xy * xy, axis=-1, keepdims=True)
    return np.concatenate([2 * xy, 1 + r2], axis=-1) / (1 - r2)


def halfplane(points: np.ndarray) -> np.ndarray:
    """Hyperboloid points (..., 3) to the upper half-plane (..., 2) by the Cayley map
    w = i(1 + z)/(1 − z) of their Poincaré point z: the disc's centre goes to i, the rim to
    the real axis, geodesics to half-circles centred on it (or vertical lines)."""
    z = poincare(points)
    x, y = z[..., 0], z[..., 1]
    d = (1 - x) ** 2 + y * y
    return np.stack([-2 * y / d, (1 - x * x - y * y) / d], axis=-1)


def halfplane_to_poincare(uv: np.ndarray) -> np.ndarray:
    """Upper half-plane points (..., 2), v > 0, back to the Poincaré disc: z = (w − i)/(w + i)."""
    u, v = uv[..., 0], uv[..., 1]
    d = u * u + (v + 1) ** 2
    return np.stack([(u * u + v * v - 1) / d, -2 * u / d], axis=-1)


#: The hyperbolic drawing planes and their default views (x0, y0, x1, y1).
PLANE_VIEWS = {"poincare": (-1.0, -1.0, 1.0, 1.0), "klein": (-1.0, -1.0, 1.0, 1.0), "halfplane": (-3.0, 0.0, 3.0, 3.0)}


def project(points: np.ndarray, plane: str) -> np.ndarray:
    """Hyperboloid points (..., 3) to a drawing plane: 'poincare', 'klein' or 'halfplane'."""
    if plane == "klein":
        return klein(points)
    if plane == "halfplane":
        return halfplane(points)
    return poincare(points)


def poincare_to_klein(xy: np.ndarray) -> np.ndarray:
    r2 = np.sum(xy * xy, axis=-1, keepdims=True)
    return 2 * xy / (1 + r2)


def orthographic(points: np.ndarray) -> np.ndarray:
    """Sphere points (..., 3) seen from far along +z: (x, y)."""
    return points[..., :2]


def stereographic(points: np.ndarray) -> np.ndarray:
    """Sphere points (..., 3) projected from the south pole (0, 0, −1) onto the plane z = 0:
    (x, y) / (1 + z). Conformal; circles on the sphere go to circles (great circles through the
    south pole to lines through the origin), the north pole to the origin, the equator to the
    unit circle."""
    return points[..., :2] / (1.0 + points[..., 2:3])


def pole_rotation(transform: np.ndarray) -> np.ndarray:
    """A rotation of the sphere taking the centre of the tile placed by ``transform`` (the image
    of the north pole) to the south pole, so that :func:`stereographic` projects from it: the
    inverse of the tile's motion, then the half-turn about the x axis (a reflection placing the
    tile is followed by the mirror x -> −x, which fixes the poles, so the picture is not
    mirrored)."""
    m = np.diag([1.0, -1.0, -1.0]) @ np.asarray(transform, dtype=float).T
    if np.linalg.det(m) < 0:
        m = np.diag([-1.0, 1.0, 1.0]) @ m
    return m


def view_rotation(tilt_deg: float = 25.0, turn_deg: float = 20.0) -> np.ndarray:
    """A rotation of the sphere that shows it from above the equator (tilt about x, turn about z)."""
    a, b = math.radians(tilt_deg), math.radians(turn_deg)
    rx = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    rz = np.array([[math.cos(b), -math.sin(b), 0], [math.sin(b), math.cos(b), 0], [0, 0, 1]])
    return rx @ rz


def apply(transforms: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(n, 3, 3) maps applied to (k, 3) model points -> (n, k, 3), through one BLAS product."""
    return np.matmul(transforms, points.T).transpose(0, 2, 1)
