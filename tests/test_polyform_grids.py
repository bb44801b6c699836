"""Polyforms on the hexagonal and triangular grids: the isohedral test and the classification
against Myers' and Kaplan's published counts.

Oracles (OEIS, offset 1; Joseph Myers' polyform tiling data):
A075214 polyhexes that tile isohedrally, A075215 anisohedral polyhexes, A070766 polyhexes that
tile, A070768 hole-free polyhexes that do not tile; A075223 / A075224 / A071332 / A071334 the
same for polyiamonds.
"""

from __future__ import annotations

import pytest

from tilekit.lattice import HEXAGONAL, SQUARE, TRIANGULAR, enumerate_free
from tilekit.plugins.polyomino.isohedral import _template_arrays, analyse, periodic_tiling

# n = 1.. ; the sequences' first terms
A075214 = [1, 1, 3, 7, 22, 76, 290, 1018, 3715]  # isohedral polyhexes
A075223 = [1, 1, 1, 3, 4, 12, 23, 66, 133, 316, 514, 1987, 2398]  # isohedral polyiamonds


def _hole_free(grid, n):
    polys, holes, _ = enumerate_free(grid, n, maxsize=n, with_holes=True)
    return [p for p, h in zip(polys, holes) if len(p) == n and not h]


def _isohedral_count(grid, n):
    return sum(analyse(grid, p, construct=False)["isohedral"] for p in _hole_free(grid, n))


@pytest.mark.parametrize("n", range(1, 8))
def test_isohedral_polyhexes_equal_a075214(n):
    assert _isohedral_count(HEXAGONAL, n) == A075214[n - 1]


@pytest.mark.slow
@pytest.mark.parametrize("n", [8, 9])
def test_isohedral_polyhexes_equal_a075214_slow(n):
    assert _isohedral_count(HEXAGONAL, n) == A075214[n - 1]


@pytest.mark.parametrize("n", range(1, 11))
def test_isohedral_polyiamonds_equal_a075223(n):
    assert _isohedral_count(TRIANGULAR, n) == A075223[n - 1]


@pytest.mark.slow
@pytest.mark.parametrize("n", [11, 12, 13])
def test_isohedral_polyiamonds_equal_a075223_slow(n):
    assert _isohedral_count(TRIANGULAR, n) == A075223[n - 1]


def test_templates_follow_the_grid_turns():
    """The quarter-turn template needs 90-degree turns (absent from the hexagonal point group);
    the third- and sixth-turn templates need 60/120-degree ones (absent from the square grid)."""
    usable = {g.name: {t[0] for t in _template_arrays(g)[5]} for g in (SQUARE, HEXAGONAL, TRIANGULAR)}
    assert "quarterturn" in usable["square"] and not usable["square"] & {"threefold", "sixfold-1", "sixfold-2"}
    for name in ("hexagonal", "triangular"):
        assert "quarterturn" not in usable[name]
        assert {"threefold", "sixfold-1", "sixfold-2"} <= usable[name]


def test_sixfold_iamonds_need_both_orders():
    """Seven 9-iamonds tile isohedrally only with type CC3C3C6C6 (IH21, p6, six tiles a unit).
    Five of them read C C6 C6 C3 C3 counter-clockwise, the mirror order of the other two: with
    one order only, the count was 128, not A075223(9) = 133."""
    orders = []
    for p in _hole_free(TRIANGULAR, 9):
        a = analyse(TRIANGULAR, p, construct=True)
        if a["isohedral"] and not any(a[k] for k in ("translation", "halfturn", "reflection", "threefold")):
            assert a["ih_types"] == [21]
            orders.append(sorted({t.factorisation.template for t in a["tilings"]}))
    assert sorted(orders) == [["sixfold-1"]] * 2 + [["sixfold-2"]] * 5


@pytest.mark.parametrize("grid,n", [(HEXAGONAL, 6), (TRIANGULAR, 9)])
def test_every_built_tiling_is_a_tiling(grid, n):
    """Independent check of the integer proof in ``build``: every tiling built for the
    hole-free n-forms, drawn in the plane, has no gap and no overlap (Patch.validate)."""
    import shapely

    for p in _hole_free(grid, n):
        a = analyse(grid, p, construct=True)
        for bt in a["tilings"][:1]:
            t = periodic_tiling(grid, p, bt)
            region = shapely.box(-6, -6, 6, 6)
            t.patch(region).validate(region)
