"""Generation of substitution patches as arrays (§6.1, exercise 6.7, §7.4's selective substitution).

All tiles of a level are expanded at once: per prototile, the (k, 3, 3) stack of tile
transforms is multiplied by the rule's (m, 3, 3) stack of child maps in one batched matmul.
Only tiles whose *inflated* bounds (a disc holding all their descendants) meet the region
are expanded. Coincident duplicates are removed exactly: a tile is keyed by its prototile
and its transform, canonicalised modulo the prototile's symmetry group (two matrices that
differ by a symmetry place the same tile) and quantised on two staggered grids.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from typing import Any

import numpy as np
import shapely

from tilekit.errors import ParameterError
from tilekit.geometry import Affine
from tilekit.limits import STREAM_CHUNK_TILES, check_chunk_tiles
from tilekit.plugins.substitution.levels import (
    expand_by_label,
    placed_points,
    substitute_in_chunks,
    substitute_levels,
)
from tilekit.plugins.substitution.system import SubstitutionSystem, inflation_radii
from tilekit.polygon import centroid

#: Quantum of the duplicate keys, relative to the tiles' linear size.
KEY_QUANTUM = 1e-6


def expand_level(system: SubstitutionSystem, proto: np.ndarray, transform: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One substitution step applied to every tile: children of tile t are T_t @ M_c."""
    return expand_by_label(proto, transform, [r.children for r in system.rules], [r.matrices for r in system.rules])


def meets_box(
    system: SubstitutionSystem,
    proto: np.ndarray,
    transform: np.ndarray,
    box: tuple[float, float, float, float],
    radii: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """Mask of tiles whose descendants (all depths) can meet the box: their disc test."""
    # start-up cost: numba, as in expand_by_label
    from tilekit.plugins.substitution import kernels

    centres, radius = radii if radii is not None else inflation_radii(system)
    return kernels.meets(proto, transform, centres, radius, box, similar=True)


def _seeds(system: SubstitutionSystem, seed_transform: np.ndarray | None,
           seed_prototile: int | np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
    """The level-``depth`` supertiles to substitute: one seed, or several (a cluster)."""
    transform = (np.eye(3) if seed_transform is None else np.asarray(seed_transform, dtype=float)).reshape(-1, 3, 3)
    seed = system.seed if seed_prototile is None else seed_prototile
    proto = np.broadcast_to(np.asarray(seed, dtype=np.int64).reshape(-1), (len(transform),)).copy()
    return proto, transform


def _level_functions(system: SubstitutionSystem, box: tuple[float, float, float, float] | None) -> tuple[Any, Any]:
    """The expansion and (with a box) the cull that every level of the system shares."""
    radii = inflation_radii(system) if box is not None else None
    children = [rule.children for rule in system.rules]
    matrices = [rule.matrices for rule in system.rules]

    def expand(proto: np.ndarray, transform: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        return expand_by_label(proto, transform, children, matrices)

    def cull(proto: np.ndarray, transform: np.ndarray, n: int) -> np.ndarray:
        return meets_box(system, proto, transform, box, radii)

    return expand, cull if box is not None else None


def generate(
    system: SubstitutionSystem,
    depth: int,
    seed_transform: np.ndarray | None = None,
    seed_prototile: int | None = None,
    box: tuple[float, float, float, float] | None = None,
    dedupe: bool | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Substitute one seed tile ``depth`` times; return (prototile, transform) arrays.

    With ``box``, only tiles whose inflated bounds meet it are expanded (and kept). Duplicates
    are removed after every level for overlapping systems and once at the end otherwise
    (``dedupe`` forces either way). Transforms are those of the rule prototiles (half-tiles
    for systems with an assembly; see :func:`assemble`).
    """
    proto, transform = _seeds(system, seed_transform, seed_prototile)
    per_level = system.kind == "overlapping" if dedupe is None else dedupe
    expand, cull = _level_functions(system, box)

    def dedupe_level(proto: np.ndarray, transform: np.ndarray) -> np.ndarray:
        return unique_tiles(proto, transform, system.symmetries)

    proto, transform = substitute_levels(proto, transform, depth, expand, cull, dedupe_level if per_level else None)
    if dedupe is not False and not per_level and system.kind == "overlapping":
        keep = unique_tiles(proto, transform, system.symmetries)
        proto, transform = proto[keep], transform[keep]
    return proto, transform


def generate_chunks(
    system: SubstitutionSystem,
    depth: int,
    seed_transform: np.ndarray | None = None,
    seed_prototile: int | np.ndarray | None = None,
    box: tuple[float, float, float, float] | None = None,
    chunk_tiles: int = STREAM_CHUNK_TILES,
) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """:func:`generate` in chunks of at most ``chunk_tiles`` rule tiles, never the whole patch.

    ``seed_transform`` may be one map or a stack (k, 3, 3) of level-``depth`` seeds (a seed
    cluster) with ``seed_prototile`` an int or k ints. The seeds are substituted to the
    level whose supertiles each become at most ``chunk_tiles`` tiles, and runs of those
    supertiles, in Hilbert order of their inflation discs' centres, are substituted the rest
    of the way (:func:`levels.substitute_in_chunks`). The union of the chunks is what
    :func:`generate` returns for each seed, tile for tile. Overlapping systems remove
    duplicates across a whole level, so they are refused (ParameterError).
    """
    check_chunk_tiles(chunk_tiles)
    if system.kind == "overlapping":
        raise ParameterError(
            f"{system.name} is an overlapping system, whose coincident tiles are removed across a "
            "whole level: it cannot be generated in chunks; ask for a patch that fits in memory"
        )
    proto, transform = _seeds(system, seed_transform, seed_prototile)
    expand, cull = _level_functions(system, box)
    centres, _ = inflation_radii(system)

    def placed_centres(proto: np.ndarray, transform: np.ndarray, n: int) -> np.ndarray:
        return placed_points(proto, transform, centres)

    yield from substitute_in_chunks(proto, transform, depth, expand, cull, system.descendants, placed_centres, chunk_tiles)


def assemble(system: SubstitutionSystem, proto: np.ndarray, transform: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Whole tiles from half-tiles (exercise 6.10), each once.

    Every half-tile names the whole tile it belongs to and where that whole tile lies in its
    frame; mapping each half by its placement gives the whole tile, and the two halves of one
    tile give the same tile modulo the whole tile's mirror symmetry, so the symmetric
    duplicate removal pairs them up (vectorised; a half whose partner lies outside the patch
    still yields its whole tile, which belongs to the same tiling).
    """
    if system.output_prototiles is None:
        return proto, transform
    if system.pairing_edge is not None:
        return pair_halves(system, proto, transform)
    out_proto, out_transform = whole_tiles(system, proto, transform)
    rep = _whole_groups(system, out_proto, out_transform)
    keep = np.flatnonzero(rep == np.arange(len(rep)))
    return out_proto[keep], out_transform[keep]


def whole_tiles(system: SubstitutionSystem, proto: np.ndarray, transform: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every half-tile's whole tile (the [assemble] table), one per half: the halves of one
    whole tile give it twice, by maps that differ by a symmetry of it."""
    assert system.assemble_tile is not None and system.assemble_matrix is not None
    n = len(system.prototiles)
    return expand_by_label(
        proto, transform, [system.assemble_tile[[p]] for p in range(n)], [system.assemble_matrix[[p]] for p in range(n)]
    )


def _whole_groups(system: SubstitutionSystem, proto: np.ndarray, transform: np.ndarray,
                  quantum: float | None = None) -> np.ndarray:
    """For every whole tile of :func:`whole_tiles`, the index of the first copy of it: by
    placed centroid, or by the canonical map when a whole tile's centroid lies outside it."""
    centres = _interior_centroids(system)
    if centres is None:  # a whole tile whose centroid is outside it: compare whole maps
        return tile_groups(proto, transform, system.output_symmetries, quantum)
    return centre_groups(proto, transform, centres, quantum)


def _interior_centroids(system: SubstitutionSystem) -> np.ndarray | None:
    """(k, 2) centroids of the whole tiles, or None when one lies outside its tile."""
    out = []
    for p in system.output_prototiles or []:
        c = centroid(p.outline)
        if not shapely.Polygon(p.outline).contains(shapely.Point(c)):
            return None
        out.append(c)
    return np.array(out)


def centre_quantum(transform: np.ndarray, centres: np.ndarray) -> float:
    """The quantum of :func:`centre_groups`: 1e-4 of the tiles' size (median linear factor
    of the maps) times the prototiles' extent."""
    sigma = np.sqrt(np.abs(_det(transform[:: max(1, len(transform) // 1000)])))
    return 1e-4 * float(np.median(sigma)) * float(np.abs(centres).max() + 1.0)


def centre_groups(proto: np.ndarray, transform: np.ndarray, centres: np.ndarray,
                  quantum: float | None = None) -> np.ndarray:
    """For every tile, the index of the first tile with equal prototile and placed centroid.

    Tiles of a tiling that lie inside one another are the same tile, so when every
    prototile's centroid is interior, (prototile, placed centroid) identifies a placed tile
    whatever symmetry of it its map carries: the two halves of a whole rhomb give it by
    maps differing by its mirror, and the same centroid. Centroids are quantised at
    ``quantum`` (default :func:`centre_quantum`) on two grids offset by half a cell (two
    copies cannot straddle a cell boundary on both); each pass is one hash of a packed int64
    key (kernels.py).
    """
    # start-up cost: numba, as in expand_by_label
    from tilekit.plugins.substitution import kernels

    if len(proto) < 2:
        return np.arange(len(proto))
    if quantum is None:
        quantum = centre_quantum(transform, centres)
    rep = kernels.centre_groups(proto, transform, centres, quantum)
    if rep is None:  # a key wider than 63 bits: group (prototile, cell) rows instead
        c = centres[proto]
        x = transform[:, 0, 0] * c[:, 0] + transform[:, 0, 1] * c[:, 1] + transform[:, 0, 2]
        y = transform[:, 1, 0] * c[:, 0] + transform[:, 1, 1] * c[:, 1] + transform[:, 1, 2]
        q = quantum

        def rows(idx: np.ndarray, offset: float) -> np.ndarray:
            return np.column_stack([proto[idx], np.floor(x[idx] / q + offset), np.floor(y[idx] / q + offset)]).astype(np.int64)

        rep = _two_pass_groups(len(proto), rows)
    return rep


def unique_centres(proto: np.ndarray, transform: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """Indices (sorted) of the first of the tiles with equal prototile and placed centroid
    (:func:`centre_groups`)."""
    rep = centre_groups(proto, transform, centres)
    return np.flatnonzero(rep == np.arange(len(rep)))


def tile_groups(proto: np.ndarray, transform: np.ndarray, groups: Sequence[np.ndarray],
                quantum: float | None = None) -> np.ndarray:
    """For every tile, the index of the first tile placed the same (prototile and map modulo
    the prototile's symmetry ``groups``, quantised at ``quantum``, default KEY_QUANTUM of
    the median linear factor, on two staggered grids)."""
    if len(proto) < 2:
        return np.arange(len(proto))
    if quantum is None:
        quantum = tile_quantum(transform)
    q = quantum

    def rows(idx: np.ndarray, offset: float) -> np.ndarray:
        return _canonical_keys(proto[idx], transform[idx], groups, q, offset)

    return _two_pass_groups(len(proto), rows)


def tile_quantum(transform: np.ndarray) -> float:
    """The quantum of :func:`tile_groups`: KEY_QUANTUM of the maps' median linear factor."""
    sigma = np.sqrt(np.abs(_det(transform)))
    return KEY_QUANTUM * float(np.median(sigma)) if len(sigma) else KEY_QUANTUM


def unique_tiles(proto: np.ndarray, transform: np.ndarray, groups: Sequence[np.ndarray]) -> np.ndarray:
    """Indices of one representative per distinct placed tile (sorted)."""
    rep = tile_groups(proto, transform, groups)
    return np.flatnonzero(rep == np.arange(len(rep)))


def _two_pass_groups(n: int, rows: Any) -> np.ndarray:
    """For each of n tiles, its group's first index: tiles with equal key rows
    ``rows(index, 0.0)`` are grouped, then the groups' first tiles by ``rows(index, 0.5)``
    (the keys on a grid offset by half a cell, so that two copies of a tile that straddle a
    cell boundary of one grid meet on the other)."""
    rep = np.arange(n)
    keep = np.arange(n)
    for offset in (0.0, 0.5):
        _, (order, starts, sizes) = _row_groups(rows(keep, offset))
        first = np.repeat(order[starts], sizes)  # per sorted row: its group's first (local)
        now = np.arange(n)
        now[keep[order]] = keep[first]
        rep = now[rep]
        keep = keep[np.sort(order[starts])]
    return rep


def _row_groups(keys: np.ndarray) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Group equal rows of an int array (much faster than np.unique(axis=0)).

    Rows are sorted by a 64-bit multiplicative hash of their columns; a group starts where
    the hash *or* the full row changes, so distinct rows are never merged (a hash collision
    can at worst split a group, with probability about n^2 / 2^64). Returns the index of the
    first row of each group, and (order, group starts in order, group sizes).
    """
    mult = np.array([0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9, 0xD6E8FEB86659FD93,
                     0xFF51AFD7ED558CCD, 0xC4CEB9FE1A85EC53, 0x94D049BB133111EB, 0xBF58476D1CE4E5B9],
                    dtype=np.uint64)[: keys.shape[1]]
    with np.errstate(over="ignore"):
        h = (keys.astype(np.uint64) * mult).sum(axis=1, dtype=np.uint64)
        h ^= h >> np.uint64(31)
    order = np.argsort(h, kind="stable")
    hs = h[order]
    ordered = keys[order]
    new = np.r_[True, (hs[1:] != hs[:-1]) | np.any(ordered[1:] != ordered[:-1], axis=1)]
    starts = np.flatnonzero(new)
    sizes = np.diff(np.r_[starts, len(keys)])
    return order[starts], (order, starts, sizes)


def _canonical_keys(
    proto: np.ndarray, transform: np.ndarray, groups: Sequence[np.ndarray], quantum: float, offset: float
) -> np.ndarray:
    """(prototile, quantised 2x3 map) rows, the map canonicalised modulo the symmetry group.

    Among the candidates T @ S (S in the prototile's group) the canonical one minimises
    (orientation reversed?, angle of the first column, offset by an irrational amount so that
    no orientation used by a tiling sits on the wrap-around). Distinct candidates differ by
    at least the group's smallest rotation or in handedness, so float noise cannot make two
    copies of one tile choose different candidates.
    """
    keys = np.zeros((len(proto), 7), dtype=np.int64)
    keys[:, 0] = proto
    for p, group in enumerate(groups):
        idx = np.flatnonzero(proto == p)
        if not len(idx):
            continue
        sub = transform[idx][:, :2, :]
        if len(group) == 1:
            best = sub
        else:
            # the candidates' angles and handedness follow from T's and each symmetry's,
            # so only the chosen product is ever formed
            det_t = sub[:, 0, 0] * sub[:, 1, 1] - sub[:, 0, 1] * sub[:, 1, 0]
            theta = np.arctan2(sub[:, 1, 0], sub[:, 0, 0])
            phi = np.arctan2(group[:, 1, 0], group[:, 0, 0])
            det_g = group[:, 0, 0] * group[:, 1, 1] - group[:, 0, 1] * group[:, 1, 0]
            sign = np.where(det_t < 0, -1.0, 1.0)
            angle = np.mod(theta[:, None] + sign[:, None] * phi[None, :] + 0.7236, 2 * np.pi)
            score = angle + 10.0 * ((det_t[:, None] * det_g[None, :]) < 0)
            choice = np.argmin(score, axis=1)
            best = np.matmul(transform[idx], group[choice])[:, :2, :]
        keys[idx, 1:] = np.floor(best.reshape(-1, 6) / quantum + offset).astype(np.int64)
    return keys


def pair_halves(system: SubstitutionSystem, proto: np.ndarray, transform: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Whole tiles from half-tiles that share their pairing edge (exercise 6.10, vectorised).

    Each half's pairing edge is keyed by its quantised, unordered end points; halves with
    equal keys are partners. A partner of opposite handedness makes the "mirror" whole tile,
    one of the same handedness the "turn" whole tile, placed in the frame of the partner
    with positive determinant (or the first one). Halves whose partner is not in the patch
    are dropped: generate a margin around the region you need.
    """
    assert system.pairing_edge is not None and system.output_prototiles is not None
    if not len(proto):
        return proto, transform
    (i, j), _ = _partners(system, transform, pairing_quantum(transform))
    return _paired(system, transform, i, j)


def pairing_quantum(transform: np.ndarray) -> float:
    """The quantum of the pairing edges' end points: 100 KEY_QUANTUM of the tiles' size."""
    return KEY_QUANTUM * 100 * float(np.median(np.sqrt(np.abs(_det(transform)))))


def _partners(system: SubstitutionSystem, transform: np.ndarray,
              quantum: float) -> tuple[tuple[np.ndarray, np.ndarray], np.ndarray]:
    """((i, j) the index pairs of partner halves, the indices of halves without a partner)."""
    assert system.pairing_edge is not None
    a, b = system.pairing_edge
    ends = Affine.apply(transform, system.prototiles[0].outline[[a, b]])  # (n, 2, 2)
    q = np.floor(ends / quantum + 0.5).astype(np.int64).reshape(-1, 2, 2)
    first_smaller = (q[:, 0, 0] < q[:, 1, 0]) | ((q[:, 0, 0] == q[:, 1, 0]) & (q[:, 0, 1] <= q[:, 1, 1]))
    lo = np.where(first_smaller[:, None], q[:, 0], q[:, 1])
    hi = np.where(first_smaller[:, None], q[:, 1], q[:, 0])
    keys = np.column_stack([lo, hi])
    _, (order, starts, sizes) = _row_groups(keys)
    pairs = starts[sizes == 2]
    return (order[pairs], order[pairs + 1]), order[starts[sizes == 1]]


def _paired(system: SubstitutionSystem, transform: np.ndarray, i: np.ndarray, j: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The whole tiles of the partner halves (i[k], j[k])."""
    di, dj = _det(transform[i]) > 0, _det(transform[j]) > 0
    ref = np.where(dj & ~di, j, i)
    mirror = di != dj
    out_p, out_t = [], []
    for relation, mask in (("mirror", mirror), ("turn", ~mirror)):
        if not mask.any():
            continue
        if relation not in system.pairing:
            continue
        tile, placement = system.pairing[relation]
        out_p.append(np.full(int(mask.sum()), tile, dtype=np.int64))
        out_t.append(np.matmul(transform[ref[mask]], placement))
    if not out_p:
        return np.zeros(0, dtype=np.int64), np.zeros((0, 3, 3))
    return np.concatenate(out_p), np.concatenate(out_t)


# --------------------------------------------------------------------------- streams


def assemble_chunks(system: SubstitutionSystem,
                    chunks: Iterable[tuple[np.ndarray, np.ndarray]]) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """:func:`assemble` over a stream of rule-tile chunks, whose union is a patch.

    The halves of one whole tile may come in different chunks: a whole tile is yielded once
    all its halves have come (by their areas, the halves' share of the whole tile adds up to
    1) and waits in a pending buffer until then, keyed exactly as :func:`assemble` keys it
    (prototile and placed centroid, or the pairing edge); each chunk is grouped together
    with the pending tiles. At the end what is still pending is handled as :func:`assemble`
    handles a half without its partner: its whole tile is yielded (pairing systems drop
    it). The union of the yielded chunks is ``assemble`` of the union of ``chunks``, as a
    set of placed tiles; pending holds the tiles along the edges of the chunks so far.
    """
    if system.output_prototiles is None:
        yield from chunks
    elif system.pairing_edge is not None:
        yield from _pair_chunks(system, chunks)
    else:
        yield from _whole_chunks(system, chunks)


def _whole_chunks(system: SubstitutionSystem,
                  chunks: Iterable[tuple[np.ndarray, np.ndarray]]) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    assert system.output_prototiles is not None and system.assemble_tile is not None
    share = np.array([abs(p.area) / abs(system.output_prototiles[int(t)].area)
                      for p, t in zip(system.prototiles, system.assemble_tile)])
    centres = _interior_centroids(system)
    pend_p, pend_t, pend_w = np.zeros(0, dtype=np.int64), np.zeros((0, 3, 3)), np.zeros(0)
    quantum: float | None = None
    for proto, transform in chunks:
        if not len(proto):
            continue
        wp, wt = whole_tiles(system, proto, transform)
        if quantum is None:  # fixed for the stream: every tile of a depth has one size
            quantum = tile_quantum(wt) if centres is None else centre_quantum(wt, centres)
        p, t = np.concatenate([pend_p, wp]), np.concatenate([pend_t, wt])
        w = np.concatenate([pend_w, share[proto]])
        rep = _whole_groups(system, p, t, quantum)
        first = np.flatnonzero(rep == np.arange(len(rep)))
        have = np.bincount(rep, weights=w, minlength=len(rep))[first]
        whole = have >= 1 - 1e-6
        yield p[first[whole]], t[first[whole]]
        pend_p, pend_t, pend_w = p[first[~whole]], t[first[~whole]], have[~whole]
    if len(pend_p):
        yield pend_p, pend_t


def _pair_chunks(system: SubstitutionSystem,
                 chunks: Iterable[tuple[np.ndarray, np.ndarray]]) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    pend_p, pend_t = np.zeros(0, dtype=np.int64), np.zeros((0, 3, 3))
    quantum: float | None = None
    for proto, transform in chunks:
        if not len(proto):
            continue
        if quantum is None:
            quantum = pairing_quantum(transform)
        p, t = np.concatenate([pend_p, proto]), np.concatenate([pend_t, transform])
        (i, j), single = _partners(system, t, quantum)
        yield _paired(system, t, i, j)
        pend_p, pend_t = p[single], t[single]
    # halves still without a partner are dropped, as pair_halves drops them


def _det(m: np.ndarray) -> np.ndarray:
    return m[..., 0, 0] * m[..., 1, 1] - m[..., 0, 1] * m[..., 1, 0]

