"""2D affine maps as 3x3 float64 arrays (batched as (n, 3, 3)), polygon helpers, tolerances.

``Affine`` is a namespace of constructors and operations on plain NumPy arrays, so maps
compose with ``@`` and batches stay arrays. The tolerance constants live here, once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import shapely
from shapely.geometry.base import BaseGeometry

from tilekit.errors import GeometryError, ParseError
from tilekit.limits import check_coordinates

# re-exported: their home is tilekit.polygon
from tilekit.polygon import centroid as centroid
from tilekit.polygon import regular_polygon as regular_polygon
from tilekit.polygon import signed_area as signed_area
from tilekit.schema import shown

#: Absolute tolerance for coordinates that should coincide (tilings are drawn at unit scale).
EPS = 1e-9
#: Tolerance for comparing points produced by chains of transforms.
POINT_TOL = 1e-6
#: Relative area tolerance: overlaps and gaps smaller than this fraction of a tile are noise.
AREA_TOL = 1e-6


@dataclass(frozen=True)
class Isometry:
    """The classification of a rigid motion (§3.1).

    ``kind`` is one of identity, translation, rotation, reflection, glide reflection.
    ``angle`` is the rotation angle (rotations) or the mirror axis direction (reflections
    and glides), in radians; ``centre`` is the rotation centre or a point on the axis;
    ``vector`` is the translation vector (translations) or the glide vector (glides).
    """

    kind: str
    angle: float = 0.0
    centre: tuple[float, float] = (0.0, 0.0)
    vector: tuple[float, float] = (0.0, 0.0)

    @property
    def order(self) -> int | None:
        """The order of a rotation through 2π/n (None when not such a rotation)."""
        if self.kind != "rotation":
            return None
        turns = (2 * math.pi) / abs(self.angle)
        n = round(turns)
        return n if abs(turns - n) < 1e-6 else None


class Affine:
    """Constructors and operations for 2D affine maps stored as 3x3 homogeneous arrays."""

    @staticmethod
    def identity() -> np.ndarray:
        return np.eye(3)

    @staticmethod
    def from_rows(a: float, b: float, c: float, d: float, e: float, f: float) -> np.ndarray:
        """The map (x, y) -> (a x + b y + c, d x + e y + f)."""
        return np.array([[a, b, c], [d, e, f], [0.0, 0.0, 1.0]])

    @staticmethod
    def translation(dx: float, dy: float | None = None) -> np.ndarray:
        if dy is None:
            dx, dy = dx  # type: ignore[misc]
        return np.array([[1.0, 0.0, dx], [0.0, 1.0, dy], [0.0, 0.0, 1.0]])

    @staticmethod
    def rotation(theta: float, centre: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
        c, s = math.cos(theta), math.sin(theta)
        m = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        return Affine._about(m, centre)

    @staticmethod
    def reflection(angle: float, point: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
        """Reflection in the line through ``point`` with direction ``angle``."""
        c, s = math.cos(2 * angle), math.sin(2 * angle)
        m = np.array([[c, s, 0.0], [s, -c, 0.0], [0.0, 0.0, 1.0]])
        return Affine._about(m, point)

    @staticmethod
    def scaling(sx: float, sy: float | None = None) -> np.ndarray:
        sy = sx if sy is None else sy
        return np.diag([sx, sy, 1.0])

    @staticmethod
    def half_turn(centre: tuple[float, float]) -> np.ndarray:
        return Affine.rotation(math.pi, centre)

    @staticmethod
    def _about(m: np.ndarray, centre: tuple[float, float]) -> np.ndarray:
        cx, cy = centre
        if cx == 0.0 and cy == 0.0:
            return m
        return Affine.translation(cx, cy) @ m @ Affine.translation(-cx, -cy)

    @staticmethod
    def segment_map(p0, p1, q0=(0.0, 0.0), q1=(1.0, 0.0)) -> np.ndarray:
        """The direct similarity taking segment q0-q1 onto p0-p1 (e.g. a unit edge shape onto a tile edge)."""
        p0, p1, q0, q1 = (np.asarray(v, dtype=float) for v in (p0, p1, q0, q1))
        dq = q1 - q0
        dp = p1 - p0
        lq = dq @ dq
        if lq < EPS * EPS:
            raise GeometryError("segment_map: source segment has zero length")
        # complex-number form: z -> a z + b with a = dp / dq
        a = complex(*dp) / complex(*dq)
        m = np.array([[a.real, -a.imag, 0.0], [a.imag, a.real, 0.0], [0.0, 0.0, 1.0]])
        t = p0 - m[:2, :2] @ q0
        m[:2, 2] = t
        return m

    @staticmethod
    def inverse(m: np.ndarray) -> np.ndarray:
        """Inverse of one map or a batch (n, 3, 3), computed in closed form."""
        m = np.asarray(m, dtype=float)
        a, b, c = m[..., 0, 0], m[..., 0, 1], m[..., 0, 2]
        d, e, f = m[..., 1, 0], m[..., 1, 1], m[..., 1, 2]
        det = a * e - b * d
        if np.any(np.abs(det) < 1e-14):
            raise GeometryError("affine map is singular and has no inverse")
        out = np.zeros_like(m)
        out[..., 0, 0] = e / det
        out[..., 0, 1] = -b / det
        out[..., 1, 0] = -d / det
        out[..., 1, 1] = a / det
        out[..., 0, 2] = (b * f - c * e) / det
        out[..., 1, 2] = (c * d - a * f) / det
        out[..., 2, 2] = 1.0
        return out

    @staticmethod
    def apply(m: np.ndarray, points: np.ndarray) -> np.ndarray:
        """Apply one map (3,3) to points (..., 2), or a batch (n,3,3) to points (k,2) -> (n,k,2)."""
        m = np.asarray(m, dtype=float)
        pts = np.asarray(points, dtype=float)
        if m.ndim == 2:
            return pts @ m[:2, :2].T + m[:2, 2]
        # batched: (n,3,3) x (k,2) -> (n,k,2)
        # batched (n,2,2) @ (2,k) through BLAS, then a transposed view (n,k,2): an order of
        # magnitude faster than the equivalent einsum on 10^5 outlines
        out = np.matmul(m[:, :2, :2], pts.T)
        out += m[:, :2, 2, None]
        return out.transpose(0, 2, 1)

    @staticmethod
    def determinant(m: np.ndarray) -> np.ndarray | float:
        m = np.asarray(m, dtype=float)
        return m[..., 0, 0] * m[..., 1, 1] - m[..., 0, 1] * m[..., 1, 0]

    @staticmethod
    def is_isometry(m: np.ndarray, tol: float = POINT_TOL) -> bool:
        lin = np.asarray(m, dtype=float)[:2, :2]
        return bool(np.allclose(lin.T @ lin, np.eye(2), atol=tol))

    @staticmethod
    def similarity_scale(m: np.ndarray, tol: float = POINT_TOL) -> float | None:
        """The scale factor if ``m`` is a similarity, else None."""
        lin = np.asarray(m, dtype=float)[:2, :2]
        g = lin.T @ lin
        s2 = (g[0, 0] + g[1, 1]) / 2
        if s2 <= 0 or not np.allclose(g, s2 * np.eye(2), atol=tol * max(1.0, s2)):
            return None
        return math.sqrt(s2)

    @staticmethod
    def is_close(m1: np.ndarray, m2: np.ndarray, tol: float = POINT_TOL) -> bool:
        return bool(np.allclose(m1, m2, atol=tol))

    @staticmethod
    def classify(m: np.ndarray, tol: float = POINT_TOL) -> Isometry:
        """Classify a rigid motion as identity, translation, rotation, reflection or glide."""
        m = np.asarray(m, dtype=float)
        if not Affine.is_isometry(m, tol):
            raise GeometryError("classify: the map is not an isometry")
        lin = m[:2, :2]
        t = m[:2, 2]
        det = lin[0, 0] * lin[1, 1] - lin[0, 1] * lin[1, 0]
        if det > 0:
            theta = math.atan2(lin[1, 0], lin[0, 0])
            if abs(theta) < tol:
                if np.hypot(*t) < tol:
                    return Isometry("identity")
                return Isometry("translation", vector=(float(t[0]), float(t[1])))
            # fixed point c: (I - R) c = t
            c = np.linalg.solve(np.eye(2) - lin, t)
            return Isometry("rotation", angle=theta, centre=(float(c[0]), float(c[1])))
        # reflection part: lin = reflection across direction phi
        phi = 0.5 * math.atan2(lin[1, 0], lin[0, 0])
        u = np.array([math.cos(phi), math.sin(phi)])
        glide = float(t @ u)
        perp = t - glide * u
        point = perp / 2.0  # the axis passes through half the perpendicular offset
        phi = phi % math.pi
        if abs(glide) < tol:
            return Isometry("reflection", angle=phi, centre=(float(point[0]), float(point[1])))
        gv = glide * u
        return Isometry(
            "glide reflection",
            angle=phi,
            centre=(float(point[0]), float(point[1])),
            vector=(float(gv[0]), float(gv[1])),
        )


def translations_into(transforms: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """Batch: for each translation vector t (k,2) and transform M (m,3,3), the map T(t) @ M.

    Returns shape (k*m, 3, 3), ordered with the m transforms varying fastest.
    """
    transforms = np.asarray(transforms, dtype=float)
    vectors = np.asarray(vectors, dtype=float).reshape(-1, 2)
    out = np.broadcast_to(transforms, (len(vectors),) + transforms.shape).copy()
    out[:, :, :2, 2] += vectors[:, None, :]
    return out.reshape(-1, 3, 3)


def as_region(region: Any) -> BaseGeometry:
    """A shapely geometry from a geometry, a (x0, y0, x1, y1) tuple, or the text 'x0,y0,x1,y1'."""
    if isinstance(region, BaseGeometry):
        if region.is_empty or region.area <= 0:
            raise GeometryError("region is empty or has no area")
        check_coordinates(region.bounds)
        return region
    if isinstance(region, str):
        parts = region.replace(" ", "").split(",")
        try:
            vals = [float(p) for p in parts]
        except ValueError:
            raise ParseError(f"region {shown(region)} is not 'x0,y0,x1,y1' (four numbers)") from None
        region = vals
    try:
        x0, y0, x1, y1 = (float(v) for v in region)
    except (TypeError, ValueError):
        raise ParseError(f"region {shown(region)} is not (x0, y0, x1, y1)") from None
    except OverflowError:  # an integer too large for a float
        raise GeometryError(f"region {shown(region)} has a coordinate too large to be a number") from None
    if not all(math.isfinite(v) for v in (x0, y0, x1, y1)):
        raise GeometryError(f"region {shown(region)} has a non-finite coordinate")
    if x1 <= x0 or y1 <= y0:
        raise GeometryError(f"region {shown(region)} is empty: need x0 < x1 and y0 < y1")
    check_coordinates((x0, y0, x1, y1))
    return shapely.box(x0, y0, x1, y1)


#: Coordinates closer to zero than this are float noise (e.g. -4e-16 in a lattice vector).
NOISE = 1e-12


def snap_noise(a: np.ndarray, zero: float = NOISE, decimals: int | None = None) -> np.ndarray:
    """A copy of ``a`` with float noise removed so that shapely (GEOS) overlays behave:
    entries with ``|x| < zero`` become exactly 0.0, and with ``decimals`` every entry is also
    rounded to that many decimals. Tiles that share a vertex on an axis, or an edge, then
    share its coordinates bit for bit; GEOS's overlay of nearly-but-not-exactly coincident
    edges is not robust (``Patch.validate`` uses a snap-rounded overlay for the same reason).

    >>> snap_noise(np.array([-4e-16, 0.5, 1.0 + 1e-14]), decimals=12).tolist()
    [0.0, 0.5, 1.0]
    """
    out = np.array(a, dtype=float)
    out[np.abs(out) < zero] = 0.0
    if decimals is not None:
        out = np.round(out, decimals)
    return out
