"""Core vocabulary: Prototile, Patch (columns, validate, clip), PeriodicTiling replication (§3.4, §3.5)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit import (
    Affine,
    Colouring,
    GeometryError,
    ParameterError,
    Patch,
    PeriodicTiling,
    Prototile,
)
from tilekit.geometry import regular_polygon

SQRT3 = math.sqrt(3)


def squares() -> PeriodicTiling:
    return PeriodicTiling([Prototile(regular_polygon(4))], [0], np.eye(3)[None], (1, 0), (0, 1))


def triangles() -> PeriodicTiling:
    # 3^6: an up triangle and its half-turn about the midpoint of its right edge form a unit.
    tri = Prototile(regular_polygon(3))
    unit = np.array([np.eye(3), Affine.half_turn((0.75, SQRT3 / 4))])
    return PeriodicTiling([tri], [0, 0], unit, (1, 0), (0.5, SQRT3 / 2))


def hexagons() -> PeriodicTiling:
    hexagon = Prototile(regular_polygon(6))
    # 6^3: the lattice of a unit regular hexagon is spanned by vectors of length sqrt(3).
    return PeriodicTiling([hexagon], [0], np.eye(3)[None], (1.5, SQRT3 / 2), (0, SQRT3))


def reshaped(t: PeriodicTiling, theta: float, shear: int) -> PeriodicTiling:
    """The same tiling rotated by theta, described by a skewed basis of the same lattice.

    (v1, v2) -> (v1 + shear*v2, v2) is unimodular, so the lattice (and the tiling) is unchanged.
    """
    rot = Affine.rotation(theta)
    v1 = rot[:2, :2] @ (t.v1 + shear * t.v2)
    v2 = rot[:2, :2] @ t.v2
    return PeriodicTiling(t.prototiles, t.unit_prototile, rot @ t.unit_transform, v1, v2)


REGULAR = {"3^6": triangles, "4^4": squares, "6^3": hexagons}


@pytest.mark.parametrize("name", sorted(REGULAR))
def test_regular_tilings_cover_a_box_without_overlap(name: str) -> None:
    t = REGULAR[name]()
    region = (-5.3, -4.1, 6.2, 3.7)
    report = t.patch(region).validate(region)
    assert report.ok, report.summary()


@settings(max_examples=25, deadline=None)
@given(
    name=st.sampled_from(sorted(REGULAR)),
    theta=st.floats(0, 2 * math.pi),
    shear=st.integers(-4, 4),
    x0=st.floats(-20, 20),
    y0=st.floats(-20, 20),
    w=st.floats(0.2, 9),
    h=st.floats(0.2, 9),
)
def test_replication_covers_random_regions_with_rotated_skewed_bases(name, theta, shear, x0, y0, w, h):
    t = reshaped(REGULAR[name](), theta, shear)
    region = (x0, y0, x0 + w, y0 + h)
    patch = t.patch(region)
    report = patch.validate(region)
    assert report.ok, report.summary()
    # nothing far away: every returned tile's bounding box meets the region's box
    b = patch.tile_bounds()
    assert np.all((b[:, 2] >= x0) & (b[:, 0] <= x0 + w) & (b[:, 3] >= y0) & (b[:, 1] <= y0 + h))


def test_unit_with_far_flung_tiles_still_covers() -> None:
    """§3.5: no fixed number of rings suffices — a unit whose tiles sit many periods away.

    Moving each unit tile by a different lattice vector gives the same tiling; the
    rasterization must find the tiles anyway.
    """
    t = triangles()
    unit = t.unit_transform.copy()
    unit[0, :2, 2] += 7 * t.v1 - 5 * t.v2
    unit[1, :2, 2] += -9 * t.v2
    far = PeriodicTiling(t.prototiles, [0, 0], unit, t.v1, t.v2)
    region = (-1.5, -1.5, 1.5, 1.5)
    assert far.patch(region).validate(region).ok
    assert len(far.patch(region)) == len(t.patch(region))


def test_non_rectangular_region_is_clipped_to_tiles_meeting_it() -> None:
    disc = shapely.Point(0.3, 0.2).buffer(3.0)
    patch = squares().patch(disc)
    assert patch.validate(disc).ok
    assert np.all(shapely.intersects(disc, patch.geometries()))


def test_validate_reports_overlap_and_gap() -> None:
    sq = Prototile(regular_polygon(4))
    moves = np.array([np.eye(3), Affine.translation(0.5, 0), Affine.translation(3, 0)])
    report = Patch([sq], [0, 0, 0], moves).validate((0, 0, 4, 1))
    assert not report.ok
    assert [(i, j) for i, j, _ in report.overlaps] == [(0, 1)]
    assert report.overlaps[0][2] == pytest.approx(0.5)
    assert report.uncovered_area == pytest.approx(4 - 2.5)
    assert "overlapping" in report.summary() and "gap" in report.summary()
    with pytest.raises(GeometryError):
        report.raise_if_invalid()


def test_shared_edges_are_not_overlaps() -> None:
    sq = Prototile(regular_polygon(4))
    moves = np.array([Affine.translation(i * (1 + 1e-12), 0) for i in range(4)])
    assert Patch([sq], [0] * 4, moves).validate((0, 0, 4, 1)).ok


def test_float_noise_on_shared_edges_is_not_an_overlap() -> None:
    """A glide-reflected hexagon tiling whose shared edges differ by float noise.

    GEOS's floating overlay once reported a full tile (area 0.984) as the intersection of
    two tiles that only share an edge; validate must use a snap-rounded overlay.
    """
    tile = Prototile(np.array([(0, 0), (0.3, 0.2), (1, 0), (1, 1), (0.3, 1.2), (0, 1)]))
    glide = Affine.translation(0, 0.5) @ Affine.reflection(math.pi / 2, (1, 0))
    t = PeriodicTiling([tile], [0, 0], np.array([np.eye(3), glide]), (2, 0), (0, 1))
    region = (-3, -3, 3, 3)
    report = t.patch(region).validate(region)
    assert report.ok, report.summary()


def test_colouring_permutes_between_units() -> None:
    """Figure 5.12's rule: aspect i in the unit at a*v1 + b*v2 has colour rho2^b(rho1^a(c_i))."""
    col = Colouring.parse("(1 2)(2 3 1)(1 2 3)")
    t = triangles()
    t = PeriodicTiling(t.prototiles, [0, 0], t.unit_transform, t.v1, t.v2, col)
    patch = t.patch((-0.01, -0.01, 3.2, 0.3))  # one row of units, a = 0..3
    # aspect-0 tiles of the row b = 0: translation (a, 0), so a is the x translation
    row = (patch.aspect == 0) & (np.abs(patch.transform[:, 1, 2]) < 1e-9)
    a_idx = np.rint(patch.transform[row, 0, 2]).astype(int)
    got = dict(zip(a_idx.tolist(), patch.colour[row].tolist()))
    # colour 1 -> 2 -> 3 -> 1 under p = (2 3 1), 0-based 0 -> 1 -> 2 -> 0; a = -1 is the inverse
    assert got == {-1: 2, 0: 0, 1: 1, 2: 2, 3: 0}


def test_degenerate_inputs_raise_clear_errors() -> None:
    sq = Prototile(regular_polygon(4))
    with pytest.raises(GeometryError, match="parallel"):
        PeriodicTiling([sq], [0], np.eye(3)[None], (1, 0), (2, 0))
    with pytest.raises(GeometryError, match="zero area"):
        Prototile(np.array([[0, 0], [1, 0], [2, 0]]))
    with pytest.raises(GeometryError, match="self-intersecting"):
        Prototile(np.array([[0, 0], [2, 0], [2, 2], [1, -1], [0, 2]]))
    with pytest.raises(ParameterError, match="translational units"):
        squares().patch((-1e5, -1e5, 1e5, 1e5))
    with pytest.raises(GeometryError, match="empty"):
        squares().patch((1, 1, 0, 2))


def test_clockwise_outline_is_reoriented_and_labels_refused() -> None:
    cw = regular_polygon(4)[::-1]
    assert Prototile(cw).area > 0
    with pytest.raises(GeometryError, match="clockwise"):
        Prototile(cw, edge_labels=(1, 2, 3, 4))


def test_spec_round_trip() -> None:
    t = triangles()
    back = PeriodicTiling.from_spec(t.spec())
    region = (-2, -2, 2, 2)
    a, b = t.patch(region), back.patch(region)
    assert len(a) == len(b)
    assert np.allclose(np.sort(a.centres(), axis=0), np.sort(b.centres(), axis=0))


def test_patch_columns_concat_subset_and_bounds() -> None:
    p = squares().patch((0, 0, 3, 2))
    assert len(p) == 6 and p.bounds() == pytest.approx((0, 0, 3, 2))
    q = Patch.concat([p, p.transformed(Affine.translation(3, 0))])
    assert len(q) == 12 and q.validate((0, 0, 6, 2)).ok
    assert len(q.subset(q.centres()[:, 0] < 1)) == 2
    assert len(p.clip((0.5, 0.5, 1.5, 1.5))) == 4


def test_colouring_notation_base_is_read_from_the_permutations() -> None:
    """Figure 5.13 numbers colours from 1, Appendix A from 0; both parse to the same colouring."""
    assert Colouring.parse("(0 1 2 0)(1 2 0)(0 1 2)") == Colouring.parse("(1 2 3 1)(2 3 1)(1 2 3)")
    assert str(Colouring.parse("(0 1)(1 0)(0 1)")) == "(1 2)(2 1)(1 2)"


def test_covered_area_counts_each_tile_inside_the_region() -> None:
    """Unit squares over (0.5, 0.5)-(2.5, 1.5): the clipped areas sum to the region's area 2;
    a disc's covered area equals its area to the snap-rounding grid."""
    p = squares().patch((0, 0, 3, 2))
    assert p.covered_area((0.5, 0.5, 2.5, 1.5)) == pytest.approx(2.0)
    disc = shapely.Point(1.5, 1.0).buffer(0.8)
    assert p.covered_area(disc) == pytest.approx(disc.area, rel=1e-9)
    assert p.subset(slice(0, 0)).covered_area(disc) == 0.0


def _broken(patch: Patch, how: str, k: int) -> Patch:
    if how == "shift":  # tile k moved by 1e-4 of the tile size
        tr = patch.transform.copy()
        tr[k, 0, 2] += 1e-4 * math.sqrt(abs(patch.prototiles[int(patch.prototile[k])].area))
        return Patch(patch.prototiles, patch.prototile, tr, patch.colour, patch.aspect)
    if how == "duplicate":
        return Patch.concat([patch, patch.subset([k])])
    return patch.subset(np.r_[0:k, k + 1 : len(patch)])  # removed


@pytest.mark.parametrize("name", sorted(REGULAR))
def test_validate_finds_a_shifted_a_duplicated_and_a_removed_tile(name: str) -> None:
    region = (-6.1, -5.3, 5.7, 6.2)
    patch = REGULAR[name]().patch(region)
    assert patch.validate(region).ok
    centres = patch.centres()
    k = int(np.argmin(np.hypot(centres[:, 0], centres[:, 1])))  # a tile well inside the region
    area = abs(patch.prototiles[0].area)
    shifted = _broken(patch, "shift", k).validate(region)
    assert not shifted.ok and shifted.overlaps and all(k in (i, j) for i, j, _ in shifted.overlaps)
    assert all(0 < a < 1e-3 * area for _, _, a in shifted.overlaps)
    doubled = _broken(patch, "duplicate", k).validate(region)
    assert [(i, j) for i, j, _ in doubled.overlaps] == [(k, len(patch))]
    assert doubled.overlaps[0][2] == pytest.approx(area, rel=1e-9)
    removed = _broken(patch, "removed", k).validate(region)
    assert not removed.overlaps and removed.uncovered_area == pytest.approx(area, rel=1e-6)
    x0, y0, x1, y1 = removed.uncovered_bounds
    cx, cy = centres[k]
    assert x0 < cx < x1 and y0 < cy < y1


@pytest.mark.parametrize("system", ["hat", "spectre", "penrose-p3"])
def test_validate_on_non_convex_and_aperiodic_tiles(system: str) -> None:
    """Non-convex prototiles are cut into convex pieces; the three breakages are found."""
    from tilekit.plugins.substitution import tiling

    t = tiling(system)
    region = t.default_region()
    patch = t.patch(region)
    assert patch.validate(region).ok
    k = len(patch) // 2
    for how in ("shift", "duplicate"):
        report = _broken(patch, how, k).validate(region)
        assert not report.ok and report.overlaps and all(k in (i, j) for i, j, _ in report.overlaps[:1])
    disc = shapely.Point(*patch.centres()[k]).buffer(0.5 * math.sqrt(abs(patch.prototiles[0].area)))
    assert patch.validate(disc).ok
    removed = _broken(patch, "removed", k).validate(disc)
    assert not removed.ok and not removed.overlaps and removed.uncovered_area > 0.1 * disc.area


def test_validate_reports_overlaps_sorted_once_and_degenerate_tiles_as_invalid() -> None:
    sq = Prototile(regular_polygon(4))
    moves = np.array([Affine.translation(0.5, 0), np.eye(3), Affine.translation(0.5, 0.5),
                      np.diag([1.0, 0.0, 1.0]), Affine.translation(9, 9)])
    moves[4, 0, 2] = np.nan
    report = Patch([sq], [0] * 5, moves).validate()
    assert [(i, j) for i, j, _ in report.overlaps] == [(0, 1), (0, 2), (1, 2)]
    assert [a for _, _, a in report.overlaps] == pytest.approx([0.5, 0.5, 0.25])
    assert report.invalid_tiles == [3, 4]


def test_compiled_tile_bounds_equal_numpy(monkeypatch):
    """Large patches take their bounding boxes from one compiled pass (tilekit.kernels): the
    same boxes as the NumPy path (to rounding: the NumPy path maps many-cornered outlines by a
    batched matrix product) for straight and many-cornered (> 16) outlines mixed, with
    rotations, reflections and scalings."""
    import tilekit.tiling as tiling_module

    rng = np.random.default_rng(3)
    tri = Prototile(np.array([[0.0, 0.0], [1.0, 0.0], [0.3, 0.8]]))
    star = Prototile(regular_polygon(20))
    n = tiling_module._COMPILED_BOUNDS + 10
    ang = rng.uniform(0, 2 * np.pi, n)
    s = rng.uniform(0.5, 3.0, n) * rng.choice([-1.0, 1.0], n)
    t = np.zeros((n, 3, 3))
    t[:, 0, 0], t[:, 0, 1], t[:, 0, 2] = np.cos(ang) * s, -np.sin(ang), rng.uniform(-1e3, 1e3, n)
    t[:, 1, 0], t[:, 1, 1], t[:, 1, 2] = np.sin(ang) * s, np.cos(ang), rng.uniform(-1e3, 1e3, n)
    t[:, 2, 2] = 1.0
    patch = Patch([tri, star], rng.integers(0, 2, n), t)
    compiled = patch.tile_bounds()
    monkeypatch.setattr(tiling_module, "_COMPILED_BOUNDS", 10**12)
    assert np.allclose(compiled, patch.tile_bounds(), rtol=0, atol=1e-9)
