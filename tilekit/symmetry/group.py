"""The symmetry group of a periodic tiling (§3.5): candidate congruences accepted on the whole
cell, the true lattice, one tidy representative per point-group coset, and the subgroup of
colour-preserving symmetries."""

from __future__ import annotations

import math

import numpy as np

from tilekit.errors import GeometryError
from tilekit.geometry import Affine
from tilekit.polygon import congruences
from tilekit.symmetry.cell import DEFAULT_TOL, _abs_tol, _base_cell, _Cell, _check, _colour_cell
from tilekit.symmetry.lattice import (
    _cell_area,
    _frac,
    _lattice_from,
    _lattice_residual,
    _small_combos,
)
from tilekit.symmetry.matching import _images, _locate
from tilekit.symmetry.results import Operation, SymmetryGroup, _operation
from tilekit.tiling import PeriodicTiling


def _cosets(maps: np.ndarray, lattice: np.ndarray, tol: float) -> tuple[Operation, ...]:
    """One canonical representative per distinct linear part of ``maps`` (identity first)."""
    key = np.round(maps[:, :2, :2].reshape(-1, 4) * 1e5).astype(np.int64)
    _, first = np.unique(key, axis=0, return_index=True)
    out = [_canonical(maps[i], lattice, tol) for i in np.sort(first)]
    out.sort(key=_op_sort_key)
    return tuple(out)


def _op_sort_key(op: Operation) -> tuple:
    kinds = ["identity", "translation", "rotation", "reflection", "glide reflection"]
    iso = op.isometry
    ang = iso.angle % (2 * math.pi) if iso.kind == "rotation" else iso.angle
    return (kinds.index(iso.kind) if iso.kind in kinds else 9, round(ang, 6))


def _canonical(g: np.ndarray, lattice: np.ndarray, tol: float) -> Operation:
    """A tidy representative of the coset g + lattice.

    Identity for the translation coset; a rotation centre in the cell nearest the origin;
    for an opposite map, a pure reflection if the coset has one, else the shortest glide.
    """
    g = np.array(g, dtype=float)
    lin, t = g[:2, :2], g[:2, 2]
    f = _frac(t, lattice)
    t = (f - np.floor(f + 1e-9)) @ lattice
    det = lin[0, 0] * lin[1, 1] - lin[0, 1] * lin[1, 0]
    combos = _small_combos(lattice, 4)
    if det > 0:
        if np.allclose(lin, np.eye(2), atol=1e-6):
            return _operation(np.eye(3))
        # rotation: choose the translation whose centre is closest to the origin
        ts = t[None, :] + combos
        centres = np.linalg.solve(np.eye(2) - lin, ts.T).T
        best = int(np.argmin(np.round(np.hypot(centres[:, 0], centres[:, 1]) / tol)))
        m = np.eye(3)
        m[:2, :2] = lin
        m[:2, 2] = ts[best]
        return _operation(m)
    phi = 0.5 * math.atan2(lin[1, 0], lin[0, 0])
    u = np.array([math.cos(phi), math.sin(phi)])
    nrm = np.array([-u[1], u[0]])
    ts = t[None, :] + combos
    glide = np.abs(ts @ u)
    offset = np.abs(ts @ nrm)
    key = np.round(glide / tol) * 1e6 + np.round(offset / tol) * 1e-3
    best = int(np.argmin(key))
    m = np.eye(3)
    m[:2, :2] = lin
    m[:2, 2] = ts[best]
    return _operation(m)


def _assemble(accepted: np.ndarray, given: np.ndarray, tol: float, coloured: bool) -> SymmetryGroup:
    """Build the group from maps accepted modulo the lattice ``given`` (rows)."""
    lin = accepted[:, :2, :2]
    is_t = np.all(np.abs(lin - np.eye(2)) < 1e-6, axis=(1, 2))
    trans = accepted[is_t, :2, 2]
    index = int(is_t.sum())
    lattice = _lattice_from(trans, given, max(index, 1), tol)
    # a candidate that maps the cell's tiles onto tiles is a symmetry only if its linear part
    # maps the lattice into the translation group (then it maps every translate correctly)
    moved = np.einsum("kj,nij->nki", lattice, accepted[:, :2, :2])  # R w for each map, basis row
    keep = (_lattice_residual(moved, lattice) < tol * 10).all(axis=1)
    ops = _cosets(accepted[keep], lattice, tol)
    return SymmetryGroup(lattice=lattice, operations=ops, lattice_index=index, tol=tol, coloured=coloured)


#: Tiles near the anchor on which every candidate is tried before the whole cell.
_PROBE = 6


def _accepts(cell: _Cell, maps: np.ndarray, anchor: int, target: _Cell | None = None) -> np.ndarray:
    """Which maps send every tile of the cell onto a tile of the tiling (of ``target``'s
    tiling when given: a congruence of one tiling onto another, labels numbered alike).

    Candidates are first tried on the few tiles nearest the anchor, which rejects almost
    every wrong one, and only the survivors on the whole cell.
    """
    target = cell if target is None else target
    ok = np.zeros(len(maps), dtype=bool)
    if not len(maps):
        return ok
    m = len(cell)
    alive = np.arange(len(maps))
    if m > _PROBE:
        near = np.argsort(np.hypot(*(cell.centre - cell.centre[anchor]).T), kind="stable")[:_PROBE]
        pts, cen, lab = _images(cell, maps, near)
        found, _ = _locate(target, pts, cen, lab)
        alive = alive[(found >= 0).reshape(len(maps), len(near)).all(axis=1)]
    if len(alive):
        pts, cen, lab = _images(cell, maps[alive])
        found, _ = _locate(target, pts, cen, lab)
        ok[alive[(found >= 0).reshape(len(alive), m).all(axis=1)]] = True
    return ok


def _primitive(cell: _Cell, lattice: np.ndarray) -> _Cell:
    """The cell's tiles modulo a finer lattice (one tile per class), over that lattice."""
    f = _frac(cell.centre, lattice)
    key = np.round((f - np.floor(f)) * 1e6).astype(np.int64) % 1_000_000
    _, first = np.unique(np.column_stack([key, cell.label]), axis=0, return_index=True)
    keep = np.sort(first)
    return _Cell(
        [cell.outlines[i] for i in keep],
        cell.points[keep],
        cell.count[keep],
        cell.centre[keep],
        cell.label[keep],
        cell.colour[keep],
        lattice,
        cell.tol,
    )


def _group_of_cell(cell: _Cell) -> SymmetryGroup:
    counts = np.bincount(cell.label)
    anchor = int(np.argmin(counts[cell.label] * 10_000 + np.arange(len(cell))))
    a = cell.outlines[anchor]
    cands = [
        congruences(a, cell.outlines[j], cell.tol)
        for j in range(len(cell))
        if cell.label[j] == cell.label[anchor]
    ]
    maps = np.concatenate([c for c in cands if len(c)]) if any(len(c) for c in cands) else np.zeros((0, 3, 3))
    if not len(maps):
        raise GeometryError("no tile of the unit is congruent to its first tile: the unit is malformed")
    # translations first: when the unit is not primitive, continue on a primitive cell
    is_t = np.all(np.abs(maps[:, :2, :2] - np.eye(2)) < 1e-6, axis=(1, 2))
    trans = maps[is_t][_accepts(cell, maps[is_t], anchor)]
    if not len(trans):
        raise GeometryError(
            "the identity is not a symmetry of the unit: tiles overlap or repeat within the unit"
        )
    if len(trans) > 1:
        lattice = _lattice_from(trans[:, :2, 2], cell.basis, len(trans), cell.tol)
        prim = _primitive(cell, lattice)
        if len(prim) * len(trans) != len(cell):
            raise GeometryError(
                f"the unit's {len(cell)} tiles do not fall into {len(trans)} translates of a "
                "primitive cell: tiles overlap or repeat within the unit"
            )
        sub = _group_of_cell(prim)
        return SymmetryGroup(sub.lattice, sub.operations, len(trans) * sub.lattice_index, sub.tol)
    rest = maps[~is_t]
    accepted = np.concatenate([trans, rest[_accepts(cell, rest, anchor)]])
    return _assemble(accepted, cell.basis, cell.tol, coloured=False)


def symmetries(
    tiling: PeriodicTiling,
    tol: float = DEFAULT_TOL,
    *,
    colours: bool = False,
    match_prototiles: bool = False,
) -> SymmetryGroup:
    """The symmetry group of a periodic tiling (§3.5).

    Every symmetry maps the unit's anchor tile onto some tile, and modulo the lattice onto
    a tile of the unit, so the candidates are the congruences (rotations and reflections of
    the outline's point cycle) of the anchor onto each unit tile. A candidate is accepted
    when it maps every tile of the unit onto a tile of the tiling — compared by outline and
    marking point sets, up to a lattice translation — and its linear part preserves the
    translation lattice. Candidates that are translations reveal the true lattice, which
    may be finer than v1, v2 (``lattice_index`` > 1).

    ``tol`` is relative to the tiling's length scale (the square root of the median tile
    area). With ``colours=True`` only colour-preserving symmetries count. Tiles are matched
    by geometry; ``match_prototiles=True`` also requires the same prototile index (for
    congruent prototiles that a family wants kept apart).
    """
    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    group = _group_of_cell(_base_cell(tiling, abs_tol, match_prototiles))
    if not colours:
        return group
    cell, n = _colour_cell(tiling, group, abs_tol, match_prototiles)
    return _colour_group(cell, group, n)


def _colour_group(cell: _Cell, group: SymmetryGroup, n: int) -> SymmetryGroup:
    """The colour-preserving subgroup: elements (modulo n*L) that keep every tile's colour.

    Each element T(s) op of the group modulo n*L permutes the cell's tiles; the permutation
    is composed from those of the coset representatives and of the two lattice
    translations, so only |P| + 2 maps are ever located, not |P| n^2.
    """
    reps = np.array([op.matrix for op in group.operations])
    steps = np.array([Affine.translation(*v) for v in group.lattice])
    perm = _tile_perm(cell, np.concatenate([reps, steps]))
    rep_perm, (w1, w2) = perm[: len(reps)], perm[len(reps) :]
    ident = np.arange(len(cell))
    shift_perm = []
    pa = ident
    for _a in range(n):
        pb = pa
        for _b in range(n):
            shift_perm.append(pb)
            pb = w2[pb]
        pa = w1[pa]
    moved = np.array(shift_perm)[:, rep_perm]  # (n^2, |P|, m): tile t -> shift(rep(t))
    good = (cell.colour[moved] == cell.colour).all(axis=2).reshape(-1)
    elems = _elements_mod(group, n)
    sub = _assemble(elems[good], cell.basis, cell.tol, coloured=True)
    coarser = int(round(_cell_area(sub.lattice) / _cell_area(group.lattice)))
    return SymmetryGroup(sub.lattice, sub.operations, coarser, sub.tol, coloured=True)


def _tile_perm(cell: _Cell, maps: np.ndarray) -> np.ndarray:
    """(len(maps), m): the cell tile (modulo the cell's lattice) each map sends each tile to."""
    pts, cen, lab = _images(cell, maps)
    found, _ = _locate(cell, pts, cen, lab)
    if (found < 0).any():
        raise GeometryError("a symmetry of the tiling failed to map the coloured cell onto itself")
    return found.reshape(len(maps), len(cell))


def _elements_mod(group: SymmetryGroup, n: int) -> np.ndarray:
    """The group's elements modulo the lattice n * L (L the group's lattice), as (|P| n^2, 3, 3)."""
    a, b = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    shifts = np.column_stack([a.ravel(), b.ravel()]) @ group.lattice
    reps = np.array([op.matrix for op in group.operations])
    out = np.broadcast_to(reps, (len(shifts),) + reps.shape).copy()
    out[:, :, :2, 2] += shifts[:, None, :]
    return out.reshape(-1, 3, 3)


def _colour_maps(cell: _Cell, maps: np.ndarray) -> list[tuple[int, ...] | None]:
    """For each symmetry in ``maps``, the colour permutation it induces on ``cell``, or None."""
    found = _tile_perm(cell, maps)
    k = int(cell.colour.max()) + 1
    used = np.unique(cell.colour)
    out: list[tuple[int, ...] | None] = []
    for row in found:
        src, dst = cell.colour, cell.colour[row]
        perm = np.arange(k)
        perm[src] = dst
        consistent = np.array_equal(perm[src], dst) and len(np.unique(perm[used])) == len(used)
        out.append(tuple(int(x) for x in perm) if consistent else None)
    return out


def group_from_maps(maps: np.ndarray, lattice: np.ndarray, tol: float) -> SymmetryGroup:
    """The symmetry group generated by ``lattice`` (rows) and the isometries ``maps`` (n, 3, 3),
    for a family that already knows its symmetries modulo the lattice (the isohedral types'
    aspects composed with the tile's symmetries): no candidate search, the same
    representatives, reduced lattice and coset tidying as :func:`symmetries`. ``tol`` is
    absolute. Maps with the identity linear part refine the lattice (as a non-primitive unit
    would)."""
    maps = np.asarray(maps, dtype=float)
    lattice = np.asarray(lattice, dtype=float)
    lin = maps[:, :2, :2]
    if not np.any(np.all(np.abs(lin - np.eye(2)) < 1e-6, axis=(1, 2))):
        maps = np.concatenate([np.eye(3)[None], maps])
    return _assemble(maps, lattice, tol, coloured=False)
