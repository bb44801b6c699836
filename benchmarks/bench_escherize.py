"""Escherization speed and quality: the 81 unmarked types against a 100-point goal.

tilekit's method (tilekit.plugins.isohedral.escher): Nelder-Mead over the tiling vertex
parameters only, each evaluation projecting the edge control points by linear least squares
(Koizumi and Sugihara's linearity), then a joint least-squares polish. The peer is what a
competent user writes first: ``scipy.optimize.minimize(method="L-BFGS-B")`` over ALL
variables (tiling vertex parameters and every control point, finite-difference gradients)
of the same metric (arc-length resampling, FFT alignment over shifts and the mirror image),
from the same starts (the default parameters with straight edges, then the same random
perturbations), with the same validity check and distance report at the end.

Run: python benchmarks/bench_escherize.py [--goal tests/data/escher/fish.json] [--repeat 1]
     [--peer-types all|IH1,IH4,...] [--skip-peer]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from pathlib import Path

import numpy as np
from scipy.optimize import minimize
from threadpoolctl import threadpool_limits

from tilekit.plugins.isohedral import escher

ROOT = Path(__file__).resolve().parent.parent


def peer_type(goal: np.ndarray, ih: int, settings: escher.Settings) -> escher.EscherResult:
    """scipy.optimize.minimize (L-BFGS-B) over parameters and control points together."""
    with threadpool_limits(limits=1, user_api="blas"):  # the same BLAS setting as tilekit's
        t0 = time.perf_counter()
        model = escher.type_model(ih, settings.edge_points)
        bank = escher.GoalBank.build(goal, settings.samples, settings.reflection)
        npar = model.n_params
        evaluations = 0

        def f(x: np.ndarray) -> float:
            nonlocal evaluations
            evaluations += 1
            bad = model.polygon_ok(x[:npar])
            if bad:
                return 1.0 + bad
            return bank.align(escher.resample(model.outline(x[:npar], x[npar:]), settings.samples))[0]

        rng = np.random.default_rng([settings.seed, ih])
        starts = [model.default]
        if npar:
            spread = 0.25 * max(1.0, float(np.max(np.abs(model.default))))
            starts += [model.default + spread * rng.standard_normal(npar) for _ in range(settings.starts - 1)]
        best = None
        for s in starts:
            if model.polygon_ok(s):
                continue
            res = minimize(f, np.concatenate([s, model.c0]), method="L-BFGS-B")
            if best is None or res.fun < best.fun:
                best = res
        assert best is not None
        r = escher._valid_result(model, best.x[:npar], best.x[npar:], goal, settings, bank)
        r.evaluations = evaluations
        r.seconds = time.perf_counter() - t0
        return r


def run_all(goal: np.ndarray, workers: int, repeat: int) -> tuple[list[float], list[escher.EscherResult]]:
    walls = []
    results: list[escher.EscherResult] = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        results, failed = escher.escherize(goal, workers=workers)
        walls.append(time.perf_counter() - t0)
        assert not failed, failed
    return walls, results


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--goal", default=str(ROOT / "tests" / "data" / "escher" / "fish.json"))
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--peer-types", default="all")
    ap.add_argument("--skip-peer", action="store_true")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    goal = escher.read_goal(args.goal)
    print(f"goal {args.goal}: {len(goal)} points; load {os.getloadavg()}")

    t0 = time.perf_counter()
    for ih in escher.unmarked_types():
        escher.type_model(ih)
    print(f"type models (read from the engine once per process): {time.perf_counter() - t0:.2f} s for 81 types")

    walls1, res1 = run_all(goal, 1, args.repeat)
    per = sorted(r.seconds for r in res1)
    print(f"serial, all 81 types: {min(walls1):.1f} s wall (runs {', '.join(f'{w:.1f}' for w in walls1)}); "
          f"per type min {per[0]:.3f} median {statistics.median(per):.3f} max {per[-1]:.3f} s")
    slow = sorted(res1, key=lambda r: -r.seconds)[:3]
    print("  slowest: " + ", ".join(f"{r.name} {r.seconds:.2f} s ({r.evaluations} evaluations)" for r in slow))
    walls2, res2 = run_all(goal, 2, args.repeat)
    print(f"2 workers, all 81 types: {min(walls2):.1f} s wall (runs {', '.join(f'{w:.1f}' for w in walls2)}); "
          f"speed-up {min(walls1) / min(walls2):.2f}x")
    assert [r.ih for r in res1] == [r.ih for r in res2]
    print("best 5: " + ", ".join(f"{r.name} {r.distance:.4f}" for r in res1[:5]))
    print(f"load after: {os.getloadavg()}")

    if args.skip_peer:
        return
    types = escher.unmarked_types() if args.peer_types == "all" else escher.parse_types(args.peer_types)
    ours = {r.ih: r for r in res1}
    settings = escher.Settings()
    rows = []
    for ih in types:
        p = peer_type(goal, ih, settings)
        rows.append((ih, ours[ih].seconds, p.seconds, ours[ih].distance, p.distance, ours[ih].evaluations, p.evaluations))
        print(f"  IH{ih:<3} tilekit {ours[ih].seconds:6.2f} s d={ours[ih].distance:.4f}   "
              f"peer {p.seconds:6.2f} s d={p.distance:.4f}  ({p.evaluations} evaluations)", flush=True)
    t_ours = sum(r[1] for r in rows)
    t_peer = sum(r[2] for r in rows)
    better = sum(r[3] < r[4] - 1e-4 for r in rows)
    worse = sum(r[3] > r[4] + 1e-4 for r in rows)
    ratio = [r[3] / r[4] for r in rows if r[4] > 0]
    best_ours = min(rows, key=lambda r: r[3])
    best_peer = min(rows, key=lambda r: r[4])
    print(f"peer over {len(rows)} types: time tilekit {t_ours:.1f} s, peer {t_peer:.1f} s, ratio {t_peer / t_ours:.1f}x; "
          f"distance tilekit/peer median {statistics.median(ratio):.2f} (tilekit better on {better}, worse on {worse}, "
          f"equal within 1e-4 on {len(rows) - better - worse}); best type tilekit IH{best_ours[0]} {best_ours[3]:.4f}, "
          f"peer IH{best_peer[0]} {best_peer[4]:.4f}")
    print(f"load after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
