"""Core replication speed: PeriodicTiling.patch and Patch.validate on a regular tiling.

Run: pytest benchmarks/bench_core.py --benchmark-enable
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tilekit import Affine, PeriodicTiling, Prototile
from tilekit.geometry import regular_polygon


@pytest.fixture(scope="module")
def triangles() -> PeriodicTiling:
    tri = Prototile(regular_polygon(3))
    unit = np.array([np.eye(3), Affine.half_turn((0.75, math.sqrt(3) / 4))])
    return PeriodicTiling([tri], [0, 0], unit, (1, 0), (0.5, math.sqrt(3) / 2))


def test_patch_one_million_tiles(benchmark, triangles) -> None:
    region = (-330, -330, 330, 330)  # about 10^6 triangles
    patch = benchmark(triangles.patch, region)
    benchmark.extra_info["tiles"] = len(patch)
    assert len(patch) > 900_000


def test_patch_with_outlines_100k(benchmark, triangles) -> None:
    region = (-105, -105, 105, 105)

    def run():
        p = triangles.patch(region)
        return p, p.polygons()

    patch, outlines = benchmark(run)
    benchmark.extra_info["tiles"] = len(patch)
    assert len(outlines) == len(patch)


def test_validate_20k(benchmark, triangles) -> None:
    region = (-47, -47, 47, 47)
    patch = triangles.patch(region)
    report = benchmark(lambda: patch.validate(region))
    benchmark.extra_info["tiles"] = len(patch)
    assert report.ok
