"""Wang family speed: the two graphics fills at 1000 x 1000 and the exact solvers on Jeandel–Rao.

Run the timed suite:  pytest benchmarks/bench_wang.py --benchmark-enable
Print the tables of docs/benchmarks.md (Wang section):  python benchmarks/bench_wang.py
(with the project's default ``--benchmark-disable`` each test runs once, untimed).
"""

from __future__ import annotations

import argparse
import statistics
import time

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

SIZE = 1000


def test_scanline_fill_1000x1000(benchmark) -> None:
    ts = get_tileset("stochastic-2colour")
    grid = benchmark(scanline_fill, ts, SIZE, SIZE, 1)
    assert grid_mismatches(grid, ts) == []
    benchmark.extra_info["tiles"] = SIZE * SIZE


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


def fills(repeat: int = 5) -> None:
    print(f"| fill | set | grid | best of {repeat} (s) | tiles/s |")
    print("|---|---|---|---|---|")
    for label, name, fn in (
        ("scanline (Cohen et al.)", "stochastic-2colour", lambda ts: scanline_fill(ts, SIZE, SIZE, seed=1)),
        ("random access (Lagae-Dutré hash)", "corner-2colour", lambda ts: random_access_fill(ts, SIZE, SIZE, seed=1)),
    ):
        ts = get_tileset(name)
        t = _best(lambda fn=fn, ts=ts: fn(ts), repeat)
        print(f"| {label} | {name} | {SIZE} x {SIZE} | {t:.3f} | {SIZE * SIZE / t:,.0f} |")


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="4,6,8,10,12,16,20,30,40,60,80")
    parser.add_argument("--limit", type=float, default=60.0, help="seconds per builder/backtracking call")
    args = parser.parse_args()
    fills()
    print()
    solvers([int(s) for s in args.sizes.split(",")], args.limit)


if __name__ == "__main__":
    main()
