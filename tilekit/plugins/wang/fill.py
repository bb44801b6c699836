"""Fills for graphics (§7.5): Cohen et al.'s scanline fill and Lagae-Dutré random access.

``scanline_fill`` places tiles in the order of the scanline method — each tile chosen at
random among those matching its north and west neighbours — in one compiled loop over the
cells (kernels.py; a few nanoseconds a tile, faster than any NumPy formulation, which needs
a step per row or per anti-diagonal).

``random_access_tiles`` gives the tile of any lattice square directly: a hash of each
lattice point (corner sets) or of each edge (edge sets with a tile for every colour
combination) chooses colours, and a lookup table turns the four colours into a tile, so a
tile is the same whether computed alone or inside any block.

Both return integer grids (``grid[i, j]``: row i from the north, column j from the west);
``grid_to_patch`` turns a grid into a :class:`~tilekit.Patch` of unit squares.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from tilekit.errors import ParameterError
from tilekit.limits import refuse_over_memory
from tilekit.plugins.wang.check import grid_size
from tilekit.plugins.wang.tileset import E, N, S, W, WangTileSet, tile_prototiles
from tilekit.tiling import Patch

#: Refuse fills larger than this many tiles (a typo guard: 10^8 tiles is ~1 GB of indices).
MAX_FILL_TILES = 100_000_000


# ---------------------------------------------------------------------- scanline fill


def _scanline_tables(tileset: WangTileSet) -> tuple[np.ndarray, np.ndarray]:
    """Candidate tables over (n, w) with an extra index ANY = len(colours) for a missing
    neighbour: ``choices[n, w, k]`` and ``counts[n, w]``."""
    cached = tileset.__dict__.get("_scanline_tables")
    if cached is not None:
        return cached
    c = len(tileset.colours)
    n_key = tileset.tiles[:, N]
    w_key = tileset.tiles[:, W]
    any_ = np.full(len(tileset), c)
    # each tile is a candidate for (n, w), (ANY, w), (n, ANY) and (ANY, ANY)
    keys = np.concatenate([n_key * (c + 1) + w_key, any_ * (c + 1) + w_key, n_key * (c + 1) + any_, any_ * (c + 1) + any_])
    tiles = np.tile(np.arange(len(tileset)), 4)
    refuse_over_memory("scanline table entries", float(c + 1) ** 2, 16, hint=f"set {tileset.name!r} has {c} colours")
    counts = np.bincount(keys, minlength=(c + 1) ** 2)
    kmax = int(counts.max())
    refuse_over_memory("scanline table entries", float(c + 1) ** 2 * kmax, 8,
                       hint=f"set {tileset.name!r} has {c} colours and up to {kmax} tiles per pair")
    order = np.argsort(keys, kind="stable")
    sk = keys[order]
    slot = np.arange(len(sk)) - np.searchsorted(sk, sk, side="left")
    choices = np.full(((c + 1) ** 2, kmax), -1, dtype=np.int64)
    choices[sk, slot] = tiles[order]
    out = (choices.reshape(c + 1, c + 1, kmax), counts.reshape(c + 1, c + 1))
    tileset.__dict__["_scanline_tables"] = out
    return out


def scanline_fill(
    tileset: WangTileSet,
    rows: int,
    cols: int,
    seed: int | None = None,
) -> np.ndarray:
    """An m x n grid filled by the scanline method of Cohen et al. (§7.5, Figure 6.9).

    Each tile is drawn uniformly from the tiles whose N and W colours match the tiles
    already placed above and to the left (the first row and column have one neighbour
    fewer, the corner none). The set must be complete (a tile for every (N, W) pair that
    can occur), or the fill could get stuck; ``seed`` makes the fill repeatable.
    """
    rows, cols = grid_size(rows, cols, "fill", MAX_FILL_TILES)
    return next(scanline_rows(tileset, rows, cols, seed, block=rows))


def scanline_rows(
    tileset: WangTileSet,
    rows: int,
    cols: int,
    seed: int | None = None,
    block: int = 256,
) -> Iterator[np.ndarray]:
    """The grid of :func:`scanline_fill` as blocks of at most ``block`` rows, from the north:
    each block continues from the south colours of the one before and draws the next
    ``block * cols`` numbers of the same generator, so the blocks stacked equal
    ``scanline_fill(tileset, rows, cols, seed)`` and a fill of any height needs the memory
    of one block."""
    if not tileset.complete:
        raise ParameterError(
            f"set {tileset.name!r} is not complete (some north/west colour pair has no tile), so "
            "the scanline fill can get stuck; use the exact solver (method='solver') instead"
        )
    if isinstance(block, bool) or not isinstance(block, int | np.integer) or block < 1:
        raise ParameterError(f"block {block!r} must be a positive whole number of rows")
    rows, cols = grid_size(rows, cols, "fill")
    grid_size(min(block, rows), cols, "fill block", MAX_FILL_TILES)
    choices, counts = _scanline_tables(tileset)
    south = tileset.tiles[:, S].astype(np.int64)
    east = tileset.tiles[:, E].astype(np.int64)
    rng = np.random.default_rng(seed)
    north = np.full(cols, counts.shape[0] - 1, dtype=np.int64)  # ANY: nothing above the first row
    # start-up cost: numba loads (~0.25 s) only when a fill runs, not when the family is listed
    from tilekit.plugins.wang.kernels import scanline_loop

    for start in range(0, rows, block):
        k = min(block, rows - start)
        grid = np.empty((k, cols), dtype=np.int64)
        scanline_loop(choices, counts, south, east, rng.random(k * cols).reshape(k, cols), grid, north)
        north = south[grid[-1]]
        yield grid


# ---------------------------------------------------------------------- random access

_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_KX = np.uint64(0xD6E8FEB86659FD93)
_KY = np.uint64(0xA0761D6478BD642F)


def _mix(z: np.ndarray) -> np.ndarray:
    """The splitmix64 finaliser: a bijection of 64-bit integers that scrambles every bit."""
    z = (z ^ (z >> np.uint64(30))) * _M1
    z = (z ^ (z >> np.uint64(27))) * _M2
    return z ^ (z >> np.uint64(31))


def lattice_hash(x: np.ndarray, y: np.ndarray, seed: int = 0, salt: int = 0) -> np.ndarray:
    """A repeatable 64-bit hash of integer points (x, y), vectorised.

    Plays the role of Lagae and Dutré's permutation-table hash: any point's value is
    computed on its own, without neighbours, and ``seed`` picks a different tiling.
    """
    with np.errstate(over="ignore"):
        xs = np.asarray(x, dtype=np.int64).astype(np.uint64)
        ys = np.asarray(y, dtype=np.int64).astype(np.uint64)
        s = _mix(np.uint64(seed & 0xFFFFFFFFFFFFFFFF) * _GOLDEN + np.uint64(salt & 0xFFFF))
        return _mix(_mix(xs * _KX + s) ^ (ys * _KY))


def supports_random_access(tileset: WangTileSet) -> bool:
    """Corner sets with a tile for every corner colouring, or edge sets with a tile for
    every (N, E, S, W) combination of the colours in use."""
    if tileset.corners is not None:
        return tileset.corner_complete
    h, v = len(tileset.horizontal_colours), len(tileset.vertical_colours)
    return len(tileset) >= h * h * v * v and _edge_table(tileset) is not None


def _edge_table(tileset: WangTileSet) -> np.ndarray | None:
    cached = tileset.__dict__.get("_edge_table", False)
    if cached is not False:
        return cached
    h, v = tileset.horizontal_colours, tileset.vertical_colours
    hpos = np.full(len(tileset.colours), -1)
    vpos = np.full(len(tileset.colours), -1)
    hpos[h] = np.arange(len(h))
    vpos[v] = np.arange(len(v))
    table = np.full((len(h), len(v), len(h), len(v)), -1, dtype=np.int64)
    t = tileset.tiles
    idx = np.arange(len(t))[::-1]
    table[hpos[t[::-1, N]], vpos[t[::-1, E]], hpos[t[::-1, S]], vpos[t[::-1, W]]] = idx
    out = table if (table >= 0).all() else None
    tileset.__dict__["_edge_table"] = out
    return out


def random_access_tiles(tileset: WangTileSet, x: np.ndarray, y: np.ndarray, seed: int = 0) -> np.ndarray:
    """The tile on the lattice square [x, x+1] x [y, y+1], for arrays of integer x and y.

    Corner sets: the colour of lattice point p is ``hash(p) mod k`` and the tile is the one
    with those four corner colours (Lagae and Dutré). Edge sets with a tile for every
    colour combination: each edge's colour is a hash of the edge. Either way the answer
    depends on (x, y, seed) only.
    """
    if not supports_random_access(tileset):
        raise ParameterError(
            f"set {tileset.name!r} has no tile for some colouring of its corners/edges, so tiles "
            "cannot be looked up by hashing; use the scanline fill or the exact solver"
        )
    x = np.asarray(x, dtype=np.int64)
    y = np.asarray(y, dtype=np.int64)
    if tileset.corners is not None:
        k = np.uint64(len(tileset.corner_colours))

        def colour(px: np.ndarray, py: np.ndarray) -> np.ndarray:
            return (lattice_hash(px, py, seed) % k).astype(np.int64)

        ne, se = colour(x + 1, y + 1), colour(x + 1, y)
        sw, nw = colour(x, y), colour(x, y + 1)
        return tileset.corner_table[ne, se, sw, nw]
    table = _edge_table(tileset)
    hk = np.uint64(len(tileset.horizontal_colours))
    vk = np.uint64(len(tileset.vertical_colours))
    # horizontal edge at height y over [x, x+1] (salt 1); vertical edge at x over [y, y+1] (salt 2)
    north = (lattice_hash(x, y + 1, seed, 1) % hk).astype(np.int64)
    south = (lattice_hash(x, y, seed, 1) % hk).astype(np.int64)
    east = (lattice_hash(x + 1, y, seed, 2) % vk).astype(np.int64)
    west = (lattice_hash(x, y, seed, 2) % vk).astype(np.int64)
    return table[north, east, south, west]


def random_access_fill(
    tileset: WangTileSet, rows: int, cols: int, x0: int = 0, y0: int = 0, seed: int = 0
) -> np.ndarray:
    """The grid of lattice squares x0 <= x < x0 + cols, y0 <= y < y0 + rows (row 0 north).

    Computes each lattice point's (or edge's) colour once and looks tiles up in bulk; the
    result equals :func:`random_access_tiles` cell by cell.
    """
    rows, cols = grid_size(rows, cols, "fill", MAX_FILL_TILES)
    if not supports_random_access(tileset):
        return random_access_tiles(tileset, np.zeros(1), np.zeros(1), seed)  # raises the error
    ys = y0 + rows - 1 - np.arange(rows)  # row 0 is the northernmost
    xs = x0 + np.arange(cols)
    if tileset.corners is not None:
        k = np.uint64(len(tileset.corner_colours))
        px = x0 + np.arange(cols + 1)
        py = y0 + rows - np.arange(rows + 1)  # point rows from the north edge down
        pts = (lattice_hash(px[None, :], py[:, None], seed) % k).astype(np.int64)
        nw, ne = pts[:-1, :-1], pts[:-1, 1:]
        sw, se = pts[1:, :-1], pts[1:, 1:]
        return tileset.corner_table[ne, se, sw, nw]
    table = _edge_table(tileset)
    hk = np.uint64(len(tileset.horizontal_colours))
    vk = np.uint64(len(tileset.vertical_colours))
    hy = y0 + rows - np.arange(rows + 1)
    horiz = (lattice_hash(xs[None, :], hy[:, None], seed, 1) % hk).astype(np.int64)
    vx = x0 + np.arange(cols + 1)
    vert = (lattice_hash(vx[None, :], ys[:, None], seed, 2) % vk).astype(np.int64)
    return table[horiz[:-1], vert[:, 1:], horiz[1:], vert[:, :-1]]


# ---------------------------------------------------------------------- grids to patches


def grid_to_patch(grid: np.ndarray, tileset: WangTileSet, x0: float = 0.0, y0: float = 0.0) -> Patch:
    """A Patch of unit squares for ``grid``; its south-west corner is at (x0, y0).

    Row 0 of the grid is the northernmost row. The prototiles are the set's tiles (one unit
    square each, edge labels = colour tokens); ``colour`` and ``prototile`` are the tile
    index, so a palette colours tiles by identity.
    """
    g = np.asarray(grid, dtype=np.int64)
    rows, cols = g.shape
    n = rows * cols
    transform = np.zeros((n, 3, 3))
    transform[:, 0, 0] = transform[:, 1, 1] = transform[:, 2, 2] = 1.0
    ii, jj = np.divmod(np.arange(n), cols)
    transform[:, 0, 2] = x0 + jj
    transform[:, 1, 2] = y0 + (rows - 1 - ii)
    flat = g.ravel()
    return Patch(tile_prototiles(tileset), flat, transform, colour=flat, aspect=np.zeros(n, dtype=np.int64))
