"""Transitivity classes of tiles and of vertices under the symmetry group (k-isohedral,
k-isogonal, §3.5, §5.1)."""

from __future__ import annotations

from typing import Any

import numpy as np

from tilekit.errors import GeometryError
from tilekit.geometry import Affine
from tilekit.polygon import vertex_stars
from tilekit.symmetry.cell import DEFAULT_TOL, _abs_tol, _base_cell, _Cell, _check
from tilekit.symmetry.group import _group_of_cell
from tilekit.symmetry.lattice import _frac, _inv2
from tilekit.symmetry.matching import _images, _locate
from tilekit.symmetry.results import SymmetryGroup
from tilekit.tiling import PeriodicTiling


def union_find(n: int, pairs: np.ndarray) -> np.ndarray:
    """Connected components of 0..n-1 under the (k, 2) pairs, labelled 0.. in first-seen order
    (so item 0 is in component 0). On Python lists: indexing a NumPy array element by element
    was 8x slower on the torus search's hot path (:mod:`tilekit.plugins.polyomino.torus`)."""
    parent = list(range(n))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b in np.asarray(pairs, dtype=np.int64).reshape(-1, 2).tolist():
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    roots = [root(i) for i in range(n)]
    order = {r: k for k, r in enumerate(dict.fromkeys(roots))}
    return np.array([order[r] for r in roots], dtype=np.int64)


def _generator_maps(group: SymmetryGroup) -> np.ndarray:
    ops = [op.matrix for op in group.operations if op.kind != "identity"]
    ops += [Affine.translation(*v) for v in group.lattice]
    return np.array(ops)


def tile_orbits(
    tiling: PeriodicTiling, tol: float = DEFAULT_TOL, *, match_prototiles: bool = False
) -> np.ndarray:
    """The transitivity class of each tile of the unit under the symmetry group (§3.5, §5.1).

    Returns one label per unit tile (0 for tile 0's orbit, then in order of first
    appearance); the number of labels is the k of a k-isohedral tiling.
    """
    tiling = _check(tiling)
    cell = _base_cell(tiling, _abs_tol(tiling, tol), match_prototiles)
    return _tile_orbits_of(cell, _group_of_cell(cell))


def _tile_orbits_of(cell: _Cell, group: SymmetryGroup) -> np.ndarray:
    maps = _generator_maps(group)
    pts, cen, lab = _images(cell, maps)
    found, _ = _locate(cell, pts, cen, lab)
    src = np.tile(np.arange(len(cell)), len(maps))
    if (found < 0).any():
        raise GeometryError("a symmetry failed to map the unit's tiles onto tiles (tolerance too tight?)")
    return union_find(len(cell), np.column_stack([src, found]))


def patch_tile_classes(tiling: PeriodicTiling, patch: Any, tol: float = DEFAULT_TOL) -> np.ndarray | None:
    """The transitivity class (:func:`tile_orbits` label) of each tile of a patch that
    ``tiling.patch`` made, read through the tile's aspect; None when the unit gives two tiles
    of different classes one aspect, so that the aspect does not tell the class."""
    tiling = _check(tiling)
    orbit = tile_orbits(tiling, tol)
    pairs = np.unique(np.column_stack([tiling.unit_aspect, orbit]), axis=0)
    if len(np.unique(pairs[:, 0])) != len(pairs):
        return None
    by_aspect = np.full(int(pairs[:, 0].max()) + 1, -1, dtype=np.int64)
    by_aspect[pairs[:, 0]] = pairs[:, 1]
    aspect = np.asarray(patch.aspect)
    if len(aspect) and (aspect.min() < 0 or aspect.max() >= len(by_aspect) or (by_aspect[aspect] < 0).any()):
        return None
    return by_aspect[aspect]


def isohedrality(tiling: PeriodicTiling, tol: float = DEFAULT_TOL) -> int:
    """k such that the tiling is k-isohedral: the number of transitivity classes of tiles."""
    return int(tile_orbits(tiling, tol).max()) + 1


def tiling_vertices(tiling: PeriodicTiling, tol: float = DEFAULT_TOL) -> np.ndarray:
    """One point per vertex of the tiling modulo the lattice of v1, v2 (§5.1).

    A vertex is a point where three or more tiles meet. Candidates are the tiles' corners
    (``Prototile.corners`` where given, else every outline point); a candidate is kept when
    at least three tiles of the surrounding patch reach it, so points that only shape an
    edge, or the straight angle of a tile drawn with a point mid-edge, are not vertices.
    """
    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    basis = np.array([tiling.v1, tiling.v2])
    cand = []
    for p, m in zip(tiling.unit_prototile, tiling.unit_transform):
        proto = tiling.prototiles[int(p)]
        pts = proto.outline if proto.corners is None else proto.outline[list(proto.corners)]
        cand.append(Affine.apply(m, pts))
    cand = np.vstack(cand)
    f = _frac(cand, basis)
    f = f - np.floor(f + 1e-9)
    reduced = f @ basis
    key = np.round(f * 1e6).astype(np.int64) % 1_000_000
    _, first = np.unique(key, axis=0, return_index=True)
    reduced = reduced[np.sort(first)]
    # tiles around the fundamental cell
    lo, hi = reduced.min(axis=0), reduced.max(axis=0)
    ub = tiling.unit_tile_bounds()
    pad = float(max(ub[:, 2].max() - ub[:, 0].min(), ub[:, 3].max() - ub[:, 1].min()))
    patch = tiling.patch((lo[0] - pad, lo[1] - pad, hi[0] + pad, hi[1] + pad))
    corners = []
    for p, proto in enumerate(patch.prototiles):
        pts = proto.outline if proto.corners is None else proto.outline[list(proto.corners)]
        corners.extend(Affine.apply(patch.transform[patch.prototile == p], pts))
    stars = vertex_stars(corners, quantum=abs_tol)
    reach = stars.reach(patch.geometries(), abs_tol * 10)
    found = stars.find(reduced)
    return reduced[(found >= 0) & (reach[np.maximum(found, 0)] >= 3)]


def vertex_orbits(tiling: PeriodicTiling, tol: float = DEFAULT_TOL) -> tuple[np.ndarray, np.ndarray]:
    """Vertices modulo the lattice (as ``tiling_vertices``) and their transitivity classes.

    The number of classes is the k of a k-isogonal tiling (1 for the regular and the
    Archimedean tilings, §5.1).
    """
    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    group = _group_of_cell(_base_cell(tiling, abs_tol, False))
    return _vertex_orbits_of(tiling, group, tol)


def _vertex_orbits_of(tiling: PeriodicTiling, group: SymmetryGroup, tol: float) -> tuple[np.ndarray, np.ndarray]:
    abs_tol = _abs_tol(tiling, tol)
    verts = tiling_vertices(tiling, tol)
    basis = np.array([tiling.v1, tiling.v2])
    inv = _inv2(basis)
    pairs = []
    for g in _generator_maps(group):
        img = Affine.apply(g, verts)
        f = (img[:, None, :] - verts[None, :, :]) @ inv
        resid = np.linalg.norm((f - np.rint(f)) @ basis, axis=2)
        hit = resid < abs_tol * 10
        if not hit.any(axis=1).all():
            raise GeometryError("a symmetry failed to map the tiling's vertices onto vertices")
        pairs.append(np.column_stack([np.arange(len(verts)), hit.argmax(axis=1)]))
    labels = union_find(len(verts), np.vstack(pairs)) if pairs else np.zeros(len(verts), dtype=np.int64)
    return verts, labels


def isogonality(tiling: PeriodicTiling, tol: float = DEFAULT_TOL) -> int:
    """k such that the tiling is k-isogonal: the number of transitivity classes of vertices."""
    return int(vertex_orbits(tiling, tol)[1].max()) + 1
