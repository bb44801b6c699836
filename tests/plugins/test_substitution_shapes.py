"""Penrose tiles with shaped, interlocking edges (§6.3, Figures 6.3 and 6.14)."""

from __future__ import annotations

import numpy as np
import pytest
from test_substitution import assert_valid

from tilekit.errors import ParameterError, ParseError
from tilekit.plugins.substitution import builtin_systems, from_spec, tiling
from tilekit.plugins.substitution.shapes import complement, edge_classes, parse_edge_shape


@pytest.mark.parametrize("name", ["penrose-p2", "penrose-p3"])
def test_penrose_tiles_have_two_free_edge_shapes(name: str) -> None:
    """§6.3: the matching conditions leave "two arbitrary J edge shapes" for each Penrose set;
    every edge carries one of them or its interlocking complement, each tile has both, and
    each class appears with both signs (a shape always meets its complement)."""
    s = builtin_systems()[name]
    ec = edge_classes(s)
    assert ec.count == 2
    for edges in ec.label:
        assert {c for c, _ in edges} == {0, 1}
    signs = {(c, sgn) for edges in ec.label for c, sgn in edges}
    assert signs == {(0, 1), (0, -1), (1, 1), (1, -1)}


def test_complement_is_the_same_curve_seen_from_the_other_side() -> None:
    shape = np.array([[0.2, 0.1], [0.5, -0.05]])
    c = complement(shape)
    assert np.allclose(c, [[0.5, 0.05], [0.8, -0.1]])
    assert np.allclose(complement(c), shape)


@pytest.mark.parametrize("name", ["penrose-p2", "penrose-p3"])
@pytest.mark.parametrize("params, edges", [([0.1, -0.07], None), (None, ["a=0.2,0.05:0.5,-0.05:0.8,0.05", "b=0.3,-0.08"])])
def test_shaped_tiles_tile_without_overlaps_or_holes(name: str, params, edges) -> None:
    t = tiling(name).configure(params=params, edges=edges)
    region = (-6.0, -6.0, 6.0, 6.0)
    patch = t.patch(region)
    assert_valid(patch, region)
    assert all(len(p.outline) > 4 for p in patch.prototiles)  # the edges really are shaped
    # and far from the origin, where the shaped tiles come from a deeper substitution
    far = (83.0, -41.0, 92.0, -30.0)
    assert_valid(t.patch(far), far)
    back = from_spec(t.spec())
    assert len(back.patch(region)) == len(patch)


def test_self_intersecting_shapes_are_rejected() -> None:
    with pytest.raises(ParameterError, match="self-intersect"):
        tiling("penrose-p3").configure(params=[0.6])
    with pytest.raises(ParameterError, match="self-intersect"):
        tiling("penrose-p2").configure(edges=["a=0.5,0.2:0.4,-0.3:0.6,0.1:0.3,0.1"])


def test_bad_edge_options_are_rejected() -> None:
    with pytest.raises(ParameterError, match="edge classes a, b"):
        tiling("penrose-p3").configure(edges=["z=0.5,0.1"])
    with pytest.raises(ParameterError, match="2 free edge shape"):
        tiling("penrose-p3").configure(params=[0.1, 0.1, 0.1])
    with pytest.raises(ParameterError, match="no assembled whole tiles"):
        tiling("sphinx").configure(params=[0.1])
    with pytest.raises(ParseError, match="not 'x,y'"):
        parse_edge_shape("a=0.5;0.1")
