"""Wang family speed: the two graphics fills at 1000 x 1000 and the exact solvers on Jeandel–Rao.

Run the timed suite:  pytest benchmarks/bench_wang.py --benchmark-enable
Print the tables of docs/benchmarks.md (Wang section):  python benchmarks/bench_wang.py
(with the project's default ``--benchmark-disable`` each test runs once, untimed).
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np
import pytest

from tilekit.errors import SolverLimit
from tilekit.plugins.wang import (
    backtrack_solve,
    builder_solve,
    get_tileset,
    grid_mismatches,
    random_access_fill,
    sat_solve,
    scanline_fill,
)
from tilekit.plugins.wang.tileset import E, N, S, W

SIZE = 1000
E_, N_, S_, W_ = 1, 0, 2, 3  # tile columns, as tileset.N, E, S, W


def row_fill_tables(ts):
    """For the row-by-row peer: tiles by (north, west, east) with ANY for a missing north or
    west neighbour, or None when pre-drawing east colours would change the distribution
    (some (n, w) does not have the same number of tiles for every east colour)."""
    assert (E, N, S, W) == (E_, N_, S_, W_)
    c = len(ts.colours)
    v = ts.vertical_colours
    t = ts.tiles
    keys = []
    for n in (t[:, N], np.full(len(t), c)):
        for w in (t[:, W], np.full(len(t), c)):
            keys.append((n * (c + 1) + w) * c + t[:, E])
    keys = np.concatenate(keys)
    tiles = np.tile(np.arange(len(t)), 4)
    counts = np.bincount(keys, minlength=(c + 1) ** 2 * c).reshape((c + 1) ** 2, c)
    used = counts.sum(axis=1) > 0
    per_e = counts[used][:, v]
    if ts.corners is not None or not (per_e == per_e[:, :1]).all() or per_e.min() < 1:
        return None
    kmax = int(counts.max())
    order = np.argsort(keys, kind="stable")
    sk = keys[order]
    slot = np.arange(len(sk)) - np.searchsorted(sk, sk, side="left")
    choices = np.full(((c + 1) ** 2 * c, kmax), -1, dtype=np.int64)
    choices[sk, slot] = tiles[order]
    return choices, counts.ravel(), v


def row_fill_peer(ts, rows: int, cols: int, seed: int) -> np.ndarray:
    """The strong NumPy peer for complete stochastic edge sets: row by row, every cell's
    east colour drawn in advance (uniform), so a cell's west colour is its left neighbour's
    drawn east colour and the whole row is a table lookup: rows NumPy steps of cols cells.
    Draws uniformly among the tiles matching (N, W), as the scanline method, when every
    (N, W) has equally many tiles per east colour (``row_fill_tables`` checks)."""
    tables = row_fill_tables(ts)
    assert tables is not None, "pre-drawn east colours do not apply to this set"
    choices, counts, v = tables
    c = len(ts.colours)
    rng = np.random.default_rng(seed)
    grid = np.empty((rows, cols), dtype=np.int64)
    north = np.full(cols, c, dtype=np.int64)
    south_of = ts.tiles[:, S_]
    for i in range(rows):
        east = v[rng.integers(len(v), size=cols)]
        west = np.empty(cols, dtype=np.int64)
        west[0] = c
        west[1:] = east[:-1]
        key = (north * (c + 1) + west) * c + east
        k = (rng.random(cols) * counts[key]).astype(np.int64)
        row = choices[key, k]
        grid[i] = row
        north = south_of[row]
    return grid


def test_scanline_fill_1000x1000(benchmark) -> None:
    ts = get_tileset("stochastic-2colour")
    grid = benchmark(scanline_fill, ts, SIZE, SIZE, 1)
    assert grid_mismatches(grid, ts) == []
    benchmark.extra_info["tiles"] = SIZE * SIZE


def test_row_fill_peer_1000x1000(benchmark) -> None:
    ts = get_tileset("stochastic-2colour")
    grid = benchmark(row_fill_peer, ts, SIZE, SIZE, 1)
    assert grid_mismatches(grid, ts) == []


def test_random_access_fill_1000x1000(benchmark) -> None:
    ts = get_tileset("corner-2colour")
    grid = benchmark(random_access_fill, ts, SIZE, SIZE, 0, 0, 1)
    assert grid_mismatches(grid, ts) == []
    benchmark.extra_info["tiles"] = SIZE * SIZE


@pytest.mark.parametrize("n", [20, 40])
def test_sat_jeandel_rao(benchmark, n) -> None:
    ts = get_tileset("jeandel-rao-11")
    result = benchmark.pedantic(sat_solve, args=(ts, n, n), rounds=3, iterations=1)
    assert result.tiles


def test_builder_jeandel_rao_6x6(benchmark) -> None:
    ts = get_tileset("jeandel-rao-11")
    result = benchmark.pedantic(builder_solve, args=(ts, 6, 6), rounds=1, iterations=1)
    assert result.tiles


# ---------------------------------------------------------------------- the report script


def _best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def _times(fn, repeat: int) -> list[float]:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return times


def fills(repeat: int = 5) -> None:
    """The fills at SIZE x SIZE, min / median of ``repeat`` runs; every grid checked valid."""
    scanline_fill(get_tileset("stochastic-2colour"), 4, 4, seed=1)  # compile once
    print(f"| fill | set | grid | min / median of {repeat} (s) | tiles/s (median) |")
    print("|---|---|---|---|---|")
    medians = {}
    for label, name, fn in (
        ("scanline (Cohen et al.), compiled loop", "stochastic-2colour", lambda ts: scanline_fill(ts, SIZE, SIZE, seed=1)),
        ("peer: row-by-row NumPy, pre-drawn east colours", "stochastic-2colour", lambda ts: row_fill_peer(ts, SIZE, SIZE, 1)),
        ("random access (Lagae-Dutré hash)", "corner-2colour", lambda ts: random_access_fill(ts, SIZE, SIZE, seed=1)),
    ):
        ts = get_tileset(name)
        assert grid_mismatches(fn(ts), ts) == []
        ts_ = _times(lambda fn=fn, ts=ts: fn(ts), repeat)
        medians[label] = statistics.median(ts_)
        print(f"| {label} | {name} | {SIZE} x {SIZE} | {min(ts_):.3f} / {statistics.median(ts_):.3f} | "
              f"{SIZE * SIZE / statistics.median(ts_):,.0f} |")
    a, b = list(medians.values())[:2]
    print(f"\nscanline / row-by-row peer (median): {b / a:.2f}x")


def solvers(sizes: list[int], limit: float) -> None:
    ts = get_tileset("jeandel-rao-11")
    print(f"| n | SAT (CaDiCaL 1.9.5) s | builder s | backtracking s |  (limit {limit:g} s per call)")
    print("|---|---|---|---|")
    dead = {"builder": False, "backtrack": False}
    for n in sizes:
        row = [str(n)]
        runs = [sat_solve(ts, n, n).seconds for _ in range(3)]
        row.append(f"{statistics.median(runs):.3f}")
        for key, fn in (("builder", builder_solve), ("backtrack", backtrack_solve)):
            if dead[key]:
                row.append("—")
                continue
            try:
                result = fn(ts, n, n, time_limit=limit, max_nodes=None)
                assert result.tiles
                row.append(f"{result.seconds:.3f}")
            except SolverLimit:
                row.append(f"> {limit:g} (limit)")
                dead[key] = True
        print("| " + " | ".join(row) + " |")


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="4,6,8,10,12,16,20,30,40,60,80")
    parser.add_argument("--limit", type=float, default=60.0, help="seconds per builder/backtracking call")
    parser.add_argument("--fills-only", action="store_true", help="only the fill table")
    parser.add_argument("--runs", type=int, default=5)
    return parser


def main() -> None:
    args = build_parser().parse_args()
    fills(args.runs)
    print()
    if args.fills_only:
        return
    solvers([int(s) for s in args.sizes.split(",")], args.limit)


if __name__ == "__main__":
    main()
