"""Notations for k-uniform tilings: GomJau-Hogg strings and Gavrog D-symbols, in and out.

Published figures used here:

- The GomJau-Hogg strings of the 11 Archimedean and 20 2-uniform tilings are those of the
  Antwerp v3 library (``configurations.json`` in github.com/HHogg/antwerp, the application of
  Gomez-Jauregui, Hogg, Manchado & Otero, *Symmetry* 13 (2021) 2376), with the names and
  wallpaper groups it gives them.
- ``<1.1:3:1 2 3,1 3,2 3:4 8,3>`` is the D-symbol of the truncated square tiling 4.8.8 as
  Gavrog writes it (the example in odf/webGavrog, src/dsymbols/delaney.js); the square tiling
  is ``<1.1:1:1,1,1:4,4>`` (Delgado-Friedrichs, Theor. Comp. Sci. 303 (2003), Fig. 3).
"""

from __future__ import annotations

import itertools
import json
import math
import re
import subprocess
import sys

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit.errors import GeometryError, ParseError
from tilekit.plugins.kuniform import gomjau
from tilekit.plugins.kuniform.dsymbol import DSymbol, from_gavrog, to_gavrog, vertex_types
from tilekit.plugins.kuniform.gomjau import (
    parse,
    parse_text,
    patch_of,
    ungenerable,
    write,
    write_outcome,
)
from tilekit.plugins.kuniform.names import ARCHIMEDEAN_TABLE
from tilekit.plugins.kuniform.search import (
    archimedean_table,
    tiling_of,
    tilings_with_types,
    types_text,
)
from tilekit.regular.notation import VertexType, parse_sequence
from tilekit.symmetry import wallpaper_group

#: Antwerp v3 library: vertex type -> GomJau-Hogg notation (the 11 Archimedean tilings).
ANTWERP_ARCHIMEDEAN = {
    "3^6": "3/m30/r(h2)", "6^3": "6/m30/r(h1)", "4^4": "4/m45/r(h1)", "3.12^2": "12-3/m30/r(h3)",
    "3.4.6.4": "6-4-3/m30/r(c2)", "4.6.12": "12-6,4/m30/r(c2)", "3.6.3.6": "6-3-6/m30/r(v4)",
    "4.8^2": "8-4/m90/r(h4)", "3^2.4.3.4": "4-3-3,4/r90/r(h2)", "3^3.4^2": "4-3/m90/r(h2)",
    "3^4.6": "6-3-3/r60/r(h5)",
}
#: Antwerp v3 library: the 2-uniform tilings (vertex types, wallpaper group, notation).
ANTWERP_TWO_UNIFORM = [
    ("3^6; 3^2.4.3.4", "p6m", "3-4-3/m30/r(c3)"),
    ("3.4.6.4; 3^2.4.3.4", "p6m", "6-4-3,3/m30/r(h1)"),
    ("3.4.6.4; 3^3.4^2", "p6m", "6-4-3-3/m30/r(h5)"),
    ("3.4.6.4; 3.4^2.6", "p6m", "6-4-3,4-6/m30/r(c4)"),
    ("4.6.12; 3.4.6.4", "p6m", "12-4,6-3/m30/r(c3)"),
    ("3^6; 3^2.4.12", "p6m", "12-3,4-3/m30/r(c3)"),
    ("3.12^2; 3.4.3.12", "p4m", "12-0,3,3-0,4/m45/m(h1)"),
    ("3^6; 3^4.6", "p6m", "6-3,3-3/m30/r(h1)"),
    ("3^6; 3^4.6", "p6", "6-3-3,3-3/r60/r(h8)"),
    ("3^2.6^2; 3^4.6", "cmm", "6-3/m90/r(h1)"),
    ("3.6.3.6; 3^2.6^2", "pmm", "6-3,6/m90/r(h3)"),
    ("3.4^2.6; 3.6.3.6", "pmm", "6-3,4-6-3,4-6,4/m90/r(c6)"),
    ("3.4^2.6; 3.6.3.6", "cmm", "6-3,4/m90/r(h4)"),
    ("3^3.4^2; 3^2.4.3.4", "p4g", "4-3,3-4,3/r90/m(h3)"),
    ("4^4; 3^3.4^2", "cmm", "4-3/m(h4)/m(h3)/r(h2)"),
    ("4^4; 3^3.4^2", "cmm", "4-4-3-3/m90/r(h3)"),
    ("3^6; 3^3.4^2", "pmm", "4-3,4-3,3/m90/r(h3)"),
    ("3^6; 3^3.4^2", "cmm", "4-3-3-3/m90/r(h7)/r(h5)"),
]
# Two more strings of that library do not draw the tiling named beside them, here or (by the
# same rules) in Antwerp: '3-6/m30/r(c2)' for [3^6; 3^2.6^2] turns the star of six triangles
# about the centre of a hexagon round it, but in [3^6; 3^2.6^2] the hexagon opposite the star
# across that hexagon is another hexagon, not a star (docs/families/k-uniform.md); and
# '4-3,3,3-4,3/r(c2)/r(h13)/r(h45)' for the pgg [3^3.4^2; 3^2.4.3.4] draws a 3-uniform p2 tiling.


def canonical(text: str) -> str:
    return VertexType.of(parse_sequence(text)).polygons


def geometric_types(parsed, radius: float = 4.0) -> set[tuple[int, ...]]:
    """The vertex types read from the parsed polygons (not from any D-symbol): at each vertex
    near the origin, the sizes of the polygons round it in angular order."""
    polys = parsed.polygons
    out = set()
    corners = {}
    for i in range(len(polys.size)):
        for x, y in polys.corners(i):
            corners.setdefault((round(x, 5), round(y, 5)), []).append(i)
    for (x, y), owners in corners.items():
        if math.hypot(x, y) > radius:
            continue
        ang = [math.atan2(*(polys.centre[i] - (x, y))[::-1]) for i in owners]
        seq = tuple(int(polys.size[i]) for _, i in sorted(zip(ang, owners)))
        out.add(VertexType.of(seq).polygons)
    return out


def symbols_to(k: int) -> list[DSymbol]:
    out = []
    for kk in range(1, k + 1):
        for types in itertools.combinations_with_replacement([t.polygons for t in vertex_types()], kk):
            if kk >= 2 and len(set(types)) == 1:
                continue
            out += tilings_with_types(types)
    return out


# --------------------------------------------------------------------------- published strings


@pytest.mark.parametrize("vt", sorted(ANTWERP_ARCHIMEDEAN))
def test_antwerps_archimedean_strings_draw_the_archimedean_tilings(vt):
    parsed = parse(ANTWERP_ARCHIMEDEAN[vt])
    (expected,) = tilings_with_types([canonical(vt)])
    assert parsed.symbol.canonical_form() == expected.canonical_form()
    assert geometric_types(parsed) == {canonical(vt)}


@pytest.mark.parametrize("types, group, text", ANTWERP_TWO_UNIFORM, ids=[t for _, _, t in ANTWERP_TWO_UNIFORM])
def test_antwerps_two_uniform_strings_draw_the_named_tilings(types, group, text):
    parsed = parse(text)
    want = [canonical(t.strip()) for t in types.split(";")]
    # read from the drawn polygons: the two vertex types and the symmetry group
    assert geometric_types(parsed) == set(want)
    tiling = tiling_of(parsed.symbol)
    assert wallpaper_group(tiling).iuc == group
    # and the symbol is the one the search found for those types
    found = {s.canonical_form() for s in tilings_with_types(want)}
    assert parsed.symbol.canonical_form() in found
    assert len(parsed.symbol.vertex_orbits()) == 2


def test_the_parsed_arrangement_is_a_tiling():
    """No gap, no overlap (Patch.validate) over a disc-sized box, for a p4g and a p6 string."""
    for text in ("4-3,3-4,3/r90/m(h3)", "6-3-3,3-3/r60/r(h8)"):
        parsed = parse(text)
        patch = patch_of(parsed.polygons, 12.0)
        report = patch.validate(region=(-6, -6, 6, 6))
        assert report, report


# --------------------------------------------------------------------------- writing


def exhaustive_write(sym: DSymbol) -> str | None:
    """The writer before it was bounded: every placement of every unit polygon on the seed
    (each corner, both hands), in order, the first text that comes out."""
    sym = DSymbol.decode(sym.encode())
    unit, chambers, v1, v2 = gomjau._unit_of(sym)
    for p, m, _chamber in gomjau._placements(unit, chambers, sym.s1):
        text = gomjau._write_placed([s.mapped(m) for s in unit], m[:2, :2] @ v1, m[:2, :2] @ v2, p, 12)
        if text is not None:
            return text
    return None


#: Orbit types of two of the three 4-uniform tilings without a written notation: a p3 one
#: and a p31m one (20 chambers).
P3_TYPES = ((3, 3, 3, 3, 6), (3, 3, 6, 6), (3, 6, 3, 6), (6, 6, 6))
P31M_TYPES = ((3, 3, 3, 3, 6), (3, 3, 3, 3, 6), (3, 3, 6, 6), (6, 6, 6))


def test_the_shipped_archimedean_table_is_what_the_writer_writes():
    assert json.loads(ARCHIMEDEAN_TABLE.read_text()) == archimedean_table()


@pytest.mark.parametrize("k", [1])
def test_written_notations_parse_back_to_the_same_tiling(k):
    for sym in symbols_to(k):
        text = write(sym)
        assert text is not None, sym.encode()
        assert text == exhaustive_write(sym)
        assert parse(text).symbol.canonical_form() == sym.canonical_form(), text


#: k = 4 writes, re-writes exhaustively and parses 151 strings (minutes on the 2-core CI
#: machine): marked exhaustive (TILEKIT_EXHAUSTIVE=1); CI runs k = 2, 3. The k = 4 strings of
#: two whole runs before and after the writer was bounded are identical (docs/benchmarks.md).


@pytest.mark.slow
@pytest.mark.parametrize("k", [2, 3, pytest.param(4, marks=pytest.mark.exhaustive)])
def test_written_notations_parse_back_to_the_same_tiling_to_k4(k):
    """Every k-uniform tiling with k = 2, 3, 4 (20 + 61 + 151) but three 4-uniform ones; the
    string is the one the exhaustive writer (every placement) writes."""
    missing = []
    for sym in symbols_to(k):
        if len(sym.vertex_orbits()) != k:
            continue
        text = write(sym)
        if text is None:
            missing.append(wallpaper_group(tiling_of(sym)).iuc)
            continue
        assert text == exhaustive_write(sym), sym.encode()
        assert parse(text).symbol.canonical_form() == sym.canonical_form(), text
    # p3 has no half-turn and no mirror: the transforms (rotations about the origin, half-turns,
    # mirrors) generate a finite group inside it, so no notation draws it. The two p31m ones are
    # a limit of the writer (its greedy mirrors do not reach the lattice), not of the notation.
    assert sorted(missing) == (["p3", "p31m", "p31m"] if k == 4 else [])


@pytest.mark.slow
def test_no_notation_exactly_for_groups_without_half_turns_or_crossing_mirrors():
    """ungenerable reads the orbifold off the D-symbol; the wallpaper group from the geometry
    (tilekit.symmetry) must agree: p1, p3, pg, pm and cm, and no other."""
    syms = symbols_to(2) + tilings_with_types(P3_TYPES)
    groups = {wallpaper_group(tiling_of(s)).iuc for s in syms}
    assert "p3" in groups and len(groups) >= 8
    for sym in syms:
        iuc = wallpaper_group(tiling_of(sym)).iuc
        assert (ungenerable(sym) is not None) == (iuc in ("p1", "p3", "pg", "pm", "cm")), iuc
        if iuc == "p3":
            text, why = write_outcome(sym)
            assert text is None and "no half-turn" in why


@pytest.mark.slow
def test_the_writer_stops_at_its_budget_and_says_so():
    """A p31m 4-uniform tiling has two crossing mirrors, but the writer's greedy mirrors do not
    reach its lattice from any placement (all 20 tried, one per chamber, measured): with a cap
    the writer stops there and says so, and the record says why it has no notation."""
    from tilekit.plugins.kuniform.names import notation_properties

    p31m = [s for s in tilings_with_types(P31M_TYPES) if wallpaper_group(tiling_of(s)).iuc == "p31m"]
    assert [s.size for s in p31m] == [20]
    sym = p31m[0]
    assert ungenerable(sym) is None
    text, why = write_outcome(sym, max_placements=2)
    assert text is None and why == "none found in the writer's budget of 2 placements"
    props = notation_properties(sym)
    assert "gomjau" not in props and props["gomjau_missing"].startswith("none found in the writer's budget")


# --------------------------------------------------------------------------- Gavrog D-symbols


def test_gavrog_symbols_of_published_examples():
    (square,) = tilings_with_types([(4, 4, 4, 4)])
    assert to_gavrog(square) == "<1.1:1:1,1,1:4,4>"
    (truncated_square,) = tilings_with_types([(4, 8, 8)])
    assert from_gavrog("<1.1:3:1 2 3,1 3,2 3:4 8,3>").minimal_image().canonical_form() == truncated_square.canonical_form()
    # the dimension may be given, as 3dt writes it
    assert from_gavrog("<1.1:3 2:1 2 3,1 3,2 3:4 8,3>").canonical_form() == truncated_square.canonical_form()


@pytest.mark.parametrize("k", [1, 2])
def test_gavrog_text_round_trips(k):
    for sym in symbols_to(k):
        assert from_gavrog(to_gavrog(sym)).canonical_form() == sym.canonical_form()


@pytest.mark.slow
def test_gavrog_text_round_trips_to_k4():
    syms = symbols_to(4)
    assert len(syms) == 11 + 20 + 61 + 151
    for sym in syms:
        assert from_gavrog(to_gavrog(sym)).canonical_form() == sym.canonical_form()


@pytest.mark.parametrize("text, needle", [
    ("<1.1:3:1 2 3,1 3,2 3:4 8,4>", "curvature -1/4"),  # 4.8.8 with degree 4: hyperbolic
    ("<1.1:3 3:1 2 3,1 3,2 3,1 2 3:4 8,3,3>", "2-dimensional"),
    ("<1.1:3:1 2 3,1 3:4 8,3>", "3 ','-separated"),
    ("<1.1:2:3,1 2,1 2:4,4>", "not a free chamber"),
    ("<1.1:3:1 2,1 3,2 3:4 8,3>", "too short"),
    ("<1.1:x>", "reads <1.1:SIZE"),
])
def test_bad_gavrog_symbols_are_refused(text, needle):
    with pytest.raises(ValueError, match=needle):
        from_gavrog(text)


# --------------------------------------------------------------------------- bad notation


@pytest.mark.parametrize("text, needle", [
    ("5-3/m30/r(h1)", "position 1: the seed polygon must be"),
    ("3-4-7/m30", "position 5: a polygon must be"),
    ("3-4-3/m30/x", "position 11: expected a transform"),
    ("3-4-3/m30/r(h2", "position 15: expected ')'"),
    ("3-4-3/m30/r(q2)", "position 13: expected a point"),
    ("3-4-3/m0", "position 8: a transform's angle"),
    ("3-4-3;m30", "position 6: expected '-'"),
    ("3-4-3/m30/r(h0)", "numbered from 1"),
])
def test_malformed_notation_names_the_position(text, needle):
    with pytest.raises(ParseError, match=needle.replace("(", r"\(").replace(")", r"\)")):
        parse_text(text)


@pytest.mark.parametrize("text, needle", [
    ("3-4-3/m30", "finite group"),                       # no translation: nothing repeats
    ("4-4,4,4,4,4/m45", "no free edge"),                  # five squares round one square
    ("4/m45/r45", "overlap"),                             # a square turned by 45° on itself
    ("12-12,12/m30/r(h1)", "sum to 450°, more than 360°"),  # three 12-gons at a vertex
    ("4/r72/r(h1)", "rotates by 72"),                     # not a multiple of 7.5°
    ("6/r90/r(h1)", "overlap"),                           # a hexagon turned by 90° on itself
])
def test_arrangements_that_are_not_tilings_are_refused_with_the_reason(text, needle):
    with pytest.raises(GeometryError, match=needle):
        parse(text)


def test_a_point_that_is_not_in_the_figure_is_named():
    with pytest.raises(ParseError, match="position 19: r\\(h99\\) names h99, but the figure has 18 h points"):
        parse("6-3,3,3,3,3,3/m30/r(h99)")


@settings(max_examples=60, deadline=None)
@given(st.text(alphabet="0123468-,/mrchv()", max_size=24))
def test_any_text_parses_or_is_refused_in_one_line(text):
    try:
        parse(text)
    except (ParseError, GeometryError) as exc:
        assert "\n" not in str(exc)


# --------------------------------------------------------------------------- the CLI


def test_show_and_where_take_the_notations(catalogue_cli):
    r = catalogue_cli.run("show", "4-3-3,4/r90/r(h2)")  # Antwerp's snub square
    assert r.exit_code == 0 and "name: 3^2.4.3.4" in r.output, r.output
    assert "gomjau" in r.output and "gavrog" in r.output
    r = catalogue_cli.run("show", "<1.1:3:1 2 3,1 3,2 3:4 8,3>")
    assert r.exit_code == 0 and "name: 4.8^2" in r.output, r.output
    r = catalogue_cli.run("search", "k-uniform", "--k", "2")
    assert r.exit_code == 0, r.output
    r = catalogue_cli.run("show", "4-3,3-4,3/r90/m(h3)")
    assert r.exit_code == 0 and "[3^3.4^2; 3^2.4.3.4] p4g" in r.output, r.output
    text = write(parse("4-3,3-4,3/r90/m(h3)").symbol)
    assert catalogue_cli.count("k-uniform", f"gomjau={text}") == 1
    assert catalogue_cli.count("k-uniform", "gomjau~/") == 20  # every 2-uniform record has one


def _cli(catalogue_cli, *args):
    return subprocess.run([sys.executable, "-m", "tilekit", "--catalogue", catalogue_cli.url, *args],
                          capture_output=True, text=True)


@pytest.mark.parametrize("name, needle", [
    ("3-4-3/m30/r(h2", "position 15: expected ')', got the end"),
    ("3-4-3,3,3,3,3,3,3,3/m30/r(h1)", "no free edge"),
    ("<1.1:3:1 2 3,1 3,2 3:4 8,4>", "curvature"),
])
def test_cli_refuses_bad_notation_in_one_line(catalogue_cli, name, needle):
    res = _cli(catalogue_cli, "show", name)
    assert res.returncode == 2, res.stderr
    assert needle in res.stderr and "Traceback" not in res.stderr and res.stderr.strip().count("\n") == 0, res.stderr


def test_a_notation_for_a_tiling_not_yet_searched_says_so(catalogue_cli):
    # Antwerp's [3^6; (3^2.4.3.4)^2]: 3-uniform, so not among the seeded records
    res = _cli(catalogue_cli, "show", "3-4-3,3/m30/m(h2)")
    assert res.returncode == 2 and "no tiling in the catalogue is the one" in res.stderr, res.stderr
    parsed = parse("3-4-3,3/m30/m(h2)")
    assert len(parsed.symbol.vertex_orbits()) == 3
    assert types_text([parsed.symbol.vertex_type(o[0]) for o in parsed.symbol.vertex_orbits()]) == \
        "[3^6; (3^2.4.3.4)^2]"
    assert geometric_types(parsed) == {(3, 3, 3, 3, 3, 3), canonical("3^2.4.3.4")}


# --------------------------------------------------------------------------- .tes files
# Fixtures written here from the format's description (hyperrogue/tessellations/sample/README.md):
# the tiles are the polygons up to symmetry, the gluings say which edge meets which.

TES_HEAD = "## {name}\ne2.\nangleunit(deg)\n"
TES_FIXTURES = {
    # a square glued to its translates across opposite edges
    "4^4": "unittile(90,90,90,90)\nconway(\"(0 2)(1 3)\")\n",
    # a square whose single edge label is mirrored onto itself: the mirror group *442
    "4^4 mirrored": "unittile(90,90,90,90)\nrepeat(0,4)\nconway(\"[0]\")\n",
    # octagon (labels 0, 1 four times) and square (label 0 four times): octagon-square and
    # octagon-octagon (a half-turn) edges
    "4.8^2": ("unittile(135,135,135,135,135,135,135,135)\nunittile(90,90,90,90)\nrepeat(0,4)\nrepeat(1,4)\n"
              "conway(\"(0 0')(1)\")\n"),
    # snub hexagonal: a 3-fold triangle, a 6-fold hexagon and a plain triangle
    "3^4.6": ("unittile(60,60,60)\nunittile(120,120,120,120,120,120)\nunittile(60,60,60)\nrepeat(0,3)\nrepeat(1,6)\n"
              "conway(\"(0 1'')(0' 0'')(2'')\")\n"),
}


@pytest.mark.parametrize("name", sorted(TES_FIXTURES))
def test_tes_files_read_to_the_archimedean_symbols(tmp_path, name):
    from tilekit.plugins.kuniform.tes import read_tes

    path = tmp_path / "t.tes"
    path.write_text(TES_HEAD.format(name=name) + TES_FIXTURES[name])
    title, sym = read_tes(path)
    vt = name.split()[0]
    (expected,) = tilings_with_types([canonical(vt)])
    assert title == name and sym.canonical_form() == expected.canonical_form()


@pytest.mark.parametrize("body, needle", [
    ("h2.\nangleunit(deg)\nunittile(90,90,90,90)\nconway(\"(0 2)(1 3)\")", "only Euclidean"),
    ("e2.\nangleunit(deg)\nunittile(90,90,100,90)\nconway(\"(0 2)(1 3)\")", "not a regular 4-gon"),
    ("e2.\nangleunit(deg)\nunittile(90,90,90,90)\nconway(\"(0 2)\")", "edge 1 of tile 0 is glued to nothing"),
    ("e2.\nangleunit(deg)\nunittile(180-90,90,90,90)\nconway(\"(0 2)(1 3)\")", "not a plain number"),
    ("e2.\nangleunit(deg)\nunittile(108,108,108,108,108)\nrepeat(0,5)\nconway(\"(0)\")", "not 360°"),
    ("e2.\nangleunit(deg)\nunittile(90,90,90,90)\nconway(\"(0 2)(1 3\")", "line 4: in the conway text"),
    ("e2.\nangleunit(deg)\nunittile(90,90,90,90)\nconway(\"(0 2)(1 7)\")", "no such edge label"),
    ("e2.\nangleunit(deg)\nbogus(1)", "line 3: bogus(...) is not read here"),
])
def test_bad_tes_files_are_refused_in_one_line(tmp_path, body, needle):
    from tilekit.plugins.kuniform.tes import read_tes

    path = tmp_path / "bad.tes"
    path.write_text(body)
    with pytest.raises(ParseError, match=re.escape(needle)) as info:
        read_tes(path)
    assert "\n" not in str(info.value)


def test_show_and_render_a_tes_file(catalogue_cli, tmp_path):
    path = tmp_path / "octagons.tes"
    path.write_text(TES_HEAD.format(name="4.8^2") + TES_FIXTURES["4.8^2"])
    r = catalogue_cli.run("show", str(path))
    assert r.exit_code == 0 and "name: 4.8^2" in r.output, r.output
    out = tmp_path / "octagons.svg"
    r = catalogue_cli.run("render", "--system", str(path), "-o", str(out))
    assert r.exit_code == 0 and out.read_text().count("<path") >= 2, r.output
    from tilekit.plugins.kuniform.search import tiling_from_file

    tiling = tiling_from_file(str(path))
    assert tiling.patch((-5, -5, 5, 5)).validate(region=(-4, -4, 4, 4))
    res = _cli(catalogue_cli, "show", str(tmp_path / "missing.tes"))
    assert res.returncode == 2 and "does not exist" in res.stderr and res.stderr.strip().count("\n") == 0
