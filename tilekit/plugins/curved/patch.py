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
    drawing plane, 'poincare' (conformal, geodesics are arcs), 'klein' (geodesics are
    chords) or 'halfplane' (the upper half-plane, conformal, geodesics are half-circles); ``view`` the sphere's viewing rotation."""

    points: np.ndarray | None = None
    sign: int = -1
    view: np.ndarray | None = None
    plane: str = "poincare"
    #: (t, 3) indices into ``points`` triangulating a non-convex tile (its geodesic polygon's
    #: corners are all of ``points``); None: the tile is convex, fanned from its centre
    triangles: np.ndarray | None = None

    @classmethod
    def on_model(cls, points: np.ndarray, *, sign: int, name: str, corners: tuple[int, ...], plane: str = "poincare",
                 triangles: np.ndarray | None = None) -> ModelPrototile:
        """The prototile whose boundary on the model is ``points`` (centred at the pole): the
        outline is their drawing in the disc model's ``plane``; on the sphere, the gnomonic
        projection from the centre where the tile lies within the open hemisphere round it
        (geodesics are straight there, so the outline is simple exactly when the geodesic polygon
        through the points is, as shaped tiles are checked: the tilted view of the patch, ``view``,
        folds a tile that reaches past its horizon, and chords of an orthographic view can cross
        where the arcs do not), else the view straight down the pole."""
        view = model.view_rotation() if sign > 0 else None
        if sign < 0:
            flat = model.project(points, plane)
        elif (points[:, 2] > 1e-6).all():
            flat = points[:, :2] / points[:, 2:3]
        else:
            flat = model.orthographic(points)
        return cls(flat, name=name, points=points, sign=sign, view=view, plane=plane, corners=corners,
                   triangles=triangles)

    def project(self, pts: np.ndarray) -> np.ndarray:
        """Model points (..., 3) to the drawing plane (..., 2)."""
        if self.sign < 0:
            return model.project(pts, self.plane)
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
    the model, geometry projected (see the module). Tiles of several prototiles (a uniform
    tiling's faces) are handled prototile by prototile (:meth:`parts`)."""

    __slots__ = ()

    @property
    def proto(self) -> ModelPrototile:
        return _proto(self)

    def parts(self, index: np.ndarray | None = None) -> list[tuple[np.ndarray, np.ndarray, ModelPrototile]]:
        """Per prototile present: (positions among the selected tiles, their tile indices,
        the prototile); ``index`` selects tiles (None: all)."""
        tiles = np.arange(len(self)) if index is None else np.arange(len(self))[index]
        if len(self.prototiles) == 1:
            return [(np.arange(len(tiles)), tiles, self.proto)]
        kinds = self.prototile[tiles]
        out = []
        for j, proto in enumerate(self.prototiles):
            pos = np.flatnonzero(kinds == j)
            if len(pos):
                if not isinstance(proto, ModelPrototile) or proto.points is None:
                    raise GeometryError("a ModelPatch needs ModelPrototiles with model points")
                out.append((pos, tiles[pos], proto))
        return out

    def _one_part(self, index: Any) -> tuple[np.ndarray, ModelPrototile]:
        parts = self.parts(index)
        if len(parts) > 1 and len({len(pr.points) for _, _, pr in parts}) > 1:
            raise GeometryError("these tiles have different outlines: take them prototile by prototile (parts)")
        if not parts:
            t = self.transform[:0]
            return t, self.proto
        if len(parts) == 1:
            return self.transform[parts[0][1]], parts[0][2]
        # same point count, different prototiles: apply each its own points
        raise GeometryError("tiles of several prototiles: take them prototile by prototile (parts)")

    def model_points(self, index: np.ndarray | slice | None = None) -> np.ndarray:
        """(n, k, 3) boundary points of the tiles on the model (tiles of one outline)."""
        t, proto = self._one_part(index)
        return model.apply(t, proto.points)

    def model_vertices(self, index: np.ndarray | slice | None = None) -> np.ndarray:
        """(n, p, 3) polygon vertices on the model (tiles of one outline)."""
        t, proto = self._one_part(index)
        return model.apply(t, proto.points[list(proto.corners or range(len(proto.points)))])

    def vertex_lists(self) -> list[np.ndarray]:
        """Every tile's polygon vertices on the model, (k, 3) each, in tile order."""
        out: list[np.ndarray] = [np.zeros((0, 3))] * len(self)
        for _, idx, proto in self.parts():
            v = model.apply(self.transform[idx], proto.points[list(proto.corners or range(len(proto.points)))])
            for i, t in enumerate(idx):
                out[t] = v[i]
        return out

    def model_centres(self) -> np.ndarray:
        """(n, 3) tile centres on the model (the images of the pole)."""
        return self.transform[:, :, 2].copy()

    def _project(self, t: np.ndarray, proto: ModelPrototile, corners: bool) -> np.ndarray:
        pts = proto.points[list(proto.corners or ())] if corners else proto.points
        if proto.sign < 0 and proto.plane == "poincare" and len(t) >= _COMPILED:
            # measured start-up cost: numba's import (~0.3 s) only for large patches
            from tilekit.plugins.curved.kernels import poincare_points

            return poincare_points(np.ascontiguousarray(t), np.ascontiguousarray(pts))
        return proto.project(model.apply(t, pts))

    def projected(self, index: np.ndarray | slice | None = None, corners: bool = False) -> np.ndarray:
        """(n, k, 2) outlines in the drawing plane (``corners``: the polygon's vertices only),
        for tiles of one outline; a large hyperbolic patch through one compiled pass
        (kernels.poincare_points)."""
        t, proto = self._one_part(index)
        return self._project(t, proto, corners)

    # the core's geometry, projected ------------------------------------------------
    def groups(self):  # type: ignore[override]
        for _, idx, proto in self.parts():
            yield int(self.prototile[idx[0]]), idx, self._project(self.transform[idx], proto, False)

    def tile_bounds(self) -> np.ndarray:
        out = np.zeros((len(self), 4))
        for _, idx, pts in self.groups():
            out[idx] = np.concatenate([pts.min(axis=1), pts.max(axis=1)], axis=1)
        return out

    def centres(self) -> np.ndarray:
        return self.prototiles[0].project(self.model_centres())

    def _geometries_at(self, index: np.ndarray) -> np.ndarray:
        out = np.empty(len(index), dtype=object)
        for pos, idx, proto in self.parts(np.asarray(index)):
            out[pos] = shapely.polygons(self._project(self.transform[idx], proto, False))
        return out

    def weld_tolerance(self) -> float:
        """1e-9 of the disc's radius: the core's default scales with the matrices' linear
        part, which for a Lorentz map grows with the tile's distance, not with its size."""
        return 1e-9

    def orientations(self) -> tuple[np.ndarray, np.ndarray]:
        """Each tile's turn in the drawing plane (the direction from its centre to its first
        vertex, less its prototile's) and reflected (placed by a motion of determinant −1)."""
        angle = np.zeros(len(self))
        c = self.centres()
        for _, idx, proto in self.parts():
            v0 = self._project(self.transform[idx], proto, True)[:, 0]
            ref = proto.project(proto.points[0])
            angle[idx] = np.degrees(np.arctan2(v0[:, 1] - c[idx, 1], v0[:, 0] - c[idx, 0]) - np.arctan2(ref[1], ref[0]))
        return np.round(angle, 9) % 360.0, np.linalg.det(self.transform) < 0

    def subset(self, index: Any) -> ModelPatch:
        return ModelPatch(self.prototiles, self.prototile[index], self.transform[index],
                          self.colour[index], self.aspect[index])

    def transformed(self, m: np.ndarray) -> ModelPatch:
        """The patch moved by a motion of the model (an O(3) or O(2,1) matrix)."""
        return ModelPatch(self.prototiles, self.prototile, np.asarray(m) @ self.transform, self.colour, self.aspect)

    # validation where the geometry is exact ---------------------------------------
    def klein_triangles(self) -> Patch:
        """The hyperbolic tiles in the Klein model as a Euclidean :class:`Patch` of k
        triangles each (centre, vertex i, vertex i + 1), each placed by the affine map that
        is exact on its three corners; ``colour`` holds the tile index."""
        if self.prototiles[0].sign > 0:
            raise GeometryError("the Klein model is for hyperbolic patches")
        mats, owners = [], []
        for _, idx, proto in self.parts():
            if proto.triangles is not None:  # a non-convex tile: its own triangulation
                v = model.klein(model.apply(self.transform[idx], proto.points))  # (n, k, 2)
                tri = proto.triangles
                n, p = len(v), len(tri)
                a = v[:, tri[:, 0]].reshape(-1, 2)
                b = v[:, tri[:, 1]].reshape(-1, 2)
                d = v[:, tri[:, 2]].reshape(-1, 2)
            else:
                corners = proto.points[list(proto.corners or range(len(proto.points)))]
                v = model.klein(model.apply(self.transform[idx], corners))   # (n, p, 2)
                c = model.klein(self.transform[idx][:, :, 2])[:, None, :]     # (n, 1, 2)
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
            mats.append(m)
            owners.append(np.repeat(idx, p))
        m = np.concatenate(mats) if mats else np.zeros((0, 3, 3))
        ref = Prototile(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]), name="fan")
        return Patch([ref], np.zeros(len(m), dtype=np.int64), m,
                     colour=np.concatenate(owners) if owners else np.zeros(0, dtype=np.int64))

    def validate(self, region: Any = None, tolerance: float = AREA_TOL) -> ValidationReport:
        """No overlap, and ``region`` (in the drawing plane's disc) covered: for a
        hyperbolic patch the core's check on :meth:`klein_triangles`, a Poincaré region carried
        to the Klein model point by point along its densified boundary; for a spherical one
        :func:`sphere_report` (``region`` None: the whole sphere)."""
        if self.prototiles[0].sign > 0:
            if any(getattr(pr, "triangles", None) is not None for pr in self.prototiles):
                return chain_report(self, tolerance)
            return sphere_report(self, tolerance)
        tri = self.klein_triangles()
        reg = None
        if region is not None:
            poly = as_region(region)
            if not isinstance(poly, shapely.Polygon):
                poly = poly.convex_hull
            ring = np.asarray(shapely.segmentize(poly, 0.01).exterior.coords)
            if self.prototiles[0].plane == "halfplane":
                if (ring[:, 1] <= 0).any():
                    raise GeometryError("a hyperbolic patch's region must lie in the upper half-plane (y > 0)")
                ring = model.halfplane_to_poincare(ring)
                poly = shapely.Polygon(ring)
            if (np.hypot(ring[:, 0], ring[:, 1]) >= 1).any():
                raise GeometryError("a hyperbolic patch's region must lie inside the unit disc")
            reg = poly if self.prototiles[0].plane == "klein" else shapely.Polygon(model.poincare_to_klein(ring))
        report = tri.validate(reg, tolerance)
        owner = tri.colour
        fan = report.overlaps
        report.overlaps = sorted({(int(owner[i]), int(owner[j]), a) for i, j, a in fan if owner[i] != owner[j]})
        # a tile is invalid when it is (its fan triangles are not finite, or their areas sum to
        # next to nothing): a sliver triangle of a good tile — a nearly straight stretch of a
        # deformed edge, squeezed towards the rim — is below the core's per-triangle tolerance
        # while its tile is not
        det = np.abs(np.linalg.det(tri.transform)) / 2
        finite = np.isfinite(det) & np.isfinite(tri.transform).all(axis=(1, 2))
        tile_area = np.bincount(owner[finite], weights=det[finite], minlength=len(self))
        tiny = tile_area <= tolerance * float(np.median(tile_area)) if len(self) else np.zeros(0, dtype=bool)
        report.invalid_tiles = sorted({int(t) for t in owner[~finite]} | {int(t) for t in np.flatnonzero(tiny)})
        report.tiles = len(self)
        return report


def sphere_report(patch: ModelPatch, tolerance: float = AREA_TOL) -> ValidationReport:
    """A spherical patch checked on the sphere: faces are convex spherical polygons (those placed
    by a reflection read backwards, so all run counter-clockwise), so two
    have disjoint interiors when a great circle through an edge of one leaves every vertex
    of the other on its far side (or on it), or a great circle through a vertex of each
    leaves them on opposite sides; the uncovered area is 4π minus the faces' areas
    (Girard: angle sum minus (p − 2)π, from the actual vertices)."""
    faces = patch.vertex_lists()  # (k, 3) each
    # a face placed by a reflection (a Laves tile's mirror image) runs clockwise: read it
    # backwards, so that every edge plane's normal below points into its face
    for i in np.flatnonzero(np.linalg.det(patch.transform) < 0):
        faces[i] = faces[i][::-1]
    n = len(faces)
    big = max((len(f) for f in faces), default=3)
    report = ValidationReport(tiles=n)
    # faces padded to the largest: extra vertices repeat vertex 0 (no change to "all on the
    # far side"), extra edges are marked and never separate
    v = np.array([np.concatenate([f, np.repeat(f[:1], big - len(f), axis=0)]) for f in faces]).reshape(n, big, 3)
    real = np.arange(big)[None, :] < np.array([len(f) for f in faces])[:, None]
    normal = np.zeros((n, big, 3))
    for i, f in enumerate(faces):
        e = np.cross(f, np.roll(f, -1, axis=0))  # inward normals of the CCW face's edge planes
        normal[i, :len(f)] = e / np.linalg.norm(e, axis=-1, keepdims=True)
    slack = 1e-9
    # side[i, e, j, k] = normal of face i, edge e, dotted with vertex k of face j
    side = np.einsum("iec,jkc->iejk", normal, v)
    separated = ((side <= slack).all(axis=3) & real[:, :, None]).any(axis=1)  # some edge of i separates j
    separated |= separated.T
    np.fill_diagonal(separated, True)
    # faces far apart (nearly antipodal) straddle every great circle through an edge of the
    # other: as in the separating-axis theorem for two convex cones, try the planes through
    # a vertex of each as well
    for i, j in zip(*np.nonzero(~separated)):
        if i < j:
            a, b = faces[i], faces[j]
            nrm = np.cross(a[:, None, :], b[None, :, :]).reshape(-1, 3)
            nrm = nrm[np.linalg.norm(nrm, axis=1) > 1e-12]
            sa, sb = a @ nrm.T, b @ nrm.T  # (k, m): each plane's side of every vertex
            ok = ((sa >= -slack).all(axis=0) & (sb <= slack).all(axis=0)) | \
                 ((sa <= slack).all(axis=0) & (sb >= -slack).all(axis=0))
            if ok.any():
                separated[i, j] = separated[j, i] = True
    areas = np.array([_spherical_area(f) for f in faces])
    report.overlaps = [(int(i), int(j), float("nan")) for i, j in zip(*np.nonzero(~separated)) if i < j]
    report.region_area = 4 * math.pi
    report.area_tolerance = tolerance * float(np.median(areas))
    report.uncovered_area = max(0.0, 4 * math.pi - float(areas.sum()))
    return report


def chain_report(patch: ModelPatch, tolerance: float = AREA_TOL) -> ValidationReport:
    """A spherical patch of non-convex tiles (each a simple geodesic polygon, counter-clockwise,
    checked when its tiling is made) checked as a 2-chain: every directed boundary segment of
    every tile must be met by the same segment reversed in exactly one other tile (points welded
    at 1e-9), so the tiles' boundaries cancel and the tiles cover the sphere a constant number
    d of times; the areas (each tile's triangulation, Girard's theorem per triangle) sum to
    d·4π, so d = 1 — every point is covered exactly once — exactly when they sum to 4π. Tiles
    with a segment matched by no other tile, or twice, are ``invalid_tiles``."""
    n = len(patch)
    report = ValidationReport(tiles=n)
    report.region_area = 4 * math.pi
    if not n:
        report.uncovered_area = 4 * math.pi
        return report
    total = 0.0
    owners, starts, ends = [], [], []
    for _, idx, proto in patch.parts():
        pts = model.apply(patch.transform[idx], proto.points)        # (m, k, 3)
        mirrored = np.linalg.det(patch.transform[idx]) < 0            # a reflected tile runs clockwise
        pts[mirrored] = pts[mirrored, ::-1]
        tri = proto.triangles if proto.triangles is not None else np.array(
            [(0, i, i + 1) for i in range(1, len(proto.points) - 1)])
        area = sum(_spherical_area(proto.points[list(t)]) for t in tri)
        total += area * len(idx)
        m, k = pts.shape[:2]
        starts.append(pts.reshape(-1, 3))
        ends.append(np.roll(pts, -1, axis=1).reshape(-1, 3))
        owners.append(np.repeat(idx, k))
    a, b, owner = np.concatenate(starts), np.concatenate(ends), np.concatenate(owners)
    _, ids = np.unique(np.round(np.concatenate([a, b]), 9), axis=0, return_inverse=True)
    ids = ids.reshape(-1)
    ia, ib = ids[: len(a)], ids[len(a):]
    big = int(ids.max()) + 1
    forward = ia.astype(np.int64) * big + ib
    backward = ib.astype(np.int64) * big + ia
    keys, counts = np.unique(forward, return_counts=True)
    pos = np.clip(np.searchsorted(keys, backward), 0, len(keys) - 1)
    matched = (keys[pos] == backward) & (counts[pos] == 1) & (counts[np.searchsorted(keys, forward)] == 1)
    report.invalid_tiles = sorted({int(t) for t in owner[~matched]})
    report.area_tolerance = tolerance * total / n
    report.uncovered_area = abs(4 * math.pi - total)
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
    g = model.geometry_of(3, 7) if patch.prototiles[0].sign < 0 else model.geometry_of(3, 3)
    all_angles, all_keys = [], []
    for _, idx, proto in patch.parts():
        v = model.apply(patch.transform[idx], proto.points[list(proto.corners or range(len(proto.points)))])
        a, c = np.roll(v, 1, axis=1), np.roll(v, -1, axis=1)
        ab, cb = g.inner(a, v)[..., None], g.inner(c, v)[..., None]
        s = float(g.sign)
        # tangent at b towards a: a − s<a,b> b (the component orthogonal to b in the model's form)
        t1 = a - s * ab * v
        t2 = c - s * cb * v
        cos = g.inner(t1, t2) / np.sqrt(g.inner(t1, t1) * g.inner(t2, t2))
        all_angles.append(np.arccos(np.clip(cos, -1, 1)).reshape(-1))
        all_keys.append(np.round(v.reshape(-1, 3), decimals))
    angles, keys = np.concatenate(all_angles), np.concatenate(all_keys)
    _, inv, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    sums = np.bincount(inv.reshape(-1), weights=angles)
    return sums, counts


def concat(patches: Sequence[ModelPatch]) -> ModelPatch:
    """Join ModelPatches with the same prototile."""
    return ModelPatch.concat(patches)  # type: ignore[return-value]
