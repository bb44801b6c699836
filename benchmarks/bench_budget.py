"""What the CPU-time budget's bookkeeping costs the polyform classification.

A fixed set of shapes that reach the SAT stages (every hole-free form with no boundary-word
factorisation: the 8-ominoes, 6-hexes and 9-iamonds) is classified with the search's bounds,
once with ``time_limit=None`` (no budget: no clock reads, no watchdog) and once with the
search's default budget of 300 CPU seconds (a :class:`tilekit.budget.Budget` checked between
the stages and by the watchdog during every solve), in alternating passes. Each pass's CPU
seconds (the thread's clock) are compared: the ratio of the medians and of the minima. The
verdicts are checked equal. The cost of the budget's own calls is printed too.

    python benchmarks/bench_budget.py --repeats 5
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import tilekit.sat as sat  # noqa: E402
from tilekit.budget import Budget, thread_cpu_clock  # noqa: E402
from tilekit.lattice import free_polyforms, get_grid  # noqa: E402
from tilekit.plugins.polyomino.classify import classify  # noqa: E402
from tilekit.plugins.polyomino.isohedral import analyse_many  # noqa: E402

#: The fixed set: (grid, cells).
SETS = (("square", 8), ("hex", 6), ("iamond", 9))
#: The polyomino-classify search's default time limit (CPU seconds per form).
SEARCH_LIMIT = 300.0


def shapes() -> list[tuple]:
    """(grid, cells, analysis) of every hole-free n-form with no boundary-word factorisation."""
    out = []
    for name, n in SETS:
        grid = get_grid(name)
        polys, flags, _ = free_polyforms(grid, n, with_holes=True)
        forms = [p for p, h in zip(polys, flags) if len(p) == n and not h]
        for cells, a in zip(forms, analyse_many(grid, forms)):
            if not a.get("isohedral"):
                out.append((grid, cells, a))
    return out


def one_pass(todo: list[tuple], limit: float | None) -> tuple[float, float, list[tuple]]:
    """(thread CPU seconds, wall seconds, verdicts) of classifying ``todo`` once."""
    clock = thread_cpu_clock()
    c0, w0 = clock(), time.perf_counter()
    verdicts = []
    for grid, cells, a in todo:
        c = classify(grid, cells, a, time_limit=limit)
        verdicts.append((c.tiles, c.anisohedral_k, c.heesch, c.heesch_holes))
    return clock() - c0, time.perf_counter() - w0, verdicts


def solver_calls(todo: list[tuple]) -> int:
    """How many solves one budgeted pass makes (each arms and disarms the watchdog once): a
    counting pass, not timed."""
    real, count = sat._run, [0]

    def counted(*args):
        count[0] += 1
        return real(*args)

    sat._run = counted
    try:
        one_pass(todo, SEARCH_LIMIT)
    finally:
        sat._run = real
    return count[0]


def per_call(fn, n: int = 100_000) -> float:
    """Microseconds per call of ``fn`` (thread CPU)."""
    clock = thread_cpu_clock()
    t = clock()
    for _ in range(n):
        fn()
    return (clock() - t) / n * 1e6


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5, help="passes of each mode, alternating")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    todo = shapes()
    print(f"{len(todo)} shapes ({', '.join(f'{g} n={n}' for g, n in SETS)}: hole-free, no boundary factorisation)")
    one_pass(todo, None)  # warm-up: the compiled kernels load once
    cpu: dict[str, list[float]] = {"plain": [], "budget": []}
    wall: dict[str, list[float]] = {"plain": [], "budget": []}
    reference = None
    for r in range(args.repeats):
        order = ("plain", "budget") if r % 2 == 0 else ("budget", "plain")
        for mode in order:
            c, w, verdicts = one_pass(todo, None if mode == "plain" else SEARCH_LIMIT)
            reference = reference or verdicts
            if verdicts != reference:
                raise SystemExit(f"the verdicts differ ({mode}, pass {r})")
            cpu[mode].append(c)
            wall[mode].append(w)
    for mode in ("plain", "budget"):
        print(f"{mode:7s} CPU min {min(cpu[mode]):.3f} s  median {statistics.median(cpu[mode]):.3f} s   "
              f"wall median {statistics.median(wall[mode]):.3f} s")
    print(f"budget / plain CPU: median {statistics.median(cpu['budget']) / statistics.median(cpu['plain']):.3f}, "
          f"min {min(cpu['budget']) / min(cpu['plain']):.3f}; verdicts equal on {len(reference)} shapes")
    b = Budget(SEARCH_LIMIT)
    print(f"Budget(...) made {per_call(lambda: Budget(1.0), 20_000):.2f} us, spent() {per_call(b.spent):.2f} us, "
          f"wake_in() {per_call(b.wake_in):.2f} us (thread CPU per call); {solver_calls(todo)} solves a pass")
    print(f"load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
