"""The vertex-species search (§4.1, exercises 4.8-4.11)."""

from __future__ import annotations

from fractions import Fraction

import pytest

import tilekit
from tilekit.errors import ParameterError
from tilekit.plugins import get_search
from tilekit.plugins.archimedean import archimedean_tiling
from tilekit.plugins.archimedean.construct import vertex_types_in
from tilekit.plugins.archimedean.species import (
    SOLIDS,
    classify_sequence,
    spherical_solid,
    spherical_vertices,
)
from tilekit.regular.notation import (
    VertexType,
    euclidean_species,
    parse_vertex_type,
    types_of_species,
)

ARCHIMEDEAN = {"3^6", "4^4", "6^3", "3^4.6", "3^3.4^2", "3^2.4.3.4", "3.4.6.4", "3.6.3.6",
               "3.12^2", "4.6.12", "4.8^2"}


def test_counts_of_types_and_species():
    """Grünbaum & Shephard, Tilings and Patterns §2.1 (Table 2.1.1): there are 21 vertex
    types (arrangements of regular polygons round a point) in 17 species; Kaplan §4.1 and
    exercise 4.10. Of the species, 10 have three polygons (exercise 4.8), 4 four, 2 five, 1 six."""
    species = euclidean_species()
    types = [t for s in species for t in types_of_species(s)]
    assert len(species) == 17
    assert len(types) == 21
    assert len(set(types)) == 21
    assert [sum(1 for s in species if len(s) == k) for k in (3, 4, 5, 6)] == [10, 4, 2, 1]
    triples = {s for s in species if len(s) == 3}
    assert triples == {(3, 7, 42), (3, 8, 24), (3, 9, 18), (3, 10, 15), (3, 12, 12), (4, 5, 20),
                       (4, 6, 12), (4, 8, 8), (5, 5, 10), (6, 6, 6)}
    for t in types:
        assert t.excess == 0


@pytest.fixture(scope="module")
def results():
    """Every chunk's vertex_species rows (one per classified type), in chunk order."""
    search = get_search("vertex-species")
    params: dict = {}
    out = []
    for chunk in search.chunks(params):
        out.extend(search.run_chunk(params, chunk).rows["vertex_species"])
    return search, params, out


def _summary(search, params):
    """The run summary as the run layer builds it: summarize(JSON results) + summed counts."""
    results, counts = [], {}
    for chunk in search.chunks(params):
        out = search.run_chunk(params, chunk)
        results.extend(out.results)
        for k, v in out.counts.items():
            counts[k] = counts.get(k, 0) + v
    return {**search.summarize(params, results), **counts}


def test_exactly_eleven_survivors(results):
    """Only the 11 Archimedean types extend (Kaplan §4.1; G&S Theorem 2.1.3); each survivor is
    the Archimedean tiling built in construct.py, whose surrounded vertices all have that type;
    each of the 10 others is refuted by an exhausted builder search."""
    _, _, res = results
    eu = {r["vertex_type"]: r for r in res if r["geometry"] == "euclidean"}
    assert len(eu) == 21
    survivors = {k for k, r in eu.items() if r["status"] == "tiles"}
    assert survivors == ARCHIMEDEAN
    for name in survivors:
        t = archimedean_tiling(name)
        found = vertex_types_in(t.patch((-8.0, -8.0, 8.0, 8.0)), list(t.vertex_type.sizes), 7.0)
        assert set(found) == {name}
        assert eu[name]["tiles_per_unit"] == len(t.unit_prototile)
    for name, r in eu.items():
        if name not in survivors:
            assert r["status"] == "impossible"
            assert r["reason"].startswith("exhausted")
            assert r["reached_radius"] < r["search_radius"]


def test_summary(results):
    search, params, res = results
    s = _summary(search, params)
    assert sorted(s["survivors"]) == sorted(ARCHIMEDEAN)
    assert s["euclidean_types"] == 21 and s["euclidean_species"] == 17
    assert s["tiling_types"] == 11 and s["impossible_types"] == 10 and s["undecided_types"] == 0
    # the 11 types fall into 10 species (3^3.4^2 and 3^2.4.3.4 share one); species such as
    # 3^2.6^2 hold a type that tiles (3.6.3.6) and one that does not (3^2.6^2)
    assert s["tiling_species"] == 10
    eu = {r["vertex_type"]: r for r in res if r["geometry"] == "euclidean"}
    assert eu["3^2.6^2"]["status"] == "impossible" and eu["3^2.6^2"]["species_tiles"] is True
    assert eu["3.7.42"]["species_tiles"] is False


def test_spherical_types_give_the_solids(results):
    """Exercise 4.11: with angle sum < 2π a type lies on the sphere. Euler's formula gives a
    vertex-transitive polyhedron V = 4 / (2 - k + 2 Σ 1/p) vertices; this matches the published
    vertex counts of the 5 Platonic and 13 Archimedean solids (Cromwell, Polyhedra, 1997),
    of the n-prisms (2n) and n-antiprisms (2n); every solid's type is found by the search."""
    for name, (_, _, vertices) in SOLIDS.items():
        assert spherical_vertices(parse_vertex_type(name)) == vertices, name
    for n in range(3, 13):
        assert spherical_vertices(VertexType.of((4, 4, n))) == 2 * n
        assert spherical_vertices(VertexType.of((3, 3, 3, n))) == 2 * n
    _, _, res = results
    sph = {r["vertex_type"]: r for r in res if r["geometry"] == "spherical"}
    assert set(SOLIDS) <= set(sph)
    named = {k for k, r in sph.items() if r["status"] == "polyhedron"}
    assert {k for k in named if sph[k]["solid_class"] in ("platonic", "archimedean")} == set(SOLIDS)
    for k in named:
        assert sph[k]["euler_feasible"] is True
    # prisms 4^2.n for n = 3, 5..12 and antiprisms 3^3.n for n = 4..12 in the default range
    assert {k for k in named if sph[k]["solid_class"] == "prism"} == {
        str(VertexType.of((4, 4, n))) for n in range(3, 13) if n != 4}
    assert {k for k in named if sph[k]["solid_class"] == "antiprism"} == {
        str(VertexType.of((3, 3, 3, n))) for n in range(4, 13)}


def test_geometry_classes():
    """Angle sums: 3^5 < 2π (icosahedron), 3^6 = 2π, 3^7 and 7^3 > 2π (hyperbolic)."""
    assert parse_vertex_type("3^5").geometry == "spherical"
    assert parse_vertex_type("3^6").geometry == "euclidean"
    assert parse_vertex_type("7^3").geometry == "hyperbolic"
    assert parse_vertex_type("4^5").geometry == "hyperbolic"
    assert parse_vertex_type("3^5").excess == Fraction(-1, 3)
    assert classify_sequence(parse_vertex_type("7^3"))["status"] == "hyperbolic"
    assert spherical_solid(parse_vertex_type("5.6^2")) == ("truncated icosahedron", "archimedean")
    assert spherical_solid(parse_vertex_type("3.3.5")) is None
    with pytest.raises(ParameterError):
        spherical_vertices(parse_vertex_type("3^6"))


def test_results_bounded_enumeration(results):
    """The documented bounds: spherical types with sides <= 12, hyperbolic ones with sides <= 6,
    3 <= k <= 6. Every type appears once."""
    _, _, res = results
    names = [r["vertex_type"] for r in res]
    assert len(names) == len(set(names))
    for r in res:
        vt = parse_vertex_type(r["vertex_type"])
        assert 3 <= len(vt.polygons) <= 6
        if r["geometry"] == "spherical":
            assert max(vt.polygons) <= 12
        if r["geometry"] == "hyperbolic":
            assert max(vt.polygons) <= 6


def test_records_for_the_catalogue(results):
    """Chunks yield catalogue records only for the types that tile (issue: impossible,
    spherical and hyperbolic types are not tilings); every type is a vertex_species row."""
    search, params, _ = results
    chunk = {"geometry": "euclidean", "species": [3, 3, 3, 4, 4]}
    out = search.run_chunk(params, chunk)
    assert {r["vertex_type"] for r in out.rows["vertex_species"]} == {"3^3.4^2", "3^2.4.3.4"}
    assert {r.name for r in out.records} == {"3^3.4^2", "3^2.4.3.4"}
    for rec in out.records:
        assert rec.properties["species"] == "3^3.4^2"
        assert rec.properties["status"] == "tiles"
        assert rec.properties["kind"] == "tiling"
    out = search.run_chunk(params, {"geometry": "euclidean", "species": [3, 7, 42]})
    assert out.records == []
    (row,) = out.rows["vertex_species"]
    assert row["vertex_type"] == "3.7.42" and row["status"] == "impossible"
    out = search.run_chunk(params, {"geometry": "non-euclidean", "k": 3, "max_sides": 12,
                                    "hyperbolic_max_sides": 6})
    assert out.records == [] and len(out.rows["vertex_species"]) > 10


def test_bad_parameters():
    search = get_search("vertex-species")
    with pytest.raises(ParameterError, match="radius"):
        search.chunks({"radius": -1.0})
    with pytest.raises(ParameterError, match="max_sides"):
        search.chunks({"max_sides": 2})
    # the case: accepted before, then ran out of memory; now refused before any run
    from tilekit.search import validate_params

    with pytest.raises(ParameterError, match="max_sides.*from 3 to 24"):
        validate_params(search, {"max_sides": 50, "hyperbolic_max_sides": 20})


def test_search_through_the_catalogue(tmp_path):
    """`tilekit search vertex-species` stores a run; `list --where species=...` finds the types."""
    from click.testing import CliRunner

    from tilekit.cli import cli

    url = f"sqlite:///{tmp_path / 'cat.db'}"
    runner = CliRunner()
    res = runner.invoke(cli, ["--catalogue", url, "search", "vertex-species"])
    assert res.exit_code == 0, res.output
    res = runner.invoke(cli, ["--catalogue", url, "list", "--family", "archimedean",
                              "--where", "species=3^3.4^2", "--format", "json"])
    assert res.exit_code == 0, res.output
    import json

    rows = json.loads(res.output)
    assert {r["name"] for r in rows} == {"3^3.4^2", "3^2.4.3.4"}
    # every classified type is a row of the search's own table, not an archimedean tiling
    res = runner.invoke(cli, ["--catalogue", url, "list", "--family", "vertex-species",
                              "--where", "status=impossible", "--format", "json"])
    assert len(json.loads(res.output)) == 10
    res = runner.invoke(cli, ["--catalogue", url, "list", "--family", "archimedean",
                              "--where", "status=impossible", "--count"])
    assert res.output.strip() == "0"
    res = runner.invoke(cli, ["--catalogue", url, "list", "--family", "vertex-species",
                              "--where", "geometry=spherical", "--where", "status=polyhedron", "--count"])
    assert int(res.output) >= 18 + 9 + 9  # the 18 solids, prisms 4^2.n and antiprisms 3^3.n
    res = runner.invoke(cli, ["--catalogue", url, "list", "--family", "archimedean", "--count"])
    assert res.output.strip() == "12"  # the 11 Archimedean tilings, 3^4.6 in both hands
    res = runner.invoke(cli, ["--catalogue", url, "runs"])
    assert res.exit_code == 0 and "vertex-species" in res.output
    # the README's Python example works after the search (it failed with a KeyError before)
    cat = tilekit.open_catalogue(url)
    for entry in cat.query(family="archimedean", where=["polygons=12"]):
        assert entry.properties["symmetry_group"]
    cat.close()
