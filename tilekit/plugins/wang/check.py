"""Independent checkers of the Wang matching rule, for grids and for patches.

These functions share no code with the fills and solvers they judge: ``grid_mismatches``
reads colours straight from the tile rows, and ``patch_mismatches`` works from a Patch's
geometry (tile positions from the transforms, colours from the prototiles' edge labels).

Grid convention used throughout the family: ``grid[i, j]`` is the tile in row i (counted
from the north) and column j (counted from the west); tile (i, j)'s south edge meets tile
(i+1, j)'s north edge, its east edge meets tile (i, j+1)'s west edge.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from tilekit.errors import GeometryError, ParameterError
from tilekit.plugins.wang.tileset import E, N, S, W, WangTileSet


@dataclass(frozen=True)
class Mismatch:
    """Two neighbouring tiles whose shared edge has different colours."""

    cell: tuple[int, int]
    neighbour: tuple[int, int]
    side: str  # the side of ``cell`` facing ``neighbour``: 'E' or 'S' (grids), 'E' or 'N' (patches)
    colour: str
    neighbour_colour: str

    def __str__(self) -> str:
        opposite = {"E": "W", "S": "N", "N": "S", "W": "E"}[self.side]
        return (
            f"tile at {self.cell} has {self.side}={self.colour!r} but its neighbour at "
            f"{self.neighbour} has {opposite}={self.neighbour_colour!r}"
        )


def _as_grid(grid: np.ndarray, tileset: WangTileSet) -> np.ndarray:
    g = np.asarray(grid)
    if g.ndim != 2 or g.size == 0:
        raise ParameterError(f"a Wang grid must be a non-empty 2-D array of tile indices, got shape {g.shape}")
    if not np.issubdtype(g.dtype, np.integer):
        raise ParameterError(f"a Wang grid holds integer tile indices, got dtype {g.dtype}")
    if g.min() < 0 or g.max() >= len(tileset):
        bad = tuple(int(v) for v in np.argwhere((g < 0) | (g >= len(tileset)))[0])
        raise ParameterError(
            f"grid cell {bad} holds tile {int(g[bad])}; set {tileset.name!r} has tiles 0..{len(tileset) - 1}"
        )
    return g


def grid_mismatches(grid: np.ndarray, tileset: WangTileSet, torus: bool = False) -> list[Mismatch]:
    """Every shared edge of ``grid`` whose two colours differ (empty list: the grid is valid).

    With ``torus`` the last column also meets the first and the last row the first.
    """
    g = _as_grid(grid, tileset)
    rows, cols = g.shape
    colours = tileset.tiles[g]  # (rows, cols, 4)
    out: list[Mismatch] = []
    # east edge of (i, j) against west edge of (i, j+1)
    east, west = colours[:, :, E], colours[:, :, W]
    south, north = colours[:, :, S], colours[:, :, N]
    if torus:
        bad_h = np.argwhere(east != np.roll(west, -1, axis=1))
        bad_v = np.argwhere(south != np.roll(north, -1, axis=0))
    else:
        bad_h = np.argwhere(east[:, :-1] != west[:, 1:])
        bad_v = np.argwhere(south[:-1, :] != north[1:, :])
    names = tileset.colours
    for i, j in bad_h.tolist():
        jj = (j + 1) % cols
        out.append(Mismatch((i, j), (i, jj), "E", names[east[i, j]], names[west[i, jj]]))
    for i, j in bad_v.tolist():
        ii = (i + 1) % rows
        out.append(Mismatch((i, j), (ii, j), "S", names[south[i, j]], names[north[ii, j]]))
    return out


def check_grid(
    grid: np.ndarray,
    tileset: WangTileSet,
    torus: bool = False,
    fixed: Mapping[tuple[int, int], int] | None = None,
) -> None:
    """Raise :class:`GeometryError` naming the first broken edge (or a moved fixed tile)."""
    g = _as_grid(grid, tileset)
    bad = grid_mismatches(g, tileset, torus=torus)
    if bad:
        more = f" (and {len(bad) - 1} more)" if len(bad) > 1 else ""
        raise GeometryError(f"Wang grid breaks the matching rule of set {tileset.name!r}: {bad[0]}{more}")
    for (i, j), t in (fixed or {}).items():
        if int(g[i, j]) != int(t):
            raise GeometryError(
                f"grid cell ({i}, {j}) holds tile {int(g[i, j])}, but tile {int(t)} was fixed there"
            )


def patch_mismatches(patch) -> list[Mismatch]:
    """Every shared edge of a patch of Wang tiles whose two edge labels differ.

    Works from geometry alone: each tile's lower-left corner is read from its transform (the
    tiles must be unit squares placed by integer translations), neighbours are found by
    position, and colours are the prototiles' edge labels (S, E, N, W in outline order).
    Cells are reported as (x, y) lattice positions.
    """
    n = len(patch)
    if n == 0:
        return []
    tr = patch.transform
    lin = tr[:, :2, :2]
    if not np.allclose(lin, np.eye(2)[None], atol=1e-9):
        raise GeometryError("patch_mismatches: Wang tiles are placed by translation only; a tile is rotated or scaled")
    pos_f = tr[:, :2, 2]
    pos = np.rint(pos_f).astype(np.int64)
    if not np.allclose(pos, pos_f, atol=1e-9):
        raise GeometryError("patch_mismatches: a tile is not placed at an integer lattice position")
    labels = [p.edge_labels for p in patch.prototiles]
    if any(lab is None or len(lab) != 4 for lab in labels):
        raise GeometryError("patch_mismatches: every prototile needs four edge labels (S, E, N, W)")
    # side colours per tile, as label strings
    side = {name: np.array([lab[k] for lab in labels], dtype=object)[patch.prototile] for k, name in enumerate("SENW")}
    key = pos[:, 0] * (1 << 32) + pos[:, 1]
    order = np.argsort(key)
    sorted_key = key[order]
    if len(sorted_key) > 1 and (np.diff(sorted_key) == 0).any():
        raise GeometryError("patch_mismatches: two tiles sit on the same lattice square")
    out: list[Mismatch] = []
    for name, dx, dy, mine, theirs in (("E", 1, 0, "E", "W"), ("N", 0, 1, "N", "S")):
        want = (pos[:, 0] + dx) * (1 << 32) + (pos[:, 1] + dy)
        at = np.clip(np.searchsorted(sorted_key, want), 0, n - 1)
        has = sorted_key[at] == want
        a = np.flatnonzero(has)
        b = order[at[has]]
        differ = side[mine][a] != side[theirs][b]
        for t, u in zip(a[differ].tolist(), b[differ].tolist()):
            out.append(
                Mismatch(
                    (int(pos[t, 0]), int(pos[t, 1])),
                    (int(pos[u, 0]), int(pos[u, 1])),
                    name,
                    str(side[mine][t]),
                    str(side[theirs][u]),
                )
            )
    return out


def grid_size(rows: Any, cols: Any, what: str = "grid", limit: int | None = None) -> tuple[int, int]:
    """``rows`` and ``cols`` as positive ints (ParameterError naming ``what`` otherwise)."""
    try:
        r, c = int(rows), int(cols)
    except (TypeError, ValueError):
        raise ParameterError(f"{what} size must be two integers, got {rows!r} x {cols!r}") from None
    if r < 1 or c < 1:
        raise ParameterError(f"{what} size {r} x {c} must be at least 1 x 1")
    if limit is not None and r * c > limit:
        raise ParameterError(f"{what} size {r} x {c} exceeds the limit of {limit} tiles")
    return r, c
