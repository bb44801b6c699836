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
