"""A measured estimate of a whole ``polyomino-classify`` run from a uniform random sample.

Every free n-form of the grid is enumerated (``lattice.free_polyforms``, the enumeration the
search runs per chunk), a uniform sample of ``--sample`` of them is drawn with a fixed seed, and
each is classified as ``classify_search.run_chunk`` does it: the sample's boundary-word tests
in one compiled call (``isohedral.analyse_many``), then ``classify.classify`` with the search's
default bounds (probe 2, max level 5, 12 tiles per unit, ``--time-limit`` CPU seconds). The CPU time
per form (``time.process_time``) gives the estimate for all forms: mean x count, with a 95%
interval from the bootstrap over the sample (the time per form has a long tail: a handful of
anisohedral tilers and Heesch-2 forms cost seconds each, so the interval is wide and the
sample's largest times are printed too). A warm-up on 20 of the forms loads the compiled
kernels first (once per worker in a run, so not part of the per-form cost). The 2-core wall is that CPU over two workers, a lower
bound (the process pool's own start-up and the chunks' imbalance are not in it).

``--profile`` classifies the same forms a second time under cProfile and splits the CPU by
phase: the boundary-word templates (``analyse_many``), the local test of corona 1
(``first_corona_rows``), the corona SAT ladder (``HeeschSolver`` set-up and ``_heesch``, the
levels), the torus search (``TorusSearch.search``) and the witness's wallpaper group.

    python benchmarks/estimate_classify.py --grid square --cells 13 --sample 1000 --seed 28 --profile
    python benchmarks/estimate_classify.py --grid iamond --cells 14 --sample 300 --seed 28
"""

from __future__ import annotations

import argparse
import collections
import cProfile
import os
import pstats
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tilekit.lattice import free_polyforms, get_grid  # noqa: E402
from tilekit.plugins.polyomino import classify as classify_module  # noqa: E402
from tilekit.plugins.polyomino import heesch, isohedral, torus  # noqa: E402
from tilekit.plugins.polyomino.classify import classify  # noqa: E402
from tilekit.plugins.polyomino.isohedral import analyse_many  # noqa: E402

#: The functions whose cumulative cProfile time is each phase's.
PHASES = {
    "boundary-word templates": isohedral.analyse_many,
    "corona 1 (local test)": heesch.first_corona_rows,
    "corona SAT set-up (HeeschSolver)": heesch.HeeschSolver.__init__,
    "corona SAT levels": heesch._heesch,
    "torus search": torus.TorusSearch.search,
    "witness wallpaper group": classify_module.wallpaper_group,
}


def classify_sample(grid, forms: list[np.ndarray], flags: np.ndarray, time_limit: float) -> tuple[list, list]:
    """Classify ``forms`` as the search's chunk does; (CPU seconds per form, verdict kind)."""
    t0 = time.process_time()
    analysed = iter(analyse_many(grid, [f for f, h in zip(forms, flags) if not h]))
    bulk = (time.process_time() - t0) / max(1, len(forms))
    seconds, kinds = [], []
    for cells, holey in zip(forms, flags):
        t = time.process_time()
        c = classify(grid, cells, None if holey else next(analysed), has_holes=bool(holey),
                     time_limit=time_limit or None)
        seconds.append(time.process_time() - t + bulk)
        if c.tiles == "true":
            kinds.append("isohedral" if c.isohedral else "anisohedral")
        elif c.tiles == "false":
            kinds.append("holes" if holey else f"Hc={c.heesch},Hh={c.heesch_holes}")
        else:
            kinds.append("undecided")
    return seconds, kinds


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grid", default="square")
    ap.add_argument("--cells", type=int, default=13)
    ap.add_argument("--sample", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=28)
    ap.add_argument("--time-limit", type=float, default=300.0, help="CPU seconds per form, as the search's default")
    ap.add_argument("--profile", action="store_true", help="a second pass under cProfile, CPU by phase")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    grid = get_grid(args.grid)
    print(f"load before: {tuple(round(x, 2) for x in os.getloadavg())}", flush=True)
    t = time.process_time()
    polys, flags, free = free_polyforms(grid, args.cells, with_holes=True)
    idx = np.flatnonzero(np.fromiter((len(p) == args.cells for p in polys), bool, len(polys)))
    total = len(idx)
    assert total == int(free[args.cells]), (total, free[args.cells])
    enum_s = time.process_time() - t
    pick = np.sort(np.random.default_rng(args.seed).choice(idx, size=min(args.sample, total), replace=False))
    forms, fl = [polys[i] for i in pick], flags[pick]
    del polys
    print(f"{total:,} free {args.cells}-forms on the {args.grid} grid (enumerated in {enum_s:.1f} s CPU); "
          f"sample {len(pick)}, seed {args.seed}", flush=True)
    classify_sample(grid, forms[:20], fl[:20], args.time_limit)  # warm-up: numba's cached kernels load once
    seconds, kinds = classify_sample(grid, forms, fl, args.time_limit)
    s = np.asarray(seconds)
    boot = np.random.default_rng(1).choice(s, size=(2000, len(s)), replace=True).mean(axis=1)
    lo, hi = np.percentile(boot, [2.5, 97.5])
    print(f"sample CPU {s.sum():.1f} s; per form mean {1e3 * s.mean():.1f} ms, median {1e3 * np.median(s):.1f} ms, "
          f"max {s.max():.2f} s; the 1% slowest forms take {100 * np.sort(s)[-max(1, len(s) // 100):].sum() / s.sum():.0f}% "
          "of the CPU")
    print(f"estimate for all {total:,}: CPU {s.mean() * total / 3600:.2f} h (95% bootstrap "
          f"{lo * total / 3600:.2f}-{hi * total / 3600:.2f} h); 2-core wall at least {s.mean() * total / 7200:.2f} h")
    by = collections.defaultdict(list)
    for k, x in zip(kinds, seconds):
        by[k].append(x)
    print("| verdict | forms in sample | estimated in all | mean ms | share of CPU |")
    print("|---|---|---|---|---|")
    for k in sorted(by, key=lambda k: -sum(by[k])):
        v = np.asarray(by[k])
        print(f"| {k} | {len(v)} | {len(v) * total / len(s):,.0f} | {1e3 * v.mean():.1f} | {100 * v.sum() / s.sum():.1f}% |")
    slow = sorted(zip(seconds, kinds), reverse=True)[:8]
    print("slowest:", ", ".join(f"{x:.2f} s {k}" for x, k in slow))
    if args.profile:
        prof = cProfile.Profile(time.process_time)
        prof.enable()
        t = time.process_time()
        classify_sample(grid, forms, fl, args.time_limit)
        profiled = time.process_time() - t
        prof.disable()
        st = pstats.Stats(prof).stats
        keys = {label: (f.__code__.co_filename, f.__code__.co_firstlineno, f.__code__.co_name)
                for label, f in PHASES.items()}
        phase = {label: st[key][3] if key in st else 0.0 for label, key in keys.items()}
        print(f"profiled pass: {profiled:.1f} s CPU (profiler overhead included)")
        print("| phase (cumulative, cProfile) | s | share |")
        print("|---|---|---|")
        for label in PHASES:
            print(f"| {label} | {phase[label]:.1f} | {100 * phase[label] / profiled:.1f}% |")
    print(f"load after: {tuple(round(x, 2) for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
