"""Colourings (c1..cm)(p1..pk)(q1..qk) of §5.4.3 and perfect colourings (§3.6.1).

The notation: aspect i of the translational unit at a*v1 + b*v2 has colour
rho2^b(rho1^a(c_i)) with rho1(j) = p_j and rho2(j) = q_j (Kaplan §5.4.3). A colouring is
perfect when every symmetry of the uncoloured tiling permutes the colours (§3.6.1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit.colouring import Colouring, permutation_order, power_table
from tilekit.errors import ParseError
from tilekit.geometry import Affine, regular_polygon
from tilekit.symmetry import colouring_report, is_perfect_colouring, symmetries, wallpaper_group
from tilekit.tiling import PeriodicTiling, Prototile

S3 = math.sqrt(3.0)


# --------------------------------------------------------------------------- strategies


@st.composite
def permutations(draw, k: int | None = None) -> tuple[int, ...]:
    if k is None:
        k = draw(st.integers(1, 7))
    return tuple(draw(st.permutations(range(k))))


@st.composite
def colourings(draw) -> Colouring:
    k = draw(st.integers(1, 6))
    m = draw(st.integers(1, 8))
    aspects = tuple(draw(st.lists(st.integers(0, k - 1), min_size=m, max_size=m)))
    return Colouring(aspects, draw(permutations(k)), draw(permutations(k)))


def naive_power(perm: tuple[int, ...], e: int, j: int) -> int:
    """perm^e (j) by repeated application (perm^-1 for negative e)."""
    if e < 0:
        inv = [0] * len(perm)
        for i, x in enumerate(perm):
            inv[x] = i
        perm, e = tuple(inv), -e
    for _ in range(e):
        j = perm[j]
    return j


# --------------------------------------------------------------------------- notation


@given(colourings())
def test_str_parse_round_trip(col: Colouring) -> None:
    assert Colouring.parse(str(col)) == col


def test_parse_accepts_commas_and_spaces() -> None:
    """Appendix A writes groups with spaces; commas are accepted too (1-based)."""
    col = Colouring.parse(" (1, 2 ,1) (2 1)(1,2) ")
    assert col.aspects == (0, 1, 0) and col.p == (1, 0) and col.q == (0, 1)
    assert str(col) == "(1 2 1)(2 1)(1 2)"


@pytest.mark.parametrize(
    "text, fragment",
    [
        ("(1 2)(1 2)", "three parenthesised groups"),
        ("(1)(1)(1) extra", "three parenthesised groups"),
        ("(1 2)(1 1)(1 2)", "not a permutation"),
        ("(1 2)(1 2)(2 2)", "not a permutation"),
        ("(1 3)(1 2)(1 2)", "outside 1..2"),
        ("(1 0)(1 2)(1 2)", "outside 1..2"),
        ("(1 x)(1 2)(1 2)", "non-integer"),
        ("()(1)(1)", "empty group"),
        ("(1)(1 2)(1)", "different lengths"),
    ],
)
def test_bad_colourings_are_rejected(text: str, fragment: str) -> None:
    with pytest.raises(ParseError, match=fragment):
        Colouring.parse(text)


def test_bad_permutation_in_constructor() -> None:
    with pytest.raises(ParseError, match="first permutation"):
        Colouring((0,), (0, 0), (0, 1))


@given(permutations())
def test_power_table(perm: tuple[int, ...]) -> None:
    """Row e is perm applied e times; the table has one row per power up to the order."""
    table = power_table(perm)
    order = permutation_order(perm)
    assert table.shape == (order, len(perm))
    for e in range(order):
        assert table[e].tolist() == [naive_power(perm, e, j) for j in range(len(perm))]
    # the order is the least e > 0 with perm^e = identity
    assert [naive_power(perm, order, j) for j in range(len(perm))] == list(range(len(perm)))
    assert all(
        [naive_power(perm, e, j) for j in range(len(perm))] != list(range(len(perm)))
        for e in range(1, order)
    )


def test_permutation_order_is_lcm_of_cycles() -> None:
    # (0 1)(2 3 4)(5 6 7 8): lcm(2, 3, 4) = 12
    perm = (1, 0, 3, 4, 2, 6, 7, 8, 5)
    assert permutation_order(perm) == 12


@settings(max_examples=60)
@given(
    colourings(),
    st.lists(st.tuples(st.integers(-40, 40), st.integers(-40, 40)), min_size=1, max_size=20),
)
def test_colour_equals_naive_iteration(col: Colouring, ab) -> None:
    """colour() reads power tables; it equals applying rho1 a times then rho2 b times."""
    m = len(col.aspects)
    aspect = np.arange(len(ab)) % m
    a = np.array([x for x, _ in ab])
    b = np.array([y for _, y in ab])
    got = col.colour(aspect, a, b)
    want = [
        naive_power(col.q, int(bb), naive_power(col.p, int(aa), col.aspects[int(i)]))
        for i, aa, bb in zip(aspect, a, b)
    ]
    assert got.tolist() == want


# --------------------------------------------------------------------------- perfect colourings

SQUARE = regular_polygon(4)
ID = np.eye(3)


def squares(colouring: str) -> PeriodicTiling:
    return PeriodicTiling([Prototile(SQUARE)], [0], ID[None], (1, 0), (0, 1), Colouring.parse(colouring))


def hexagons(colouring: str) -> PeriodicTiling:
    ang = np.arange(6) * math.pi / 3
    hexagon = np.column_stack([np.cos(ang), np.sin(ang)])
    return PeriodicTiling(
        [Prototile(hexagon)], [0], ID[None], (1.5, S3 / 2), (0, S3), Colouring.parse(colouring)
    )


def triangles(colouring: str) -> PeriodicTiling:
    return PeriodicTiling(
        [Prototile(regular_polygon(3))],
        [0, 0],
        np.array([ID, Affine.half_turn((0.75, S3 / 4))]),
        (1, 0),
        (0.5, S3 / 2),
        Colouring.parse(colouring),
    )


def test_checkerboard_is_perfect() -> None:
    """The chessboard 2-colouring of 4^4 is perfect; colour-preserving symmetries form *442
    on the diagonal lattice (1,1), (1,-1) of twice the cell area: index 2."""
    tiling = squares("(1)(2 1)(2 1)")
    report = colouring_report(tiling)
    assert report.perfect and is_perfect_colouring(tiling)
    assert report.colours == 2
    assert report.symmetry.iuc == "p4m"
    assert report.colour_group.iuc == "p4m"
    assert report.index == 2
    assert abs(abs(np.linalg.det(report.colour_group.lattice)) - 2.0) < 1e-9
    # the unit translations swap the two colours
    assert report.permutations[0] == (1, 0) and report.permutations[1] == (1, 0)
    assert wallpaper_group(tiling, colours=True).iuc == "p4m"


def test_stripes_are_not_perfect() -> None:
    """Columns coloured alternately: a quarter turn sends one column's tiles to a row of
    both colours, so no permutation of colours accounts for it (§3.6.1)."""
    tiling = squares("(1)(2 1)(1 2)")
    report = colouring_report(tiling)
    assert not report.perfect and not is_perfect_colouring(tiling)
    assert "rotation 90" in report.violation or "rotation -90" in report.violation
    # what survives with colours: mirrors along columns and rows, half-turns: *2222
    assert report.colour_group.iuc == "pmm"
    quarter = [p for g, p in zip(report.generators, report.permutations) if g.isometry.order == 4]
    assert quarter and all(p is None for p in quarter)
    # the unit translations and the half-turn do permute the colours
    assert report.permutations[0] == (1, 0) and report.permutations[1] == (0, 1)


def test_diagonal_three_colouring_is_not_perfect() -> None:
    """Colour (a + b) mod 3 on 4^4: the quarter turn (a, b) -> (-b, a) sends colour a + b to
    a - b, not a function of a + b, so the colouring is not perfect."""
    assert not is_perfect_colouring(squares("(1)(2 3 1)(2 3 1)"))


def test_hexagon_three_colouring_is_perfect() -> None:
    """The proper 3-colouring of 6^3 (colour a + 2b mod 3) is perfect: its kernel is the
    sqrt(3) sublattice, which every rotation preserves. Colour-preserving: 3-fold turns
    about hexagon centres and mirrors through edge midpoints, every 3-fold centre on a
    mirror: *333 (p3m1); the colours are permuted by all of S3: index 6."""
    tiling = hexagons("(1)(2 3 1)(3 1 2)")
    report = colouring_report(tiling)
    assert report.perfect
    assert report.colours == 3
    assert report.symmetry.iuc == "p6m"
    assert report.colour_group.iuc == "p3m1"
    assert report.index == 6
    # neighbours differ: the six neighbours of the origin tile have colours != its colour
    patch = tiling.patch((-3, -3, 3, 3))
    c = patch.centres()
    d = np.hypot(*(c - c[np.argmin(np.hypot(*c.T))]).T)
    origin_colour = patch.colour[np.argmin(np.hypot(*c.T))]
    assert np.all(patch.colour[np.abs(d - S3) < 1e-6] != origin_colour)


def test_hexagon_colouring_along_one_direction_is_not_perfect() -> None:
    """Colour a mod 3 (constant along v2): a 60-degree turn carries v1 to a direction whose
    colour change differs, so it is not perfect."""
    assert not is_perfect_colouring(hexagons("(1)(2 3 1)(1 2 3)"))


def test_triangles_by_orientation_is_perfect() -> None:
    """Up and down triangles of 3^6 coloured apart: every symmetry keeps or swaps the two
    classes. Colour-preserving: 3-fold turns about vertices and centres, mirrors
    perpendicular to the edges through all of them: *333, index 2."""
    report = colouring_report(triangles("(1 2)(1 2)(1 2)"))
    assert report.perfect
    assert report.colour_group.iuc == "p3m1"
    assert report.index == 2


def test_single_colour_is_perfect_with_index_one() -> None:
    report = colouring_report(hexagons("(1)(1)(1)"))
    assert report.perfect and report.index == 1 and report.colours == 1
    assert report.colour_group.iuc == report.symmetry.iuc == "p6m"


def test_unused_colour_labels_are_allowed() -> None:
    """Colours 1 and 3 of three, 3 and 1 swapped by v1 and v2 (a chessboard): perfect."""
    report = colouring_report(squares("(1)(3 2 1)(3 2 1)"))
    assert report.perfect and report.colours == 2


def test_colour_preserving_group_is_a_subgroup() -> None:
    """Every colour-preserving operation is a symmetry of the uncoloured tiling."""
    tiling = hexagons("(1)(2 3 1)(3 1 2)")
    full = symmetries(tiling)
    sub = symmetries(tiling, colours=True)
    assert sub.coloured and sub.lattice_index == 3
    for op in sub.operations:
        assert full.contains(op.matrix)
    for v in sub.lattice:
        assert full.contains(Affine.translation(*v))


def test_herringbone_coloured_by_aspect_is_perfect() -> None:
    """Herringbone (pgg) with horizontal and vertical bricks coloured by aspect: half-turns
    keep each brick's direction, the diagonal glides swap the two: perfect, and the
    colour-preserving group is the translations and half-turns, p2, of index 2."""
    rect = np.array([(0, 0), (2, 0), (2, 1), (0, 1)], dtype=float)
    vert = Affine.translation(1, 1) @ Affine.rotation(math.pi / 2)
    tiling = PeriodicTiling(
        [Prototile(rect)], [0, 0], np.array([ID, vert]), (1, 1), (2, -2), Colouring.parse("(1 2)(1 2)(1 2)")
    )
    report = colouring_report(tiling)
    assert report.perfect
    assert report.symmetry.iuc == "pgg"
    assert report.colour_group.iuc == "p2"
    assert report.index == 2
