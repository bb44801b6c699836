"""tilekit's classification against Kaplan's heesch-sat on grids with cells of several shapes.

For every free polyform of 1..n cells on a grid with cells of several shapes (octasquare,
trihex, abolo, drafter, halfcairo, bevelhex), tilekit's full classification
(:func:`tilekit.plugins.polyomino.classify.classify_form`: holes, corona 1's local test, boundary words, coronas, tori) and heesch-sat's ``sat -isohedral -hh``
(Kaplan, github.com/isohedral/heesch-sat; the binary that ``bench_heesch_sat.py --build`` puts in
the cache folder) answer on the same shapes, and the verdicts are compared shape by shape:

- heesch-sat ``I`` (isohedral) against tilekit's isohedral tilers;
- heesch-sat ``~ Hc Hh`` (non-tiler) against tilekit's proved non-tilers, Hc and Hh equal, and
  against tilekit's forms with holes (heesch-sat gives them Hc = Hh = 0; tilekit stops at the
  hole);
- heesch-sat ``!`` (inconclusive: it cannot recognise anisohedral tilers) against tilekit's
  anisohedral tilers and undecided forms.

heesch-sat's cells are integer pairs in its own coordinates: :data:`TO_FINE` maps them onto
tilekit's fine coordinates by an integer similarity, :data:`BY_VERTICES` matches the cells by
their vertex sets (heesch-sat's tables transcribed). Both tools get the same number of forms
(tilekit's enumeration, checked distinct); the timing is CPU time, ``--runs`` rounds of each.

    python benchmarks/heesch_sat_grids.py --grid octasquare --max-cells 5
"""

from __future__ import annotations

import argparse
import collections
import os
import resource
import statistics
import subprocess
import sys
import time
from functools import cache
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))  # bench_heesch_sat, its neighbour

from bench_heesch_sat import cache_dir, child_cpu, parse_verdicts  # noqa: E402

from tilekit.lattice import canonical, free_polyforms, get_grid  # noqa: E402
from tilekit.plugins.polyomino.classify import classify_form  # noqa: E402

#: heesch-sat's grid letter and the map of its cell (x, y) to tilekit's fine coordinates:
#: fine = A @ (x, y) + b. octasquare: heesch-sat's squares are the cells with x + y even, its
#: octagons the others, on the square lattice turned by 45 degrees (octasquaregrid.h);
#: trihex: its hexagons are the cells with x - y = 0 mod 3 in the 60-degree basis, turned by
#: 30 degrees and scaled by sqrt(3) here (trihexgrid.h); bevelhex: tilekit's table is heesch-sat's.
TO_FINE = {
    "octasquare": ("o", np.array([[2, 2], [-2, 2]]), np.array([2, 2])),
    "trihex": ("T", np.array([[2, -2], [2, 4]]), np.array([0, 0])),
    "bevelhex": ("B", np.eye(2, dtype=np.int64), np.array([0, 0])),  # the same coordinates (bevelhexgrid.h)
}


def _abolo_vertices(x: int, y: int) -> list | None:
    t = {(0, 0): 0, (1, 0): 1, (1, 1): 2, (0, 1): 3}[(x % 2, y % 2)]
    vs = [[(1, 1), (1, -3), (-3, 1)], [(-1, 1), (3, 1), (-1, -3)], [(-1, -1), (-1, 3), (3, -1)],
          [(1, -1), (-3, -1), (1, 3)]][t]
    return [(2 * x + a, 2 * y + b) for a, b in vs]


_DRAFTER_TYPES = {(2, 1): 0, (1, 2): 1, (6, 3): 2, (5, 3): 3, (4, 2): 4, (4, 1): 5, (5, 6): 6, (6, 5): 7,
                  (1, 4): 8, (2, 4): 9, (3, 5): 10, (3, 6): 11}
_DRAFTER_VERTS = [[(6, 0), (4, 4)], [(4, 4), (0, 6)], [(0, 6), (-4, 8)], [(-4, 8), (-6, 6)], [(-6, 6), (-8, 4)],
                  [(-8, 4), (-6, 0)], [(-6, 0), (-4, -4)], [(-4, -4), (0, -6)], [(0, -6), (4, -8)],
                  [(4, -8), (6, -6)], [(6, -6), (8, -4)], [(8, -4), (6, 0)]]


_DRAFTER_LOS = [(-2, -1), (-1, -2), (1, -3), (2, -3), (3, -2), (3, -1), (2, 1), (1, 2), (-1, 3), (-2, 3), (-3, 2),
                (-3, 1)]


def _drafter_vertices(x: int, y: int) -> list | None:
    o = (x % 7, y % 7)
    if o not in _DRAFTER_TYPES:
        return None
    t = _DRAFTER_TYPES[o]
    lx, ly = _DRAFTER_LOS[t]
    hx, hy = (x + lx) // 7 * 12, (y + ly) // 7 * 12  # its corner at the hub: (p + lo) * 12 / 7
    return [(hx, hy)] + [(hx + a, hy + b) for a, b in _DRAFTER_VERTS[t]]


def _cdiv(a: int, b: int) -> int:
    """C's integer division (truncation toward zero)."""
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b > 0) else -q


_HC_TYPES = [None, 0, 4, 2, 1, 3, 6, 7, 5]  # by (y mod 3) * 3 + (x mod 3): E, W, N, NE, NW, S, SE, SW
_HC_OFFS = [(2, -1), (2, 1), (1, 2), (-1, 2), (-2, 1), (-2, -1), (-1, -2), (1, -2)]
_HC_CORNERS = [(2, 2), (-2, 2), (-2, -2), (2, -2)]


def _halfcairo_vertices(x: int, y: int) -> list | None:
    t = _HC_TYPES[(y % 3) * 3 + x % 3]
    if t is None:
        return None
    hx = _cdiv(x + 1, 3) * 4 if x >= 0 else _cdiv(x - 1, 3) * 4
    hy = _cdiv(y + 1, 3) * 4 if y >= 0 else _cdiv(y - 1, 3) * 4
    out = [(hx, hy), (hx + _HC_OFFS[t][0], hy + _HC_OFFS[t][1])]
    if t % 2:
        out.append((hx + _HC_CORNERS[t // 2][0], hy + _HC_CORNERS[t // 2][1]))
    out.append((hx + _HC_OFFS[(t + 1) % 8][0], hy + _HC_OFFS[(t + 1) % 8][1]))
    return out


#: Grids matched through their cells' vertices: heesch-sat's vertices of its cell (x, y) (from
#: its *grid.h tables) and the map of tilekit's fine vertex u to heesch-sat's vertex
#: ``(F u) / D + b``. abolo: heesch-sat's tetrakis squares are turned by 45 degrees, centred on
#: (1, 1) + 4 Z^2 (abologrid.h); drafter: the same 60-degree basis, hexagons of apothem 6
#: around hubs 12 Z^2 (draftergrid.h); halfcairo: squares of side 4 around hubs 4 Z^2
#: (halfcairogrid.h).
BY_VERTICES = {
    "abolo": ("A", np.array([[2, 2], [-2, 2]]), 3, np.array([1, 1]), _abolo_vertices),
    "drafter": ("D", np.array([[2, 0], [0, 2]]), 3, np.array([0, 0]), _drafter_vertices),
    "halfcairo": ("h", np.array([[1, 0], [0, 1]]), 3, np.array([0, 0]), _halfcairo_vertices),
}


@cache
def _peer_cells(grid_name: str, reach: int) -> dict:
    """heesch-sat's cells with |x|, |y| <= reach, by their vertex sets."""
    cell_vertices = BY_VERTICES[grid_name][4]
    out = {}
    for x in range(-reach, reach + 1):
        for y in range(-reach, reach + 1):
            vs = cell_vertices(x, y)
            if vs is not None:
                out[frozenset(vs)] = (x, y)
    return out


def _by_vertices(grid_name: str, cells: np.ndarray) -> str:
    letter, F, D, b, _ = BY_VERTICES[grid_name]
    grid = get_grid(grid_name)
    table = _peer_cells(grid_name, 80)
    out = []
    for c in cells:
        t = int(grid.cell_type(c[None])[0])
        num = (c + grid.vertices[t][: grid.degrees[t]]) @ F.T
        if (num % D).any():
            raise ValueError(f"{c.tolist()}: a vertex is not on heesch-sat's lattice")
        key = frozenset(map(tuple, (num // D + b).tolist()))
        if key not in table:
            raise ValueError(f"{c.tolist()} matches no heesch-sat cell")
        out.append(table[key])
    return letter + "?" + "".join(f" {x} {y}" for x, y in out) + "\n"


def to_peer(grid_name: str, cells: np.ndarray) -> str:
    """A form as heesch-sat's input record (unclassified)."""
    if grid_name in BY_VERTICES:
        return _by_vertices(grid_name, cells)
    letter, A, b = TO_FINE[grid_name]
    xy = np.linalg.solve(A, (cells - b).T).T
    q = np.round(xy).astype(np.int64)
    if not np.array_equal(q @ A.T + b, cells):
        raise ValueError(f"{cells.tolist()} is not on heesch-sat's lattice")
    return letter + "?" + "".join(f" {x} {y}" for x, y in q.tolist()) + "\n"


def parse_records(text: str) -> list[tuple]:
    """heesch-sat's output as (kind, hc, hh) per record (:func:`bench_heesch_sat.parse_verdicts`)."""
    return [(*v, None, None)[:3] for v in parse_verdicts(text)]


def ours(grid, cells: np.ndarray, holey: bool, time_limit: float) -> tuple:
    r = classify_form(grid, cells, has_holes=holey, time_limit=time_limit)
    if holey:
        return ("O", None, None), r
    if r.tiles == "true":
        return ("I", None, None) if r.isohedral else ("#", r.anisohedral_k, None), r
    if r.tiles == "false":
        return ("~", r.heesch, r.heesch_holes), r
    return ("!", None, None), r


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--grid", choices=sorted([*TO_FINE, *BY_VERTICES]), default="octasquare")
    ap.add_argument("--max-cells", type=int, default=5, help="largest size (forms of 1..N cells)")
    ap.add_argument("--sat", help="heesch-sat's sat binary (default: the user cache, tilekit/heesch-sat/sat)")
    ap.add_argument("--time-limit", type=float, default=120.0, help="tilekit's CPU seconds per form")
    ap.add_argument("--runs", type=int, default=3, help="rounds of both tools (CPU time: min and median)")
    ap.add_argument("--max-level", type=int, default=7,
                    help="heesch-sat's -maxlevel (coronas before 'inconclusive'; its default 7)")
    ap.add_argument("--per-form", type=int, default=0, metavar="R",
                    help="also time each form alone and print the medians: tilekit by process_time around each "
                         "call; heesch-sat as (CPU of a process given the form R + 1 times - CPU of one given it "
                         "once) / R, which leaves out its start-up and first-record costs (0: not timed)")
    return ap


def _medians(label: str, mine: np.ndarray, peer: np.ndarray, sel: np.ndarray) -> str:
    if not sel.any():
        return ""
    a, b = float(np.median(mine[sel])), float(np.median(peer[sel]))
    return (f"  {label} ({int(sel.sum())}): tilekit {1000 * a:.2f} ms, heesch-sat {1000 * b:.2f} ms, "
            f"heesch-sat / tilekit {b / a if a else float('inf'):.2f}\n")


def main() -> None:
    ap = build_parser()
    args = ap.parse_args()
    sat = Path(args.sat) if args.sat else cache_dir(None) / "sat"
    if not sat.exists():
        raise SystemExit(f"no heesch-sat binary at {sat}: run benchmarks/bench_heesch_sat.py --build first")
    grid = get_grid(args.grid)
    polys, holes, counts = free_polyforms(grid, args.max_cells, with_holes=True)
    print(f"{grid.name}: free forms per size {counts[1:].tolist()}; load {os.getloadavg()}", flush=True)
    keys = {tuple(map(tuple, canonical(grid, p).tolist())) for p in polys}
    assert len(keys) == len(polys), "the forms are not distinct"
    text = "".join(to_peer(grid.name, p) for p in polys)
    # load the compiled loops (numba's on-disk cache) once per process before timing, by
    # classifying the forms of up to 4 cells untimed; printed, as heesch-sat's start-up (a few
    # ms) stays in its time
    t0 = time.process_time()
    for cells, holey in zip(polys, holes):
        if len(cells) <= 4:
            ours(grid, cells, bool(holey), args.time_limit)
    print(f"warm-up (loading compiled code, forms of <= 4 cells): {time.process_time() - t0:.2f} s CPU", flush=True)
    peer_cpu, mine_cpu = [], []
    lines = text.splitlines(keepends=True)
    cmd = [str(sat), "-isohedral", "-hh", "-maxlevel", str(args.max_level)]
    mine_per = np.full((args.runs, len(polys)), np.inf)
    peer_per = np.full((args.runs, len(polys)), np.inf)
    for rnd in range(args.runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        out = subprocess.run([str(sat), "-isohedral", "-hh", "-maxlevel", str(args.max_level)], input=text,
                             capture_output=True, text=True, check=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        peer_cpu.append((after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime))
        t0 = time.process_time()
        answers = []
        for i, (cells, holey) in enumerate(zip(polys, holes)):
            t1 = time.process_time()
            answers.append(ours(grid, cells, bool(holey), args.time_limit))
            mine_per[rnd, i] = time.process_time() - t1
        mine_cpu.append(time.process_time() - t0)
        if args.per_form:
            R = args.per_form
            peer_per[rnd] = [(child_cpu(cmd, line * (R + 1))[0] - child_cpu(cmd, line)[0]) / R for line in lines]
    peer = parse_records(out.stdout)
    if len(peer) != len(polys):
        raise SystemExit(f"heesch-sat answered {len(peer)} records for {len(polys)} forms")
    table: dict[int, collections.Counter] = collections.defaultdict(collections.Counter)
    disagree = []
    for cells, theirs, (mine, r) in zip(polys, peer, answers):
        table[len(cells)][(mine[0], theirs[0])] += 1
        # heesch-sat cannot recognise anisohedral tilers ("!"); given a form with a hole it
        # computes its (zero) Heesch number, where tilekit stops at the hole: both non-tilers
        same = mine == theirs or (theirs[0] == "!" and mine[0] in "#!") or (mine[0] == "O" and theirs[0] == "~")
        if not same:
            disagree.append((cells, mine, theirs, r.verdict))
    dist: dict[int, collections.Counter] = collections.defaultdict(collections.Counter)
    for cells, theirs in zip(polys, peer):
        dist[len(cells)][theirs[0] if theirs[0] != "~" else f"Hc{theirs[1]}Hh{theirs[2]}"] += 1
    for n in sorted(dist):
        print(f"heesch-sat n = {n}: " + ", ".join(f"{k} {v}" for k, v in sorted(dist[n].items())))
    for n in sorted(table):
        row = ", ".join(f"tilekit {a} / heesch-sat {b}: {c}" for (a, b), c in sorted(table[n].items()))
        print(f"n = {n}: {row}")
    print(f"agree on {len(polys) - len(disagree)} of {len(polys)} forms")
    print(f"CPU s over {args.runs} runs (min / median): tilekit's classification {min(mine_cpu):.3f} / "
          f"{statistics.median(mine_cpu):.3f}, heesch-sat -isohedral -hh {min(peer_cpu):.3f} / "
          f"{statistics.median(peer_cpu):.3f}; heesch-sat / tilekit {min(peer_cpu) / min(mine_cpu):.2f} (min); "
          f"load {os.getloadavg()}")
    if args.per_form:
        mine_min, peer_min = mine_per.min(axis=0), peer_per.min(axis=0)
        kind = np.array([m[0] for m, _ in answers])
        print(f"per form, CPU, min of {args.runs} rounds, median (heesch-sat: form given {args.per_form + 1} times "
              f"less given once, / {args.per_form}):\n" + _medians("all forms", mine_min, peer_min, np.ones(len(kind), bool))
              + _medians("isohedral", mine_min, peer_min, kind == "I")
              + _medians("non-tilers without holes", mine_min, peer_min, kind == "~")
              + _medians("anisohedral or undecided", mine_min, peer_min, (kind == "#") | (kind == "!")), end="")
    for cells, mine, theirs, verdict in disagree:
        print(f"  differs: {to_peer(grid.name, cells).strip()} tilekit {mine} heesch-sat {theirs}: {verdict}")


if __name__ == "__main__":
    main()
