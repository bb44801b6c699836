"""The hat's continuum Tile(a, b) and supertile overlays against the strongest simple peers,
side by side in one process, outputs checked equal.

``generate``: a level-d supertile of Tile(a, b).
  tilekit: ``continuum_system(hat, a, b).generate(d)`` (the lifted hierarchy, solved once per
  level and kept, then the hat's batched products with other translations).
  peer:    what a competent user writes from tilekit's own hat patch (``hat.generate(d)``,
  the fastest hat generator there is): the hats' vertices as exact lattice points, one
  ``np.unique``-style sort to find shared vertices, the lift offsets along them, a BFS
  spanning tree in C (``scipy.sparse.csgraph.breadth_first_order``) and the lifts summed
  down the tree by pointer jumping (log n NumPy passes), then the deformed translations.
  Checked equal: the same tiles in the same order, transforms within 1e-9 after both are
  moved so that tile 0 sits at the origin (a lift is defined up to a constant).

``overlay``: the outlines of the level-L supertiles of a level-d patch.
  tilekit: ``export.group_boundaries`` (the patch's elementary segments, once, by sorted keys).
  peer:    shapely: the tiles of each supertile merged (``shapely.union_all`` per supertile,
  as GeoPandas' ``dissolve`` does; the faster coverage union refuses the hats' T-junctions),
  then the boundary pieces the merged supertiles share: ``shapely.intersection`` of each
  touching pair's boundaries (STRtree query).
  Checked equal: the total length of the lines.

Run:  python benchmarks/bench_continuum.py generate [--runs 5] [--depth 5 --depth 6] [-a 1 -b 2]
      python benchmarks/bench_continuum.py overlay [--runs 5] [--depth 5] [--level 2]
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from functools import partial

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import breadth_first_order

from tilekit import export
from tilekit.plugins.substitution import builtin_systems, tiling
from tilekit.plugins.substitution.continuum import continuum_system, deform, lifts_of
from tilekit.plugins.substitution.hat import TO_LATTICE, to_cartesian
from tilekit.tiling import Patch

SQRT3 = math.sqrt(3.0)


def timed(fn, runs: int):
    """(CPU seconds per run, the result): CPU time, since the 2 shared cores make wall time
    wander; the wall times are printed beside them by ``fmt``."""
    cpu, wall = [], []
    for _ in range(runs):
        start, start_cpu = time.perf_counter(), time.process_time()
        fn()
        cpu.append(time.process_time() - start_cpu)
        wall.append(time.perf_counter() - start)
    _WALL[id(cpu)] = wall
    return cpu, fn()


_WALL: dict[int, list[float]] = {}


def fmt(ts: list[float]) -> str:
    """CPU min / median (wall min / median)."""
    wall = _WALL.get(id(ts), ts)
    return f"{min(ts):.3f} / {statistics.median(ts):.3f} ({min(wall):.3f} / {statistics.median(wall):.3f})"


# ----------------------------------------------------------------------------- generate


def tilekit_generate(a: float, b: float, depth: int) -> np.ndarray:
    return continuum_system(builtin_systems()["hat"], a, b).generate(depth)[1]


def peer_generate(a: float, b: float, depth: int) -> np.ndarray:
    """Tile(a, b) from the hat patch by integrating the edge classes over a spanning tree."""
    hat = builtin_systems()["hat"]
    lifts = lifts_of(hat)  # the hat outline's own class steps (13 x 2 integers each)
    _, tr, _ = hat.generate(depth)
    lat = np.rint(TO_LATTICE @ tr @ np.linalg.inv(TO_LATTICE)).astype(np.int64)
    n, k = len(lat), len(lifts.outline)
    l00, l01, l10, l11 = (lat[:, r, c, None] for r in (0, 1) for c in (0, 1))
    X, XU = lifts.outline, lifts.tile_u
    px = (l00 * X[:, 0] + l01 * X[:, 1] + lat[:, 0, 2, None]).ravel()  # (n * 13,) exact lattice points
    py = (l10 * X[:, 0] + l11 * X[:, 1] + lat[:, 1, 2, None]).ravel()
    ux = (l00 * XU[:, 0] + l01 * XU[:, 1]).ravel()  # each vertex's class-1 steps from its hat's origin
    uy = (l10 * XU[:, 0] + l11 * XU[:, 1]).ravel()
    key = (px + (1 << 30)) * (1 << 31) + py + (1 << 30)
    order = np.argsort(key, kind="stable")
    ks = key[order]
    same = np.flatnonzero(ks[1:] == ks[:-1])  # consecutive copies of one vertex: a graph edge
    i, j = order[same], order[same + 1]
    ti, tj = i // k, j // k
    delta = np.column_stack([ux[i] - ux[j], uy[i] - uy[j]])  # u[tj] = u[ti] + delta
    keep = ti != tj
    ti, tj, delta = ti[keep], tj[keep], delta[keep]
    # both directions as one edge list, keyed for the tree's lookups
    src, dst = np.concatenate([ti, tj]), np.concatenate([tj, ti])
    dd = np.concatenate([delta, -delta])
    graph = coo_matrix((np.ones(len(src), dtype=np.int8), (src, dst)), shape=(n, n)).tocsr()
    tree, pred = breadth_first_order(graph, 0, directed=True, return_predecessors=True)
    tree, pred = tree.astype(np.int64), pred.astype(np.int64)  # (int32 from scipy: pred * n would overflow)
    assert len(tree) == n, "the hats' vertex graph is connected"
    ekey = src * n + dst
    eo = np.argsort(ekey, kind="stable")
    child = tree[1:]
    at = eo[np.searchsorted(ekey[eo], pred[child] * n + child)]
    step = np.zeros((n, 2), dtype=np.int64)
    step[child] = dd[at]
    # pointer jumping: u[x] = the sum of the steps from the root to x
    u, up = step, np.where(pred < 0, 0, pred)
    while up.any():
        u = u + u[up]
        up = up[up]
    out = to_cartesian(lat)
    out[:, :2, 2] = deform(a, b, u, lat[:, :2, 2] - u)
    return out


def check_generate(tk: np.ndarray, peer: np.ndarray) -> None:
    assert tk.shape == peer.shape, (tk.shape, peer.shape)
    a, b = tk.copy(), peer.copy()
    a[:, :2, 2] -= a[0, :2, 2]
    b[:, :2, 2] -= b[0, :2, 2]
    scale = max(1.0, float(np.abs(a[:, :2, 2]).max()))
    assert np.allclose(a, b, rtol=0, atol=1e-9 * scale), "placements differ"


def main_generate(runs: int, depths: list[int], a: float, b: float) -> None:
    tilekit_generate(a, b, 2), peer_generate(a, b, 2)  # compile, lift the low levels
    hat = builtin_systems()["hat"]
    print(f"Tile({a:g}, {b:g}); CPU min / median (wall min / median) of {runs} runs, seconds; "
          "ratio = peer CPU median / tilekit CPU median")
    print(f"{'depth':>5s} {'tiles':>9s} {'tilekit':>29s} {'hat alone':>29s} {'peer':>29s} {'ratio':>6s}")
    for d in depths:
        lifts_of(hat).rules(d)  # solved once per level and kept (timed separately below)
        t_tk, tk = timed(partial(tilekit_generate, a, b, d), runs)
        t_hat, _ = timed(partial(hat.generate, d), runs)
        t_peer, peer = timed(partial(peer_generate, a, b, d), runs)
        check_generate(tk, peer)
        print(f"{d:5d} {len(tk):9,d} {fmt(t_tk):>29s} {fmt(t_hat):>29s} {fmt(t_peer):>29s} "
              f"{statistics.median(t_peer) / statistics.median(t_tk):6.1f}")
    def fresh() -> None:
        hat.lifted = None
        lifts_of(hat).rules(max(depths))

    t_fresh, _ = timed(fresh, runs)
    print(f"solving the lifts of levels 1..{max(depths)} from scratch (once per process): {fmt(t_fresh)} s")


# ----------------------------------------------------------------------------- overlay


def peer_overlay(patch: Patch, group: np.ndarray) -> float:
    """Total length of the lines between supertiles, by shapely: dissolve, then shared boundaries."""
    g = shapely.set_precision(patch.geometries(), 1e-9)
    order = np.argsort(group, kind="stable")
    starts = np.flatnonzero(np.r_[True, group[order][1:] != group[order][:-1]])
    parts = np.array([shapely.union_all(g[order[s:e]], grid_size=1e-9)
                      for s, e in zip(starts, np.r_[starts[1:], len(order)])])
    tree = shapely.STRtree(parts)
    i, j = tree.query(parts, predicate="intersects")
    keep = i < j
    shared = shapely.intersection(shapely.boundary(parts[i[keep]]), shapely.boundary(parts[j[keep]]))
    return float(shapely.length(shared).sum())


def main_overlay(runs: int, depth: int, level: int) -> None:
    t = tiling("hat", depth=depth)
    patch = t.patch()
    group, _ = t.supertiles(patch, None, level)
    export.group_boundaries(patch, group)
    print(f"hat depth {depth} ({len(patch):,} tiles), level-{level} supertiles ({len(np.unique(group)):,}); "
          f"CPU min / median (wall min / median) of {runs} runs, seconds")
    t_tk, segs = timed(lambda: export.group_boundaries(patch, group), runs)
    t_grp, _ = timed(lambda: t.supertiles(patch, None, level), runs)
    t_peer, length = timed(lambda: peer_overlay(patch, group), runs)
    mine = float(np.linalg.norm(segs[:, 1] - segs[:, 0], axis=1).sum())
    assert math.isclose(mine, length, rel_tol=1e-7), (mine, length)
    print(f"group_boundaries {fmt(t_tk)}   supertiles (regenerate + match) {fmt(t_grp)}   "
          f"shapely dissolve + shared boundaries {fmt(t_peer)}   ratio {statistics.median(t_peer) / statistics.median(t_tk):.1f}"
          f"   (line length {mine:.6g} both)")


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mode", choices=["generate", "overlay"])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--depth", type=int, action="append")
    ap.add_argument("--level", type=int, default=2)
    ap.add_argument("-a", type=float, default=1.0)
    ap.add_argument("-b", type=float, default=2.0)
    return ap


def main() -> None:
    args = build_parser().parse_args()
    if args.mode == "generate":
        main_generate(args.runs, args.depth or [5, 6, 7], args.a, args.b)
    else:
        main_overlay(args.runs, (args.depth or [5])[0], args.level)


if __name__ == "__main__":
    main()
