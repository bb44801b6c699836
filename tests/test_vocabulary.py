"""The shared property vocabulary (issue 26): ``sides``, ``aperiodic`` ... across every family,
the old names as aliases, ``tilekit keys``, and errors for keys a family does not have.

Counts are checked twice: against published figures (cited at each test) and against the
families' own records, counted here in Python from what the plugins ship."""

from __future__ import annotations

import json
import re

import pytest
from cliutil import assert_one_line_error

from tilekit.catalogue.vocabulary import (
    KEY_ALIASES,
    SHARED_KEYS,
    canonical_key,
    normalise_properties,
)
from tilekit.plugins import catalogue_records, get_plugin_manager


def curved_isohedral_records() -> list:
    from tilekit.plugins.curved import isohedral_records

    return isohedral_records()


def curved_laves_records() -> list:
    """The curved family's Laves records: the Wythoffian duals and the vertex-star tilings' duals."""
    from tilekit.plugins.curved import laves_records, star_laves_records

    return laves_records() + star_laves_records()


@pytest.fixture(scope="module")
def cli(tmp_path_factory):
    from cliutil import CatalogueCLI

    return CatalogueCLI(f"sqlite:///{tmp_path_factory.mktemp('vocab') / 'cli.sqlite'}")


@pytest.fixture(scope="module")
def records():
    return [r for r in catalogue_records(get_plugin_manager())]


def names(cli, *args: str) -> set[str]:
    r = cli.run("list", "--format", "json", *args)
    assert r.exit_code == 0, r.output
    return {e["name"] for e in json.loads(r.stdout)} if r.stdout.strip() else set()


def where(*filters: str) -> list[str]:
    return [arg for f in filters for arg in ("--where", f)]


def expand(vertex_type: str) -> list[int]:
    """'3^4.6' -> [3, 3, 3, 3, 6]: the polygons round a vertex, read from the symbol."""
    out: list[int] = []
    for part in vertex_type.strip("[]").split("."):
        base, _, power = part.partition("^")
        out += [int(base)] * int(power or 1)
    return out


# ------------------------------------------------------------------ the vocabulary itself


def test_aliases_name_shared_keys_only_once():
    shared = {k.name for k in SHARED_KEYS}
    assert set(KEY_ALIASES.values()) <= shared and not set(KEY_ALIASES) & shared
    assert canonical_key("polygons") == canonical_key("edges") == canonical_key("tile_vertices") == "sides"
    assert canonical_key("known_aperiodic") == "aperiodic" and canonical_key("cells") == "cells"


def test_normalise_properties_renames_aliases_and_keeps_the_shared_value():
    assert normalise_properties({"edges": 6, "ih": 1}) == {"sides": [6], "ih": 1}
    assert normalise_properties({"polygons": [12, 3, 3]}) == {"sides": [3, 12]}
    # a catalogue refreshed from an older installation holds both: the shared name wins
    assert normalise_properties({"polygons": [4], "sides": [6]}) == {"sides": [6]}
    # a periodic tiling's prototiles are not an aperiodic set; unknown stays unknown
    assert normalise_properties({"periodic": True})["aperiodic"] is False
    assert "aperiodic" not in normalise_properties({"periodic": None})
    assert normalise_properties({"known_aperiodic": True, "periodic": False}) == {"aperiodic": True,
                                                                                 "periodic": False}


# ------------------------------------------------------------------ sides across families


def test_every_family_fills_sides(cli, records):
    """Every shipped record has ``sides``; ``--where sides=N`` over all families equals the
    records counted here, for every N that occurs, and each old name finds the same tilings."""
    by_n: dict[int, set[str]] = {}
    for rec in records:
        sides = normalise_properties(rec.properties)["sides"]
        assert sides and all(isinstance(s, int) and s >= 3 for s in sides), rec.name
        for s in sides:
            by_n.setdefault(s, set()).add(rec.name)
    assert {r.family for r in records} >= {"archimedean", "laves", "isohedral", "polyomino", "substitution",
                                          "wang", "quasiperiodic"}
    for n, expected in by_n.items():
        assert names(cli, *where(f"sides={n}")) == expected, n
    assert names(cli, *where("polygons=6")) == names(cli, *where("edges=6")) == by_n[6]
    assert names(cli, *where("tile_vertices=5")) == by_n[5]


def test_isohedral_sides_follow_the_topological_types(cli, records):
    """Grünbaum and Shephard number the 93 isohedral types by topological type (Tilings and
    Patterns, 1987, §6.2; Kaplan §5.2 names the eleven types by their Laves tilings): IH1-IH20
    are [3^6] (hexagons), IH21-IH29 [3^4.6], [3^3.4^2], [3^2.4.3.4] (pentagons), IH30-IH37
    [3.4.6.4], [3.6.3.6] and IH41-IH76 [4^4] (quadrilaterals), IH38-IH40 [3.12^2] and IH77-IH93
    [4.6.12], [4.8^2], [6^3] (triangles): so 20, 9, 44 and 20 types have 6, 5, 4 and 3 tiling
    vertices."""
    published = {6: 20, 5: 9, 4: 44, 3: 20}
    iso = [r for r in records if r.family == "isohedral"]
    assert len(iso) == 93
    for n, count in published.items():
        assert cli.count("isohedral", f"sides={n}") == count
        assert cli.count("isohedral", f"edges={n}") == count  # the old name
        # the family's own data: the tile's vertex count is the length of its topology
        assert sum(1 for r in iso if len(expand(r.properties["topology"])) == n) == count
    ranges = {6: [*range(1, 21)], 5: [*range(21, 30)], 4: [*range(30, 38), *range(41, 77)],
              3: [*range(38, 41), *range(77, 94)]}
    for n, ihs in ranges.items():
        assert names(cli, "--family", "isohedral", *where(f"sides={n}")) == {f"IH{i}" for i in ihs}


def test_isohedral_types_cover_the_17_wallpaper_groups(cli):
    """Every one of the 17 wallpaper groups is the group of some isohedral type (Grünbaum and
    Shephard, Tilings and Patterns §6.2): ``keys`` lists them through their entries."""
    r = cli.run("list", "--family", "isohedral", "--format", "json")
    groups = {e["wallpaper_group"] for e in json.loads(r.stdout)}
    assert len(groups) == 17
    assert cli.count("isohedral", "wallpaper_group=p6m") == cli.count("isohedral", "orbifold=*632") > 0


# The eleven Archimedean tilings, as Kaplan §4.2 (Figure 4.3) lists them; 3^4.6 comes in two hands.
ARCHIMEDEAN = ["3^6", "4^4", "6^3", "3^4.6", "3^3.4^2", "3^2.4.3.4", "3.4.6.4", "3.6.3.6", "3.12^2",
               "4.6.12", "4.8^2"]


@pytest.mark.parametrize("n", [3, 4, 6, 8, 12])
def test_archimedean_and_laves_counts(cli, n):
    """Archimedean tilings with an n-gon: counted over Kaplan's list (the chiral 3^4.6 twice,
    once per hand); a Laves tile has as many sides as its Archimedean dual has polygons at a
    vertex (§4.2)."""
    hands = {"3^4.6": 2}
    with_n = sum(hands.get(vt, 1) for vt in ARCHIMEDEAN if n in expand(vt))
    assert cli.count("archimedean", f"sides={n}") == cli.count("archimedean", f"polygons={n}") == with_n
    laves_n = sum(hands.get(vt, 1) for vt in ARCHIMEDEAN if len(expand(vt)) == n)
    assert cli.count("laves", f"sides={n}") == cli.count("laves", f"tile_vertices={n}") == laves_n
    assert {3: 8, 4: 6, 6: 6, 8: 1, 12: 2}[n] == with_n  # e.g. six contain a hexagon, two a 12-gon


# ------------------------------------------------------------------ aperiodic across families


def test_aperiodic_across_families(cli, records):
    """``aperiodic=true`` finds the aperiodic sets of every family: the Penrose and Ammann
    substitution tilings, the hat and the Spectre (Smith, Myers, Kaplan, Goodman-Strauss 2023),
    and the Jeandel-Rao, Kari and Culik Wang sets (FACTS.md), which the old Wang-only name
    ``known_aperiodic`` missed. The families' own records say the same."""
    expected = {r.name for r in records if normalise_properties(r.properties).get("aperiodic") is True}
    assert {"jeandel-rao-11", "kari-14", "culik-13", "hat", "spectre", "penrose-p3", "penrose-p2"} <= expected
    assert names(cli, *where("aperiodic=true")) == expected
    assert names(cli, *where("known_aperiodic=true")) == expected
    # no periodic tiling is by an aperiodic set, and every periodic record says so
    assert names(cli, *where("aperiodic=true", "periodic=true")) == set()
    periodic = {r.name for r in records if r.properties.get("periodic") is True}
    assert periodic <= names(cli, *where("aperiodic=false"))
    # the multigrid's unmarked rhombs tile periodically on their own: not an aperiodic set
    assert cli.count("quasiperiodic", "aperiodic=false") == sum(1 for rec in records if rec.family == "quasiperiodic")


def test_prototiles_and_transitivity_aliases(cli):
    assert names(cli, *where("prototiles=3", "periodic=true")) == names(cli, *where("k_hedral=3", "periodic=true"))
    assert names(cli, *where("transitivity=2")) == names(cli, *where("k_isohedral=2"))


def test_order_by_an_alias(cli):
    r = cli.run("list", "--family", "laves", "--order", "-tile_vertices", "--format", "json")
    sides = [e["sides"][0] for e in json.loads(r.stdout)]
    assert sides == sorted(sides, reverse=True) and sides[0] == 6


# ------------------------------------------------------------------ errors and `tilekit keys`


def test_a_key_of_another_family_is_an_error_naming_it(cli):
    r = cli.run("list", "--family", "wang", "--where", "edge_kinds=JJ")
    assert_one_line_error(r, "family 'wang' has no property 'edge_kinds'; curved, curved-isohedral, isohedral have it")
    r = cli.run("list", "--family", "archimedean", "--where", "cells=4")
    assert_one_line_error(r, "polyomino has it")
    assert_one_line_error(cli.run("list", "--where", "sidez=4"), "did you mean 'sides'")


def test_keys_lists_key_type_families_and_example(cli):
    r = cli.run("keys", "--format", "json")
    assert r.exit_code == 0, r.output
    infos = {i["key"]: i for i in json.loads(r.stdout)}
    sides = infos["sides"]
    assert sides["type"] == "list of int" and sides["example"] == "sides=6"
    assert set(sides["families"]) >= {"archimedean", "laves", "isohedral", "polyomino", "substitution", "wang",
                                      "quasiperiodic"}
    assert sides["aliases"] == ["polygons", "edges", "tile_vertices"]
    assert infos["aperiodic"]["type"] == "bool" and "known_aperiodic" in infos["aperiodic"]["aliases"]
    # the planar types, the curved ones on {p,q} (tilekit.plugins.curved.isohedral_records) and the
    # curved family's Laves tilings (laves_records, star_laves_records) share the key
    assert infos["edge_kinds"]["families"] == ["curved", "curved-isohedral", "isohedral"]
    assert infos["edge_kinds"]["tilings"] == 93 + len(curved_isohedral_records()) + len(curved_laves_records())
    # every example runs as a filter
    for info in infos.values():
        r = cli.run("list", "--count", "--where", info["example"])
        assert r.exit_code == 0, (info["example"], r.output)
    table = cli.run("keys", "isohedral").stdout.splitlines()
    assert re.split(r"\s{2,}", table[0]) == ["KEY", "TYPE", "FAMILIES", "TILINGS", "EXAMPLE", "ALIASES"]
    assert any(line.startswith("ih ") for line in table) and not any(line.startswith("cells ") for line in table)


def test_keys_of_a_result_table_family_are_its_columns(cli):
    r = cli.run("keys", "vertex-species", "--format", "json")
    assert r.exit_code == 0, r.output
    keys = {i["key"]: i["type"] for i in json.loads(r.stdout)}
    assert keys["polygons"] == "json" and keys["valence"] == "int" and keys["species_tiles"] == "bool"
    assert cli.run("list", "--family", "vertex-species", "--count", "--where", "valence>=3").exit_code == 0
    assert_one_line_error(cli.run("keys", "no-such-family"), "unknown family 'no-such-family'")


def test_keys_aliases_and_symbols_on_every_database(db_url):
    """The same vocabulary, key table and normalised filters on SQLite and PostgreSQL."""
    from tilekit import open_catalogue
    from tilekit.errors import ParameterError

    cat = open_catalogue(db_url)
    try:
        infos = {i.key: i for i in cat.key_table()}
        assert infos["sides"].type == "list of int" and infos["aperiodic"].type == "bool"
        assert infos["edge_kinds"].tilings == 93 + len(curved_isohedral_records()) + len(curved_laves_records())
        assert infos["edge_kinds"].families == ("curved", "curved-isohedral", "isohedral")
        assert cat.count_matching(where=["sides=6"]) == cat.count_matching(where=["polygons=6"]) > 20
        assert cat.count_matching(family="isohedral", where=["edges=6"]) == 20
        assert [e.name for e in cat.query(where=["vertex_type=4.3.4.6"])] == ["3.4.6.4", "[3.4.6.4]"]
        assert [e.name for e in cat.query(family="isohedral", limit=3, offset=8)] == ["IH9", "IH10", "IH11"]
        assert cat.get("[c+b+a+a-b-c-; c-a+b+]").name == "IH16"
        with pytest.raises(ParameterError, match="curved, curved-isohedral, isohedral have it"):
            cat.query(family="wang", where=["edge_kinds=JJ"])
    finally:
        cat.close()
