"""tilekit.polygon: array-first polygon functions (doctests plus facts about regular polygons)."""

import doctest
import math

import numpy as np
import pytest

import tilekit.geometry
import tilekit.polygon
from tilekit.geometry import Affine
from tilekit.polygon import (
    area,
    canonical_cycle,
    centroid,
    congruences,
    interior_angles,
    regular_polygon,
    signed_area,
    symmetry_maps,
    vertex_stars,
)


def test_doctests():
    assert doctest.testmod(tilekit.polygon).failed == 0
    assert doctest.testmod(tilekit.geometry).failed == 0


@pytest.mark.parametrize("n", [3, 4, 5, 6, 8, 12])
def test_regular_polygons(n):
    p = regular_polygon(n)
    # area of a regular n-gon with unit side: n / (4 tan(pi / n))
    assert signed_area(p) == pytest.approx(n / (4 * math.tan(math.pi / n)))
    assert np.allclose(interior_angles(p), math.pi * (n - 2) / n)
    assert len(symmetry_maps(p)) == 2 * n  # the dihedral group D_n
    assert len(congruences(p, p + 3.0, 1e-9)) == 2 * n


def test_stacks_answer_per_polygon():
    p = regular_polygon(6)
    stack = np.stack([p, 2 * p, p[::-1]])
    assert np.allclose(signed_area(stack), [signed_area(p), 4 * signed_area(p), -signed_area(p)])
    assert np.allclose(area(stack), np.abs(signed_area(stack)))
    assert np.allclose(centroid(stack), [centroid(p), 2 * centroid(p), centroid(p)])
    assert interior_angles(stack).shape == (3, 6)


def test_vertex_stars_of_the_hexagonal_tiling_have_three_corners():
    from tilekit.plugins.archimedean import archimedean_tiling

    patch = archimedean_tiling("6^3").patch((-4, -4, 4, 4))
    stars = vertex_stars(patch.polygons())
    inner = np.hypot(*stars.points.T) < 2
    assert set(stars.valence()[inner].tolist()) == {3}


def test_canonical_cycle_reads_a_word_either_way_round():
    word = [("a", 1), ("b", 2), ("b", 3), ("c", 1)]
    turned = word[2:] + word[:2]
    assert canonical_cycle(word) == canonical_cycle(turned) == canonical_cycle(list(reversed(word)))
    assert canonical_cycle(word) != canonical_cycle([("a", 1), ("b", 3), ("b", 2), ("c", 1)])


def _codes(patch, radius, inside):
    polys = patch.polygons()
    stars = vertex_stars(polys)
    labels = [len(p) for p in polys]
    centres = np.array([p.mean(axis=0) for p in polys])
    keep = [v for v in range(len(stars)) if inside(stars.points[v])]
    star_codes = {stars.star_code(v, polys, labels) for v in keep}
    hoods = set()
    for v in keep:
        near = np.flatnonzero(np.hypot(*(centres - stars.points[v]).T) < radius)
        hoods.add(stars.neighbourhood_code(v, polys, labels, centres, near))
    return star_codes, hoods


def test_star_and_neighbourhood_codes_of_a_vertex_transitive_tiling():
    # 3.4.6.4 has one vertex orbit: one star, and one neighbourhood of every radius
    from tilekit.plugins.archimedean import archimedean_tiling

    patch = archimedean_tiling("3.4.6.4").patch((-9, -9, 9, 9))
    stars, hoods = _codes(patch, 2.3, lambda p: np.abs(p).max() < 5)
    assert len(stars) == 1 and len(hoods) == 1
    (star,) = stars
    assert sorted(label for label, *_ in star) == [3, 4, 4, 6]


def test_codes_do_not_change_under_isometries():
    from tilekit.plugins.archimedean import archimedean_tiling

    patch = archimedean_tiling("3^3.4^2").patch((-9, -9, 9, 9))
    moved = patch.transformed(Affine.translation(17.25, -3.5) @ Affine.rotation(0.7) @ np.diag([1.0, -1.0, 1.0]))
    a = _codes(patch, 1.9, lambda p: np.abs(p).max() < 5)
    inv = np.linalg.inv(Affine.translation(17.25, -3.5) @ Affine.rotation(0.7) @ np.diag([1.0, -1.0, 1.0]))
    b = _codes(moved, 1.9, lambda p: np.abs(Affine.apply(inv, p[None])[0]).max() < 5)
    assert a == b and None not in a[0]


# -- edge to edge (§4.1) ---------------------------------------------------------------------

def _meets_edge_to_edge(tiling) -> bool:
    patch = tiling.patch(tiling.default_region())
    return tilekit.polygon.edge_to_edge(pts for _, _, pts in patch.groups())


ARCHIMEDEAN = ["3^6", "4^4", "6^3", "3^4.6", "3^3.4^2", "3^2.4.3.4", "3.4.6.4", "3.6.3.6", "3.12^2",
               "4.6.12", "4.8^2"]


@pytest.mark.parametrize("vertex_type", ARCHIMEDEAN)
def test_archimedean_and_laves_tilings_are_edge_to_edge(vertex_type):
    """§4.1: the eleven Archimedean tilings are edge-to-edge tilings by regular polygons, and
    their duals, the Laves tilings, are "monohedral, edge-to-edge" tilings."""
    from tilekit.plugins.archimedean import archimedean_tiling, laves_tiling

    assert _meets_edge_to_edge(archimedean_tiling(vertex_type))
    assert _meets_edge_to_edge(laves_tiling(vertex_type))


@pytest.mark.parametrize(("system", "expected"), [
    ("penrose-p2", True), ("penrose-p3", True), ("ammann-beenker", True),
    ("chair", False), ("pinwheel", False)])
def test_substitution_tilings_edge_to_edge_or_not(system, expected):
    """Penrose's kites and darts and rhombs and the Ammann-Beenker rhombs and squares meet edge
    to edge (Grünbaum & Shephard §10.3; Baake & Grimm, Aperiodic Order vol. 1, §6.1); a chair's
    corner sits at the middle of a neighbour's long side (G&S §10.1) and the pinwheel's
    triangles meet vertex to side (Radin, Ann. Math. 139, 1994)."""
    from tilekit.plugins.substitution import tiling

    assert _meets_edge_to_edge(tiling(system)) is expected
    assert tiling(system).properties()["edge_to_edge"] is expected


def test_a_shifted_row_breaks_edge_to_edge():
    """Fig. 4.1's situation: shifting one row of a square grid by half a side puts corners on
    sides; shifting it by a whole side does not."""
    sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    for shift, expected in ((0.5, False), (1.0, True), (0.25, False)):
        tiles = np.stack([sq + [i + shift * (j == 1), j] for i in range(4) for j in range(3)])
        assert tilekit.polygon.edge_to_edge([tiles]) is expected
    # a straight angle is not a corner: squares whose outline repeats the midpoint of a side
    with_mid = np.array([[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    assert tilekit.polygon.edge_to_edge([np.stack([with_mid + [i, j] for i in range(3) for j in range(3)])])
