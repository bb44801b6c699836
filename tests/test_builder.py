"""The shared backtracking patch builder (§2.4 Extension Theorem, exercise 6.2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from tilekit.budget import Budget
from tilekit.builder import PatchBuilder, VertexView, build_patch, labels_match
from tilekit.errors import ParameterError
from tilekit.geometry import regular_polygon
from tilekit.tiling import Prototile


def _disc(result, radius: float):
    patch = result.patch
    seed = patch.centres()[0]
    return shapely.Point(*seed).buffer(radius, quad_segs=64)


@pytest.mark.parametrize(
    "sides, radius",
    [((3,), 3.0), ((4,), 4.0), ((6,), 4.0), ((4, 8), 4.0), ((3, 12), 5.0)],
)
def test_sets_that_tile_reach_the_radius(sides, radius):
    """Regular 3-, 4-, 6-gons, the (4.8^2) and (3.12^2) sets tile (§4.1), so a patch covering
    a disc of any radius exists; the builder must return one that covers it exactly."""
    protos = [Prototile(regular_polygon(n)) for n in sides]
    res = build_patch(protos, radius=radius, seed=len(protos) - 1, max_nodes=50_000)
    assert res.status == "complete", res.stats.reason
    report = res.patch.validate(_disc(res, radius))
    assert report, report.summary()
    assert res.stats.placements == len(res.patch) + res.stats.backtracks


def test_regular_pentagons_alone_are_exhausted():
    """Regular pentagons cannot tile (exercise 4.3a: 108° does not divide 360°): the builder
    must prove it (status exhausted, no patch), for a tile goal and a radius goal."""
    pent = [Prototile(regular_polygon(5))]
    for goal in ({"tiles": 3}, {"radius": 2.0}):
        res = build_patch(pent, **goal)
        assert res.status == "exhausted"
        assert res.patch is None
        assert not res


def test_pentagons_without_the_angle_test_die_by_overlap():
    """With a rule that accepts everything the pentagon still fails: three pentagons leave a
    36° gap no pentagon fits, so every branch dies when a vertex cannot close."""

    class Anything:
        def closed(self, view: VertexView) -> bool:
            return True

        def open(self, view: VertexView) -> bool:
            return True

    res = PatchBuilder([Prototile(regular_polygon(5))], rule=Anything()).build(radius=2.0)
    assert res.status == "exhausted"
    assert "exhausted" in res.stats.reason


def test_node_and_time_limits_are_honoured():
    """A limit is reported as 'limit' with no patch, never as a partial success."""
    tri = [Prototile(regular_polygon(3))]
    res = build_patch(tri, radius=50.0, max_nodes=40)
    assert res.status == "limit" and res.patch is None
    assert res.stats.nodes == 40
    assert "node limit" in res.stats.reason
    # the time limit is CPU seconds of the calling thread (tilekit.budget), not wall-clock time
    res = build_patch(tri, radius=500.0, max_seconds=0.05)
    assert res.status == "limit" and res.patch is None
    assert res.stats.reason.startswith("gave up at the time limit (0.05 CPU seconds) (largest patch")
    budget = Budget(0.05)
    res = build_patch(tri, radius=500.0, max_seconds=budget)
    assert res.status == "limit" and budget.spent() and 0.05 <= budget.used() < 1.0
    spent = Budget(0.0)
    res = build_patch(tri, radius=500.0, max_seconds=spent)
    assert res.status == "limit" and (res.stats.nodes, res.stats.max_tiles) == (1, 1)  # one candidate tried after the seed


def test_deterministic():
    """Two runs with the same input place the same tiles in the same order."""
    protos = [Prototile(regular_polygon(4)), Prototile(regular_polygon(8))]
    a = build_patch(protos, tiles=60, seed=1)
    b = build_patch(protos, tiles=60, seed=1)
    assert a.ok and b.ok
    assert np.array_equal(a.patch.prototile, b.patch.prototile)
    assert np.array_equal(a.patch.transform, b.patch.transform)


@pytest.mark.parametrize("order", ["bfs", "dfs", "nearest", lambda e: -e["angle_sum"]])
def test_frontier_orders(order):
    """Every order (and a callable key: fill edges at the fullest vertex first) grows a valid
    patch of the (3.12^2) set reaching the radius."""
    protos = [Prototile(regular_polygon(3)), Prototile(regular_polygon(12))]
    res = build_patch(protos, radius=3.5, seed=1, order=order, max_nodes=100_000)
    assert res.ok, res.stats.reason
    assert res.patch.validate(_disc(res, 3.5))


def test_fill_goal_covers_a_box():
    """A fill predicate as the goal: close every open edge whose midpoint lies inside a box;
    the patch then covers the box (here squares, so exactly the 5 x 3 unit cells)."""
    inside = lambda e: -1.9 < e["midpoint"][0] < 2.9 and -0.9 < e["midpoint"][1] < 1.9  # noqa: E731
    res = build_patch([Prototile(regular_polygon(4))], fill=inside)
    assert res.ok and len(res.patch) == 15
    assert res.patch.validate((-2.0, -1.0, 3.0, 2.0))
    # a first corona: close every edge of the seed tile (4 neighbours for a square)
    res = build_patch([Prototile(regular_polygon(4))], fill=lambda e: e["tile"] == 0)
    assert res.ok and len(res.patch) == 5
    # pentagons on two adjacent edges of a pentagon leave 36° at their common corner, which
    # no pentagon corner fills (the angle test sees it at once): no first corona that could
    # be part of a tiling; without the angle test the flower of 5 pentagons is a valid patch
    pent = [Prototile(regular_polygon(5))]
    assert build_patch(pent, fill=lambda e: e["tile"] == 0).status == "exhausted"
    flower = build_patch(pent, fill=lambda e: e["tile"] == 0, angle_check=False)
    assert flower.ok and len(flower.patch) == 6 and flower.patch.validate()


def test_tile_goal_and_bfs_order():
    """Exercise 6.2: breadth-first from one tile to a given number of tiles; the first ring of a
    square patch is the 4 edge neighbours of the seed."""
    res = build_patch([Prototile(regular_polygon(4))], tiles=5)
    assert res.ok and len(res.patch) == 5
    assert res.patch.validate()
    centres = res.patch.centres()
    d = np.hypot(*(centres[1:] - centres[0]).T)
    assert np.allclose(d, 1.0)


def test_edge_labels_i_minus_i():
    """Exercise 6.2's rule: a shared edge carries labels i and -i. A square labelled
    (1, 2, -1, -2) tiles (each label meets its negative across the square); (1, 1, 1, 1)
    cannot even have a neighbour."""
    sq = regular_polygon(4)
    good = build_patch([Prototile(sq, edge_labels=(1, 2, -1, -2))], radius=3.0)
    assert good.ok and good.patch.validate()
    bad = build_patch([Prototile(sq, edge_labels=(1, 1, 1, 1))], tiles=2)
    assert bad.status == "exhausted"
    assert labels_match(3, -3) and not labels_match(3, 3) and labels_match(None, None)
    assert not labels_match(None, 1)


def test_pluggable_compatibility():
    """A custom compatibility predicate replaces the i / -i rule (here: equal colours)."""
    sq = Prototile(regular_polygon(4), edge_labels=("a", "b", "a", "b"))
    res = build_patch([sq], tiles=9, compatible=lambda x, y: x == y)
    assert res.ok and res.patch.validate()
    res = build_patch([sq], tiles=2, compatible=lambda x, y: x != y and x == "never")
    assert res.status == "exhausted"


def test_non_convex_prototile_with_reflections():
    """The L-tromino (non-convex, split into convex pieces for the overlap test) tiles the
    plane; a patch covering radius 2.5 exists and is valid."""
    ell = np.array([(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2), (0, 1)], float)
    for reflections in (False, True):
        res = build_patch([Prototile(ell)], radius=2.5, reflections=reflections, max_nodes=100_000)
        assert res.ok, res.stats.reason
        assert res.patch.validate(_disc(res, 2.5))


def test_reflections_give_mirror_images():
    """A scalene triangle has 3 distinct edge placements per hand: 6 with reflections; a
    square's mirror image is a rotated copy, so reflections add none. Without reflections
    every placement is direct (determinant +1)."""
    tri = Prototile(np.array([(0, 0), (2, 0), (0, 1)], float))
    assert len(PatchBuilder([tri])._cands) == 3
    assert len(PatchBuilder([tri], reflections=True)._cands) == 6
    sq = Prototile(regular_polygon(4))
    assert len(PatchBuilder([sq], reflections=True)._cands) == len(PatchBuilder([sq])._cands) == 1
    direct = build_patch([tri], radius=2.0, reflections=False, max_nodes=50_000)
    both = build_patch([tri], radius=2.0, reflections=True, max_nodes=50_000)
    assert direct.ok and both.ok
    t = direct.patch.transform
    assert np.all(t[:, 0, 0] * t[:, 1, 1] - t[:, 0, 1] * t[:, 1, 0] > 0)
    assert both.patch.validate() and direct.patch.validate()


def test_reflected_labels_follow_their_edges():
    """A mirrored tile keeps each label on its own (mirrored) edge: with equal-label matching
    a triangle labelled by edge length meets a copy only along equal edges, in both hands."""
    tri = Prototile(np.array([(0, 0), (2, 0), (0, 1)], float), edge_labels=("long", "hyp", "short"))
    res = build_patch([tri], radius=2.0, reflections=True, compatible=lambda a, b: a == b)
    assert res.ok and res.patch.validate()
    lengths = {"long": 2.0, "hyp": math.sqrt(5), "short": 1.0}
    # every label sits on an edge of its own length, in every placed tile
    for t, pts in enumerate(res.patch.polygons()):
        proto = res.patch.prototiles[int(res.patch.prototile[t])]
        edge = np.hypot(*(np.roll(pts, -1, axis=0) - pts).T)
        assert np.allclose(edge, [lengths[lab] for lab in proto.edge_labels])


def test_vertex_rule_sees_closed_vertices():
    """The rule's closed() is called with the corners round each surrounded vertex, in
    counter-clockwise order, summing to 2π."""
    seen: list[VertexView] = []

    class Record:
        def closed(self, view: VertexView) -> bool:
            seen.append(view)
            return True

        def open(self, view: VertexView) -> bool:
            return True

    res = PatchBuilder([Prototile(regular_polygon(6))], rule=Record()).build(radius=2.5)
    assert res.ok and seen
    for v in seen:
        assert v.closed and len(v.fans) == 1 and len(v.corners) == 3
        assert math.isclose(sum(c.angle for c in v.corners), 2 * math.pi, abs_tol=1e-9)


def test_bad_input_is_rejected():
    sq = [Prototile(regular_polygon(4))]
    with pytest.raises(ParameterError, match="exactly one goal"):
        build_patch(sq)
    with pytest.raises(ParameterError, match="exactly one goal"):
        build_patch(sq, tiles=3, radius=2.0)
    with pytest.raises(ParameterError, match="exactly one goal"):
        build_patch(sq, radius=2.0, fill=lambda e: True)
    with pytest.raises(ParameterError, match="order"):
        PatchBuilder(sq, order="sideways")
    with pytest.raises(ParameterError, match="seed"):
        build_patch(sq, tiles=3, seed=4)
    with pytest.raises(ParameterError, match="radius"):
        build_patch(sq, radius=-1.0)
    with pytest.raises(ParameterError, match="at least one prototile"):
        PatchBuilder([])


def _polygon_from(angles: list[float], radii: list[float]) -> np.ndarray | None:
    a = np.sort(np.asarray(angles))
    pts = np.c_[np.asarray(radii) * np.cos(a), np.asarray(radii) * np.sin(a)]
    try:
        proto = Prototile(pts)
    except Exception:
        return None
    from tilekit.polygon import interior_angles as _interior_angles

    ang = _interior_angles(proto.outline)
    if ang.min() < math.radians(20) or ang.max() > math.radians(160):
        return None  # slivers tile too, but need hundreds of tiles per vertex
    edges = np.hypot(*(np.roll(proto.outline, -1, axis=0) - proto.outline).T)
    if edges.min() < 0.4:
        return None  # tiny tiles need tens of thousands of tiles to cover the disc
    return proto.outline


@settings(max_examples=25, deadline=None)
@given(
    st.integers(3, 4),
    st.lists(st.floats(0.0, 2 * math.pi), min_size=4, max_size=4),
    st.lists(st.floats(0.7, 1.3), min_size=4, max_size=4),
)
def test_any_triangle_or_quadrilateral_tiles(k, angles, radii):
    """Exercise 2.1: any triangle and any (convex) quadrilateral tiles the plane, so the
    builder must find a patch covering a disc for every such tile it is given."""
    outline = _polygon_from(angles[:k], radii[:k])
    assume(outline is not None)
    res = build_patch([Prototile(outline)], radius=1.5, order="nearest", max_nodes=20_000)
    assert res.ok, res.stats.reason
    report = res.patch.validate(_disc(res, 1.5))
    assert report, report.summary()


# ---------------------------------------------------------------------- periodic mode (a torus)

SQRT3 = math.sqrt(3.0)


def _images(result, period, k: int = 1):
    """The representatives and their lattice images in a (2k+1)^2 block, as one patch."""
    patch = result.patch
    per = np.asarray(period, dtype=float)
    transforms, protos = [], []
    for a in range(-k, k + 1):
        for b in range(-k, k + 1):
            t = patch.transform.copy()
            t[:, :2, 2] += a * per[0] + b * per[1]
            transforms.append(t)
            protos.append(patch.prototile)
    pr = np.concatenate(protos)
    from tilekit.tiling import Patch

    return Patch(patch.prototiles, pr, np.concatenate(transforms), pr.copy(), np.zeros(len(pr), dtype=np.int64))


def _cell(result, period):
    per = np.asarray(period, dtype=float)
    o = np.asarray(result.patch.centres()[0]) - 0.5 * (per[0] + per[1])
    return shapely.Polygon([o, o + per[0], o + per[0] + per[1], o + per[1]])


@pytest.mark.parametrize(
    "sides, period, count",
    [
        ((4,), ((3, 0), (0, 2)), 6),  # 3 x 2 squares
        ((4,), ((1, 0), (0, 1)), 1),  # one square is its own translational unit
        ((4,), ((2, 1), (0, 2)), 4),  # a sheared sublattice of Z^2 is a period of (4^4) too
        ((3,), ((1, 0), (0.5, SQRT3 / 2)), 2),  # (3^6): two triangles per lattice cell
        ((3,), ((3, 0), (1, SQRT3)), 12),
        ((6,), ((1.5, SQRT3 / 2), (0, SQRT3)), 1),  # (6^3): one hexagon per cell
        ((6,), ((3, 0), (0, 2 * SQRT3)), 4),
        ((4, 8), ((1 + math.sqrt(2), 0), (0, 1 + math.sqrt(2))), 2),  # (4.8^2): one of each
    ],
)
def test_regular_and_archimedean_tori_close(sides, period, count):
    """The regular tilings (4^4), (3^6), (6^3) and the Archimedean (4.8^2) (§4.1) have these
    lattices as periods, so the torus closes; the representatives number area / tile area
    (per prototile mix) and their lattice images tile the fundamental cell exactly."""
    protos = [Prototile(regular_polygon(n)) for n in sides]
    res = build_patch(protos, period=period, seed=len(protos) - 1, max_nodes=20_000)
    assert res.status == "complete", res.stats.reason
    assert len(res.patch) == count and "closed torus" in res.stats.reason
    report = _images(res, period).validate(_cell(res, period))
    assert report, report.summary()


@pytest.mark.parametrize("period", [((1, 0.5), (0, 1)), ((2.5, 0), (0, 2)), ((1.5, 0), (0, 1))])
def test_lattices_that_are_no_period_of_the_square_grid_are_exhausted(period):
    """The only edge-to-edge tiling by congruent squares is (4^4), whose periods are the
    vectors of Z^2 (edge length 1): a lattice with another vector admits no torus (the
    column shift of (1, 0.5) would give a brick tiling, which is not edge to edge)."""
    res = build_patch([Prototile(regular_polygon(4))], period=period, max_nodes=20_000)
    assert res.status == "exhausted", res.stats.reason
    assert res.patch is None


@pytest.mark.parametrize("period", [((3, 0), (0, 3)), ((2, 0), (1, 2)), ((1.618, 0), (0.5, 1.539))])
@pytest.mark.parametrize("angle_check", [True, False])
def test_regular_pentagons_never_close_a_torus(period, angle_check):
    """Regular pentagons do not tile the plane (108 does not divide 360), so no torus."""
    res = build_patch([Prototile(regular_polygon(5))], period=period, angle_check=angle_check, max_nodes=50_000)
    assert res.status == "exhausted", res.stats.reason


def test_periodic_tile_goal_counts_representatives_and_backtracks_past_a_closed_torus():
    """A 2 x 2 square torus holds exactly 4 tiles: tiles=3 stops on a partial torus, tiles=5
    finds every branch closing at 4 and is exhausted (not 'complete', not a plane answer)."""
    square = [Prototile(regular_polygon(4))]
    part = build_patch(square, period=((2, 0), (0, 2)), tiles=3)
    assert part.status == "complete" and len(part.patch) == 3
    over = build_patch(square, period=((2, 0), (0, 2)), tiles=5)
    assert over.status == "exhausted" and "torus with 5 tiles" in over.stats.reason


def test_periodic_labels_must_match_across_the_cell_boundary():
    """Exercise 6.2 labels on a 1 x 1 square torus: the tile meets its own images, so its E
    edge meets its own W edge and N meets S; labels (1, 2, -1, -2) close it, (1, 2, 1, -2)
    cannot (1 meets 1, not -1)."""
    sq = regular_polygon(4)
    good = Prototile(sq, edge_labels=(1, 2, -1, -2))
    bad = Prototile(sq, edge_labels=(1, 2, 1, -2))
    assert build_patch([good], period=((1, 0), (0, 1))).status == "complete"
    res = build_patch([bad], period=((1, 0), (0, 1)))
    assert res.status == "exhausted" and res.stats.rejections.get("edge labels", 0) >= 1


def test_periodic_fill_goal_sees_representatives_only():
    """With a period, the fill predicate and the frontier order only ever see the open edges
    of representatives (their images' edges are filled through them)."""
    seen: list[int] = []

    def fill(edge):
        seen.append(edge["tile"])
        return True

    builder = PatchBuilder([Prototile(regular_polygon(4))], period=((3, 0), (0, 2)))
    res = builder.build(fill=fill)
    assert res.status == "complete" and len(res.patch) == 6
    assert set(seen) <= builder._canon | {0}


def test_period_is_validated():
    square = [Prototile(regular_polygon(4))]
    with pytest.raises(ParameterError, match="parallel"):
        PatchBuilder(square, period=((1, 0), (2, 0)))
    with pytest.raises(ParameterError, match="two lattice vectors"):
        PatchBuilder(square, period=(1, 0))
    with pytest.raises(ParameterError, match="radius=R is a goal in the plane"):
        build_patch(square, period=((1, 0), (0, 1)), radius=2.0)
    with pytest.raises(ParameterError, match="at most one goal"):
        build_patch(square, period=((1, 0), (0, 1)), tiles=1, fill=lambda e: True)
