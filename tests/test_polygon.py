"""tilekit.polygon: array-first polygon functions (doctests plus facts about regular polygons)."""

import doctest
import math

import numpy as np
import pytest

import tilekit.geometry
import tilekit.polygon
from tilekit.polygon import (
    area,
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
