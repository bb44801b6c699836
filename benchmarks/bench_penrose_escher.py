"""Penrose Escherization speed and quality against the same optimiser without the linear edge model.

tilekit's method (tilekit.plugins.substitution.penrose_escher): Nelder-Mead over the four
quasivertex parameters only, each evaluation projecting the edge shapes' control points by
linear least squares for both rhombs, then a joint least-squares polish. The peer is what a
competent user writes first: ``scipy.optimize.minimize(method="L-BFGS-B")`` over ALL
variables (the four parameters and every control point, finite-difference gradients) of the
same objective (the larger of the two rhombs' metric distances, the same FFT alignment over
shifts and mirror images), from the same starts, with the same validity check (patch
validated, matching rules) and distance report at the end.

With ``--tiling p2`` the same comparison runs on the kite and dart (goal A: kite, goal B: dart).

Run: python benchmarks/bench_penrose_escher.py [--tiling p3|p2] [--pairs fish,fish+bird,known] [--starts 4] [--repeat 1]
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

from tilekit import escher
from tilekit.plugins.substitution import penrose_escher as pe
from tilekit.plugins.substitution import tiling

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data" / "escher"


def goals(name: str, system: str = "penrose-p3") -> list[np.ndarray]:
    """fish / bird (one goal), fish+bird (thick / kite: fish, thin / dart: bird), known (a deformed pair)."""
    if name == "known":
        t = tiling(system).configure(r1=0.12, theta1=25, r2=0.2, theta2=-15,
                                     edges=["a=0.25,0.06:0.5,0.1:0.75,0.04", "c=0.5,0.07", "f=0.4,-0.06"])
        tiles = {p.name: np.asarray(p.outline) for p in t.prototiles}
        return [tiles[n] for n in pe.GOAL_TILES[system]]
    return [escher.read_goal(DATA / f"{part}.json") for part in name.split("+")]


def peer(gs: list[np.ndarray], settings: pe.PenroseSettings, system: str = "penrose-p3") -> pe.PenroseResult:
    """L-BFGS-B over (q, x) on the larger of the two distances, the same starts and checks."""
    with threadpool_limits(limits=1, user_api="blas"):
        t0 = time.perf_counter()
        model = pe.PenroseModel(settings.edge_points, system)
        pair = gs if len(gs) == 2 else [gs[0], gs[0]]
        banks = [escher.GoalBank.build(g, settings.samples, settings.reflection) for g in pair]
        evaluations = 0

        def f(z: np.ndarray) -> float:
            nonlocal evaluations
            evaluations += 1
            if model.bad(z[:4]):
                return 2.0
            return max(b.align(escher.resample(o, settings.samples))[0]
                       for o, b in zip(model.outlines(z[:4], z[4:]), banks))

        best = None
        for s in pe._starts(settings, model):
            res = minimize(f, np.concatenate([s, model.c0]), method="L-BFGS-B")
            if best is None or res.fun < best.fun:
                best = res
        r = pe._valid_result(model, best.x[:4], best.x[4:], pair, system, settings)
        r.evaluations = evaluations
        r.seconds = time.perf_counter() - t0
        return r


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--tiling", default="p3", choices=pe.TILINGS)
    ap.add_argument("--pairs", default="fish,fish+bird,known")
    ap.add_argument("--starts", type=int, default=pe.DEFAULT_STARTS)
    ap.add_argument("--repeat", type=int, default=1)
    return ap


def main() -> None:
    args = build_parser().parse_args()
    settings = pe.PenroseSettings(starts=args.starts)
    system = pe.SYSTEMS[args.tiling]
    print(f"load {os.getloadavg()}; {system}; starts {args.starts}")
    for name in args.pairs.split(","):
        gs = goals(name, system)
        ours, theirs = [], []
        for _ in range(args.repeat):
            t0 = time.process_time()
            r = pe.escherize_penrose(*gs, tiling=args.tiling, settings=settings)
            ours.append((time.process_time() - t0, r))
            t0 = time.process_time()
            p = peer(gs, settings, system)
            theirs.append((time.process_time() - t0, p))
        ot = [t for t, _ in ours]
        pt = [t for t, _ in theirs]
        r, p = ours[-1][1], theirs[-1][1]
        print(f"{name}: tilekit CPU min {min(ot):.1f} s median {statistics.median(ot):.1f} s, d = {r.distance:.5f} "
              f"(shrink {r.shrink:g}, {r.evaluations} evaluations); peer CPU min {min(pt):.1f} s median "
              f"{statistics.median(pt):.1f} s, d = {p.distance:.5f} (shrink {p.shrink:g}, {p.evaluations} evaluations); "
              f"time ratio {min(pt) / min(ot):.1f}x", flush=True)
    print(f"load after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
