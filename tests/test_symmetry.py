"""Wallpaper groups of periodic tilings built by hand, one or more for each of the 17 groups.

Each tiling is checked to be a genuine tiling with ``Patch.validate`` and its expected group
is justified in a comment. Two arguments recur:

* *Free action.* When the tiles have no symmetry of their own (an asymmetric outline or
  marking), a symmetry is determined by where it sends one tile, so the group acts simply
  transitively on the tiles of an isohedral tiling: the tiles per primitive cell equal the
  point-group order, and each symmetry is the map carrying tile 0 onto some tile.
* *Decorated grids.* Markings placed on the tiles of a regular grid can only remove
  symmetries of the grid; the grid's group (Kaplan §3.2, §3.5, Figure 3.5) bounds the
  answer from above and the marking's own symmetry decides which remain.

Group facts (which groups have mirrors, glides, which rotation orders) are those of the
standard tables: Kaplan §3.2 and §3.6.3; Conway, Burgiel and Goodman-Strauss, *The
Symmetries of Things* (2008), chapter 6 (orbifold notation).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit.errors import GeometryError, ParameterError
from tilekit.geometry import Affine, regular_polygon
from tilekit.symmetry import (
    IUC,
    ORBIFOLD,
    isogonality,
    isohedrality,
    symmetries,
    tile_orbits,
    tiling_vertices,
    vertex_orbits,
    wallpaper_group,
)
from tilekit.tiling import PeriodicTiling, Prototile

S3 = math.sqrt(3.0)


def periodic(outlines, placements, v1, v2, markings=None) -> PeriodicTiling:
    """A PeriodicTiling from prototile outlines and (prototile index, 3x3 transform) pairs."""
    markings = markings or {}
    protos = [Prototile(np.asarray(o, dtype=float), marking=markings.get(i, ())) for i, o in enumerate(outlines)]
    return PeriodicTiling(
        protos,
        [p for p, _ in placements],
        np.array([m for _, m in placements]),
        v1,
        v2,
    )


def assert_tiles(tiling: PeriodicTiling) -> None:
    """The unit and vectors really tile: no overlaps, no gaps on a region several cells wide."""
    ub = tiling.unit_tile_bounds()
    size = max(ub[:, 2].max() - ub[:, 0].min(), ub[:, 3].max() - ub[:, 1].min())
    region = (-1.5 * size, -1.5 * size, 1.5 * size, 1.5 * size)
    report = tiling.patch(region).validate(region)
    assert report, report.summary()


ID = np.eye(3)
T = Affine.translation


# --------------------------------------------------------------------------- the tilings

SQUARE = regular_polygon(4)
RECT = np.array([(0, 0), (2, 0), (2, 1), (0, 1)], dtype=float)
CHEVRON = np.array([(0, 0), (0.5, 0.3), (1, 0), (1, 1), (0.5, 1.3), (0, 1)])
SKEW_CHEVRON = np.array([(0, 0), (0.3, 0.2), (1, 0), (1, 1), (0.3, 1.2), (0, 1)])
#: a generic quadrilateral: no two sides parallel or equal
QUAD = np.array([(0, 0), (1, 0.1), (1.3, 0.9), (0.2, 1.1)])


def hexagon(radius: float = 1.0) -> np.ndarray:
    """Regular hexagon centred at the origin with a vertex on the positive x axis."""
    ang = np.arange(6) * math.pi / 3
    return radius * np.column_stack([np.cos(ang), np.sin(ang)])


HEX_V1, HEX_V2 = (1.5, S3 / 2), (0.0, S3)


def arms(n: int, bend: float, start: float = 0.0) -> tuple[np.ndarray, ...]:
    """n arms from the centre, each bent by ``bend`` radians: C_n, and chiral when bend != 0."""
    out = []
    for k in range(n):
        a = start + 2 * math.pi * k / n
        out.append(
            np.array(
                [(0.1 * math.cos(a), 0.1 * math.sin(a)), (0.5 * math.cos(a), 0.5 * math.sin(a)),
                 (0.62 * math.cos(a + bend), 0.62 * math.sin(a + bend))]
            )
        )
    return tuple(out)


def triangle_mark(start: float) -> tuple[np.ndarray, ...]:
    """An equilateral triangle (symmetry D3) with a corner at angle ``start``."""
    ang = start + np.arange(4) * 2 * math.pi / 3
    return (0.5 * np.column_stack([np.cos(ang), np.sin(ang)]),)


#: an asymmetric marking (a bent flag) for unit squares
FLAG = (np.array([(0.2, 0.2), (0.2, 0.8), (0.6, 0.7), (0.3, 0.55)]),)


def wavy_square() -> np.ndarray:
    """A unit square whose opposite sides carry the same generic curve (translation pairs)."""
    bottom = np.array([(0, 0), (0.3, 0.1), (0.6, -0.05), (1, 0)])
    left = np.array([(0, 0), (0.08, 0.35), (-0.05, 0.7), (0, 1)])
    right = left + (1, 0)
    top = bottom + (0, 1)
    return np.vstack([bottom[:-1], right[:-1], top[::-1][:-1], left[::-1][:-1]])


def tilings() -> dict[str, tuple[str, PeriodicTiling]]:
    """name -> (expected IUC name, tiling)."""
    tri = regular_polygon(3)
    out: dict[str, tuple[str, PeriodicTiling]] = {}
    # Regular tilings (Kaplan §3.5, Figure 3.5): 4^4 is *442, 3^6 and 6^3 are *632.
    out["squares"] = ("p4m", periodic([SQUARE], [(0, ID)], (1, 0), (0, 1)))
    out["triangles"] = (
        "p6m",
        periodic([tri], [(0, ID), (0, Affine.half_turn((0.75, S3 / 4)))], (1, 0), (0.5, S3 / 2)),
    )
    out["hexagons"] = ("p6m", periodic([hexagon()], [(0, ID)], HEX_V1, HEX_V2))
    # p1: translates of a tile with no symmetry (free action, one aspect): only translations.
    out["wavy squares"] = ("p1", periodic([wavy_square()], [(0, ID)], (1, 0), (0, 1)))
    out["flagged squares"] = ("p1", periodic([SQUARE], [(0, ID)], (1, 0), (0, 1), {0: FLAG}))
    # p2: a generic quadrilateral and its half-turn about an edge midpoint tile with
    # translations C-A and D-B (the diagonals); free action, two aspects, half-turns only.
    a, b, c, d = QUAD
    out["quadrilaterals"] = (
        "p2",
        periodic([QUAD], [(0, ID), (0, Affine.half_turn(tuple((a + b) / 2)))], c - a, d - b),
    )
    # p2: a parallelogram (neither rectangle nor rhombus) is centrally symmetric, with no
    # mirror; translates of it have half-turns about tile centres, edge midpoints, vertices.
    para = np.array([(0, 0), (1, 0), (1.3, 0.8), (0.3, 0.8)])
    out["parallelograms"] = ("p2", periodic([para], [(0, ID)], (1, 0), (0.3, 0.8)))
    # p2: 2x1 bricks with rows offset by a quarter brick: mirrors would need the offset s to
    # satisfy s = -s (mod 2), so none; half-turns about points of the row lines remain.
    out["quarter-offset bricks"] = ("p2", periodic([RECT], [(0, ID)], (2, 0), (0.5, 1)))
    # pm: symmetric chevrons in aligned columns: vertical mirrors through tile axes and
    # column lines, no half-turn (all point up), lattice rectangular (1,0), (0,1).
    out["chevrons"] = ("pm", periodic([CHEVRON], [(0, ID)], (1, 0), (0, 1)))
    # cm: the same columns offset by half a tile: mirrors through tile axes survive, those
    # on the column lines become glides (offset 1/2): mirrors and glides parallel, centred.
    out["offset chevrons"] = ("cm", periodic([CHEVRON], [(0, ID)], (1, 0.5), (0, 1)))
    # pg: an asymmetric chevron column and its mirror image shifted by half a tile: the
    # only opposite symmetries carry a column to its mirror column with the half shift.
    # (x, y) -> (2 - x, y + 1/2): the mirror x = 1 then a half-tile shift (exact entries)
    glide = Affine.from_rows(-1, 0, 2, 0, 1, 0.5)
    out["glided chevrons"] = ("pg", periodic([SKEW_CHEVRON], [(0, ID), (0, glide)], (2, 0), (0, 1)))
    # pmm: 2x1 rectangles on a rectangular grid: mirrors along all grid lines and midlines.
    out["rectangles"] = ("pmm", periodic([RECT], [(0, ID)], (2, 0), (0, 1)))
    # pmg: up-chevron columns alternating with down-chevron columns: vertical mirrors
    # through tile axes, half-turns about column-line points, glides with horizontal axes.
    down = T(1, 1) @ Affine.reflection(0.0)
    out["alternating chevrons"] = ("pmg", periodic([CHEVRON], [(0, ID), (0, down)], (2, 0), (0, 1)))
    # pgg: herringbone of 2x1 bricks; glide axes along (1,1) and (1,-1) whose glide
    # components are half the shortest lattice vector along them, half-turns, no mirror.
    vert = T(1, 1) @ Affine.rotation(math.pi / 2)
    out["herringbone"] = ("pgg", periodic([RECT], [(0, ID), (0, vert)], (1, 1), (2, -2)))
    # cmm: running bond (rows offset by half a brick): vertical mirrors at every integer x,
    # horizontal mirrors along row midlines, and half-turns at (0.5, 1) off every mirror.
    out["running bond"] = ("cmm", periodic([RECT], [(0, ID)], (2, 0), (1, 1)))
    # p4: the Pythagorean tiling (squares of sides 2 and 1) has 4-fold centres at the
    # centres of both squares and is chiral: a mirror would turn its pinwheel of four big
    # squares round each small one the other way.
    out["pythagorean"] = (
        "p4",
        periodic([SQUARE * 2, SQUARE], [(0, ID), (1, T(2, 0))], (2, 1), (-1, 2)),
    )
    # p4g: basketweave: 2x2 blocks of two parallel bricks, alternately horizontal and
    # vertical; 4-fold centres at block corners, mirrors through block centres only.
    rot = Affine.rotation(math.pi / 2)
    out["basketweave"] = (
        "p4g",
        periodic(
            [RECT],
            [(0, ID), (0, T(0, 1)), (0, T(3, 0) @ rot), (0, T(4, 0) @ rot)],
            (2, 2),
            (2, -2),
        ),
    )
    # Decorated hexagons (the grid is *632): a chiral C3 marking leaves p3, a chiral C6
    # marking p6; a D3 triangle whose mirrors pass through the hexagon's corners keeps
    # mirrors through every 3-fold centre (*333), one whose mirrors pass through edge
    # midpoints misses the 3-fold centres at the grid vertices (3*3).
    hx = hexagon()
    out["C3 hexagons"] = ("p3", periodic([hx], [(0, ID)], HEX_V1, HEX_V2, {0: arms(3, 0.4)}))
    out["C6 hexagons"] = ("p6", periodic([hx], [(0, ID)], HEX_V1, HEX_V2, {0: arms(6, 0.3)}))
    out["corner triangles"] = (
        "p3m1",
        periodic([hx], [(0, ID)], HEX_V1, HEX_V2, {0: triangle_mark(0.0)}),
    )
    out["edge triangles"] = (
        "p31m",
        periodic([hx], [(0, ID)], HEX_V1, HEX_V2, {0: triangle_mark(math.pi / 6)}),
    )
    return out


TILINGS = tilings()


@pytest.mark.parametrize("name", sorted(TILINGS))
def test_test_tilings_are_tilings(name: str) -> None:
    """Every hand-built tiling covers the plane without overlaps (Patch.validate)."""
    assert_tiles(TILINGS[name][1])


@pytest.mark.parametrize("name", sorted(TILINGS))
def test_wallpaper_group(name: str) -> None:
    expected, tiling = TILINGS[name]
    group = wallpaper_group(tiling)
    assert group.iuc == expected, f"{name}: {group}"
    assert group.orbifold == ORBIFOLD[expected]


def test_all_seventeen_groups_are_exercised() -> None:
    """The hand-built tilings reach every one of the 17 wallpaper groups."""
    assert {iuc for iuc, _ in TILINGS.values()} == set(ORBIFOLD)
    assert len(ORBIFOLD) == 17 and len(IUC) == 17


@pytest.mark.parametrize("name", sorted(TILINGS))
def test_rotation_orders_are_the_orbifold_digits(name: str) -> None:
    """The orders of the rotation centres found are the digits of the orbifold symbol.

    In Conway's notation each digit is a cone point (a rotation centre off the mirrors) or
    a corner (on mirrors); every class of rotation centre gives one (Kaplan §3.6.3).
    """
    group = wallpaper_group(TILINGS[name][1])
    digits = {int(ch) for ch in group.orbifold if ch.isdigit()}
    assert set(group.rotation_orders) == digits


# facts of the standard table: (has mirrors, has essential glides, highest rotation order)
GROUP_FACTS = {
    "p1": (False, False, 1), "p2": (False, False, 2), "pm": (True, False, 1),
    "pg": (False, True, 1), "cm": (True, True, 1), "pmm": (True, False, 2),
    "pmg": (True, True, 2), "pgg": (False, True, 2), "cmm": (True, True, 2),
    "p4": (False, False, 4), "p4m": (True, True, 4), "p4g": (True, True, 4),
    "p3": (False, False, 3), "p3m1": (True, True, 3), "p31m": (True, True, 3),
    "p6": (False, False, 6), "p6m": (True, True, 6),
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(TILINGS))
def test_mirror_glide_and_rotation_facts(name: str) -> None:
    """Mirrors, essential glides and the point group agree with the group's standard facts."""
    group = wallpaper_group(TILINGS[name][1])
    mirrors, glides, n = GROUP_FACTS[group.iuc]
    assert group.reflections == mirrors
    assert group.glide_reflections == glides
    assert max(group.rotation_orders, default=1) == n
    opposite = any(op.kind in ("reflection", "glide reflection") for op in group.operations)
    assert group.point_group_order == n * (2 if opposite else 1)


@pytest.mark.parametrize("name", sorted(TILINGS))
def test_operations_are_symmetries_and_generators_generate(name: str) -> None:
    """Every operation maps the tiling onto itself; the generators reach the whole point group."""
    tiling = TILINGS[name][1]
    group = wallpaper_group(tiling)
    region = (-4, -4, 4, 4)
    patch = tiling.patch((-9, -9, 9, 9))
    keys = _tile_keys(patch)
    inner = tiling.patch(region)
    for op in group.operations + group.generators:
        moved = _tile_keys(inner.transformed(op.matrix))
        assert moved <= keys, f"{op} is not a symmetry"
        assert group.group.contains(op.matrix)
    linear = {_lin_key(np.eye(3))}
    gens = [g.matrix for g in group.generators]
    for _ in range(12):
        linear |= {_lin_key(g @ _unkey(k)) for g in gens for k in linear}
    assert len(linear) == group.point_group_order


def _tile_keys(patch) -> set:
    """Each tile as the rounded set of its outline and marking points (order-free)."""
    out = set()
    for p, idx, pts in patch.groups():
        marks = [Affine.apply(patch.transform[idx], m) for m in patch.prototiles[p].marking]
        allpts = np.concatenate([pts, *marks], axis=1) if marks else pts
        for row in np.round(allpts, 5) + 0.0:
            out.add(frozenset(map(tuple, row.tolist())))
    return out


def _lin_key(m: np.ndarray) -> tuple:
    return tuple(np.round(m[:2, :2], 6).ravel() + 0.0)


def _unkey(k: tuple) -> np.ndarray:
    m = np.eye(3)
    m[:2, :2] = np.array(k).reshape(2, 2)
    return m


def test_symmetry_that_fails_is_not_in_group() -> None:
    """A 90-degree turn is no symmetry of the 2x1 rectangle grid; a half-turn is."""
    group = symmetries(TILINGS["rectangles"][1])
    assert not group.contains(Affine.rotation(math.pi / 2))
    assert group.contains(Affine.rotation(math.pi, (1, 0.5)))
    assert not group.contains(Affine.translation(1, 0))
    assert group.contains(Affine.translation(2, 1))


# --------------------------------------------------------------------------- lattices


def test_non_primitive_unit_is_detected() -> None:
    """A 2x2 block of unit squares as the unit: the true lattice is 4 times finer."""
    block = periodic(
        [SQUARE], [(0, T(a, b)) for a in (0, 1) for b in (0, 1)], (2, 0), (0, 2)
    )
    group = symmetries(block)
    assert group.lattice_index == 4 and not group.primitive
    assert abs(abs(np.linalg.det(group.lattice)) - 1.0) < 1e-9
    assert wallpaper_group(block).iuc == "p4m"


def test_hexagons_with_three_tile_unit() -> None:
    """Three hexagons per unit over a sqrt(3)-scaled lattice: index 3, still *632."""
    w1, w2 = np.array(HEX_V1), np.array(HEX_V2)
    big1, big2 = w1 + w2, 2 * w2 - w1
    tiling = periodic([hexagon()], [(0, ID), (0, T(*w1)), (0, T(*w2))], big1, big2)
    assert_tiles(tiling)
    group = wallpaper_group(tiling)
    assert group.lattice_index == 3
    assert group.iuc == "p6m"
    assert abs(abs(np.linalg.det(group.lattice)) - abs(w1[0] * w2[1] - w1[1] * w2[0])) < 1e-9


def test_lattice_is_reduced() -> None:
    """The reported basis is Lagrange-reduced: |w1| <= |w2| and |w1.w2| <= |w1|^2 / 2."""
    tiling = periodic([SQUARE], [(0, ID)], (1, 0), (5, 1))  # a skew basis of the square grid
    lat = symmetries(tiling).lattice
    w1, w2 = lat
    assert np.linalg.norm(w1) <= np.linalg.norm(w2) + 1e-12
    assert abs(w1 @ w2) <= w1 @ w1 / 2 + 1e-12
    assert sorted(np.round(np.abs(lat), 9).ravel().tolist()) == [0, 0, 1, 1]


# --------------------------------------------------------------------------- invariance


@settings(max_examples=25, deadline=None)
@given(
    angle=st.floats(0, 2 * math.pi),
    dx=st.floats(-50, 50),
    dy=st.floats(-50, 50),
    scale=st.floats(0.05, 20),
    mirror=st.booleans(),
    name=st.sampled_from(sorted(TILINGS)),
)
def test_group_is_invariant_under_similarities(angle, dx, dy, scale, mirror, name) -> None:
    """Moving, turning, mirroring and scaling a tiling does not change its wallpaper type."""
    expected, tiling = TILINGS[name]
    m = Affine.translation(dx, dy) @ Affine.rotation(angle) @ Affine.scaling(scale)
    if mirror:
        m = m @ Affine.reflection(0.3)
    moved = PeriodicTiling(
        [
            Prototile(Affine.apply(m, p.outline) * 1.0, marking=tuple(Affine.apply(m, k) for k in p.marking))
            for p in tiling.prototiles
        ],
        tiling.unit_prototile,
        # tile i is placed by  m T_i m^-1  on the moved prototile
        np.array([m @ t @ Affine.inverse(m) for t in tiling.unit_transform]),
        m[:2, :2] @ tiling.v1,
        m[:2, :2] @ tiling.v2,
    )
    assert wallpaper_group(moved).iuc == expected


# --------------------------------------------------------------------------- errors


def test_rejects_non_periodic_input() -> None:
    with pytest.raises(ParameterError, match="PeriodicTiling"):
        symmetries("squares")  # type: ignore[arg-type]


@pytest.mark.parametrize("tol", [0, -1e-6, 0.5, float("nan")])
def test_rejects_bad_tolerance(tol: float) -> None:
    with pytest.raises(ParameterError, match="tolerance"):
        symmetries(TILINGS["squares"][1], tol=tol)


def test_overlapping_unit_is_not_a_tiling() -> None:
    """A unit holding the same square twice is no translational unit of a tiling.

    Both copies are congruent to tile 0 by the identity, so two "translations" are found
    modulo v1, v2 where a lattice refining v1, v2 would need distinct ones: rejected.
    """
    bad = periodic([SQUARE], [(0, ID), (0, ID)], (1, 0), (0, 1))
    with pytest.raises(GeometryError):
        symmetries(bad)


# --------------------------------------------------------------------------- orbits


def rhombitrihexagonal() -> PeriodicTiling:
    """3.4.6.4: a unit hexagon, squares on three of its edges, triangles at two corners.

    Hexagon centres are 2 apothems plus a square side apart: sqrt(3) + 1, along the edge
    normals at 30 and 90 degrees. Each square is shared by two hexagons and each triangle
    by three, so a cell holds 1 hexagon, 3 squares and 2 triangles.
    """
    corner = [np.array([math.cos(k * math.pi / 3), math.sin(k * math.pi / 3)]) for k in range(7)]
    normal = [np.array([math.cos(math.pi / 6 + k * math.pi / 3), math.sin(math.pi / 6 + k * math.pi / 3)]) for k in range(-1, 6)]
    tiles = [np.array(corner[:6])]
    for k in range(3):  # squares on edges 0, 1, 2 (normals at 30, 90, 150 degrees)
        n = normal[k + 1]
        tiles.append(np.array([corner[k], corner[k] + n, corner[k + 1] + n, corner[k + 1]]))
    for k in range(2):  # triangles at corners 0 and 1, between the squares on either side
        tiles.append(np.array([corner[k], corner[k] + normal[k], corner[k] + normal[k + 1]]))
    s = S3 + 1
    return periodic(tiles, [(i, ID) for i in range(len(tiles))], s * normal[1], s * normal[2])


def test_archimedean_3464_is_isogonal_and_3_isohedral() -> None:
    """An Archimedean tiling is vertex-transitive (Kaplan §5.1; Grünbaum & Shephard §2.1);
    3.4.6.4 has three tile shapes, each one transitivity class, and symmetry *632."""
    tiling = rhombitrihexagonal()
    assert_tiles(tiling)
    assert wallpaper_group(tiling).iuc == "p6m"
    assert isohedrality(tiling) == 3
    assert tile_orbits(tiling).tolist() == [0, 1, 1, 1, 2, 2]
    verts, labels = vertex_orbits(tiling)
    assert len(verts) == 6  # 6 vertices per cell: each hexagon corner, each counted once
    assert isogonality(tiling) == 1


@pytest.mark.parametrize(
    "name, tile_classes, vertex_classes",
    [
        # regular tilings are isohedral and isogonal
        ("squares", 1, 1),
        ("triangles", 1, 1),
        ("hexagons", 1, 1),
        # Pythagorean: two sizes of square cannot be equivalent; every vertex is a corner
        # of exactly one small square, whose 4-fold turn permutes its corners: 1 class
        ("pythagorean", 2, 1),
        # basketweave: one brick class; vertices of valence 4 (block corners) and 3 (ends
        # of the line between the two bricks of a block) cannot be equivalent: 2 classes
        ("basketweave", 1, 2),
        # 6^3 has two classes of vertices (Y and inverted Y) swapped only by half-turns or
        # mirrors through edge midpoints: p3 and *333 keep them apart, 632 and 3*3 do not
        ("C3 hexagons", 1, 2),
        ("corner triangles", 1, 2),
        ("C6 hexagons", 1, 1),
        ("edge triangles", 1, 1),
    ],
)
def test_tile_and_vertex_orbits(name: str, tile_classes: int, vertex_classes: int) -> None:
    tiling = TILINGS[name][1]
    assert isohedrality(tiling) == tile_classes
    assert isogonality(tiling) == vertex_classes


def test_vertices_exclude_points_on_straight_edges() -> None:
    """Chevron corners at the notch meet only two tiles, so they are no tiling vertices;
    aligned chevron columns have one 4-valent vertex per cell."""
    verts = tiling_vertices(TILINGS["chevrons"][1])
    assert len(verts) == 1
    assert np.allclose(verts[0], (0, 0)) or np.allclose(verts[0] % 1, (0, 0))


# --------------------------------------------------------------------------- isohedral types


def tactile_tiling(ih: int) -> PeriodicTiling:
    """An isohedral tiling of type IH``ih`` from Kaplan's Tactile tables, with generic edges.

    Each edge shape class gets its own small asymmetric curve (completed by Tactile to a U
    or S edge where the type demands) and the tiling-vertex parameters are nudged off
    their defaults, so that the tile has no symmetry beyond what its type forces.
    """
    from tactile import EdgeShape, IsohedralTiling, Point, mul

    til = IsohedralTiling(ih)
    if til.num_parameters:
        til.parameters = [p + 0.013 * (i + 1) for i, p in enumerate(til.parameters)]
    base = [(0.0, 0.0), (0.3, 0.05), (0.6, 0.02), (1.0, 0.0)]
    jbase = [(0.0, 0.0), (0.25, 0.05), (0.45, -0.03), (0.7, 0.06), (1.0, 0.0)]
    pts = []
    for part in til.parts:
        kind = til.edge_shapes[part.id]
        f = 1.0 + 0.37 * part.id
        if kind == EdgeShape.I:
            curve = [(0.0, 0.0), (1.0, 0.0)]
        elif kind == EdgeShape.J:
            curve = [(x, y * (f if k % 2 else 2 - f)) for k, (x, y) in enumerate(jbase)]
        else:
            curve = [(x, y * f) for x, y in base]
        ej = [Point(*p) for p in curve]
        cur, inc = (len(ej) - 2, -1) if part.rev else (1, 1)
        for _ in range(len(ej) - 1):
            q = mul(part.T, ej[cur])
            pts.append((q.x, q.y))
            cur += inc
    aspects = np.array([[a[0:3], a[3:6], [0.0, 0.0, 1.0]] for a in til.aspects], dtype=float)
    return PeriodicTiling(
        [Prototile(np.array(pts))],
        [0] * len(aspects),
        aspects,
        (til.t1.x, til.t1.y),
        (til.t2.x, til.t2.y),
        name=f"IH{ih}",
    )


def test_isohedral_types_are_isohedral() -> None:
    """All 81 unmarked isohedral types (Tactile's tables of Kaplan's Appendix A) give
    tilings whose symmetry group is transitive on the tiles (the definition, §5.2); where
    the type places reflected copies of the tile, the group has opposite isometries."""
    from tactile import tiling_types

    assert len(tiling_types) == 81
    for ih in tiling_types:
        tiling = tactile_tiling(ih)
        group = wallpaper_group(tiling)
        assert isohedrality(tiling) == 1, f"IH{ih}"
        reflected = bool((np.linalg.det(tiling.unit_transform[:, :2, :2]) < 0).any())
        has_opposite = any(op.kind in ("reflection", "glide reflection") for op in group.operations)
        assert has_opposite or not reflected, f"IH{ih}"


# --------------------------------------------------------------------------- Archimedean and Laves

#: Symmetry groups of the 11 Archimedean tilings (Grünbaum & Shephard, Tilings and
#: Patterns, §2.1; Kaplan §5.1); each Laves tiling, the dual, has the same group.
ARCHIMEDEAN_GROUPS = {
    "3^6": "p6m", "4^4": "p4m", "6^3": "p6m", "3.12^2": "p6m", "4.6.12": "p6m",
    "3.4.6.4": "p6m", "3.6.3.6": "p6m", "4.8^2": "p4m", "3^4.6": "p6",
    "3^3.4^2": "cmm", "3^2.4.3.4": "p4g",
}  # fmt: skip


def test_archimedean_and_laves_catalogue_tilings() -> None:
    """The family's 11 Archimedean tilings (both hands of 3^4.6) have the published groups
    and are isogonal (vertex-transitive, §5.1); their Laves duals are isohedral."""
    from tilekit.plugins.archimedean.records import (
        archimedean_from_spec,
        catalogue_records,
        laves_from_spec,
    )

    seen = {"archimedean": set(), "laves": set()}
    for record in catalogue_records():
        if record.family not in seen:
            continue
        build = archimedean_from_spec if record.family == "archimedean" else laves_from_spec
        tiling = build(record.spec)
        key = record.name.strip("[]").rstrip("lr").rstrip("]")
        assert wallpaper_group(tiling).iuc == ARCHIMEDEAN_GROUPS[key], record.name
        if record.family == "archimedean":
            assert isogonality(tiling) == 1, record.name
        else:
            assert isohedrality(tiling) == 1, record.name
        seen[record.family].add(key)
    assert seen["archimedean"] == seen["laves"] == set(ARCHIMEDEAN_GROUPS)


# --------------------------------------------------------------------------- options and output


def test_match_prototiles_keeps_congruent_prototiles_apart() -> None:
    """A chessboard drawn with two congruent prototiles: by geometry alone it is 4^4 with
    unit translations; keeping the prototiles apart leaves the chessboard's colour group,
    *442 on the diagonal lattice (1, 1), (1, -1)."""
    tiling = periodic([SQUARE, SQUARE], [(0, ID), (1, T(1, 0))], (1, 1), (1, -1))
    plain = symmetries(tiling)
    assert plain.lattice_index == 2 and wallpaper_group(tiling).iuc == "p4m"
    kept = symmetries(tiling, match_prototiles=True)
    assert kept.lattice_index == 1
    assert abs(abs(np.linalg.det(kept.lattice)) - 2.0) < 1e-9
    assert wallpaper_group(tiling, match_prototiles=True).iuc == "p4m"
    assert isohedrality(tiling) == 1


def test_properties_are_json_scalars() -> None:
    """Catalogue records need JSON scalars or lists under snake_case keys."""
    props = wallpaper_group(TILINGS["basketweave"][1]).properties()
    assert props == {
        "wallpaper_group": "p4g",
        "orbifold": "4*2",
        "point_group_order": 8,
        "rotation_orders": [2, 4],
        "reflections": True,
        "glide_reflections": True,
    }
    assert all(isinstance(v, str | int | bool | list) for v in props.values())
    assert str(wallpaper_group(TILINGS["basketweave"][1])) == "p4g (4*2)"


def test_generators_are_classified() -> None:
    """Generators carry their classification: p4g's are two translations, a quarter turn
    and an opposite isometry."""
    group = wallpaper_group(TILINGS["basketweave"][1])
    kinds = [g.kind for g in group.generators]
    assert kinds[:3] == ["translation", "translation", "rotation"]
    assert kinds[3] in ("reflection", "glide reflection")
    assert group.generators[2].isometry.order == 4


@pytest.mark.parametrize("name", ["basketweave", "pythagorean", "C3 hexagons", "glided chevrons"])
def test_symmetry_properties_agree_with_the_single_functions(name: str) -> None:
    """symmetry_properties computes the group once; its answers equal the separate calls."""
    from tilekit.colouring import Colouring
    from tilekit.symmetry import is_perfect_colouring, symmetry_properties

    tiling = TILINGS[name][1]
    if name == "glided chevrons":  # colour the two columns apart: every symmetry keeps or swaps them
        tiling = PeriodicTiling(
            tiling.prototiles, tiling.unit_prototile, tiling.unit_transform, tiling.v1, tiling.v2,
            Colouring.parse("(1 2)(1 2)(1 2)"),
        )
    props = symmetry_properties(tiling)
    expected = wallpaper_group(tiling).properties()
    expected.update(
        k_isohedral=isohedrality(tiling),
        k_isogonal=isogonality(tiling),
        perfect_colouring=is_perfect_colouring(tiling),
    )
    assert props == expected
    assert set(symmetry_properties(tiling, colouring=False, vertices=False)) == set(expected) - {
        "k_isogonal",
        "perfect_colouring",
    }
