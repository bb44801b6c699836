"""A Patch of a curved tiling: one 3x3 matrix per tile as for the plane, but the matrices are
rotations of the sphere (O(3)) or Lorentz maps of the hyperboloid (O(2,1)), and the drawing
plane is a projection (Poincaré disc; the sphere seen orthographically).

``ModelPrototile`` carries the central tile's points on the model; ``ModelPatch`` keeps the
core's columns and overrides only where the core applies a matrix to 2D points (outlines,
bounds, centres, shapely polygons), so exports, clipping and ``tilekit render``'s streamed
output work on the projected outlines. ``validate`` checks the geometry where it is exact:
a hyperbolic patch in the Klein model, where geodesics are straight, each tile cut into p
triangles whose affine maps are exact (three points fix one), through the core's
``Patch.validate``; a spherical patch on the sphere itself (every pair of faces separated
by a great circle through an edge of one, and the face areas summing to 4π).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import shapely

from tilekit.errors import GeometryError
from tilekit.geometry import AREA_TOL, as_region
from tilekit.plugins.curved import model
from tilekit.tiling import Patch, Prototile, ValidationReport


@dataclass(frozen=True, eq=False)
class ModelPrototile(Prototile):
    """A prototile whose ``outline`` is the projected central tile and ``points`` the same
    boundary on the model (k, 3); ``corners`` are the polygon's vertices among them;
    ``sign`` is +1 for the sphere, −1 for the hyperbolic plane; ``plane`` the hyperbolic
    drawing plane, 'poincare' (conformal, geodesics are arcs) or 'klein' (geodesics are
    chords); ``view`` the sphere's viewing rotation."""

    points: np.ndarray | None = None
    sign: int = -1
    view: np.ndarray | None = None
    plane: str = "poincare"

    def project(self, pts: np.ndarray) -> np.ndarray:
        """Model points (..., 3) to the drawing plane (..., 2)."""
        if self.sign < 0:
            return model.klein(pts) if self.plane == "klein" else model.poincare(pts)
        return model.orthographic(pts @ self.view.T if self.view is not None else pts)


def _proto(patch: Patch) -> ModelPrototile:
    proto = patch.prototiles[0]
    if not isinstance(proto, ModelPrototile) or proto.points is None:
        raise GeometryError("a ModelPatch needs a ModelPrototile with model points")
    return proto


#: Tiles from which the Poincaré outlines come from the compiled kernel (below it NumPy's
#: matmul is as fast and spares numba's import).
_COMPILED = 20_000


class ModelPatch(Patch):
    """Tiles of a spherical or hyperbolic tiling: columns as in :class:`Patch`, transforms on
    the model, geometry projected (see the module)."""

    __slots__ = ()

    @property
    def proto(self) -> ModelPrototile:
        return _proto(self)

    def model_points(self, index: np.ndarray | slice | None = None) -> np.ndarray:
        """(n, k, 3) boundary points of the tiles on the model."""
        t = self.transform if index is None else self.transform[index]
        return model.apply(t, self.proto.points)

    def model_vertices(self, index: np.ndarray | slice | None = None) -> np.ndarray:
        """(n, p, 3) polygon vertices on the model."""
        proto = self.proto
        t = self.transform if index is None else self.transform[index]
        return model.apply(t, proto.points[list(proto.corners or range(len(proto.points)))])

    def model_centres(self) -> np.ndarray:
        """(n, 3) tile centres on the model (the images of the pole)."""
        return self.transform[:, :, 2].copy()

    def projected(self, index: np.ndarray | slice | None = None, corners: bool = False) -> np.ndarray:
        """(n, k, 2) outlines in the drawing plane (``corners``: the polygon's vertices only);
        a large hyperbolic patch through one compiled pass (kernels.poincare_points)."""
        proto = self.proto
        t = self.transform if index is None else self.transform[index]
        pts = proto.points[list(proto.corners or ())] if corners else proto.points
        if proto.sign < 0 and proto.plane == "poincare" and len(t) >= _COMPILED:
            # measured start-up cost: numba's import (~0.3 s) only for large patches
            from tilekit.plugins.curved.kernels import poincare_points

            return poincare_points(np.ascontiguousarray(t), np.ascontiguousarray(pts))
        return proto.project(model.apply(t, pts))

    # the core's geometry, projected ------------------------------------------------
    def groups(self):  # type: ignore[override]
        if len(self):
            yield 0, np.arange(len(self)), self.projected()

    def tile_bounds(self) -> np.ndarray:
        if not len(self):
            return np.zeros((0, 4))
        pts = self.projected()
        return np.concatenate([pts.min(axis=1), pts.max(axis=1)], axis=1)

    def centres(self) -> np.ndarray:
        return self.proto.project(self.model_centres())

    def _geometries_at(self, index: np.ndarray) -> np.ndarray:
        if not len(index):
            return np.empty(0, dtype=object)
        return shapely.polygons(self.projected(index))

    def weld_tolerance(self) -> float:
        """1e-9 of the disc's radius: the core's default scales with the matrices' linear
        part, which for a Lorentz map grows with the tile's distance, not with its size."""
        return 1e-9

    def orientations(self) -> tuple[np.ndarray, np.ndarray]:
        """Each tile's turn in the drawing plane (the direction from its centre to its first
        vertex, less the central tile's) and reflected (never: the tiles are placed by
        products of half-turns)."""
        proto = self.proto
        v0 = self.projected(corners=True)[:, 0]
        c = self.centres()
        ref = proto.project(proto.points[0])
        angle = np.degrees(np.arctan2(v0[:, 1] - c[:, 1], v0[:, 0] - c[:, 0]) - np.arctan2(ref[1], ref[0]))
        return np.round(angle, 9) % 360.0, np.zeros(len(self), dtype=bool)

    def subset(self, index: Any) -> ModelPatch:
        return ModelPatch(self.prototiles, self.prototile[index], self.transform[index],
                          self.colour[index], self.aspect[index])

    def transformed(self, m: np.ndarray) -> ModelPatch:
        """The patch moved by a motion of the model (an O(3) or O(2,1) matrix)."""
        return ModelPatch(self.prototiles, self.prototile, np.asarray(m) @ self.transform, self.colour, self.aspect)

    # validation where the geometry is exact ---------------------------------------
    def klein_triangles(self) -> Patch:
        """The hyperbolic tiles in the Klein model as a Euclidean :class:`Patch` of p
        triangles each (centre, vertex i, vertex i + 1), each placed by the affine map that
        is exact on its three corners; ``colour`` holds the tile index."""
        if self.proto.sign > 0:
            raise GeometryError("the Klein model is for hyperbolic patches")
        v = model.klein(self.model_vertices())            # (n, p, 2)
        c = model.klein(self.model_centres())[:, None, :]  # (n, 1, 2)
        n, p = v.shape[:2]
        a = np.broadcast_to(c, v.shape).reshape(-1, 2)
        b = v.reshape(-1, 2)
        d = np.roll(v, -1, axis=1).reshape(-1, 2)
        # the reference triangle (0,0), (1,0), (0,1) mapped to (a, b, d)
        m = np.zeros((n * p, 3, 3))
        m[:, :2, 0] = b - a
        m[:, :2, 1] = d - a
        m[:, :2, 2] = a
        m[:, 2, 2] = 1.0
        ref = Prototile(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]), name="fan")
        return Patch([ref], np.zeros(n * p, dtype=np.int64), m, colour=np.repeat(np.arange(n), p))

    def validate(self, region: Any = None, tolerance: float = AREA_TOL) -> ValidationReport:
        """No overlap, and ``region`` (in the drawing plane's disc) covered: for a
        hyperbolic patch the core's check on :meth:`klein_triangles`, a Poincaré region carried
        to the Klein model point by point along its densified boundary; for a spherical one
        :func:`sphere_report` (``region`` None: the whole sphere)."""
        if self.proto.sign > 0:
            return sphere_report(self, tolerance)
        tri = self.klein_triangles()
        reg = None
        if region is not None:
            poly = as_region(region)
            if not isinstance(poly, shapely.Polygon):
                poly = poly.convex_hull
            ring = np.asarray(shapely.segmentize(poly, 0.01).exterior.coords)
            if (np.hypot(ring[:, 0], ring[:, 1]) >= 1).any():
                raise GeometryError("a hyperbolic patch's region must lie inside the unit disc")
            reg = poly if self.proto.plane == "klein" else shapely.Polygon(model.poincare_to_klein(ring))
        report = tri.validate(reg, tolerance)
        p = len(self.proto.corners or ())
        fan = report.overlaps
        report.overlaps = sorted({(i // p, j // p, a) for i, j, a in fan})
        report.invalid_tiles = sorted({i // p for i in report.invalid_tiles})
        report.tiles = len(self)
        return report


def sphere_report(patch: ModelPatch, tolerance: float = AREA_TOL) -> ValidationReport:
    """A spherical patch checked on the sphere: faces are convex spherical polygons, so two
    have disjoint interiors when a great circle through an edge of one leaves every vertex
    of the other on its far side (or on it); the uncovered area is 4π minus the faces' areas
    (Girard: angle sum minus (p − 2)π, from the actual vertices)."""
    v = patch.model_vertices()  # (n, p, 3)
    n, p = v.shape[:2]
    report = ValidationReport(tiles=n)
    nxt = np.roll(v, -1, axis=1)
    normal = np.cross(v, nxt)  # inward normals of the CCW faces' edge planes
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    slack = 1e-9
    # side[i, e, j, k] = normal of face i, edge e, dotted with vertex k of face j
    side = np.einsum("iec,jkc->iejk", normal, v)
    separated = (side <= slack).all(axis=3).any(axis=1)  # (i, j): some edge of i separates j
    separated |= separated.T
    np.fill_diagonal(separated, True)
    areas = np.array([_spherical_area(v[i]) for i in range(n)])
    report.overlaps = [(int(i), int(j), float("nan")) for i, j in zip(*np.nonzero(~separated)) if i < j]
    report.region_area = 4 * math.pi
    report.area_tolerance = tolerance * float(np.median(areas))
    report.uncovered_area = max(0.0, 4 * math.pi - float(areas.sum()))
    return report


def _spherical_area(vertices: np.ndarray) -> float:
    """Girard's theorem for a convex spherical polygon (k, 3): angle sum − (k − 2)π."""
    k = len(vertices)
    total = 0.0
    for i in range(k):
        a, b, c = vertices[i - 1], vertices[i], vertices[(i + 1) % k]
        t1 = a - np.dot(a, b) * b
        t2 = c - np.dot(c, b) * b
        total += math.acos(max(-1.0, min(1.0, float(np.dot(t1, t2) / (np.linalg.norm(t1) * np.linalg.norm(t2))))))
    return total - (k - 2) * math.pi


def vertex_angle_sums(patch: ModelPatch, decimals: int = 9) -> tuple[np.ndarray, np.ndarray]:
    """For the patch's vertices (welded by their rounded model coordinates): the sum of the
    tiles' interior angles at each and how many tiles meet there, measured from the
    actual vertex coordinates (the angle between the tangent directions of the two edges)."""
    g = model.geometry_of(3, 7) if patch.proto.sign < 0 else model.geometry_of(3, 3)
    v = patch.model_vertices()
    a, c = np.roll(v, 1, axis=1), np.roll(v, -1, axis=1)
    ab, cb = g.inner(a, v)[..., None], g.inner(c, v)[..., None]
    s = float(g.sign)
    # tangent at b towards a: a − s<a,b> b (the component orthogonal to b in the model's form)
    t1 = a - s * ab * v
    t2 = c - s * cb * v
    cos = g.inner(t1, t2) / np.sqrt(g.inner(t1, t1) * g.inner(t2, t2))
    angles = np.arccos(np.clip(cos, -1, 1)).reshape(-1)
    keys = np.round(v.reshape(-1, 3), decimals)
    _, inv, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    sums = np.bincount(inv.reshape(-1), weights=angles)
    return sums, counts


def concat(patches: Sequence[ModelPatch]) -> ModelPatch:
    """Join ModelPatches with the same prototile."""
    return ModelPatch.concat(patches)  # type: ignore[return-value]
