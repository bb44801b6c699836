"""Polygons as arrays: areas, centroids, interior angles, ear clipping, an inscribed disc,
regular polygons, and the symmetries and congruences of outlines.

Array-first in the manner of Shapely 2's vectorised functions: ``signed_area``, ``area``,
``centroid`` and ``interior_angles`` take one outline ``(k, 2)`` or a stack ``(n, k, 2)``
and answer per polygon. No tilekit import but the errors, so every layer may use it.

>>> square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
>>> signed_area(square), signed_area(square[::-1])
(1.0, -1.0)
>>> signed_area(np.stack([square, 2 * square])).tolist()
[1.0, 4.0]
>>> centroid(square).tolist()
[0.5, 0.5]
>>> np.degrees(interior_angles(square)).round(6).tolist()
[90.0, 90.0, 90.0, 90.0]
>>> len(symmetry_maps(square)), len(symmetry_maps(regular_polygon(6)))
(8, 12)
>>> len(ear_clip(np.array([[0, 0], [2, 0], [2, 2], [1, 1], [0, 2]], dtype=float)))
3
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Iterable, Sequence

import numpy as np
import shapely
from shapely.ops import polylabel

from tilekit.errors import GeometryError

TWO_PI = 2 * math.pi
#: Areas below this count as zero (degenerate outlines) in :func:`centroid` (geometry.EPS).
_AREA_EPS = 1e-9

__all__ = [
    "area",
    "canonical_cycle",
    "centroid",
    "congruences",
    "corner_count",
    "corner_mask",
    "cyclic_equal",
    "ear_clip",
    "edge_signature",
    "edge_to_edge",
    "inscribed_disc",
    "interior_angles",
    "regular_polygon",
    "signature_rotations",
    "signed_area",
    "symmetry_maps",
    "vertex_symmetries",
]


def signed_area(points: np.ndarray) -> float | np.ndarray:
    """Shoelace signed area, positive for counter-clockwise: a float for one outline
    ``(k, 2)``, an ``(n,)`` array for a stack ``(n, k, 2)``."""
    p = np.asarray(points, dtype=float)
    x, y = p[..., 0], p[..., 1]
    if p.ndim == 2:
        return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))
    return 0.5 * ((x * np.roll(y, -1, axis=-1)).sum(-1) - (np.roll(x, -1, axis=-1) * y).sum(-1))


def area(points: np.ndarray) -> float | np.ndarray:
    """Unsigned area (see :func:`signed_area`)."""
    return abs(signed_area(points)) if np.asarray(points).ndim == 2 else np.abs(signed_area(points))


def centroid(points: np.ndarray) -> np.ndarray:
    """Area centroid of a simple polygon ``(k, 2)`` -> ``(2,)``, or of a stack -> ``(n, 2)``;
    the vertex mean where the area vanishes."""
    p = np.asarray(points, dtype=float)
    x, y = p[..., 0], p[..., 1]
    x1, y1 = np.roll(x, -1, axis=-1), np.roll(y, -1, axis=-1)
    cross = x * y1 - x1 * y
    a = cross.sum(-1) / 2
    flat = np.abs(a) < _AREA_EPS
    safe = np.where(flat, 1.0, a)
    c = np.stack([((x + x1) * cross).sum(-1) / (6 * safe), ((y + y1) * cross).sum(-1) / (6 * safe)], axis=-1)
    return np.where(np.asarray(flat)[..., None], p.mean(axis=-2), c)


def interior_angles(points: np.ndarray) -> np.ndarray:
    """Interior angle at each vertex of a counter-clockwise outline, in [0, 2π) (reflex
    angles above π): ``(k,)`` for one outline, ``(n, k)`` for a stack."""
    p = np.asarray(points, dtype=float)
    nxt = np.roll(p, -1, axis=-2) - p
    prv = np.roll(p, 1, axis=-2) - p
    cross = nxt[..., 0] * prv[..., 1] - nxt[..., 1] * prv[..., 0]
    dot = (nxt * prv).sum(axis=-1)
    return np.mod(np.arctan2(cross, dot), TWO_PI)


def corner_mask(points: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """Which vertices of an outline are corners, where the boundary turns: a point on a
    straight run between two others is not (the book's *shape vertices*, §4.1)."""
    p = np.asarray(points, dtype=float)
    nxt = np.roll(p, -1, axis=0) - p
    prv = p - np.roll(p, 1, axis=0)
    cross = prv[:, 0] * nxt[:, 1] - prv[:, 1] * nxt[:, 0]
    scale = np.linalg.norm(prv, axis=1) * np.linalg.norm(nxt, axis=1)
    dot = (prv * nxt).sum(axis=1)
    return (np.abs(cross) > tol * scale) | (dot < 0)


def corner_count(points: np.ndarray, corners: Sequence[int] | None = None, tol: float = 1e-9) -> int:
    """How many sides an outline has as a polygon: its vertices where the boundary turns (a
    point on a straight run between two others is not a corner), or ``len(corners)`` when the
    outline names its tiling vertices (a shaped or curved edge is one side)."""
    if corners is not None:
        return len(corners)
    return int(np.count_nonzero(corner_mask(points, tol)))


def edge_to_edge(batches: Iterable[np.ndarray], tol: float = 1e-7) -> bool:
    """Whether placed polygons meet edge to edge: every shape vertex (a corner, see
    :func:`corner_mask`) of every tile is a shape vertex of each tile whose boundary it touches,
    i.e. no corner lies inside another tile's side. That is the book's definition (§4.1: the
    tiling vertices and the shape vertices coincide), since a tiling vertex that is not a corner
    of some tile lies inside that tile's side and is a corner of a tile meeting it there.

    ``batches`` are stacks ``(m, k, 2)`` of congruent outlines (``Patch.groups``); ``tol`` is
    relative to the median side. Vectorised: one shapely STRtree over all sides, one query.

    >>> sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    >>> grid = np.stack([sq + [i, j] for i in range(3) for j in range(3)])
    >>> bricks = np.stack([sq + [i + 0.5 * (j % 2), j] for i in range(3) for j in range(3)])
    >>> edge_to_edge([grid]), edge_to_edge([bricks])
    (True, False)
    """
    points, starts, ends, owner_p, owner_s = [], [], [], [], []
    tiles = 0
    for pts in batches:
        pts = np.asarray(pts, dtype=float)
        if pts.ndim == 2:
            pts = pts[None]
        if not len(pts):
            continue
        c = pts[:, corner_mask(pts[0], 1e-9)]  # congruent copies turn at the same vertices
        m, k = c.shape[:2]
        ids = np.arange(tiles, tiles + m)
        tiles += m
        points.append(c.reshape(-1, 2))
        owner_p.append(np.repeat(ids, k))
        starts.append(c.reshape(-1, 2))
        ends.append(np.roll(c, -1, axis=1).reshape(-1, 2))
        owner_s.append(np.repeat(ids, k))
    if tiles < 2:
        return True
    pts_all, a, b = np.concatenate(points), np.concatenate(starts), np.concatenate(ends)
    owner_pt, owner_seg = np.concatenate(owner_p), np.concatenate(owner_s)
    side = b - a
    length = np.linalg.norm(side, axis=1)
    eps = tol * float(np.median(length))
    tree = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
    pi, si = tree.query(shapely.points(pts_all), predicate="dwithin", distance=eps)
    other = owner_pt[pi] != owner_seg[si]
    pi, si = pi[other], si[other]
    t = ((pts_all[pi] - a[si]) * side[si]).sum(axis=1) / length[si] ** 2
    inside = (t * length[si] > eps) & ((1 - t) * length[si] > eps)
    return not bool(inside.any())


def ear_clip(pts: np.ndarray) -> list[np.ndarray]:
    """Triangulate a simple counter-clockwise polygon (non-convex prototiles are split into
    convex pieces this way); the last piece may be the remaining triangle."""
    idx = list(range(len(pts)))
    out: list[np.ndarray] = []

    def cross(o, a, b) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    guard = 0
    while len(idx) > 3 and guard < 10000:
        guard += 1
        n = len(idx)
        for k in range(n):
            i0, i1, i2 = idx[k - 1], idx[k], idx[(k + 1) % n]
            a, b, c = pts[i0], pts[i1], pts[i2]
            if cross(a, b, c) <= 1e-12:
                continue
            inside = False
            for j in idx:
                if j in (i0, i1, i2):
                    continue
                p = pts[j]
                if cross(a, b, p) >= -1e-12 and cross(b, c, p) >= -1e-12 and cross(c, a, p) >= -1e-12:
                    inside = True
                    break
            if not inside:
                out.append(np.array([a, b, c]))
                del idx[k]
                break
        else:
            raise GeometryError("prototile outline could not be triangulated (is it simple?)")
    out.append(pts[idx])
    return out


def inscribed_disc(outline: np.ndarray) -> tuple[np.ndarray, float]:
    """A large disc inside the outline (centre, radius), by shapely's polylabel."""
    poly = shapely.Polygon(outline)
    tol = math.sqrt(poly.area) * 1e-4
    c = polylabel(poly, tolerance=tol)
    return np.array([c.x, c.y]), float(poly.exterior.distance(c))


def regular_polygon(n: int, side: float = 1.0) -> np.ndarray:
    """A regular n-gon with the given side, first edge from (0,0) to (side,0), counter-clockwise."""
    if n < 3:
        raise GeometryError(f"a regular polygon needs at least 3 sides, not {n}")
    ext = 2 * math.pi / n
    pts = [(0.0, 0.0)]
    x = y = 0.0
    for i in range(n - 1):
        x += side * math.cos(i * ext)
        y += side * math.sin(i * ext)
        pts.append((x, y))
    return np.array(pts)


# --------------------------------------------------------------------------- symmetries


def _map_of_triangles(src: np.ndarray, dst: np.ndarray) -> np.ndarray | None:
    """The affine map sending three points onto three points, or None if src is degenerate."""
    a = np.column_stack([src, np.ones(3)])
    if abs(np.linalg.det(a)) < 1e-12:
        return None
    m = np.eye(3)
    m[:2, :] = np.linalg.solve(a, dst).T
    return m


def vertex_symmetries(outline: np.ndarray, tol: float = 1e-7) -> list[tuple[int, int, np.ndarray]]:
    """The isometries mapping the outline onto itself as ``(j, direction, matrix)``: vertex i
    goes to vertex ``(j + direction * i) % k`` (direction -1 for the opposite ones); the
    identity first, then by j and direction."""
    pts = np.asarray(outline, dtype=float)
    k = len(pts)
    out: list[tuple[int, int, np.ndarray]] = [(0, 1, np.eye(3))]
    atol = tol * max(1.0, float(np.abs(pts).max()))
    for j in range(k):
        for direction in (1, -1):
            if j == 0 and direction == 1:
                continue
            m = _map_of_triangles(pts[[0, 1, 2]], pts[[j % k, (j + direction) % k, (j + 2 * direction) % k]])
            if m is None:
                continue
            lin = m[:2, :2]
            if not np.allclose(lin.T @ lin, np.eye(2), atol=1e-6):
                continue
            img = pts @ lin.T + m[:2, 2]
            perm = pts[[(j + direction * i) % k for i in range(k)]]
            if np.allclose(img, perm, atol=atol):
                out.append((j, direction, m))
    return out


def symmetry_maps(outline: np.ndarray, tol: float = 1e-7) -> np.ndarray:
    """All isometries mapping the outline onto itself, ``(s, 3, 3)``, identity first."""
    return np.array([m for _, _, m in vertex_symmetries(outline, tol)])


def edge_signature(points: np.ndarray, labels: Sequence[Hashable], length_quantum: float) -> list[tuple]:
    """Per edge i (from vertex i): its length in units of ``length_quantum``, the interior
    angle at vertex i in units of 1e-4 rad, and its label — a cyclic word whose rotations
    that fix it are the polygon's rotational symmetries respecting labels."""
    p = np.asarray(points, dtype=float)
    edges = np.roll(p, -1, axis=0) - p
    lengths = np.hypot(edges[:, 0], edges[:, 1])
    ang = interior_angles(p)
    return [(round(float(lengths[i]) / length_quantum), round(float(ang[i]) / 1e-4), labels[i]) for i in range(len(p))]


def cyclic_equal(a: Sequence, b: Sequence) -> bool:
    """Whether the cyclic words ``a`` and ``b`` agree up to a rotation."""
    a, b = list(a), list(b)
    if len(a) != len(b):
        return False
    return any(a[s:] + a[:s] == b for s in range(len(a)))


def signature_rotations(sig: Sequence) -> list[int]:
    """The edges j whose rotation of the cyclic word ``sig`` differs from every earlier one:
    one edge per orbit of the polygon's rotational symmetry group."""
    sig = list(sig)
    seen: list[list] = []
    out: list[int] = []
    for j in range(len(sig)):
        rot = sig[j:] + sig[:j]
        if any(rot == s for s in seen):
            continue
        seen.append(rot)
        out.append(j)
    return out


# --------------------------------------------------------------------------- congruences


def congruences(a: np.ndarray, b: np.ndarray, tol: float) -> np.ndarray:
    """Every isometry mapping the cyclic outline ``a`` onto ``b`` (same point count), (c, 3, 3)."""
    k = len(a)
    za = a[:, 0] + 1j * a[:, 1]
    zb = b[:, 0] + 1j * b[:, 1]
    ca, cb = za.mean(), zb.mean()
    a0, b0 = za - ca, zb - cb
    i = int(np.argmax(np.abs(a0)))
    if abs(a0[i]) < tol:
        return np.zeros((0, 3, 3))
    j = np.arange(k)
    out = []
    forward = (j[:, None] + j[None, :]) % k  # row s: b[(s + j) % k]
    backward = (j[:, None] - j[None, :]) % k  # row s: b[(s - j) % k]
    # placed outlines may run either way round (a reflected placement reverses its
    # order), so both traversal directions are tried for direct and opposite maps
    for opposite, idx in ((False, forward), (False, backward), (True, forward), (True, backward)):
        src = np.conj(a0) if opposite else a0
        tgt = b0[idx]
        r = tgt[:, i] / src[i]
        ok = np.abs(np.abs(r) - 1.0) < tol / abs(a0[i])
        r = r / np.where(np.abs(r) > 0, np.abs(r), 1.0)
        ok &= np.max(np.abs(r[:, None] * src[None, :] - tgt), axis=1) < tol
        for rr in r[ok]:
            if opposite:
                lin = np.array([[rr.real, rr.imag], [rr.imag, -rr.real]])
                t = cb - rr * np.conj(ca)
            else:
                lin = np.array([[rr.real, -rr.imag], [rr.imag, rr.real]])
                t = cb - rr * ca
            m = np.eye(3)
            m[:2, :2] = lin
            m[:2, 2] = (t.real, t.imag)
            out.append(m)
    return np.array(out) if out else np.zeros((0, 3, 3))


# --------------------------------------------------------------------------- vertex stars


class StarIndex:
    """Vertices of placed polygons by position, kept up to date as corners come and go: a
    point is snapped to a grid of ``quantum`` and matched within 2 ``quantum`` in the
    neighbouring cells too (so points that straddle a grid line still meet); ``corners[v]``
    holds whatever the caller files at vertex v (the builder: its Corner records). Freed
    numbers are reused. :class:`VertexStars` is the batch form over a set of outlines.

    >>> index = StarIndex(1e-6)
    >>> v = index.add(1.0, 2.0)
    >>> index.find(1.0 + 1e-7, 2.0) == v, index.find(1.1, 2.0)
    (True, None)
    """

    def __init__(self, quantum: float) -> None:
        self.quantum = quantum
        self._by_key: dict[tuple[int, int], int] = {}
        self.points: list[tuple[float, float]] = []
        self.keys: list[tuple[int, int]] = []
        self.corners: list[list] = []
        self.live: list[bool] = []
        self._free: list[int] = []

    def __len__(self) -> int:
        return len(self.points)

    def key(self, x: float, y: float) -> tuple[int, int]:
        return round(x / self.quantum), round(y / self.quantum)

    def find(self, x: float, y: float) -> int | None:
        """The vertex at (x, y) (within 2 quanta), or None."""
        kx, ky = self.key(x, y)
        v = self._by_key.get((kx, ky))
        if v is not None:
            return v
        q2 = 2 * self.quantum
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                v = self._by_key.get((kx + dx, ky + dy))
                if v is not None:
                    px, py = self.points[v]
                    if abs(px - x) <= q2 and abs(py - y) <= q2:
                        return v
        return None

    def add(self, x: float, y: float) -> int:
        """A new vertex at (x, y) with no corners (the caller has checked ``find``)."""
        key = self.key(x, y)
        if self._free:
            v = self._free.pop()
            self.points[v], self.keys[v], self.corners[v], self.live[v] = (x, y), key, [], True
        else:
            v = len(self.points)
            self.points.append((x, y))
            self.keys.append(key)
            self.corners.append([])
            self.live.append(True)
        self._by_key[key] = v
        return v

    def remove(self, v: int) -> None:
        """Forget vertex v (its number is reused by the next ``add``)."""
        del self._by_key[self.keys[v]]
        self.live[v] = False
        self._free.append(v)


class VertexStars:
    """The corners of a set of placed polygons grouped by the point they sit at.

    ``vertex[c]`` is the vertex of corner c (corners numbered tile by tile, outline order),
    ``tile[c]`` and ``index[c]`` name the corner; ``points[v]`` is where vertex v is (the
    position of the last corner found there); ``members(v)`` lists its corners in the order
    they were found. Vertices are numbered in order of first appearance; positions are
    matched as in :class:`StarIndex`.
    """

    def __init__(self, polygons: Sequence[np.ndarray], quantum: float = 1e-6) -> None:
        self.index_of = StarIndex(quantum)
        vertex, tile, index = [], [], []
        for t, pts in enumerate(polygons):
            for i, (x, y) in enumerate(np.asarray(pts, dtype=float).tolist()):
                v = self.index_of.find(x, y)
                if v is None:
                    v = self.index_of.add(x, y)
                else:
                    self.index_of.points[v] = (x, y)
                vertex.append(v)
                tile.append(t)
                index.append(i)
        self.keys = self.index_of.keys
        self.points = np.array(self.index_of.points, dtype=float).reshape(-1, 2)
        self.vertex = np.array(vertex, dtype=np.int64)
        self.tile = np.array(tile, dtype=np.int64)
        self.index = np.array(index, dtype=np.int64)
        order = np.argsort(self.vertex, kind="stable")
        self._order = order
        self._starts = np.searchsorted(self.vertex[order], np.arange(len(self.points) + 1))

    def __len__(self) -> int:
        return len(self.points)

    def members(self, v: int) -> np.ndarray:
        """Corner numbers at vertex ``v``, in the order they were found."""
        return self._order[self._starts[v] : self._starts[v + 1]]

    def valence(self) -> np.ndarray:
        """Number of corners at each vertex."""
        return np.diff(self._starts)

    def find(self, points: np.ndarray) -> np.ndarray:
        """The vertex at each of ``points`` ``(m, 2)``, -1 where there is none."""
        found = (self.index_of.find(x, y) for x, y in np.asarray(points, dtype=float).reshape(-1, 2).tolist())
        return np.fromiter((-1 if v is None else v for v in found), dtype=np.int64)

    def corners_at(self, v: int, polygons: Sequence[np.ndarray]) -> list[tuple[int, float, np.ndarray, np.ndarray]]:
        """The corners at vertex ``v`` counter-clockwise round it: (tile, interior angle, the
        corner's first edge, its second edge), the edges as vectors from v, the first on the
        corner's clockwise side; outlines given clockwise (reflected placements) are read the
        other way round."""
        out = []
        for c in self.members(v):
            t, i = int(self.tile[c]), int(self.index[c])
            pts = np.asarray(polygons[t], dtype=float)
            k = len(pts)
            nxt, prv = pts[(i + 1) % k] - pts[i], pts[i - 1] - pts[i]
            if signed_area(pts) < 0:
                nxt, prv = prv, nxt
            angle = math.atan2(nxt[0] * prv[1] - nxt[1] * prv[0], float(nxt @ prv)) % TWO_PI
            out.append((t, angle, nxt, prv))
        out.sort(key=lambda c: math.atan2(c[2][1], c[2][0]))
        return out

    def star_code(self, v: int, polygons: Sequence[np.ndarray], labels: Sequence[Hashable],
                  quantum: float = 1e-4) -> tuple | None:
        """Vertex ``v``'s star up to congruence (rotations and reflections): the cyclic word
        of its corners (label, angle, edge lengths) in canonical form (:func:`canonical_cycle`),
        numbers in units of ``quantum`` (radians for angles); None when the corners do not
        close round v (a vertex on a patch's boundary, or one an edge passes through)."""
        corners = self.corners_at(v, polygons)
        if abs(sum(c[1] for c in corners) - TWO_PI) > 1e-6:
            return None

        def q(x: float) -> int:
            return round(x / quantum)

        word = [(labels[t], q(a), q(float(np.hypot(*nx))), q(float(np.hypot(*pv)))) for t, a, nx, pv in corners]
        mirror = [(lab, a, lp, ln) for lab, a, ln, lp in reversed(word)]
        return canonical_cycle(word, mirror)

    def neighbourhood_code(self, v: int, polygons: Sequence[np.ndarray], labels: Sequence[Hashable],
                           centres: np.ndarray, near: np.ndarray, quantum: float = 1e-4) -> tuple:
        """The tiles ``near`` (indices) about vertex ``v`` up to the isometries fixing v: each
        as (label, x, y) of its centre in units of ``quantum``, in every frame that puts an edge
        leaving v along +x, directly or mirrored; the least of the sorted words. Two vertices
        get the same code exactly when an isometry maps one onto the other and the near
        tiles onto the near tiles (labels kept), up to ``quantum``."""
        rel = np.asarray(centres, dtype=float)[near] - self.points[v]
        labs = [labels[int(t)] for t in near]
        best: tuple | None = None
        for _, _, edge, _ in self.corners_at(v, polygons):
            c, s = edge / math.hypot(*edge)
            x = np.rint((rel[:, 0] * c + rel[:, 1] * s) / quantum).astype(np.int64).tolist()
            y = np.rint((rel[:, 1] * c - rel[:, 0] * s) / quantum).astype(np.int64).tolist()
            for sign in (1, -1):
                word = tuple(sorted(zip(labs, x, [sign * w for w in y])))
                if best is None or word < best:
                    best = word
        return best if best is not None else ()

    def reach(self, polygons: Sequence[shapely.Geometry] | np.ndarray, tol: float) -> np.ndarray:
        """Per vertex, how many of ``polygons`` (shapely geometries) come within ``tol`` of
        it: the tiles with a corner there and those whose edge passes through it (a vertex
        of a tiling that is not edge to edge). Three or more make a vertex of the tiling."""
        tree = shapely.STRtree(np.asarray(polygons))
        hit, _ = tree.query(shapely.points(self.points), predicate="dwithin", distance=tol)
        return np.bincount(hit, minlength=len(self.points))


def canonical_cycle(word: Sequence, mirror: Sequence | None = None) -> tuple:
    """The least of the cyclic shifts of ``word`` and of ``mirror`` (the word read the other
    way round; default: reversed): a cyclic word up to rotation and reflection, e.g. the
    corners round a vertex.

    >>> canonical_cycle([3, 1, 2]), canonical_cycle([2, 1, 3])
    ((1, 2, 3), (1, 2, 3))
    """
    forms = []
    for base in (list(word), list(reversed(word)) if mirror is None else list(mirror)):
        forms += [tuple(base[i:] + base[:i]) for i in range(len(base))]
    return min(forms) if forms else ()


def vertex_stars(polygons: Sequence[np.ndarray], quantum: float = 1e-6) -> VertexStars:
    """Group the corners of placed outlines by position (coordinates rounded to ``quantum``).

    >>> sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    >>> stars = vertex_stars([sq, sq + [1.0, 0.0], sq + [0.0, 1.0], sq + [1.0, 1.0]])
    >>> int(stars.valence().max()), stars.tile[stars.members(2)].tolist()
    (4, [0, 1, 2, 3])
    """
    return VertexStars(polygons, quantum)
