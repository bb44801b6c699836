"""The estimates behind tilekit/limits.py are measured, not assumed (issue 27).

benchmarks/bench_limits.py measures the peak resident memory of each engine's work in a
fresh process (SAT questions, the patch builder, patch generation, adjacency, exports); this
test runs its SMALL cases and fails when tilekit's estimate of a case (limits.sat_bytes,
BUILDER_BYTES_PER_TILE, a tiling's bytes_per_tile, export.memory_per_tile,
ADJACENCY_BYTES_PER_VERTEX) is off by more than a factor of two either way: an estimate too
low lets a command exhaust the machine, one too high refuses what would fit.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

_SPEC = importlib.util.spec_from_file_location(
    "bench_limits", Path(__file__).resolve().parents[1] / "benchmarks" / "bench_limits.py")
bench = importlib.util.module_from_spec(_SPEC)
sys.modules["bench_limits"] = bench  # its dataclasses look their module up
_SPEC.loader.exec_module(bench)

SMALL = [c for c in bench.CASES if c.small]


def test_every_engine_with_an_estimate_is_measured():
    engines = {c.engine.split(" (")[0] for c in SMALL}
    assert {"sat", "builder", "patch generation", "adjacency", "export .svg", "export .geojson"} <= engines, engines


@pytest.mark.parametrize("case", SMALL, ids=[f"{c.engine}: {c.label}" for c in SMALL])
def test_estimate_within_twice_the_measured_peak(case):
    measured = bench.measure(case)
    assert measured["bytes"] > 1 << 20, measured  # a peak of at least a MB, not noise
    ratio = measured["estimate"] / measured["bytes"]
    assert 0.5 <= ratio <= 2.0, (case.label, measured, ratio)
