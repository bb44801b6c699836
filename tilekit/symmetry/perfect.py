"""Perfect colourings (§3.6.1, §5.4.3): does every symmetry of the uncoloured tiling permute
the colours?"""

from __future__ import annotations

import numpy as np

from tilekit.symmetry.cell import DEFAULT_TOL, _abs_tol, _base_cell, _Cell, _check, _colour_cell
from tilekit.symmetry.classify import classify_group
from tilekit.symmetry.group import _colour_group, _colour_maps, _group_of_cell
from tilekit.symmetry.lattice import _cell_area
from tilekit.symmetry.results import ColouringReport, Operation, SymmetryGroup
from tilekit.tiling import PeriodicTiling


def colouring_report(
    tiling: PeriodicTiling, tol: float = DEFAULT_TOL, *, match_prototiles: bool = False
) -> ColouringReport:
    """Decide whether the tiling's colouring is perfect (§3.6.1, §5.4.3), with the evidence.

    A colouring is perfect when every symmetry of the uncoloured tiling maps all tiles of
    one colour onto tiles of one colour (so it induces a permutation of the colours). It
    suffices to test a generating set of the group — the lattice translations and one
    representative per point-group coset — on a cell of the coloured tiling whose lattice
    every symmetry preserves, since induced permutations compose. The report also gives
    the wallpaper group of the colour-preserving symmetries and its index.
    """
    perfect, gens, perms, cell, group, n = _perfect(tiling, tol, match_prototiles)
    violation = None
    if not perfect:
        bad = perms.index(None)
        violation = f"the symmetry {gens[bad]!r} sends tiles of one colour to tiles of different colours"
    colour_group = _colour_group(cell, group, n)
    index = (group.point_group_order * _cell_area(colour_group.lattice)) / (
        colour_group.point_group_order * _cell_area(group.lattice)
    )
    return ColouringReport(
        perfect=perfect,
        colours=len(np.unique(cell.colour)),
        symmetry=classify_group(group),
        colour_group=classify_group(colour_group),
        index=int(round(index)),
        generators=gens,
        permutations=tuple(perms),
        violation=violation,
    )


def _perfect(
    tiling: PeriodicTiling, tol: float, match_prototiles: bool, group: SymmetryGroup | None = None
) -> tuple[bool, tuple[Operation, ...], list[tuple[int, ...] | None], _Cell, SymmetryGroup, int]:
    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    if group is None:
        group = _group_of_cell(_base_cell(tiling, abs_tol, match_prototiles))
    cell, n = _colour_cell(tiling, group, abs_tol, match_prototiles)
    gens = group.translations() + tuple(op for op in group.operations if op.kind != "identity")
    perms = _colour_maps(cell, np.array([g.matrix for g in gens]))
    return all(p is not None for p in perms), gens, perms, cell, group, n


def is_perfect_colouring(
    tiling: PeriodicTiling,
    tol: float = DEFAULT_TOL,
    *,
    match_prototiles: bool = False,
    group: SymmetryGroup | None = None,
) -> bool:
    """True when every symmetry of the uncoloured tiling permutes the colours (§3.6.1).

    ``group``: the tiling's symmetry group when the caller already knows it (a family whose
    type tables give it, through :func:`tilekit.symmetry.group_from_maps`); the search for
    it is then skipped.
    """
    return _perfect(tiling, tol, match_prototiles, group)[0]
