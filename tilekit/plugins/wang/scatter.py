"""Primitive distribution with Wang tiles (§7.5; Cohen et al. 2003 strewed plants this way):
points spread like Poisson-disk samples over an unbounded plane, by random access, and an
SVG primitive drawn at each.

The points are the importance sampler's (:mod:`tilekit.plugins.wang.sampling`): Lagae and
Dutré's complete corner set over four colours, each tile carrying the quadrants of its four
corner patches' progressive best-candidate point sets, so points on both sides of a tile edge
come from one patch and stay well spaced across it. Keeping the points of rank < k of every
tile gives about k points per tile, as well spaced as a prefix of a progressive set is.
The tile of every lattice square is hashed from its corners, so a window of the plane is
computed alone and equals the same window of any larger one; each point's primitive,
rotation and scale come from a hash of its tile's position and its index there, so equal
tiles in two places do not show equal primitives.
"""

from __future__ import annotations

import html
import math
from pathlib import Path

import numpy as np

from tilekit import limits
from tilekit.errors import ParameterError, ParseError
from tilekit.plugins.wang.fill import lattice_hash, random_access_fill
from tilekit.plugins.wang.sampling import PATCH_POINTS, corner_set, tile_point_sets
from tilekit.plugins.wang.synth import check_window
from tilekit.resources import read_toml

#: Points a scatter may hold (csv / npy), and the points of one SVG picture.
MAX_POINTS = 20_000_000
MAX_SVG_POINTS = 1_000_000
#: Hash salts of the per-point choices (kept apart from the fills' salts 0..3).
_SALT_ID = 11


def scatter_points(x0: int, y0: int, width: int, height: int, tile: float = 64.0, per_tile: int = 16,
                   seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Points in the window [x0, x0 + width) x [y0, y0 + height) of the plane (pixel units, y
    down), about ``per_tile`` (1..PATCH_POINTS) in each ``tile`` x ``tile`` square: (points
    (m, 2) as (x, y), ids (m,) uint64, a hash of each point's tile and index there)."""
    width, height, x0, y0 = check_window(width, height, x0, y0)
    if not (isinstance(tile, int | float) and not isinstance(tile, bool) and math.isfinite(tile) and 2 <= tile <= 1 << 20):
        raise ParameterError(f"tile {tile!r} must be a number of pixels from 2 to {1 << 20}")
    if isinstance(per_tile, bool) or not isinstance(per_tile, int | np.integer) or not 1 <= per_tile <= PATCH_POINTS:
        raise ParameterError(f"points per tile {per_tile!r} must be a whole number from 1 to {PATCH_POINTS}")
    j0, j1 = math.floor(x0 / tile), math.floor((x0 + width) / tile)
    i0, i1 = math.floor(y0 / tile), math.floor((y0 + height) / tile)
    rows, cols = i1 - i0 + 1, j1 - j0 + 1
    limits.refuse_over("points", float(rows) * cols * per_tile, MAX_POINTS, hint="give a smaller window or --per-tile")
    tp, tr, start, count = tile_point_sets()
    # each tile's points of rank < per_tile, as flat (points, start, count) again
    keep = tr < per_tile / PATCH_POINTS
    kept_count = np.add.reduceat(keep.astype(np.int64), start)
    kept_count[count == 0] = 0
    kept_points = tp[keep]
    kept_index = np.flatnonzero(keep) - np.repeat(start, count)[keep]  # index within its tile
    kept_start = np.cumsum(kept_count) - kept_count
    # tile row i is the lattice row y = -1 - i (as in the texture); the fill's row 0 is northernmost
    grid = random_access_fill(corner_set(), rows, cols, x0=j0, y0=-(i1 + 1), seed=seed)
    cells = grid.ravel()
    n = kept_count[cells]
    owner = np.repeat(np.arange(len(cells)), n)
    row = kept_start[cells][owner] + (np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n))
    ci, cj = np.divmod(owner, cols)
    ti, tj = i0 + ci, j0 + cj
    px, py = kept_points[row, 0], kept_points[row, 1]
    x = (tj + px) * tile
    y = (ti + 1.0 - py) * tile  # the unit tile's y points up, the picture's down
    inside = (x >= x0) & (x < x0 + width) & (y >= y0) & (y < y0 + height)
    ids = lattice_hash(tj * (4 * PATCH_POINTS) + kept_index[row], ti, seed, _SALT_ID)
    return np.column_stack([x[inside], y[inside]]), ids[inside]


def load_motifs(path: str | Path) -> list[str]:
    """Read a motif file: a TOML table ``[motifs]`` of ``NAME = '<svg fragment>'``, each drawn
    around (0, 0) in units of the point spacing (radius about 0.5 keeps neighbours apart)."""
    p = Path(path)
    data = read_toml(p, "motif file")
    table = data.get("motifs")
    if not isinstance(table, dict) or not table:
        raise ParseError(f"{p.name}: needs a [motifs] table of NAME = '<svg fragment>'")
    out = []
    for name, frag in table.items():
        if not isinstance(frag, str) or "<" not in frag:
            raise ParseError(f"{p.name}: motif {name!r} must be an SVG fragment string like '<circle .../>'")
        out.append(frag)
    return out


def scatter_svg(points: np.ndarray, ids: np.ndarray, width: int, height: int, spacing: float,
                motifs: list[str] | None = None, x0: float = 0.0, y0: float = 0.0,
                background: str = "#f4efe1") -> str:
    """An SVG of the window: at each point one of ``motifs`` (chosen by its id), turned and
    scaled by its id, in units of ``spacing``; without motifs, a dot."""
    if len(points) > MAX_SVG_POINTS:
        limits.refuse_over("points in an SVG", len(points), MAX_SVG_POINTS, hint="write .csv or .npy instead")
    shapes = motifs or ['<circle r="0.3" fill="#3a3a3a"/>']
    ids = np.asarray(ids, dtype=np.uint64)
    which = (ids % np.uint64(len(shapes))).astype(np.int64)
    angle = ((ids >> np.uint64(16)) % np.uint64(360)).astype(np.int64)
    scale = spacing * (0.85 + 0.3 * ((ids >> np.uint64(32)) % np.uint64(1000)).astype(np.float64) / 1000.0)
    defs = "".join(f'<g id="m{k}">{frag}</g>' for k, frag in enumerate(shapes))
    uses = "".join(
        f'<use href="#m{k}" transform="translate({x - x0:.2f},{y - y0:.2f}) rotate({a}) scale({s:.3f})"/>'
        for k, a, s, x, y in zip(which.tolist(), angle.tolist(), scale.tolist(), points[:, 0].tolist(),
                                 points[:, 1].tolist())
    )
    return (f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
            f'width="{width}" height="{height}" viewBox="0 0 {width} {height}">'
            f'<title>{html.escape(f"{len(points)} primitives strewn by Wang tiles")}</title>'
            f'<rect width="{width}" height="{height}" fill="{background}"/><defs>{defs}</defs>{uses}</svg>\n')
