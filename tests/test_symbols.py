"""Queries by meaning, not by spelling (issue 26): an equivalent incidence symbol, vertex type,
polyomino code or D-symbol finds the stored tiling in ``show`` and in ``--where`` filters;
names sort naturally; the names people use (penrose, P3, kites and darts, einstein, both hands
of the snub hexagonal tiling) are aliases.

Equivalent spellings are made here independently of the families' own normalisers: rotations
and reflections of a vertex sequence, the eight orientations of a polyomino's rows, a random
renumbering of a D-symbol's chambers, consistent relabelling of an incidence symbol."""

from __future__ import annotations

import json
import random
import re

import pytest
from cliutil import assert_one_line_error


@pytest.fixture(scope="module")
def cli(tmp_path_factory):
    from cliutil import CatalogueCLI

    return CatalogueCLI(f"sqlite:///{tmp_path_factory.mktemp('symbols') / 'cli.sqlite'}")


@pytest.fixture(scope="module")
def cat(cli):
    from tilekit import open_catalogue

    cli.run("list", "--count")  # seeds
    c = open_catalogue(cli.url)
    yield c
    c.close()


def shown_name(cli, name: str) -> str:
    r = cli.run("show", name)
    assert r.exit_code == 0, (name, r.output)
    return r.stdout.splitlines()[0].removeprefix("name: ")


def listed(cli, *args: str) -> list[str]:
    r = cli.run("list", "--format", "json", *args)
    assert r.exit_code == 0, r.output
    return [e["name"] for e in json.loads(r.stdout)] if r.stdout.strip() else []


# ------------------------------------------------------------------ incidence symbols


def relabel(symbol: str, rng: random.Random) -> str:
    """The same incidence symbol with its edge letters renamed by a random permutation (the
    letters are names; what they say is which edges are alike, §5.2)."""
    letters = sorted(set(re.findall(r"[a-z]", symbol)))
    shuffled = letters[:]
    rng.shuffle(shuffled)
    table = str.maketrans(dict(zip(letters, shuffled)))
    return symbol.translate(table)


def test_issue_example_finds_ih16(cli):
    assert shown_name(cli, "[a+b+c+c-b-a-; a-c+b+]") == "IH16"
    # a-> c, c -> a: the same type (Kaplan §5.2, Figure 5.4's IH16)
    assert shown_name(cli, "[c+b+a+a-b-c-; c-a+b+]") == "IH16"
    assert listed(cli, "--family", "isohedral", "--where", "incidence_symbol=[c+b+a+a-b-c-; c-a+b+]") == ["IH16"]
    # the symbol is topological: in the hyperbolic plane the hexagonal duals of the vertex-star
    # tilings 3.6.3.6.p.6 (and kin) carry it too, and only they
    r = cli.run("list", "--format", "json", "--where", "incidence_symbol=[c+b+a+a-b-c-; c-a+b+]")
    others = [e for e in json.loads(r.stdout) if e["name"] != "IH16"]
    assert others and all((e["family"], e["geometry"], e["laves"], e["sides"]) == ("curved", "hyperbolic", True, [6])
                          for e in others), others


def test_every_relabelled_symbol_finds_its_type(cat):
    """For each of the 81 types with a symbol: a renamed symbol, with its topology, names the
    type; the filter on the symbol finds every type sharing it and nothing else."""
    rng = random.Random(26)
    entries = [e for e in cat.query(family="isohedral") if "incidence_symbol" in e.properties]
    assert len(entries) == 93
    for e in entries:
        other = relabel(e.properties["incidence_symbol"], rng)
        assert cat.get(f"{e.properties['topology']} {other}").name == e.name
        same = {f.name for f in entries if f.properties["canonical_symbol"] == e.properties["canonical_symbol"]}
        assert {f.name for f in cat.query(family="isohedral", where=[f"incidence_symbol={other}"])} == same


def test_a_symbol_of_several_topologies_asks_for_the_topology(cli, cat):
    """Exercise 5.6: types that differ in topology can share an incidence symbol; the bare
    symbol is then an error naming them, and the topology picks one."""
    by_symbol: dict[str, list] = {}
    for e in cat.query(family="isohedral"):
        by_symbol.setdefault(e.properties["canonical_symbol"], []).append(e)
    shared = [v for v in by_symbol.values() if len({e.properties["topology"] for e in v}) > 1]
    assert shared, "exercise 5.6 says such types exist"
    first, second = shared[0][:2]
    r = cli.run("show", first.properties["incidence_symbol"])
    assert_one_line_error(r, "give the topology too")
    assert first.name in r.stderr and second.name in r.stderr
    assert shown_name(cli, f"{second.properties['topology']} {first.properties['incidence_symbol']}") \
        in {e.name for e in shared[0] if e.properties["topology"] == second.properties["topology"]}


# ------------------------------------------------------------------ vertex types


def expand(vertex_type: str) -> list[int]:
    out: list[int] = []
    for part in vertex_type.strip("[]()").split("."):
        base, _, power = part.partition("^")
        out += [int(base)] * int(power or 1)
    return out


def spellings(seq: list[int]) -> set[str]:
    """Every rotation and reflection of the cyclic sequence, dotted."""
    out = set()
    for s in (seq, seq[::-1]):
        for i in range(len(s)):
            out.add(".".join(map(str, s[i:] + s[:i])))
    return out


def test_vertex_types_in_any_rotation_or_reflection(cli, cat):
    for e in cat.query(family="archimedean"):
        vt = e.properties["vertex_type"]
        expected = set(listed(cli, "--where", f"vertex_type={vt}"))
        assert e.name in expected
        for text in spellings(expand(vt)):
            assert set(listed(cli, "--where", f"vertex_type={text}")) == expected, text
            hand = e.name[-1] if e.name[-1] in "lr" else ""
            assert cat.get(f"({text}){hand}").name == e.name
            assert cat.get(f"[{text}]{hand}").family == "laves"
    assert shown_name(cli, "4.3.4.6") == "3.4.6.4" and shown_name(cli, "3.3.3.3.6") == "3^4.6l"
    assert shown_name(cli, "[6.3.3.3.3]r") == "[3^4.6]r"


# ------------------------------------------------------------------ polyomino codes


def orientations(code: str) -> set[str]:
    """The eight images of a polyomino's rows under the square's symmetries."""
    grid = [list(row) for row in code.split("/")]
    out = set()
    for _ in range(4):
        grid = [list(row) for row in zip(*grid[::-1])]  # quarter turn
        for g in (grid, [row[::-1] for row in grid]):
            out.add("/".join("".join(row) for row in g))
    return out


def test_polyomino_codes_in_any_orientation(cli, cat):
    entries = cat.query(family=None, where=["family=polyomino"])
    assert len(entries) == 21
    for e in entries:
        code = e.properties["code"]
        for text in orientations(code):
            assert cat.get(text).name == e.name, text
            assert [x.name for x in cat.query(where=[f"code={text}"])] == [e.name]
    assert shown_name(cli, "x./xx/.x") == "S-tetromino"


# ------------------------------------------------------------------ D-symbols


def renumber(text: str, rng: random.Random) -> str:
    """The D-symbol text with its chambers numbered by a random permutation."""
    face, degree, s0, s1, s2 = ([int(v) for v in part.split(",")] for part in text.split("/"))
    n = len(face)
    p = list(range(n))
    rng.shuffle(p)
    new = [[0] * n for _ in range(5)]
    for i in range(n):
        new[0][p[i]], new[1][p[i]] = face[i], degree[i]
        for k, s in enumerate((s0, s1, s2)):
            new[2 + k][p[i]] = p[s[i]]
    return "/".join(",".join(map(str, col)) for col in new)


def test_d_symbols_with_chambers_renumbered(cli):
    """The 11 1-uniform tilings (Grünbaum and Shephard 2.1; OEIS A068599) from the k-uniform
    search: each found by its D-symbol numbered any way."""
    r = cli.run("search", "k-uniform", "--k", "1")
    assert r.exit_code == 0, r.output
    entries = json.loads(cli.run("list", "--family", "k-uniform", "--format", "json").stdout)
    assert len(entries) == 11
    rng = random.Random(5)
    for e in entries:
        other = renumber(e["dsymbol"], rng)
        # the Archimedean record of the same tiling carries the same D-symbol (Kaplan §4.1:
        # the 1-uniform tilings are the 11 Archimedean ones): either is the tiling shown
        same = listed(cli, "--where", f"dsymbol={other}")
        assert e["name"] in same and len(same) >= 2, same  # snub hexagonal: both hands share one
        assert shown_name(cli, other) in same
        assert listed(cli, "--family", "k-uniform", "--where", f"dsymbol={other}") == [e["name"]]


# ------------------------------------------------------------------ names


@pytest.mark.parametrize(("alias", "name"), [
    ("penrose", "penrose-p3"), ("P3", "penrose-p3"), ("p3", "penrose-p3"), ("P2", "penrose-p2"),
    ("kites and darts", "penrose-p2"), ("einstein", "hat"), ("snub hexagonal", "3^4.6l"),
    ("snub hexagonal left", "3^4.6l"), ("snub hexagonal right", "3^4.6r"), ("right snub hexagonal", "3^4.6r"),
    ("floret pentagonal right", "[3^4.6]r"),
])
def test_names_people_use(cli, alias, name):
    assert shown_name(cli, alias) == name


def test_both_hands_of_the_snub_hexagonal_tiling(cli):
    assert listed(cli, "--text", "snub hexagonal") == ["3^4.6l", "3^4.6r"]


def test_names_sort_naturally(cli):
    iso = listed(cli, "--family", "isohedral")
    assert iso == [f"IH{i}" for i in range(1, 94)]
    assert listed(cli, "--family", "isohedral", "--order", "-name", "--limit", "3") == ["IH93", "IH92", "IH91"]
    grids = listed(cli, "--family", "quasiperiodic")
    assert grids.index("multigrid-5") < grids.index("multigrid-10")
    paged = [n for off in range(0, 93, 40) for n in listed(cli, "--family", "isohedral", "--limit", "40",
                                                           "--offset", str(off))]
    assert paged == iso


def test_polyomino_codes_in_the_result_table(cli):
    """``--family polyomino`` reads the search's result table: a code in any orientation finds
    its row there too (the 5 free tetrominoes, A000105(4) = 5)."""
    r = cli.run("search", "polyominoes", "--max-cells", "4")
    assert r.exit_code == 0, r.output
    rows = json.loads(cli.run("list", "--family", "polyomino", "--where", "cells=4", "--format", "json").stdout)
    assert len(rows) == 5
    for row in rows:
        for text in orientations(row["code"]):
            found = json.loads(cli.run("list", "--family", "polyomino", "--where", f"code={text}",
                                       "--format", "json").stdout)
            assert [f["code"] for f in found] == [row["code"]], text
