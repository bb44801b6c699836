"""The catalogue database: migrations, seeding, typed queries, lookups, export, runs, errors.

The records come from tests/data/testkit.py: the 11 Archimedean tilings with facts from
Grünbaum & Shephard, Tilings and Patterns §2.1 (vertex types and symmetry groups).
"""

from __future__ import annotations

import csv
import io
import json
import math
import sqlite3
import sys
from pathlib import Path

import pytest
import sqlalchemy as sa
from hypothesis import given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).parent / "data"))

import testkit  # noqa: E402

import tilekit  # noqa: E402
from tilekit.catalogue import (  # noqa: E402
    Filter,
    open_catalogue,
    open_reader,
    parse_filter,
    resolve_url,
)
from tilekit.errors import CatalogueError, NotFoundError, ParameterError, ParseError  # noqa: E402
from tilekit.models import METADATA  # noqa: E402
from tilekit.plugins import CatalogueRecord, ChunkResult  # noqa: E402

ALL = set(testkit.ARCHIMEDEAN)


def vertex_types() -> dict[str, tuple[int, ...]]:
    return {name: data[0] for name, data in testkit.ARCHIMEDEAN.items()}


@pytest.fixture
def pm(monkeypatch):
    return testkit.isolated_pm(monkeypatch, testkit.GridPlugin())


@pytest.fixture
def url(tmp_path):
    """A SQLite file: the tests that take it check SQLite-only things (files, WAL, locks)."""
    return f"sqlite:///{tmp_path / 'catalogue.sqlite'}"


@pytest.fixture
def cat(db_url, pm):
    """A seeded catalogue on each backend (SQLite, and PostgreSQL when a server is given)."""
    catalogue = open_catalogue(db_url, pm=pm)
    yield catalogue
    catalogue.close()


@pytest.fixture(params=["sqlite", "sqlite3 read path", "postgresql"])
def reading(request, tmp_path, pm):
    """What reads tilings: the seeded catalogue on each backend, and the same SQLite file read
    through the standard library's sqlite3 (tilekit.catalogue.reading.open_reader), which
    must answer every query alike."""
    if request.param == "postgresql":
        url = request.getfixturevalue("postgres_url")
    else:
        url = f"sqlite:///{tmp_path / 'catalogue.sqlite'}"
    catalogue = open_catalogue(url, pm=pm)
    if request.param == "sqlite3 read path":
        reader = open_reader(url, pm)
        assert reader is not None, "a catalogue just brought up to date is read without SQLAlchemy"
        yield reader
        reader.close()
    else:
        yield catalogue
    catalogue.close()


def names(entries) -> set[str]:
    return {e.name for e in entries}


# --------------------------------------------------------------------------- opening


def test_fresh_url_is_migrated_and_seeded_on_first_open(url, pm, tmp_path):
    cat = open_catalogue(url, pm=pm)
    tables = set(sa.inspect(cat.engine).get_table_names())
    assert {"tilings", "tiling_aliases", "tiling_properties", "runs", "run_chunks", "run_results",
            "alembic_version"} <= tables
    current, heads = cat.revisions()
    assert current == heads == {"0003"}
    assert cat.count() == 11  # the 11 Archimedean tilings (Grünbaum & Shephard §2.1)
    cat.close()
    # opening again neither duplicates nor re-seeds
    again = open_catalogue(url, pm=pm)
    assert again.count() == 11
    again.close()
    # WAL mode and a busy timeout, seen from an independent sqlite3 connection
    raw = sqlite3.connect(tmp_path / "catalogue.sqlite")
    assert raw.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
    raw.close()
    with open_catalogue(url, pm=pm) as c, c.engine.connect() as conn:
        assert conn.exec_driver_sql("PRAGMA busy_timeout").scalar() == 30000
        assert conn.exec_driver_sql("PRAGMA foreign_keys").scalar() == 1


def test_seed_false_leaves_catalogue_empty(url, pm):
    with open_catalogue(url, pm=pm, seed=False) as cat:
        assert cat.count() == 0
        assert cat.seed() == (11, 0)
        assert cat.seed() == (0, 0)


def test_downgrade_base_then_upgrade_head(cat):
    from alembic.autogenerate import compare_metadata
    from alembic.runtime.migration import MigrationContext

    cat.downgrade("base")
    assert set(sa.inspect(cat.engine).get_table_names()) <= {"alembic_version"}
    assert cat.revisions()[0] == set()
    cat.upgrade()
    assert cat.revisions()[0] == {"0003"}
    assert cat.count() == 0  # data went with the tables; the schema is back
    assert cat.seed() == (11, 0)
    # the migrated schema is exactly the models' schema (tables, columns, indexes, constraints)
    with cat.engine.connect() as conn:
        diff = compare_metadata(MigrationContext.configure(conn, opts={"compare_type": True}), METADATA)
    assert diff == []


def test_default_url_and_environment(monkeypatch, tmp_path):
    import platformdirs

    monkeypatch.delenv("TILEKIT_CATALOGUE", raising=False)
    expected = Path(platformdirs.user_data_dir("tilekit")) / "catalogue.sqlite"
    assert resolve_url() == f"sqlite:///{expected}"
    monkeypatch.setenv("TILEKIT_CATALOGUE", "postgresql://u@db.example/tilings")
    assert resolve_url() == "postgresql://u@db.example/tilings"
    assert resolve_url("sqlite:///x.db") == "sqlite:///x.db"  # the argument wins
    file_path = tmp_path / "plain.sqlite"
    assert resolve_url(file_path) == f"sqlite:///{file_path.resolve()}"


def test_environment_variable_selects_the_catalogue(monkeypatch, tmp_path, pm):
    target = tmp_path / "from_env.sqlite"
    monkeypatch.setenv("TILEKIT_CATALOGUE", str(target))
    with open_catalogue(pm=pm) as cat:
        assert cat.path == target.resolve()
        assert cat.count() == 11
    assert target.exists()


def test_corrupt_file_is_refused_and_left_untouched(tmp_path, pm):
    bad = tmp_path / "notes.sqlite"
    content = b"these are my notes, not a database\n" * 10
    bad.write_bytes(content)
    with pytest.raises(CatalogueError) as info:
        open_catalogue(f"sqlite:///{bad}", pm=pm)
    message = str(info.value)
    assert "not a SQLite database" in message and "\n" not in message
    assert bad.read_bytes() == content
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.sqlite"]  # no -wal/-shm either


def test_truncated_database_is_refused_without_damage(tmp_path, url, pm):
    with open_catalogue(url, pm=pm):
        pass
    path = tmp_path / "catalogue.sqlite"
    raw = path.read_bytes()
    broken = tmp_path / "broken.sqlite"
    broken.write_bytes(raw[:100] + b"\x00garbage" * 200)  # valid header, corrupt pages
    before = broken.read_bytes()
    with pytest.raises(CatalogueError) as info:
        open_catalogue(f"sqlite:///{broken}", pm=pm)
    assert "\n" not in str(info.value)
    assert broken.read_bytes() == before


@pytest.mark.parametrize(
    "bad_url, fragment",
    [
        ("nosuchdb://user@host/db", "cannot open catalogue"),
        ("sqlite:////definitely/not/a/dir/cat.sqlite", "does not exist"),
        ("postgresql+nosuchdriver://u@127.0.0.1:1/db", "cannot open catalogue"),
        ("://no-scheme", "not a database URL"),
    ],
)
def test_unreachable_or_invalid_urls_give_one_line_errors(bad_url, fragment, pm):
    with pytest.raises(CatalogueError) as info:
        open_catalogue(bad_url, pm=pm)
    assert fragment in str(info.value)
    assert "\n" not in str(info.value)


def test_directory_is_not_a_catalogue(tmp_path, pm):
    with pytest.raises(CatalogueError, match="is a directory"):
        open_catalogue(f"sqlite:///{tmp_path}", pm=pm)


# --------------------------------------------------------------------------- filters


def test_parse_filter_operators_and_auto_typing():
    assert parse_filter("periodic=true") == Filter("periodic", "=", True, "true")
    assert parse_filter("k_hedral>=2") == Filter("k_hedral", ">=", 2, "2")
    assert parse_filter("polygon_area<1.5") == Filter("polygon_area", "<", 1.5, "1.5")
    assert parse_filter("symmetry_group!=p6m") == Filter("symmetry_group", "!=", "p6m", "p6m")
    assert parse_filter("vertex_type~12") == Filter("vertex_type", "~", "12", "12")
    assert parse_filter("k-hedral > 1") == Filter("k_hedral", ">", 1, "1")
    assert parse_filter('name="6"').value == "6"  # quoted values stay text
    assert parse_filter("x=1e3").value == 1000.0
    assert parse_filter("x=-7").value == -7
    assert parse_filter("x=3.4.6.4").value == "3.4.6.4"
    assert parse_filter("x=nan").value == "nan"  # not a number we compare with


@pytest.mark.parametrize("bad", ["polygons", "=3", "k_hedral>=two", "3x=1", "a b=1", ""])
def test_parse_filter_rejects_malformed(bad):
    with pytest.raises(ParseError) as info:
        parse_filter(bad)
    assert "\n" not in str(info.value)
    # only a bare key (what bash leaves of an unquoted heesch>=2) gets the hint about quoting
    assert ("quote the filter" in str(info.value)) == (bad == "polygons")


@given(
    key=st.from_regex(r"[a-z][a-z0-9_]{0,15}", fullmatch=True),
    op=st.sampled_from(["=", "!=", ">=", "<=", ">", "<"]),
    n=st.integers(min_value=-10**12, max_value=10**12),
)
def test_parse_filter_integers_roundtrip(key, op, n):
    f = parse_filter(f"{key}{op}{n}")
    assert (f.key, f.op, f.value) == (key, op, n)
    assert type(f.value) is int
    assert parse_filter(str(f)) == f


@given(text=st.text(alphabet=st.characters(blacklist_categories=("Cs", "Zs", "Cc"),
                                          blacklist_characters="'\""), min_size=1, max_size=30))
def test_parse_filter_substring_keeps_text_verbatim(text):
    f = parse_filter(f"title~{text}")
    assert (f.key, f.op, f.value, f.raw) == ("title", "~", text, text)


# --------------------------------------------------------------------------- queries


def test_membership_in_list_properties(reading):
    vts = vertex_types()
    for n in (3, 4, 6, 8, 12):
        expected = {name for name, vt in vts.items() if n in vt}
        assert names(reading.query(where=[f"polygons={n}"])) == expected, n
    # the Archimedean tilings with hexagons: 6^3, 3^4.6, 3.4.6.4, 3.6.3.6, 4.6.12
    assert names(reading.query(where=["polygons=6"])) == {"6^3", "3^4.6", "3.4.6.4", "3.6.3.6", "4.6.12"}


def test_not_equal_on_lists_means_no_element_equals(reading):
    # no triangles: 4^4, 6^3, 4.8^2, 4.6.12
    assert names(reading.query(where=["polygons!=3"])) == {"4^4", "6^3", "4.8^2", "4.6.12"}


def test_ranges_and_combined_filters(reading):
    vts = vertex_types()
    assert names(reading.query(where=["vertex_degree>=5"])) == {n for n, vt in vts.items() if len(vt) >= 5}
    assert names(reading.query(where=["vertex_degree>=5"])) == {"3^6", "3^4.6", "3^3.4^2", "3^2.4.3.4"}
    assert names(reading.query(where=["vertex_degree<4"])) == {"6^3", "3.12^2", "4.6.12", "4.8^2"}
    assert names(reading.query(where=["k_hedral=3"])) == {"3.4.6.4", "4.6.12"}
    assert names(reading.query(where=["polygons=3", "vertex_degree<5", "k_hedral>1"])) == {
        "3.4.6.4", "3.6.3.6", "3.12^2"}
    # unit-edge polygon areas: triangle sqrt(3)/4, square 1, hexagon 3 sqrt(3)/2
    assert names(reading.query(where=["polygon_area>1"])) == {"6^3"}
    assert names(reading.query(where=["polygon_area<0.5"])) == {"3^6"}
    assert names(reading.query(where=["polygon_area=1"])) == {"4^4"}
    # numeric equality has a relative tolerance of 1e-9: ten digits of sqrt(3)/4 find 3^6
    assert names(reading.query(where=["polygon_area=0.4330127019"])) == {"3^6"}
    assert names(reading.query(where=["polygon_area=0.43301"])) == set()


def test_shared_columns_text_and_booleans(reading):
    # symmetry groups (Grünbaum & Shephard §2.1): six of the eleven are p6m
    assert names(reading.query(where=["symmetry_group=p6m"])) == {
        "3^6", "6^3", "3.4.6.4", "3.6.3.6", "3.12^2", "4.6.12"}
    assert names(reading.query(where=["symmetry_group!=p6m", "symmetry_group!=p4m"])) == {
        "3^4.6", "3^3.4^2", "3^2.4.3.4"}
    # the snub hexagonal tiling is the only chiral Archimedean tiling
    assert names(reading.query(where=["chiral=true"])) == {"3^4.6"}
    assert names(reading.query(where=["regular=true"])) == {"3^6", "4^4", "6^3"}
    assert names(reading.query(where=["periodic=false"])) == set()
    assert names(reading.query(where=["edge_to_edge=true"])) == ALL


def test_substring_and_text_search(reading):
    assert names(reading.query(where=["vertex_type~12"])) == {"3.12^2", "4.6.12"}
    assert names(reading.query(where=["title~SNUB"])) == {"3^4.6", "3^2.4.3.4"}
    assert names(reading.query(text="snub")) == {"3^4.6", "3^2.4.3.4"}
    assert names(reading.query(text="4.4.4.4")) == {"4^4"}  # an alias
    assert names(reading.query(text="p4g")) == {"3^2.4.3.4"}  # a text property
    # LIKE wildcards in the user's text are literal characters
    assert reading.query(text="%") == [] and reading.query(text="_") == []
    assert names(reading.query(where=["name~^"])) == {"3^6", "4^4", "6^3", "3^4.6", "3^3.4^2", "3^2.4.3.4",
                                                  "3.12^2", "4.8^2"}


def test_family_filter_ordering_and_paging(reading):
    assert len(reading.query(family="testgrid")) == 11
    assert reading.query(family="nosuch") == []
    by_degree = [e.name for e in reading.query(order_by="-vertex_degree")]
    assert by_degree[0] == "3^6"
    degrees = [len(vertex_types()[n]) for n in by_degree]
    assert degrees == sorted(degrees, reverse=True)
    from tilekit.catalogue.filters import natural_key

    ordered = [e.name for e in reading.query()]
    assert ordered == sorted(ALL, key=natural_key)  # natural order: 3.4.6.4 before 3.12^2
    assert ordered.index("3.4.6.4") < ordered.index("3.12^2")
    pages = [e.name for off in range(0, 11, 4) for e in reading.query(limit=4, offset=off)]
    assert pages == ordered
    assert [e.name for e in reading.query(order_by="-name", limit=2)] == sorted(ALL, key=natural_key, reverse=True)[:2]
    assert reading.count_matching(where=["polygons=4"]) == len(reading.query(where=["polygons=4"]))
    with pytest.raises(NotFoundError, match="vertex_degree"):
        reading.query(order_by="vertex_degre")
    with pytest.raises(ParameterError):
        reading.query(limit=-1)


def test_entry_properties_keep_their_types(cat):
    entry = cat.get("3.4.6.4")
    assert entry.family == "testgrid" and entry.title == "rhombitrihexagonal tiling"
    assert entry.properties["sides"] == [3, 4, 6]
    assert all(type(v) is int for v in entry.properties["sides"])
    assert entry.properties["periodic"] is True and entry.properties["chiral"] is False
    assert entry.properties["vertex_type"] == "3.4.6.4"
    area = cat.get("6^3").properties["polygon_area"]
    assert type(area) is float and math.isclose(area, 3 * math.sqrt(3) / 2)
    from tilekit.catalogue.vocabulary import normalise_properties

    # record order kept, under the shared names (polygons -> sides; periodic implies aperiodic=false)
    assert list(entry.properties) == list(normalise_properties(testkit.records()[6].properties))


def test_every_property_is_stored_as_typed_rows(cat):
    from tilekit.models import PROPS as p
    from tilekit.models import TILINGS as t

    with cat.engine.connect() as conn:
        rows = conn.execute(sa.select(p.c.key, p.c.position, p.c.kind, p.c.value_num)
                            .join(t, t.c.id == p.c.tiling_id).where(t.c.name == "4.6.12")).all()
    keys = {r.key for r in rows}
    assert {"periodic", "k_hedral", "symmetry_group", "sides", "vertex_degree"} <= keys
    polygon_rows = sorted((r.position, r.value_num) for r in rows if r.key == "sides")
    assert polygon_rows == [(0, 4.0), (1, 6.0), (2, 12.0)]


def test_unknown_property_suggests_close_keys(cat):
    with pytest.raises(NotFoundError) as info:
        cat.query(where=["polygon=3"])
    assert "'polygons'" in str(info.value)


@pytest.mark.parametrize("expr", ["periodic=yes", "periodic>1", "k_hedral=two", "k_hedral~1",
                                  "name>=3", "symmetry_group<2"])
def test_type_mismatch_on_shared_columns(cat, expr):
    with pytest.raises((ParameterError, ParseError)) as info:
        cat.query(where=[expr])
    assert "\n" not in str(info.value)


def test_hostile_filter_values_are_data(cat):
    hostile = "x'; DROP TABLE tilings; --"
    assert cat.query(where=[f"name={hostile}"]) == []
    assert cat.query(where=[f"vertex_type={hostile}"]) == []
    assert cat.query(where=['title~" OR 1=1 --']) == []
    assert cat.query(text=hostile) == []
    assert cat.count() == 11
    # stored and found back verbatim
    cat.upsert([CatalogueRecord("testgrid", hostile, {"vertex_type": "4^4"}, title="Robert'); --",
                                properties={"note": "'; DELETE FROM tiling_properties; --"})])
    assert [e.name for e in cat.query(where=[f"name={hostile}"])] == [hostile]
    assert cat.get(hostile).properties == {"note": "'; DELETE FROM tiling_properties; --"}
    assert cat.count() == 12 and len(cat.get("4^4").properties) > 5


# --------------------------------------------------------------------------- lookups


def test_get_by_name_alias_and_case(cat):
    assert cat.get("4^4").aliases == ["4.4.4.4", "(4^4)"]
    assert cat.get("4.4.4.4").name == "4^4"
    assert cat.get("(3^6)").name == "3^6"
    assert cat.get("3.12.12").name == "3.12^2"
    assert cat.get("3^4.6").name == cat.get("3.3.3.3.6").name


def test_unknown_name_suggests_close_names(cat):
    with pytest.raises(NotFoundError) as info:
        cat.get("4.4.4.5")
    assert "did you mean" in str(info.value) and "'4.4.4.4'" in str(info.value)


def test_tiling_is_rebuilt_by_the_family(cat):
    for name, tiles_per_unit in (("3^6", 2), ("4^4", 1), ("6^3", 1)):
        tiling = cat.tiling(name)
        assert tiling.name == name and len(tiling.unit_prototile) == tiles_per_unit
        region = (-2.3, -1.7, 3.1, 2.9)
        assert tiling.patch(region).validate(region)


def test_tiling_of_an_uninstalled_family(cat):
    cat.upsert([CatalogueRecord("ghost", "ghost-1", {})])
    with pytest.raises(NotFoundError, match="unknown family 'ghost'"):
        cat.tiling("ghost-1")


# --------------------------------------------------------------------------- writing


def test_seed_replace_restores_plugin_data_and_keeps_other_tilings(cat):
    changed = CatalogueRecord("testgrid", "4^4", {"vertex_type": "4^4"}, title="edited",
                              properties={"periodic": False})
    extra = CatalogueRecord("testgrid", "found-by-search", {"vertex_type": "4^4"}, properties={"k_hedral": 1})
    assert cat.upsert([changed, extra]) == (1, 1)
    assert cat.get("4^4").title == "edited" and cat.get("4^4").aliases == []
    assert cat.seed() == (0, 0)  # existing names are left alone
    assert cat.get("4^4").title == "edited"
    assert cat.seed(replace=True) == (0, 11)
    restored = cat.get("4.4.4.4")
    assert restored.title == "regular square tiling" and restored.properties["periodic"] is True
    assert cat.get("found-by-search").properties == {"k_hedral": 1}
    assert names(cat.query(where=["periodic=false"])) == set()


@pytest.mark.parametrize(
    "record, fragment",
    [
        (CatalogueRecord("f", "a", {}, properties={"Bad-Key": 1}), "not snake_case"),
        (CatalogueRecord("f", "a", {}, properties={"k_hedral": "2"}), "must be an integer"),
        (CatalogueRecord("f", "a", {}, properties={"periodic": 1}), "true or false"),
        (CatalogueRecord("f", "a", {}, properties={"x": float("nan")}), "finite"),
        (CatalogueRecord("f", "a", {}, properties={"name": "b"}), "reserved"),
        (CatalogueRecord("f", "", {}), "empty name"),
        (CatalogueRecord("f", "a", {"x": {1, 2}}), "not plain JSON"),
        (CatalogueRecord("f", "a", {}, aliases=["4.4.4.4"]), "already belongs"),
        (CatalogueRecord("f", "a", {}, aliases=["6^3"]), "name of another tiling"),
    ],
)
def test_bad_records_are_refused_atomically(cat, record, fragment):
    with pytest.raises(CatalogueError, match=fragment):
        cat.upsert([CatalogueRecord("f", "ok-before", {}), record])
    assert cat.count() == 11  # nothing of the batch was written


def test_nested_values_round_trip_as_json(cat):
    matrix = [[1, 1], [1, 2]]
    cat.upsert([CatalogueRecord("f", "m", {}, properties={"matrix": matrix, "empty": [], "none": None})])
    props = cat.get("m").properties
    assert props == {"matrix": matrix, "empty": [], "none": None}


# --------------------------------------------------------------------------- export


def test_export_json_and_csv(cat, tmp_path):
    out = tmp_path / "all.json"
    assert cat.export(out) == 11
    data = json.loads(out.read_text())
    by_name = {d["name"]: d for d in data}
    assert set(by_name) == ALL
    assert by_name["4.8^2"]["properties"]["sides"] == [4, 8]
    assert by_name["4^4"]["aliases"] == ["4.4.4.4", "(4^4)"]
    assert by_name["4^4"]["spec"] == {"vertex_type": "4^4"}

    stream = io.StringIO()
    assert cat.export(stream, format="csv", where=["regular=true"]) == 3
    rows = list(csv.DictReader(io.StringIO(stream.getvalue())))
    assert [r["name"] for r in rows] == ["3^6", "4^4", "6^3"]
    assert json.loads(rows[2]["sides"]) == [6] and rows[0]["periodic"] == "true"
    assert json.loads(rows[1]["spec"]) == {"vertex_type": "4^4"}
    with pytest.raises(ParameterError, match="json, csv"):
        cat.export(stream, format="xml")
    with pytest.raises(CatalogueError, match="cannot write"):
        cat.export(tmp_path / "no" / "such" / "dir.json")


# --------------------------------------------------------------------------- runs


def test_record_chunk_is_atomic_and_never_duplicates(cat):
    run_id = cat.create_run("demo", {"n": 2}, [{"i": 0}, {"i": 1}])
    info = cat.run(run_id)
    assert (info.status, info.chunks_total, info.chunks_done) == ("queued", 2, 0)
    result = ChunkResult(results=[{"i": 0, "value": 1}],
                         records=[CatalogueRecord("testgrid", "search-hit", {}, properties={"k_hedral": 1})])
    assert cat.record_chunk(run_id, 0, result, seconds=0.5) is True
    assert cat.record_chunk(run_id, 0, result, seconds=0.5) is False  # already done: nothing written
    assert cat.results(run_id) == [{"i": 0, "value": 1}]
    assert cat.run(run_id).chunks_done == 1
    assert cat.pending_chunks(run_id) == [(1, {"i": 1})]
    assert cat.get("search-hit").properties == {"k_hedral": 1}
    # a bad record in the chunk: nothing of the chunk is stored, it stays pending
    bad = ChunkResult(results=[{"i": 1}], records=[CatalogueRecord("testgrid", "bad", {}, properties={"k_hedral": "x"})])
    with pytest.raises(CatalogueError):
        cat.record_chunk(run_id, 1, bad)
    assert cat.pending_chunks(run_id) == [(1, {"i": 1})]
    assert cat.results(run_id) == [{"i": 0, "value": 1}]
    assert cat.run(run_id).chunks_done == 1
    with pytest.raises(CatalogueError, match="no chunk 7"):
        cat.record_chunk(run_id, 7, ChunkResult())
    with pytest.raises(NotFoundError, match="unknown run '99'"):
        cat.run(99)


# --------------------------------------------------------------------------- robustness


def test_unknown_migration_revision_is_refused_untouched(url, pm, tmp_path):
    with open_catalogue(url, pm=pm) as cat, cat.engine.begin() as conn:
        conn.execute(sa.text("UPDATE alembic_version SET version_num = 'f00dcafe'"))
    with pytest.raises(CatalogueError) as info:
        open_catalogue(url, pm=pm)
    assert "'f00dcafe'" in str(info.value) and "left untouched" in str(info.value)
    raw = sqlite3.connect(tmp_path / "catalogue.sqlite")
    assert raw.execute("SELECT count(*) FROM tilings").fetchone()[0] == 11
    raw.close()


def test_in_memory_catalogue(pm):
    with open_catalogue("sqlite://", pm=pm) as cat:
        assert cat.count() == 11 and cat.path is None
        assert names(cat.query(where=["regular=true"])) == {"3^6", "4^4", "6^3"}


def test_two_writers_on_one_file(url, pm):
    """WAL + busy timeout: two connections record chunks at the same time without errors."""
    import threading

    first = open_catalogue(url, pm=pm)
    second = open_catalogue(url, pm=pm)
    runs = {c: c.create_run("demo", {}, [{"i": i} for i in range(40)]) for c in (first, second)}
    errors: list[BaseException] = []

    def work(cat):
        try:
            for i in range(40):
                cat.record_chunk(runs[cat], i, ChunkResult(results=[{"i": i}], records=[
                    CatalogueRecord("testgrid", f"w{runs[cat]}-{i}", {}, properties={"k_hedral": 1})]))
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)

    threads = [threading.Thread(target=work, args=(c,)) for c in (first, second)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    for run_id in runs.values():
        assert first.run(run_id).chunks_done == 40 and len(first.results(run_id)) == 40
    assert first.count() == 11 + 80
    first.close()
    second.close()


def _open_and_count(target: str) -> int:
    import os

    from tilekit.plugins import make_plugin_manager

    os.environ["TILEKIT_PLUGINS"] = "no-such-plugin"
    pm = make_plugin_manager(extra_plugins=[testkit.GridPlugin()])
    with open_catalogue(target, pm=pm) as cat:
        return cat.count()


def test_processes_opening_a_new_catalogue_at_once(tmp_path):
    """Three first opens race; all succeed, whichever migrates and seeds first; nothing doubles."""
    import multiprocessing

    target = f"sqlite:///{tmp_path / 'race.sqlite'}"
    with multiprocessing.get_context("fork").Pool(3) as pool:
        assert pool.map(_open_and_count, [target] * 3) == [11, 11, 11]


def test_threads_opening_catalogues_at_once(tmp_path, pm):
    """Alembic's global migration context is guarded: threads may open catalogues together."""
    import threading

    results: list[object] = []

    def opener(i: int) -> None:
        try:
            with open_catalogue(f"sqlite:///{tmp_path / f't{i}.sqlite'}", pm=pm) as cat:
                results.append(cat.count())
        except BaseException as exc:  # pragma: no cover - reported below
            results.append(exc)

    threads = [threading.Thread(target=opener, args=(i,)) for i in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == [11, 11, 11]


def test_family_failing_to_rebuild_is_a_plugin_error(cat):
    from tilekit.errors import PluginError

    cat.upsert([CatalogueRecord("testgrid", "no-vertex-type", {"other": 1})])
    with pytest.raises(PluginError) as info:
        cat.tiling("no-vertex-type")
    assert "could not rebuild 'no-vertex-type'" in str(info.value) and "KeyError" in str(info.value)


_scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(2**53), max_value=2**53),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=20),
)
_properties = st.dictionaries(
    st.from_regex(r"[a-z][a-z0-9_]{0,12}", fullmatch=True).filter(
        lambda k: k not in {"name", "family", "title", "spec", "aliases", "id", *SHARED}),
    st.one_of(_scalars, st.lists(_scalars.filter(lambda v: v is not None), max_size=5)),
    max_size=6,
)
SHARED = {"periodic", "k_hedral", "k_isohedral", "edge_to_edge", "symmetry_group"}
_MEMORY: list = []


def _memory_catalogue():
    if not _MEMORY:
        import os

        from tilekit.plugins import make_plugin_manager

        old = os.environ.get("TILEKIT_PLUGINS")
        os.environ["TILEKIT_PLUGINS"] = "no-such-plugin"
        try:
            _MEMORY.append(open_catalogue("sqlite://", seed=False, pm=make_plugin_manager()))
        finally:
            if old is None:
                del os.environ["TILEKIT_PLUGINS"]
            else:
                os.environ["TILEKIT_PLUGINS"] = old
    return _MEMORY[0]


@settings(max_examples=40, deadline=None)
@given(props=_properties)
def test_properties_round_trip_with_their_types(props):
    """Whatever JSON scalars and lists a plugin stores come back equal and of the same type."""
    cat = _memory_catalogue()
    cat.upsert([CatalogueRecord("f", "round-trip", {"p": props}, properties=props)])
    back = cat.get("round-trip")
    assert back.properties == props and back.spec == {"p": props}
    for key, value in props.items():
        restored = back.properties[key]
        if isinstance(value, list):
            assert [type(v) for v in restored] == [type(v) for v in value]
        else:
            assert type(restored) is type(value)
    # every scalar is findable by equality through the typed columns
    for key, value in props.items():
        for item in value if isinstance(value, list) else [value]:
            if isinstance(item, bool) or (isinstance(item, int | float) and abs(item) < 1e300):
                expr = f"{key}={str(item).lower() if isinstance(item, bool) else repr(item)}"
                assert "round-trip" in names(cat.query(where=[expr])), expr


class _UpgradePlugin(testkit.GridPlugin):
    """The test family after an upgrade: 4^4 gains a property, every record's vertex_degree is
    renamed valence, and one new tiling ships."""

    @tilekit.hookimpl
    def tilekit_catalogue_records(self):
        out = []
        for r in testkit.records():
            props = {("valence" if k == "vertex_degree" else k): v for k, v in r.properties.items()}
            if r.name == "4^4":
                props["shipped_in_upgrade"] = True
            out.append(CatalogueRecord(r.family, r.name, r.spec, r.title, props, r.aliases))
        square = out[-1]
        out.append(CatalogueRecord(square.family, "new-in-upgrade", square.spec, "",
                                   {"periodic": True, "k_hedral": 1}))
        return out


def test_changed_plugins_refresh_shipped_records_keeping_search_results(db_url, monkeypatch):
    """Upgrading tilekit or a plugin must update shipped records without losing what searches
    added (on both backends: PostgreSQL enforces the meta table's value length)."""
    url = db_url
    before = testkit.isolated_pm(monkeypatch, testkit.GridPlugin())
    cat = open_catalogue(url, pm=before)
    assert cat.refresh_shipped() is None  # unchanged plugins: nothing to do
    entry = cat.get("4^4")
    cat.upsert([CatalogueRecord(entry.family, entry.name, entry.spec, entry.title,
                                {**entry.properties, "found_by_search": 7}, entry.aliases)])
    cat.upsert([CatalogueRecord(entry.family, "search-result", entry.spec, "",
                                {"periodic": True, "k_hedral": 1})])
    cat.close()

    after = testkit.isolated_pm(monkeypatch, _UpgradePlugin())
    cat = open_catalogue(url, pm=after)
    square = cat.get("4^4").properties
    assert square["shipped_in_upgrade"] is True and square["found_by_search"] == 7
    # a shipped property the plugin renamed is gone, not left beside its new name
    assert square["valence"] == 4 and "vertex_degree" not in square
    with pytest.raises(NotFoundError, match="unknown property 'vertex_degree'"):
        cat.count_matching(testkit.FAMILY, ["vertex_degree=3"])
    assert cat.count_matching(testkit.FAMILY, ["valence=3"]) == 4  # 6^3, 4.8.8, 4.6.12, 3.12.12
    assert cat.get("new-in-upgrade").name == "new-in-upgrade"
    assert cat.get("search-result").name == "search-result"  # never dropped
    assert cat.refresh_shipped() is None


def test_a_meta_value_longer_than_its_column_is_split_over_rows(cat):
    """catalogue_meta.value holds 400 characters (PostgreSQL enforces it): the shipped property
    keys of every family are longer, so they are written over numbered rows and read back whole."""
    from tilekit.catalogue.core import _read_long_meta, _write_long_meta

    text = "".join(chr(ord("a") + i % 26) for i in range(1234))
    with cat.engine.begin() as conn:
        _write_long_meta(conn, "long_test", text)
    with cat.engine.begin() as conn:
        assert _read_long_meta(conn, "long_test") == text
        _write_long_meta(conn, "long_test", "short")  # fewer rows than before: none left over
    with cat.engine.connect() as conn:
        assert _read_long_meta(conn, "long_test") == "short"
        assert _read_long_meta(conn, "absent") is None


def test_a_resumed_run_is_not_finished_until_it_finishes_again(cat):
    """Issue 26: ``runs show`` of a resumed run showed the finished_at of its interruption."""
    run_id = cat.create_run("demo", {"n": 1}, [{"i": 0}])
    owner = cat.start_worker(run_id, "first")
    cat.finish_worker(owner)
    cat.finish_run(run_id, "interrupted")
    stopped = cat.run(run_id).finished_at
    assert cat.run(run_id).status == "interrupted" and stopped is not None
    owner = cat.start_worker(run_id, "resumed")
    assert cat.run(run_id).status == "running" and cat.run(run_id).finished_at is None
    cat.finish_worker(owner)
    cat.finish_run(run_id, "done")
    assert cat.run(run_id).finished_at >= stopped
