"""Importance sampling with recursive Wang tiles carrying progressive point sets, after Kopf,
Cohen-Or, Deussen and Lischinski, "Recursive Wang tiles for real-time blue noise" (SIGGRAPH
2006), on Lagae and Dutré's corner tiles (§7.5): the complete set over :data:`CORNER_COLOURS` colours.

The tiles' point sets. Every corner colour c has a *corner patch*: a progressive point set of
:data:`PATCH_POINTS` points on the unit square centred on a lattice point, made by Mitchell's
best-candidate dart throwing (each new point the farthest of many random candidates from the
points so far), so every prefix of it (its points of rank < r) is itself well spaced. A corner
tile is the four quadrants next to its corners, each cut from that corner's patch: across a
tile edge the points on both sides come from the same patch, so any grid of tiles from the
hashed random-access fill is seamless at tile edges. The seams between patches run along the
tiles' mid-lines, inside one tile, so each tile is repaired on its own: in rank
order, a point nearer than :data:`SEAM_DISTANCE` / sqrt(PATCH_POINTS) to a kept point of
another quadrant is dropped.

Recursion. The unit square is one level-0 tile; a tile of side h = 2^-l whose integral wants
more than :data:`SPLIT_FRACTION` x PATCH_POINTS samples is split into 2 x 2 tiles of level l + 1
(the tile of each lattice square chosen by the fill's hash, seeded per level). In a tile that
stops, a point p of normalised rank u = (rank + o_t) / PATCH_POINTS (o_t in [0, 1) hashed per tile) is kept when
u < d(p) h^2 / (tau x PATCH_POINTS): the rank threshold against the local density of Kopf et
al. So p is in the set made with threshold tau exactly for tau in
[S(t), min(A(t), d(p) h^2 / (PATCH_POINTS u))), S(t) = integral(t) / (SPLIT_FRACTION x
PATCH_POINTS) and A(t) the least S of its ancestors: the interval the sampler reports.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from tilekit.limits import refuse_over_memory
from tilekit.plugins.wang.fill import lattice_hash, random_access_tiles
from tilekit.plugins.wang.tileset import WangTileSet, from_corners

#: Corner colours of the tile set the sampler fills with: the complete corner set over this many
#: colours (CORNER_COLOURS^4 tiles; with 2 it is the shipped ``corner-2colour``). Each colour is
#: one corner patch, so more colours mean fewer repeats of one patch in a fill.
CORNER_COLOURS = 4
#: Points of one corner patch (a tile holds about as many: a quarter of each of four patches).
PATCH_POINTS = 64
#: Best-candidate dart throwing tries this many candidates per point already placed.
CANDIDATES_PER_POINT = 8
#: Seam repair distance, in units of the patch's point spacing 1 / sqrt(PATCH_POINTS).
SEAM_DISTANCE = 0.55
#: A tile is split when its integral wants more than this fraction of PATCH_POINTS samples.
SPLIT_FRACTION = 0.5
#: Deepest level (tile side 2^-MAX_LEVEL; the lattice hash takes int64 coordinates).
MAX_LEVEL = 40
#: Seed of the construction of the patches (fixed: the tiles are data, the same in every run).
CONSTRUCTION_SEED = 2006


@lru_cache(maxsize=1)
def corner_set(colours: int = CORNER_COLOURS) -> WangTileSet:
    """The complete corner tile set over ``colours`` colours (every (NE, SE, SW, NW) colouring)."""
    grid = np.stack(np.meshgrid(*[np.arange(colours)] * 4, indexing="ij"), axis=-1).reshape(-1, 4)
    return from_corners(f"corner-{colours}colour", grid.tolist())


def best_candidate(n: int, rng: np.random.Generator, k: int = CANDIDATES_PER_POINT) -> np.ndarray:
    """``n`` points in [-1/2, 1/2]^2 by Mitchell's best-candidate algorithm, in insertion order.
    Distances wrap around the square (a torus): with plain distances the first points crowd
    the square's sides, which are the tiles' mid-lines, and the seams would show as lines."""
    pts = np.empty((n, 2))
    pts[0] = rng.uniform(-0.5, 0.5, 2)
    for i in range(1, n):
        cand = rng.uniform(-0.5, 0.5, (k * i + 1, 2))
        delta = np.abs(cand[:, None, :] - pts[None, :i, :])
        delta = np.minimum(delta, 1.0 - delta)
        d = np.min(np.sum(delta**2, axis=2), axis=1)
        pts[i] = cand[int(np.argmax(d))]
    return pts


@lru_cache(maxsize=2)
def tile_point_sets(patch_points: int = PATCH_POINTS) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The tiles' point sets, flat: ``(points (M, 2) in the unit tile, ranks / PATCH_POINTS (M,),
    start (T,), count (T,))``; tile t's points are rows start[t] .. start[t] + count[t]."""
    ts = corner_set()
    assert ts.corners is not None
    rng = np.random.default_rng(CONSTRUCTION_SEED)
    patches = [best_candidate(patch_points, rng) for _ in ts.corner_colours]
    rank = np.arange(patch_points) / patch_points
    # (corner column in NE SE SW NW order, the corner's position in the tile)
    corners = ((0, (1.0, 1.0)), (1, (1.0, 0.0)), (2, (0.0, 0.0)), (3, (0.0, 1.0)))
    seam = SEAM_DISTANCE / np.sqrt(patch_points)
    out_p, out_r, counts = [], [], []
    for t in range(len(ts)):
        pts, ranks, quads = [], [], []
        for q, (col, (cx, cy)) in enumerate(corners):
            patch = patches[int(ts.corners[t, col])]
            local = patch + np.array([cx, cy])
            inside = (local[:, 0] >= 0) & (local[:, 0] < 1) & (local[:, 1] >= 0) & (local[:, 1] < 1)
            pts.append(local[inside])
            ranks.append(rank[inside])
            quads.append(np.full(int(inside.sum()), q))
        p, r, qd = np.concatenate(pts), np.concatenate(ranks), np.concatenate(quads)
        order = np.argsort(r, kind="stable")
        p, r, qd = p[order], r[order], qd[order]
        keep = np.ones(len(p), dtype=bool)
        close = (np.hypot(*(p[:, None, :] - p[None, :, :]).transpose(2, 0, 1)) < seam) & (qd[:, None] != qd[None, :])
        for i in np.flatnonzero(close.any(axis=1)):  # construction, once: 256 tiles x ~64 points
            if (close[i, :i] & keep[:i]).any():
                keep[i] = False
        out_p.append(p[keep])
        out_r.append(r[keep])
        counts.append(int(keep.sum()))
    count = np.array(counts, dtype=np.int64)
    start = np.cumsum(count) - count
    return np.concatenate(out_p), np.concatenate(out_r), start, count


def candidates(density, tau_lo: float, tau_hi: float, seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sample points whose threshold interval meets [tau_lo, tau_hi] (module docstring):
    ``(points (m, 2), lo (m,), hi (m,))``. Array code per level, no Python per tile."""
    ts = corner_set()
    tp, tr, start, count = tile_point_sets()
    k = float(PATCH_POINTS)
    # a level holds at most total / (SPLIT_FRACTION k tau_lo) split tiles (disjoint, each over
    # the split bound), 4 children each, and a stopping tile up to k candidate points
    refuse_over_memory("candidate points in one level of the Wang recursion",
                       4 * k * density.total / (SPLIT_FRACTION * k * tau_lo), 200, hint="ask for fewer samples")
    i = np.zeros(1, dtype=np.int64)
    j = np.zeros(1, dtype=np.int64)
    ancestors = np.full(1, np.inf)
    out_p: list[np.ndarray] = []
    out_lo: list[np.ndarray] = []
    out_hi: list[np.ndarray] = []
    for level in range(MAX_LEVEL + 1):
        h = 0.5**level
        integral = density.box_integral(i * h, j * h, (i + 1) * h, (j + 1) * h)
        s = integral / (SPLIT_FRACTION * k)
        stop_here = (s < tau_hi) & (s < ancestors)
        if stop_here.any():
            level_seed = int(lattice_hash(np.array([level]), np.array([seed]), CONSTRUCTION_SEED)[0] & 0x7FFFFFFF)
            ti, tj = i[stop_here], j[stop_here]
            tiles = random_access_tiles(ts, ti, tj, seed=level_seed)
            n = count[tiles]
            owner = np.repeat(np.arange(len(tiles)), n)
            row = start[tiles][owner] + (np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n))
            x = (ti[owner] + tp[row, 0]) * h
            y = (tj[owner] + tp[row, 1]) * h
            d = density.at(x, y)
            # rank r of a tile becomes u = (r + offset) / PATCH_POINTS with one hashed offset per
            # tile, so that ranks of equal tiles do not all cross a threshold together
            offset = ((lattice_hash(ti, tj, level_seed, 3) >> np.uint64(11)).astype(np.float64) / 2.0**53)[owner]
            hi = np.minimum(ancestors[stop_here][owner], d * h * h / (k * tr[row] + offset))
            lo = s[stop_here][owner]
            ok = (lo < hi) & (hi > tau_lo)
            out_p.append(np.column_stack([x[ok], y[ok]]))
            out_lo.append(lo[ok])
            out_hi.append(hi[ok])
        split = s > tau_lo
        if not split.any() or level == MAX_LEVEL:
            break
        i, j = i[split], j[split]
        ancestors = np.minimum(ancestors[split], s[split])
        # the four children of each split tile
        i = (2 * i[:, None] + np.array([0, 1, 0, 1])).ravel()
        j = (2 * j[:, None] + np.array([0, 0, 1, 1])).ravel()
        ancestors = np.repeat(ancestors, 4)
    if not out_p:
        return np.zeros((0, 2)), np.zeros(0), np.zeros(0)
    return np.concatenate(out_p), np.concatenate(out_lo), np.concatenate(out_hi)
