"""The on-disk cache of shipped records (tilekit.recordcache): what it returns is what the
plugins compute, a broken cache file is recomputed, and ``TILEKIT_CACHE_DIR=none`` turns it off."""

from __future__ import annotations

import json
import types

import pytest

from tilekit import recordcache
from tilekit.plugins import CatalogueRecord, catalogue_records, get_plugin_manager


def _as_rows(records):
    return [json.loads(json.dumps([r.family, r.name, r.spec, r.title, r.properties, r.aliases])) for r in records]


@pytest.fixture
def cache_dir(tmp_path, monkeypatch):
    monkeypatch.setenv("TILEKIT_CACHE_DIR", str(tmp_path))
    return tmp_path / "records"


def test_cached_records_equal_the_computed_ones(cache_dir, monkeypatch):
    pm = get_plugin_manager()
    first = catalogue_records(pm)
    files = sorted(cache_dir.glob("*.json"))
    assert len(files) >= 6  # one per built-in plugin module that ships records
    again = catalogue_records(pm)
    monkeypatch.setenv("TILEKIT_CACHE_DIR", "none")
    computed = catalogue_records(pm)
    assert _as_rows(first) == _as_rows(again) == _as_rows(computed)
    assert len({r.name for r in computed}) == len(computed) > 800


def _module_plugin(calls):
    plugin = types.ModuleType("tilekit_cache_probe")
    plugin.__file__ = recordcache.__file__  # any real source file: part of the key

    def records():
        calls.append(1)
        return [CatalogueRecord(family="probe", name="p1", spec={"x": [1.5, 2]}, title="t",
                                properties={"k": 3}, aliases=["q"])]
    return plugin, records


def test_a_second_call_reads_the_cache_and_a_broken_file_is_recomputed(cache_dir):
    calls: list[int] = []
    plugin, compute = _module_plugin(calls)
    one = recordcache.cached_records("probe", plugin, compute, CatalogueRecord)
    two = recordcache.cached_records("probe", plugin, compute, CatalogueRecord)
    assert len(calls) == 1 and one == two
    (path,) = cache_dir.glob("probe-*.json")
    for broken in ("", "{", "[[1, 2]]", json.dumps([["probe", "p1", [], "t", {}, []]])):
        path.write_text(broken)
        assert recordcache.cached_records("probe", plugin, compute, CatalogueRecord) == one
    assert len(calls) == 5
    assert json.loads(path.read_text()) == [["probe", "p1", {"x": [1.5, 2]}, "t", {"k": 3}, ["q"]]]


def test_objects_and_a_cache_turned_off_are_always_computed(cache_dir, monkeypatch):
    calls: list[int] = []
    plugin, compute = _module_plugin(calls)
    recordcache.cached_records("probe", object(), compute, CatalogueRecord)
    recordcache.cached_records("probe", object(), compute, CatalogueRecord)
    assert len(calls) == 2 and not list(cache_dir.glob("*.json"))
    monkeypatch.setenv("TILEKIT_CACHE_DIR", "none")
    recordcache.cached_records("probe", plugin, compute, CatalogueRecord)
    recordcache.cached_records("probe", plugin, compute, CatalogueRecord)
    assert len(calls) == 4 and not cache_dir.exists()
