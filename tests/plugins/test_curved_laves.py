"""Laves tilings of the sphere and the hyperbolic plane (issue 35: the duals of the uniform
tilings; tilekit/plugins/curved/laves.py).

Facts checked: the 13 Catalan solids' face counts equal the Archimedean solids' vertex counts
and their vertex counts the Archimedean face counts (Cromwell, *Polyhedra*, 1997, ch. 2, the
table test_uniform.py holds: e.g. pentakis dodecahedron 60 faces, disdyakis triacontahedron
120, deltoidal hexecontahedron 60, rhombic triacontahedron 30), with Euler's formula; the
dual of the dual (the tiles meeting round each corner of the tile, counted on the patch, are
the uniform tiling's vertex configuration, and the tiles' corners are the uniform tiling's
face centres, their centres its vertices); no overlap and no gap (the geometry's validate);
the hyperbolic duals of the regular tilings have the regular tilings' layer counts (the
boundary automaton of layers.py, an independent construction); the incidence symbols agree
with the group (the symbol's own tile symmetries are the generator's stabiliser; mirrors make
every edge an I edge, §5.3.1); and one-line errors.
"""

from __future__ import annotations

import math
from collections import Counter
from fractions import Fraction

import numpy as np
import pytest
from cliutil import assert_one_line_error
from family_cli import family_cli
from test_uniform import ARCHIMEDEAN, assert_peak_within_bound, vertex_table

from tilekit.errors import ParameterError, ParseError
from tilekit.incidence import IncidenceSymbol
from tilekit.plugins.curved import (
    delaney,
    laves_configuration,
    laves_records,
    layers,
    notation,
    tilekit_normalise,
)
from tilekit.plugins.curved.laves import LavesTiling
from tilekit.plugins.curved.orbifold import construction_stabiliser
from tilekit.plugins.curved.patch import ModelPatch
from tilekit.plugins.curved.uniform import UniformTiling

# The Catalan solids by the Archimedean solid they are dual to (Cromwell, Polyhedra, ch. 2).
CATALAN = {
    "3.6.6": "triakis-tetrahedron", "3.4.3.4": "rhombic-dodecahedron", "3.8.8": "triakis-octahedron",
    "4.6.6": "tetrakis-hexahedron", "3.4.4.4": "deltoidal-icositetrahedron", "4.6.8": "disdyakis-dodecahedron",
    "3.3.3.3.4": "pentagonal-icositetrahedron", "3.5.3.5": "rhombic-triacontahedron",
    "3.10.10": "triakis-icosahedron", "5.6.6": "pentakis-dodecahedron", "3.4.5.4": "deltoidal-hexecontahedron",
    "4.6.10": "disdyakis-triacontahedron", "3.3.3.3.5": "pentagonal-hexecontahedron",
}
# The examples, as published: faces of four Catalan solids.
PUBLISHED_FACES = {"pentakis-dodecahedron": 60, "disdyakis-triacontahedron": 120, "deltoidal-hexecontahedron": 60,
                   "rhombic-triacontahedron": 30, "rhombic-dodecahedron": 12, "triakis-tetrahedron": 12}


@pytest.mark.parametrize("config", sorted(CATALAN))
def test_catalan_solids_faces_vertices_and_euler(config):
    faces_by_size, vertices = ARCHIMEDEAN[config]
    t = LavesTiling(config)
    patch = t.patch()
    k = len(config.split("."))
    assert t.faces == len(patch) == vertices  # a tile per vertex of the Archimedean solid
    published = PUBLISHED_FACES.get(CATALAN[config])
    assert published is None or published == t.faces
    table = vertex_table(patch)
    assert len(table) == sum(faces_by_size.values())  # a vertex per Archimedean face
    # a vertex of valence n per Archimedean n-gon, every tile a k-gon, angles 2π round it
    assert Counter(len(sizes) for _, sizes, _ in table) == Counter(faces_by_size)
    assert all(set(sizes) == {k} for _, sizes, _ in table)
    assert all(abs(total - 2 * math.pi) < 1e-9 for _, _, total in table)
    edges = t.faces * k // 2
    assert t.faces - edges + len(table) == 2  # Euler
    report = patch.validate()
    assert report.ok, report


@pytest.mark.parametrize("config", ["3.4.3.4", "4.6.10", "3.3.3.3.5", "4.4.7", "3.3.3.6"])
def test_dual_of_the_dual(config):
    """The tile's corners are the uniform tiling's face centres and its centres the uniform
    tiling's vertices; the valences round the tile read the vertex configuration."""
    t = LavesTiling(config)
    u = UniformTiling(config)
    lp, up = t.patch(), u.patch()
    corners = np.round(np.concatenate(lp.vertex_lists()), 7)
    assert {tuple(v) for v in corners} == {tuple(v) for v in np.round(up.model_centres(), 7)}
    uniform_vertices = np.round(np.concatenate(up.vertex_lists()), 7)
    assert {tuple(v) for v in np.round(lp.model_centres(), 7)} == {tuple(v) for v in uniform_vertices}
    assert notation.canonical(t.valences) == notation.canonical(notation.parse(config))
    # counted on the patch: the tiles at the central tile's corners, in order
    central = lp.vertex_lists()[0]
    at = Counter(tuple(v) for v in corners)
    assert notation.canonical(tuple(at[tuple(v)] for v in np.round(central, 7))) == t.symbol.configuration


@pytest.mark.parametrize("config, p, q", [("7.7.7", 3, 7), ("3.3.3.3.3.3.3", 7, 3), ("5.5.5.5", 4, 5)])
def test_hyperbolic_duals_of_regular_tilings_have_their_layer_counts(config, p, q):
    """[q^p]'s tiles are {p,q}'s: tiles per layer of edge neighbours round the centre tile
    equal the boundary automaton's (layers.layer_counts) while the patch holds the layer whole."""
    t = LavesTiling(config, radius=3.0)
    patch = t.patch()
    assert patch.validate().ok
    verts = patch.vertex_lists()
    index: dict[tuple, list[int]] = {}
    for i, face in enumerate(verts):
        ks = [tuple(np.round(v / v[2], 8)) for v in face]  # Klein coordinates of the corners
        for a, b in zip(ks, ks[1:] + ks[:1]):
            index.setdefault(tuple(sorted((a, b))), []).append(i)
    assert all(len(v) <= 2 for v in index.values())  # an edge has at most two tiles
    nbrs: dict[int, set[int]] = {i: set() for i in range(len(verts))}
    for tiles in index.values():
        if len(tiles) == 2:
            nbrs[tiles[0]].add(tiles[1])
            nbrs[tiles[1]].add(tiles[0])
    centre = int(np.argmin(patch.transform[:, 2, 2]))
    depth = {centre: 0}
    frontier = [centre]
    while frontier:
        nxt = []
        for i in frontier:
            for j in nbrs[i] - set(depth):
                depth[j] = depth[i] + 1
                nxt.append(j)
        frontier = nxt
    want = layers.layer_counts(p, q, 3)
    got = Counter(depth.values())
    assert [got[d] for d in range(3)] == want[:3]
    assert len(patch) >= sum(want[:3])


@pytest.mark.parametrize("config", ["4.6.14", "3.14.14", "3.4.7.4", "3.3.3.3.7", "4.8.10"])
def test_hyperbolic_laves_validate_and_vertex_angles(config):
    t = LavesTiling(config, radius=1.5)
    patch = t.patch()
    assert patch.validate().ok
    assert len(patch) <= t.estimate_tiles()
    # round the central tile's corners the tiles close up (angles 2π), as many as the configuration says
    central = int(np.argmin(patch.transform[:, 2, 2]))
    inner = {tuple(v) for v in np.round(patch.vertex_lists()[central], 7)}
    for v, _sizes, total in vertex_table(patch):
        if tuple(np.round(v, 7)) in inner:
            assert abs(total - 2 * math.pi) < 1e-9
    assert notation.canonical(t.valences) == t.symbol.configuration


@pytest.mark.parametrize("config", sorted(CATALAN) + ["4.6.14", "7.7.7", "3.7.3.7", "3.3.3.3.7"])
def test_incidence_symbol_agrees_with_the_group(config):
    t = LavesTiling(config)
    sym = t.incidence_symbol
    assert IncidenceSymbol.parse(str(sym)) == sym and len(sym) == len(t.corners)
    # the symbol's own tile symmetries are the generator's stabiliser in the group
    assert len(sym.tile_symmetries()) == len(t.stabiliser) == construction_stabiliser(t.symbol)
    if t.symbol.form != "snub":  # every dual edge lies on a mirror of the kaleidoscope (§5.3.1: I edges)
        assert set(sym.edge_kinds()) == {"I"}
    else:  # rotations only: no edge is reflected, and the half-turn axes make one S edge per tile
        assert sym.edge_kinds().count("S") == 1 and set(sym.edge_kinds()) == {"S", "J"}


@pytest.mark.parametrize("config, kinds", [("3.4.3.4", "JJJJ"), ("3.4.4.4", "JJJJ"), ("3.6.6", "JJS"),
                                           ("7.7.7", "SSS"), ("5.5.5.5", "SSSS")])
def test_rotation_group_makes_chiral_tiles(config, kinds):
    """Under the rotations the tiles are the same (the same patch, still one orbit) but nothing
    reflects an edge: only S and J edges, and the tile keeps its rotations only."""
    full, rot = LavesTiling(config), LavesTiling(config, group="rotations")
    sym = rot.incidence_symbol
    assert sorted(sym.edge_kinds()) == sorted(kinds)
    assert len(rot.stabiliser) == len(full.stabiliser) // 2
    assert all(not reflect for _, reflect in sym.tile_symmetries())
    if not full.hyperbolic:
        assert len(rot.patch()) == len(full.patch()) == full.faces
        assert rot.patch().validate().ok
    assert rot.properties()["symbol_group"] == full.properties()["symbol_group"].lstrip("*")
    assert rot.properties()["construction_group"] == full.properties()["construction_group"]  # Wythoff's *pqr


def test_records_names_and_spec_round_trip():
    recs = {r.name: r for r in laves_records()}
    for config, name in CATALAN.items():
        assert recs[name].properties["faces"] == ARCHIMEDEAN[config][1]
        assert recs[name].properties["dual_configuration"] == config
    assert recs["rhombic-dodecahedron-rotations"].properties["group"] == "rotations"
    assert {r.properties["geometry"] for r in recs.values()} == {"spherical", "hyperbolic"}
    assert "[4.6.14]" in recs and "V4.6.14" in recs["[4.6.14]"].aliases
    # every shipped full-group record's incidence symbol is under the tiling's whole group
    for r in recs.values():
        if r.properties["group"] == "full":
            assert r.properties["symbol_group"] == r.properties["symmetry_group"], r.name
    # an antiprism's dual: the construction gives the trapezohedron on 22n, the symbol is under 2*n
    trapezohedron = recs["pentagonal-trapezohedron"].properties
    assert (trapezohedron["construction_group"], trapezohedron["symmetry_group"], trapezohedron["symbol_group"]) \
        == ("522", "2*5", "2*5")
    assert recs["pentagonal-trapezohedron-rotations"].properties["symbol_group"] == "225"
    t = LavesTiling("[3.14.14]", radius=2.0, samples=3, group="rotations")
    again = LavesTiling.from_spec(t.spec())
    assert again.spec() == t.spec() and again.configuration == "3.14.14"
    assert laves_configuration("V4.3.4.3") == laves_configuration("[3.4.3.4]") == (3, 4, 3, 4)
    assert laves_configuration("3.4.3.4") is None
    # V names go to the bracket name both families use: the plane's stays the laves family's
    assert tilekit_normalise("name", "V4.3.4.6") == ("name", "[3.4.6.4]")
    assert tilekit_normalise("name", "V6.4.3.4") == ("name", "[3.4.6.4]")


@pytest.mark.parametrize("kwargs, needle", [
    ({"configuration": "3.4.5"}, "no uniform tiling by Wythoff's construction"),
    ({"configuration": "[3.4.6.4]"}, "tiles the Euclidean plane: see the laves family"),
    ({"configuration": "3.4.4.4", "geometry": "hyperbolic"}, "is spherical, not hyperbolic"),
    ({"symbol": "2 3 | 61"}, "r must be an integer 2..60"),
    ({"symbol": "2 3 | 1"}, "r must be an integer 2..60"),
    ({"configuration": "3.4.3.4", "group": "mirrors"}, "group must be one of full, rotations"),
    ({"configuration": "4.6.14", "group": "rotations"}, "has two tile orbits"),
    ({"configuration": "3.4.4.4", "radius": 2}, "radius applies to hyperbolic tilings"),
    ({"configuration": "4.6.14", "radius": 40}, "radius must be a number 0..12"),
    ({"configuration": "[3.x.3]"}, "cannot read"),
])
def test_bad_input_is_one_line(kwargs, needle):
    with pytest.raises((ParameterError, ParseError)) as err:
        LavesTiling(**kwargs)
    assert needle in str(err.value) and "\n" not in str(err.value)


def test_hyperbolic_has_no_face_count():
    with pytest.raises(ParameterError, match="infinitely many tiles"):
        _ = LavesTiling("4.6.14").faces


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "curved")


def test_cli_names_render_and_query(cli):
    r = cli("render", "[3.4.3.4]", "--geometry", "sphere", "-o", "rd.svg")
    assert r.exit_code == 0 and "(12 tiles)" in r.output, r.output
    r = cli("render", "V4.3.4.3", "-o", "rd2.svg")  # V notation, another rotation
    assert r.exit_code == 0 and "(12 tiles)" in r.output, r.output
    r = cli("render", "[4.6.14]", "--set", "radius=1.5", "-o", "h.svg")
    assert r.exit_code == 0, r.output
    r = cli("render", "pentakis-dodecahedron", "-o", "pd.svg")
    assert r.exit_code == 0 and "(60 tiles)" in r.output, r.output
    r = cli("list", "--family", "curved", "--where", "faces=12")
    assert r.exit_code == 0 and "rhombic-dodecahedron" in r.output and "triakis-tetrahedron" in r.output
    r = cli("list", "--family", "curved", "--where", "faces=120")
    assert "disdyakis-triacontahedron" in r.output


@pytest.mark.parametrize("args, needle", [
    (["[3.5.9]"], "no uniform tiling by Wythoff's construction has the vertex configuration 3.5.9"),
    (["V3.16.16"], "has no catalogue record"),
    (["[3.4.3.4]", "--geometry", "hyperbolic"], "is spherical, not hyperbolic"),
    (["[4.6.14]", "--set", "group=rotations"], "has two tile orbits"),
    (["[4.6.14]", "--set", "radius=12", "--max-tiles", "1000"], "over the limit"),
])
def test_cli_bad_input_is_one_line(cli, args, needle):
    assert_one_line_error(cli("render", *args, "-o", "x.svg"), needle)


@pytest.mark.parametrize("config", ["4.6.10", "4.6.8", "4.6.14"])
def test_validate_sees_a_mirrored_tile_twice(config):
    """The omnitruncations' duals place half their tiles by reflections (clockwise on the
    model): validate passes the patch, and finds the overlap when one of those is doubled or
    the gap when it is dropped."""
    patch = LavesTiling(config).patch()
    mirrored = np.flatnonzero(np.linalg.det(patch.transform) < 0)
    assert 2 * len(mirrored) == len(patch) and patch.validate().ok
    i = int(mirrored[0])
    doubled = ModelPatch(patch.prototiles, np.r_[patch.prototile, 0], np.concatenate([patch.transform,
                                                                                      patch.transform[i:i + 1]]))
    assert any(i in pair[:2] for pair in doubled.validate().overlaps)
    if not LavesTiling(config).hyperbolic:
        keep = np.arange(len(patch)) != i
        assert not patch.subset(keep).validate().ok


def test_bytes_per_tile_bounds_the_peak():
    for config, radius in (("4.6.14", 5.0), ("7.7.7", 5.5), ("5.5.5.5", 5.5), ("3.3.3.3.3.3.3", 6.0)):
        assert_peak_within_bound(LavesTiling(config, radius=radius))


def test_plane_names_stay_the_laves_familys(tmp_path, monkeypatch):
    """With the archimedean plugin loaded beside the curved one, [3.4.6.4], V3.4.6.4 and V4.3.4.6
    are the plane's Laves tiling (the laves family), [3.4.3.4] and V3.4.3.4 the sphere's."""
    cli = family_cli(tmp_path, monkeypatch, "archimedean,curved")
    for name in ("[3.4.6.4]", "V3.4.6.4", "V4.3.4.6"):
        r = cli("show", name)
        assert r.exit_code == 0 and "family: laves" in r.output and "name: [3.4.6.4]" in r.output, r.output
    for name in ("[3.4.3.4]", "V3.4.3.4", "[4.3.4.3]"):
        r = cli("show", name)
        assert r.exit_code == 0 and "name: rhombic-dodecahedron" in r.output, r.output


def test_the_viewers_rebasing_symmetries_keep_the_tiling():
    """The curved-space viewer rebases by the construction's cells (web.symmetries): each maps
    the Laves tiling's tile centres, and its tiles' corners, onto the tiling's own."""
    from tilekit.plugins.curved.web import symmetries, view_data

    t = LavesTiling("3.4.7.4", radius=3.0)
    data = view_data(LavesTiling("3.4.7.4"), 3000)
    assert set(data["sizes"]) == {4} and len(data["symmetries"]) % 9 == 0
    patch = t.patch()
    centres = patch.model_centres()
    corners = np.concatenate(patch.vertex_lists())
    near = centres[centres[:, 2] <= math.cosh(1.0)]
    near_corners = corners[corners[:, 2] <= math.cosh(1.0)]
    for g in symmetries(t, 1.0):
        for pts, pool in ((near, centres), (near_corners, corners)):
            moved = pts @ g.T
            gap = np.abs(moved[:, None, :] - pool[None, :, :]).max(axis=2).min(axis=1)
            assert gap.max() < 1e-7


# ------------------------------------------------------------------ the antiprisms' duals under 2*n


@pytest.mark.parametrize("n", range(4, 25))
def test_trapezohedra_under_their_full_group(n):
    """The dual of the antiprism 3.3.3.n is the n-gonal trapezohedron: 2n kites, 4n edges,
    2n + 2 vertices (Cromwell, *Polyhedra*, 1997, ch. 2). Its group is 2*n (D_nd, order 4n),
    which Wythoff's construction (| 2 2 n on 22n) does not give whole: the kites are taken under
    it, so the kite has its mirror (one reflection among its tile symmetries), the long edges
    lie on mirrors (I) and the short ones on half-turn axes (S), and 4n = faces × |tile symmetry|."""
    t = LavesTiling(f"3.3.3.{n}")
    props = t.properties()
    patch = t.patch()
    assert t.faces == len(patch) == props["faces"] == 2 * n
    table = vertex_table(patch)
    assert len(table) == props["vertices"] == 2 * n + 2
    assert Counter(len(sizes) for _, sizes, _ in table) == Counter({n: 2, 3: 2 * n})
    assert t.faces - 4 * n + len(table) == 2  # Euler
    assert patch.validate().ok
    assert props["symmetry_group"] == props["orbifold"] == props["symbol_group"] == f"2*{n}"
    assert props["construction_group"] == t.symbol.group and t.symbol.form == "snub"
    assert t.symmetry.group.order() == 4 * n == t.faces * props["tile_symmetry"]
    sym = t.incidence_symbol
    assert sorted(sym.edge_kinds()) == ["I", "I", "S", "S"]
    assert sorted(reflect for _, reflect in sym.tile_symmetries()) == [False, True]  # the kite's mirror
    # the kite: the two edges at the n-valent corner (I) are equal, as are the two others (S)
    k = t.valences.index(n)
    lengths = np.roll(t.edge_lengths, -k)
    assert abs(lengths[0] - lengths[3]) < 1e-12 and abs(lengths[1] - lengths[2]) < 1e-12
    assert [t.tile_symbol.label_kind(t.tile_symbol.edges[(k + i) % 4][0]) for i in range(4)] == list("ISSI")
    # the Delaney symbol on the kite's topology (corner valences n, 3, 3, 3) closes and reads 2*n
    assert t.symbol_orbifold() == f"2*{n}"
    assert delaney.euler_characteristic(t.delaney_symbol, t.valences) == Fraction(2, 4 * n)


@pytest.mark.parametrize("n", [4, 5, 6, 9])
def test_trapezohedron_group_as_matrices(n):
    """2*n = D_nd as O(3) matrices: 4n elements, closed under products; 2n rotations (22n, the
    construction's group), n mirrors (det −1, trace 1) and n rotary reflections, among them
    S_2n, the rotation by π/n followed by the reflection in the plane across its axis
    (trace 2cos(π/n) − 1), of order 2n."""
    t = LavesTiling(f"3.3.3.{n}")
    g = t.group_matrices()
    assert len(g) == 4 * n
    prod = np.matmul(g[:, None], g[None]).reshape(-1, 9)
    assert np.abs(prod[:, None, :] - g.reshape(1, -1, 9)).max(axis=2).min(axis=1).max() < 1e-9  # closed
    det, trace = np.linalg.det(g), np.trace(g, axis1=1, axis2=2)
    assert (det > 0).sum() == 2 * n
    assert ((det < 0) & (np.abs(trace - 1) < 1e-9)).sum() == n
    s2n = g[(det < 0) & (np.abs(trace - (2 * math.cos(math.pi / n) - 1)) < 1e-9)]
    assert len(s2n) == 2  # S_2n and its inverse
    powers = [np.linalg.matrix_power(s2n[0], k) for k in range(1, 2 * n + 1)]
    assert np.allclose(powers[-1], np.eye(3)) and not any(np.allclose(m, np.eye(3)) for m in powers[:-1])
    rot = LavesTiling(f"3.3.3.{n}", group="rotations").group_matrices()
    assert len(rot) == 2 * n and (np.linalg.det(rot) > 0).all()
    cube = LavesTiling("3.4.3.4").group_matrices()
    assert len(cube) == 48  # *432 (Conway, Burgiel, Goodman-Strauss)


@pytest.mark.parametrize("n", [4, 5, 11])
def test_trapezohedra_rotations_are_the_construction_group(n):
    """group=rotations is the rotation subgroup of 2*n, 22n (Wythoff's group for the snub):
    chiral kites, no tile symmetry, S and J edges, 2n = faces × 1."""
    full, rot = LavesTiling(f"3.3.3.{n}"), LavesTiling(f"3.3.3.{n}", group="rotations")
    props = rot.properties()
    assert props["symbol_group"] == rot.symbol_orbifold() == full.symmetry.group.rotations().notation
    assert full.symmetry.group.rotations().order() == 2 * n == rot.faces * props["tile_symmetry"]
    assert sorted(rot.incidence_symbol.edge_kinds()) == ["J", "J", "S", "S"]
    assert props["incidence_symbol"] == "[a+b+c+d+; a+b+d+c+]"
    assert rot.patch().validate().ok and len(rot.patch()) == 2 * n


def test_the_trigonal_trapezohedron_is_the_cube():
    """n = 3: the antiprism | 2 2 3 is the octahedron, so its dual is the cube, whose group *432
    (order 48 = 6 faces × 8 symmetries of the square) is larger than 2*3: taken under the
    tiling's whole group the tile is the square with all its symmetries, as [3.3.3.3] (4 | 2 3) gives."""
    t = LavesTiling(symbol="| 2 2 3")
    cube = LavesTiling("3.3.3.3")
    assert str(cube.symbol) == "4 | 2 3" and t.symbol.form == "snub"
    for x in (t, cube):
        props = x.properties()
        assert (props["faces"], props["vertices"], props["symmetry_group"]) == (6, 8, "*432")
        assert (props["incidence_symbol"], props["tile_symmetry"]) == ("[aaaa; a]", 8)
        assert x.symbol_orbifold() == "*432" and x.patch().validate().ok
    assert t.symmetry.index == 8  # 223 (order 6) in *432 (order 48)
    assert LavesTiling(symbol="| 2 2 3", group="rotations").properties()["symbol_group"] == "432"


def test_the_delaney_reading_agrees_with_the_geometry_on_every_record():
    """Independent readings of one group: the orbifold the geometry finds (orbifold.py, the
    tiling's symmetries) and the one the tile's incidence symbol gives on its topology
    (delaney.py, combinatorics only), on every shipped Laves record; on the sphere the
    group's order 2/χ is the faces times the tile's symmetries, and the number of its matrices."""
    for r in laves_records():
        t = LavesTiling(r.properties["dual_configuration"], group=r.properties["group"])
        assert t.symbol_orbifold() == r.properties["symbol_group"], r.name
        if not t.hyperbolic:
            chi = delaney.euler_characteristic(t.delaney_symbol, t.valences)
            assert 2 / chi == r.properties["faces"] * r.properties["tile_symmetry"] == len(t.group_matrices()), r.name


def test_delaney_refuses_a_symbol_that_does_not_fit_the_valences():
    """The kite's symbol tiles the topology with valences n, 3, 3, 3 at its corners in that
    order, not one whose n-valent corner sits where the mirror does not fix a corner."""
    kite = IncidenceSymbol.parse("[a+a-b+b-; a+b-]")
    assert delaney.orbifold_symbol(delaney.check_on(kite, 4, (3, 3, 3, 5)), (3, 3, 3, 5)) == "2*5"
    with pytest.raises(ParameterError) as err:
        delaney.check_on(kite, 4, (5, 3, 3, 3))
    assert "does not tile the 4-gon with corner valences 5.3.3.3" in str(err.value) and "\n" not in str(err.value)
    with pytest.raises(ParameterError, match="3 corner valences given for a 4-gon"):
        delaney.check_on(kite, 4, (3, 3, 5))


def test_shaped_trapezohedron_under_its_full_group():
    """Under 2*n the short edges are S edges and take shapes (the long ones stay straight on
    their mirrors); the kites still tile, and the least perfect colouring splits the top n
    kites from the bottom n (the half-turns swap them, the mirrors keep them)."""
    t = LavesTiling("3.3.3.6", edges={"a": "0.2,0.1:0.35,0.08"})
    assert sorted(t.edge_shapes) == ["a"] and t.incidence_symbol.edge_kinds() == "SSII"
    patch = t.patch()
    assert patch.validate().ok and len(patch) == 12
    assert Counter(patch.colour.tolist()) == Counter({0: 6, 1: 6})
    # each colour's six kites are those round one of the two 6-valent apices
    corners = [{tuple(v) for v in np.round(face, 7)} for face in patch.vertex_lists()]
    for colour in (0, 1):
        members = [c for c, k in zip(corners, patch.colour.tolist()) if k == colour]
        assert len(set.intersection(*members)) == 1
    with pytest.raises(ParameterError, match="its shaped edges are a"):
        LavesTiling("3.3.3.6", edges={"b": "0.2,0.1"})
