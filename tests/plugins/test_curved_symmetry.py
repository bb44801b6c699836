"""The full symmetry groups of the curved uniform tilings (issue 35's leftover: each record
stores its group, computed from Wythoff's construction by tilekit.plugins.curved.orbifold).

Facts checked: the polyhedral groups of the Archimedean solids (Cromwell, *Polyhedra*, 1997,
ch. 8; Conway, Burgiel, Goodman-Strauss, *The Symmetries of Things*, 2008, ch. 4: *532 the
icosahedral solids, 532 the snub dodecahedron, *432 the octahedral ones, 432 the snub cube,
*332 the truncated tetrahedron, *22n the prisms, 2*n the antiprisms); constructions on a
smaller group that have more symmetry (3 3 | 2 is the cuboctahedron: *432; | 2 3 3 is the
icosahedron: *532; | 2 2 3 is the octahedron: *432); the {7,3} family's *732 (also written
*237) and 732 for its snub. Independent checks: on the sphere the group's order from its
orbifold (2/χ, Conway's Euler characteristic) equals the number of vertices (from the face
counts) times the vertex stabiliser found; everywhere the index of the construction's group
found from the vertex stabilisers equals the ratio of the two orbifolds' Euler characteristics
(Riemann–Hurwitz).
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import pytest

from tilekit.plugins.curved import wythoff
from tilekit.plugins.curved.orbifold import OrbifoldGroup, check_index, uniform_symmetry
from tilekit.plugins.curved.uniform import UniformTiling

KNOWN = {
    # the icosahedral solids
    "3.5.3.5": "*532", "3.10.10": "*532", "5.6.6": "*532", "3.4.5.4": "*532", "4.6.10": "*532",
    "3.3.3.3.5": "532",
    # the octahedral ones
    "3.4.3.4": "*432", "3.8.8": "*432", "4.6.6": "*432", "3.4.4.4": "*432", "4.6.8": "*432",
    "3.3.3.3.4": "432",
    "3.6.6": "*332",
    # prisms and antiprisms
    "4.4.5": "*225", "4.4.7": "*227", "3.3.3.5": "2*5", "3.3.3.8": "2*8",
    # hyperbolic
    "3.14.14": "*732", "3.7.3.7": "*732", "4.6.14": "*732", "3.3.3.3.7": "732",
    "4.8.8.8": "*844", "3.3.4.3.5": "542", "3.4.3.4.3.4": "*433",
}

SYMBOLS = {
    "3 3 | 2": "*432",   # the cuboctahedron on the tetrahedral group
    "| 2 3 3": "*532",   # the snub tetrahedron is the icosahedron
    "| 2 2 3": "*432",   # the triangular antiprism is the octahedron
    "2 | 3 3": "*432",   # the octahedron as a tetratetrahedron
    "3 | 2 3": "*332",   # the tetrahedron
    "3 | 2 5": "*532",   # the dodecahedron
    "3 | 2 7": "*732",   # {7,3}
    "2 | 3 7": "*732",   # {3,7}'s rectification
    "| 2 3 7": "732",
    "| 3 3 4": "3*4",    # a hyperbolic snub on an isosceles triangle: a mirror through the 4-fold corner
}


@pytest.mark.parametrize("configuration, group", sorted(KNOWN.items()))
def test_known_groups_by_configuration(configuration: str, group: str) -> None:
    t = UniformTiling(configuration)
    props = t.properties()
    assert props["symmetry_group"] == group
    assert props["orbifold"] == group


@pytest.mark.parametrize("symbol, group", sorted(SYMBOLS.items()))
def test_groups_beyond_the_construction(symbol: str, group: str) -> None:
    sym = wythoff.Symbol.parse(symbol)
    found = uniform_symmetry(wythoff.Construction(sym))
    assert found.notation == group
    assert check_index(found, sym)


def test_more_symmetry_than_the_construction_group() -> None:
    """The cuboctahedron is made on *332 (order 24) and has the group *432 (order 48)."""
    t = UniformTiling(symbol="3 3 | 2")
    assert t.properties()["construction_group"] == "*332"
    assert t.symmetry.index == 2
    assert t.symmetry.group.order() == 48


def test_sphere_orders_equal_vertices_times_stabiliser() -> None:
    """Every spherical uniform tiling with orders up to 5 and the prisms/antiprisms to 9:
    |G| = 2/χ of the orbifold found equals V times the vertex stabiliser's order (V from the
    symbol's face counts), and the index agrees with Riemann–Hurwitz."""
    seen = 0
    for orders in {tuple(sorted(o)) for o in itertools.product(range(2, 6), repeat=3)} | \
            {(2, 2, n) for n in range(6, 10)}:
        if wythoff.geometry_of_orders(orders) != wythoff.SPHERE:
            continue
        for form in wythoff.FORMS:
            sym = wythoff.Symbol(form, orders)
            if sym.configuration is None:
                continue
            found = uniform_symmetry(wythoff.Construction(sym))
            counts = sym.face_counts()
            corners = sum(n * k for n, k in counts.items())
            vertices = corners // len(sym.configuration)
            assert found.group.order() == vertices * found.vertex_stabiliser, (str(sym), found.notation)
            assert check_index(found, sym), str(sym)
            seen += 1
    assert seen >= 25  # 28 symbols with three polygons at a vertex


def test_hyperbolic_index_agrees_with_areas() -> None:
    for text in ("2 3 | 8", "4 | 4 4", "| 4 4 4", "| 3 4 4", "2 4 5 |", "| 2 5 5", "3 3 | 4", "5 | 2 5",
                 "2 3 | 60"):
        sym = wythoff.Symbol.parse(text)
        found = uniform_symmetry(wythoff.Construction(sym))
        assert check_index(found, sym), text
        assert found.group.euler_characteristic < 0


def test_orbifold_notation_and_characteristic() -> None:
    assert OrbifoldGroup((), (5, 3, 2), True).notation == "*532"
    assert OrbifoldGroup((2, 2, 7), (), False).notation == "227"
    assert OrbifoldGroup((), (7, 2, 2), True).notation == "*227"
    assert OrbifoldGroup((2,), (6,), True).notation == "2*6"
    assert OrbifoldGroup((), (5, 3, 2), True).order() == 120
    assert OrbifoldGroup((4, 3, 2), (), False).order() == 24
    assert OrbifoldGroup((2,), (6,), True).order() == 24   # D6d, the hexagonal antiprism's group
    assert OrbifoldGroup((), (7, 3, 2), True).euler_characteristic == Fraction(-1, 84)  # area 2π/84 = π/42, the (2,3,7) triangle


@pytest.mark.parametrize("symbol", ["8 | 3 8", "8 | 4 6", "6 | 6 8"])
def test_far_corner_orbits(symbol: str) -> None:
    """p | q r with a large p: the generator's orbit round the far corners has coordinates of
    cosh(2d); its points were once told apart at a fixed 1e-9 and the faces came out wrong
    (8 | 3 8 gave triangles and 10-gons). The faces are the symbol's, and the group *pqr's
    rotation by 2π/p about the generator is a symmetry (vertex stabiliser 2p)."""
    sym = wythoff.Symbol.parse(symbol)
    c = wythoff.Construction(sym)
    assert [(f.corner, f.sides) for f in c.face_types] == sym.face_sizes()
    assert uniform_symmetry(c).vertex_stabiliser == 2 * sym.orders[0]


def test_one_orbifold_spelling_past_order_nine(tmp_path, monkeypatch) -> None:
    """Orders past 9 are separated by commas (Conway, Burgiel, Goodman-Strauss, *The Symmetries
    of Things*, 2008): the uniform tilings' groups (orbifold.py) and the isohedral types'
    (delaney.py) are written by one function, tilekit.symmetry.names.orbifold_symbol, and a
    catalogue query answers to the old run-together spelling too. 2 | 3 10 (3.10.3.10) lies on
    the (2, 3, 10) triangle group *10,3,2; so does the regular 10-gon of {10,3} with its full
    symmetry as an isohedral tile, and its rotations alone give 10,3,2."""
    from family_cli import family_cli

    from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling
    from tilekit.symmetry.names import orbifold_spellings, orbifold_symbol

    assert OrbifoldGroup((), (10, 3, 2), True).notation == "*10,3,2" == orbifold_symbol((), [[10, 3, 2]])
    assert OrbifoldGroup((12, 6), (2,), True).notation == "12,6*2"
    assert OrbifoldGroup((), (6, 3, 2), True).notation == "*632"      # single digits unchanged
    assert UniformTiling("3.10.3.10").properties()["orbifold"] == "*10,3,2"
    assert CurvedIsohedralTiling(10, 3, symbol="[aaaaaaaaaa; a]").properties()["orbifold"] == "*10,3,2"
    assert CurvedIsohedralTiling(10, 3, symbol="[a+a+a+a+a+a+a+a+a+a+; a+]").properties()["orbifold"] == "10,3,2"
    assert "*10,3,2" in orbifold_spellings("*1032") and "*1032" in orbifold_spellings("*10,3,2")
    cli = family_cli(tmp_path, monkeypatch, "curved")
    for spelling in ("*10,3,2", "*1032"):
        r = cli("list", "--family", "curved", "--where", f"orbifold={spelling}")
        assert r.exit_code == 0 and "3.10.3.10" in r.output, r.output
        assert "3.4.10.4" in r.output          # 3 10 | 2, the same group
        assert "rhombicosidodecahedron" not in r.output and "3.20.20" not in r.output   # *532; no record
