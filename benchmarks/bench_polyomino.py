"""Polyomino benchmarks: Redelmeier (numba) against a plain Python Redelmeier counter, the
isohedral test per polyomino (one by one and one compiled call per chunk), the stored
``--max-cells 12`` run with the isohedral test, and counting to n = 16 and 18.

    .venv/bin/python benchmarks/bench_polyomino.py [--quick] [--workers 2] [--n18]

Prints one line per measurement (min and median of several runs where cheap); the figures
go to docs/benchmarks.md.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from concurrent.futures import ProcessPoolExecutor

from tilekit.lattice import SQUARE, count_fixed, enumerate_free, prefixes
from tilekit.plugins.polyomino.isohedral import analyse, analyse_many


def plain_redelmeier(n: int) -> list[int]:
    """The peer: Redelmeier's algorithm as a competent user writes it (sets, recursion)."""
    counts = [0] * (n + 1)

    def allowed(c):
        return c[1] > 0 or (c[1] == 0 and c[0] >= 0)

    def rec(untried: list, poly: set, reached: set, size: int) -> None:
        while untried:
            c = untried.pop()
            counts[size + 1] += 1
            if size + 1 < n:
                new = []
                x, y = c
                for q in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)):
                    if allowed(q) and q not in reached:
                        new.append(q)
                reached.update(new)
                poly.add(c)
                rec(untried + new, poly, reached, size + 1)
                poly.discard(c)
                reached.difference_update(new)

    rec([(0, 0)], set(), {(0, 0)}, 0)
    return counts


def timed(fn, repeat: int = 3):
    times = []
    out = None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return out, min(times), statistics.median(times)


def isohedral_rate(n: int) -> None:
    """The isohedral test of every hole-free n-omino: one compiled call for the whole list
    (``analyse_many``, what a chunk does) against ``analyse`` one polyomino at a time."""
    polys, flags, _ = enumerate_free(SQUARE, n, maxsize=n, with_holes=True)
    plain = [p for p, h in zip(polys, flags) if not h and len(p) == n]
    analyse_many(SQUARE, plain[:10])  # load the numba cache
    _, bmin, bmed = timed(lambda: analyse_many(SQUARE, plain), repeat=3)
    some = plain[::10]
    _, omin, _ = timed(lambda: [analyse(SQUARE, p, construct=False) for p in some], repeat=1)
    print(f"isohedral test, {len(plain)} hole-free {n}-ominoes: analyse_many {bmin:.2f}s min / {bmed:.2f}s median "
          f"({1e6 * bmin / len(plain):.0f} us each); analyse one by one {1e6 * omin / len(some):.0f} us each "
          f"({len(some)} of them)")


def _stored_chunk(args):
    from tilekit.plugins.polyomino.search import chunk_rows

    params, chunk = args
    rows, counts = chunk_rows(params, chunk)
    return len(rows["polyominoes"]), counts


def _count_chunk(args):
    n, pre = args
    return count_fixed(SQUARE, n, prefix=pre)["fixed"]


def stored_run(n: int, workers: int) -> tuple[int, float]:
    from tilekit.plugins.polyomino.search import chunks

    params = {"max_cells": n}
    cs = chunks(params)
    t = time.perf_counter()
    with ProcessPoolExecutor(workers) as ex:
        res = list(ex.map(_stored_chunk, [(params, c) for c in cs]))
    return sum(r[0] for r in res), time.perf_counter() - t


def parallel_fixed(n: int, depth: int, workers: int) -> tuple[int, float]:
    pres = prefixes(SQUARE, n, depth, 0)
    t = time.perf_counter()
    with ProcessPoolExecutor(workers) as ex:
        res = list(ex.map(_count_chunk, [(n, p) for p in pres], chunksize=4))
    top = count_fixed(SQUARE, n, maxsize=depth - 1)["fixed"]
    total = sum(int(r[n]) for r in res) + int(top[n])
    return total, time.perf_counter() - t


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--n18", action="store_true")
    ap.add_argument("--quick", action="store_true")
    return ap


def main() -> None:
    a = build_parser().parse_args()
    print("uptime:", os.popen("uptime").read().strip())
    count_fixed(SQUARE, 4, free=True)  # compile / load the numba cache
    n = 10 if a.quick else 11
    ref, pmin, pmed = timed(lambda: plain_redelmeier(n), repeat=1 if not a.quick else 2)
    ours, omin, omed = timed(lambda: count_fixed(SQUARE, n)["fixed"].tolist(), repeat=5)
    assert ref == ours, (ref, ours)
    nodes = sum(ref)
    print(f"fixed n<= {n}: {nodes} nodes; plain Python Redelmeier {pmin:.2f}s ({nodes / pmin:,.0f}/s); "
          f"numba {omin:.3f}s min / {omed:.3f}s median ({nodes / omin:,.0f}/s); ratio {pmin / omin:.0f}x")
    for m in (14, 16):
        c, tmin, tmed = timed(lambda m=m: count_fixed(SQUARE, m)["fixed"], repeat=2)
        print(f"count fixed to n={m}: {int(c[m])} in {tmin:.2f}s (median {tmed:.2f}s), one process")
    c, t = timed(lambda: count_fixed(SQUARE, 14, free=True), repeat=1)[:2]
    print(f"count fixed+free+holey to n=14: free {int(c['free'][14])} holey {int(c['holey'][14])} in {t:.2f}s")
    isohedral_rate(10 if a.quick else 11)
    rows, t = stored_run(10 if a.quick else 12, a.workers)
    print(f"stored run --max-cells {10 if a.quick else 12} (rows + isohedral test), {a.workers} workers: "
          f"{rows} rows in {t:.1f}s")
    if a.n18:
        total, t = parallel_fixed(18, 7, a.workers)
        print(f"count fixed to n=18 in {a.workers} processes: {total} in {t:.1f}s")
    print("uptime:", os.popen("uptime").read().strip())


if __name__ == "__main__":
    main()
