"""The symmetry group of a periodic tiling (§3.5), its wallpaper type (§3.2, §3.6.3), colourings (§3.6.1).

``symmetries(tiling)`` finds every isometry that maps the tiling onto itself, by testing the
congruences of one tile onto the tiles of the translational unit against the geometry of
the whole unit (outlines and markings); ``wallpaper_group(tiling)`` names the group among
the 17 (orbifold and IUC names); ``colouring_report(tiling)`` / ``is_perfect_colouring``
decide whether every symmetry of the uncoloured tiling permutes the colours (§3.6.1);
``tile_orbits`` / ``vertex_orbits`` give the transitivity classes (k-isohedral,
k-isogonal). The method, tolerances and limits are described in docs/symmetry.md.

The group is returned as a lattice of translations plus one coset representative per
element of the point group: every symmetry is ``T(L) @ op`` for exactly one representative
``op`` and one lattice vector ``L``.

One job per module: :mod:`.names` (the 17 groups' IUC and orbifold names), :mod:`.lattice`
(2D lattice algebra), :mod:`.results` (the returned types), :mod:`.cell` (a period cell as
arrays), :mod:`.matching` (congruences, locating tiles), :mod:`.group` (the group search),
:mod:`.classify` (naming the wallpaper group), :mod:`.congruence` (one tiling onto another),
:mod:`.orbits` (transitivity classes), :mod:`.perfect` (perfect colourings).
"""

from __future__ import annotations

from typing import Any

from tilekit.symmetry.cell import DEFAULT_TOL, _abs_tol, _base_cell, _check, absolute_tolerance
from tilekit.symmetry.classify import classify_group, wallpaper_group
from tilekit.symmetry.congruence import congruence, congruent
from tilekit.symmetry.group import _group_of_cell, group_from_maps, symmetries
from tilekit.symmetry.lattice import canonical_basis, reduce_basis, successive_minima
from tilekit.symmetry.names import IUC, ORBIFOLD
from tilekit.symmetry.orbits import (
    _tile_orbits_of,
    _vertex_orbits_of,
    isogonality,
    isohedrality,
    tile_orbits,
    tiling_vertices,
    vertex_orbits,
)
from tilekit.symmetry.perfect import _perfect, colouring_report, is_perfect_colouring
from tilekit.symmetry.results import ColouringReport, Operation, SymmetryGroup, WallpaperGroup
from tilekit.tiling import PeriodicTiling

__all__ = [
    "DEFAULT_TOL",
    "IUC",
    "ORBIFOLD",
    "ColouringReport",
    "Operation",
    "SymmetryGroup",
    "WallpaperGroup",
    "canonical_basis",
    "classify_group",
    "absolute_tolerance",
    "colouring_report",
    "congruence",
    "congruent",
    "group_from_maps",
    "is_perfect_colouring",
    "isogonality",
    "isohedrality",
    "reduce_basis",
    "successive_minima",
    "symmetries",
    "symmetry_properties",
    "tile_orbits",
    "tiling_vertices",
    "vertex_orbits",
    "wallpaper_group",
]


def symmetry_properties(
    tiling: PeriodicTiling, tol: float = DEFAULT_TOL, *, colouring: bool = True, vertices: bool = True
) -> dict[str, Any]:
    """The symmetry facts a catalogue record wants, from one computation of the group.

    Keys: wallpaper_group, orbifold, point_group_order, rotation_orders, reflections,
    glide_reflections (as ``WallpaperGroup.properties``), k_isohedral (tile classes),
    k_isogonal (vertex classes; omitted with ``vertices=False``) and perfect_colouring
    (whether the tiling's own colouring is perfect; omitted with ``colouring=False``).
    All values are JSON scalars or lists.
    """
    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    cell = _base_cell(tiling, abs_tol, False)
    group = _group_of_cell(cell)
    props = classify_group(group).properties()
    props["k_isohedral"] = int(_tile_orbits_of(cell, group).max()) + 1
    if vertices:
        props["k_isogonal"] = int(_vertex_orbits_of(tiling, group, tol)[1].max()) + 1
    if colouring:
        props["perfect_colouring"] = bool(_perfect(tiling, tol, False, group)[0])
    return props
