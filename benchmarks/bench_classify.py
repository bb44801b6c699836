"""The polyomino classification (`tilekit search polyomino-classify`): time per n and per
polyomino, serial / 2 process workers / a dask LocalCluster, with the published counts checked.

Published figures: OEIS A054359 (tile), A054360 (do not tile), A054361 (hole-free
non-tilers), A075206 (anisohedral); Kaplan, "Heesch numbers of unmarked polyforms" (2022),
Tables 1-2 (Hc, Hh of the hole-free non-tilers).

The Heesch encoding is also timed against the obvious SAT encoding as the peer (``--peer``):
one Boolean per placement and corona, overlaps forbidden pairwise (every pair of overlapping
copies, as in Kaplan's heesch-sat), touching and halo clauses written directly over the
placements — the same questions, the same answers (checked), a different formula.

Run: python benchmarks/bench_classify.py --max-cells 10 --executor process --workers 2
     python benchmarks/bench_classify.py --max-cells 9 --peer 60
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tilekit.catalogue import open_catalogue  # noqa: E402
from tilekit.lattice import SQUARE, enumerate_free  # noqa: E402
from tilekit.plugins.polyomino.heesch import HeeschSolver, heesch  # noqa: E402
from tilekit.plugins.polyomino.isohedral import analyse  # noqa: E402
from tilekit.search import run_search  # noqa: E402

A054359 = [1, 1, 2, 5, 12, 35, 104, 343, 1050, 3070, 6620, 23449]
A054360 = [0, 0, 0, 0, 0, 0, 4, 26, 235, 1585, 10453, 40151]
A054361 = [0, 0, 0, 0, 0, 0, 3, 20, 198, 1390, 9474, 35488]
A075206 = [0, 0, 0, 0, 0, 0, 0, 1, 9, 44, 108, 222]
KAPLAN_HC = {7: {0: 1, 1: 2}, 8: {0: 6, 1: 14}, 9: {0: 75, 1: 122, 2: 1}, 10: {0: 747, 1: 642, 2: 1},
             11: {0: 5807, 1: 3628, 2: 39}, 12: {0: 28572, 1: 6906, 2: 10}}


def classification(n: int, executor: str, workers: int | None, min_cells: int = 1) -> tuple[dict, float]:
    with tempfile.TemporaryDirectory() as tmp:
        cat = open_catalogue(f"sqlite:///{tmp}/c.sqlite")
        t0 = time.perf_counter()
        run = run_search(cat, "polyomino-classify", {"max_cells": n, "min_cells": min_cells},
                         executor=executor, workers=workers)
        wall = time.perf_counter() - t0
        summary = cat.run(run).summary
        cat.close()
    return summary, wall


def report(summary: dict, wall: float, n: int, min_cells: int) -> None:
    print(f"wall {wall:.1f} s")
    print("| n | free | tile | isohedral | anisohedral (k: count) | do not tile | hole-free | Hc 0/1/2/3 | undecided | s total | ms / polyomino | published |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for m in range(min_cells, n + 1):
        g = lambda k, m=m: int(summary.get(f"{k}_{m}", 0))  # noqa: E731
        ks = {k: int(v) for key, v in summary.items() if key.startswith(f"anisohedral_{m}_k") for k in [key.rsplit("k", 1)[1]]}
        hc = "/".join(str(int(summary.get(f"hc_{m}_{h}", 0))) for h in range(4))
        secs = float(summary.get(f"seconds_{m}", 0.0))
        ok = (g("tiles") == A054359[m - 1] and g("nontilers") == A054360[m - 1]
              and g("holefree_nontilers") == A054361[m - 1] and g("anisohedral") == A075206[m - 1]
              and g("undecided") == 0
              and all(int(summary.get(f"hc_{m}_{h}", 0)) == c for h, c in KAPLAN_HC.get(m, {}).items()))
        print(f"| {m} | {g('free')} | {g('tiles')} | {g('isohedral')} | {g('anisohedral')} {ks or ''} | "
              f"{g('nontilers')} | {g('holefree_nontilers')} | {hc} | {g('undecided')} | {secs:.1f} | "
              f"{1000 * secs / max(1, g('free')):.1f} | {'equal' if ok else 'DIFFERENT'} |")


# --------------------------------------------------------------------------- the peer encoding

PEER_SOLVE = [0.0]  # seconds inside the solver, summed over peer_heesch calls


def peer_heesch(cells: np.ndarray, max_level: int = 2, solver: str = "glucose4") -> tuple[int, int]:
    """(Hc, Hh) with the obvious encoding: one variable per placement and corona, every pair
    of overlapping copies forbidden, halo and touching clauses written over the placements.
    Only the placement sets are shared with tilekit (HeeschSolver.levels)."""
    from tilekit.lattice import holes_of, pack, unpack
    from tilekit.sat import IncrementalSolver

    hs = HeeschSolver(SQUARE, cells)
    f = hs.forms
    kernel = set(hs.kernel_keys.tolist())
    hc = hh = 0
    for k in range(1, max_level + 1):
        while len(hs.levels) <= k:
            hs._grow()
        rows = np.concatenate(hs.levels[1:k + 1])
        lvl = np.concatenate([np.full(len(hs.levels[i]), i) for i in range(1, k + 1)]).tolist()
        ys = list(range(1, len(rows) + 1))
        cells_k = f.placement_cells(rows).tolist()
        halo_k = f.placement_halos(rows).tolist()
        by_cell: dict[int, list[int]] = {}
        for v, cs in zip(ys, cells_k):
            for c in cs:
                by_cell.setdefault(c, []).append(v)
        pairs = {(a, b) for lits in by_cell.values() for i, a in enumerate(lits) for b in lits[i + 1:]}
        clauses = [[-a, -b] for a, b in pairs]
        kernel_halo = [h for h in hs.kernel_halo.tolist() if h not in kernel]
        if any(h not in by_cell for h in kernel_halo):  # a halo cell no copy can cover
            break
        clauses += [list(by_cell[h]) for h in kernel_halo]
        for v, hl, lv in zip(ys, halo_k, lvl):
            if lv < k:
                for h in hl:
                    if h not in kernel:
                        clauses.append([-v, *by_cell.get(h, [])])
            if lv >= 2:
                near = {u for h in hl for u in by_cell.get(h, [])}
                clauses.append([-v, *sorted(u for u in near if lvl[u - 1] == lv - 1)])
                clauses += [[-v, -u] for u in near if lvl[u - 1] < lv - 1]
        free = holey = False
        with IncrementalSolver(clauses, solver=solver) as s:
            while True:
                ans = s.solve()
                PEER_SOLVE[0] += ans.seconds
                if not ans.satisfiable:
                    break
                used = np.flatnonzero(ans.values(ys)) + 1
                found = holes_of(SQUARE, np.concatenate([hs.kernel_keys, np.asarray(cells_k)[used - 1].ravel()]))
                if not found:
                    free = True
                    break
                holey = True
                for hole in found:
                    hx = unpack(hole)
                    ring = set(pack(hx[:, None, :] + SQUARE.neighbours[0][None]).ravel().tolist())
                    hole_set = set(hole.tolist())
                    bound = [int(v) for v in used if ring & set(cells_k[v - 1])]
                    inside = [v for v in ys if hole_set & set(cells_k[v - 1])]
                    s.add([-v for v in bound] + inside)
        if free:
            hc = hh = k
            continue
        if holey:
            hh = k
        break
    return hc, hh


def peer_benchmark(n: int, count: int, repeat: int) -> None:
    polys, flags, _ = enumerate_free(SQUARE, n, with_holes=True)
    sample = []
    for cells, holey in zip(polys, flags):
        if len(cells) == n and not holey and not analyse(SQUARE, cells, construct=False)["isohedral"]:
            r = heesch(SQUARE, cells, max_level=2)
            if r.decided:
                sample.append((cells, (r.hc, r.hh)))
        if len(sample) == count:
            break
    ours, peers, ours_solve, peers_solve = [], [], [], []
    for _ in range(repeat):
        t = time.perf_counter()
        solving = 0.0
        for cells, want in sample:
            hs = HeeschSolver(SQUARE, cells, solver="glucose4")
            r = heesch(SQUARE, cells, max_level=2, hs=hs)
            assert (r.hc, r.hh) == want
            solving += hs.solve_seconds
        ours.append(time.perf_counter() - t)
        ours_solve.append(solving)
        t = time.perf_counter()
        PEER_SOLVE[0] = 0.0
        for cells, want in sample:
            assert peer_heesch(cells) == want, "the peer encoding disagrees"
        peers.append(time.perf_counter() - t)
        peers_solve.append(PEER_SOLVE[0])
    print(f"Heesch numbers of {len(sample)} {n}-ominoes (non-tilers, Hc <= 1), {repeat} runs:")
    print(f"  tilekit (cell ladder encoding): min {min(ours):.2f} s, median {statistics.median(ours):.2f} s")
    print(f"  peer (pairwise overlaps):       min {min(peers):.2f} s, median {statistics.median(peers):.2f} s")
    print(f"  ratio peer / tilekit (median): {statistics.median(peers) / statistics.median(ours):.2f}")
    # the encodings alone, without the cost of writing the formulas in Python
    print(f"  inside the solver: tilekit median {statistics.median(ours_solve):.2f} s, "
          f"peer median {statistics.median(peers_solve):.2f} s, ratio "
          f"{statistics.median(peers_solve) / max(1e-9, statistics.median(ours_solve)):.2f}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-cells", type=int, default=10)
    ap.add_argument("--min-cells", type=int, default=1)
    ap.add_argument("--executor", default="process", choices=["local", "process", "dask"])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--peer", type=int, default=0, help="time the peer encoding on this many non-tilers")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    print(f"load before: {os.getloadavg()}")
    if args.peer:
        peer_benchmark(args.max_cells, args.peer, args.repeat)
        return
    summary, wall = classification(args.max_cells, args.executor, args.workers if args.executor != "local" else None,
                                   args.min_cells)
    print(f"{args.executor} x{args.workers if args.executor != 'local' else 1}, load after: {os.getloadavg()}")
    report(summary, wall, args.max_cells, args.min_cells)


if __name__ == "__main__":
    main()
