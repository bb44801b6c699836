"""The catalogue's read path without SQLAlchemy (tilekit.catalogue.reading).

``open_reader`` reads a current SQLite catalogue through the standard library's sqlite3; it
must give exactly what the Catalogue gives through SQLAlchemy (the same SQL text, another
driver: JSON, booleans and bound values are decoded differently), and must not be used when
the catalogue is not current, since it neither migrates nor seeds.
"""

from __future__ import annotations

import sqlite3

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tilekit.catalogue import open_catalogue, open_reader
from tilekit.catalogue.reading import RESULT_FAMILIES_KEY, SCRIPTS_KEY, SEED_KEY, sqlite_path
from tilekit.errors import TilekitError
from tilekit.plugins import get_plugin_manager


@pytest.fixture(scope="module")
def seeded(tmp_path_factory):
    """A catalogue of every installed plugin's shipped tilings, and its two readers."""
    url = f"sqlite:///{tmp_path_factory.mktemp('reading') / 'catalogue.sqlite'}"
    pm = get_plugin_manager()
    catalogue = open_catalogue(url, pm=pm)
    reader = open_reader(url, pm)
    assert reader is not None
    yield url, catalogue, reader
    reader.close()
    catalogue.close()


def outcome(call):
    """What a read gives: the entries in full (spec, properties, aliases, in order), a count,
    or the error's type and message."""
    try:
        got = call()
    except TilekitError as exc:
        return ("error", type(exc).__name__, str(exc))
    if isinstance(got, int):
        return ("count", got)
    return ("entries", [(e.id, e.full()) for e in got])


def test_every_shipped_tiling_reads_alike(seeded):
    _, catalogue, reader = seeded
    full = outcome(lambda: catalogue.query())
    assert full[0] == "entries" and len(full[1]) == catalogue.count() > 100
    assert outcome(lambda: reader.query()) == full
    # JSON specs come back as objects and booleans as booleans, as through SQLAlchemy
    for _, entry in full[1]:
        assert isinstance(entry["spec"], dict)
    periodic = [e for e in reader.query(where=["periodic=true"]) if "periodic" in e.properties]
    assert periodic and all(e.properties["periodic"] is True for e in periodic)


def values_of(catalogue) -> dict[str, list]:
    """Every stored value of every property (scalars and list elements), by key."""
    out: dict[str, set] = {}
    for entry in catalogue.query():
        for key, value in entry.flat().items():
            for v in value if isinstance(value, list) else [value]:
                if isinstance(v, str | int | float | bool):
                    out.setdefault(key, set()).add(v)
    return {k: sorted(v, key=repr) for k, v in out.items()}


@st.composite
def queries(draw, values):
    keys = sorted(values)
    filters = []
    for _ in range(draw(st.integers(0, 3))):
        key = draw(st.sampled_from([*keys, "symmetry_group", "k_hedral", "no_such_key"]))
        op = draw(st.sampled_from(["=", "!=", ">", "<", ">=", "<=", "~"]))
        pool = values.get(key, [])
        value = draw(st.one_of(
            st.sampled_from(pool) if pool else st.just("x"),
            st.integers(-2, 13),
            st.floats(-10, 10, allow_nan=False).map(lambda f: round(f, 3)),
            st.sampled_from(["true", "false", "p6m", "*632", "%", "_", "'6'", "snub"]),
        ))
        text = str(value).lower() if isinstance(value, bool) else str(value)
        filters.append(f"{key}{op}{text}")
    family = draw(st.sampled_from([None, "archimedean", "laves", "isohedral", "substitution", "wang", "nosuch"]))
    text = draw(st.sampled_from([None, "snub", "penrose", "%", "IH1", "4.4.4.4"]))
    order = draw(st.sampled_from(["name", "-name", "family", "-k_hedral", "polygons", "-vertex_type", "nope"]))
    limit = draw(st.sampled_from([None, 0, 1, 7, 1500]))
    offset = draw(st.sampled_from([0, 3, 150]))
    return family, filters, text, order, limit, offset


def test_random_queries_read_alike(seeded):
    _, catalogue, reader = seeded
    values = values_of(catalogue)

    @settings(max_examples=150, deadline=None, suppress_health_check=list(HealthCheck))
    @given(queries(values))
    def check(q):
        family, where, text, order, limit, offset = q
        for call in (
            lambda r: r.query(family=family, where=where, text=text, order_by=order, limit=limit, offset=offset),
            lambda r: r.count_matching(family=family, where=where, text=text),
            lambda r: r.check_family(family) or 0,
        ):
            assert outcome(lambda c=call: c(reader)) == outcome(lambda c=call: c(catalogue)), q

    check()


def test_pages_of_a_long_listing_are_fetched_in_order(seeded, monkeypatch):
    from tilekit.catalogue import reading

    _, catalogue, reader = seeded
    monkeypatch.setattr(reading, "PAGE", 7)  # many pages, and the last one short
    assert [e.name for e in reader.iter_query(order_by="-name")] == [e.name for e in catalogue.query(order_by="-name")]
    assert [e.name for e in reader.iter_query(limit=20, offset=5)] == [e.name for e in catalogue.query()][5:25]


def _meta(path, key, value):
    with sqlite3.connect(path) as conn:
        conn.execute("UPDATE catalogue_meta SET value = ? WHERE key = ?", (value, key))


@pytest.mark.parametrize("key", [SEED_KEY, SCRIPTS_KEY, RESULT_FAMILIES_KEY])
def test_a_catalogue_not_known_current_is_not_read_this_way(tmp_path, key):
    """Other plugins or tilekit code (the seed fingerprint), other migrations (the scripts'
    key) or no record of the result-table families: the full open must run (and it brings
    the catalogue up to date again)."""
    path = tmp_path / "c.sqlite"
    pm = get_plugin_manager()
    open_catalogue(f"sqlite:///{path}", pm=pm).close()
    assert open_reader(f"sqlite:///{path}", pm) is not None
    _meta(path, key, "stale")
    assert open_reader(f"sqlite:///{path}", pm) is None
    open_catalogue(f"sqlite:///{path}", pm=pm).close()
    assert open_reader(str(path), pm) is not None  # a plain path is a sqlite:/// URL too


def test_families_in_result_tables_and_other_catalogues_are_not_read_this_way(seeded, tmp_path):
    url, catalogue, _ = seeded
    pm = get_plugin_manager()
    tabled = {rt.family for rt in catalogue.result_tables.values() if rt.family}
    assert {"polyomino", "vertex-species"} <= tabled
    for family in tabled:
        assert open_reader(url, pm, family) is None, family
    assert open_reader(url, pm, "archimedean") is not None
    assert open_reader(f"sqlite:///{tmp_path / 'missing.sqlite'}", pm) is None
    assert not (tmp_path / "missing.sqlite").exists()  # nothing is created
    assert open_reader("postgresql+psycopg://u@127.0.0.1:1/db", pm) is None
    foreign = tmp_path / "foreign.sqlite"
    with sqlite3.connect(foreign) as conn:
        conn.execute("CREATE TABLE notes (x)")
    assert open_reader(f"sqlite:///{foreign}", pm) is None
    (tmp_path / "text.sqlite").write_text("not a database")
    assert open_reader(f"sqlite:///{tmp_path / 'text.sqlite'}", pm) is None


@pytest.mark.parametrize("url, path", [
    ("sqlite:////tmp/a.sqlite", "/tmp/a.sqlite"),
    ("sqlite:///rel/a.sqlite", "rel/a.sqlite"),
    ("sqlite://", None),
    ("sqlite:///:memory:", None),
    ("sqlite+pysqlite:////tmp/a.sqlite", None),  # a driver named: SQLAlchemy's business
    ("sqlite:////tmp/a%20b.sqlite", None),  # escapes: SQLAlchemy's parsing decides
    ("sqlite:////tmp/a.sqlite?mode=ro", None),
    ("postgresql://u@h/db", None),
])
def test_sqlite_path_takes_only_plain_file_urls(url, path):
    got = sqlite_path(url)
    assert (str(got) if got is not None else None) == path
