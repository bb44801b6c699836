"""Archimedean and Laves tilings (§4.1, §4.2): notation, construction, duals, symmetry, records."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit.errors import ParameterError, ParseError
from tilekit.geometry import signed_area
from tilekit.plugins import catalogue_records, families, get_family
from tilekit.plugins.archimedean import archimedean_tiling, laves_prototile, laves_tiling
from tilekit.plugins.archimedean.construct import (
    _match_polygon,
    cached_data,
    hand_of,
    transitivity,
    vertex_types_in,
)
from tilekit.regular.notation import VertexType, canonical, parse_vertex_type
from tilekit.symmetry import wallpaper_group

#: The 11 Archimedean tilings (Kaplan §4.1, Figure 4.2; Grünbaum & Shephard, Tilings and
#: Patterns, §2.1) with their wallpaper groups as published: G&S §2.1 / the Wythoff
#: construction tables give p6m for (3^6), (6^3), (3.6.3.6), (3.4.6.4), (3.12^2), (4.6.12),
#: p4m for (4^4), (4.8^2), p4g (4*2) for the snub square (3^2.4.3.4), p6 (632) for the snub
#: hexagonal (3^4.6) and cmm (2*22) for the elongated triangular (3^3.4^2) tiling.
PUBLISHED_GROUPS = {
    "3^6": "p6m", "4^4": "p4m", "6^3": "p6m", "3^4.6": "p6", "3^3.4^2": "cmm",
    "3^2.4.3.4": "p4g", "3.4.6.4": "p6m", "3.6.3.6": "p6m", "3.12^2": "p6m",
    "4.6.12": "p6m", "4.8^2": "p4m",
}
TYPES = list(PUBLISHED_GROUPS)
HANDS = [(t, h) for t in TYPES for h in (("l", "r") if t == "3^4.6" else ("",))]

REGIONS = [(-7.0, -7.0, 7.0, 7.0), (3.3, -12.1, 11.9, -1.7), (-20.5, 4.25, -9.0, 13.0)]


# ----------------------------------------------------------------------------- notation


@pytest.mark.parametrize(
    "text, name",
    [("3.3.3.3.6", "3^4.6"), ("3^4.6", "3^4.6"), ("(3^4.6)", "3^4.6"), ("[3^4.6]", "3^4.6"),
     ("6.3.3.3.3", "3^4.6"), ("4.4.4.4", "4^4"), ("(4^4)", "4^4"), ("4^4", "4^4"),
     ("3.4.3.3.4", "3^2.4.3.4"), ("4.4.3.3.3", "3^3.4^2"), ("12.3.12", "3.12^2"),
     ("8.4.8", "4.8^2"), ("3⁴.6", "3^4.6"), ("4.6.4.3", "3.4.6.4")],
)
def test_parse_spellings(text, name):
    """§4.1: types equal under cyclic shift and reversal; usual spellings all accepted."""
    assert str(parse_vertex_type(text)) == name


@pytest.mark.parametrize("bad", ["", "3..6", "3^0.6", "2.4.4", "3.x", "3.6", "(4^4", "3^4,,6"])
def test_bad_notation_is_a_one_line_parse_error(bad):
    with pytest.raises(ParseError) as err:
        parse_vertex_type(bad)
    assert "\n" not in str(err.value) and "vertex type" in str(err.value)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.integers(3, 20), min_size=3, max_size=6), st.integers(0, 5), st.booleans())
def test_canonical_form_is_invariant(seq, shift, reverse):
    """Canonical form is the same for every cyclic shift and reversal, and printing then
    parsing gives the same type back."""
    s = tuple(seq)
    other = s[shift % len(s):] + s[: shift % len(s)]
    if reverse:
        other = other[::-1]
    assert canonical(s) == canonical(other)
    vt = VertexType.of(s)
    assert parse_vertex_type(str(vt)) == vt
    assert parse_vertex_type(vt.dotted) == vt


def test_species_disregards_order():
    """Exercise 4.10: 3^2.4.3.4 and 3^3.4^2 are distinct types of one species."""
    a, b = parse_vertex_type("3^2.4.3.4"), parse_vertex_type("3^3.4^2")
    assert a != b and a.species == b.species == (3, 3, 3, 4, 4)


# ----------------------------------------------------------------------------- tilings


@pytest.mark.parametrize("name, hand", HANDS)
def test_archimedean_patches_are_valid_and_every_vertex_has_the_type(name, hand):
    """Every patch covers its region without overlap (Patch.validate) and every surrounded
    vertex has the declared type (the definition of an Archimedean tiling, §4.1)."""
    t = archimedean_tiling(name, hand)
    sizes = list(t.vertex_type.sizes)
    for region in REGIONS:
        patch = t.patch(region)
        report = patch.validate(region)
        assert report, report.summary()
    patch = t.patch((-9.0, -9.0, 9.0, 9.0))
    found = vertex_types_in(patch, sizes, 8.0)
    assert set(found) == {name}
    assert sum(found.values()) >= 20


@pytest.mark.parametrize("name, hand", HANDS)
def test_laves_patches_are_valid_monohedral_and_dual(name, hand):
    """§4.2: the dual is monohedral (every tile is the prototile moved by an isometry, so
    congruent to the first) and edge-to-edge; its tile round a vertex of type p1...pk has k
    corners, at which p1...pk tiles meet (its topological type [p1...pk])."""
    t = laves_tiling(name, hand)
    assert len(t.prototiles) == 1
    for region in REGIONS:
        report = t.patch(region).validate(region)
        assert report, report.summary()
    patch = t.patch((-8.0, -8.0, 8.0, 8.0))
    lin = patch.transform[:, :2, :2]
    gram = np.einsum("nji,njk->nik", lin, lin)
    assert np.allclose(gram, np.eye(2), atol=1e-9)
    polys = patch.polygons()
    ccw = [pts if signed_area(pts) > 0 else pts[::-1] for pts in polys]  # mirrored tiles run clockwise
    for pts in ccw:
        assert _match_polygon(ccw[0], pts) is not None
    # valence of each corner of the central tile = the polygon sizes round the vertex
    corners = np.concatenate(polys)
    central = int(np.argmin(np.hypot(*patch.centres().T)))
    valences = []
    for x, y in polys[central]:
        valences.append(int(np.sum(np.hypot(corners[:, 0] - x, corners[:, 1] - y) < 1e-6)))
    assert VertexType.of(valences) == parse_vertex_type(name)
    assert t.properties()["topology"] == f"[{name}]"


def test_laves_tilings_are_isohedral_and_archimedean_isogonal():
    """Archimedean tilings are vertex-transitive (isogonal, 'uniform', §4.1) and their duals
    are isohedral (§5.1 notes every Laves tiling is isohedral); the counts swap under
    duality: tiles orbits of one are the vertex orbits of the other."""
    for name in TYPES:
        a = transitivity(archimedean_tiling(name))
        lv = transitivity(laves_tiling(name))
        assert a["k_isogonal"] == 1 and lv["k_isohedral"] == 1
        assert a["k_isohedral"] == lv["k_isogonal"]


@pytest.mark.parametrize("name", TYPES)
def test_wallpaper_groups_match_the_published_ones(name):
    hands = ("l", "r") if name == "3^4.6" else ("",)
    for hand in hands:
        assert wallpaper_group(archimedean_tiling(name, hand)).iuc == PUBLISHED_GROUPS[name]
        assert wallpaper_group(laves_tiling(name, hand)).iuc == PUBLISHED_GROUPS[name]


def test_snub_hexagonal_hands_are_mirror_images():
    """(3^4.6) is chiral (Kaplan Figure 4.2): the two hands are mirror images, not related by
    a direct motion (their group p6 has no reflection); other types take no hand."""
    left, right = archimedean_tiling("3^4.6", "l"), archimedean_tiling("3^4.6", "r")
    assert hand_of((3, 6), left.unit_prototile, left.unit_transform, left.v1) == "l"
    assert hand_of((3, 6), right.unit_prototile, right.unit_transform, right.v1) == "r"
    assert not wallpaper_group(left).reflections
    with pytest.raises(ParseError, match="not chiral"):
        archimedean_tiling("4^4", "l")
    with pytest.raises(ParseError, match="hand"):
        archimedean_tiling("3^4.6", "x")


def test_tiles_per_unit_and_colours_by_size():
    """Tiles per primitive unit follow from counting: e.g. (4.6.12) has 1 dodecagon, 2
    hexagons and 3 squares per unit (12 vertices, each in one of each); (3^4.6) has 1
    hexagon and 8 triangles; (3^6) 2 triangles. Tiles are coloured by their number of sides."""
    expect = {"4.6.12": {12: 1, 6: 2, 4: 3}, "3^4.6": {6: 1, 3: 8}, "3^6": {3: 2},
              "3.12^2": {12: 1, 3: 2}, "4.8^2": {8: 1, 4: 1}, "3^2.4.3.4": {3: 4, 4: 2}}
    for name, counts in expect.items():
        t = archimedean_tiling(name)
        sizes = [t.vertex_type.sizes[p] for p in t.unit_prototile]
        assert {s: sizes.count(s) for s in set(sizes)} == counts
        unit = t.unit()
        by_size: dict[int, set[int]] = {}
        for s, c in zip(sizes, unit.colour):
            by_size.setdefault(s, set()).add(int(c))
        assert all(len(c) == 1 for c in by_size.values())
        assert len({next(iter(c)) for c in by_size.values()}) == len(by_size)


def test_cairo_pentagon():
    """Exercise 4.12: the Laves tiling [3^2.4.3.4] is the Cairo tiling; its pentagon has
    angles 120°, 120°, 90°, 120°, 90° and four equal long edges and one shorter edge."""
    proto = laves_prototile("3^2.4.3.4")
    pts = proto.outline
    assert len(pts) == 5
    nxt, prv = np.roll(pts, -1, axis=0) - pts, np.roll(pts, 1, axis=0) - pts
    ang = np.degrees(np.arccos(np.sum(nxt * prv, axis=1) / np.hypot(*nxt.T) / np.hypot(*prv.T)))
    assert sorted(np.round(ang, 6)) == [90.0, 90.0, 120.0, 120.0, 120.0]
    edges = np.sort(np.hypot(*nxt.T))
    assert np.allclose(edges[1:], edges[-1]) and edges[0] < edges[1] - 1e-3


def test_non_plane_types_are_rejected():
    with pytest.raises(ParseError, match="spherical"):
        archimedean_tiling("3^5")
    with pytest.raises(ParseError, match="hyperbolic"):
        laves_tiling("7^3")


def test_shipped_data_is_what_the_construction_gives():
    """catalogue/archimedean/tilings.json is a cache: regenerating it from the vertex types
    (builder, lattice detection, duals, symmetry) gives the same units, lattices and facts."""
    from tilekit.plugins.archimedean.generate import generate

    fresh = generate()
    shipped = cached_data()
    assert set(fresh["archimedean"]) == set(shipped["archimedean"]) == set(TYPES)
    for key, value in fresh["archimedean"].items():
        old = shipped["archimedean"][key]
        assert [p for p, _ in value["unit"]] == [p for p, _ in old["unit"]]
        assert np.allclose([r for _, r in value["unit"]], [r for _, r in old["unit"]], atol=1e-9)
        assert np.allclose(value["v1"], old["v1"], atol=1e-9) and np.allclose(value["v2"], old["v2"], atol=1e-9)
    assert set(fresh["laves"]) == set(shipped["laves"])
    for key, value in fresh["laves"].items():
        assert np.allclose(value["unit"], shipped["laves"][key]["unit"], atol=1e-9)
        assert np.allclose(value["outline"], shipped["laves"][key]["outline"], atol=1e-9)
    assert fresh["symmetry"] == shipped["symmetry"]


def test_rebuild_equals_cached():
    """archimedean_tiling(..., rebuild=True) constructs afresh and agrees with the data."""
    a = archimedean_tiling("3.4.6.4", rebuild=True)
    b = archimedean_tiling("3.4.6.4")
    assert np.allclose(a.unit_transform, b.unit_transform, atol=1e-9)
    assert np.allclose(a.v1, b.v1) and np.allclose(a.v2, b.v2)


# ----------------------------------------------------------------------------- plugin


def test_families_and_records():
    """Two families; 12 Archimedean records (11 tilings, 3^4.6 in both hands) and 12 Laves;
    every record round-trips through its family's from_spec and carries the properties."""
    fams = families()
    assert {"archimedean", "laves"} <= set(fams)
    recs = [r for r in catalogue_records() if r.family in ("archimedean", "laves")]
    arch = [r for r in recs if r.family == "archimedean"]
    lav = [r for r in recs if r.family == "laves"]
    assert len(arch) == 12 and len(lav) == 12
    assert len({r.properties["vertex_type"] for r in arch}) == 11
    names = {r.name for r in recs} | {a for r in recs for a in r.aliases}
    assert len(names) == sum(1 + len(r.aliases) for r in recs)  # no clashes
    for r in recs:
        p = r.properties
        for key in ("vertex_type", "species", "tiles_per_unit", "symmetry_group", "chiral", "dual",
                    "periodic", "k_hedral", "k_isohedral", "edge_to_edge"):
            assert key in p, (r.name, key)
        assert p["wallpaper_group"] == PUBLISHED_GROUPS[p["vertex_type"]]
        tiling = get_family(r.family).from_spec(r.spec)
        assert tiling.name == r.name
        assert len(tiling.unit_prototile) == p["tiles_per_unit"]
    lv = {r.name: r for r in lav}
    assert lv["[3^6]"].properties["topology"] == "[3^6]" and lv["[3^6]"].properties["k_hedral"] == 1
    by_name = {r.name: r for r in arch}
    assert "4.4.4.4" in by_name["4^4"].aliases and "(4^4)" in by_name["4^4"].aliases
    assert "3^4.6" in by_name["3^4.6l"].aliases


def test_describe():
    text = archimedean_tiling("4.6.12").describe()
    assert "3 4-gons, 2 6-gons, 1 12-gon" in text and "[4.6.12]" in text
    assert "5 corners" in laves_tiling("3^2.4.3.4").describe()


def test_configure_rejects_options():
    with pytest.raises(ParameterError):
        archimedean_tiling("4^4").configure(params=[1.0])


def test_patch_cost_is_vectorised():
    """A large region is rasterised by the core (§3.4), quickly."""
    import time

    t = archimedean_tiling("4.6.12")
    start = time.perf_counter()
    patch = t.patch((-150.0, -150.0, 150.0, 150.0))
    assert len(patch) > 20_000
    assert time.perf_counter() - start < 5.0
    assert math.isfinite(float(patch.transform.sum()))


def test_exercise_4_12_cairo_coordinates():
    """Exercise 4.12: with the edge joining the two 3-valent corners (the two adjacent 120°
    corners) from (-1/2, 0) to (1/2, 0), the Cairo tile's other corners are
    (±(3+√3)/4, (3+√3)/4) and (0, 1+√3/2): the long edges have length (1+√3)/2 and leave the
    base at 60° (regular 3-valent corners), meeting the 90° corners (regular 4-valent)."""
    from tilekit.geometry import Affine

    pts = laves_prototile("3^2.4.3.4").outline
    k = len(pts)
    nxt, prv = np.roll(pts, -1, axis=0) - pts, np.roll(pts, 1, axis=0) - pts
    ang = np.degrees(np.arccos(np.sum(nxt * prv, axis=1) / np.hypot(*nxt.T) / np.hypot(*prv.T)))
    (i,) = [i for i in range(k) if abs(ang[i] - 120) < 1e-6 and abs(ang[(i + 1) % k] - 120) < 1e-6]
    m = Affine.segment_map((-0.5, 0.0), (0.5, 0.0), pts[i], pts[(i + 1) % k])  # similarity
    placed = Affine.apply(m, np.roll(pts, -i, axis=0))
    s3 = math.sqrt(3)
    expect = [(-0.5, 0), (0.5, 0), ((3 + s3) / 4, (3 + s3) / 4), (0, 1 + s3 / 2), (-(3 + s3) / 4, (3 + s3) / 4)]
    assert np.allclose(placed, expect, atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(
    st.sampled_from(HANDS),
    st.booleans(),
    st.floats(-60, 60),
    st.floats(-60, 60),
    st.floats(0.5, 10),
    st.floats(0.5, 10),
)
def test_random_regions_are_covered(name_hand, dual, cx, cy, w, h):
    """Any box, anywhere: the Archimedean or Laves patch covers it without overlap."""
    name, hand = name_hand
    t = laves_tiling(name, hand) if dual else archimedean_tiling(name, hand)
    region = (cx - w, cy - h, cx + w, cy + h)
    report = t.patch(region).validate(region)
    assert report, report.summary()
