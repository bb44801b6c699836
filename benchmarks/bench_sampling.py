"""Tile-based importance sampling (§7.4) against dart throwing, at N = 10^6, in one process.

Peers, both making a Poisson-disk set of the same N points over the unit square (uniform
density, which is all they support):
  * scipy.stats.qmc.PoissonDisk (Bridson's algorithm, the existing library call), filling the
    square (``fill_space``) with radius 0.775 / sqrt(N), which gives about N points (0.80 gave
    0.94 N at N = 4096); asking it for exactly N points with ``random(N)`` instead stops its
    growing front before the square is full, a set with a hole, so the full fill is the peer;
  * a vectorised NumPy dart thrower (the twenty-line peer): rounds of candidate darts, each
    checked against the accepted points through a background grid of cells of side r / sqrt(2)
    (at most one point a cell) and against the other darts of its round through a k-d tree;
    a dart conflicting with either is dropped; stops at N points.

Run:  python benchmarks/bench_sampling.py [--n 1000000] [--repeat 3] [--skip-scipy]
Prints points per second (min and median of the runs), the ratios, and `uptime`.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import time

import numpy as np
from scipy.spatial import cKDTree

from tilekit.density import density_from
from tilekit.sampling import nearest_neighbour_distances, sample


def numpy_dart_throwing(n: int, radius: float, seed: int = 0, batch: int | None = None) -> np.ndarray:
    """Up to ``n`` points in [0, 1)^2 with pairwise distances >= ``radius`` by rounds of darts."""
    rng = np.random.default_rng(seed)
    cell = radius / math.sqrt(2.0)
    g = int(math.ceil(1.0 / cell))
    grid = np.full((g + 4, g + 4), -1, dtype=np.int64)  # a margin of 2 cells: no bounds checks
    pts = np.empty((n, 2))
    count = 0
    batch = batch or max(1000, n // 4)
    offsets = np.array([(a, b) for a in range(-2, 3) for b in range(-2, 3)])
    while count < n:
        d = rng.random((batch, 2))
        ci = (d / cell).astype(np.int64) + 2
        # against accepted points: the 5 x 5 cells around the dart
        nb = grid[ci[:, 0, None] + offsets[:, 0], ci[:, 1, None] + offsets[:, 1]]  # (batch, 25)
        has = nb >= 0
        near = np.zeros(batch, dtype=bool)
        if has.any():
            q = pts[np.where(has, nb, 0)]
            dist2 = np.sum((q - d[:, None, :]) ** 2, axis=2)
            near = np.any(has & (dist2 < radius * radius), axis=1)
        d, ci = d[~near], ci[~near]
        # against the other darts of the round: drop both ends of every close pair
        pairs = cKDTree(d).query_pairs(radius, output_type="ndarray")
        ok = np.ones(len(d), dtype=bool)
        ok[pairs.ravel()] = False
        d, ci = d[ok], ci[ok]
        # two survivors can share a cell only if closer than r: impossible now
        take = min(len(d), n - count)
        if take == 0:
            if batch > 50 * n:
                break
            batch *= 2
            continue
        pts[count : count + take] = d[:take]
        grid[ci[:take, 0], ci[:take, 1]] = np.arange(count, count + take)
        count += take
    return pts[:count]


def timed(fn, repeat: int):
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), statistics.median(times), out


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--skip-scipy", action="store_true", help="leave out qmc.PoissonDisk (slow at 10^6)")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    n = args.n
    uniform = density_from("uniform", size=64)
    ramp = density_from("ramp")
    rows = []

    def run(label, fn, repeat=args.repeat):
        lo, med, pts = timed(fn, repeat)
        dmin = nearest_neighbour_distances(pts).min() * math.sqrt(len(pts))
        rows.append((label, len(pts), lo, med, dmin))
        print(f"{label:48s} {len(pts):>9,d} pts  min {lo:7.2f} s  median {med:7.2f} s  "
              f"{len(pts) / lo:>12,.0f} pts/s  min NN x sqrt(N) {dmin:.3f}", flush=True)

    for method in ("penrose", "polyomino", "wang"):  # warm up: systems, tile sets, compiled kernels
        sample(uniform, 1000, method, seed=1, relax=0)
    for method in ("penrose", "polyomino", "wang"):
        run(f"{method} (uniform)", lambda m=method: sample(uniform, n, m, seed=1).points)
        run(f"{method} (ramp)", lambda m=method: sample(ramp, n, m, seed=1).points)
    for method in ("penrose", "polyomino"):
        run(f"{method} (uniform, no correction table)", lambda m=method: sample(uniform, n, m, seed=1, correct=False).points)
    run("penrose (uniform, + 1 Lloyd iteration)", lambda: sample(uniform, n, "penrose", seed=1, relax=1).points, 1)
    radius = 0.75 / math.sqrt(n)
    run("numpy dart throwing (uniform)", lambda: numpy_dart_throwing(n, radius, seed=1))
    if not args.skip_scipy:
        from scipy.stats import qmc

        run("scipy.stats.qmc.PoissonDisk fill_space (uniform)",
            lambda: qmc.PoissonDisk(2, radius=0.775 / math.sqrt(n), seed=1).fill_space(), 1)
    best = {label: count / lo for label, count, lo, _, _ in rows}
    print()
    for peer in [r for r in best if "dart" in r or "Poisson" in r]:
        for label in best:
            if label.startswith(("penrose", "polyomino", "wang")) and "uniform" in label:
                print(f"{label:48s} / {peer}: {best[label] / best[peer]:8.1f} x")
    print("\nuptime:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip(), "| cpus:", os.cpu_count())


if __name__ == "__main__":
    main()
