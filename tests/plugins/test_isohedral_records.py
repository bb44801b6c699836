"""Catalogue records of the isohedral family, the family hook and the command line."""

from __future__ import annotations

import json
import time

import pytest
from click.testing import CliRunner

from tilekit.cli import cli
from tilekit.plugins import catalogue_records, families, get_family
from tilekit.plugins.isohedral.records import records, type_properties
from tilekit.plugins.isohedral.templates import load_templates

KEYS = {
    "ih", "topology", "marked", "periodic", "k_hedral", "k_isohedral", "edge_kinds",
    "j_edges", "u_edges", "s_edges", "i_edges", "incidence_symbol", "canonical_symbol", "symmetry_group",
}
UNMARKED_KEYS = KEYS | {"parameters", "aspects", "colours", "perfect_colouring"}


def test_93_records_named_ih1_to_ih93_with_aliases():
    recs = records()
    assert [r.name for r in recs] == [f"IH{i}" for i in range(1, 94)]
    ih16 = recs[15]
    assert ih16.family == "isohedral" and ih16.spec == {"ih": 16}
    assert set(ih16.aliases) == {"ih16", "IH016"}


def test_record_properties():
    for r in records():
        props = r.properties
        assert KEYS <= set(props), r.name
        if not props["marked"]:
            assert UNMARKED_KEYS <= set(props), r.name
        for v in props.values():
            assert isinstance(v, str | int | float | bool)
        n = props["j_edges"] + props["u_edges"] + props["s_edges"] + props["i_edges"]
        assert n == len(props["edge_kinds"])
        assert props["k_hedral"] == 1 and props["k_isohedral"] == 1 and props["periodic"] is True
    p16 = type_properties(16)
    assert p16["incidence_symbol"] == "[a+b+c+c-b-a-; a-c+b+]"
    assert p16["edge_kinds"] == "IJJJJI" and p16["aspects"] == 3 and p16["parameters"] == 1
    assert p16["symmetry_group"] == "3*3" and p16["colours"] == 3
    assert "heesch_type" not in p16 and type_properties(1)["heesch_type"] == "TTTTTT"
    # §5.3.2: 21 types have only I edges; 12 of them are the marked types
    all_i = [ih for ih in range(1, 94) if set(type_properties(ih)["edge_kinds"]) == {"I"}]
    assert len(all_i) == 21
    assert sum(1 for ih in all_i if type_properties(ih)["marked"]) == 12


def test_records_are_cheap():
    type_properties.cache_clear()
    start = time.perf_counter()
    records()
    assert time.perf_counter() - start < 1.0


def test_family_and_records_through_the_plugin_manager():
    fam = families()["isohedral"]
    assert get_family("isohedral") is not None and fam.summary
    mine = [r for r in catalogue_records() if r.family == "isohedral"]
    assert len(mine) == 93
    t = fam.from_spec({"ih": 16, "params": [0.3]})
    assert t.name == "IH16" and t.params == (0.3,)
    marked = fam.from_spec({"ih": 48})
    assert marked.name == "IH48" and marked.prototiles[0].marking
    region = (0, 0, 6, 6)
    assert marked.patch(region).validate(region)


def test_every_marked_type_draws_as_a_valid_laves_tiling():
    for ih, t in load_templates().items():
        if t.marked:
            tiling = get_family("isohedral").from_spec({"ih": ih})
            region = (0, 0, 5, 5)
            assert tiling.patch(region).validate(region), ih
            assert tiling.spec() == {"ih": ih}


@pytest.fixture()
def runner_args(tmp_path):
    return ["--catalogue", f"sqlite:///{tmp_path / 'cat.db'}"]


def test_cli_render_show_and_list(tmp_path, runner_args):
    runner = CliRunner()
    out = tmp_path / "f.svg"
    res = runner.invoke(cli, runner_args + ["render", "IH16", "--param", "0.3", "--edge", "b=0,0:0.3,0.2:1,0", "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert out.read_text().lstrip().startswith("<")
    res = runner.invoke(cli, runner_args + ["show", "IH16"])
    assert res.exit_code == 0, res.output
    assert "parameterization TV14" in res.output and "3 <- 1; 6" in res.output
    res = runner.invoke(
        cli, runner_args + ["list", "--family", "isohedral", "--where", "topology=3^6", "--where", "edge_kinds~S", "--format", "json"]
    )
    assert res.exit_code == 0, res.output
    names = {row["name"] for row in json.loads(res.output)}
    expected = {
        f"IH{ih}" for ih, t in load_templates().items()
        if t.topology == "3^6" and "S" in type_properties(ih)["edge_kinds"]
    }
    assert names == expected and "IH8" in names


def test_cli_reports_bad_edge_on_one_line(tmp_path, runner_args):
    res = CliRunner().invoke(cli, runner_args + ["render", "IH16", "--edge", "q=0,0:1,0", "-o", str(tmp_path / "x.svg")])
    assert res.exit_code == 2
    assert "no edge label 'q'" in res.output and "Traceback" not in res.output


@pytest.mark.slow
def test_all_i_enumeration_gives_the_9_unmarked_and_the_12_marked_types():
    """§5.3.1: 21 types have only I edges; 12 need marked tiles (FACTS.md numbers them).

    The enumeration of marked.all_i_types (from the Laves tiles, first principles) must
    return exactly the 9 all-I types of Appendix A and the 12 marked symbols of the data,
    topology by topology.
    """
    from tilekit.plugins.isohedral.marked import all_i_types

    expected: dict[str, set[str]] = {}
    for t in load_templates().values():
        if t.symbol is not None and set(t.symbol.edge_kinds()) == {"I"}:
            expected.setdefault(t.topology, set()).add(str(t.symbol.canonical()))
    assert sum(len(v) for v in expected.values()) == 21
    for topology in {t.topology for t in load_templates().values()}:
        found = {str(s) for s in all_i_types(topology)}
        assert found == expected.get(topology, set()), topology


def test_marked_tilings_agree_with_the_geometric_symmetry_finder():
    from tilekit import symmetry
    from tilekit.plugins.isohedral.analysis import wallpaper_group
    from tilekit.plugins.isohedral.marked import MarkedTiling

    for ih, t in load_templates().items():
        if t.marked:
            tiling = MarkedTiling(ih)
            assert symmetry.wallpaper_group(tiling).orbifold == wallpaper_group(tiling) == type_properties(ih)["symmetry_group"]
    assert type_properties(19)["wallpaper_group"] == "p3m1"  # as listed for IH19 (gist TriHydera/63e7...)


# Published data on the marked types. The only public table reachable here that covers any
# of them is the list "Isohedral Tiling | Wallpaper Group | Tile" (gist by andybak,
# https://gist.github.com/andybak/51c01feaecb233e0500851a1bb5ee30b, copied in
# https://gist.github.com/TriHydera/63e704512f58605461c0af036fc49159); its stored copy
# shows rows IH1..IH41 and so covers IH19 and IH35 only. It gives the wallpaper group and
# the tile polygon (the number of edges, which fixes the topology's length). No published
# incidence symbol of a marked type was found (see catalogue/isohedral/README.md).
PUBLISHED_MARKED = {
    19: ("p3m1", "Hexagon"),
    35: ("p3m1", "Quadrilateral"),
}
POLYGON_EDGES = {"Triangle": 3, "Quadrilateral": 4, "Pentagon": 5, "Hexagon": 6}


@pytest.mark.parametrize("ih", sorted(PUBLISHED_MARKED))
def test_marked_types_match_the_published_list(ih):
    """Wallpaper group and tile polygon of IH19 and IH35 as listed in the gist above."""
    group, polygon = PUBLISHED_MARKED[ih]
    props = type_properties(ih)
    assert props["marked"] is True
    assert props["wallpaper_group"] == group
    assert props["sides"] == POLYGON_EDGES[polygon]
    # the stored value is the computed one, not a copy of the list
    from tilekit.plugins.isohedral.records import computed_properties

    assert computed_properties(ih)["wallpaper_group"] == group


def test_marked_tiles_are_fixed_exactly_by_their_symbol_symmetries():
    """In an isohedral tiling the stabiliser of a tile is the tile symmetry group the symbol
    records (§5.3.1). For each marked type, generate the tiling group from the hops and the
    symbol's tile symmetries on the Laves tile, and collect the elements that map the tile
    onto itself: there must be exactly as many as the symbol has symmetries. This catches a
    symbol whose start is rotated against its topology: read from a 6-valent vertex of
    3.6.3.6, IH35's mirror lies on the long diagonal, the edge reflections add the short
    one, and the tile would be fixed by four isometries instead of two."""
    import numpy as np

    from tilekit.geometry import Affine
    from tilekit.plugins.isohedral.engine import HopEngine, laves_polygon

    for ih, t in load_templates().items():
        if not t.marked:
            continue
        assert t.symbol is not None
        verts = laves_polygon(t.topology)
        engine = HopEngine(t.symbol, verts)
        sym = engine.tile_symmetries()
        gens = list(engine.hops) + list(sym)
        reach = 4 * float(np.ptp(verts, axis=0).max())
        centre = verts.mean(axis=0)
        seen = {tuple(np.round(np.eye(3)[:2].ravel(), 6))}
        frontier = [np.eye(3)]
        stabiliser = 0
        for _ in range(8):
            nxt = []
            for m in frontier:
                img = Affine.apply(m, verts)
                if np.linalg.norm(img[:, None] - verts[None], axis=2).min(axis=1).max() < 1e-6:
                    stabiliser += 1
                for g in gens:
                    h = m @ g
                    key = tuple(np.round(h[:2].ravel(), 6) + 0.0)
                    if key in seen or np.hypot(*(Affine.apply(h, centre[None])[0] - centre)) > reach:
                        continue
                    seen.add(key)
                    nxt.append(h)
            frontier = nxt
        assert stabiliser == len(sym), (ih, str(t.symbol), stabiliser, len(sym))
