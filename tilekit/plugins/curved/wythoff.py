"""Wythoff's construction of the uniform tilings on the triangle group (p, q, r): the sphere
(1/p + 1/q + 1/r > 1), the plane (= 1) and the hyperbolic plane (< 1).

The Schwarz triangle with angles π/p, π/q, π/r at its corners X0, X1, X2 is placed with X0
at the pole of the model (the sphere, the hyperboloid, or the plane z = 1 in homogeneous
coordinates), and its three sides are mirrors (one 3x3 reflection each). A generator point
G is put in the triangle at given distances from the sides, so that every edge (G to its
mirror image, or to its image under a corner's rotation) has one length:

- ``p | q r``: G at the corner X0; faces q-gons round X1 and r-gons round X2, vertex (q.r)^p;
- ``p q | r``: G on the side X0X1, as far from the other two sides; vertex p.2r.q.2r;
- ``p q r |``: G the incentre; vertex 2p.2q.2r;
- ``| p q r``: the snub, G where its images under the three corner rotations are equally far,
  found by Newton's method; vertex 3.p.3.q.3.r, the rotation group only.

Digons (a 2 in p, q, r) collapse to edges and drop out of the vertex configuration. Faces
are regular polygons: round corner Xi the images of G under the corner's dihedral group (its
cyclic group for a snub), plus for a snub the triangles between them. The tiling is made by
the group's *cells*, the 2n triangles round the corner of largest order n: a breadth-first
walk over cells (neighbours across the cell's sides), new cells told apart from the last two
layers by their centres on a grid (distinct centres are a cell's width apart), then every
face as a cell's matrix times a face frame. Each face is a matrix taking the regular
polygon at the pole onto it, so a patch is one 3x3 matrix per tile as for the regular
tilings, and the plane's tilings become a :class:`tilekit.PeriodicTiling` (the group's
translations, the faces of one translational unit).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import Any

import numpy as np

from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.plugins.curved import notation

SPHERE, EUCLIDEAN, HYPERBOLIC = "spherical", "euclidean", "hyperbolic"
GEOMETRIES = {"sphere": SPHERE, "spherical": SPHERE, "hyperbolic": HYPERBOLIC,
              "plane": EUCLIDEAN, "euclidean": EUCLIDEAN}


def check_geometry(geometry: Any) -> str | None:
    """The geometry hint as 'spherical', 'euclidean' or 'hyperbolic' (None: no hint)."""
    if geometry is None:
        return None
    if not isinstance(geometry, str) or geometry.lower() not in GEOMETRIES:
        raise ParameterError(f"geometry must be one of sphere, plane, hyperbolic, got {str(geometry)[:40]}")
    return GEOMETRIES[geometry.lower()]

#: Largest order p, q, r accepted in a Wythoff symbol (the corner angle π/60).
MAX_ORDER = 60

FORMS = ("vertex", "edge", "omni", "snub")
#: The generator's weights (its distance functions from the sides opposite X0, X1, X2).
_WEIGHTS = {"vertex": (1.0, 0.0, 0.0), "edge": (1.0, 1.0, 0.0), "omni": (1.0, 1.0, 1.0)}
_J = np.diag([1.0, 1.0, -1.0])


# --------------------------------------------------------------------------- symbols


@dataclass(frozen=True)
class Symbol:
    """A Wythoff symbol: ``form`` one of FORMS, ``orders`` (p, q, r) as written."""

    form: str
    orders: tuple[int, int, int]

    def __str__(self) -> str:
        p, q, r = self.orders
        return {"vertex": f"{p} | {q} {r}", "edge": f"{p} {q} | {r}", "omni": f"{p} {q} {r} |",
                "snub": f"| {p} {q} {r}"}[self.form]

    @classmethod
    def parse(cls, text: str) -> Symbol:
        """``'3 | 2 7'``, ``'2 7 | 3'``, ``'2 3 7 |'``, ``'| 2 3 7'`` (one-line ParseError)."""
        if not isinstance(text, str) or text.count("|") != 1:
            raise ParseError(f"Wythoff symbol {str(text)[:40]!r}: write three orders and one bar, e.g. "
                             "'3 | 2 7', '2 7 | 3', '2 3 7 |' or '| 2 3 7'")
        left, right = (s.split() for s in text.split("|"))
        try:
            orders = tuple(int(x) for x in left + right)
        except ValueError:
            raise ParseError(f"Wythoff symbol {text[:40]!r}: the orders must be integers 2..{MAX_ORDER}") from None
        if len(orders) != 3:
            raise ParseError(f"Wythoff symbol {text[:40]!r} has {len(orders)} orders; it needs three (p q r)")
        form = {1: "vertex", 2: "edge", 3: "omni", 0: "snub"}[len(left)]
        return cls(form, check_orders(orders))  # type: ignore[arg-type]

    @property
    def sequence(self) -> tuple[int, ...]:
        """The faces round a vertex in order, digons dropped (not canonical)."""
        p, q, r = self.orders
        raw = {"vertex": [q, r] * p, "edge": [p, 2 * r, q, 2 * r], "omni": [2 * p, 2 * q, 2 * r],
               "snub": [3, p, 3, q, 3, r]}[self.form]
        return tuple(n for n in raw if n > 2)

    @property
    def configuration(self) -> tuple[int, ...] | None:
        """The canonical vertex configuration, or None when fewer than three polygons meet
        (a dihedron, a hosohedron, the degenerate symbols)."""
        seq = self.sequence
        return notation.canonical(seq) if len(seq) >= 3 else None

    @property
    def geometry(self) -> str:
        return geometry_of_orders(self.orders)

    def face_sizes(self) -> list[tuple[int, int]]:
        """(corner, sides) of each kind of face, digons and points dropped: round corner i
        the generator's orbit under the corner's dihedral group (2n_i, or n_i when the
        generator is on a side through the corner), its cyclic group for a snub (n_i), and
        for a snub the triangles between (corner 3)."""
        on = {"vertex": (False, True, True), "edge": (False, False, True), "omni": (False, False, False),
              "snub": (False, False, False)}[self.form]  # is G on the side opposite corner 0, 1, 2
        out = []
        for i, n in enumerate(self.orders):
            if self.form == "snub":
                k = n
            else:
                through = [on[j] for j in range(3) if j != i]  # the two sides through corner i
                k = 1 if all(through) else n if any(through) else 2 * n
            if k >= 3:
                out.append((i, k))
        if self.form == "snub":
            out.append((3, 3))
        return out

    def group_order(self) -> int:
        """The order of the triangle group *pqr on the sphere, 4 / (1/p + 1/q + 1/r − 1)
        (a one-line error for an infinite group)."""
        p, q, r = self.orders
        s, t = q * r + p * r + p * q, p * q * r
        if s <= t:
            raise ParameterError(f"{self} is not spherical: its group is infinite")
        return 4 * t // (s - t)

    def face_counts(self) -> dict[int, int]:
        """Faces per polygon size on the sphere: the group's order over each face's
        stabiliser (2n_i round corner i, a snub's triangles 2)."""
        order = self.group_order()
        out: dict[int, int] = {}
        for corner, k in self.face_sizes():
            count = order // (2 * self.orders[corner]) if corner < 3 else order // 2
            out[k] = out.get(k, 0) + count
        return out

    @property
    def group(self) -> str:
        """The construction's group in orbifold notation: *pqr, or pqr for a snub (2s kept)."""
        digits = "".join(str(n) for n in sorted(self.orders, reverse=True))
        return digits if self.form == "snub" else "*" + digits


def check_orders(orders: object) -> tuple[int, int, int]:
    """Three integers 2..MAX_ORDER (one-line ParameterError naming the bad one)."""
    if not isinstance(orders, (tuple, list)) or len(orders) != 3:
        raise ParameterError(f"a triangle group needs three orders p, q, r (2..{MAX_ORDER}), got {str(orders)[:40]}")
    out = []
    for name, v in zip("pqr", orders):
        if isinstance(v, bool) or not isinstance(v, int) or not 2 <= v <= MAX_ORDER:
            raise ParameterError(f"{name} must be an integer 2..{MAX_ORDER} (the corner angle π/{name}), "
                                 f"got {str(v)[:20]}")
        out.append(int(v))
    return tuple(out)  # type: ignore[return-value]


def geometry_of_orders(orders: tuple[int, int, int]) -> str:
    """The sign of 1/p + 1/q + 1/r − 1, in integers: qr + pr + pq against pqr."""
    p, q, r = orders
    s, t = q * r + p * r + p * q, p * q * r
    return SPHERE if s > t else EUCLIDEAN if s == t else HYPERBOLIC


def triangle_area(orders: tuple[int, int, int]) -> float:
    """|π(1/p + 1/q + 1/r − 1)| (Gauss–Bonnet; the plane's triangle has no intrinsic size)."""
    return abs(math.pi * (sum(1.0 / n for n in orders) - 1.0))


def symbols_for(config: tuple[int, ...]) -> list[Symbol]:
    """Every Wythoff symbol whose vertex configuration is ``config`` (any rotation or
    reflection), largest group first (smallest triangle; in the plane the largest corner
    order), then vertex, edge, omni, snub.

    The candidates come from the polygon sizes: an order is 2, a size, or half an even size.
    """
    return list(_symbols_for(notation.canonical(config)))


@lru_cache(maxsize=4096)
def _symbols_for(want: tuple[int, ...]) -> tuple[Symbol, ...]:
    config = want
    multiset = sorted(want)
    k = len(config)  # p | q r repeats q.r p times (p | q 2: q, p times)
    cand = {2, k, k // 2} | set(config) | {n // 2 for n in config if n % 2 == 0}
    cand = {n for n in cand if 2 <= n <= MAX_ORDER}
    found: dict[tuple[str, tuple[int, int, int]], Symbol] = {}
    for orders in itertools.product(sorted(cand), repeat=3):
        if geometry_of_orders(orders) == EUCLIDEAN and notation.geometry_of(want) != EUCLIDEAN:
            continue
        for form in FORMS:
            sym = Symbol(form, orders)  # type: ignore[arg-type]
            if sorted(sym.sequence) == multiset and sym.configuration == want:
                key = (form, _orbit_key(form, orders))
                found.setdefault(key, sym)
    return tuple(sorted(found.values(), key=lambda s: (triangle_area(s.orders), -max(s.orders), FORMS.index(s.form), s.orders)))


def _orbit_key(form: str, orders: tuple[int, int, int]) -> tuple[int, int, int]:
    """Symbols that are the same construction: p | q r = p | r q, p q | r = q p | r, omni and
    snub under any order."""
    p, q, r = orders
    if form == "vertex":
        return (p, *sorted((q, r)))  # type: ignore[return-value]
    if form == "edge":
        return (*sorted((p, q)), r)  # type: ignore[return-value]
    return tuple(sorted(orders))  # type: ignore[return-value]


def symbol_for(config: tuple[int, ...]) -> Symbol:
    """The Wythoff symbol of the uniform tiling with this vertex configuration (the first of
    :func:`symbols_for`), or a one-line ParameterError when there is none."""
    syms = symbols_for(config)
    if not syms:
        kind = notation.geometry_of(config)
        where = {"spherical": "the sphere", "euclidean": "the plane", "hyperbolic": "the hyperbolic plane"}[kind]
        raise ParameterError(
            f"{notation.dotted(config)}: no uniform tiling by Wythoff's construction has this vertex configuration "
            f"(its angles close on {where}, but no symbol p|q r, p q|r, p q r| or |p q r gives it); "
            "e.g. 3.4.4.4, 3.3.3.3.5, 3.14.14, 4.6.10")
    return syms[0]


# --------------------------------------------------------------------------- the models


@dataclass(frozen=True)
class Space:
    """One of the three models: ``sign`` +1 sphere (unit vectors), −1 hyperboloid
    (x² + y² − t² = −1), 0 the plane (x, y, 1). Vectorised over leading axes."""

    sign: int

    def point(self, d: float | np.ndarray, theta: float | np.ndarray) -> np.ndarray:
        """The point at distance d from the pole (origin) in direction theta."""
        if self.sign > 0:
            s, c = np.sin(d), np.cos(d)
        elif self.sign < 0:
            s, c = np.sinh(d), np.cosh(d)
        else:
            s, c = d, np.ones_like(np.asarray(d, dtype=float))
        return np.stack(np.broadcast_arrays(s * np.cos(theta), s * np.sin(theta), c), axis=-1).astype(float)

    def distance(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        if self.sign > 0:
            return np.arccos(np.clip((a * b).sum(axis=-1), -1.0, 1.0))
        if self.sign < 0:
            inner = a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] - a[..., 2] * b[..., 2]
            return np.arccosh(np.maximum(-inner, 1.0))
        return np.hypot(a[..., 0] - b[..., 0], a[..., 1] - b[..., 1])

    def normalise(self, v: np.ndarray) -> np.ndarray:
        """A vector on the model along v (the sphere's unit vector, the hyperboloid's point
        with t > 0, the plane's z = 1)."""
        if self.sign > 0:
            return v / np.linalg.norm(v, axis=-1, keepdims=True)
        if self.sign < 0:
            n = v[..., 2:3] ** 2 - v[..., 0:1] ** 2 - v[..., 1:2] ** 2
            if np.any(n <= 0):
                raise GeometryError("a point of the construction left the hyperboloid (not timelike)")
            return v / (np.sqrt(n) * np.sign(v[..., 2:3]))
        return v / v[..., 2:3]

    def mirror(self, a: np.ndarray, b: np.ndarray, inside: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(f, w) of the line through a and b: f·x is the signed distance function (sin, sinh
        or the distance itself), positive at ``inside``; the reflection is I − 2 w fᵀ."""
        if self.sign == 0:
            d = (b - a)[:2] / np.hypot(*(b - a)[:2])
            m = np.array([-d[1], d[0]])
            f = np.array([m[0], m[1], -float(m @ a[:2])])
            w = np.array([m[0], m[1], 0.0])
        elif self.sign > 0:
            n = np.cross(a, b)
            n = n / np.linalg.norm(n)
            f, w = n, n
        else:
            n = _J @ np.cross(a, b)
            n = n / math.sqrt(float(n @ _J @ n))
            f, w = _J @ n, n
        if float(f @ inside) < 0:
            f, w = -f, -w
        return f, w

    def frame(self, centre: np.ndarray, towards: np.ndarray) -> np.ndarray:
        """The motion (determinant +1) taking the pole to ``centre`` and the direction of the
        x axis there to the direction of ``towards``."""
        c = np.asarray(centre, dtype=float)
        v = np.asarray(towards, dtype=float)
        if self.sign == 0:
            e1 = np.array([v[0] - c[0], v[1] - c[1], 0.0])
            e1 /= np.linalg.norm(e1)
            e2 = np.array([-e1[1], e1[0], 0.0])
        elif self.sign > 0:
            e1 = v - float(v @ c) * c
            e1 /= np.linalg.norm(e1)
            e2 = np.cross(c, e1)
        else:
            e1 = v + float(v @ _J @ c) * c
            e1 /= math.sqrt(float(e1 @ _J @ e1))
            e2 = _J @ np.cross(c, e1)
            e2 /= math.sqrt(float(e2 @ _J @ e2))
        m = np.column_stack([e1, e2, c])
        if np.linalg.det(m) < 0:
            m[:, 1] *= -1
        return m


def regular_polygon(space: Space, sides: int, circumradius: float) -> np.ndarray:
    """(sides, 3): the regular polygon at the pole, vertex k at angle 2πk/sides."""
    return space.point(circumradius, 2 * np.pi * np.arange(sides) / sides)


# --------------------------------------------------------------------------- the construction


@dataclass(frozen=True)
class FaceType:
    """One kind of face: ``sides``, ``circumradius``, ``frame`` (the pole's regular polygon
    onto the face in the fundamental position), ``centre`` (model point), ``corner`` (the
    triangle corner it is centred on, 0..2, or 3 for a snub triangle)."""

    sides: int
    circumradius: float
    frame: np.ndarray
    centre: np.ndarray
    corner: int


def weld(points: np.ndarray, sep: float) -> np.ndarray:
    """For each point (n, D) the index of its cluster's lowest-numbered point: points closer
    than sep/2 are one cluster, and distinct points are assumed at least ``sep`` apart.

    A grid of cells sep/4 wide holds at most one cluster per cell (its diagonal is under
    sep/2 for D <= 3); a cluster spread by float error over neighbouring cells is one cluster
    because the cells are neighbours and their representatives close: the lowest index wins."""
    n, dim = points.shape
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    h = sep / 4.0
    cell = np.floor(points / h).astype(np.int64)
    lo = cell.min(axis=0) - 1
    span = cell.max(axis=0) - lo + 2
    if float(np.prod(span.astype(float))) >= 2.0 ** 62:
        raise GeometryError("the construction's points are spread too far for the grid (radius too large)")
    weights = np.cumprod(np.concatenate([[1], span[:-1]])).astype(np.int64)
    key = ((cell - lo) * weights).sum(axis=1)
    ukey, rep, inv = np.unique(key, return_index=True, return_inverse=True)  # rep: lowest index per cell
    target = rep.copy()
    for off in itertools.product((-1, 0, 1), repeat=dim):
        if not any(off):
            continue
        nk = ukey + int(np.dot(off, weights))
        pos = np.minimum(np.searchsorted(ukey, nk), len(ukey) - 1)
        close = (ukey[pos] == nk) & (np.linalg.norm(points[rep[pos]] - points[rep], axis=1) < sep / 2)
        target = np.where(close & (rep[pos] < target), rep[pos], target)
    return target[inv.reshape(-1)]


def dedup(points: np.ndarray, sep: float, first: int = 0) -> np.ndarray:
    """Indices (sorted) of one point per cluster (:func:`weld`), the lowest-numbered; points
    below index ``first`` are known ones: the answer lists only clusters with none of them."""
    cluster = weld(points, sep)
    keep = np.flatnonzero(cluster == np.arange(len(points)))
    return keep[keep >= first]


class Construction:
    """Wythoff's construction for one symbol: the triangle, its mirrors and rotations, the
    generator, the face types, and the cells of the group (see the module)."""

    def __init__(self, symbol: Symbol) -> None:
        if symbol.configuration is None:
            raise ParameterError(f"Wythoff symbol {symbol} makes fewer than three faces at a vertex (a degenerate "
                                 "tiling): no uniform tiling by polygons")
        self.symbol = symbol
        self.orders = symbol.orders
        self.geometry = symbol.geometry
        self.space = Space({SPHERE: 1, EUCLIDEAN: 0, HYPERBOLIC: -1}[self.geometry])
        n0, n1, n2 = self.orders
        al, be, ga = math.pi / n0, math.pi / n1, math.pi / n2
        if self.space.sign == 0:
            c_side, b_side = 1.0, math.sin(be) / math.sin(ga)
        else:
            cos_c = (math.cos(ga) + math.cos(al) * math.cos(be)) / (math.sin(al) * math.sin(be))
            cos_b = (math.cos(be) + math.cos(al) * math.cos(ga)) / (math.sin(al) * math.sin(ga))
            acos = math.acos if self.space.sign > 0 else math.acosh
            c_side, b_side = acos(min(cos_c, 1.0) if self.space.sign > 0 else cos_c), \
                acos(min(cos_b, 1.0) if self.space.sign > 0 else cos_b)
        sp = self.space
        x = np.array([sp.point(0.0, 0.0), sp.point(c_side, 0.0), sp.point(b_side, al)])
        self.corners = x
        self.f = np.empty((3, 3))
        self.reflections = np.empty((3, 3, 3))
        for i in range(3):
            j, k = (i + 1) % 3, (i + 2) % 3
            f, w = sp.mirror(x[j], x[k], x[i])
            self.f[i] = f
            self.reflections[i] = np.eye(3) - 2.0 * np.outer(w, f)
        # the rotation by 2π/n_i about corner i: the product of the two mirrors through it
        self.rotations = np.array([self.reflections[(i + 1) % 3] @ self.reflections[(i + 2) % 3]
                                   for i in range(3)])
        self.generator = self._generator()
        self.edge_length = self._edge_length()
        self.face_types = self._face_types()

    # -- the generator --------------------------------------------------------
    def _point_from_weights(self, a: np.ndarray) -> np.ndarray:
        return self.space.normalise(np.linalg.solve(self.f, np.asarray(a, dtype=float)))

    def _generator(self) -> np.ndarray:
        form = self.symbol.form
        if form != "snub":
            return self._point_from_weights(np.array(_WEIGHTS[form]))
        sp, rot = self.space, self.rotations

        def residual(u: np.ndarray) -> np.ndarray:
            g = self._point_from_weights(np.array([math.exp(u[0]), math.exp(u[1]), 1.0]))
            e = sp.distance(g, (rot @ g))
            return np.array([e[0] - e[1], e[0] - e[2]])

        u = np.zeros(2)
        for _ in range(100):
            r = residual(u)
            if np.abs(r).max() < 1e-14:
                break
            jac = np.empty((2, 2))
            for k in range(2):
                du = np.zeros(2)
                du[k] = 1e-7
                jac[:, k] = (residual(u + du) - residual(u - du)) / 2e-7
            step = np.linalg.solve(jac, -r)
            u = u + np.clip(step, -1.0, 1.0)
        if np.abs(residual(u)).max() > 1e-10:
            raise GeometryError(f"the snub {self.symbol}: Newton's method found no generator with equal edges")
        return self._point_from_weights(np.array([math.exp(u[0]), math.exp(u[1]), 1.0]))

    def _edge_length(self) -> float:
        g = self.generator
        if self.symbol.form == "snub":
            d = self.space.distance(g, self.rotations @ g)
        else:  # an edge crosses each side G is not on
            d = self.space.distance(g, self.reflections @ g)[np.abs(self.f @ g) > 1e-12]
        if not len(d) or d.max() - d.min() > 1e-9 * max(1.0, d.max()):
            raise GeometryError(f"{self.symbol}: the generator's edges are not equal ({d.tolist()})")
        return float(d.mean())

    def _corner_orbit(self, i: int) -> np.ndarray:
        """Images of the generator round corner i (dihedral group; cyclic for a snub), distinct."""
        g, n = self.generator, self.orders[i]
        pts = []
        m = np.eye(3)
        for _ in range(n):
            pts.append(m @ g)
            if self.symbol.form != "snub":
                pts.append(m @ self.reflections[(i + 1) % 3] @ g)
            m = self.rotations[i] @ m
        out: list[np.ndarray] = []
        # coordinates, not arccos/arccosh, which lose half the digits near 0; the tolerance
        # scales with the orbit's coordinates (a generator at X0 whose orbit round a far
        # corner has coordinates of cosh(2d): 8 | 3 8 found ten triangles' worth of points)
        scale = 1e-9 * max(1.0, float(np.abs(np.array(pts)).max()))
        for pt in pts:
            if all(np.abs(pt - o).max() > scale for o in out):
                out.append(pt)
        return np.array(out)

    def _face_types(self) -> list[FaceType]:
        sp, g = self.space, self.generator
        out = []
        for i in range(3):
            orbit = self._corner_orbit(i)
            if len(orbit) >= 3:
                rho = float(sp.distance(self.corners[i], g))
                out.append(FaceType(len(orbit), rho, sp.frame(self.corners[i], g), self.corners[i], i))
        if self.symbol.form == "snub":
            out.append(self._snub_triangle())
        if [(f.corner, f.sides) for f in out] != self.symbol.face_sizes():
            raise GeometryError(f"{self.symbol}: the faces found ({[f.sides for f in out]}) are not the symbol's "
                                f"({[k for _, k in self.symbol.face_sizes()]})")
        return out

    def _snub_triangle(self) -> FaceType:
        sp, g, e = self.space, self.generator, self.edge_length
        rot = self.rotations
        for i, j in ((0, 1), (1, 2), (0, 2)):
            for si, sj in itertools.product((1, -1), repeat=2):
                a = np.linalg.matrix_power(rot[i], si) @ g
                b = np.linalg.matrix_power(rot[j], sj) @ g
                if (abs(float(sp.distance(a, b)) - e) < 1e-9 * max(1.0, e) and float(sp.distance(a, g)) > 1e-9
                        and float(sp.distance(b, g)) > 1e-9):
                    c = sp.normalise(g + a + b)
                    return FaceType(3, float(sp.distance(c, g)), sp.frame(c, g), c, 3)
        raise GeometryError(f"the snub {self.symbol}: no equilateral triangle at the generator")

    # -- the cells --------------------------------------------------------------
    @cached_property
    def cell_corner(self) -> int:
        """The corner of largest order: a cell is the 2n triangles round it."""
        return int(np.argmax(self.orders))

    @cached_property
    def stabiliser(self) -> np.ndarray:
        """(2n, 3, 3): the dihedral group at the cell corner (rotations, then rotations times a
        mirror through the corner and the next corner)."""
        c = self.cell_corner
        n = self.orders[c]
        mirror = self.reflections[(c + 2) % 3]  # the side through corners c and c + 1
        rots = [np.linalg.matrix_power(self.rotations[c], k) for k in range(n)]
        return np.array(rots + [r @ mirror for r in rots])

    @cached_property
    def cell_separation(self) -> float:
        """The distance from the cell corner to its mirror image across the opposite side:
        distinct cell centres are at least this far apart."""
        c = self.cell_corner
        x = self.corners[c]
        return float(self.space.distance(x, self.reflections[c] @ x))

    @cached_property
    def cell_radius(self) -> float:
        c = self.cell_corner
        return float(max(self.space.distance(self.corners[c], self.corners[k]) for k in range(3)))

    @cached_property
    def face_reach(self) -> float:
        """How far from the cell corner a face centre of its cell can lie."""
        c = self.cell_corner
        return float(max(self.space.distance(self.corners[c], f.centre) for f in self.face_types))

    def faces_per_area(self) -> float:
        """Faces per unit area (per triangle, the triangle's area: none for the plane)."""
        per_triangle = sum(1.0 / (2 * self.orders[f.corner]) if f.corner < 3 else 0.5 for f in self.face_types)
        return per_triangle / triangle_area(self.orders)

    def face_counts(self) -> dict[int, int]:
        """Faces per polygon size on the sphere (:meth:`Symbol.face_counts`)."""
        return self.symbol.face_counts()

    def _key_points(self, pts: np.ndarray) -> np.ndarray:
        """Coordinates the grid dedup uses: the hyperboloid's (x, y) (their Euclidean distance
        is at least the hyperbolic one), the sphere's (x, y, z), the plane's (x, y)."""
        return pts if self.space.sign > 0 else pts[:, :2]

    def cells(self, radius: float | None) -> np.ndarray:
        """(N, 3, 3) proper motions, one per cell whose corner lies within ``radius`` of the
        pole (every cell on the sphere, radius None), breadth first."""
        if radius is None and self.space.sign <= 0:
            raise ParameterError("an infinite tiling needs a radius")
        c = self.cell_corner
        x = self.corners[c]
        gens = self.stabiliser @ self.reflections[c]  # across each side of the cell
        sep = self.cell_separation
        bound = math.inf if radius is None else radius + self.cell_radius
        pole = self.corners[0]
        layers = [np.eye(3)[None]]
        prev: list[np.ndarray] = [np.zeros((0, 3, 3)), layers[0]]
        while True:
            cand = np.matmul(layers[-1][:, None], gens[None]).reshape(-1, 3, 3)
            centres = cand @ x
            if radius is not None:
                cand = cand[self.space.distance(centres, pole) <= bound]
                centres = cand @ x
            known = np.concatenate(prev)
            allpts = np.concatenate([known @ x, centres])
            new = dedup(self._key_points(allpts), sep, first=len(known)) - len(known)
            if not len(new):
                break
            layer = cand[new]
            layers.append(layer)
            prev = [prev[-1], layer]
        out = np.concatenate(layers)
        # proper representatives: a mirror through the corner keeps the cell
        flip = np.linalg.det(out) < 0
        out[flip] = out[flip] @ self.reflections[(c + 2) % 3]
        if radius is not None:
            out = out[self.space.distance(out @ x, pole) <= radius + 1e-12]
        return out

    def faces(self, radius: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(transforms (n, 3, 3), face type (n,)): every face whose centre lies within
        ``radius`` plus its circumradius of the pole, so every face meeting the disc of that
        radius (all of them on the sphere)."""
        c = self.cell_corner
        n = self.orders[c]
        grow = max(f.circumradius for f in self.face_types)
        reach = None if radius is None else radius + grow + self.face_reach
        cells = self.cells(reach)
        rots = np.array([np.linalg.matrix_power(self.rotations[c], k) for k in range(n)])
        pole = self.corners[0]
        mats, kinds = [], []
        for t, face in enumerate(self.face_types):
            if face.corner == c:
                m = cells @ face.frame
            elif face.corner < 3:
                cand = np.matmul(np.matmul(cells[:, None], rots[None]), face.frame).reshape(-1, 3, 3)
                sep = float(self.space.distance(face.centre, self.reflections[face.corner] @ face.centre))
                keep = dedup(self._key_points(cand[:, :, 2].copy()), sep)
                m = cand[keep]
            else:  # snub triangles: one per element of the rotation group, no two alike
                m = np.matmul(np.matmul(cells[:, None], rots[None]), face.frame).reshape(-1, 3, 3)
            if radius is not None:
                m = m[self.space.distance(m[:, :, 2], pole) <= radius + face.circumradius]
            mats.append(m)
            kinds.append(np.full(len(m), t, dtype=np.int64))
        return np.concatenate(mats), np.concatenate(kinds)

    def translations(self) -> tuple[np.ndarray, np.ndarray]:
        """The plane's group: two shortest independent translations (a reduced basis)."""
        if self.space.sign != 0:
            raise ParameterError(f"{self.symbol} is not Euclidean: its group has no translations")
        c = self.cell_corner
        cells = self.cells(6.0 * (self.cell_radius + 1.0))
        g = np.matmul(cells[:, None], self.stabiliser[None]).reshape(-1, 3, 3)
        lin = np.abs(g[:, :2, :2] - np.eye(2)).max(axis=(1, 2)) < 1e-9
        vec = g[lin, :2, 2]
        vec = vec[np.hypot(vec[:, 0], vec[:, 1]) > 1e-9]
        vec = vec[np.argsort(np.hypot(vec[:, 0], vec[:, 1]), kind="stable")]
        v1 = vec[0]
        cross = np.abs(v1[0] * vec[:, 1] - v1[1] * vec[:, 0])
        v2 = vec[np.flatnonzero(cross > 1e-9 * np.hypot(*v1) ** 2)[0]]
        del c
        return v1, v2


def enumerate_configurations(max_order: int, max_prism: int, species_max_order: int, species_max_sides: int,
                             species_max_valence: int) -> dict[tuple[int, ...], Symbol]:
    """Canonical vertex configuration -> its symbol (the first of :func:`symbols_for`'s
    order) for the spherical and hyperbolic uniform tilings: every symbol on orders
    2..max_order, the prisms and antiprisms up to max_prism sides, and the symbols on orders
    up to species_max_order whose configuration has at most species_max_valence polygons of
    at most species_max_sides sides."""
    top = max(max_order, species_max_order)
    found: dict[tuple[int, ...], Symbol] = {}
    orders_list = list(itertools.product(range(2, top + 1), repeat=3))
    orders_list += [o for n in range(top + 1, max_prism + 1) for o in ((2, 2, n), (2, n, 2), (n, 2, 2))]
    for orders in orders_list:
        if geometry_of_orders(orders) == EUCLIDEAN:
            continue
        for form in FORMS:
            sym = Symbol(form, orders)  # type: ignore[arg-type]
            cfg = sym.configuration
            if cfg is None or cfg in found:
                continue
            if recorded(sym, max_order, max_prism, species_max_order, species_max_sides, species_max_valence):
                found[cfg] = sym
    # the preferred symbol of each (largest group first), as symbol_for gives it
    return {cfg: symbols_for(cfg)[0] for cfg in sorted(found)}


def recorded(sym: Symbol, max_order: int, max_prism: int, species_max_order: int, species_max_sides: int,
             species_max_valence: int) -> bool:
    """Whether the bounds of :func:`enumerate_configurations` take this symbol."""
    cfg = sym.configuration
    if cfg is None or sym.geometry == EUCLIDEAN:
        return False
    top = max(sym.orders)
    species = top <= species_max_order and len(cfg) <= species_max_valence and max(cfg) <= species_max_sides
    prism = sym.orders.count(2) >= 2 and max(cfg) <= max_prism
    return top <= max_order or species or prism


def uniform_configuration(symbol: Symbol) -> str:
    """The symbol's vertex configuration, dotted (``3.4.4.4``)."""
    cfg = symbol.configuration
    if cfg is None:
        raise ParameterError(f"Wythoff symbol {symbol} makes fewer than three faces at a vertex")
    return notation.dotted(cfg)
