"""The level-by-level substitution loop that every generator shares (§6.1, §7.4).

The similarity engine, the keypoint (spectre) systems and the hat all substitute a seed
supertile level by level: drop the placed supertiles that cannot reach the region, replace
every survivor by its children (one compiled pass over the level, kernels.py), and at the end place
the base tiles. Only the rules per level, the culling test and the base differ; they are
arguments here.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence

import numpy as np

from tilekit.limits import check_chunk_tiles

Expand = Callable[[np.ndarray, np.ndarray, int], tuple[np.ndarray, np.ndarray]]
Cull = Callable[[np.ndarray, np.ndarray, int], np.ndarray]


def substitute_levels(
    label: np.ndarray,
    maps: np.ndarray,
    depth: int,
    expand: Expand,
    cull: Cull | None = None,
    after_level: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
    stop: int = 0,
) -> tuple[np.ndarray, np.ndarray]:
    """Substitute the placed supertiles (``label``, ``maps``) of level ``depth`` down to level
    ``stop`` (0: the tiles).

    For n = depth .. stop + 1: keep the supertiles for which ``cull(label, maps, n)`` is true
    (when given), then ``expand(label, maps, n)`` replaces each level-n supertile by its
    level-(n-1) children; ``after_level(label, maps)`` may return a mask to keep (duplicates
    removed, for overlapping systems). Finally ``cull(label, maps, stop)`` drops those that
    miss the region.
    """
    for n in range(depth, stop, -1):
        if cull is not None:
            keep = cull(label, maps, n)
            label, maps = label[keep], maps[keep]
        label, maps = expand(label, maps, n)
        if after_level is not None:
            keep = after_level(label, maps)
            label, maps = label[keep], maps[keep]
    if cull is not None:
        keep = cull(label, maps, stop)
        label, maps = label[keep], maps[keep]
    return label, maps


#: sizes(n) -> per label, how many tiles a level-n supertile of that label becomes (float)
Sizes = Callable[[int], np.ndarray]
#: centres(label, maps, n) -> (k, 2) points near the placed level-n supertiles
Centres = Callable[[np.ndarray, np.ndarray, int], np.ndarray]


def chunk_level(sizes: Sizes, depth: int, chunk_tiles: int) -> int:
    """The highest level n <= depth whose supertiles all become at most ``chunk_tiles``
    tiles (0 when even a level-0 supertile may have more: a chunk is then one of them)."""
    level = 0
    for n in range(1, depth + 1):
        if float(np.max(sizes(n))) > chunk_tiles:
            break
        level = n
    return level


def hilbert_order(points: np.ndarray, bits: int = 16) -> np.ndarray:
    """Indices that sort ``points`` (k, 2) along a Hilbert curve over their bounding box
    (a 2^bits grid): points close on the curve are close in the plane, so consecutive
    runs of the order are compact clusters. Vectorised over the points, one pass per bit."""
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    if len(pts) < 2:
        return np.arange(len(pts))
    lo = pts.min(axis=0)
    span = max(float(np.ptp(pts, axis=0).max()), 1e-300)
    side = 1 << bits
    q = np.minimum(((pts - lo) / span * side).astype(np.int64), side - 1)
    x, y = q[:, 0].copy(), q[:, 1].copy()
    d = np.zeros(len(pts), dtype=np.int64)
    s = side >> 1
    while s:
        rx = (x & s) > 0
        ry = (y & s) > 0
        d += s * s * ((3 * rx.astype(np.int64)) ^ ry.astype(np.int64))
        # turn the quadrant so that the curve's sub-squares join up
        flip = ~ry & rx
        x = np.where(flip, side - 1 - x, x)
        y = np.where(flip, side - 1 - y, y)
        swap = ~ry
        x, y = np.where(swap, y, x), np.where(swap, x, y)
        s >>= 1
    return np.argsort(d, kind="stable")


def placed_points(label: np.ndarray, maps: np.ndarray, points: np.ndarray) -> np.ndarray:
    """``points[label[k]]`` (a point per label, in the label's frame) placed by ``maps[k]``."""
    p = np.asarray(points, dtype=float)[label]
    m = np.asarray(maps, dtype=float)
    return np.einsum("nij,nj->ni", m[:, :2, :2], p) + m[:, :2, 2]


def substitute_in_chunks(
    label: np.ndarray,
    maps: np.ndarray,
    depth: int,
    expand: Expand,
    cull: Cull | None,
    sizes: Sizes,
    centres: Centres,
    chunk_tiles: int,
) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """:func:`substitute_levels` in chunks of at most ``chunk_tiles`` tiles each.

    The supertiles are substituted (and culled) down to the level L of
    :func:`chunk_level`, where each supertile becomes at most ``chunk_tiles`` tiles
    (``sizes``, from the substitution matrix); the level-L supertiles are ordered along a
    Hilbert curve through their ``centres`` and cut greedily into runs of at most
    ``chunk_tiles`` descendants, and each run is substituted the remaining L levels by
    ``substitute_levels`` itself. The union of the chunks is exactly what
    ``substitute_levels(label, maps, depth, expand, cull)`` returns (expansion and culling are
    per tile), in another order. Held at once: the level-L supertiles and one chunk (a chunk
    is larger than ``chunk_tiles`` only when one level-0 supertile is).
    """
    chunk_tiles = check_chunk_tiles(chunk_tiles)
    level = chunk_level(sizes, depth, chunk_tiles)
    label, maps = substitute_levels(label, maps, depth, expand, cull, stop=level)
    if not len(label):
        return
    order = hilbert_order(centres(label, maps, level))
    label, maps = label[order], maps[order]
    weight = np.asarray(sizes(level), dtype=float)[label].tolist()
    start, total = 0, 0.0
    for i, w in enumerate(weight):  # per level-L supertile: a few per chunk
        if i > start and total + w > chunk_tiles:
            yield substitute_levels(label[start:i], maps[start:i], level, expand, cull)
            start, total = i, 0.0
        total += w
    yield substitute_levels(label[start:], maps[start:], level, expand, cull)


def expand_base(
    label: np.ndarray, maps: np.ndarray, base: Sequence[np.ndarray], colours: Sequence[np.ndarray]
) -> tuple[np.ndarray, np.ndarray]:
    """The base tiles of level-0 supertiles: label j's tiles are placed by ``maps @ base[j]``
    and coloured ``colours[j]``. Returns (transforms, colours); the dtype of ``maps`` is kept
    (the tiles of one supertile are contiguous, in supertile order)."""
    colour, out = expand_by_label(label, maps, colours, base)
    return out, colour


def expand_by_label(
    label: np.ndarray,
    maps: np.ndarray,
    children: Sequence[np.ndarray],
    matrices: Sequence[np.ndarray],
) -> tuple[np.ndarray, np.ndarray]:
    """One substitution level as arrays: every placed supertile of label j (``maps[k]``)
    becomes its children ``children[j]`` placed by ``maps[k] @ matrices[j]``.

    The dtype of ``maps`` is kept (integer lattice maps stay exact). Returns the children's labels and maps; the children of one supertile are
    contiguous, in supertile order. One compiled pass per level (kernels.py).
    """
    # start-up cost: numba loads in ~0.25 s; only generation needs it, not listing the family
    from tilekit.plugins.substitution import kernels

    return kernels.expand(label, maps, list(children), list(matrices))


def meets_discs(label: np.ndarray, transform: np.ndarray, bounds: tuple[np.ndarray, np.ndarray], box: Sequence[float]) -> np.ndarray:
    """Mask of placed supertiles (rigid ``transform``) whose bounding disc (``bounds``:
    centre and radius per label) meets the box (x0, y0, x1, y1), with a relative and an
    absolute margin of 1e-9 for float noise."""
    # start-up cost: numba, as in expand_by_label
    from tilekit.plugins.substitution import kernels

    centres, radii = bounds
    return kernels.meets(label, transform, centres, radii * (1 + 1e-9) + 1e-9, box, similar=False)


#: step(label, maps, carry, level) -> mask of the tiles to substitute further (see refine_levels)
Step = Callable[[np.ndarray, np.ndarray, dict[str, np.ndarray], int], np.ndarray]


def refine_levels(
    label: np.ndarray,
    maps: np.ndarray,
    children: Sequence[np.ndarray],
    matrices: Sequence[np.ndarray],
    step: Step,
    max_depth: int,
    carry: dict[str, np.ndarray] | None = None,
) -> int:
    """Selective substitution (§7.4): substitute only the tiles that ``step`` asks for.

    Level 0 is the given tiles. At each level ``step(label, maps, carry, level)`` sees every
    tile of the level (it may record them) and returns the mask of those to replace by their
    children; the others stop there. ``carry`` holds per-tile arrays that the children
    inherit from their parent, plus ``carry["child"]`` (the child's index in its parent's
    rule) and ``carry["parent_label"]``; ``step`` may update them in place. Stops when no tile
    is substituted or after ``max_depth`` levels; returns the number of levels seen. Each level
    is one compiled expansion of the chosen tiles (kernels.py), no Python per tile.
    """
    carry = dict(carry or {})
    sizes = np.array([len(c) for c in children], dtype=np.int64)
    level = 0
    while True:
        split = np.asarray(step(label, maps, carry, level), dtype=bool)
        if level >= max_depth or not split.any():
            return level + 1
        label, maps = label[split], maps[split]
        parent_carry = {k: v[split] for k, v in carry.items()}
        kids = sizes[label]
        new_label, new_maps = expand_by_label(label, maps, children, matrices)
        parent = np.repeat(np.arange(len(label)), kids)
        starts = np.cumsum(kids) - kids
        carry = {k: v[parent] for k, v in parent_carry.items()}
        carry["child"] = np.arange(len(parent)) - starts[parent]
        carry["parent_label"] = label[parent]
        label, maps = new_label, new_maps
        level += 1
