"""The backtracking patch builder shared by every family (§2.4, exercise 6.2).

Polygonal prototiles (optionally with edge labels) are placed edge to edge against the
open edges of a growing patch, taken from a frontier (breadth-first by default). Each
candidate placement is checked against its neighbours (a grid hash over tile bounding
boxes, then an exact separating-axis test with a tolerance on convex pieces), against the
angle sums of the vertices it touches, and against a pluggable local rule called for every
vertex it changes (``closed`` when a vertex becomes surrounded, ``open`` otherwise).
Backtracking uses an explicit stack, so there is no recursion limit, and the search order is
fixed by the inputs, so results are deterministic.

With ``period=(v1, v2)`` the builder tiles a torus instead: every placement stands for its
whole orbit under the lattice of v1 and v2. One representative per orbit lies in a
fundamental domain round the seed; its images in the surrounding block of lattice cells are
placed as real tiles, so overlap, edge matching, vertex angle sums and the rule see the
neighbours across the domain's boundary, and only the representatives' open edges are
filled. The default goal is then a closed torus (no open edge left on a representative).

The result is honest: ``complete`` with a patch that meets the goal, ``exhausted`` when every
branch died (a proof, for a radius goal, that no edge-to-edge patch covering the disc of that
radius around the seed exists), or ``limit`` when the node or time budget ran out.
"""

from __future__ import annotations

import heapq
import math
import time
from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from tilekit.budget import Budget
from tilekit.errors import GeometryError, ParameterError
from tilekit.geometry import Affine, snap_noise
from tilekit.limits import DEFAULT_SOLVER_SECONDS
from tilekit.polygon import (
    StarIndex,
    cyclic_equal,
    ear_clip,
    edge_signature,
    interior_angles,
    signature_rotations,
)
from tilekit.tiling import Patch, Prototile

TWO_PI = 2.0 * math.pi
#: Angles (radians) closer than this are equal.
ANGLE_TOL = 1e-6

ORDERS = ("bfs", "dfs", "nearest")


# --------------------------------------------------------------------------- public types


@dataclass(frozen=True)
class Corner:
    """One tile corner at a vertex: the tile, its prototile, the prototile's vertex index,
    the interior angle, and the direction (radians) of the corner's first (CCW-most
    clockwise) edge, so corners sorted by ``start`` go counter-clockwise round the vertex."""

    tile: int
    prototile: int
    index: int
    angle: float
    start: float


@dataclass(frozen=True)
class VertexView:
    """What a rule sees of one vertex of the patch.

    ``fans`` are the maximal runs of corners that abut one another, in counter-clockwise
    order; ``gaps[i]`` is the uncovered angle after ``fans[i]`` (before the next fan). A
    closed vertex has one fan and no gap.
    """

    point: tuple[float, float]
    closed: bool
    angle_sum: float
    fans: tuple[tuple[Corner, ...], ...]
    gaps: tuple[float, ...]

    @property
    def corners(self) -> tuple[Corner, ...]:
        return tuple(c for fan in self.fans for c in fan)


class VertexRule(Protocol):
    """A local acceptance rule: ``closed(view)`` for a surrounded vertex, ``open(view)`` for
    a partly surrounded one. Either returns True to accept. ``describe()`` names the rule."""

    def closed(self, view: VertexView) -> bool: ...

    def open(self, view: VertexView) -> bool: ...


@dataclass
class BuildStats:
    """Search statistics. ``nodes``: candidate placements examined; ``placements``: tiles
    placed; ``backtracks``: tiles removed; ``max_tiles``: the largest patch seen;
    ``max_radius``: the largest covered disc (radius goal) seen on any branch."""

    nodes: int = 0
    placements: int = 0
    backtracks: int = 0
    seconds: float = 0.0
    reason: str = ""
    max_tiles: int = 0
    max_radius: float = 0.0
    rejections: dict[str, int] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            "nodes": self.nodes,
            "placements": self.placements,
            "backtracks": self.backtracks,
            "seconds": round(self.seconds, 6),
            "reason": self.reason,
            "max_tiles": self.max_tiles,
            "max_radius": round(self.max_radius, 6),
            "rejections": dict(self.rejections),
        }


@dataclass
class BuildResult:
    """``status`` is ``complete`` (``patch`` meets the goal), ``exhausted`` (no patch meeting
    the goal exists from this seed) or ``limit`` (gave up; ``patch`` is None)."""

    status: str
    patch: Patch | None
    stats: BuildStats

    @property
    def ok(self) -> bool:
        return self.status == "complete"

    def __bool__(self) -> bool:
        return self.ok


def labels_match(a: Hashable, b: Hashable) -> bool:
    """The rule of exercise 6.2: a shared edge carries labels i and -i (unlabelled edges
    match only unlabelled edges)."""
    if a is None or b is None:
        return a is None and b is None
    try:
        return a == -b  # type: ignore[operator]
    except TypeError:
        return False


# --------------------------------------------------------------------------- internals

#: Fractional lattice coordinates of the fundamental domain are [-a, 1 - a) with this a: a
#: generic number, so that no tile centroid of a regular tiling falls on the boundary.
_DOMAIN_OFFSET = 0.4142135623730951


def _lattice(period: Sequence[Sequence[float]]) -> np.ndarray:
    """Validate ``period=(v1, v2)``: a (2, 2) array of two independent lattice vectors."""
    try:
        lat = np.asarray(period, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"period={period!r} must be two lattice vectors ((x1, y1), (x2, y2))") from None
    if lat.shape != (2, 2) or not np.all(np.isfinite(lat)):
        raise ParameterError(f"period={period!r} must be two lattice vectors ((x1, y1), (x2, y2))")
    if abs(float(np.linalg.det(lat))) <= 1e-9 * max(1.0, float(np.abs(lat).max()) ** 2):
        raise ParameterError(f"period={period!r}: the two lattice vectors are parallel (the cell has no area)")
    return lat



def _segment_distance(p: np.ndarray, q: np.ndarray, cx: float, cy: float) -> float:
    px, py, qx, qy = float(p[0]), float(p[1]), float(q[0]), float(q[1])
    dx, dy = qx - px, qy - py
    len2 = dx * dx + dy * dy
    u = 0.0 if len2 == 0 else max(0.0, min(1.0, ((cx - px) * dx + (cy - py) * dy) / len2))
    return math.hypot(px + u * dx - cx, py + u * dy - cy)


def _pad(pts: np.ndarray, k: int) -> np.ndarray:
    if len(pts) == k:
        return pts
    return np.vstack([pts, np.repeat(pts[-1:], k - len(pts), axis=0)])


def _normals(padded: np.ndarray) -> np.ndarray:
    """Unit outward-ish edge normals of padded convex pieces (..., K, 2); zero-length padding
    edges get the first real normal (a repeated axis is harmless in the SAT test)."""
    d = np.roll(padded, -1, axis=-2) - padded
    n = np.stack([d[..., 1], -d[..., 0]], axis=-1)
    length = np.linalg.norm(n, axis=-1, keepdims=True)
    good = length[..., 0] > 1e-12
    n = np.where(good[..., None], n / np.where(length > 1e-12, length, 1.0), 0.0)
    if n.ndim == 2:
        first = n[np.argmax(good)]
        n[~good] = first
    else:
        first = n[np.arange(len(n)), np.argmax(good, axis=-1)]
        n = np.where(good[..., None], n, first[:, None, :])
    return n


@dataclass
class _Candidate:
    prototile: int
    variant: int
    edge: int  # variant edge index placed against the open edge
    length: float
    label: Hashable
    local: np.ndarray  # (k, 2) outline with edge `edge` from (0,0) to (length,0)
    angles: np.ndarray  # (k,) interior angles aligned with local
    labels: tuple[Hashable, ...]  # per local edge
    vertex_map: tuple[int, ...]  # local vertex -> prototile vertex index
    pieces: np.ndarray  # (c, K, 2) convex pieces, padded
    normals: np.ndarray  # (c, K, 2) the pieces' unit edge normals
    proj_min: np.ndarray  # (c, K) each piece's projection on its own normals: min
    proj_max: np.ndarray  # (c, K) and max
    base: np.ndarray  # 3x3 map from prototile coordinates to the local frame
    outline_next: np.ndarray  # (k, 2) local outline rolled by one (edge ends)


@dataclass
class _Tile:
    cand: int
    transform: np.ndarray
    points: np.ndarray
    vids: list[int]
    new_vids: list[int]
    edges: list[tuple[int, int]]
    pieces: list[int]
    cells: list[tuple[int, int]]
    bbox: tuple[float, float, float, float]



@dataclass
class _Run:
    """One call of :meth:`PatchBuilder.build`: its goal, statistics and budget."""

    tiles: int | None
    radius: float | None
    fill: Callable[[dict[str, Any]], bool] | None
    periodic: bool
    stats: BuildStats
    started: float
    budget: Budget | None
    max_nodes: int

    def goal_text(self) -> str:
        if self.tiles is not None:
            return f"{self.tiles} tiles"
        if self.radius is not None:
            return f"the disc of radius {self.radius:g}"
        return "every edge the fill predicate asks for" if self.fill is not None else "a closed torus"

    def over_budget(self, strict: bool) -> bool:
        """Node or CPU-time budget spent. Between failed candidates the clock is read every 64
        nodes only (``strict=False``); after a placement, always."""
        if self.stats.nodes >= self.max_nodes:
            return True
        if self.budget is None:
            return False
        if not strict and (self.stats.nodes & 63) != 0:
            return False
        return self.budget.spent()


Edge = tuple[int, int]


class _Frontier:
    """The open edges of the patch, in a heap keyed by the builder's order and kept up to
    date incrementally, so choosing the next edge costs O(log n), never a scan of every open
    edge (which made periodic, fill and callable-order builds quadratic).

    Static orders (bfs, dfs, nearest) key an edge once, when it opens. A callable order or a
    fill predicate may read an edge's ``angle_sum``, which changes as tiles are placed and
    undone round its end points: such edges are marked dirty when an end point's angle sum
    changes and re-keyed (or, for ``fill``, re-asked) before the next choice, with a version
    number per edge so that superseded heap entries are skipped. Every open edge has exactly
    one live entry with its current key, and keys end with the edge's serial number, so the
    choice is the same as the scan's minimum. With a period, edges of lattice images are
    never chosen (they are filled through their representative)."""

    def __init__(self, builder: PatchBuilder, radius: float | None, fill: Callable[[dict[str, Any]], bool] | None) -> None:
        self.b = builder
        self.order = builder.order
        self.fill = fill
        self.limit = None if radius is None else radius - builder.tol
        self.dynamic = callable(self.order) or fill is not None
        self.heap: list[tuple[Any, int, int, Edge]] = []  # (key, serial, version, edge)
        self.dheap: list[tuple[float, int, Edge]] = []  # (distance, serial, edge): the covered disc
        self.version: dict[Edge, int] = {}
        self.dirty: set[Edge] = set()
        self.at_vertex: dict[int, set[Edge]] = {}

    def opened(self, e: Edge, image: bool = False) -> None:
        """``e`` became open: placed with no partner, or its partner was undone. ``image``: it
        belongs to a lattice image on a torus, never chosen, so it is not queued at all."""
        if image:
            return
        _, _, serial, dist = self.b._edges[e]
        if self.limit is not None:  # the covered disc matters for a radius goal only
            heapq.heappush(self.dheap, (dist, serial, e))
        if self.dynamic:
            for v in e:
                self.at_vertex.setdefault(v, set()).add(e)
            self.dirty.add(e)
        else:
            order = self.order
            key: Any = serial if order == "bfs" else (-serial if order == "dfs" else (round(dist, 9), serial))
            heapq.heappush(self.heap, (key, serial, 0, e))

    def closed(self, e: Edge) -> None:
        """``e`` stopped being open (its heap entries die lazily)."""
        if self.dynamic:
            for v in e:
                edges = self.at_vertex.get(v)
                if edges is not None:
                    edges.discard(e)

    def touched(self, vertices: Sequence[int]) -> None:
        """The angle sums at ``vertices`` changed: re-key their open edges before the next choice."""
        if self.dynamic:
            for v in vertices:
                self.dirty.update(self.at_vertex.get(v, ()))

    def _live(self, e: Edge, serial: int) -> bool:
        return e in self.b._open and self.b._edges[e][2] == serial

    def _rekey(self) -> None:
        b, canon = self.b, (self.b._canon if self.b.period is not None else None)
        for e in self.dirty:
            if e not in b._open:
                continue
            info = b._edges[e]
            if canon is not None and info[0] not in canon:
                continue
            if self.limit is not None and info[3] >= self.limit:
                continue
            version = self.version.get(e, 0) + 1
            self.version[e] = version
            data = b._edge_info(e)
            if self.fill is not None and not self.fill(data):
                continue
            order = self.order
            if order == "bfs":
                key: Any = info[2]
            elif order == "dfs":
                key = -info[2]
            elif order == "nearest":
                key = (round(info[3], 9), info[2])
            else:
                key = (order(data), info[2])
            heapq.heappush(self.heap, (key, info[2], version, e))
        self.dirty.clear()

    def choose(self) -> tuple[Edge | None, float]:
        """The open edge to fill next (None: none left that the goal wants) and the radius of
        the disc round the centre that the patch covers (the nearest open edge's distance)."""
        if self.dirty:
            self._rekey()
        dheap = self.dheap
        while dheap and not self._live(dheap[0][2], dheap[0][1]):
            heapq.heappop(dheap)
        covered = dheap[0][0] if dheap else math.inf
        heap, b = self.heap, self.b
        canon = b._canon if b.period is not None else None
        while heap:
            _, serial, version, e = heap[0]
            if not self._live(e, serial) or (self.dynamic and self.version.get(e) != version):
                heapq.heappop(heap)
                continue
            info = b._edges[e]
            if canon is not None and info[0] not in canon:
                heapq.heappop(heap)  # an image's edge: filled through its representative
                continue
            if self.limit is not None and info[3] >= self.limit:
                heapq.heappop(heap)  # outside the disc for good: its distance never changes
                continue
            return e, covered
        return None, covered


class PatchBuilder:
    """Grow patches of ``prototiles`` edge to edge with backtracking.

    ``compatible(a, b)`` decides whether edge labels a (existing tile) and b (new tile) may
    share an edge (default :func:`labels_match`, the i / -i rule); ``reflections`` allows
    mirror images; ``rule`` is a :class:`VertexRule`; ``order`` picks the open edge to fill
    next: ``bfs`` (oldest first, exercise 6.2), ``dfs`` (newest first), ``nearest``
    (closest to the seed's centre first) or a callable ``key(edge) -> sortable`` where
    ``edge`` is a dict with ``serial``, ``distance``, ``midpoint``, ``angle_sum``.
    ``angle_check`` rejects a placement early when a vertex's remaining angle is no sum of
    corner angles of the prototiles (off: such dead ends are found later, by overlap).
    ``period=(v1, v2)``: two independent lattice vectors; patches are built on the torus
    R^2 / (Z v1 + Z v2) (see the module docstring).
    """

    def __init__(
        self,
        prototiles: Sequence[Prototile],
        *,
        reflections: bool = False,
        compatible: Callable[[Hashable, Hashable], bool] | None = None,
        rule: VertexRule | None = None,
        order: str | Callable[[dict[str, Any]], Any] = "bfs",
        tolerance: float = 1e-6,
        angle_check: bool = True,
        period: Sequence[Sequence[float]] | None = None,
    ) -> None:
        if not prototiles:
            raise ParameterError("the builder needs at least one prototile")
        self.period = None if period is None else _lattice(period)
        if isinstance(order, str) and order not in ORDERS:
            raise ParameterError(f"builder order {order!r} is not one of {', '.join(ORDERS)} or a callable")
        self.prototiles = list(prototiles)
        self.reflections = reflections
        self.compatible = compatible or labels_match
        self.rule = rule
        self.order = order
        self.angle_check = angle_check
        scale = max(
            float(np.linalg.norm(np.roll(p.outline, -1, axis=0) - p.outline, axis=1).max())
            for p in self.prototiles
        )
        self.scale = scale
        self.tol = tolerance * scale
        shortest = min(
            float(np.linalg.norm(np.roll(p.outline, -1, axis=0) - p.outline, axis=1).min())
            for p in self.prototiles
        )
        #: Angles measured from edge directions are trusted to this: vertices merge within
        #: 2 tol, so a direction along the shortest edge may turn by up to 4 tol / length.
        self.angle_tol = max(ANGLE_TOL, 4 * self.tol / shortest)
        self._prepare()

    # ------------------------------------------------------------------ preparation
    def _prepare(self) -> None:
        variants: list[tuple[int, np.ndarray, tuple, tuple, np.ndarray]] = []
        signatures: list[tuple[int, list[tuple]]] = []
        for p, proto in enumerate(self.prototiles):
            k = len(proto.outline)
            labels = proto.edge_labels if proto.edge_labels is not None else (None,) * k
            forms = [(proto.outline.copy(), tuple(labels), tuple(range(k)), np.eye(3))]
            if self.reflections:
                refl = proto.outline * np.array([1.0, -1.0])
                pts = refl[::-1].copy()
                vmap = tuple((k - 1 - i) for i in range(k))
                rl = tuple(labels[(k - 2 - i) % k] for i in range(k))
                forms.append((pts, rl, vmap, Affine.scaling(1.0, -1.0)))
            for pts, labs, vmap, base in forms:
                sig = self._signature(pts, labs)
                if any(q == p and cyclic_equal(sig, s) for q, s in signatures):
                    continue  # the mirror image is a rotated copy: no new placements
                signatures.append((p, sig))
                variants.append((p, pts, labs, vmap, base))
        self._variants = variants
        convex_pieces: list[list[np.ndarray]] = []
        kmax = 3
        for _, pts, _, _, _ in variants:
            ang = interior_angles(pts)
            if np.all(ang <= math.pi + ANGLE_TOL):
                pieces = [pts]
            else:
                pieces = ear_clip(pts)
            convex_pieces.append(pieces)
            kmax = max(kmax, max(len(pc) for pc in pieces), len(pts))
        self._K = kmax
        cands: list[_Candidate] = []
        for vi, (p, pts, labs, vmap, base) in enumerate(variants):
            k = len(pts)
            sig = self._signature(pts, labs)
            ang = interior_angles(pts)
            # one edge per orbit of the tile's rotational symmetries (labels respected)
            for j in signature_rotations(sig):
                q0, q1 = pts[j], pts[(j + 1) % k]
                length = float(np.hypot(*(q1 - q0)))
                frame = Affine.segment_map((0.0, 0.0), (length, 0.0), q0, q1)
                local = Affine.apply(frame, pts)
                pieces = np.stack([_pad(Affine.apply(frame, pc), kmax) for pc in convex_pieces[vi]])
                normals = _normals(pieces)
                proj = np.einsum("cad,ckd->cak", normals, pieces)
                cands.append(
                    _Candidate(
                        prototile=p,
                        variant=vi,
                        edge=j,
                        length=length,
                        label=labs[j],
                        local=local,
                        angles=ang,
                        labels=labs,
                        vertex_map=vmap,
                        pieces=pieces,
                        normals=normals,
                        proj_min=proj.min(-1),
                        proj_max=proj.max(-1),
                        base=frame @ base,
                        outline_next=np.roll(local, -1, axis=0),
                    )
                )
        self._cands = cands
        self._lengths = np.array([c.length for c in cands])
        # tile diameter bounds the grid cell
        diam = 0.0
        for _, pts, _, _, _ in variants:
            d = pts[:, None, :] - pts[None, :, :]
            diam = max(diam, float(np.sqrt((d**2).sum(-1)).max()))
        self._cell = diam
        self._angle_set = self._fillable_angles() if self.angle_check else None
        if self.period is not None:
            self._prepare_period()

    def _prepare_period(self) -> None:
        """The block of lattice offsets whose images a representative needs round it.

        A representative's centroid (vertex mean) has fractional lattice coordinates in
        [-a, 1 - a) (a generic a, so no centroid sits on the boundary). A tile touching it
        has its centroid within D = 2 r + 2 tol (r: the largest centroid-to-vertex
        distance), i.e. fractional coordinates moved by at most d_i = D |row i of the
        inverse lattice matrix|, hence lattice offsets floor(-d_i) .. floor(1 + d_i)."""
        lattice = self.period
        assert lattice is not None
        r = max(float(np.linalg.norm(c.local - c.local.mean(axis=0), axis=1).max()) for c in self._cands)
        inv = np.linalg.inv(lattice.T)  # fractional coordinates of a point: inv @ point
        reach = (2 * r + 2 * self.tol) * np.linalg.norm(inv, axis=1)
        ranges = [range(math.floor(-d), math.floor(1 + d) + 1) for d in reach]
        offsets = [(0, 0)] + [(a, b) for a in ranges[0] for b in ranges[1] if (a, b) != (0, 0)]
        self._lattice_inv = inv
        self._offsets = np.array(offsets, dtype=float) @ lattice  # (m, 2) vectors, 0 first
        self._period_area = abs(float(np.linalg.det(lattice)))
        self._proto_area = [abs(p.area) for p in self.prototiles]

    def _canonical_shift(self, point: np.ndarray) -> np.ndarray:
        """The lattice vector moving ``point`` into the fundamental domain round the seed."""
        frac = self._lattice_inv @ (np.asarray(point) - self._origin)
        return -(np.floor(frac + _DOMAIN_OFFSET) @ self.period)

    def _signature(self, pts: np.ndarray, labels: Sequence[Hashable]) -> list[tuple]:
        return edge_signature(pts, labels, 100 * (self.tol if hasattr(self, "tol") else 1e-6))

    def _fillable_angles(self) -> np.ndarray | None:
        """Sorted sums (<= 2π) of corner angles with repetition: the angles an open vertex's
        gap can still be filled with. None when there are too many to be a useful test."""
        angles = sorted({round(float(a), 9) for _, pts, _, _, _ in self._variants for a in interior_angles(pts)})
        sums = {0.0}
        frontier = {0.0}
        while frontier:
            nxt = set()
            for s in frontier:
                for a in angles:
                    t = round(s + a, 7)
                    if t <= TWO_PI + 1e-6 and t not in sums:
                        nxt.add(t)
            sums |= nxt
            frontier = nxt
            if len(sums) > 20000:
                return None
        return np.array(sorted(sums))

    # ------------------------------------------------------------------ state
    def _reset(self, radius: float | None = None, fill: Callable[[dict[str, Any]], bool] | None = None) -> None:
        self._tiles: list[_Tile] = []
        # the vertex stars: positions, the Corner records at each vertex, live flags
        self._stars = StarIndex(self.tol)
        self._vpos = self._stars.points
        self._vcorners: list[list[Corner]] = self._stars.corners
        self._vlive = self._stars.live
        self._vsum: list[float] = []  # angle sum per vertex
        self._edges: dict[tuple[int, int], tuple[int, int, int, float]] = {}
        self._open: set[tuple[int, int]] = set()
        self._serial = 0
        self._grid: dict[tuple[int, int], list[int]] = {}
        cap = 256
        self._ppts = np.zeros((cap, self._K, 2))
        self._pnorm = np.zeros((cap, self._K, 2))
        self._pmin = np.zeros((cap, self._K))
        self._pmax = np.zeros((cap, self._K))
        self._frontier = _Frontier(self, radius, fill)
        self._committing_image = False  # periodic: placing a lattice image, not a representative
        self._directions: dict[int, float] = {}
        self._pcount = 0
        self._pfree: list[int] = []
        self._tpts = np.zeros((cap, self._K, 2))
        self._tnext = np.zeros((cap, self._K, 2))
        self._tbox = np.zeros((cap, 4))
        self._canon: set[int] = set()  # periodic: the tiles that represent their orbit
        self._groups: list[int] = []  # periodic: tiles (images) per placement

    def _find_vertex(self, x: float, y: float) -> int | None:
        return self._stars.find(x, y)

    def _new_vertex(self, x: float, y: float) -> int:
        v = self._stars.add(x, y)
        if v == len(self._vsum):
            self._vsum.append(0.0)
        else:
            self._vsum[v] = 0.0
        return v

    def _drop_vertex(self, v: int) -> None:
        self._stars.remove(v)

    def _cells(self, bbox: tuple[float, float, float, float]) -> list[tuple[int, int]]:
        c = self._cell
        x0, y0, x1, y1 = bbox
        return [
            (i, j)
            for i in range(math.floor(x0 / c), math.floor(x1 / c) + 1)
            for j in range(math.floor(y0 / c), math.floor(y1 / c) + 1)
        ]

    def _alloc_piece(self) -> int:
        if self._pfree:
            return self._pfree.pop()
        if self._pcount == len(self._ppts):
            self._ppts = np.concatenate([self._ppts, np.zeros_like(self._ppts)])
            self._pnorm = np.concatenate([self._pnorm, np.zeros_like(self._pnorm)])
            self._pmin = np.concatenate([self._pmin, np.zeros_like(self._pmin)])
            self._pmax = np.concatenate([self._pmax, np.zeros_like(self._pmax)])
        self._pcount += 1
        return self._pcount - 1

    # ------------------------------------------------------------------ geometry tests
    def _neighbours(self, bbox: tuple[float, float, float, float]) -> list[int]:
        found: set[int] = set()
        for cell in self._cells(bbox):
            found.update(self._grid.get(cell, ()))
        if not found:
            return []
        ids = np.fromiter(found, dtype=np.int64, count=len(found))
        b = self._tbox[ids]
        keep = (b[:, 0] <= bbox[2]) & (b[:, 2] >= bbox[0]) & (b[:, 1] <= bbox[3]) & (b[:, 3] >= bbox[1])
        return np.sort(ids[keep]).tolist()

    def _overlaps(
        self,
        pieces: np.ndarray,
        an: np.ndarray,
        amin: np.ndarray,
        amax: np.ndarray,
        pts: np.ndarray,
        nxt: np.ndarray,
        neighbours: list[int],
    ) -> str | None:
        """'overlap' if a placed piece meets a neighbour's interior, 'vertex on edge' if a
        corner lies strictly inside another tile's edge (not edge to edge), else None.

        Separating axes: a pair of convex pieces is disjoint (up to ``tol``) when their
        projections on some edge normal of either piece are separated; each piece's
        projections on its own normals are stored, so only the cross terms are computed."""
        if not neighbours:
            return None
        tol = self.tol
        nb_pieces = [pc for t in neighbours for pc in self._tiles[t].pieces]
        bp = self._ppts[nb_pieces]  # (m, K, 2)
        bn = self._pnorm[nb_pieces]
        pb = np.einsum("cad,mkd->cmak", an, bp)  # neighbours on the new piece's axes
        sep = ((amax[:, None, :] <= pb.min(-1) + tol) | (pb.max(-1) <= amin[:, None, :] + tol)).any(-1)
        pa = np.einsum("mad,ckd->cmak", bn, pieces)  # new piece on the neighbours' axes
        bmin, bmax = self._pmin[nb_pieces], self._pmax[nb_pieces]
        sep |= ((pa.max(-1) <= bmin[None] + tol) | (bmax[None] <= pa.min(-1) + tol)).any(-1)
        if not sep.all():
            return "overlap"
        # corners strictly inside edges (T-junctions), both ways; linear in the neighbours
        nb_out = self._tpts[neighbours].reshape(-1, 2)
        if self._t_junction(pts, nb_out, self._tnext[neighbours].reshape(-1, 2)):
            return "vertex on edge"
        if self._t_junction(nb_out, pts, nxt):
            return "vertex on edge"
        return None

    def _t_junction(self, points: np.ndarray, s: np.ndarray, t: np.ndarray) -> bool:
        d = t - s
        len2 = (d**2).sum(-1)
        good = len2 > 1e-18
        if not good.any():
            return False
        s, d, len2 = s[good], d[good], len2[good]
        rel = points[:, None, :] - s[None, :, :]
        u = (rel * d[None]).sum(-1) / len2[None]
        cross = d[None, :, 0] * rel[..., 1] - d[None, :, 1] * rel[..., 0]
        perp = np.abs(cross) / np.sqrt(len2)[None]
        ltol = self.tol / np.sqrt(len2)[None]
        return bool(np.any((perp <= self.tol) & (u > ltol) & (u < 1 - ltol)))

    # ------------------------------------------------------------------ placement
    def _try_place(self, ci: int, frame: np.ndarray, stats: BuildStats) -> bool:
        cand = self._cands[ci]
        lin, off = frame[:2, :2], frame[:2, 2]
        pts = cand.local @ lin.T + off
        k = len(pts)
        vids: list[int | None] = [self._find_vertex(float(x), float(y)) for x, y in pts]
        for i, v in enumerate(vids):
            if v is not None and self._vsum[v] + cand.angles[i] > TWO_PI + ANGLE_TOL:
                return self._reject(stats, "angle sum")
        # directed edges: each must be new, and any reverse edge must carry compatible labels
        for i in range(k):
            a, b = vids[i], vids[(i + 1) % k]
            if a is None or b is None:
                continue
            if (a, b) in self._edges:
                return self._reject(stats, "overlap")
            rev = self._edges.get((b, a))
            if rev is not None:
                other = self._tiles[rev[0]]
                other_label = self._cands[other.cand].labels[rev[1]]
                if not self.compatible(other_label, cand.labels[i]):
                    return self._reject(stats, "edge labels")
        pieces = cand.pieces @ lin.T + off
        normals = cand.normals @ lin.T
        shift = normals @ off  # (c, K): projections move by normal . offset
        amin, amax = cand.proj_min + shift, cand.proj_max + shift
        nxt = cand.outline_next @ lin.T + off
        bbox = (float(pts[:, 0].min()), float(pts[:, 1].min()), float(pts[:, 0].max()), float(pts[:, 1].max()))
        tb = (bbox[0] - self.tol, bbox[1] - self.tol, bbox[2] + self.tol, bbox[3] + self.tol)
        problem = self._overlaps(pieces, normals, amin, amax, pts, nxt, self._neighbours(tb))
        if problem:
            return self._reject(stats, problem)
        t = self._commit(ci, frame @ cand.base, pts, vids, pieces, bbox, normals, nxt, amin, amax)
        touched = self._tiles[t].vids
        if not self._vertices_ok(touched, stats):
            self._undo()
            return False
        return True

    def _reject(self, stats: BuildStats, why: str) -> bool:
        stats.rejections[why] = stats.rejections.get(why, 0) + 1
        return False

    def _commit(self, ci, transform, pts, vids, pieces, bbox, normals, nxt, amin, amax) -> int:
        cand = self._cands[ci]
        t = len(self._tiles)
        k = len(pts)
        new_vids: list[int] = []
        full: list[int] = []
        for i, v in enumerate(vids):
            if v is None:
                v = self._new_vertex(float(pts[i, 0]), float(pts[i, 1]))
                new_vids.append(v)
            full.append(v)
        for i, v in enumerate(full):
            dx, dy = pts[(i + 1) % k] - pts[i]
            start = math.atan2(dy, dx)
            self._vcorners[v].append(
                Corner(t, cand.prototile, cand.vertex_map[i], float(cand.angles[i]), start)
            )
            self._vsum[v] += float(cand.angles[i])
        self._frontier.touched(full)
        edges = []
        cx, cy = float(self._centre[0]), float(self._centre[1])
        for i in range(k):
            a, b = full[i], full[(i + 1) % k]
            self._serial += 1
            dist = _segment_distance(pts[i], pts[(i + 1) % k], cx, cy)
            self._edges[(a, b)] = (t, i, self._serial, dist)
            edges.append((a, b))
            if (b, a) in self._open:
                self._open.discard((b, a))
                self._frontier.closed((b, a))
            else:
                self._open.add((a, b))
                self._frontier.opened((a, b), self._committing_image)
        piece_ids = []
        for pc, pn, lo, hi in zip(pieces, normals, amin, amax):
            pid = self._alloc_piece()
            self._ppts[pid] = pc
            self._pnorm[pid] = pn
            self._pmin[pid] = lo
            self._pmax[pid] = hi
            piece_ids.append(pid)
        if t == len(self._tpts):
            self._tpts = np.concatenate([self._tpts, np.zeros_like(self._tpts)])
            self._tnext = np.concatenate([self._tnext, np.zeros_like(self._tnext)])
            self._tbox = np.concatenate([self._tbox, np.zeros_like(self._tbox)])
        self._tbox[t] = bbox
        self._tpts[t] = _pad(pts, self._K)
        self._tnext[t] = _pad(nxt, self._K)
        cells = self._cells(bbox)
        for cell in cells:
            self._grid.setdefault(cell, []).append(t)
        self._tiles.append(_Tile(ci, transform, pts, full, new_vids, edges, piece_ids, cells, bbox))
        return t

    def _undo(self) -> None:
        tile = self._tiles.pop()
        t = len(self._tiles)
        for cell in tile.cells:
            lst = self._grid[cell]
            lst.remove(t)
            if not lst:
                del self._grid[cell]
        self._pfree.extend(reversed(tile.pieces))
        for a, b in tile.edges:
            del self._edges[(a, b)]
            if (a, b) in self._open:
                self._open.discard((a, b))
                self._frontier.closed((a, b))
            elif (b, a) in self._edges:
                self._open.add((b, a))
                image = self.period is not None and self._edges[(b, a)][0] not in self._canon
                self._frontier.opened((b, a), image)
        for v in tile.vids:
            corners = self._vcorners[v]
            for idx in range(len(corners) - 1, -1, -1):
                if corners[idx].tile == t:
                    self._vsum[v] -= corners[idx].angle
                    del corners[idx]
                    break
        self._frontier.touched(tile.vids)
        for v in reversed(tile.new_vids):
            self._drop_vertex(v)

    def vertex_view(self, v: int) -> VertexView:
        corners = sorted(self._vcorners[v], key=lambda c: (c.start % TWO_PI, c.tile))
        total = self._vsum[v]
        closed = abs(total - TWO_PI) <= ANGLE_TOL
        if closed:
            # rotate so the list starts at a deterministic corner (the lowest tile index)
            first = min(range(len(corners)), key=lambda i: corners[i].tile)
            corners = corners[first:] + corners[:first]
            return VertexView(self._vpos[v], True, total, (tuple(corners),), ())
        # split into fans: corner i abuts corner i+1 when its end equals the next start
        n = len(corners)
        ends = [(c.start + c.angle) % TWO_PI for c in corners]
        breaks = []
        for i in range(n):
            nxt = corners[(i + 1) % n].start % TWO_PI
            gap = (nxt - ends[i]) % TWO_PI
            if gap > self.angle_tol and TWO_PI - gap > self.angle_tol:
                breaks.append((i, gap))
        if len(breaks) <= 1:
            # one fan: its gap is exactly what the corner angles leave (no direction noise)
            breaks = [(breaks[0][0] if breaks else n - 1, TWO_PI - total)]
        fans = []
        gaps = []
        for b_idx, (i, gap) in enumerate(breaks):
            prev_i = breaks[b_idx - 1][0]
            start = (prev_i + 1) % n
            fan = []
            j = start
            while True:
                fan.append(corners[j])
                if j == i:
                    break
                j = (j + 1) % n
            fans.append(tuple(fan))
            gaps.append(gap)
        return VertexView(self._vpos[v], False, total, tuple(fans), tuple(gaps))

    def _vertices_ok(self, vids: list[int], stats: BuildStats) -> bool:
        for v in vids:
            total = self._vsum[v]
            if abs(total - TWO_PI) <= ANGLE_TOL:
                if self.rule is not None and not self.rule.closed(self.vertex_view(v)):
                    return self._reject(stats, "closed vertex rule")
                continue
            if self._angle_set is not None:
                # every gap must be fillable by corner angles
                view = self.vertex_view(v)
                tol = self.angle_tol
                for gap in view.gaps:
                    i = np.searchsorted(self._angle_set, gap - tol)
                    if i >= len(self._angle_set) or abs(self._angle_set[i] - gap) > tol:
                        return self._reject(stats, "unfillable angle")
                if self.rule is not None and not self.rule.open(view):
                    return self._reject(stats, "open vertex rule")
            elif self.rule is not None and not self.rule.open(self.vertex_view(v)):
                return self._reject(stats, "open vertex rule")
        return True

    # ------------------------------------------------------------------ frontier
    def _edge_info(self, e: tuple[int, int]) -> dict[str, Any]:
        info = self._edges[e]
        pa, pb = self._vpos[e[0]], self._vpos[e[1]]
        return {
            "serial": info[2],
            "distance": info[3],
            "midpoint": ((pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2),
            "start": pa,
            "end": pb,
            "angle_sum": max(self._vsum[e[0]], self._vsum[e[1]]),
            "tile": info[0],
            "prototile": self._cands[self._tiles[info[0]].cand].prototile,
        }

    def _snap_direction(self, theta: float) -> float:
        """The first direction seen within 1e-9 rad of ``theta``, so tiles placed along
        parallel edges get bit-identical rotations; otherwise the rounding error of an edge's
        direction, amplified along every chain of placements, grows with each generation."""
        key = round(theta * 1e9)
        for k in (key, key - 1, key + 1):
            seen = self._directions.get(k)
            if seen is not None and abs(seen - theta) <= 1e-9:
                return seen
        self._directions[key] = theta
        return theta

    def _candidates_for(self, e: tuple[int, int]) -> tuple[list[int], np.ndarray]:
        a, b = e
        pa = np.asarray(self._vpos[a])
        pb = np.asarray(self._vpos[b])
        d = pa - pb
        length = float(np.hypot(*d))
        theta = self._snap_direction(math.atan2(d[1], d[0]))
        frame = Affine.rotation(theta)
        frame[:2, 2] = pb
        owner = self._tiles[self._edges[e][0]]
        label = self._cands[owner.cand].labels[self._edges[e][1]]
        room_a = TWO_PI - self._vsum[a] + ANGLE_TOL
        room_b = TWO_PI - self._vsum[b] + ANGLE_TOL
        ids = []
        for ci in np.flatnonzero(np.abs(self._lengths - length) <= self.tol * 10):
            c = self._cands[ci]
            k = len(c.local)
            if c.angles[c.edge] > room_b or c.angles[(c.edge + 1) % k] > room_a:
                continue
            if not self.compatible(label, c.label):
                continue
            ids.append(int(ci))
        return ids, frame

    # ------------------------------------------------------------------ the search
    def build(
        self,
        *,
        tiles: int | None = None,
        radius: float | None = None,
        fill: Callable[[dict[str, Any]], bool] | None = None,
        seed: int = 0,
        seed_transform: np.ndarray | None = None,
        max_nodes: int = 1_000_000,
        max_seconds: Budget | float | None = DEFAULT_SOLVER_SECONDS,
    ) -> BuildResult:
        """Grow a patch from prototile ``seed`` (placed by ``seed_transform``, default the
        identity) until it has ``tiles`` tiles, or covers the disc of ``radius`` round the
        seed's centroid, or has no open edge that ``fill(edge)`` accepts (``edge`` as for a
        callable order, plus ``tile`` and ``prototile`` of the tile that owns it: e.g. "every
        edge inside this box", or "every edge of the seed" for a first corona). Stops at
        ``max_nodes`` candidate placements or ``max_seconds`` CPU seconds of the calling thread
        (a number, or a :class:`tilekit.budget.Budget` shared with other work; default
        ``limits.DEFAULT_SOLVER_SECONDS``; None: no time limit), so that the result does not
        depend on the machine's load; ``stats.seconds`` is the wall-clock time the call took.

        With a ``period`` the goal may be left out: it is then a closed torus (every open
        edge of the representatives filled, so their lattice images tile the plane and the
        representatives cover the fundamental domain's area); ``tiles`` counts
        representatives, ``fill`` sees their open edges only, and the patch returned holds
        the representatives (one tile per orbit). A radius goal needs the plane."""
        self._check_goal(tiles, radius, fill, seed, max_nodes)
        started = time.perf_counter()
        run = _Run(tiles, radius, fill, self.period is not None, BuildStats(), started, Budget.of(max_seconds),
                   max_nodes)
        self._reset(radius, fill)
        failed = self._place_seed(seed, seed_transform, run)
        return failed if failed is not None else self._search(run)

    def _check_goal(self, tiles: int | None, radius: float | None, fill: Any, seed: int, max_nodes: int) -> None:
        goals = sum(g is not None for g in (tiles, radius, fill))
        if self.period is not None:
            if radius is not None:
                raise ParameterError("radius=R is a goal in the plane; with a period give tiles=N, fill=predicate or no goal (a closed torus)")
            if goals > 1:
                raise ParameterError("give at most one goal with a period: tiles=N or fill=predicate (none: a closed torus)")
        elif goals != 1:
            raise ParameterError("give exactly one goal: tiles=N, radius=R or fill=predicate")
        if tiles is not None and tiles < 1:
            raise ParameterError(f"tiles={tiles}: the goal must be at least 1 tile")
        if radius is not None and not radius > 0:
            raise ParameterError(f"radius={radius}: the goal radius must be positive")
        if not 0 <= seed < len(self.prototiles):
            raise ParameterError(f"seed={seed} is not a prototile index 0..{len(self.prototiles) - 1}")
        if max_nodes < 1:
            raise ParameterError(f"max_nodes={max_nodes} must be at least 1")

    def _place_seed(self, seed: int, seed_transform: np.ndarray | None, run: _Run) -> BuildResult | None:
        """Place the seed tile (its variant 0 as given, edge 0 in the local frame) and, on a
        torus, its lattice images; an exhausted result when that already fails."""
        stats = run.stats
        seed_ci = next(i for i, c in enumerate(self._cands) if c.prototile == seed and c.variant == min(
            c2.variant for c2 in self._cands if c2.prototile == seed))
        cand = self._cands[seed_ci]
        placement = np.eye(3) if seed_transform is None else np.asarray(seed_transform, dtype=float)
        frame = placement @ Affine.inverse(cand.base)  # so that the tile transform is `placement`
        pts = cand.local @ frame[:2, :2].T + frame[:2, 2]
        pieces = cand.pieces @ frame[:2, :2].T + frame[:2, 2]
        normals = cand.normals @ frame[:2, :2].T
        nxt = cand.outline_next @ frame[:2, :2].T + frame[:2, 2]
        bbox = (float(pts[:, 0].min()), float(pts[:, 1].min()), float(pts[:, 0].max()), float(pts[:, 1].max()))
        self._centre = pts.mean(axis=0) if run.tiles is not None or run.periodic else np.asarray(
            Patch(self.prototiles, [seed], [placement]).centres()[0]
        )
        self._origin = pts.mean(axis=0)
        shift = normals @ frame[:2, 2]
        self._commit(seed_ci, frame @ cand.base, pts, [None] * len(pts), pieces, bbox, normals, nxt,
                     cand.proj_min + shift, cand.proj_max + shift)
        stats.placements = 1
        if run.periodic:
            self._canon.add(0)
            self._groups.append(1)
            for off in self._offsets[1:]:  # the seed's images must fit round it
                image = frame.copy()
                image[:2, 2] += off
                self._committing_image = True
                try:
                    placed = self._try_place(seed_ci, image, stats)
                finally:
                    self._committing_image = False
                if not placed:
                    stats.seconds = time.perf_counter() - run.started
                    stats.reason = ("exhausted: the seed tile's own lattice images already fail ("
                                    + ", ".join(sorted(stats.rejections)) + ")")
                    return BuildResult("exhausted", None, stats)
                self._groups[0] += 1
        if not self._vertices_ok(self._tiles[0].vids, stats):
            stats.seconds = time.perf_counter() - run.started
            stats.reason = "exhausted: the seed tile alone already fails (" + ", ".join(sorted(stats.rejections)) + ")"
            return BuildResult("exhausted", None, stats)
        return None

    def _search(self, run: _Run) -> BuildResult:
        """The search, a state machine over the frontier and a stack of frames (candidate ids,
        next index, frame map): *choose* the next open edge (or finish) and push its
        candidates; *try* the top frame's next candidates until one is placed (then choose
        again) or none is left; *backtrack*: pop the frame and undo the placement below it.
        No recursion, so depth is unlimited; budgets end the search as a *limit* outcome."""
        stack: list[list[Any]] = []
        state = "choose"
        while True:
            if state == "choose":
                result = self._choose_step(run, stack)
                if result is not None:
                    return result
                state = "try"
            elif state == "try":
                state = self._try_step(run, stack[-1])
                if state == "placed":
                    state = "limit" if run.over_budget(strict=True) else "choose"
            elif state == "backtrack":
                stack.pop()
                if not stack:
                    return self._exhausted(run)
                self._unplace()
                run.stats.backtracks += 1
                state = "try"
            else:  # "limit"
                return self._give_up(run.stats, run.started, run.max_nodes, run.budget)

    def _choose_step(self, run: _Run, stack: list[list[Any]]) -> BuildResult | None:
        """Finish (goal met, or no edge left in the plane), or push the next edge's candidates."""
        stats = run.stats
        n = len(self._tiles) if not run.periodic else len(self._canon)
        stats.max_tiles = max(stats.max_tiles, n)
        edge, covered = self._frontier.choose()
        if run.radius is not None:
            stats.max_radius = max(stats.max_radius, min(covered, run.radius))
        if (run.tiles is not None and n >= run.tiles) or (run.tiles is None and edge is None):
            stats.seconds = time.perf_counter() - run.started
            stats.reason = f"reached {run.goal_text()} with {n} tiles"
            if run.periodic and run.tiles is None and run.fill is None:
                self._check_area(n)
            return BuildResult("complete", self._patch(), stats)
        if edge is None and not run.periodic:  # a tile goal and no open edge: impossible in the plane
            stats.seconds = time.perf_counter() - run.started
            stats.reason = "no open edge left"
            return BuildResult("exhausted", None, stats)
        if edge is None:  # the torus closed below the tile goal: a dead branch
            ids, fr = [], np.eye(3)
        else:
            ids, fr = self._candidates_for(edge)
        stack.append([ids, 0, fr])
        return None

    def _try_step(self, run: _Run, top: list[Any]) -> str:
        """Try the frame's remaining candidates: "placed", "backtrack" (none fits) or "limit"."""
        stats = run.stats
        while top[1] < len(top[0]):
            ci = top[0][top[1]]
            top[1] += 1
            stats.nodes += 1
            if self._place(ci, top[2], stats):
                stats.placements += 1
                return "placed"
            if run.over_budget(strict=False):
                return "limit"
        return "backtrack"

    def _exhausted(self, run: _Run) -> BuildResult:
        stats = run.stats
        stats.seconds = time.perf_counter() - run.started
        if run.periodic and run.fill is None:
            stats.reason = (
                "exhausted: no tiling of the torus "
                + (f"with {run.tiles} tiles " if run.tiles is not None else "")
                + f"exists from this seed (largest patch {stats.max_tiles} tiles)"
            )
        elif run.fill is not None:
            stats.reason = (
                "exhausted: no patch from this seed closes every edge the fill predicate "
                f"asks for (largest patch {stats.max_tiles} tiles)"
            )
        elif run.radius is not None:
            stats.reason = (
                f"exhausted: no patch covering the disc of radius {run.radius:g} round the seed "
                f"exists; every branch died by radius {stats.max_radius:.3g} "
                f"(largest patch {stats.max_tiles} tiles)"
            )
        else:
            stats.reason = (
                f"exhausted: no patch of {run.tiles} tiles exists from this seed "
                f"(largest {stats.max_tiles} tiles)"
            )
        return BuildResult("exhausted", None, stats)

    def _give_up(self, stats: BuildStats, started: float, max_nodes: int, budget: Budget | None) -> BuildResult:
        stats.seconds = time.perf_counter() - started
        which = f"node limit {max_nodes}" if stats.nodes >= max_nodes else f"time limit ({budget})"
        stats.reason = f"gave up at the {which} (largest patch {stats.max_tiles} tiles)"
        return BuildResult("limit", None, stats)

    def _place(self, ci: int, frame: np.ndarray, stats: BuildStats) -> bool:
        """Place candidate ``ci`` by ``frame``; with a period, its representative in the
        fundamental domain and then every image of the offset block, all or nothing."""
        if self.period is None:
            return self._try_place(ci, frame, stats)
        cand = self._cands[ci]
        pts = cand.local @ frame[:2, :2].T + frame[:2, 2]
        shift = self._canonical_shift(pts.mean(axis=0))
        first = len(self._tiles)
        try:
            for k, off in enumerate(self._offsets):
                image = frame.copy()
                image[:2, 2] += shift + off
                self._committing_image = k > 0  # offsets[0] is the representative's own cell
                if not self._try_place(ci, image, stats):
                    self._committing_image = False
                    for _ in range(len(self._tiles) - first):
                        self._undo()
                    return False
        finally:
            self._committing_image = False
        self._canon.add(first)
        self._groups.append(len(self._tiles) - first)
        return True

    def _unplace(self) -> None:
        """Undo the last placement (with a period: the representative and its images)."""
        if self.period is None:
            self._undo()
            return
        count = self._groups.pop()
        self._canon.discard(len(self._tiles) - count)
        for _ in range(count):
            self._undo()

    def _check_area(self, n: int) -> None:
        """A closed torus: the representatives must cover the fundamental domain's area."""
        area = sum(self._proto_area[self._cands[self._tiles[t].cand].prototile] for t in self._canon)
        if abs(area - self._period_area) > 1e-6 * self._period_area:
            raise GeometryError(
                f"closed torus with {n} tiles covers area {area:.9g}, not the cell's {self._period_area:.9g} "
                "(the image block is too small: report this as a builder bug)"
            )

    def _patch(self) -> Patch:
        tiles = self._tiles if self.period is None else [self._tiles[t] for t in sorted(self._canon)]
        protos = np.array([self._cands[t.cand].prototile for t in tiles], dtype=np.int64)
        # float noise below 1e-12 is set to zero (e.g. 6e-16 versus 5e-16 at a shared vertex
        # on an axis), which otherwise trips GEOS's overlay in Patch.validate
        transforms = snap_noise(np.array([t.transform for t in tiles]))
        return Patch(self.prototiles, protos, transforms, protos.copy(), np.zeros(len(protos), dtype=np.int64))

    # ------------------------------------------------------------------ inspection
    def closed_vertices(self) -> list[VertexView]:
        """Views of the closed vertices of the last patch built (after a complete build)."""
        return [self.vertex_view(v) for v in range(len(self._vpos)) if self._vlive[v] and
                abs(self._vsum[v] - TWO_PI) <= ANGLE_TOL]


def build_patch(prototiles: Sequence[Prototile], **options: Any) -> BuildResult:
    """One-call form: ``build_patch(tiles, tiles=50)``; constructor and ``build`` options mixed."""
    names = ("reflections", "compatible", "rule", "order", "tolerance", "angle_check", "period")
    ctor = {k: options.pop(k) for k in names if k in options}
    return PatchBuilder(prototiles, **ctor).build(**options)
