"""The isohedral data files: transcription of Appendix A, TV matrices, parser errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tilekit.errors import ParseError
from tilekit.plugins.isohedral.engine import laves_polygon
from tilekit.plugins.isohedral.records import properties_table_text
from tilekit.plugins.isohedral.templates import (
    data_dir,
    load_parameterizations,
    load_templates,
    parse_parameterizations,
    parse_templates,
    topology_valences,
)

MARKED = {19, 35, 48, 60, 63, 65, 70, 75, 80, 87, 89, 92}

# Topological types by IH range, as Appendix A lists them (Kaplan 2009, pp. 97-116).
BOOK_TOPOLOGY = (
    [(range(1, 21), "3^6"), (range(21, 22), "3^4.6"), (range(22, 27), "3^3.4^2")]
    + [(range(27, 30), "3^2.4.3.4"), (range(30, 33), "3.4.6.4"), (range(33, 38), "3.6.3.6")]
    + [(range(38, 41), "3.12^2"), (range(41, 77), "4^4"), (range(77, 78), "4.6.12")]
    + [(range(78, 83), "4.8^2"), (range(83, 94), "6^3")]
)

# Aspect counts printed in Appendix A ("Aspects" lines), 81 unmarked types.
BOOK_ASPECTS = {
    1: 1, 2: 2, 3: 2, 4: 2, 5: 4, 6: 4, 7: 3, 8: 1, 9: 2, 10: 1, 11: 1, 12: 1, 13: 2, 14: 1, 15: 2,
    16: 3, 17: 1, 18: 1, 20: 1, 21: 6, 22: 2, 23: 2, 24: 4, 25: 4, 26: 2, 27: 4, 28: 4, 29: 4,
    30: 6, 31: 6, 32: 6, 33: 3, 34: 3, 36: 3, 37: 3, 38: 6, 39: 6, 40: 6, 41: 1, 42: 2, 43: 2,
    44: 2, 45: 2, 46: 2, 47: 2, 49: 4, 50: 4, 51: 4, 52: 4, 53: 4, 54: 4, 55: 4, 56: 8, 57: 1,
    58: 2, 59: 2, 61: 2, 62: 1, 64: 1, 66: 2, 67: 2, 68: 1, 69: 2, 71: 4, 72: 1, 73: 2, 74: 1,
    76: 1, 77: 12, 78: 4, 79: 4, 81: 8, 82: 4, 83: 2, 84: 2, 85: 4, 86: 4, 88: 6, 90: 2, 91: 2, 93: 2,
}


def test_all_93_types_and_81_templates_parse():
    templates = load_templates()
    assert sorted(templates) == list(range(1, 94))
    assert {ih for ih, t in templates.items() if t.marked} == MARKED  # FACTS.md / §5.2
    assert sum(1 for t in templates.values() if not t.marked) == 81


def test_topologies_agree_with_the_book():
    templates = load_templates()
    for block, topology in BOOK_TOPOLOGY:
        for ih in block:
            assert templates[ih].topology == topology, ih


def test_aspect_counts_agree_with_the_book():
    templates = load_templates()
    assert {ih: len(t.aspects) for ih, t in templates.items() if not t.marked} == BOOK_ASPECTS


def test_symbol_edge_count_matches_topology():
    for t in load_templates().values():
        if t.symbol is not None:
            assert len(t.symbol) == len(topology_valences(t.topology)), t.name


def test_43_parameterizations_used():
    # §5.3.2: "the 93 isohedral types require 43 different parameterizations"; the 81 unmarked use them all
    used = {t.parameterization for t in load_templates().values() if not t.marked}
    assert used == {f"TV{i}" for i in range(1, 44)}
    assert set(load_parameterizations()) == used


def test_square_and_parallelogram_parameterizations():
    # §5.3.2: nine types have squares as tiling polygons (no parameters), seven have
    # parallelograms (two parameters). Among the unmarked 4^4 types, TV35 is the square (six
    # types; the other three square types are marked) and TV26 the parallelogram (seven types).
    tvs = load_parameterizations()
    users = {}
    for t in load_templates().values():
        if not t.marked:
            users.setdefault(t.parameterization, []).append(t.ih)
    assert tvs["TV35"].parameters == 0 and len(users["TV35"]) == 6
    assert tvs["TV26"].parameters == 2 and len(users["TV26"]) == 7
    sq = tvs["TV35"].evaluate([])
    sides = np.linalg.norm(np.roll(sq, -1, axis=0) - sq, axis=1)
    assert np.allclose(sides, sides[0])
    for vv in ([0.1, 0.3], [0.4, 0.7]):
        p = tvs["TV26"].evaluate(vv)
        assert np.allclose(p[1] - p[0], p[2] - p[3]) and np.allclose(p[3] - p[0], p[2] - p[1])


def test_ih16_matrix_is_the_books():
    # §5.4.1 prints IH16's 12 x 2 coefficient matrix. Tactile's (our data) measures the
    # parameter in quarters of the book's v0 (v = v0 / 4): the constant column is identical
    # and the parameter column is exactly four times the book's.
    r3 = math.sqrt(3)
    book = np.array(
        [
            [0, 1 / 2], [0, -1 / (2 * r3)], [0, 1], [0, 0], [1 / (2 * r3), 3 / 4], [1 / 2, 1 / (4 * r3)],
            [0, 1 / 2], [1, 0], [-1 / (2 * r3), 1 / 4], [1 / 2, 1 / (4 * r3)], [0, 0], [0, 0],
        ]
    )
    assert load_templates()[16].parameterization == "TV14"
    ours = load_parameterizations()["TV14"].coefficients
    assert np.allclose(ours[:, 1], book[:, 1], atol=1e-9)
    assert np.allclose(ours[:, 0], 4 * book[:, 0], atol=1e-9)


def _similar(a: np.ndarray, b: np.ndarray) -> bool:
    """Polygons equal up to a direct or opposite similarity and a cyclic relabelling."""
    za = a[:, 0] + 1j * a[:, 1]
    for cand in (b, b[::-1] * [1, 1], b * [1, -1], (b * [1, -1])[::-1]):
        zb = cand[:, 0] + 1j * cand[:, 1]
        for s in range(len(zb)):
            r = np.roll(zb, s)
            scale = (za[1] - za[0]) / (r[1] - r[0])
            if np.allclose(za - za[0], (r - r[0]) * scale, atol=1e-7):
                return True
    return False


def test_default_parameters_give_the_laves_tile():
    # §5.4.5: the Laves tile is within every type's range and serves as the default shape.
    for name, tv in load_parameterizations().items():
        assert _similar(tv.evaluate(tv.default), laves_polygon(tv.topology)), name


def test_laves_tiles_have_the_right_angles():
    # A Laves tile's vertex of valence p has angle 360/p (§4.2).
    for topology in ("3^6", "3^4.6", "3^3.4^2", "3^2.4.3.4", "3.4.6.4", "3.6.3.6", "3.12^2", "4^4", "4.6.12", "4.8^2", "6^3"):
        poly = laves_polygon(topology)
        vals = topology_valences(topology)
        for j, p in enumerate(vals):
            u = poly[j - 1] - poly[j]
            w = poly[(j + 1) % len(poly)] - poly[j]
            ang = math.acos(u @ w / np.linalg.norm(u) / np.linalg.norm(w))
            assert ang == pytest.approx(2 * math.pi / p), (topology, j)


@pytest.mark.parametrize(
    "text, problem",
    [
        ("IH16 3^6 [a+b+c+c-b-a-; a-c+b+]\n  parameterization TV14\n  colouring (0 1 2)(0 1 2)(0 1 2)\n"
         "  aspects 1, 2, 3\n  rule 2 <- 1; 1\n  rule 3 <- 1; 9\n  rule v1 <- 2; 5\n  rule v2 <- 2; 3\n",
         "line 6: rule '3 <- 1; 9' hops across edge 9; edges are 1..6"),
        ("IH16 3^6 [a+b+c+c-b-a-; a-c+b+]\n  parameterization TV14\n  colouring (0 1)(0 1 2)(0 1 2)\n"
         "  aspects 1, 2, 3\n  rule 2 <- 1; 1\n  rule 3 <- 1; 6\n  rule v1 <- 2; 5\n  rule v2 <- 2; 3\n",
         "line 3: colouring gives 2 aspect colours for 3 aspects"),
        ("IH16 3^6 [a+b+c+c-b-a-; a-c+b+]\n  parametrisation TV14\n", "line 2: unknown entry 'parametrisation'"),
        ("IH16 4^4 [a+b+c+c-b-a-; a-c+b+]\n", "line 1: IH16: symbol [a+b+c+c-b-a-; a-c+b+] has 6 edges but topology 4^4 has 4"),
        ("IH99 4^4 [abab; ab]\n", "line 1: IH99 is not one of IH1..IH93"),
        ("  rule 2 <- 1; 1\n", "line 1: indented line before the first 'IHn' header"),
        ("IH41 4^4 [a+b+c+d+; c+d+a+b+]\n  parameterization TV26\n  colouring (0)(1 0)(1 0)\n  aspects 1\n"
         "  rule v1 <- 2; 1\n  rule v2 <- 1; 2\n", "line 5: rule 'v1 <- 2; 1' uses aspect '2' before it is defined"),
        ("IH41 4^4 [a+b+c+d+; c+d+a+q+]\n", "line 1: incidence symbol"),
    ],
)
def test_template_parser_reports_file_line_and_problem(text, problem):
    with pytest.raises(ParseError) as info:
        parse_templates(text, "bad.ih")
    assert str(info.value).startswith("bad.ih, ")
    assert problem in str(info.value)


@pytest.mark.parametrize(
    "text, problem",
    [
        ("TV1 4^4 parameters 1\n  default 0.5\n  P1 x 0 0 y 0 0\n  P2 x 1 0 y 0\n", "line 4: P2 needs 2 coefficients"),
        ("TV1 4^4 parameters 1\n  default 0.5 0.2\n", "line 2: TV1 has 1 parameters but 2 defaults"),
        ("TV1 4^4 parameters 0\n  default -\n  P1 x 0 y 0\n  P3 x 1 y 0\n", "line 4: expected vertex P2, got P3"),
        ("TV1 4^4 params 0\n", "line 1: expected 'TVn <topology> parameters <n>'"),
    ],
)
def test_parameterization_parser_reports_file_line_and_problem(text, problem):
    with pytest.raises(ParseError) as info:
        parse_parameterizations(text, "bad.tv")
    assert str(info.value).startswith("bad.tv, ") and problem in str(info.value)


def test_stored_properties_match_recomputation():
    """properties.tsv is generated; recompute every row and compare."""
    stored = (data_dir() / "properties.tsv").read_text(encoding="utf-8")
    assert stored == properties_table_text()


def test_every_template_prints_in_the_file_format_and_parses_back():
    for ih, t in load_templates().items():
        again = parse_templates(t.text() + "\n", "printed.ih")[ih]
        assert (again.topology, again.symbol, again.marked, again.parameterization) == (
            t.topology, t.symbol, t.marked, t.parameterization
        )
        assert (again.colouring_text, again.aspects, again.rules, again.edge_offset, again.notes) == (
            t.colouring_text, t.aspects, t.rules, t.edge_offset, t.notes
        )
