"""Wang family: tile-set data and parser, fills, checkers, rendering, plugin hooks.

Facts come from Kaplan's *Introductory Tiling Theory for Computer Graphics* §6.2 and §7.5
(Figure 6.9; Cohen et al. 2003; Lagae and Dutré 2006) and from the papers cited in
catalogue/wang/*.wang; the aperiodic sets' tiles are those of design/FACTS.md.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit.errors import GeometryError, NotFoundError, ParameterError, ParseError
from tilekit.plugins import families, get_search
from tilekit.plugins.wang import (
    WangTileSet,
    WangTiling,
    builtin_sets,
    check_grid,
    from_corners,
    from_tuples,
    get_tileset,
    grid_mismatches,
    grid_to_patch,
    load_texture,
    load_tileset,
    parse_tileset,
    patch_mismatches,
    random_access_fill,
    random_access_tiles,
    record_for,
    scanline_fill,
    wang_svg,
    write_wang_image,
)
from tilekit.plugins.wang.fill import lattice_hash, supports_random_access
from tilekit.plugins.wang.tileset import E, N, S, W, catalogue_folder

# ---------------------------------------------------------------------- the shipped sets


def test_shipped_sets_have_the_published_sizes():
    """Jeandel–Rao 11 tiles (arXiv:1506.06492), Culik 13 (Discrete Math. 160, 1996),
    Kari 14 (ibid.), Figure 6.9's 8 tiles, and 2^4 = 16 corner tiles over 2 colours."""
    sizes = {name: len(ts) for name, ts in builtin_sets().items()}
    assert sizes["jeandel-rao-11"] == 11
    assert sizes["culik-13"] == 13
    assert sizes["kari-14"] == 14
    assert sizes["stochastic-2colour"] == 8
    assert sizes["corner-2colour"] == 16
    for name in ("jeandel-rao-11", "culik-13", "kari-14"):
        assert get_tileset(name).known_aperiodic
        assert get_tileset(name).source


def test_jeandel_rao_colour_counts():
    """Jeandel and Rao's set uses 5 colours on horizontal edges and 4 on vertical edges."""
    jr = get_tileset("jeandel-rao-11")
    assert len(jr.horizontal_colours) == 5
    assert len(jr.vertical_colours) == 4


def test_figure_6_9_every_north_west_pair_has_exactly_two_tiles():
    """Figure 6.9: two colours per orientation; for any N and W colours exactly two tiles fit."""
    ts = get_tileset("stochastic-2colour")
    assert len(ts.horizontal_colours) == 2 and len(ts.vertical_colours) == 2
    counts = {}
    for n, _e, _s, w in ts.tiles.tolist():
        counts[(n, w)] = counts.get((n, w), 0) + 1
    assert sorted(counts) == sorted(itertools.product(ts.horizontal_colours.tolist(), ts.vertical_colours.tolist()))
    assert set(counts.values()) == {2}
    assert ts.complete and ts.stochastic


def test_corner_set_has_every_corner_colouring_once():
    """Lagae and Dutré's complete corner set over k colours has one tile per colouring: k^4."""
    ts = get_tileset("corner-2colour")
    assert ts.kind == "corner"
    assert sorted(map(tuple, ts.corners.tolist())) == list(itertools.product(range(2), repeat=4))
    assert ts.corner_complete and supports_random_access(ts)
    # an edge's colour is the pair of its end points, so N of one tile meets S of another
    # exactly when they agree on both shared corners
    assert ts.complete and ts.stochastic


def test_aperiodic_and_small_sets_are_not_complete():
    for name in ("jeandel-rao-11", "culik-13", "kari-14", "cycle-3", "counter-4"):
        ts = get_tileset(name)
        assert not ts.complete
        assert not supports_random_access(ts)


def test_unknown_set_name_suggests_close_names():
    with pytest.raises(NotFoundError, match="jeandel-rao-11"):
        get_tileset("jeandel-rao-1")
    assert get_tileset("jeandel-rao") is get_tileset("jeandel-rao-11")  # alias


# ---------------------------------------------------------------------- the parser


GOOD = """\
# a comment
name: tiny
title: A tiny set
palette: a=#ff0000 b=blue   # colours for rendering
tiles: W S E N   # columns in another order
a b a c   one
b c b c   two
"""


def test_parser_reads_columns_in_the_declared_order():
    ts = parse_tileset(GOOD, "tiny.wang")
    assert ts.name == "tiny" and ts.tile_names == ("one", "two")
    assert ts.tile_colours(0) == {"N": "c", "E": "a", "S": "b", "W": "a"}
    assert ts.palette == {"a": "#ff0000", "b": "blue"}


@pytest.mark.parametrize(
    ("text", "line", "needle"),
    [
        ("name: x\ntiles: N E S W\n1 2 3\n", 3, "needs 4 colours"),
        ("name: x\ncolour: 3\ntiles: N E S W\n1 2 3 4\n", 2, "unknown key 'colour'"),
        ("name: x\ntiles: N E S\n", 2, "must list N E S W"),
        ("name: x\ntiles: N E S W\n1 2 3 4\n1 2 3 4\n", 4, "repeats the tile on line 3"),
        ("name: x\ntiles: N E S W\n1 2 3 4 a\n4 3 2 1 a\n", 4, "tile name 'a' repeats"),
        ("name: x\ntiles: N E S W\n", 2, "tile list is empty"),
        ("name: x\n", 1, "no 'tiles: N E S W'"),
        ("title: t\ntiles: N E S W\n1 2 3 4\n", 1, "no 'name:' line"),
        ("name: X Y\ntiles: N E S W\n1 2 3 4\n", 1, "must be lower case"),
        ("name: x\npalette: 1=#12\ntiles: N E S W\n1 2 3 4\n", 2, "palette entry"),
        ("name: x\npalette: 9=#123456\ntiles: N E S W\n1 2 3 4\n", 2, "no tile uses"),
        ("name: x\nknown_aperiodic: maybe\ntiles: N E S W\n1 2 3 4\n", 2, "true or false"),
        ("name: x\ntiles: N E S W\n1 2 3 4$\n", 3, "colour '4$'"),
        ("name: x\nname: y\ntiles: N E S W\n1 2 3 4\n", 2, "given twice"),
        ("name: x\ncorners: NE SE SW NW\n0 1 0\n", 3, "NE SE SW NW"),
    ],
)
def test_malformed_sets_name_file_line_and_problem(text, line, needle):
    with pytest.raises(ParseError) as info:
        parse_tileset(text, "bad.wang")
    msg = str(info.value)
    assert msg.startswith(f"bad.wang:{line}: "), msg
    assert needle in msg
    assert "\n" not in msg


def test_load_tileset_missing_file(tmp_path):
    with pytest.raises(ParseError, match="does not exist"):
        load_tileset(tmp_path / "nope.wang")


def test_every_shipped_file_round_trips_through_text_and_json():
    for path in sorted(catalogue_folder().glob("*.wang")):
        ts = load_tileset(path)
        again = parse_tileset(ts.to_text(), "again.wang")
        assert np.array_equal(again.tiles, ts.tiles) and again.colours == ts.colours
        assert again.tile_names == ts.tile_names and again.aliases == ts.aliases
        back = WangTileSet.from_json(ts.to_json())
        assert np.array_equal(back.tiles, ts.tiles) and back.known_aperiodic == ts.known_aperiodic


_tokens = st.sampled_from(["0", "1", "2", "a", "b", "x_1", "R+"])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(_tokens, _tokens, _tokens, _tokens), min_size=1, max_size=12, unique=True))
def test_parser_round_trips_random_sets(rows):
    ts = from_tuples("random", rows)
    again = parse_tileset(ts.to_text())
    assert [tuple(again.colours[c] for c in r) for r in again.tiles.tolist()] == [tuple(r) for r in rows]


def test_duplicate_tiles_in_code_are_rejected():
    with pytest.raises(ParseError, match="same tile"):
        from_tuples("dup", [(1, 2, 3, 4), (1, 2, 3, 4)])
    with pytest.raises(ParseError, match="expected 4"):
        from_corners("bad", [(0, 1, 0)])


# ---------------------------------------------------------------------- checkers


def test_checker_names_the_cell_side_and_colours_of_a_mismatch():
    ts = get_tileset("checkerboard-2")  # a = (x, p, y, q), b = (y, q, x, p)
    good = np.array([[0, 1], [1, 0]])
    assert grid_mismatches(good, ts) == [] and grid_mismatches(good, ts, torus=True) == []
    bad = np.array([[0, 0], [1, 0]])  # a east of a: E=p meets W=q
    found = grid_mismatches(bad, ts)
    assert [(m.cell, m.neighbour, m.side, m.colour, m.neighbour_colour) for m in found][0] == (
        (0, 0), (0, 1), "E", "p", "q"
    )
    with pytest.raises(GeometryError, match=r"tile at \(0, 0\) has E='p' but its neighbour at \(0, 1\) has W='q'"):
        check_grid(bad, ts)
    with pytest.raises(ParameterError, match="tiles 0..1"):
        check_grid(np.array([[0, 2]]), ts)


def test_torus_check_wraps_round():
    ts = get_tileset("cycle-3")
    row = np.array([[0, 1, 2, 0]])
    assert grid_mismatches(row, ts) == []
    assert len(grid_mismatches(row, ts, torus=True)) == 1  # E of tile 0 (=1) meets W of tile 0 (=0)


def test_patch_checker_works_from_geometry_alone():
    ts = get_tileset("checkerboard-2")
    patch = grid_to_patch(np.array([[0, 1, 0], [1, 0, 1]]), ts, x0=5, y0=-2)
    assert patch_mismatches(patch) == []
    broken = grid_to_patch(np.array([[0, 1, 0], [1, 1, 1]]), ts)
    found = patch_mismatches(broken)
    # the bottom row b b b has two bad E/W edges, and the middle b sits under b (N/S)
    assert len(found) == 3
    assert {m.side for m in found} == {"E", "N"}


# ---------------------------------------------------------------------- the scanline fill


def test_scanline_fill_obeys_the_matching_rule_everywhere():
    """Cohen et al.'s scanline fill (§7.5) of the Figure 6.9 set: every shared edge matches,
    checked on the grid and, independently, on the patch geometry."""
    ts = get_tileset("stochastic-2colour")
    grid = scanline_fill(ts, 37, 53, seed=11)
    assert grid.shape == (37, 53)
    assert grid_mismatches(grid, ts) == []
    patch = grid_to_patch(grid, ts)
    assert patch_mismatches(patch) == []
    assert patch.validate((0, 0, 53, 37)).ok
    assert set(np.unique(grid).tolist()) == set(range(8))


def test_scanline_fill_large_grid_is_valid_and_repeatable():
    ts = get_tileset("stochastic-2colour")
    a = scanline_fill(ts, 1000, 1000, seed=3)
    assert grid_mismatches(a, ts) == []
    assert np.array_equal(a, scanline_fill(ts, 1000, 1000, seed=3))
    assert not np.array_equal(a, scanline_fill(ts, 1000, 1000, seed=4))


def test_scanline_choices_are_balanced():
    """With exactly two tiles per (N, W) pair each is chosen with probability 1/2: over a
    300 x 300 fill the two candidates of every pair appear within 5% of each other."""
    ts = get_tileset("stochastic-2colour")
    grid = scanline_fill(ts, 300, 300, seed=1)
    counts = np.bincount(grid.ravel(), minlength=8)
    for n, w in itertools.product(ts.horizontal_colours.tolist(), ts.vertical_colours.tolist()):
        pair = np.flatnonzero((ts.tiles[:, N] == n) & (ts.tiles[:, W] == w))
        a, b = counts[pair]
        assert abs(a - b) <= 0.05 * (a + b)


def test_scanline_fill_of_corner_tiles():
    ts = get_tileset("corner-2colour")
    grid = scanline_fill(ts, 40, 25, seed=2)
    assert grid_mismatches(grid, ts) == []


def test_scanline_fill_refuses_incomplete_sets():
    with pytest.raises(ParameterError, match="not complete"):
        scanline_fill(get_tileset("jeandel-rao-11"), 5, 5)
    with pytest.raises(ParameterError, match="at least 1 x 1"):
        scanline_fill(get_tileset("stochastic-2colour"), 0, 5)


# ---------------------------------------------------------------------- random access


def test_random_access_tile_is_the_same_alone_or_in_a_block():
    """Lagae and Dutré: the tile at (x, y) depends only on (x, y) and the seed."""
    ts = get_tileset("corner-2colour")
    block = random_access_fill(ts, 30, 40, x0=-17, y0=5, seed=9)
    rng = np.random.default_rng(0)
    for _ in range(200):
        i, j = int(rng.integers(30)), int(rng.integers(40))
        x, y = -17 + j, 5 + (30 - 1 - i)
        assert random_access_tiles(ts, np.array(x), np.array(y), seed=9) == block[i, j]
    # an overlapping block with another origin agrees on the overlap
    other = random_access_fill(ts, 20, 20, x0=-7, y0=15, seed=9)
    # other covers x in [-7, 13), y in [15, 35); block covers x in [-17, 23), y in [5, 35)
    assert np.array_equal(other, block[0:20, 10:30])
    assert grid_mismatches(block, ts) == []


def test_random_access_far_from_the_origin():
    ts = get_tileset("corner-2colour")
    far = random_access_fill(ts, 8, 8, x0=10**12, y0=-(10**12), seed=1)
    assert grid_mismatches(far, ts) == []
    assert far[0, 0] == random_access_tiles(ts, np.array(10**12), np.array(-(10**12) + 7), seed=1)


def test_random_access_for_an_edge_set_with_every_colour_combination():
    """An edge set with a tile for every (N, E, S, W) over 2 x 2 colours (16 tiles) can be
    looked up by hashing edges instead of corners."""
    ts = from_tuples("full-edge", list(itertools.product("ab", "xy", "ab", "xy")))
    assert supports_random_access(ts)
    grid = random_access_fill(ts, 25, 31, x0=3, y0=-4, seed=2)
    assert grid_mismatches(grid, ts) == []
    ys = -4 + 25 - 1 - np.arange(25)
    xs = 3 + np.arange(31)
    assert np.array_equal(random_access_tiles(ts, xs[None, :], ys[:, None], seed=2), grid)


def test_random_access_refuses_sets_without_every_colouring():
    with pytest.raises(ParameterError, match="cannot be looked up by hashing"):
        random_access_fill(get_tileset("stochastic-2colour"), 3, 3)


def test_lattice_hash_is_balanced():
    """Corner colours mod 2 over a million lattice points are 1 with frequency 1/2 +- 0.3%."""
    x, y = np.meshgrid(np.arange(-500, 500), np.arange(-500, 500))
    bits = lattice_hash(x, y, seed=5) % np.uint64(2)
    assert abs(float(bits.mean()) - 0.5) < 0.003
    assert not np.array_equal(lattice_hash(x, y, seed=5), lattice_hash(x, y, seed=6))


# ---------------------------------------------------------------------- the tiling and plugin


def test_wang_family_and_records():
    fam = families()["wang"]
    recs = {r.name: r for r in (record_for(ts) for ts in builtin_sets().values())}
    assert set(recs) == set(builtin_sets())
    jr = recs["jeandel-rao-11"].properties
    assert jr["tiles"] == 11 and jr["aperiodic"] is True and "1506.06492" in jr["aperiodic_source"]
    assert jr["periodic"] is False and jr["periodic_unit"] is None and jr["wang_outcome"] == "no_answer"
    assert recs["cycle-3"].properties["periodic_unit"] == 3 and recs["cycle-3"].properties["periodic"] is True
    assert recs["cycle-3"].properties["aperiodic"] is False and recs["counter-4"].properties["aperiodic"] is False
    assert recs["checkerboard-2"].properties["periodic_unit"] == 2
    assert recs["counter-4"].properties["does_not_tile_beyond"] == 4
    assert recs["mismatch-1"].properties["does_not_tile_beyond"] == 1
    assert recs["stochastic-2colour"].properties["stochastic"] is True
    assert recs["corner-2colour"].properties["random_access"] is True
    for rec in recs.values():
        for key, value in rec.properties.items():
            assert key == key.lower() and " " not in key
            assert value is None or isinstance(value, bool | int | float | str | list)
        tiling = fam.from_spec(rec.spec)
        assert tiling.tileset is builtin_sets()[rec.name]


@pytest.mark.parametrize("name", ["stochastic-2colour", "corner-2colour", "jeandel-rao-11", "kari-14", "cycle-3"])
def test_patches_validate_and_match(name):
    tiling = WangTiling(get_tileset(name), seed=4)
    region = (-2.5, 1.2, 9.7, 9.0)
    patch = tiling.patch(region)
    assert patch.validate(region).ok
    assert patch_mismatches(patch) == []
    assert len(patch) == 13 * 8  # lattice squares meeting the box: x -3..9, y 1..8


def test_patch_of_a_disc_covers_it_and_matches():
    import shapely

    disc = shapely.Point(3.3, -2.1).buffer(6.0)
    for name in ("corner-2colour", "stochastic-2colour"):
        patch = WangTiling(get_tileset(name), seed=1).patch(disc)
        assert patch.validate(disc).ok
        assert patch_mismatches(patch) == []
        # only squares meeting the disc are kept: none lies entirely outside it
        assert shapely.intersects(disc, patch.geometries()).all()


def test_fill_methods_resolve_per_set():
    assert WangTiling(get_tileset("corner-2colour")).fill_method() == "random-access"
    assert WangTiling(get_tileset("stochastic-2colour")).fill_method() == "scanline"
    assert WangTiling(get_tileset("culik-13")).fill_method() == "solver"
    assert WangTiling(get_tileset("cycle-3")).fill_method() == "periodic"


def test_periodic_sets_fill_large_regions_by_repeating_their_unit():
    """cycle-3 has a 3 x 3 torus, so a 200 x 200 region (beyond the solver's limit) is filled
    by repetition; the pattern is the same whatever the region, and every edge matches."""
    tiling = WangTiling(get_tileset("cycle-3"))
    big = tiling.patch((-50, -50, 150, 150))
    assert len(big) == 40_000 and patch_mismatches(big) == []
    small = tiling.patch((3, 4, 8, 9))
    pos_big = {tuple(p): t for p, t in zip(np.rint(big.transform[:, :2, 2]).astype(int).tolist(), big.prototile.tolist())}
    for p, t in zip(np.rint(small.transform[:, :2, 2]).astype(int).tolist(), small.prototile.tolist()):
        assert pos_big[tuple(p)] == t
    with pytest.raises(ParameterError, match="no torus tiling of side <= 6"):
        WangTiling(get_tileset("kari-14"), method="periodic").patch((0, 0, 3, 3))


def test_random_access_tiling_patches_agree_on_overlaps():
    tiling = WangTiling(get_tileset("corner-2colour"), seed=7)
    a, b = tiling.patch((0, 0, 20, 20)), tiling.patch((10, 10, 30, 30))

    def at(patch):
        pos = np.rint(patch.transform[:, :2, 2]).astype(int)
        return {tuple(p): t for p, t in zip(pos.tolist(), patch.prototile.tolist())}

    ta, tb = at(a), at(b)
    shared = set(ta) & set(tb)
    assert len(shared) == 100 and all(ta[k] == tb[k] for k in shared)


def test_non_tiling_set_patch_is_a_clear_error():
    with pytest.raises(GeometryError, match="does not tile a 2 x 2 rectangle"):
        WangTiling(get_tileset("mismatch-1")).patch((0, 0, 2, 2))


def test_configure_and_spec_round_trip(tmp_path):
    t = WangTiling(get_tileset("stochastic-2colour"))
    t2 = t.configure(seed="12", method="scanline", params=[], edges=[])
    assert (t2.seed, t2.method) == (12, "scanline")
    assert not np.array_equal(t.patch((0, 0, 10, 10)).prototile, t2.patch((0, 0, 10, 10)).prototile)
    back = WangTiling.from_spec(t2.spec())
    assert np.array_equal(back.patch((0, 0, 10, 10)).prototile, t2.patch((0, 0, 10, 10)).prototile)
    with pytest.raises(ParameterError, match="not 'depth'"):
        t.configure(depth=3)
    with pytest.raises(ParameterError, match="not an integer"):
        t.configure(seed="x")
    with pytest.raises(ParameterError, match="not one of"):
        t.configure(method="magic")
    # a user's file: from_file, and its spec carries the tiles inline
    path = tmp_path / "mine.wang"
    path.write_text(GOOD)
    mine = families()["wang"].from_file(str(path))
    spec = mine.spec()
    assert spec["tileset"]["name"] == "tiny"
    assert np.array_equal(WangTiling.from_spec(spec).tileset.tiles, mine.tileset.tiles)
    with pytest.raises(ParseError, match="must name a 'set'"):
        WangTiling.from_spec({"seed": 1})


def test_periodicity_search_reports_and_updates_the_record():
    search = get_search("wang-periodicity")
    params = {"set": "counter-4", "max_m": 7}
    chunks = search.chunks(params)
    out = search.run_chunk(params, chunks[0])
    (result,) = out.results
    assert result["outcome"] == "does_not_tile" and result["m"] == 5
    assert "no 5 x 5 square can be tiled" in result["statement"]
    (record,) = out.records
    assert record.name == "counter-4" and record.properties["does_not_tile_beyond"] == 4
    assert search.summarize(params, out.results)["outcome"] == "does_not_tile"
    with pytest.raises(NotFoundError):
        search.chunks({"set": "no-such-set", "max_m": 3})
    with pytest.raises(ParameterError, match="at least 1"):
        search.chunks({"set": "cycle-3", "max_m": 0})


# ---------------------------------------------------------------------- rendering


def test_svg_draws_one_use_per_cell_and_four_coloured_triangles():
    ts = get_tileset("stochastic-2colour")
    grid = scanline_fill(ts, 6, 9, seed=1)
    svg = wang_svg(grid, ts)
    assert svg.count("<use ") == 54
    t = int(grid[0, 0])
    colours = ts.tile_colours(t)
    tile_def = svg.split(f'<g id="wt{t}">', 1)[1].split("</g>", 1)[0]
    fills = [seg.split('"')[0] for seg in tile_def.split('fill="')[1:5]]
    assert fills == [ts.palette[colours[side]] for side in "NESW"]


def test_texture_motifs_from_a_file_and_missing_motifs(tmp_path):
    ts = get_tileset("stochastic-2colour")
    texture = load_texture(catalogue_folder() / "textures" / "stochastic-2colour.toml")
    assert set(texture) == {"R", "G", "Y", "B"}
    svg = wang_svg(scanline_fill(ts, 4, 4, seed=2), ts, texture=texture)
    assert svg.count('clip-path="url(#clip') >= 4 * 4  # every used tile clips four motifs
    with pytest.raises(ParameterError, match="no motif for edge colour"):
        wang_svg(np.array([[0]]), ts, texture={"R": "<circle r='1'/>"})
    bad = tmp_path / "bad.toml"
    bad.write_text("[colours]\nR = 3\n")
    with pytest.raises(ParseError, match="SVG fragment"):
        load_texture(bad)
    out = write_wang_image(scanline_fill(ts, 3, 3, seed=1), ts, tmp_path / "w.png", size=90)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_generic_patch_carries_tile_identity_and_edge_labels():
    ts = get_tileset("jeandel-rao-11")
    patch = grid_to_patch(np.array([[0, 1]]), ts)
    assert patch.colour.tolist() == [0, 1]
    proto = patch.prototiles[0]
    # outline edges S, E, N, W carry tile a = (N 4, E 2, S 1, W 2)
    assert proto.edge_labels == ("1", "2", "4", "2")
    assert len(proto.marking) == 2  # the diagonals that split the square into four triangles
    assert (ts.tiles[0, [N, E, S, W]] == [ts.colours.index(c) for c in ("4", "2", "1", "2")]).all()


# ---------------------------------------------------------------------- command line


def _run(tmp_path, *args: str):
    from click.testing import CliRunner

    from tilekit.cli import cli

    return CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{tmp_path / 'cat.db'}", *args])


def test_cli_wang_solve_and_render(tmp_path):
    res = _run(tmp_path, "wang", "solve", "cycle-3", "--rows", "2", "--cols", "6", "--torus")
    assert res.exit_code == 0, res.output
    lines = res.output.splitlines()
    assert "2 x 6 torus: tiles" in lines[0]
    # every row of a cycle-3 torus cycles t0 t1 t2 (from some start)
    for row in lines[1:3]:
        names = row.split()
        assert len(names) == 6 and all(int(b[1]) == (int(a[1]) + 1) % 3 for a, b in zip(names, names[1:]))
    res = _run(tmp_path, "wang", "solve", "counter-4", "--rows", "2", "--cols", "5", "--method", "builder")
    assert res.exit_code == 0 and "proved untileable (builder" in res.output
    res = _run(tmp_path, "wang", "solve", "counter-4", "--rows", "2", "--cols", "5", "--fix", "7,0=c0")
    assert res.exit_code == 2 and "outside the 2 x 5 grid" in res.output
    out = tmp_path / "t.svg"
    res = _run(tmp_path, "wang", "render", "corner-2colour", "--rows", "5", "--cols", "7", "-o", str(out))
    assert res.exit_code == 0 and out.read_text().count("<use ") == 35


def test_cli_search_stores_the_run(tmp_path):
    res = _run(tmp_path, "search", "wang-periodicity", "--set", "checkerboard-2", "--max-m", "4")
    assert res.exit_code == 0, res.output
    assert "outcome: periodic" in res.output
    show = _run(tmp_path, "show", "checkerboard-2")
    assert "periodic_unit" in show.output


def test_corner_colours_with_dashes_do_not_collide():
    """Edge colours of corner tiles pair the end points' colours; 'a-b' + 'c' and 'a' + 'b-c'
    must stay different edges."""
    ts = from_corners("dashes", [("a-b", "c", "x", "y"), ("a", "b-c", "x", "y")])
    # tile 0's N edge is (NW, NE) = ('y', 'a-b'); tile 1's is ('y', 'a'): E edges differ too
    assert ts.tiles[0, E] != ts.tiles[1, E]
    assert len(set(ts.colours)) == len(ts.colours)
    with pytest.raises(ParseError, match="corner colour 'a/b'"):
        from_corners("slash", [("a/b", "c", "x", "y")])


def test_corner_textures_are_drawn_per_corner():
    """Exercise 6.8 for corner tiles: one motif per corner colour, clipped to each quadrant."""
    ts = get_tileset("corner-2colour")
    texture = load_texture(catalogue_folder() / "textures" / "corner-2colour.toml")
    assert set(texture) == {"0", "1"}
    grid = random_access_fill(ts, 4, 5, seed=1)
    svg = wang_svg(grid, ts, texture=texture)
    used = len(np.unique(grid))
    assert svg.count('<g clip-path="url(#clipN') + svg.count('<g clip-path="url(#clipS') == 4 * used
    with pytest.raises(ParameterError, match="no motif for corner colour '1'"):
        wang_svg(np.array([[15]]), ts, texture={"0": "<circle r='0.3'/>"})


def test_periodicity_search_on_a_user_file(tmp_path):
    """A user's set: the record carries the tiles inline so the catalogue can rebuild it."""
    path = tmp_path / "pair.wang"
    path.write_text("name: my-pair\ntiles: N E S W\na x b y\nb y a x\n")
    search = get_search("wang-periodicity")
    params = {"set": str(path), "max_m": 4}
    out = search.run_chunk(params, search.chunks(params)[0])
    assert out.results[0]["outcome"] == "periodic" and out.results[0]["m"] == 2
    (record,) = out.records
    assert record.name == "my-pair" and record.properties["periodic_unit"] == 2
    rebuilt = families()["wang"].from_spec(record.spec)
    assert rebuilt.tileset.name == "my-pair" and len(rebuilt.tileset) == 2
