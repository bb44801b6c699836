"""Shaped edges for assembled substitution tilings (§6.3: Penrose tiles with interlocking edges).

Which tile edges may carry which shapes is read off the substitution tiling itself, in the
spirit of Figure 6.14's edge labels: a generated patch lists every pair of coincident edges
(prototile p, edge i) ~ (prototile q, edge j); two such edges must interlock, i.e. carry a
shape s and its complement s* (the same curve seen from the other side). A union-find with
parity over the prototiles' edges groups them into classes; each class takes one free edge
shape (a J edge in the book's terms), its members carrying s or s* by parity. For the
Penrose rhombs and the kite and dart this yields the two free edge shapes of the matching
conditions of Figure 6.3 ("two arbitrary J edge shapes").

Whole tiles placed by a reflection are re-expressed by the tile's mirror symmetry that swaps
its two halves, so every placement has positive determinant and edge shapes keep their side.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import shapely

from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.geometry import Affine
from tilekit.limits import MAX_EDGE_POINTS
from tilekit.plugins.substitution.engine import _row_groups, assemble, generate
from tilekit.plugins.substitution.system import SubstitutionSystem
from tilekit.tiling import Prototile

#: Depth of the patch from which edge adjacencies are read (every adjacency of a Penrose
#: tiling already occurs in a few levels; deeper ones add nothing).
ADJACENCY_DEPTH = 7


@dataclass(frozen=True)
class EdgeClasses:
    """Per output prototile and edge: (class index, +1 for s or -1 for the complement s*)."""

    label: tuple[tuple[tuple[int, int], ...], ...]
    count: int
    mirror: tuple[np.ndarray | None, ...]

    def describe(self, names: Sequence[str]) -> str:
        letters = "abcdefghijklmnopqrstuvwxyz"
        parts = []
        for name, edges in zip(names, self.label):
            parts.append(name + ": " + " ".join(letters[c] + ("" if s > 0 else "*") for c, s in edges))
        return "; ".join(parts)


def halves_mirror(system: SubstitutionSystem) -> list[np.ndarray | None]:
    """Per output tile, the reflection symmetry swapping its two halves (None if not found)."""
    out: list[np.ndarray | None] = [None] * len(system.tiles)
    if system.assemble_tile is None or system.assemble_matrix is None:
        return out
    for i, t in enumerate(system.assemble_tile):
        half_in_whole = Affine.apply(Affine.inverse(system.assemble_matrix[i]), system.prototiles[i].outline)
        half = shapely.Polygon(half_in_whole)
        for g in system.output_symmetries[int(t)]:
            if Affine.determinant(g) < 0:
                moved = shapely.Polygon(Affine.apply(g, half_in_whole))
                if shapely.intersection(half, moved, grid_size=1e-9).area < 1e-6 * half.area:
                    out[int(t)] = g
                    break
    for t in range(len(system.tiles)):  # whole tiles not made of halves: any mirror
        if out[t] is None:
            refl = [g for g in system.output_symmetries[t] if Affine.determinant(g) < 0]
            out[t] = refl[0] if refl else None
    return out


def canonical_transforms(proto: np.ndarray, transform: np.ndarray, mirrors: Sequence[np.ndarray | None]) -> np.ndarray:
    """Transforms with negative determinant re-expressed as T @ mirror (positive)."""
    out = transform.copy()
    neg = Affine.determinant(transform) < 0
    for p, m in enumerate(mirrors):
        sel = neg & (proto == p)
        if sel.any():
            if m is None:
                raise GeometryError(f"prototile {p} is placed reflected but has no mirror symmetry")
            out[sel] = transform[sel] @ m
    return out


#: The grid (edge lengths) that tile corners are snapped to before edges are matched.
EDGE_QUANTUM = 1e-6


def edge_keys(outline: np.ndarray, transforms: np.ndarray, quantum: float = EDGE_QUANTUM) -> tuple[np.ndarray, np.ndarray]:
    """Every edge (corner i to i + 1) of ``outline`` placed by each of ``transforms``, in
    placement-major order: its key, the two snapped end points (lower first; int64, (m k, 4)),
    and whether it runs from the lower end (two placed edges with one key coincide, and
    interlock when these differ)."""
    pts = Affine.apply(transforms, np.asarray(outline))  # (m, k, 2)
    qa = np.floor(pts / quantum + 0.5).astype(np.int64)
    qb = np.roll(qa, -1, axis=1)
    first = (qa[..., 0] < qb[..., 0]) | ((qa[..., 0] == qb[..., 0]) & (qa[..., 1] <= qb[..., 1]))
    lo = np.where(first[..., None], qa, qb)
    hi = np.where(first[..., None], qb, qa)
    return np.concatenate([lo, hi], axis=-1).reshape(-1, 4), first.ravel()


class InterlockClasses:
    """A union-find with parity over ``n`` edges (or pieces): two that interlock carry a shape
    and its complement, so they join one class with opposite parities."""

    def __init__(self, n: int) -> None:
        self.parent = list(range(n))
        self.parity = [0] * n

    def find(self, x: int) -> tuple[int, int]:
        """(root of x's class, x's parity relative to it)."""
        p = 0
        while self.parent[x] != x:
            p ^= self.parity[x]
            x = self.parent[x]
        return x, p

    def union(self, a: int, b: int) -> bool:
        """a and b interlock (opposite parity); False if their class already has them alike."""
        ra, pa = self.find(a)
        rb, pb = self.find(b)
        if ra == rb:
            return pa != pb
        self.parent[rb] = ra
        self.parity[rb] = pa ^ pb ^ 1
        return True

    def numbered(self) -> list[tuple[int, int]]:
        """Per member: (class index, numbered in order of first member; parity)."""
        roots: dict[int, int] = {}
        out = []
        for x in range(len(self.parent)):
            r, par = self.find(x)
            out.append((roots.setdefault(r, len(roots)), par))
        return out

    @property
    def count(self) -> int:
        return sum(1 for x, p in enumerate(self.parent) if x == p)


def edge_classes(system: SubstitutionSystem, depth: int = ADJACENCY_DEPTH) -> EdgeClasses:
    """Interlocking edge classes read off a generated patch (see the module docstring)."""
    mirrors = halves_mirror(system)
    tiles = system.tiles
    offsets = np.cumsum([0] + [len(t.outline) for t in tiles])
    classes = InterlockClasses(int(offsets[-1]))

    for seed in range(system.n):
        proto, tr = generate(system, depth, Affine.scaling(system.scale**depth), seed)
        proto, tr = assemble(system, proto, tr)
        tr = canonical_transforms(proto, tr, mirrors)
        rows, nodes = [], []
        for p, tile in enumerate(tiles):
            idx = np.flatnonzero(proto == p)
            if not len(idx):
                continue
            rows.append(edge_keys(tile.outline, tr[idx])[0])
            nodes.append(offsets[p] + np.tile(np.arange(len(tile.outline)), len(idx)))
        keys = np.concatenate(rows)
        node = np.concatenate(nodes)
        _, (order, starts, sizes) = _row_groups(keys)
        for s, z in zip(starts[sizes == 2], sizes[sizes == 2]):
            del z
            if not classes.union(int(node[order[s]]), int(node[order[s + 1]])):
                raise GeometryError("edges cannot interlock consistently (a class meets itself unreversed)")
    numbered = classes.numbered()
    label = tuple(tuple((cls, 1 if par == 0 else -1) for cls, par in numbered[offsets[p] : offsets[p + 1]])
                  for p in range(len(tiles)))
    return EdgeClasses(label, classes.count, tuple(mirrors))


def complement(shape: np.ndarray) -> np.ndarray:
    """The interlocking partner of a unit edge shape: the same curve seen from the other tile."""
    pts = np.asarray(shape, dtype=float).reshape(-1, 2)
    return np.column_stack([1.0 - pts[::-1, 0], -pts[::-1, 1]])


def parse_edge_shape(text: str) -> tuple[str, np.ndarray]:
    """'name=x,y:x,y:...' -> (name, interior points of a path from (0,0) to (1,0))."""
    if "=" not in text:
        raise ParseError(f"edge shape {text!r} is not 'name=x,y:x,y:...'")
    name, _, body = text.partition("=")
    if body.count(":") > MAX_EDGE_POINTS + 2:
        raise ParameterError(f"edge shape of {body.count(':') + 1:,} points is over the limit of {MAX_EDGE_POINTS} "
                             "(limits.MAX_EDGE_POINTS)")
    pts = []
    for part in filter(None, body.split(":")):
        try:
            x, y = (float(v) for v in part.split(","))
        except ValueError:
            raise ParseError(f"edge shape {text!r}: point {part!r} is not 'x,y'") from None
        if not (np.isfinite(x) and np.isfinite(y)):
            raise ParseError(f"edge shape {text!r}: point {part!r} is not finite")
        pts.append((x, y))
    # one --edge syntax for every family: the end points (0,0) and (1,0) may be written too
    if pts and np.allclose(pts[0], (0.0, 0.0), atol=1e-9):
        pts = pts[1:]
    if pts and np.allclose(pts[-1], (1.0, 0.0), atol=1e-9):
        pts = pts[:-1]
    if len(pts) > MAX_EDGE_POINTS:
        raise ParameterError(f"edge shape of {len(pts)} interior points is over the limit of {MAX_EDGE_POINTS} "
                             "(limits.MAX_EDGE_POINTS)")
    return name.strip(), np.array(pts, dtype=float).reshape(-1, 2)


def default_shape(height: float) -> np.ndarray:
    """A J edge (no symmetry): a tooth of the given height, off centre."""
    return np.array([[0.3, height], [0.45, 0.0]]) if height else np.zeros((0, 2))


def shaped_tiles(tiles: Sequence[Prototile], classes: EdgeClasses, shapes: Sequence[np.ndarray]) -> list[Prototile]:
    """The tiles with every edge replaced by its class's shape (or its complement).

    Raises ParameterError naming the tile when a shape makes it self-intersect.
    """
    out = []
    for tile, edges in zip(tiles, classes.label):
        pts = tile.outline
        k = len(pts)
        outline, corners = [], []
        for i, (cls, sign) in enumerate(edges):
            shape = shapes[cls] if sign > 0 else complement(shapes[cls])
            m = Affine.segment_map(pts[i], pts[(i + 1) % k])
            corners.append(len(outline))
            outline.append(pts[i])
            if len(shape):
                outline.extend(Affine.apply(m, shape))
        try:
            out.append(Prototile(np.array(outline), name=tile.name, corners=tuple(corners)))
        except GeometryError:
            raise ParameterError(
                f"edge shapes make tile {tile.name!r} self-intersect; use smaller or different shapes"
            ) from None
    return out


#: Points of the S-curve of :func:`spectre_edge` (interior points of one edge).
SPECTRE_EDGE_POINTS = 15


def spectre_edge(height: float, points: int = SPECTRE_EDGE_POINTS) -> np.ndarray:
    """An S-shaped unit edge shape, y = height * sin(2 pi x) from (0, 0) to (1, 0): turned by
    a half-turn about its midpoint it is itself, so it is its own complement and fits every
    edge of a tiling onto the edge it meets -- when the two tiles have the same handedness;
    a reflected tile brings the mirrored S, which does not fit. Put on every edge of Tile(1, 1),
    it makes the Spectre, which tiles only without reflections (arXiv:2305.17743)."""
    x = np.arange(1, points + 1) / (points + 1)
    return np.column_stack([x, height * np.sin(2 * np.pi * x)])


def curved_tiles(tiles: Sequence[Prototile], shape: np.ndarray) -> list[Prototile]:
    """The tiles with every edge replaced by ``shape``, which must be its own complement
    (:func:`spectre_edge`); ParameterError when a tile then self-intersects."""
    if not np.allclose(complement(shape), shape, atol=1e-12):
        raise ParameterError("an edge shape on every edge must be its own complement (turned a half-turn)")
    classes = EdgeClasses(tuple(tuple((0, 1) for _ in t.outline) for t in tiles), 1, tuple(None for _ in tiles))
    return shaped_tiles(tiles, classes, [shape])
