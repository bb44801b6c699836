"""Catalogue speed: seeding 10,000 records and filtered queries over them (SQLite, WAL).

Run: pytest benchmarks/bench_catalogue.py --benchmark-enable
(with the project's default ``--benchmark-disable`` each function runs once, untimed).
"""

from __future__ import annotations

import random

import pytest

import tilekit
from tilekit.catalogue import open_catalogue
from tilekit.plugins import CatalogueRecord, make_plugin_manager

N_RECORDS = 10_000
GROUPS = ("p1", "p2", "pm", "pg", "cm", "pmm", "pmg", "pgg", "cmm", "p4", "p4m", "p4g",
          "p3", "p3m1", "p31m", "p6", "p6m")


def synthetic_records(n: int = N_RECORDS, seed: int = 1) -> list[CatalogueRecord]:
    """n deterministic records with about ten properties each, lists included."""
    rng = random.Random(seed)
    out = []
    for i in range(n):
        polygons = sorted(rng.sample([3, 4, 5, 6, 8, 12], rng.randint(1, 3)))
        k = len(polygons)
        out.append(CatalogueRecord(
            "synthetic",
            f"syn-{i:05d}",
            {"index": i, "polygons": polygons},
            title=f"synthetic tiling {i}",
            properties={
                "periodic": rng.random() < 0.8,
                "k_hedral": k,
                "k_isohedral": rng.randint(k, k + 2),
                "edge_to_edge": rng.random() < 0.5,
                "symmetry_group": rng.choice(GROUPS),
                "polygons": polygons,
                "vertex_degree": rng.randint(3, 6),
                "area": round(rng.uniform(0.1, 10.0), 6),
                "symbol": "".join(rng.choice("abcdefgh+-") for _ in range(8)),
            },
            aliases=[f"s{i}"],
        ))
    return out


class SyntheticPlugin:
    def __init__(self, records: list[CatalogueRecord]) -> None:
        self.records = records

    @tilekit.hookimpl
    def tilekit_catalogue_records(self):
        return self.records


@pytest.fixture(scope="module")
def pm():
    mp = pytest.MonkeyPatch()
    mp.setenv("TILEKIT_PLUGINS", "no-such-plugin")
    manager = make_plugin_manager(extra_plugins=[SyntheticPlugin(synthetic_records())])
    mp.undo()
    return manager


@pytest.fixture(scope="module")
def seeded(tmp_path_factory, pm):
    url = f"sqlite:///{tmp_path_factory.mktemp('bench') / 'seeded.sqlite'}"
    cat = open_catalogue(url, pm=pm)
    yield cat
    cat.close()


def test_seed_10000_records(benchmark, tmp_path_factory, pm) -> None:
    counter = iter(range(1_000_000))

    def fresh():
        url = f"sqlite:///{tmp_path_factory.mktemp('seed') / f'c{next(counter)}.sqlite'}"
        return (open_catalogue(url, pm=pm, seed=False),), {}

    def seed(cat):
        added = cat.seed()
        cat.close()
        return added

    added = benchmark.pedantic(seed, setup=fresh, rounds=3, iterations=1)
    assert added == (N_RECORDS, 0)


def test_filtered_query(benchmark, seeded) -> None:
    where = ["polygons=6", "k_hedral>=2", "periodic=true", "area<5"]
    entries = benchmark(seeded.query, where=where, limit=100)
    benchmark.extra_info["matches"] = seeded.count_matching(where=where)
    assert entries and all(6 in e.properties["polygons"] and e.properties["area"] < 5 for e in entries)


def test_full_listing(benchmark, seeded) -> None:
    entries = benchmark(seeded.query)
    assert len(entries) == N_RECORDS


def test_get_by_alias(benchmark, seeded) -> None:
    entry = benchmark(seeded.get, "s4321")
    assert entry.name == "syn-04321"
