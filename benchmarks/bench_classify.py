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


def _join(a_keys: np.ndarray, a_ids: np.ndarray, b_keys: np.ndarray, b_ids: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """All pairs (a_id, b_id) whose keys are equal (a sort-merge join in NumPy)."""
    o = np.argsort(b_keys, kind="stable")
    bk, bi = b_keys[o], b_ids[o]
    lo = np.searchsorted(bk, a_keys, "left")
    hi = np.searchsorted(bk, a_keys, "right")
    cnt = hi - lo
    left = np.repeat(a_ids, cnt)
    offs = np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    return left, bi[np.repeat(lo, cnt) + offs]


def peer_heesch(cells: np.ndarray, max_level: int = 2, solver: str = "glucose4") -> tuple[int, int]:
    """(Hc, Hh) with the obvious encoding, written as vectorised NumPy: one variable per
    placement and corona, no cell variables; every pair of overlapping copies forbidden by a
    binary clause (as in Kaplan's heesch-sat), found by a sort-merge join of (cell, copy)
    incidences; each halo cell of an inner copy (and of the kernel) covered by one of the
    copies covering it; a copy of corona i >= 2 touches some copy of corona i-1 and none
    below. Only the placement sets are shared with tilekit (HeeschSolver.levels)."""
    from tilekit.lattice import holes_of, pack, unique_keys, unpack
    from tilekit.sat import IncrementalSolver, gc_paused

    hs = HeeschSolver(SQUARE, cells)
    f = hs.forms
    hc = hh = 0
    for k in range(1, max_level + 1):
        while len(hs.levels) <= k:
            hs._grow()
        rows = np.concatenate(hs.levels[1:k + 1])
        lvl = np.concatenate([np.full(len(hs.levels[i]), i) for i in range(1, k + 1)])
        m = len(rows)
        ys = np.arange(1, m + 1)
        pcells = f.placement_cells(rows)  # (m, n)
        phalo = f.placement_halos(rows)  # (m, H)
        inc_c, inc_y = pcells.ravel(), np.repeat(ys, pcells.shape[1])
        with gc_paused():
            clauses: list[list[int]] = []
            # overlaps: pairs of copies sharing a cell, each pair once
            a, b = _join(inc_c, inc_y, inc_c, inc_y)
            keep = a < b
            pair = unique_keys(a[keep] * (m + 1) + b[keep])  # np.unique hashes: 20x slower here
            clauses += np.column_stack([-(pair // (m + 1)), -(pair % (m + 1))]).tolist()
            # covering lists per cell
            o = np.argsort(inc_c, kind="stable")
            sc, sy = inc_c[o], inc_y[o]
            starts = np.flatnonzero(np.r_[True, sc[1:] != sc[:-1]])
            cover_keys, covers = sc[starts], np.split(sy, starts[1:])

            def covering(keys: np.ndarray, cover_keys=cover_keys, covers=covers) -> list[list[int]]:
                pos = np.searchsorted(cover_keys, keys)
                pos = np.minimum(pos, len(cover_keys) - 1)
                return [covers[p].tolist() if cover_keys[p] == key else [] for p, key in zip(pos.tolist(), keys.tolist())]

            kh = hs.kernel_halo
            kcov = covering(kh)
            if any(not c for c in kcov):  # a kernel halo cell no copy can cover
                break
            clauses += kcov
            # halos of inner copies: y -> OR of the copies covering each halo cell
            inner = np.flatnonzero(lvl < k)
            hcells = phalo[inner]
            hy = np.repeat(ys[inner], hcells.shape[1])
            hk = hcells.ravel()
            notk = ~np.isin(hk, hs.kernel_keys)
            for y, cov in zip(hy[notk].tolist(), covering(hk[notk])):
                clauses.append([-y, *cov])
            # touching: (p, q) with q covering a halo cell of p
            p_, q_ = _join(phalo.ravel(), np.repeat(ys, phalo.shape[1]), inc_c, inc_y)
            tp = unique_keys(p_ * (m + 1) + q_)
            p_, q_ = tp // (m + 1), tp % (m + 1)
            lp, lq = lvl[p_ - 1], lvl[q_ - 1]
            low = (lp >= 2) & (lq < lp - 1)
            clauses += np.column_stack([-p_[low], -q_[low]]).tolist()
            up = (lp >= 2) & (lq == lp - 1)
            sel_p, sel_q = p_[up], q_[up]
            st = np.flatnonzero(np.r_[True, sel_p[1:] != sel_p[:-1]]) if len(sel_p) else np.zeros(0, int)
            has = set(sel_p[st].tolist())
            for y, g in zip(sel_p[st].tolist(), np.split(sel_q, st[1:]) if len(st) else []):
                clauses.append([-y, *g.tolist()])
            clauses += [[-int(y)] for y in ys[lvl >= 2] if int(y) not in has]
        free = holey = False
        with IncrementalSolver(clauses, solver=solver) as s:
            while True:
                ans = s.solve()
                PEER_SOLVE[0] += ans.seconds
                if not ans.satisfiable:
                    break
                used = np.flatnonzero(ans.values(ys))
                found = holes_of(SQUARE, np.concatenate([hs.kernel_keys, pcells[used].ravel()]))
                if not found:
                    free = True
                    break
                holey = True
                for hole in found:
                    hx = unpack(hole)
                    ring = pack(hx[:, None, :] + SQUARE.neighbours[0][None]).ravel()
                    bound = ys[used][np.isin(pcells[used], ring).any(axis=1)]
                    inside = ys[np.isin(pcells, hole).any(axis=1)]
                    s.add([*(-bound).tolist(), *inside.tolist()])
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


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-cells", type=int, default=10)
    ap.add_argument("--min-cells", type=int, default=1)
    ap.add_argument("--executor", default="process", choices=["local", "process", "dask"])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--peer", type=int, default=0, help="time the peer encoding on this many non-tilers")
    ap.add_argument("--repeat", type=int, default=5)
    return ap


def main() -> None:
    args = build_parser().parse_args()
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
