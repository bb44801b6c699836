"""Dihedral Escherization speed and quality, per goal pair and type, against the peer.

tilekit's method (tilekit.plugins.isohedral.dihedral): end pairs screened, Nelder-Mead over
the tiling vertex parameters and the two ends only, each evaluation projecting the edge
control points and the splitting path's points by linear least squares, then a joint
least-squares polish. The peer is the same optimiser without the linear model, the peer of
the monohedral round: ``scipy.optimize.minimize(method="L-BFGS-B")`` over ALL variables
(parameters, control points, path points, both ends; finite-difference gradients) of the same
objective (the larger piece distance with the same penalties), from the same starts (the
default parameters, straight edges, the straight chord between each of tilekit's screened end
pairs, as many as --starts), with the same validity check and distance report at the end.

Run: python benchmarks/bench_escherize_dihedral.py [--types IH1,IH41,IH84] [--repeat 1]
Times are CPU seconds of this process (time.process_time) and wall seconds; the load is printed.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import time
from pathlib import Path

import numpy as np
from scipy.optimize import minimize
from threadpoolctl import threadpool_limits

from tilekit.plugins.isohedral import dihedral, escher
from tilekit.plugins.isohedral.spec import tiling_from_spec
from tilekit.polygon import signed_area

ROOT = Path(__file__).resolve().parent.parent
#: The synthetic pair: the two pieces of a known IH1 split tile (tests/plugins/test_escherize_dihedral.py).
KNOWN = json.loads((ROOT / "tests" / "data" / "escher" / "ih1-split.json").read_text())


def peer_type(a: np.ndarray, b: np.ndarray, ih: int, settings: dihedral.DihedralSettings) -> dihedral.DihedralResult:
    """scipy.optimize.minimize (L-BFGS-B) over everything, on the objective written directly."""
    with threadpool_limits(limits=1, user_api="blas"):  # the same BLAS setting as tilekit's
        t0 = time.perf_counter()
        goals = dihedral.check_goals(a, b)
        model = dihedral.SplitModel(escher.type_model(ih, settings.edge_points), settings.path_points)
        banks = [escher.GoalBank.build(g, settings.samples, settings.reflection) for g in goals]
        log_ratio = math.log(signed_area(goals[0]) / signed_area(goals[1]))
        npar, nx = model.tile.n_params, model.nc + 2 * model.k
        evaluations = 0

        def f(y: np.ndarray) -> float:
            nonlocal evaluations
            evaluations += 1
            p, x = y[:npar], y[npar : npar + nx]
            bad = model.tile.polygon_ok(p)
            if bad:
                return 1.0 + bad
            u, v, short = dihedral._wrap(model, y[-2], y[-1])
            if short:
                return 1.0 + short
            pieces = model.pieces(p, x, u, v)
            d = max(bank.align(escher.resample(q, settings.samples))[0] for q, bank in zip(pieces, banks))
            outline = model.tile.outline(p, x[: model.nc])
            return (d + escher.CROSSING_PENALTY * dihedral._bad_pieces(pieces, outline)
                    + dihedral._area_penalty(pieces, log_ratio))

        pairs = screened_pairs(model, banks, goals, settings)
        best = None
        for u, v in pairs[: settings.starts]:
            y0 = np.concatenate([model.tile.default, model.start(model.tile.default, u, v), [u, v]])
            res = minimize(f, y0, method="L-BFGS-B")
            if best is None or res.fun < best.fun:
                best = res
        assert best is not None
        y = best.x
        u, v, _ = dihedral._wrap(model, y[-2], y[-1])
        r = dihedral._valid_result(model, y[:npar], y[npar : npar + nx], u, v, goals, settings)
        r.evaluations = evaluations
        r.seconds = time.perf_counter() - t0
        return r


def screened_pairs(model: dihedral.SplitModel, banks: list, goals: tuple, settings: dihedral.DihedralSettings
                   ) -> list[tuple[float, float]]:
    """tilekit's screening (the same code path: its projection at the default parameters), so
    the peer starts from the same end pairs."""
    cands = model.candidate_ends()
    pairs = [(a, b) for a in cands for b in cands if min((b - a) % model.m, (a - b) % model.m) >= dihedral.MIN_END_GAP]
    p0 = model.tile.default
    scored = sorted((dihedral.project_split(model, p0, a, b, banks, dihedral.SCREEN_STEPS)[0], i)
                    for i, (a, b) in enumerate(pairs))
    out = [scored[0]]
    for sc in scored[1:]:
        if sc[0] - out[-1][0] > 1e-9:
            out.append(sc)
    return [pairs[i] for _, i in out]


def timed(fn, *args):  # noqa: ANN001, ANN202 - a benchmark helper
    c0, w0 = time.process_time(), time.perf_counter()
    out = fn(*args)
    return out, time.process_time() - c0, time.perf_counter() - w0


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--types", default="IH1,IH41,IH84")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--skip-peer", action="store_true")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    types = escher.parse_types(args.types)
    settings = dihedral.DihedralSettings()
    known = tiling_from_spec(KNOWN)
    pairs = {
        "IH1 split (known)": [np.asarray(p.outline, dtype=float) for p in known.prototiles],
        "bird + fish": [escher.read_goal(ROOT / "tests" / "data" / "escher" / n) for n in ("bird.json", "fish.json")],
    }
    print(f"types {args.types}, repeat {args.repeat}; load {os.getloadavg()}")
    for ih in types:
        escher.type_model(ih)
    for name, (a, b) in pairs.items():
        rows = []
        for ih in types:
            cpu, wall, res = [], [], None
            for _ in range(args.repeat):
                res, c, w = timed(dihedral.escherize_dihedral_type, a, b, ih, settings)
                cpu.append(c)
                wall.append(w)
            line = (f"  {name:<18} IH{ih:<3} tilekit cpu {min(cpu):6.2f} s (median {statistics.median(cpu):.2f}) "
                    f"wall {min(wall):6.2f} s  d={res.distance:.2e} ({res.evaluations} ev)")
            prow = None
            if not args.skip_peer:
                pc, pw, pr = [], [], None
                for _ in range(args.repeat):
                    pr, c, w = timed(peer_type, a, b, ih, settings)
                    pc.append(c)
                    pw.append(w)
                prow = (min(pc), pr.distance)
                line += (f" | peer cpu {min(pc):6.2f} s (median {statistics.median(pc):.2f}) wall {min(pw):6.2f} s  "
                         f"d={pr.distance:.2e} ({pr.evaluations} ev)")
            rows.append((ih, min(cpu), res.distance, prow))
            print(line, flush=True)
        if not args.skip_peer:
            t_ours = sum(r[1] for r in rows)
            t_peer = sum(r[3][0] for r in rows)
            best_ours = min(rows, key=lambda r: r[2])
            best_peer = min(rows, key=lambda r: r[3][1])
            print(f"{name}: cpu tilekit {t_ours:.1f} s, peer {t_peer:.1f} s (peer/tilekit {t_peer / t_ours:.2f}x); "
                  f"best tilekit IH{best_ours[0]} {best_ours[2]:.2e}, peer IH{best_peer[0]} {best_peer[3][1]:.2e}")
    print(f"load after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
