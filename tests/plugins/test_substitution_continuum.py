"""The hat's continuum Tile(a, b), supertile overlays and tile tables (issue 26, hatviz #7).

Source: D. Smith, J. S. Myers, C. S. Kaplan, C. Goodman-Strauss, "An aperiodic monotile",
arXiv:2303.10798 (2023), the section on Tile(a, b): Tile(a, b) keeps the hat's edge directions and gives its edges
along the lattice directions length a and the others length b; the hat is Tile(1, sqrt3), the
turtle Tile(sqrt3, 1) (10 kites), the chevron Tile(0, 1), the comet Tile(1, 0); hat tilings
deform edge by edge into combinatorially equivalent Tile(a, b) tilings. Tile(1, 1) is the
Spectre's polygon ("A chiral aperiodic monotile", arXiv:2305.17743).
"""

from __future__ import annotations

import csv
import dataclasses
import itertools
import json
import math

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from cliutil import assert_one_line_error
from test_substitution import assert_valid

from tilekit import export
from tilekit.errors import ParameterError, ParseError
from tilekit.geometry import Affine
from tilekit.plugins.substitution import builtin_systems, from_spec, tiling
from tilekit.plugins.substitution.continuum import (
    HatLifts,
    continuum_system,
    edge_classes,
    lifts_of,
    members,
)
from tilekit.plugins.substitution.hat import LATTICE, hat_system_from_data
from tilekit.plugins.substitution.shapes import complement, spectre_edge
from tilekit.plugins.substitution.tiling import match_placements
from tilekit.polygon import congruences, signed_area
from tilekit.tiling import Patch, PeriodicTiling

SQRT3 = math.sqrt(3)
KITE = SQRT3  # the kite of the hat's scale: sides 1, 1, sqrt3, sqrt3

#: Tile(a, b) with a, b > 0 and a != b, besides the named members
GENERIC = [(1.0, 2.0), (2.0, 1.0), (1.0, 0.3), (0.4, 1.0), (3.0, 0.5)]


def hat():
    return builtin_systems()["hat"]


def tile_of(a: float, b: float) -> np.ndarray:
    return continuum_system(hat(), a, b).tile.outline


def whole(a: float, b: float, depth: int, label: int = 0) -> Patch:
    """The level-``depth`` supertile of label ``label`` of Tile(a, b) (the hat itself at
    (1, sqrt3) through the same deformed hierarchy)."""
    s = continuum_system(hat(), a, b)
    proto, transform, colour = s.generate(depth, seed_label=label)
    return Patch(s.tiles, proto, transform, colour)


# ------------------------------------------------------------------ the shape


def test_edges_keep_their_directions_and_take_lengths_a_and_b() -> None:
    """arXiv:2303.10798: Tile(a, b) has the hat's 14 edges (the edge of length 2 as two), 8 of length a
    along the lattice directions and 6 of length b between them, in the hat's directions."""
    hat_pts = hat().tile.outline
    hat_edges = np.roll(hat_pts, -1, axis=0) - hat_pts
    hat_dirs = hat_edges / np.linalg.norm(hat_edges, axis=1)[:, None]
    lattice = np.rint(np.linalg.solve(LATTICE, hat_edges.T).T).astype(int)
    along, between = edge_classes(lattice)
    units = np.where(along, np.round(np.linalg.norm(hat_edges, axis=1)), np.round(np.linalg.norm(hat_edges, axis=1) / SQRT3))
    assert int(units[along].sum()) == 8 and int(units[between].sum()) == 6
    for a, b in [(1.0, SQRT3), (SQRT3, 1.0), *GENERIC]:
        pts = tile_of(a, b)
        edges = np.roll(pts, -1, axis=0) - pts
        assert len(pts) == 13
        lengths = np.linalg.norm(edges, axis=1)
        assert np.allclose(lengths, np.where(along, a, b) * units)
        assert np.allclose(edges / lengths[:, None], hat_dirs)


def test_hat_turtle_and_ends_of_the_continuum() -> None:
    """The hat is Tile(1, sqrt3) itself; Tile(0, 1) and Tile(1, 0) lose the edges of length
    0 (6 and 7 corners left); the hat and the turtle are 8 and 10 kites (arXiv:2303.10798)."""
    hat_tile = hat().tile.outline
    assert len(congruences(tile_of(1.0, SQRT3), hat_tile, 1e-9))
    assert abs(signed_area(tile_of(1.0, SQRT3))) == pytest.approx(8 * KITE)
    assert abs(signed_area(tile_of(SQRT3, 1.0))) == pytest.approx(10 * KITE)
    assert len(tile_of(0.0, 1.0)) == 6 and len(tile_of(1.0, 0.0)) == 7
    m = members(hat())
    assert {k: (v.a, v.b) for k, v in m.items()} == {"hat": (1, SQRT3), "turtle": (SQRT3, 1), "chevron": (0, 1),
                                                      "comet": (1, 0)}


def test_tile_1_1_is_the_spectres_polygon() -> None:
    """Tile(1, 1) is congruent to the Spectre's polygon as shipped in spectre.toml (the
    chiral paper's coordinates, independent data; there its edge of length 2 is two unit
    edges, so the collinear corner is dropped before comparing)."""
    spectre = np.asarray(shapely.Polygon(builtin_systems()["spectre"].tile.outline).simplify(0).exterior.coords)[:-1]
    assert len(spectre) == 13
    assert len(congruences(tile_of(1.0, 1.0), spectre, 1e-9))


def test_area_is_the_quadratic_form_fixed_by_hat_turtle_and_spectre() -> None:
    """Edges scale linearly with (a, b), so the area is a quadratic form alpha a^2 + beta ab
    + gamma b^2; the hat (8 kites), the turtle (10 kites) and the Spectre's polygon fix it
    (alpha = 2 sqrt3, beta = 3, gamma = sqrt3), and every Tile(a, b) of a generated patch has
    that area."""
    spectre = abs(signed_area(builtin_systems()["spectre"].tile.outline))
    rows = np.array([[1, SQRT3, 3], [3, SQRT3, 1], [1, 1, 1]], dtype=float)
    alpha, beta, gamma = np.linalg.solve(rows, [8 * KITE, 10 * KITE, spectre])
    assert (alpha, beta, gamma) == pytest.approx((2 * SQRT3, 3, SQRT3))
    for a, b in [*GENERIC, (0.0, 1.0), (1.0, 0.0)]:
        patch = whole(a, b, 2)
        areas = shapely.area(patch.geometries())
        assert np.allclose(areas, alpha * a * a + beta * a * b + gamma * b * b)


# ------------------------------------------------------------------ the lift


def test_every_vertex_of_a_hat_patch_has_one_lift() -> None:
    """The lift (sums of each class's edge steps) is path-independent on a hat tiling: the
    hats of a level-4 supertile, lifted through the hierarchy, give every shared vertex the
    same lift from every hat at it, and the lifts' sums are the vertices' positions."""
    lifts = HatLifts(hat())
    big = (-1e9, -1e9, 1e9, 1e9)
    eye = np.eye(3, dtype=np.int64)[None]
    zero = eye.copy()
    U, V = lifts.generate(np.array([0]), eye, zero, 4, big)
    pos, u = lifts.vertices(U, V)
    assert len(U) == hat().tile_counts(4)[-1]
    order = np.lexsort((pos[:, 1], pos[:, 0]))
    p, uu = pos[order], u[order]
    same = np.all(p[1:] == p[:-1], axis=1)
    assert same.sum() > len(U)  # most vertices are shared
    assert np.array_equal(uu[1:][same], uu[:-1][same])
    # the positions are those of the hat patch itself
    _, tr, _ = hat().generate(4)
    hat_vertices = Affine.apply(tr, hat().tile.outline).reshape(-1, 2)
    lifted = pos @ LATTICE.T
    assert np.allclose(np.sort(lifted[:, 0]), np.sort(hat_vertices[:, 0]))


def test_bad_data_is_a_one_line_parse_error() -> None:
    """Hats that cannot be lifted together (a metatile whose two hats share no vertex) are
    refused naming the file and the metatile; a continuum member with a bad value too."""
    base = [b.copy() for b in hat().base]
    base[2][1, :2, 2] += [40, 0]  # P's second hat far away (the hats do not overlap)
    far = dataclasses.replace(hat(), base=base, source="far.toml", lifted=None, _levels=[], _bounds=[])
    with pytest.raises(ParseError, match=r"far.toml: \[metatiles.P\] hats do not form one patch"):
        lifts_of(far)
    data = dict(hat().data)
    cont = dict(data["continuum"])
    cont["members"] = {**cont["members"], "bad": {"a": "-1", "b": "1"}}
    s = hat_system_from_data({**data, "continuum": cont}, "bad.toml")
    with pytest.raises(ParseError, match=r"bad.toml: \[continuum.members.bad\]: .*out of range"):
        members(s)
    cont["members"] = {"bad": {"a": "sqrt(", "b": "1"}}
    with pytest.raises(ParseError, match="bad.toml"):
        members(hat_system_from_data({**data, "continuum": cont}, "bad.toml"))


# ------------------------------------------------------------------ the tilings


@pytest.mark.parametrize("shape", ["hat", "turtle", "chevron", "comet", "spectre"])
def test_every_named_member_tiles_a_region(shape: str) -> None:
    """Patch.validate (no overlap, no gap) on a region away from the origin, for each member
    (the spectre through its own system, Tile(1, 1) without reflections)."""
    t = tiling("hat").configure(shape=shape)
    size = math.sqrt(abs(t.prototiles[0].area))
    region = (40 * size, -25 * size, 52 * size, -13 * size)
    patch = t.patch(region)
    assert_valid(patch, region)
    if shape == "spectre":
        assert np.all(np.linalg.det(patch.transform[:, :2, :2]) > 0)


@pytest.mark.parametrize(("a", "b"), GENERIC)
def test_generic_members_tile_regions_and_deep_supertiles(a: float, b: float) -> None:
    """Tile(a, b) for a, b > 0, a != b: a region near the origin and the corner of a level-8
    supertile (lifts of eight levels, culled generation) both validate."""
    t = tiling("hat", a=a, b=b)
    assert_valid(t.patch((-20, -20, 20, 20)), (-20, -20, 20, 20))
    deep = t.configure(depth=8)
    x0, y0, x1, y1 = deep.default_region().bounds
    cx, cy = x0 + 0.3 * (x1 - x0), y0 + 0.5 * (y1 - y0)
    region = (cx - 15, cy - 15, cx + 15, cy + 15)
    patch = deep.patch(region)
    assert len(patch) > 20
    assert_valid(patch, region)


@pytest.mark.parametrize(("a", "b"), [(SQRT3, 1.0), *GENERIC])
def test_combinatorially_equivalent_to_the_hat_tiling(a: float, b: float) -> None:
    """arXiv:2303.10798: the Tile(a, b) tiling is the hat tiling deformed edge by edge: the same tiles (in
    the same order, with the same colours and orientations) share the same edges."""
    hat_patch, other = whole(1.0, SQRT3, 3, 2), whole(a, b, 3, 2)
    assert len(hat_patch) == len(other) == hat().tile_counts(3, 2)[-1]
    assert np.array_equal(hat_patch.colour, other.colour)
    assert np.allclose(hat_patch.transform[:, :2, :2], other.transform[:, :2, :2])
    ha, oa = hat_patch.adjacency(), other.adjacency()
    assert len(ha.edge) > len(hat_patch)
    assert np.array_equal(ha.edge, oa.edge)
    assert np.array_equal(ha.vertex, oa.vertex)


def test_ends_of_the_continuum_keep_the_pairs_that_share_an_edge_that_stays() -> None:
    """At the chevron (a = 0) and the comet (b = 0) one edge class has length 0: two tiles
    still share an edge exactly when their hats share a segment of the other class (read off
    the hat patch's shared segments by direction), and every pair of hats that touched still
    touches."""
    hat_patch = whole(1.0, SQRT3, 3)
    e = export.tile_edges(hat_patch)
    o = e.order
    k, tiles = e.key[o], e.tile[o]
    pair = k[1:] == k[:-1]
    seg = o[1:][pair]
    d = e.points[e.v[seg]] - e.points[e.u[seg]]
    turn = np.round(np.degrees(np.arctan2(d[:, 1], d[:, 0])) / 30).astype(int) % 2  # 0: class 1, 1: class 2
    lo, hi = np.minimum(tiles[:-1][pair], tiles[1:][pair]), np.maximum(tiles[:-1][pair], tiles[1:][pair])
    ha = hat_patch.adjacency()
    for (a, b), kept_class in [((0.0, 1.0), 1), ((1.0, 0.0), 0)]:
        oa = whole(a, b, 3).adjacency()
        expect = {(int(x), int(y)) for x, y, c in zip(lo, hi, turn) if c == kept_class}
        assert {tuple(p) for p in oa.edge.tolist()} == expect
        assert {tuple(p) for p in ha.touching.tolist()} <= {tuple(p) for p in oa.touching.tolist()}


@pytest.mark.parametrize("shape", ["chevron", "comet"])
def test_ends_of_the_continuum_tile_periodically(shape: str) -> None:
    """arXiv:2303.10798: the chevron and the comet are no aperiodic monotiles; each even tiles by
    translations alone: a lattice of two sums of its vertex differences whose cell has the
    tile's area, checked with Patch.validate on a region, is found by a small search."""
    tile = tiling("hat", shape=shape).prototiles[0]
    pts = tile.outline
    diffs = {tuple(np.round(p - q, 9)) for p in pts for q in pts if not np.allclose(p, q)}
    sums = {tuple(np.round(np.add(d, e), 9)) for d in diffs for e in diffs} | diffs
    vectors = sorted((v for v in sums if np.hypot(*v) > 1e-9), key=lambda v: (np.hypot(*v), v))
    region = (-6, -6, 6, 6)
    for v1, v2 in itertools.combinations(vectors, 2):
        if abs(abs(v1[0] * v2[1] - v1[1] * v2[0]) - abs(tile.area)) < 1e-9:
            periodic = PeriodicTiling([tile], [0], np.eye(3)[None], v1, v2)
            if periodic.patch(region).validate(region):
                break
    else:
        pytest.fail(f"no lattice tiling of the {shape} found")
    assert tiling("hat", shape=shape).properties()["aperiodic"] is False
    assert tiling("hat", shape="turtle").properties()["aperiodic"] is True


def test_hat_member_is_the_hat_system_and_spectre_is_the_spectre() -> None:
    t = tiling("hat")
    assert t.configure(shape="hat").system is hat()
    assert t.configure(a=1, b="sqrt3").system is hat()
    s = t.configure(a=1, b=1, depth=2)
    assert s.system is builtin_systems()["spectre"] and s.spec() == {"system": "spectre", "depth": 2}
    assert t.configure(shape="spectre").system is builtin_systems()["spectre"]


def test_spec_round_trips() -> None:
    for t in [tiling("hat", shape="turtle", depth=2), tiling("hat", a=1, b=2, overlay="0,1"),
              tiling("spectre", curved=0.15, overlay=1)]:
        back = from_spec(t.spec())
        assert back.spec() == t.spec()
        region = t.default_region()
        assert np.allclose(back.patch(region).transform, t.patch(region).transform)
    assert tiling("hat", shape="turtle").spec() == {"system": "hat", "shape": "turtle"}


@pytest.mark.parametrize(("options", "fragment"), [
    ({"a": 1}, "needs both a and b"),
    ({"a": -1, "b": 1}, "out of range"),
    ({"a": 1, "b": 1e6}, "out of range"),
    ({"a": 0, "b": 0}, "Tile(0, 0) is a point"),
    ({"a": 2, "b": 2}, "Spectre's polygon"),
    ({"a": "nan", "b": 1}, "is not a number or an expression"),
    ({"shape": "tortoise"}, "valid: hat, turtle, chevron, comet, spectre"),
    ({"shape": "turtle", "b": 1}, "not both"),
    ({"overlay": "99"}, "levels 0..15"),
    ({"overlay": "x"}, "levels 0..15"),
    ({"curved": 1}, "without reflected tiles"),
    ({"size": 3}, "valid: depth, seed, overlay, a, b, shape"),
])
def test_bad_options_are_parameter_errors(options, fragment) -> None:
    with pytest.raises(ParameterError, match=None) as err:
        tiling("hat").configure(**options)
    assert fragment in str(err.value) and "\n" not in str(err.value)


# ------------------------------------------------------------------ labels, table, overlay


def test_labels_are_the_metatiles_of_the_substitution() -> None:
    """Each tile's level-0 supertile is its metatile: H tiles are colours 0 and 1, T 2, P 3,
    F 4, and a level-3 supertile of label j has 4, 1, 2, 2 tiles per metatile counted by the
    substitution matrix, M^3 e_j (arXiv:2303.10798, the metatile substitution)."""
    for t in [tiling("hat", depth=3, seed="P"), tiling("hat", depth=3, seed="P", shape="turtle")]:
        patch = t.patch()
        labels = t.tile_labels(patch)
        expect = np.array(["H", "H", "T", "P", "F"], dtype=object)[patch.colour]
        assert np.array_equal(labels, expect)
        counts = hat().counts(3, start=2)[-1]
        assert [int((labels == x).sum()) for x in "HTPF"] == [4 * counts[0], counts[1], 2 * counts[2], 2 * counts[3]]


def test_spectre_labels_and_supertiles() -> None:
    """The spectre's level-0 supertiles: each Gamma (the Mystic) holds two tiles, every other
    label one; the level-1 supertiles of a level-2 Delta are 8 (Delta's rule has 8 slots)."""
    t = tiling("spectre", depth=2)
    patch = t.patch()
    group, label = t.supertiles(patch, None, 0)
    names = np.array(builtin_systems()["spectre"].labels)[label]
    sizes = np.bincount(group)
    assert np.all(sizes[group][names == "Gamma"] == 2) and np.all(sizes[group][names != "Gamma"] == 1)
    assert len(np.unique(t.supertiles(patch, None, 1)[0])) == 8


def test_neighbour_table_matches_shapely() -> None:
    """The tile table's edge neighbours are exactly the pairs of tiles whose boundaries share
    a segment of positive length, found independently with shapely on a small patch of each
    shape (hat, turtle, a generic member)."""
    for t in [tiling("hat"), tiling("hat", shape="turtle"), tiling("hat", a=1, b=0.5)]:
        patch = t.patch((-10, -10, 10, 10))
        labels = t.tile_labels(patch, (-10, -10, 10, 10))
        assert set(labels) == {"H", "T", "P", "F"}  # every tile of the region patch found again
        table = patch.tile_table(labels)
        g = shapely.set_precision(patch.geometries(), 1e-9)
        tree = shapely.STRtree(g)
        i, j = tree.query(g, predicate="intersects")
        keep = i < j
        i, j = i[keep], j[keep]
        shared = shapely.length(shapely.intersection(shapely.boundary(g[i]), shapely.boundary(g[j])))
        oracle = {(int(x), int(y)) for x, y, s in zip(i, j, shared) if s > 1e-6}
        found = {(t_, int(n)) for t_ in range(len(table)) for n in table.neighbours(t_) if t_ < n}
        assert found == oracle
        assert np.allclose(table.centre, [np.asarray(p.centroid.coords[0]) for p in g], atol=1e-7)
        # the angle and reflection rebuild the placements' linear parts
        th = np.radians(table.angle)
        rot = np.stack([np.stack([np.cos(th), -np.sin(th)], -1), np.stack([np.sin(th), np.cos(th)], -1)], -2)
        flip = np.where(table.reflected[:, None, None], np.diag([1.0, -1.0]), np.eye(2))
        assert np.allclose(rot @ flip, patch.transform[:, :2, :2])


def test_csv_and_json_tables_read_back(tmp_path) -> None:
    t = tiling("hat", depth=2)
    patch = t.patch()
    labels = t.tile_labels(patch)
    table = patch.tile_table(labels)
    export.write_patch(patch, tmp_path / "t.csv", labels=labels)
    export.write_patch(patch, tmp_path / "t.json", labels=labels)
    with open(tmp_path / "t.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(patch) == 169
    for k, row in enumerate(rows):
        assert int(row["index"]) == k and row["label"] == labels[k]
        assert [int(x) for x in row["neighbours"].split()] == table.neighbours(k).tolist()
        assert float(row["angle"]) == pytest.approx(table.angle[k])
        assert bool(int(row["reflected"])) == table.reflected[k]
        assert (float(row["x"]), float(row["y"])) == pytest.approx(tuple(table.centre[k]))
    tiles = json.loads((tmp_path / "t.json").read_text())["tiles"]
    assert [x["label"] for x in tiles] == labels.tolist()
    assert [x["neighbours"] for x in tiles] == [table.neighbours(k).tolist() for k in range(len(table))]
    assert sum(x["reflected"] for x in tiles) == int(table.reflected.sum()) == hat().counts(2)[-1][0]


def test_overlay_is_the_union_boundary_of_each_supertile() -> None:
    """The overlay's lines between level-L supertiles have the length of the supertiles'
    boundaries inside the patch, computed independently as shapely unions of their tiles:
    sum of the supertiles' perimeters minus the whole patch's, halved."""
    for t, level in [(tiling("hat", depth=3), 1), (tiling("hat", depth=3, shape="turtle"), 0),
                     (tiling("spectre", depth=2), 1)]:
        patch = t.patch()
        group, _ = t.supertiles(patch, None, level)
        segments = export.group_boundaries(patch, group)
        length = float(np.linalg.norm(segments[:, 1] - segments[:, 0], axis=1).sum())
        g = shapely.set_precision(patch.geometries(), 1e-9)
        parts = [shapely.union_all(g[group == k]) for k in np.unique(group)]
        perimeters = sum(p.length for p in parts)
        assert length == pytest.approx((perimeters - shapely.union_all(g).length) / 2, rel=1e-6)
        assert len(np.unique(group)) == len(np.unique(t.supertiles(patch, None, level)[0])) > 1


def test_overlay_draws_a_path_per_level(tmp_path) -> None:
    t = tiling("hat", depth=2, overlay="0,1")
    svg = t.render_svg(t.patch(), region=t.default_region())
    assert svg.count('stroke="#b40000"') == 1 and svg.count('stroke="#1f3fbf"') == 1
    assert not tiling("hat", depth=2).configure(overlay="0").streams


# ------------------------------------------------------------------ the curved Spectre


def test_curved_spectre_edge_is_its_own_complement_and_tiles() -> None:
    """The S-curve turned a half-turn about its midpoint is itself, so it fits every edge of
    a tiling without reflections; the curved Spectre keeps its straight polygon's area (the
    S bulges equally to both sides) and its patches validate."""
    edge = spectre_edge(0.15)
    assert np.allclose(complement(edge), edge)
    t = tiling("spectre", curved="0.15")
    straight = builtin_systems()["spectre"].tile
    assert t.prototiles[0].area == pytest.approx(straight.area)
    assert len(t.prototiles[0].outline) == 14 * (1 + len(edge))
    region = (-12, -12, 12, 12)
    assert_valid(t.patch(region), region)
    with pytest.raises(ParameterError, match="in \\(0, 0.2\\]"):
        tiling("spectre", curved="0.5")


def test_curved_and_deformed_tilings_stream_as_they_patch() -> None:
    """iter_patches in small chunks gives the tiles of patch(region), curved or deformed."""
    for t in [tiling("spectre", curved=1), tiling("hat", a=2, b=1)]:
        region = (-15, -15, 15, 15)
        whole = t.patch(region)
        parts = list(t.iter_patches(region, chunk_tiles=40))
        assert len(parts) > 1 and parts[0].prototiles[0] is t.prototiles[0]
        joined = np.concatenate([p.transform for p in parts])
        assert len(joined) == len(whole)
        assert np.all(match_placements(whole.transform, joined) >= 0)


# ------------------------------------------------------------------ catalogue and CLI


@pytest.fixture(scope="module")
def cli_db(tmp_path_factory):
    return f"sqlite:///{tmp_path_factory.mktemp('cont') / 'c.sqlite'}"


def run(db: str, *args: str):
    from tilekit.cli import cli

    return CliRunner().invoke(cli, ["--catalogue", db, *args])


def test_catalogue_records_and_aliases(cli_db) -> None:
    r = run(cli_db, "list", "--family", "substitution", "--where", "aperiodic=false", "--format", "json")
    assert r.exit_code == 0, r.output
    assert {x["name"] for x in json.loads(r.output)} >= {"chevron", "comet"}
    r = run(cli_db, "show", "tile(sqrt3,1)")
    assert r.exit_code == 0 and "name: turtle" in r.output and "Tile(sqrt3, 1)" in r.output
    assert "name: spectre" in run(cli_db, "show", "tile(1,1)").output
    assert "name: hat" in run(cli_db, "show", "tile(1,sqrt3)").output


def test_cli_renders_members_tables_and_overlays(cli_db, tmp_path) -> None:
    out = tmp_path / "t.svg"
    r = run(cli_db, "render", "hat", "--set", "a=1", "--set", "b=2", "--depth", "2", "--set", "overlay=1", "-o", str(out))
    assert r.exit_code == 0, r.output
    assert "(169 tiles)" in r.output and 'stroke="#b40000"' in out.read_text()
    r = run(cli_db, "render", "turtle", "--depth", "1", "-o", str(tmp_path / "t.csv"))
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(open(tmp_path / "t.csv", newline="")))
    assert [row["label"] for row in rows].count("T") == 1 and len(rows) == 25
    r = run(cli_db, "render", "hat", "--set", "shape=comet", "--depth", "1", "-o", str(tmp_path / "c.json"))
    assert r.exit_code == 0 and json.loads((tmp_path / "c.json").read_text())["prototiles"][0]["name"] == "Tile(1, 0)"


@pytest.mark.parametrize(("args", "fragment"), [
    (["--set", "a=1"], "needs both a and b"),
    (["--set", "a=x", "--set", "b=1"], "a='x' is not a number"),
    (["--set", "shape=boat"], "is not a named member"),
    (["--set", "overlay=-1"], "overlay '-1'"),
    (["--set", "curved=1"], "without reflected tiles"),
])
def test_cli_bad_options_are_one_line_errors(cli_db, tmp_path, args, fragment) -> None:
    assert_one_line_error(run(cli_db, "render", "hat", *args, "-o", str(tmp_path / "x.svg")), fragment)
