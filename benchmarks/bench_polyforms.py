"""Free polyforms on every grid: tilekit's compiled Redelmeier (``lattice.free_polyforms``)
against the simple peer, in one process, on the same output (checked equal).

The peer is what a competent user writes in twenty lines: grow every free form of size k by
one neighbour (the grid's own neighbour tables), canonicalise the result with NumPy (all
point-group images at once, each translated so its least cell lies in the period box,
sorted; the least image wins) and keep a set. Both sides produce the free forms of sizes
1..n; the peer's canonical sets are compared with tilekit's forms canonicalised the same way.

    .venv/bin/python benchmarks/bench_polyforms.py [--runs 3] [--grids kite,hex]

Prints per grid: n, forms, tilekit min / median seconds, peer min / median, the median ratio.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from tilekit.lattice import GRIDS, free_polyforms, get_grid

#: sizes per grid: a second or so for the peer on a quiet machine
SIZES = {"square": 9, "hex": 7, "iamond": 10, "kite": 7, "octasquare": 6, "trihex": 7,
         "drafter": 9, "abolo": 10, "halfcairo": 7, "bevelhex": 5}


def peer_canonical(grid, cells: np.ndarray) -> tuple:
    """The least image, under the point group and translations, as a sorted tuple."""
    imgs = np.einsum("gij,kj->gki", grid.group, cells)  # (G, k, 2)
    p = grid.period
    out = []
    for im in imgs:
        least = im[np.lexsort((im[:, 0], im[:, 1]))[0]]
        im = im - (least - np.mod(least, p))
        out.append(tuple(map(tuple, im[np.lexsort((im[:, 0], im[:, 1]))][:, ::-1].tolist())))
    return min(out)


def peer(grid, n: int) -> set:
    level = {peer_canonical(grid, np.array([r])) for r in grid.roots}
    found = set(level)
    for _ in range(n - 1):
        nxt = set()
        for form in level:
            cells = np.array(form)[:, ::-1]
            have = set(map(tuple, cells.tolist()))
            types = grid.cell_type(cells)
            for c, t in zip(cells, types):
                for q in (c + grid.neighbours[t][: grid.degrees[t]]).tolist():
                    if tuple(q) not in have:
                        nxt.add(peer_canonical(grid, np.vstack([cells, q])))
        found |= nxt
        level = nxt
    return found


def timed(fn, runs: int) -> tuple[list[float], object]:
    times, out = [], None
    for _ in range(runs):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return times, out


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=3, help="timed runs per side (min and median)")
    ap.add_argument("--grids", default=",".join(GRIDS), help="comma-separated grid names")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    for name in args.grids.split(","):
        grid = get_grid(name)
        n = SIZES[grid.name]
        free_polyforms(grid, 3)  # compile (numba cache) outside the timing
        t_tk, (polys, free) = timed(lambda grid=grid, n=n: free_polyforms(grid, n), args.runs)
        t_peer, forms = timed(lambda grid=grid, n=n: peer(grid, n), args.runs)
        mine = {peer_canonical(grid, p) for p in polys}
        assert mine == forms and len(mine) == int(free.sum()), name
        ratio = statistics.median(t_peer) / statistics.median(t_tk)
        print(f"{grid.name:10s} n={n:2d} forms={len(mine):7d}  tilekit {min(t_tk):.4f}/{statistics.median(t_tk):.4f} s"
              f"  peer {min(t_peer):.3f}/{statistics.median(t_peer):.3f} s  peer/tilekit {ratio:.0f}x", flush=True)


if __name__ == "__main__":
    main()
