"""Multigrid speed and memory against the strongest simple peers, side by side in one process.

- ``peer_numpy``: the vectorised NumPy multigrid a competent user writes in 40 lines: for
  each pair of grids, every pair of line indices (k_r, k_s) whose lines cross the window
  (a meshgrid of the two index ranges), their intersections, those inside the window, then
  the index vectors K = ceil(z . e_j - gamma_j) of all of them at once as an (m, N) matrix,
  the lower vertices K @ E and the rhombs whose box meets the region. It gets the same grid
  window as tilekit (:func:`multigrid.grid_window`) and returns the same thing as
  ``multigrid.rhombs``: each rhomb's pair and lower vertex (checked equal, as sets).
- the substitution family's Penrose P3 (``tiling("penrose-p3").patch(region)``, whole
  rhombs) against ``QuasiperiodicTiling(5).patch(region)``, both Patches at the same tile count.

Run:  python benchmarks/bench_quasiperiodic.py [--runs 5] [--tiles 1000000]
      python benchmarks/bench_quasiperiodic.py --memory     (bytes per tile, tracemalloc)
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time
import tracemalloc
from functools import partial

import numpy as np

from tilekit.plugins.quasiperiodic import multigrid
from tilekit.plugins.quasiperiodic.star import star
from tilekit.plugins.quasiperiodic.tiling import QuasiperiodicTiling, default_gamma
from tilekit.plugins.substitution import tiling as substitution

ORDERS = (5, 8, 12)


def peer_numpy(n: int, gamma: np.ndarray, bounds: tuple[float, float, float, float]) -> tuple[np.ndarray, np.ndarray]:
    """(pair, lower vertex) of every rhomb whose box overlaps ``bounds`` (see the module)."""
    st = star(n)
    e = st.directions
    qx0, qy0, qx1, qy1 = multigrid.grid_window(st, gamma, bounds)
    corners = np.array([[qx0, qy0], [qx1, qy0], [qx1, qy1], [qx0, qy1]])
    x0, y0, x1, y1 = bounds
    pairs, lowers = [], []
    for p, (r, s) in enumerate(st.pairs.tolist()):
        pr, ps = corners @ e[r] - gamma[r], corners @ e[s] - gamma[s]
        kr = np.arange(math.ceil(pr.min()), math.floor(pr.max()) + 1)
        ks = np.arange(math.ceil(ps.min()), math.floor(ps.max()) + 1)
        kr, ks = (a.ravel() for a in np.meshgrid(kr, ks, indexing="ij"))
        z = np.column_stack([kr + gamma[r], ks + gamma[s]]) @ np.linalg.inv(np.array([e[r], e[s]])).T
        inside = (z[:, 0] >= qx0) & (z[:, 0] <= qx1) & (z[:, 1] >= qy0) & (z[:, 1] <= qy1)
        z, kr, ks = z[inside], kr[inside], ks[inside]
        k = np.ceil(z @ e.T - gamma)
        k[:, r], k[:, s] = kr, ks
        lower = k @ e
        b = st.pair_bounds[p]
        keep = ((lower[:, 0] + b[2] > x0 + 1e-9) & (lower[:, 0] + b[0] < x1 - 1e-9)
                & (lower[:, 1] + b[3] > y0 + 1e-9) & (lower[:, 1] + b[1] < y1 - 1e-9))
        pairs.append(np.full(int(keep.sum()), p))
        lowers.append(lower[keep])
    return np.concatenate(pairs), np.concatenate(lowers)


def keys(pair: np.ndarray, lower: np.ndarray) -> set:
    return set(zip(pair.tolist(), *np.round(lower, 6).T.tolist()))


def region_for(n: int, tiles: float, centre: tuple[float, float] = (0.0, 0.0)) -> tuple[float, float, float, float]:
    """A square of about ``tiles`` tiles of the order-n multigrid."""
    half = math.sqrt(tiles / star(n).density) / 2
    return (centre[0] - half, centre[1] - half, centre[0] + half, centre[1] + half)


def timed(f, runs: int) -> tuple[float, float, object]:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times), statistics.median(times), f()


def load() -> str:
    return "load averages " + " ".join(f"{v:.2f}" for v in os.getloadavg())


def speed(runs: int, tiles: float) -> None:
    print(f"# {load()}; {runs} runs each, min / median seconds")
    print("| n | tiles | tilekit rhombs | M tiles/s | tilekit patch() | M tiles/s | NumPy peer | ratio (peer / rhombs) | ratio (peer / patch) |")
    print("|---|---:|---|---:|---|---:|---|---:|---:|")
    for n in ORDERS:
        g, st, bounds = default_gamma(n), star(n), region_for(n, tiles)
        t = QuasiperiodicTiling(n)
        rmin, rmed, rh = timed(partial(multigrid.rhombs, st, g, bounds), runs)
        pmin, pmed, patch = timed(partial(t.patch, bounds), runs)
        qmin, qmed, (pp, pl) = timed(partial(peer_numpy, n, g, bounds), runs)
        assert keys(rh.pair, rh.lower) == keys(pp, pl), "the peer made other rhombs"
        assert len(patch) == len(rh)
        m = len(rh)
        print(f"| {n} | {m:,} | {rmin:.3f} / {rmed:.3f} | {m / rmed / 1e6:.1f} | {pmin:.3f} / {pmed:.3f} | "
              f"{m / pmed / 1e6:.1f} | {qmin:.3f} / {qmed:.3f} | **{qmed / rmed:.1f}** | **{qmed / pmed:.1f}** |")
    print()
    # the substitution family's P3 at the same tile count, whole rhombs in a region
    bounds = region_for(5, tiles)
    t = QuasiperiodicTiling(5)
    p3 = substitution("penrose-p3")
    pmin, pmed, mine = timed(partial(t.patch, bounds), runs)
    smin, smed, theirs = timed(partial(p3.patch, bounds), runs)
    print("| Penrose rhombs in the same box | tiles | min / median s | M tiles/s |")
    print("|---|---:|---|---:|")
    print(f"| multigrid-5 `patch(region)` | {len(mine):,} | {pmin:.3f} / {pmed:.3f} | {len(mine) / pmed / 1e6:.1f} |")
    print(f"| substitution penrose-p3 `patch(region)` | {len(theirs):,} | {smin:.3f} / {smed:.3f} | {len(theirs) / smed / 1e6:.1f} |")
    print(f"\nper tile, multigrid-5 is **{(smed / len(theirs)) / (pmed / len(mine)):.1f}x** the substitution's speed")
    print()
    # random access: the same region size at the origin and far away
    print("| region | where | tiles | min / median s |")
    print("|---|---|---:|---|")
    for size in (500, tiles):
        for centre in ((0.0, 0.0), (1e6, 1e6)):
            bounds = region_for(5, size, centre)
            amin, amed, got = timed(partial(t.patch, bounds), runs if size > 1000 else 50 * runs)
            print(f"| ~{size:,.0f} tiles | {centre} | {len(got):,} | {amin * 1e3:.2f} / {amed * 1e3:.2f} ms |")
    print(f"\n# {load()}")


def memory(tiles: float) -> None:
    print(f"# {load()}")
    print("| what | tiles | peak bytes / tile (tracemalloc) | result bytes / tile |")
    print("|---|---:|---:|---:|")
    for n in ORDERS:
        g, st, bounds = default_gamma(n), star(n), region_for(n, tiles)
        t = QuasiperiodicTiling(n)
        for name, f in ((f"n = {n} multigrid.rhombs", partial(multigrid.rhombs, st, g, bounds)),
                        (f"n = {n} patch()", partial(t.patch, bounds)),
                        (f"n = {n} NumPy peer", partial(peer_numpy, n, g, bounds))):
            f()  # compile and warm caches outside the measurement
            tracemalloc.start()
            out = f()
            peak = tracemalloc.get_traced_memory()[1]
            tracemalloc.stop()
            if isinstance(out, tuple):
                count, size = len(out[0]), sum(a.nbytes for a in out)
            elif hasattr(out, "transform"):
                count = len(out)
                size = out.transform.nbytes + out.prototile.nbytes + out.colour.nbytes + out.aspect.nbytes
            else:
                count, size = len(out), out.pair.nbytes + out.lower.nbytes
            print(f"| {name} | {count:,} | {peak / count:.0f} | {size / count:.0f} |")


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--tiles", type=float, default=1e6)
    ap.add_argument("--memory", action="store_true", help="bytes per tile instead of times")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    QuasiperiodicTiling(5).patch((-5, -5, 5, 5))  # load numba's cached loops before timing
    if args.memory:
        memory(args.tiles)
    else:
        speed(args.runs, args.tiles)


if __name__ == "__main__":
    main()
