"""Isohedral fill speed: ~100,000 tiles with their outlines, tilekit next to Tactile.

Both sides fill the same box with IH16 tiles (one J edge shape, 14-point outline) and
produce every tile's outline coordinates: tilekit as one (n, k, 2) array from
``IsohedralTiling.patch`` + ``tile_outlines`` (one batched matmul); Tactile (PyPI ``tactile``, the reference
implementation's Python port) by iterating ``fill_region_bounds`` and transforming the
outline of each tile it yields.

Run as a script (prints a table):   python benchmarks/bench_isohedral.py [IH] [tiles]
or with pytest-benchmark:           pytest benchmarks/bench_isohedral.py --benchmark-enable
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
import pytest

from tilekit.plugins.isohedral import EdgeShape, IsohedralTiling
from tilekit.plugins.isohedral.engine import tile_outlines

TARGET_TILES = 100_000


def make_tiling(ih: int = 16) -> IsohedralTiling:
    shape = EdgeShape(np.array([[0.0, 0.0], [0.3, 0.12], [0.62, -0.08], [1.0, 0.0]]))
    edges = {c: shape for c in _classes(ih)}
    return IsohedralTiling(ih, edges=edges)


def _classes(ih: int) -> list[str]:
    from tilekit.plugins.isohedral.engine import shape_classes
    from tilekit.plugins.isohedral.templates import get_template

    t = get_template(ih)
    return [c for c in shape_classes(t.symbol) if t.symbol.label_kind(c) == "J"]


def region_for(tiling: IsohedralTiling, tiles: int) -> tuple[float, float, float, float]:
    side = math.sqrt(abs(tiling.prototile.area) * tiles)
    return (0.0, 0.0, side, side)


def tilekit_fill(tiling: IsohedralTiling, region: tuple[float, float, float, float]) -> np.ndarray:
    return tile_outlines(tiling.patch(region))  # (n, k, 2)


def tactile_fill(ih: int, params: list[float], outline: np.ndarray, region) -> list[list[tuple[float, float]]]:
    from tactile import IsohedralTiling as TactileTiling
    from tactile import Point, mul

    tt = TactileTiling(ih)
    if params:
        tt.parameters = list(params)
    pts = [Point(float(x), float(y)) for x, y in outline]
    out = []
    for shape in tt.fill_region_bounds(*region):
        m = shape.T
        out.append([mul(m, p) for p in pts])
    return out


def measure(ih: int = 16, tiles: int = TARGET_TILES) -> dict[str, float]:
    tiling = make_tiling(ih)
    region = region_for(tiling, tiles)
    t0 = time.perf_counter()
    ours = tilekit_fill(tiling, region)
    t1 = time.perf_counter()
    # Tactile places its aspects relative to its own tile frame: give it its own vertices'
    # outline (the same shape up to the IH43/IH58 edge offset, which IH16 does not have)
    theirs = tactile_fill(ih, list(tiling.params), tiling.prototile.outline, region)
    t2 = time.perf_counter()
    return {
        "tilekit_tiles": len(ours),
        "tilekit_seconds": t1 - t0,
        "tilekit_tiles_per_s": len(ours) / (t1 - t0),
        "tactile_tiles": len(theirs),
        "tactile_seconds": t2 - t1,
        "tactile_tiles_per_s": len(theirs) / (t2 - t1),
        "outline_points": len(tiling.prototile.outline),
    }


@pytest.fixture(scope="module")
def bench_setup():
    tiling = make_tiling(16)
    return tiling, region_for(tiling, TARGET_TILES)


def test_tilekit_fill_100k(benchmark, bench_setup):
    tiling, region = bench_setup
    out = benchmark(tilekit_fill, tiling, region)
    assert len(out) >= 0.9 * TARGET_TILES


def test_tactile_fill_100k(benchmark, bench_setup):
    tiling, region = bench_setup
    out = benchmark(tactile_fill, 16, list(tiling.params), tiling.prototile.outline, region)
    assert len(out) >= 0.9 * TARGET_TILES


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("ih", nargs="?", type=int, default=16, help="the IH type (default 16)")
    ap.add_argument("tiles", nargs="?", type=int, default=TARGET_TILES, help="about how many tiles")
    return ap


if __name__ == "__main__":
    args = build_parser().parse_args()
    ih, n = args.ih, args.tiles
    r = measure(ih, n)
    print(f"IH{ih}, {r['outline_points']}-point outline")
    print(f"tilekit : {r['tilekit_tiles']:>8} tiles in {r['tilekit_seconds']:.3f} s = {r['tilekit_tiles_per_s']:,.0f} tiles/s")
    print(f"tactile : {r['tactile_tiles']:>8} tiles in {r['tactile_seconds']:.3f} s = {r['tactile_tiles_per_s']:,.0f} tiles/s")
    print(f"speed-up: {r['tilekit_tiles_per_s'] / r['tactile_tiles_per_s']:.1f}x (tiles per second)")
