"""GomJau-Hogg notation for tilings by regular polygons: parse a notation into the D-symbol of
the tiling it draws, and write a notation for a k-uniform tiling.

The notation (Gomez-Jauregui, Hogg, Manchado & Otero, "GomJau-Hogg's notation for automatic
generation of k-uniform tessellations with ANTWERP v3.0", *Symmetry* 13 (2021) 2376; the
Antwerp v3 application is its reference implementation) has two stages::

    6-4-3,3/m30/r(h1)
    ^ ^ ^^^  ^^^ ^^^^^
    | | |    |   a transform at a point: r = half-turn about it, m = mirror through it
    | | |    a transform at the origin: m<a> mirrors in lines at a-90, 2a-90, 4a-90 ... degrees,
    | | |    r<a> rotates by a, 2a, 4a ... (doubling while below 360; a defaults to 180)
    | | a phase: polygons placed on the free edges of the previous phase, in order, 0 skips one
    | the first phase around the seed
    the seed polygon (3, 4, 6, 8 or 12)

The seed stands at the origin with two edges perpendicular to the x axis (a triangle: a
vertex at the origin, its left edge on the y axis). Each later phase walks the free edges
of the polygons placed in the phase before, sorted by the angle of their midpoints from the
origin (edges on the y axis last), and puts its polygons on them one by one. A point is
named by its kind and number: ``c`` polygon centres, ``h`` edge midpoints, ``v`` vertices,
each numbered from 1 in order of angle from the origin, then distance, among the points of
the figure drawn so far (the origin left out). ``m(hN)`` mirrors in the edge's line;
``m(cN)``/``m(vN)`` in the line through the point perpendicular to the ray from the origin.
Each transform adds its image of the whole figure; the tiling is the figure's orbit under the
group the transforms generate.

Parsing (:func:`parse`) builds the seed, runs the transforms, closes the figure under their
group within a disc, checks that the result is a tiling (no two polygons overlap, the angles at
each vertex sum to 360°, every edge is shared), finds its translations and returns the minimal
D-symbol of the tiling (:func:`tilekit.plugins.kuniform.dsymbol.DSymbol.minimal_image`), which
is what the catalogue's k-uniform records store. Writing (:func:`write`) places a tiling so that
one of its polygons is the seed, grows phases until the seed holds a whole translational unit,
then adds the transforms that are symmetries of the tiling — a centre transform, then half-turns
and mirrors at points of the figure — until they generate every translation; the written text
is checked by parsing it back.

Not every periodic tiling has a notation: the transforms are rotations about the origin,
half-turns and mirrors, so a tiling whose symmetry group has neither half-turns nor mirrors in
two directions (groups p1, p3, pg, pm, cm) cannot be generated; :func:`write` returns None there.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from functools import cmp_to_key

import numpy as np

from tilekit.errors import GeometryError, ParseError
from tilekit.plugins.kuniform.dsymbol import DSymbol, closure
from tilekit.polygon import regular_polygon
from tilekit.tiling import Patch, Prototile

SIZES = (3, 4, 6, 8, 12)
#: The longest notation text accepted, and the most polygons its seed may place.
MAX_TEXT = 600
MAX_SEED = 400
#: The most polygons the closure may hold before the notation is refused.
MAX_POLYGONS = 60000
#: Orientations are whole multiples of this many degrees (15° edges, 22.5° octagon corners).
STEP = 7.5
_TURN = 48  # steps in a full turn
_EPS = 1e-6
_ANGLE_EPS = 0.001  # Antwerp's angle precision (radians)
_KEY = 1e4  # points are hashed at this resolution
_CELL = 4.0  # grid cell for overlap tests: more than two circumradii of a 12-gon


def _inradius(p: int) -> float:
    return 0.5 / math.tan(math.pi / p)


def _circumradius(p: int) -> float:
    return 0.5 / math.sin(math.pi / p)


def _interior(p: int) -> float:
    return 180.0 - 360.0 / p


# --------------------------------------------------------------------------- the text


@dataclass(frozen=True)
class Transform:
    """One transform: ``m`` or ``r``, an angle (degrees; centre transforms) or a point
    (kind ``c``/``h``/``v`` and number), and where it starts in the text."""

    action: str
    angle: float
    point: tuple[str, int] | None
    text: str
    position: int


@dataclass(frozen=True)
class Notation:
    seed: int
    phases: tuple[tuple[int, ...], ...]
    transforms: tuple[Transform, ...]

    def __str__(self) -> str:
        return "/".join(["-".join([str(self.seed), *(",".join(map(str, ph)) for ph in self.phases)]),
                         *(t.text for t in self.transforms)])


class _Reader:
    def __init__(self, text: str) -> None:
        self.text = text
        self.i = 0

    def error(self, expected: str, at: int | None = None) -> ParseError:
        i = self.i if at is None else at
        got = repr(self.text[i]) if i < len(self.text) else "the end"
        return ParseError(f"GomJau-Hogg notation {self.text!r}, position {i + 1}: expected {expected}, got {got}")

    def peek(self) -> str:
        return self.text[self.i] if self.i < len(self.text) else ""

    def number(self, expected: str) -> tuple[int, int]:
        m = re.compile(r"\d+").match(self.text, self.i)
        if not m:
            raise self.error(expected)
        start, self.i = self.i, m.end()
        return int(m.group()), start


def parse_text(text: str) -> Notation:
    """The parts of a notation; a one-line ParseError naming the position of what is wrong."""
    if not isinstance(text, str):
        raise ParseError("a GomJau-Hogg notation is a text such as 3-4-3,3/m30/r(h2)")
    text = text.strip()
    if len(text) > MAX_TEXT:
        raise ParseError(f"a GomJau-Hogg notation may be at most {MAX_TEXT} characters, got {len(text)}")
    r = _Reader(text)
    seed, at = r.number("a seed polygon (3, 4, 6, 8 or 12)")
    if seed not in SIZES:
        raise r.error("a seed polygon (3, 4, 6, 8 or 12)", at).__class__(
            f"GomJau-Hogg notation {text!r}, position {at + 1}: the seed polygon must be 3, 4, 6, 8 or 12, got {seed}")
    phases: list[tuple[int, ...]] = []
    placed = 1
    while r.peek() == "-":
        r.i += 1
        phase = []
        while True:
            n, at = r.number("a polygon (3, 4, 6, 8 or 12) or 0 to skip an edge")
            if n != 0 and n not in SIZES:
                raise ParseError(f"GomJau-Hogg notation {text!r}, position {at + 1}: a polygon must be "
                                 f"3, 4, 6, 8 or 12 (0 skips an edge), got {n}")
            phase.append(n)
            placed += n != 0
            if r.peek() != ",":
                break
            r.i += 1
        phases.append(tuple(phase))
    if placed > MAX_SEED:
        raise ParseError(f"GomJau-Hogg notation places {placed} polygons before its transforms; at most {MAX_SEED}")
    transforms: list[Transform] = []
    if r.peek() not in ("", "/"):
        raise r.error("'-' (a new phase), ',' (another polygon) or '/' (a transform)")
    while r.peek() == "/":
        r.i += 1
        start = r.i
        action = r.peek()
        if action not in ("m", "r"):
            raise r.error("a transform: m (mirror) or r (rotation)")
        r.i += 1
        angle, point = 180.0, None
        m = re.compile(r"\d+(\.\d+)?").match(text, r.i)
        if m:
            angle = float(m.group())
            if not 0 < angle < 360:
                raise ParseError(f"GomJau-Hogg notation {text!r}, position {r.i + 1}: a transform's angle must be "
                                 f"between 0 and 360 degrees, got {m.group()}")
            r.i = m.end()
        elif r.peek() == "(":
            r.i += 1
            kind = r.peek()
            if kind not in ("c", "h", "v"):
                raise r.error("a point: c (centre), h (edge midpoint) or v (vertex) and its number")
            r.i += 1
            index, at = r.number(f"the number of the {kind} point")
            if index < 1:
                raise ParseError(f"GomJau-Hogg notation {text!r}, position {at + 1}: points are numbered from 1")
            if r.peek() != ")":
                raise r.error("')'")
            r.i += 1
            point = (kind, index)
        if r.peek() not in ("", "/"):
            raise r.error("'/' (another transform) or the end")
        transforms.append(Transform(action, angle, point, text[start:r.i], start))
    return Notation(seed, tuple(phases), tuple(transforms))


# --------------------------------------------------------------------------- stage 1: placement


def _getangle(x: float, y: float) -> float:
    """Antwerp's angle of a direction: atan2, with near-zero snapped to 0 and angles below
    -90° turned by a full turn (so points sort from -90° counter-clockwise)."""
    a = math.atan2(y, x)
    if -_ANGLE_EPS < a < _ANGLE_EPS:
        a = 0.0
    if a < -math.pi / 2 - _ANGLE_EPS:
        a += 2 * math.pi
    return a


def _key(x: float, y: float) -> tuple[int, int]:
    return (round(x * _KEY), round(y * _KEY))


class _Shape:
    __slots__ = ("p", "verts", "centre")

    def __init__(self, p: int, verts: list[tuple[float, float]]) -> None:
        self.p = p
        self.verts = verts
        self.centre = (sum(v[0] for v in verts) / p, sum(v[1] for v in verts) / p)

    def segments(self) -> list[tuple[tuple[float, float], tuple[float, float]]]:
        return [(self.verts[i], self.verts[(i + 1) % self.p]) for i in range(self.p)]

    def mapped(self, m: np.ndarray) -> _Shape:
        pts = np.asarray(self.verts) @ m[:2, :2].T + m[:2, 2]
        return _Shape(self.p, [(float(x), float(y)) for x, y in pts])


def seed_shape(p: int) -> _Shape:
    """The seed at the origin: edges perpendicular to the x axis; a triangle with a vertex at
    the origin and its left edge on the y axis. Unit edges."""
    r = _circumradius(p)
    if p == 3:
        # Antwerp: a triangle from its radius, turned 60°, moved by its radius along x, turned back
        out = []
        for k in range(3):
            a = 2 * math.pi * k / 3 + math.pi / 3
            x, y = r * math.cos(a) + r, r * math.sin(a)
            c, s = math.cos(-math.pi / 3), math.sin(-math.pi / 3)
            out.append((c * x - s * y, s * x + c * y))
        return _Shape(3, out)
    return _Shape(p, [(r * math.cos(2 * math.pi * k / p + math.pi / p), r * math.sin(2 * math.pi * k / p + math.pi / p))
                      for k in range(p)])


def _on_segment(seg: tuple[tuple[float, float], tuple[float, float]], p: int) -> _Shape:
    """A p-gon on the far side of ``seg`` (its end first, as Antwerp builds it)."""
    (x1, y1), (x2, y2) = seg
    verts = [(x2, y2), (x1, y1)]
    step = 2 * math.pi / p
    a = math.atan2(y1 - y2, x1 - x2) + step
    for _ in range(2, p):
        x, y = verts[-1]
        verts.append((x + math.cos(a), y + math.sin(a)))
        a += step
    return _Shape(p, verts)


def _seg_cmp(a, b) -> int:
    def on_y(s):
        return abs(s[0][0]) < _EPS and abs(s[1][0]) < _EPS

    if on_y(a):
        return 1
    if on_y(b):
        return -1
    d = _getangle((a[0][0] + a[1][0]) / 2, (a[0][1] + a[1][1]) / 2) - _getangle((b[0][0] + b[1][0]) / 2,
                                                                               (b[0][1] + b[1][1]) / 2)
    return (d > 0) - (d < 0)


class _Figure:
    """Polygons placed so far, with the count of each edge midpoint (free edges: count 1) and
    the angle sum at each vertex (overlap and non-Euclidean checks)."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.shapes: list[_Shape] = []
        self.centres: dict[tuple[int, int], int] = {}
        self.mids: dict[tuple[int, int], int] = {}
        self.angles: dict[tuple[int, int], float] = {}
        self.grid: dict[tuple[int, int], list[int]] = {}

    def free(self, seg) -> bool:
        (x1, y1), (x2, y2) = seg
        return self.mids.get(_key((x1 + x2) / 2, (y1 + y2) / 2), 0) == 1

    def add(self, shape: _Shape, where: str, *, check: bool = True) -> bool:
        """Add ``shape`` unless one with its centre is there; refuse an overlap (``check``)."""
        ck = _key(*shape.centre)
        gx, gy = math.floor(shape.centre[0] / _CELL), math.floor(shape.centre[1] / _CELL)
        if ck in self.centres and not check:
            return False
        if ck in self.centres:
            other = self.shapes[self.centres[ck]]
            if other.p != shape.p or not _same_corners(other, shape):
                raise GeometryError(f"GomJau-Hogg notation {self.text!r}: {where} puts a {shape.p}-gon on a "
                                    f"{other.p}-gon at ({shape.centre[0]:.3f}, {shape.centre[1]:.3f}): they overlap")
            return False
        for v in shape.verts if check else ():
            k = _key(*v)
            total = self.angles.get(k, 0.0) + _interior(shape.p)
            if total > 360 + 1e-6:
                raise GeometryError(
                    f"GomJau-Hogg notation {self.text!r}: {where} makes the corners at vertex ({v[0]:.3f}, {v[1]:.3f}) "
                    f"sum to {total:.0f}°, more than 360°: the polygons overlap (no Euclidean vertex has that)")
        near = (i for dx in (-1, 0, 1) for dy in (-1, 0, 1) for i in self.grid.get((gx + dx, gy + dy), ()))
        for s in (self.shapes[i] for i in near) if check else ():
            if _overlap(s, shape):
                raise GeometryError(f"GomJau-Hogg notation {self.text!r}: {where} puts a {shape.p}-gon at "
                                    f"({shape.centre[0]:.3f}, {shape.centre[1]:.3f}) over a {s.p}-gon: they overlap")
        for v in shape.verts:
            k = _key(*v)
            self.angles[k] = self.angles.get(k, 0.0) + _interior(shape.p)
        for (x1, y1), (x2, y2) in shape.segments():
            k = _key((x1 + x2) / 2, (y1 + y2) / 2)
            self.mids[k] = self.mids.get(k, 0) + 1
        self.grid.setdefault((gx, gy), []).append(len(self.shapes))
        self.centres[ck] = len(self.shapes)
        self.shapes.append(shape)
        return True


def _same_corners(a: _Shape, b: _Shape) -> bool:
    ka = {_key(*v) for v in a.verts}
    return all(_key(*v) in ka for v in b.verts)


def _overlap(a: _Shape, b: _Shape) -> bool:
    """Whether two convex polygons' interiors meet (separating axes, with a small slack)."""
    dx, dy = a.centre[0] - b.centre[0], a.centre[1] - b.centre[1]
    if math.hypot(dx, dy) >= _circumradius(a.p) + _circumradius(b.p) - 1e-9:
        return False
    for shape in (a, b):
        for (x1, y1), (x2, y2) in shape.segments():
            nx, ny = y2 - y1, x1 - x2
            pa = [nx * x + ny * y for x, y in a.verts]
            pb = [nx * x + ny * y for x, y in b.verts]
            if max(pa) <= min(pb) + 1e-7 or max(pb) <= min(pa) + 1e-7:
                return False
    return True


def place(notation: Notation, text: str = "") -> _Figure:
    """Stage 1: the seed and its phases."""
    fig = _Figure(text or str(notation))
    seed = seed_shape(notation.seed)
    fig.add(seed, "the seed")
    tail = seed.segments()
    for i, phase in enumerate(notation.phases, 1):
        order = sorted(tail, key=cmp_to_key(_seg_cmp))
        group: list = []
        skip = 0
        for j, p in enumerate(phase, 1):
            if p == 0:
                skip += 1
                continue
            s = skip
            for seg in order:
                if fig.free(seg):
                    if s:
                        s -= 1
                        continue
                    shape = _on_segment(seg, p)
                    fig.add(shape, f"phase {i + 1}, polygon {j} ({p})")
                    group += shape.segments()
                    break
            else:
                raise GeometryError(f"GomJau-Hogg notation {fig.text!r}: phase {i + 1} has no free edge left for "
                                    f"polygon {j} ({p}); the phase before it has fewer free edges")
        tail = group
    return fig


# --------------------------------------------------------------------------- stage 2: transforms


def nodes(fig: _Figure) -> list[tuple[str, float, float, float]]:
    """The named points of a figure: (kind, x, y, direction), in Antwerp's order. The direction
    is the point's angle from the origin, or for ``h`` the edge's own direction."""
    pts: dict[tuple[int, int], tuple[str, float, float, float]] = {}
    for s in fig.shapes:
        pts[_key(*s.centre)] = ("c", s.centre[0], s.centre[1], _getangle(*s.centre))
    for s in fig.shapes:
        for (x1, y1), (x2, y2) in s.segments():
            pts[_key(x1, y1)] = ("v", x1, y1, _getangle(x1, y1))
            mx, my = (x1 + x2) / 2, (y1 + y2) / 2
            pts[_key(mx, my)] = ("h", mx, my, _getangle(x2 - x1, y2 - y1))
            pts[_key(x2, y2)] = ("v", x2, y2, _getangle(x2, y2))
    pts.pop((0, 0), None)

    # Antwerp compares angles within 0.001 rad, then distances; distinct points of a figure
    # at nearly one angle are collinear with the origin (their separation, at least 0.28,
    # would need a radius over 280 otherwise), so angles rounded far finer sort the same
    return sorted(pts.values(), key=lambda q: (round(_getangle(q[1], q[2]), 7), math.hypot(q[1], q[2])))


def _point(fig: _Figure, kind: str, index: int) -> tuple[float, float, float] | None:
    n = 0
    for k, x, y, a in nodes(fig):
        if k == kind:
            n += 1
            if n == index:
                return x, y, a
    return None


def _mirror(x: float, y: float, a: float) -> np.ndarray:
    c, s = math.cos(2 * a), math.sin(2 * a)
    lin = np.array([[c, s], [s, -c]])
    m = np.eye(3)
    m[:2, :2] = lin
    m[:2, 2] = np.array([x, y]) - lin @ np.array([x, y])
    return m


def _rotation(a: float, x: float = 0.0, y: float = 0.0) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    lin = np.array([[c, -s], [s, c]])
    m = np.eye(3)
    m[:2, :2] = lin
    m[:2, 2] = np.array([x, y]) - lin @ np.array([x, y])
    return m


def transform_maps(fig: _Figure, t: Transform) -> list[np.ndarray]:
    """The isometries one transform applies, in order, given the figure before it."""
    if t.point is not None:
        got = _point(fig, *t.point)
        if got is None:
            count = sum(1 for k, *_ in nodes(fig) if k == t.point[0])
            raise ParseError(f"GomJau-Hogg notation {fig.text!r}, position {t.position + 1}: {t.text} names "
                             f"{t.point[0]}{t.point[1]}, but the figure has {count} {t.point[0]} points")
        x, y, a = got
        if t.action == "r":
            return [_rotation(math.pi, x, y)]
        return [_mirror(x, y, a if t.point[0] == "h" else a + math.pi / 2)]
    out = []
    a = t.angle
    while a < 360 - 1e-9:
        rad = math.radians(a)
        out.append(_rotation(rad) if t.action == "r" else _mirror(0.0, 0.0, rad - math.pi / 2))
        a *= 2
    return out


def run_transforms(fig: _Figure, transforms: Sequence[Transform]) -> list[np.ndarray]:
    """Stage 2: apply each transform to the figure (adding its images) and return every map."""
    gens = []
    for t in transforms:
        for m in transform_maps(fig, t):
            _linear_code(m, f"GomJau-Hogg notation {fig.text!r}: the transform {t.text}")
            gens.append(m)
            for s in list(fig.shapes):
                fig.add(s.mapped(m), f"the transform {t.text}")
    return gens


# --------------------------------------------------------------------------- the tiling


def _linear_code(m: np.ndarray, where: str) -> tuple[int, int]:
    """(+1, k): a rotation by k steps; (-1, j): a mirror sending direction θ to j·STEP - θ."""
    det = m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0]
    if det > 0:
        a = math.degrees(math.atan2(m[1, 0], m[0, 0]))
        s = 1
    else:
        a = math.degrees(math.atan2(m[1, 0], m[0, 0]))  # = 2 × the mirror's angle
        s = -1
    k = a / STEP
    if abs(k - round(k)) > 1e-6:
        what = (f"rotates by {a % 360:.2f}°, not a multiple of {STEP}°" if s > 0
                else f"mirrors in a line at {(a / 2) % 180:.2f}°, not a multiple of {STEP / 2}°")
        raise GeometryError(f"{where} {what}: its image of the seed cannot meet the seed edge to edge")
    return s, round(k) % _TURN


def _compose_linear(a: tuple[int, int], b: tuple[int, int]) -> tuple[int, int]:
    # a ∘ b on directions θ: rotation θ+k, mirror j-θ
    (sa, ka), (sb, kb) = a, b
    if sa > 0:
        return sb, (ka + kb) % _TURN
    return -sb, (ka - kb) % _TURN


def check_point_group(gens: Sequence[np.ndarray], text: str) -> None:
    """Refuse transforms whose rotations are not 2-, 3-, 4- or 6-fold (crystallographic
    restriction: a pattern with two independent translations has no others)."""
    codes = [_linear_code(g, f"GomJau-Hogg notation {text!r}: a transform") for g in gens]
    for s, k in closure((1, 0), codes, _compose_linear):
        if s > 0 and k % 8 and k % 12:
            raise GeometryError(f"GomJau-Hogg notation {text!r}: the transforms generate a rotation by {k * STEP:g}°; "
                                "a pattern repeating in two directions has only 2-, 3-, 4- and 6-fold rotations")


@dataclass
class Polygons:
    """Polygons as columns: size, centre, orientation (the direction from the centre to a
    corner, in steps of 7.5°, least representative)."""

    size: np.ndarray
    centre: np.ndarray
    orient: np.ndarray

    def corners(self, i: int) -> np.ndarray:
        p = int(self.size[i])
        a = np.radians(self.orient[i] * STEP + 360.0 * np.arange(p) / p)
        return self.centre[i] + _circumradius(p) * np.column_stack([np.cos(a), np.sin(a)])


def _orient_of(shape: _Shape) -> int:
    x, y = shape.verts[0]
    a = math.degrees(math.atan2(y - shape.centre[1], x - shape.centre[0])) / STEP
    if abs(a - round(a)) > 1e-6:
        raise GeometryError("a polygon's corners are not at multiples of 7.5°")
    return round(a) % (_TURN // shape.p)


def close(shapes: Sequence[_Shape], gens: Sequence[np.ndarray], radius: float, text: str) -> tuple[Polygons, bool]:
    """The orbit of the figure under the group of ``gens``, within ``radius`` of the origin
    (breadth first); whether some image fell outside (False: the group is finite)."""
    codes = [_linear_code(g, "a transform") for g in gens]
    size = [s.p for s in shapes]
    centre = [s.centre for s in shapes]
    orient = [_orient_of(s) for s in shapes]
    seen: dict[tuple[int, int], int] = {}
    for i, c in enumerate(centre):
        seen.setdefault(_key(*c), i)
    frontier = np.arange(len(size))
    escaped = False
    while len(frontier):
        fs = np.asarray(size)[frontier]
        fc = np.asarray(centre, dtype=float)[frontier]
        fo = np.asarray(orient)[frontier]
        new = []
        for g, (s, k) in zip(gens, codes):
            c2 = fc @ g[:2, :2].T + g[:2, 2]
            o2 = (fo + k) if s > 0 else (k - fo)
            inside = np.hypot(c2[:, 0], c2[:, 1]) <= radius
            escaped |= not inside.all()
            keys = np.round(c2 * _KEY).astype(np.int64)
            for idx in np.flatnonzero(inside):
                key = (int(keys[idx, 0]), int(keys[idx, 1]))
                p = int(fs[idx])
                o = int(o2[idx]) % (_TURN // p)
                j = seen.get(key)
                if j is None:
                    seen[key] = len(size)
                    new.append(len(size))
                    size.append(p)
                    centre.append((float(c2[idx, 0]), float(c2[idx, 1])))
                    orient.append(o)
                    if len(size) > MAX_POLYGONS:
                        raise GeometryError(f"GomJau-Hogg notation {text!r}: more than {MAX_POLYGONS} polygons within "
                                            f"radius {radius:g}: the transforms' copies do not form a periodic pattern")
                elif size[j] != p or orient[j] != o:
                    raise GeometryError(
                        f"GomJau-Hogg notation {text!r}: the transforms put a {p}-gon on a {size[j]}-gon at "
                        f"({c2[idx, 0]:.3f}, {c2[idx, 1]:.3f}): they overlap")
        frontier = np.asarray(new, dtype=np.int64)
    return Polygons(np.asarray(size), np.asarray(centre, dtype=float).reshape(-1, 2), np.asarray(orient)), escaped


def check_tiling(polys: Polygons, radius: float, text: str) -> str | None:
    """Refuse an overlap (corners summing to more than 360°, an edge of three polygons);
    return where a gap is within ``radius`` (corners summing to less), else None."""
    angle: dict[tuple[int, int], float] = {}
    edges: dict[tuple[int, int], int] = {}
    for i in range(len(polys.size)):
        p = int(polys.size[i])
        pts = polys.corners(i)
        for j, (x, y) in enumerate(pts):
            k = _key(x, y)
            angle[k] = angle.get(k, 0.0) + _interior(p)
            x2, y2 = pts[(j + 1) % p]
            mk = _key((x + x2) / 2, (y + y2) / 2)
            edges[mk] = edges.get(mk, 0) + 1
    r2 = (radius * _KEY) ** 2
    for (kx, ky), total in angle.items():
        if total > 360 + 1e-6:
            raise GeometryError(f"GomJau-Hogg notation {text!r}: the corners at vertex ({kx / _KEY:.3f}, {ky / _KEY:.3f}) "
                                f"sum to {total:.0f}°, more than 360°: the polygons overlap (not a Euclidean vertex)")
    gap = None
    for (kx, ky), total in angle.items():
        if kx * kx + ky * ky <= r2 and total < 360 - 1e-6:
            gap = (f"GomJau-Hogg notation {text!r}: the corners at vertex ({kx / _KEY:.3f}, {ky / _KEY:.3f}) "
                   f"sum to {total:.0f}°, less than 360°: the transforms leave a gap there")
            break
    for (kx, ky), n in edges.items():
        if n > 2:
            raise GeometryError(f"GomJau-Hogg notation {text!r}: {n} polygons share the edge at ({kx / _KEY:.3f}, "
                                f"{ky / _KEY:.3f}): they overlap")
    return gap


def translations(polys: Polygons, radius: float) -> tuple[np.ndarray, np.ndarray] | None:
    """A reduced basis of the translations that map the polygons within ``radius`` into the
    set (checked polygon by polygon), or None if no two independent ones show."""
    keyset = {(_key(*polys.centre[i]), int(polys.size[i]), int(polys.orient[i])) for i in range(len(polys.size))}
    r0 = np.hypot(polys.centre[:, 0], polys.centre[:, 1])
    base = int(np.argmin(r0))
    same = np.flatnonzero((polys.size == polys.size[base]) & (polys.orient == polys.orient[base]))
    cands = polys.centre[same] - polys.centre[base]
    cands = cands[np.argsort(np.hypot(cands[:, 0], cands[:, 1]), kind="stable")]
    found: list[np.ndarray] = []
    for t in cands:
        n = math.hypot(*t)
        if n < 1e-6:
            continue
        if found and abs(found[0][0] * t[1] - found[0][1] * t[0]) < 1e-6 * n:
            continue
        inner = np.flatnonzero(r0 + n <= radius)
        if len(inner) < 4:
            break
        ok = all((_key(*(polys.centre[i] + t)), int(polys.size[i]), int(polys.orient[i])) in keyset for i in inner)
        if ok:
            found.append(t)
            if len(found) == 2:
                return _gauss(found[0], found[1])
    return None


def _gauss(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    while True:
        if a @ a > b @ b:
            a, b = b, a
        mu = round((a @ b) / (a @ a))
        if mu == 0:
            break
        b = b - mu * a
    if a[0] * b[1] - a[1] * b[0] < 0:
        b = -b
    return a, b


def symbol_of(polys: Polygons, v1: np.ndarray, v2: np.ndarray) -> DSymbol:
    """The D-symbol of the tiling modulo the lattice (v1, v2): one chamber per flag (polygon,
    corner, side) of the polygons in a fundamental parallelogram. Not minimal."""
    inv = np.linalg.inv(np.column_stack([v1, v2]))
    frac = polys.centre @ inv.T
    cell = np.floor(frac + 1e-7)
    red = frac - cell
    red[red > 1 - 1e-7] = 0.0
    reps: dict[tuple, int] = {}
    order: list[int] = []
    for i in np.flatnonzero((cell[:, 0] == 0) & (cell[:, 1] == 0)):
        key = (int(polys.size[i]), int(polys.orient[i]), round(red[i, 0] * 1e5), round(red[i, 1] * 1e5))
        if key not in reps:
            reps[key] = len(order)
            order.append(int(i))
    # directed edges and corners of every polygon near the unit
    reach = np.hypot(*(np.abs(v1) + np.abs(v2))) + 6
    near = np.flatnonzero(np.hypot(polys.centre[:, 0], polys.centre[:, 1]) <= reach)
    edge_at: dict[tuple, tuple[int, int]] = {}
    degree: dict[tuple[int, int], int] = {}
    corners = {}
    for i in near:
        pts = polys.corners(int(i))
        corners[int(i)] = [_key(*q) for q in pts]
        p = len(pts)
        for j in range(p):
            degree[corners[int(i)][j]] = degree.get(corners[int(i)][j], 0) + 1
            edge_at[(corners[int(i)][j], corners[int(i)][(j + 1) % p])] = (int(i), j)

    def rep(i: int) -> int:
        key = (int(polys.size[i]), int(polys.orient[i]), round(red[i, 0] * 1e5), round(red[i, 1] * 1e5))
        got = reps.get(key)
        if got is None:
            raise GeometryError("the polygons do not repeat with the translations found")
        return got

    base: list[int] = []
    total = 0
    for i in order:
        base.append(total)
        total += 2 * int(polys.size[i])
    s0, s1, s2, face, deg = [0] * total, [0] * total, [0] * total, [0] * total, [0] * total
    for r, i in enumerate(order):
        p = int(polys.size[i])
        ck = corners[i]
        for j in range(p):
            for s in (0, 1):
                c = base[r] + 2 * j + s
                s1[c] = c ^ 1
                s0[c] = base[r] + (2 * ((j + 1) % p) + 1 if s == 0 else 2 * ((j - 1) % p))
                if s == 0:
                    g, gi = edge_at[(ck[(j + 1) % p], ck[j])]
                    s2[c] = base[rep(g)] + 2 * ((gi + 1) % int(polys.size[g])) + 1
                else:
                    g, gi = edge_at[(ck[j], ck[(j - 1) % p])]
                    s2[c] = base[rep(g)] + 2 * gi
                face[c] = p
                deg[c] = degree[ck[j]]
    return DSymbol(tuple(s0), tuple(s1), tuple(s2), tuple(face), tuple(deg))


@dataclass
class Parsed:
    """A parsed notation: its parts, the polygons of the closed figure, the lattice and the
    tiling's minimal D-symbol."""

    notation: Notation
    polygons: Polygons
    v1: np.ndarray
    v2: np.ndarray
    symbol: DSymbol


def parse(text: str, *, max_radius: float = 96.0) -> Parsed:
    """Parse a GomJau-Hogg notation and return the tiling it draws (see the module text).
    ParseError for bad text, GeometryError for an arrangement that is not a tiling."""
    notation = parse_text(text)
    text = str(notation) if not isinstance(text, str) else text.strip()
    if len(notation.transforms) == 0:
        raise GeometryError(f"GomJau-Hogg notation {text!r} has no transforms ('/m30', '/r(h2)', ...): "
                            "the seed alone does not cover the plane")
    fig = place(notation, text)
    gens = run_transforms(fig, notation.transforms)
    check_point_group(gens, text)
    extent = max(math.hypot(*v) for s in fig.shapes for v in s.verts)
    radius = max(12.0, 2 * extent + 8)
    while True:
        polys, escaped = close(fig.shapes, gens, radius, text)
        if not escaped:
            raise GeometryError(f"GomJau-Hogg notation {text!r}: the transforms make only {len(polys.size)} polygons "
                                "(a finite group): they do not repeat the seed across the plane")
        inner = radius - extent - 4
        gap = check_tiling(polys, inner, text)
        basis = None if gap else translations(polys, inner)
        if basis is not None and np.hypot(*basis[0]) + np.hypot(*basis[1]) + 8 <= inner:
            v1, v2 = basis
            break
        if radius >= max_radius:
            raise GeometryError(gap or f"GomJau-Hogg notation {text!r}: the transforms do not repeat the seed in two "
                                f"independent directions within radius {max_radius:g}")
        radius = min(max_radius, radius * 1.6)
    report = patch_of(polys, np.hypot(*v1) + np.hypot(*v2) + 4).validate()
    if not report:
        raise GeometryError(f"GomJau-Hogg notation {text!r}: the polygons overlap ({report})")
    symbol = symbol_of(polys, v1, v2).minimal_image()
    return Parsed(notation, polys, v1, v2, symbol)


def patch_of(polys: Polygons, radius: float) -> Patch:
    """The polygons whose centres lie within ``radius`` as a Patch of unit regular polygons."""
    keep = np.flatnonzero(np.hypot(polys.centre[:, 0], polys.centre[:, 1]) <= radius)
    sizes = sorted({int(p) for p in polys.size[keep]})
    transforms = []
    for i in keep:
        c = polys.corners(int(i))
        a = math.atan2(c[1, 1] - c[0, 1], c[1, 0] - c[0, 0])
        m = _rotation(a)
        m[:2, 2] = c[0]
        transforms.append(m)
    protos = [Prototile(regular_polygon(p), name=f"{p}-gon") for p in sizes]
    return Patch(protos, [sizes.index(int(p)) for p in polys.size[keep]], np.array(transforms).reshape(-1, 3, 3))


# --------------------------------------------------------------------------- writing


class _Placed:
    """A tiling in the plane as polygons modulo a lattice: lookups by centre."""

    def __init__(self, unit: Polygons, v1: np.ndarray, v2: np.ndarray) -> None:
        self.unit, self.v1, self.v2 = unit, v1, v2
        self.inv = np.linalg.inv(np.column_stack([v1, v2]))
        self.keys = {self._key(unit.centre[i], int(unit.size[i]), int(unit.orient[i])) for i in range(len(unit.size))}

    def _key(self, c: np.ndarray, p: int, o: int) -> tuple:
        f = self.inv @ np.asarray(c, dtype=float)
        f = f - np.floor(f + 1e-7)
        f[f > 1 - 1e-7] = 0.0
        return (p, o % (_TURN // p), round(f[0] * 1e5), round(f[1] * 1e5))

    def has(self, c, p: int, o: int) -> bool:
        return self._key(c, p, o) in self.keys

    def is_symmetry(self, m: np.ndarray) -> bool:
        try:
            s, k = _linear_code(m, "")
        except GeometryError:
            return False
        # g(P + t) = g(P) + A t: the linear part must keep the lattice, then the unit decides
        for v in (self.v1, self.v2):
            f = self.inv @ (m[:2, :2] @ v)
            if np.abs(f - np.round(f)).max() > 1e-6:
                return False
        c2 = self.unit.centre @ m[:2, :2].T + m[:2, 2]
        for i in range(len(self.unit.size)):
            p = int(self.unit.size[i])
            o = int(self.unit.orient[i])
            if not self.has(c2[i], p, (o + k) if s > 0 else (k - o)):
                return False
        return True

    def across(self, seg) -> int:
        """The size of the polygon on the far side of ``seg`` (as _on_segment would put it)."""
        for p in SIZES:
            sh = _on_segment(seg, p)
            if self.has(np.array(sh.centre), p, _orient_of(sh)):
                return p
        raise GeometryError("no polygon of the tiling lies across an edge")


def _polygons_of(shapes: Sequence[_Shape]) -> Polygons:
    return Polygons(np.array([s.p for s in shapes]), np.array([s.centre for s in shapes], dtype=float).reshape(-1, 2),
                    np.array([_orient_of(s) for s in shapes]))


def _unit_of(symbol: DSymbol) -> tuple[list[_Shape], list[list[int]], np.ndarray, np.ndarray]:
    """The tiling of ``symbol`` laid out (realize.py): its unit's polygons, the chamber of
    each polygon's flag (corner j, edge j to j+1, the polygon) for every j, and the lattice."""
    # start-up cost: the notation and search modules (NumPy, shapely) load only when used
    from tilekit.plugins.kuniform.realize import faces, layout

    flags, v1, v2 = layout(symbol)
    inv = np.linalg.inv(np.column_stack([v1, v2]))
    out, chambers = [], []
    for p, centre, m, c in faces(symbol, flags):
        f = inv @ centre
        if np.all(np.floor(f + 1e-7) == 0):
            # the unit polygon: first edge from the origin along +x, counter-clockwise
            pts = [(0.0, 0.0)]
            ang = 0.0
            for _ in range(p - 1):
                pts.append((pts[-1][0] + math.cos(ang), pts[-1][1] + math.sin(ang)))
                ang += 2 * math.pi / p
            q = np.asarray(pts) @ m[:2, :2].T + m[:2, 2]
            out.append(_Shape(p, [(float(x), float(y)) for x, y in q]))
            # corner 0's flag is chamber c; σ0 moves to corner 1 along the edge, σ1 turns to
            # the edge 1-2 in the same polygon: corner j's forward flag is (σ1σ0)^j c
            walk = [c]
            for _ in range(p - 1):
                walk.append(symbol.s1[symbol.s0[walk[-1]]])
            chambers.append(walk)
    return out, chambers, np.asarray(v1, dtype=float), np.asarray(v2, dtype=float)


def _placements(unit: Sequence[_Shape], chambers: Sequence[Sequence[int]],
                s1: Sequence[int]) -> Iterator[tuple[int, np.ndarray, int]]:
    """Candidate isometries putting a polygon of the unit on the seed (each corner, both
    hands): (seed size, map, chamber of the flag put on the seed's), largest polygons first.
    The flag of corner j, the edge to corner j - 1 (``flip``), is σ1 of corner j's forward flag."""
    for p in sorted({s.p for s in unit}, reverse=True):
        seed = seed_shape(p)
        for s, walk in zip(unit, chambers):
            if s.p == p:
                for flip in (False, True):
                    for j in range(p):
                        yield p, _fit(s, seed, j, flip), (s1[walk[j]] if flip else walk[j])


def _fit(s: _Shape, seed: _Shape, j: int, flip: bool) -> np.ndarray:
    """The isometry mapping corner j of ``s`` and its next corner (the one before when
    ``flip``, a mirror image) onto corners 0 and 1 of ``seed``."""
    p = s.p
    a0 = np.array(s.verts[j])
    a1 = np.array(s.verts[(j - 1) % p] if flip else s.verts[(j + 1) % p])
    b0, b1 = np.array(seed.verts[0]), np.array(seed.verts[1])
    da, db = a1 - a0, b1 - b0
    lin = np.eye(3)
    if flip:
        lin = np.diag([1.0, -1.0, 1.0])
        da = np.array([da[0], -da[1]])
    lin = _rotation(math.atan2(db[1], db[0]) - math.atan2(da[1], da[0])) @ lin
    lin[:2, 2] = b0 - lin[:2, :2] @ a0
    return lin


#: Centre transforms tried, most symmetric first.
_CENTRE = ("m30", "r60", "m45", "r90", "m60", "r120", "m90", "r", "m")
#: How many placements (one per flag orbit, see :func:`write_outcome`) the writer tries for
#: one tiling before it gives up. Every k <= 4 tiling that has a written notation gets it from
#: the first placement tried (measured; docs/families/k-uniform.md); a failing try costs about
#: a second (up to ``max_phases`` phases), so the cap bounds a tiling to a few seconds.
MAX_PLACEMENTS = 4


def ungenerable(symbol: DSymbol) -> str | None:
    """Why no notation can draw the tiling of ``symbol``, or None. The transforms are
    rotations about the origin, half-turns and mirrors; without a half-turn or two mirrors
    that cross among the tiling's symmetries (groups p1, p3, pg, pm, cm) they generate a
    finite group, or translations in one direction only. Read from the symbol's orbifold:
    a <σi, σj>-orbit of n chambers is a corner point (two mirrors) when it holds a chamber
    that σi or σj fixes and v = m_ij / n > 1, and a cone point of order v = m_ij / (n / 2)
    otherwise (m01 the face size, m12 the degree, m02 = 2); a half-turn is a cone point of
    even order."""
    m = {(0, 1): symbol.face, (1, 2): symbol.degree, (0, 2): (2,) * symbol.size}
    for (i, j), mij in m.items():
        si, sj = symbol.sigma(i), symbol.sigma(j)
        for orbit in symbol.orbits(i, j):
            n = len(orbit)
            bounded = any(si[c] == c or sj[c] == c for c in orbit)
            v = mij[orbit[0]] / (n if bounded else n / 2)
            if (bounded and v > 1) or (not bounded and round(v) % 2 == 0):
                return None
    return "its symmetry group has no half-turn and no two crossing mirrors (p1, p3, pg, pm or cm)"


def write_outcome(symbol: DSymbol, *, max_phases: int = 12, max_placements: int | None = MAX_PLACEMENTS,
                  verify: bool = False) -> tuple[str | None, str]:
    """(text, "") as :func:`write` writes it, or (None, why there is none).

    Placements: a placement is the isometry putting one flag (corner, edge, polygon) of the
    tiling on the seed's first flag; it is unique for the flag. If a symmetry g of the tiling
    maps flag f to f', the placements m (of f) and m' (of f') satisfy m = m' g, so they put
    the tiling in the same place, m(T) = m'(g(T)) = m'(T). The writer reads only that placed
    tiling (which polygons it holds, which isometries keep it), never the unit or the basis it
    was given, so both give the same text or both none. Flags related by a symmetry lie in one
    chamber of the symbol, so trying the placements in the exhaustive order but only the first
    of each chamber returns the exhaustive writer's text: the first placement that succeeds is
    the first of its chamber, since any earlier one of that chamber would succeed too (tests:
    identical strings for every tiling to k = 4). That cuts the tries by the order of the
    point group (at most 12); ``max_placements`` (None: no cap) bounds them further, and each
    try is bounded by ``max_phases``."""
    symbol = DSymbol.decode(symbol.encode())
    why = ungenerable(symbol)
    if why is not None:
        return None, why
    target = symbol.canonical_form()
    unit, chambers, v1, v2 = _unit_of(symbol)
    tried: set[int] = set()
    for p, m, chamber in _placements(unit, chambers, symbol.s1):
        if chamber in tried:
            continue
        if max_placements is not None and len(tried) >= max_placements:
            return None, f"none found in the writer's budget of {max_placements} placements"
        tried.add(chamber)
        text = _write_placed([s.mapped(m) for s in unit], m[:2, :2] @ v1, m[:2, :2] @ v2, p, max_phases)
        if text is None:
            continue
        if not verify:
            return text, ""
        try:
            got = parse(text)
        except (GeometryError, ParseError):
            continue
        if got.symbol.canonical_form() == target:
            return text, ""
    return None, f"none found: every one of the {len(tried)} placements (one per flag orbit) failed"


def write(symbol: DSymbol, *, max_phases: int = 12, max_placements: int | None = MAX_PLACEMENTS,
          verify: bool = False) -> str | None:
    """A GomJau-Hogg notation for the tiling of ``symbol`` that :func:`parse` reads back to
    the same minimal symbol, or None when the tiling has none or the writer finds none within
    its budget (:func:`write_outcome` says which).

    Why the text is right without parsing it: every transform chosen is a symmetry of the
    tiling, the seed's polygons are the tiling's and include one of each orbit of the
    lattice, and the transforms generate the whole lattice, so the seed's orbit is the
    tiling. ``verify`` parses it back all the same (the tests do, for every record)."""
    return write_outcome(symbol, max_phases=max_phases, max_placements=max_placements, verify=verify)[0]


def _write_placed(unit: list[_Shape], v1: np.ndarray, v2: np.ndarray, seed: int, max_phases: int) -> str | None:
    tiling = _Placed(_polygons_of(unit), v1, v2)
    fig = _Figure("")
    first = seed_shape(seed)
    if not tiling.has(np.array(first.centre), seed, _orient_of(first)):
        return None
    fig.add(first, "the seed")
    phases: list[list[int]] = []
    tail = first.segments()
    for _ in range(max_phases):
        text = _add_transforms(tiling, fig, seed, phases)
        if text is not None:
            return text
        order = sorted(tail, key=cmp_to_key(_seg_cmp))
        group: list = []
        phase: list[int] = []
        for seg in order:
            if not fig.free(seg):
                continue
            p = tiling.across(seg)
            shape = _on_segment(seg, p)
            fig.add(shape, "", check=False)
            group += shape.segments()
            phase.append(p)
        if not phase:
            return None
        phases.append(phase)
        tail = group
    return None


class _Group:
    """The group generated by some symmetries of a placed tiling: its linear parts with a
    representative each, and its translations as an integer lattice in the tiling's lattice
    coordinates (Hermite form: (a, b), (0, d)). By Schreier's lemma the translations are
    generated by rep(gx)^-1 g rep(x) over representatives x and generators g."""

    def __init__(self, maps: Sequence[np.ndarray], inv: np.ndarray) -> None:
        self.inv = inv
        self.reps: dict[tuple[int, int], np.ndarray] = {(1, 0): np.eye(3)}
        frontier = [np.eye(3)]
        while frontier:
            e = frontier.pop()
            for g in maps:
                x = g @ e
                c = _linear_code(x, "")
                if c not in self.reps:
                    self.reps[c] = x
                    frontier.append(x)
        vecs = [self._translation(g @ e) for e in self.reps.values() for g in maps]
        self.a, self.b, self.d = _hermite(vecs)

    def _translation(self, x: np.ndarray) -> tuple[int, int]:
        t = np.linalg.inv(self.reps[_linear_code(x, "")]) @ x
        f = self.inv @ t[:2, 2]
        return round(f[0]), round(f[1])

    def contains(self, g: np.ndarray) -> bool:
        if _linear_code(g, "") not in self.reps:
            return False
        x, y = self._translation(g)
        if self.a == 0:
            return x == 0 and (y == 0 if self.d == 0 else y % self.d == 0)
        if x % self.a:
            return False
        y -= self.b * (x // self.a)
        return y == 0 if self.d == 0 else y % self.d == 0

    @property
    def index(self) -> float:
        """The index of the translations in the tiling's lattice (inf below rank 2)."""
        return math.inf if self.a == 0 or self.d == 0 else float(abs(self.a * self.d))


def _hermite(vecs: Sequence[tuple[int, int]]) -> tuple[int, int, int]:
    """(a, b, d) with the vectors' integer span = {(a i, b i + d j)}, a >= 0, d >= 0."""
    rows = [list(v) for v in vecs if v != (0, 0)]
    pivot = None
    while True:
        xs = [r for r in rows if r[0] != 0]
        if len(xs) <= 1:
            pivot = xs[0] if xs else None
            break
        m = min(xs, key=lambda r: abs(r[0]))
        for r in xs:
            if r is not m:
                q = r[0] // m[0]
                r[0] -= q * m[0]
                r[1] -= q * m[1]
    d = 0
    for r in rows:
        if r is not pivot:
            d = math.gcd(d, abs(r[1]))
    if pivot is None:
        return 0, 0, d
    a, b = pivot
    if a < 0:
        a, b = -a, -b
    if d:
        b %= d
    return a, b, d


def _add_transforms(tiling: _Placed, fig0: _Figure, seed: int, phases: list[list[int]]) -> str | None:
    """Choose transforms for a seed: the largest centre transform that is a symmetry, then
    half-turns and mirrors at points of the figure, each kept when it is not yet in the group
    generated, until that group holds every translation; None unless the seed's orbit under
    it then meets every polygon orbit."""
    head = "-".join([str(seed), *(",".join(map(str, ph)) for ph in phases)])
    fig = _Figure("")
    for s in fig0.shapes:
        fig.add(s, "", check=False)
    chosen: list[str] = []
    maps: list[np.ndarray] = []
    for text in _CENTRE:
        t = parse_text(f"3/{text}").transforms[0]
        ms = transform_maps(fig, t)
        if all(tiling.is_symmetry(m) for m in ms):
            chosen.append(text)
            maps += ms
            for m in ms:
                for s in list(fig.shapes):
                    fig.add(s.mapped(m), "", check=False)
            break
    group = _Group(maps, tiling.inv)
    reach = max(math.hypot(*v) for s in fig0.shapes for v in s.verts) + 1e-6
    for _round in range(8):
        if group.index <= 1:
            break
        improved = False
        counts = {"c": 0, "h": 0, "v": 0}
        for kind, x, y, a in nodes(fig):
            counts[kind] += 1
            if math.hypot(x, y) > reach:
                continue  # points far out make the figure, and the disc a parse needs, large
            for action in ("r", "m"):
                if action == "r":
                    m = _rotation(math.pi, x, y)
                else:
                    m = _mirror(x, y, a if kind == "h" else a + math.pi / 2)
                if not tiling.is_symmetry(m) or group.contains(m):
                    continue
                chosen.append(f"{action}({kind}{counts[kind]})")
                maps.append(m)
                group = _Group(maps, tiling.inv)
                for s in list(fig.shapes):
                    fig.add(s.mapped(m), "", check=False)
                improved = True
                break
            if improved:
                break
        if not improved:
            return None
    if group.index > 1:
        return None
    # the seed's images under the group (modulo the lattice it now holds) must meet every
    # orbit of polygons, else the seed is too small
    seen = set()
    for r in group.reps.values():
        s_, k = _linear_code(r, "")
        for sh in fig0.shapes:
            o = _orient_of(sh)
            c = r[:2, :2] @ np.asarray(sh.centre) + r[:2, 2]
            seen.add(tiling._key(c, sh.p, (o + k) if s_ > 0 else (k - o)))
    if not seen >= tiling.keys:
        return None
    return "/".join([head, *chosen])
