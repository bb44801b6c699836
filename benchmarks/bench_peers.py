"""tilekit's core paths against the strongest simple peer, in one process, on the same output.

    python benchmarks/bench_peers.py patch --sizes 1e5 1e6 1e7 --runs 5
    python benchmarks/bench_peers.py validate --sizes 2e4 1e5 1e6 --runs 5

``patch``: ``PeriodicTiling.patch`` of the 3^6 triangle tiling over a square holding about N
tiles, against :func:`numpy_patch`, a plain NumPy replication (the lattice box, the (L, m)
bounding-box test, one gather); the four output columns are checked equal bit for bit.

``validate``: ``Patch.validate`` against :func:`shapely_validate`, what a Shapely 2 user writes:
the union of the tiles (snap-rounded, as GEOS needs on shared edges with float noise), an
overlap where the union's area falls short of the sum of the areas, and the region minus the
union as the gap. Both run on the valid patch and on the patch with one tile shifted by 1e-4,
and their verdicts (overlap or not, gap area to the tolerance) are checked equal.

Each round runs tilekit then the peer; the figures are min and median over the rounds of
CPU seconds (``time.process_time``, what the machine's other jobs disturb least) and wall
seconds, and the ratio peer / tilekit per round (> 1: tilekit is faster).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time

import numpy as np
import shapely

from tilekit import Affine, Patch, PeriodicTiling, Prototile
from tilekit.geometry import regular_polygon


def triangles() -> PeriodicTiling:
    tri = Prototile(regular_polygon(3))
    unit = np.array([np.eye(3), Affine.half_turn((0.75, math.sqrt(3) / 4))])
    return PeriodicTiling([tri], [0, 0], unit, (1, 0), (0.5, math.sqrt(3) / 2))


def region_for(tiles: float) -> tuple[float, float, float, float]:
    half = math.sqrt(tiles * (math.sqrt(3) / 4)) / 2  # triangles of area sqrt(3)/4
    return (-half, -half, half, half)


def numpy_patch(t: PeriodicTiling, region: tuple[float, float, float, float]):
    """The peer: §3.4's replication in plain NumPy (columns: prototile, transform, colour, aspect)."""
    rx0, ry0, rx1, ry1 = region
    ub = t.unit_tile_bounds()
    ex0, ex1, ey0, ey1 = rx0 - ub[:, 2].max(), rx1 - ub[:, 0].min(), ry0 - ub[:, 3].max(), ry1 - ub[:, 1].min()
    inv = np.linalg.inv(t.basis)
    c = np.array([[ex0, ey0], [ex1, ey0], [ex1, ey1], [ex0, ey1]]) @ inv.T
    lo, hi = np.floor(c.min(0) - 1e-9).astype(int), np.ceil(c.max(0) + 1e-9).astype(int)
    a, b = np.meshgrid(np.arange(lo[0], hi[0] + 1), np.arange(lo[1], hi[1] + 1), indexing="ij")
    ab = np.column_stack([a.ravel(), b.ravel()])
    tr = ab @ t.basis.T
    tol, eps = 1e-9, 1e-9
    tr = tr[(tr[:, 0] >= ex0 - tol) & (tr[:, 0] <= ex1 + tol) & (tr[:, 1] >= ey0 - tol) & (tr[:, 1] <= ey1 + tol)]
    hit = ((ub[None, :, 2] + tr[:, None, 0] > rx0 + eps) & (ub[None, :, 0] + tr[:, None, 0] < rx1 - eps)
           & (ub[None, :, 3] + tr[:, None, 1] > ry0 + eps) & (ub[None, :, 1] + tr[:, None, 1] < ry1 - eps))
    li, ti = np.nonzero(hit)
    transform = t.unit_transform[ti]
    transform[:, :2, 2] += tr[li]
    aspect = t.unit_aspect[ti]
    return t.unit_prototile[ti], transform, np.asarray(t.colouring.aspects)[aspect], aspect


def shapely_validate(patch: Patch, region, tolerance: float = 1e-6) -> tuple[bool, float]:
    """The peer: (some overlap, uncovered area) from the union of the tiles."""
    geoms = shapely.polygons(patch.polygons())
    areas = shapely.area(geoms)
    grid = 1e-9 * math.sqrt(float(np.median(areas)))
    union = shapely.union_all(geoms, grid_size=grid)
    tol = tolerance * float(np.median(areas))
    overlap = float(areas.sum()) - union.area > tol
    gap = shapely.difference(shapely.box(*region), union, grid_size=grid).area
    return bool(overlap), float(gap)


def timed(fn, *args):
    c, w = time.process_time(), time.perf_counter()
    out = fn(*args)
    return out, time.process_time() - c, time.perf_counter() - w


def report(label: str, n: int, ours: list[tuple[float, float]], peer: list[tuple[float, float]]) -> None:
    def mm(xs):
        return f"{min(xs):.3f} / {statistics.median(xs):.3f}"

    oc, ow = [c for c, _ in ours], [w for _, w in ours]
    pc, pw = [c for c, _ in peer], [w for _, w in peer]
    rc = [p / o for p, o in zip(pc, oc)]
    rw = [p / o for p, o in zip(pw, ow)]
    print(f"| {label} | {n:,} | {mm(oc)} | {mm(ow)} | {mm(pc)} | {mm(pw)} | {min(rc):.2f} / {statistics.median(rc):.2f} "
          f"| {min(rw):.2f} / {statistics.median(rw):.2f} | {statistics.median(oc) / n * 1e9:.0f} |", flush=True)


HEADER = ("| what | tiles | tilekit CPU s (min / median) | tilekit wall s | peer CPU s | peer wall s "
          "| peer/tilekit CPU (min / median) | peer/tilekit wall | tilekit CPU ns/tile |\n"
          "|---|---|---|---|---|---|---|---|---|")


def bench_patch(sizes: list[float], runs: int) -> None:
    t = triangles()
    print(HEADER)
    for size in sizes:
        region = region_for(size)
        ours, peer = [], []
        n = 0
        for _ in range(runs):
            p, c, w = timed(t.patch, region)
            ours.append((c, w))
            cols = (p.prototile, p.transform, p.colour, p.aspect)
            n = len(p)
            del p
            q, c, w = timed(numpy_patch, t, region)
            peer.append((c, w))
            assert all(np.array_equal(x, y) for x, y in zip(cols, q)), "tilekit and the peer differ"
            del q, cols
        report("PeriodicTiling.patch", n, ours, peer)


def bench_validate(sizes: list[float], runs: int, peer_limit: float) -> None:
    t = triangles()
    print(HEADER)
    for size in sizes:
        region = region_for(size)
        patch = t.patch(region)
        centres = patch.centres()
        k = int(np.argmin(np.hypot(centres[:, 0], centres[:, 1])))
        tr = patch.transform.copy()
        tr[k, 0, 2] += 1e-4
        shifted = Patch(patch.prototiles, patch.prototile, tr)
        for label, p in (("Patch.validate, valid", patch), ("Patch.validate, one tile shifted 1e-4", shifted)):
            ours, peer = [], []
            for _ in range(runs):
                rep, c, w = timed(p.validate, region)
                ours.append((c, w))
                if len(p) > peer_limit:
                    continue
                (overlap, gap), c, w = timed(shapely_validate, p, region)
                peer.append((c, w))
                assert overlap == bool(rep.overlaps), (overlap, rep.summary())
                assert abs(gap - rep.uncovered_area) <= 10 * rep.area_tolerance, (gap, rep.uncovered_area)
            if peer:
                report(label, len(p), ours, peer)
            else:
                oc = [c for c, _ in ours]
                print(f"| {label} | {len(p):,} | {min(oc):.3f} / {statistics.median(oc):.3f} | "
                      f"{min(w for _, w in ours):.3f} / {statistics.median([w for _, w in ours]):.3f} | "
                      f"(peer not run above {peer_limit:g} tiles) | | | | {statistics.median(oc) / len(p) * 1e9:.0f} |",
                      flush=True)


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=["patch", "validate"])
    ap.add_argument("--sizes", nargs="+", type=float, default=None, help="tiles (about)")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--peer-limit", type=float, default=2e5, help="validate: largest patch the peer runs on")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    print(f"load: {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f} (1, 5, 15 min)", flush=True)
    if args.what == "patch":
        bench_patch(args.sizes or [1e5, 1e6, 1e7], args.runs)
    else:
        bench_validate(args.sizes or [2e4, 1e5, 1e6], args.runs, args.peer_limit)
    print(f"load: {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f} (1, 5, 15 min)")


if __name__ == "__main__":
    main()
