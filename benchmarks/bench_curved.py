"""Hyperbolic {p, q} patches against the PyPI package hypertiling (the field's fast Python
library), in one process, on the same tiling and the same polygons.

The output both sides make: every polygon of the first ``depth`` layers (layers by
reflections across edges, hypertiling's GR definition and OEIS's) as its centre and p
vertices in the Poincaré disc, an (N, p + 1) array.

- tilekit: ``layers.hyperbolic_layers`` (the exact boundary automaton, one compiled pass a
  layer) and ``kernels.poincare_points`` (every tile's centre and vertices).
- hypertiling GR ("generative reflection", its fastest kernel with coordinates): it
  computes one of the p rotational sectors and rotates it on access; the peer here is its
  constructor plus the rotation of the stored sector to all p sectors in one NumPy
  broadcast (what its ``__iter__`` does per polygon), so no Python loop runs per polygon.
  Its constructor alone (one sector, 1/p of the polygons) is timed too, as "GR sector".
- hypertiling GRC with ``tiling=True`` (its combinatorial variant that also computes
  coordinates), expanded the same way.

Checked equal: the polygon counts, and, the two being the same set rotated about the centre,
the sorted distances of all centres and all vertices from the origin (to 1e-9).

Run:  python benchmarks/bench_curved.py [--runs 5]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import statistics
import time
import warnings
from functools import partial

import numpy as np

from tilekit.plugins.curved import model
from tilekit.plugins.curved.kernels import poincare_points
from tilekit.plugins.curved.layers import hyperbolic_transforms
from tilekit.plugins.curved.tiling import RegularTiling

CASES = [((7, 3), 11), ((7, 3), 13), ((5, 4), 11), ((5, 4), 13)]


def tilekit_polygons(p: int, q: int, depth: int) -> np.ndarray:
    """(N, p + 1, 2): each tile's centre then its vertices, Poincaré disc."""
    capacity = int(RegularTiling(p, q, depth=depth).estimate_tiles()) + 1
    t, _ = hyperbolic_transforms(p, q, depth, capacity)
    pts = np.vstack([[0.0, 0.0, 1.0], model.RegularPolygon(p, q).vertices()])
    return poincare_points(t, pts)


def _expand(sector: np.ndarray, p: int) -> np.ndarray:
    """The centre polygon, then the sector's other polygons turned by 2πk/p, k = 0..p-1."""
    rot = np.exp(2j * np.pi * np.arange(p) / p)
    rest = (sector[None, 1:, :] * rot[:, None, None]).reshape(-1, sector.shape[1])
    return np.concatenate([sector[:1], rest])


def quiet(fn):
    """hypertiling prints status lines on stdout; keep them out of the table."""
    def run():
        with contextlib.redirect_stdout(io.StringIO()):
            return fn()
    return run


def peer_gr_sector(p: int, q: int, depth: int) -> np.ndarray:
    """GR's constructor alone: one sector's polygons (1/p of them), the rest not yet made."""
    from hypertiling import HyperbolicTiling

    return HyperbolicTiling(p, q, depth + 1, kernel="GR")._sector_polys


def peer_gr(p: int, q: int, depth: int) -> np.ndarray:
    from hypertiling import HyperbolicTiling

    tiling = HyperbolicTiling(p, q, depth + 1, kernel="GR")
    out = _expand(tiling._sector_polys, p)
    assert len(out) == len(tiling)
    return out


def peer_grc(p: int, q: int, depth: int) -> np.ndarray:
    from hypertiling import HyperbolicTiling

    tiling = HyperbolicTiling(p, q, depth + 1, kernel="GRC", tiling=True)
    out = _expand(tiling.coords, p)
    assert len(out) == len(tiling)
    return out


def same_polygons(ours: np.ndarray, theirs: np.ndarray) -> bool:
    z = ours[..., 0] + 1j * ours[..., 1]
    if z.shape != theirs.shape:
        return False
    for col in (slice(0, 1), slice(1, None)):
        a = np.sort(np.abs(z[:, col]).ravel())
        b = np.sort(np.abs(theirs[:, col]).ravel())
        if not np.allclose(a, b, atol=1e-9, rtol=0):
            return False
    return True


def timed(fns: dict, runs: int) -> dict:
    """Each function's (min, median) seconds over ``runs`` runs, the functions taking turns
    (A B C A B C ...) so that a drift of the machine's load falls on all of them alike; the
    first round is a warm-up (numba compiles or loads its cache there), not counted."""
    times: dict = {name: [] for name in fns}
    for r in range(runs + 1):
        for name, fn in fns.items():
            t0 = time.perf_counter()
            out = fn()
            dt = time.perf_counter() - t0
            del out
            if r:
                times[name].append(dt)
    return {name: (min(v), statistics.median(v)) for name, v in times.items()}


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5, help="timed runs of each side (after one warm-up round)")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    warnings.simplefilter("ignore")
    print(f"load average {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f}, {os.cpu_count()} cores")
    print(f"{'{p,q}':7} {'depth':>5} {'polygons':>10}   {'tilekit min/med s':>17}   {'GR min/med s':>13} "
          f"{'GRC min/med s':>13}  {'GR sector':>13}   {'GR/tk':>6} {'GRC/tk':>6} {'sect/tk':>7}  equal")
    for (p, q), depth in CASES:
        fns = {"tk": partial(tilekit_polygons, p, q, depth), "gr": quiet(partial(peer_gr, p, q, depth)),
               "grc": quiet(partial(peer_grc, p, q, depth)), "sec": quiet(partial(peer_gr_sector, p, q, depth))}
        ours, gr, grc = fns["tk"](), fns["gr"](), fns["grc"]()
        ok = same_polygons(ours, gr) and same_polygons(ours, grc)
        n = len(ours)
        del ours, gr, grc
        t = timed(fns, args.runs)
        tk = t["tk"][1]
        print(f"{{{p},{q}}}   {depth:5d} {n:10,d}   {t['tk'][0]:8.3f} {tk:8.3f}   {t['gr'][0]:6.3f} {t['gr'][1]:6.3f} "
              f"{t['grc'][0]:6.3f} {t['grc'][1]:6.3f}  {t['sec'][0]:6.3f} {t['sec'][1]:6.3f}   {t['gr'][1] / tk:6.2f} "
              f"{t['grc'][1] / tk:6.2f} {t['sec'][1] / tk:7.2f}  {ok}")

if __name__ == "__main__":
    main()
