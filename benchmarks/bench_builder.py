"""Builder speed (placements per second) and the whole vertex-species search.

Run: pytest benchmarks/bench_builder.py --benchmark-enable
"""

from __future__ import annotations

import pytest

from tilekit import Prototile
from tilekit.builder import PatchBuilder
from tilekit.geometry import regular_polygon
from tilekit.plugins import get_search
from tilekit.plugins.archimedean.construct import grow


@pytest.mark.parametrize("sides", [(3,), (4, 8)])
def test_builder_free_growth(benchmark, sides) -> None:
    """No rule: every placement is checked for overlap, vertex-on-edge and angle sums."""
    protos = [Prototile(regular_polygon(n)) for n in sides]

    def run():
        return PatchBuilder(protos).build(tiles=500)

    res = benchmark(run)
    assert res.ok
    benchmark.extra_info["placements"] = res.stats.placements
    benchmark.extra_info["placements_per_second"] = round(res.stats.placements / res.stats.seconds)


def test_builder_vertex_rule(benchmark) -> None:
    """With the vertex-type rule (3^4.6) to radius 9, as the Archimedean construction does."""
    res = benchmark(grow, "3^4.6", 9.0)
    assert res.ok
    benchmark.extra_info["placements"] = res.stats.placements
    benchmark.extra_info["placements_per_second"] = round(res.stats.placements / res.stats.seconds)


def test_vertex_species_search(benchmark) -> None:
    """Every chunk of the search with default parameters, in-process."""
    search = get_search("vertex-species")

    def run():
        out = []
        for chunk in search.chunks({}):
            out.extend(search.run_chunk({}, chunk).results)
        return out

    results = benchmark.pedantic(run, rounds=3, iterations=1)
    summary = search.summarize({}, results)
    assert summary["tiling_types"] == 11
    benchmark.extra_info.update({k: v for k, v in summary.items() if k != "survivors"})
