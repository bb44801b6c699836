"""Substitution speed: tiles generated per second at ~10^6 tiles (Penrose P3), array engine
versus the recursive DRAW procedure exactly as the book gives it (§6.1), side by side.

Run the comparison table:   python benchmarks/bench_substitution.py
Run as pytest-benchmark:    pytest benchmarks/bench_substitution.py --benchmark-enable
(with the project's default ``--benchmark-disable`` each function runs once, untimed).
"""

from __future__ import annotations

import sys
import time

import numpy as np

from tilekit.geometry import Affine
from tilekit.plugins.substitution import builtin_systems
from tilekit.plugins.substitution.engine import assemble, generate

#: From one obtuse Robinson triangle, depth 14 gives F(30) = 832,040 half-rhombs.
DEPTH = 14


def book_draw(rules: list[list[tuple[int, np.ndarray]]], i0: int, m0: np.ndarray, level: int, out: list) -> None:
    """DRAW(i0, M0, l, rules) of §6.1: recurse with M0 M until l = 0, then DRAWONETILE."""
    if level == 0:
        out.append((i0, m0))  # DRAWONETILE(i0, M0): record the placement
    else:
        for i, m in rules[i0]:
            book_draw(rules, i, m0 @ m, level - 1, out)


def run_book(depth: int = DEPTH) -> tuple[int, float]:
    s = builtin_systems()["penrose-p3"]
    rules = [[(int(j), m) for j, m in zip(r.children, r.matrices)] for r in s.rules]
    out: list = []
    start = time.perf_counter()
    book_draw(rules, s.seed, Affine.scaling(s.scale**depth), depth, out)
    return len(out), time.perf_counter() - start


def run_engine(depth: int = DEPTH) -> tuple[int, float]:
    s = builtin_systems()["penrose-p3"]
    start = time.perf_counter()
    proto, _ = generate(s, depth, Affine.scaling(s.scale**depth), s.seed)
    return len(proto), time.perf_counter() - start


def run_engine_with_assembly(depth: int = DEPTH) -> tuple[int, int, float]:
    s = builtin_systems()["penrose-p3"]
    start = time.perf_counter()
    proto, tr = generate(s, depth, Affine.scaling(s.scale**depth), s.seed)
    whole, _ = assemble(s, proto, tr)
    return len(proto), len(whole), time.perf_counter() - start


def test_engine_p3(benchmark) -> None:
    n, _ = benchmark.pedantic(run_engine, rounds=3, iterations=1)
    assert n == 832_040


def test_book_draw_p3(benchmark) -> None:
    n, _ = benchmark.pedantic(run_book, rounds=1, iterations=1)
    assert n == 832_040


def main() -> None:
    depth = int(sys.argv[1]) if len(sys.argv) > 1 else DEPTH
    best_engine = min(run_engine(depth)[1] for _ in range(3))
    n, _ = run_engine(depth)
    halves, rhombs, t_assembly = min((run_engine_with_assembly(depth) for _ in range(3)), key=lambda r: r[2])
    nb, t_book = run_book(depth)
    assert nb == n
    print(f"Penrose P3, depth {depth} from one obtuse half-rhomb: {n:,} half-rhombs")
    print(f"{'method':44s} {'seconds':>9s} {'tiles/s':>14s}")
    print(f"{'recursive DRAW (book, §6.1)':44s} {t_book:9.3f} {n / t_book:14,.0f}")
    print(f"{'array engine (batched levels)':44s} {best_engine:9.3f} {n / best_engine:14,.0f}")
    print(f"{'array engine + whole-rhomb assembly':44s} {t_assembly:9.3f} {halves / t_assembly:14,.0f}"
          f"   ({rhombs:,} rhombs)")
    print(f"speed-up of the engine over DRAW: {t_book / best_engine:.1f}x")


if __name__ == "__main__":
    main()
