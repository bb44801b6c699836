"""Builder torus mode: placements per second as the torus grows (10^2, 10^3, 10^4 tiles).

Unit squares on the n x n torus (period (n, 0), (0, n)), default goal (a closed torus), bfs
order: n^2 representatives, each placed with its 3 x 3 block of lattice images. The next
edge comes from the frontier's heap, so the rate should not fall as the torus grows.

Run: python benchmarks/bench_builder_torus.py [--peer PATH_TO_OLD_BUILDER_PY] [--sides 10 32 100] [--repeat 5]
(the peer is the builder of another commit, e.g. ``git show f7ace6b:tilekit/builder.py >
/tmp/builder_old.py``, run on the same tori in the same process); or as a pytest benchmark:
pytest benchmarks/bench_builder_torus.py --benchmark-enable
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import sys
import time

import numpy as np
import pytest

from tilekit import Prototile
from tilekit.builder import PatchBuilder
from tilekit.geometry import regular_polygon


def torus_run(builder_cls: type, side: int, choice_clock: list[float] | None = None,
              cpu_clock: list[float] | None = None) -> tuple[int, float, int]:
    """(representatives, seconds, placements) of one closed n x n torus of unit squares.
    With ``cpu_clock`` (a one-element list) the process CPU seconds of the build are added to
    it: on a shared machine the wall clock measures the load as much as the builder.
    With ``choice_clock`` (a one-element list) the seconds spent choosing the next edge
    (``_Frontier.choose``, or ``_choose`` in builders before the frontier) are added to it."""
    square = [Prototile(regular_polygon(4))]
    builder = builder_cls(square, period=((side, 0.0), (0.0, side)))
    if choice_clock is not None:
        _clock_choices(builder, choice_clock)
    start, cpu = time.perf_counter(), time.process_time()
    res = builder.build(max_nodes=10_000_000)
    seconds = time.perf_counter() - start
    if cpu_clock is not None:
        cpu_clock[0] += time.process_time() - cpu
    assert res.status == "complete", res.stats.reason
    assert len(res.patch) == side * side
    return len(res.patch), seconds, res.stats.placements


def _clock_choices(builder: object, clock: list[float]) -> None:
    def timed(fn):
        def wrapper(*args, **kwargs):
            t = time.perf_counter()
            try:
                return fn(*args, **kwargs)
            finally:
                clock[0] += time.perf_counter() - t
        return wrapper

    if hasattr(builder, "_choose"):  # the scanning builder
        builder._choose = timed(builder._choose)
        return
    reset = builder._reset

    def reset_and_clock(*args, **kwargs):
        reset(*args, **kwargs)
        builder._frontier.choose = timed(builder._frontier.choose)

    builder._reset = reset_and_clock


@pytest.mark.parametrize("side", [10, 32])
def test_torus_placements_per_second(benchmark, side) -> None:
    n, seconds, placements = benchmark(torus_run, PatchBuilder, side)
    benchmark.extra_info["tiles"] = n
    benchmark.extra_info["placements_per_second"] = round(placements / seconds)


def _load_peer(path: str) -> type:
    spec = importlib.util.spec_from_file_location("builder_peer", path)
    mod = importlib.util.module_from_spec(spec)
    assert spec.loader is not None
    sys.modules["builder_peer"] = mod  # dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod.PatchBuilder


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sides", type=int, nargs="+", default=[10, 32, 100])
    ap.add_argument("--peer", help="path of another builder.py to time on the same tori")
    ap.add_argument("--peer-max-side", type=int, default=100)
    ap.add_argument("--repeat", type=int, default=5, help="runs per torus (min and median are shown)")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    builders = [("this", PatchBuilder)]
    if args.peer:
        builders.append(("peer", _load_peer(args.peer)))
    print(f"load average at start: {' '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)
    print("| builder | torus | tiles | placements | wall s (min / median) | placements/s, wall (best / median) "
          "| placements/s, CPU (best / median) | next-edge choice, µs/step |")
    print("|---|---|---|---|---|---|---|---|")
    for name, cls in builders:
        for side in args.sides:
            if name == "peer" and side > args.peer_max_side:
                continue
            clocks, cpus, runs = [], [], []
            for _ in range(args.repeat):
                clock, cpu = [0.0], [0.0]
                runs.append(torus_run(cls, side, clock, cpu))
                clocks.append(clock[0])
                cpus.append(cpu[0])
                print(f"  run {len(runs)}: {side} x {side}, {runs[-1][1]:.3g} s wall, {cpu[0]:.3g} s CPU, "
                      f"load {os.getloadavg()[0]:.2f}", file=sys.stderr, flush=True)
            n, _, placements = runs[0]
            wall = np.array([r[1] for r in runs])
            cpu_s = np.array(cpus)
            choice = 1e6 * float(np.min(clocks)) / placements
            print(f"| {name} | {side} x {side} | {n} | {placements} | {wall.min():.3g} / {np.median(wall):.3g} "
                  f"| {placements / wall.min():,.0f} / {placements / np.median(wall):,.0f} "
                  f"| {placements / cpu_s.min():,.0f} / {placements / np.median(cpu_s):,.0f} | {choice:.0f} |",
                  flush=True)
    print(f"load average at end: {' '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)

if __name__ == "__main__":
    main()
