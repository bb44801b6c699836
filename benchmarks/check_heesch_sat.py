"""A stored classification's Heesch numbers against Kaplan's heesch-sat, form by form.

Kaplan's census tables ("Heesch numbers of unmarked polyforms", 2022, arXiv:2105.09438,
Tables 3-6 for polyhexes and polyiamonds) are the output of his program's ``sat -hh``. Where the
printed tables cannot be read, running that program on the same shapes is the next best
reference. This script reads every hole-free n-form that a tilekit catalogue records as a
non-tiler (``tilekit search polyomino-classify --grid G``), runs ``sat -hh`` on all of them (the
file cut into ``--jobs`` parts, one process each), and checks heesch-sat's (Hc, Hh) against the
stored ``heesch`` / ``heesch_holes`` pair shape by shape. It prints both tallies per value, the
forms that differ, and heesch-sat's CPU time. Exit status 1 when any decided pair differs.

It does not re-run tilekit: for the timing side by side, see ``bench_heesch_sat.py --mode hc --hh``.
heesch-sat is built by ``bench_heesch_sat.py --build`` into the same cache folder.

    python benchmarks/check_heesch_sat.py --catalogue sqlite:///hex9.sqlite --grid hex --cells 9
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench_heesch_sat import PEER_GRID, cache_dir, peer_line, run_whole  # noqa: E402

from tilekit.catalogue import open_catalogue  # noqa: E402
from tilekit.errors import TilekitError  # noqa: E402
from tilekit.lattice import get_grid  # noqa: E402


def stored_nontilers(url: str, grid: str, n: int) -> tuple[list[tuple[str, np.ndarray, int, int]], Counter]:
    """(code, cells, Hc, Hh) of every hole-free non-tiler of the run, and the tally of all its rows
    by ``tiles`` (true / false / undecided) and holes; read through the catalogue API, streamed."""
    cat = open_catalogue(url, seed=False)
    rows = []
    tally: Counter = Counter()
    for row in cat.iter_result_rows("polyominoes", [f"grid={grid}", f"cells={n}"]):
        tally["with holes" if row["holes"] else f"tiles={row['tiles']}"] += 1
        if not row["holes"] and row["tiles"] == "false":
            rows.append((row["code"], np.array(json.loads(row["cell_list"]), dtype=np.int64),
                         int(row["heesch"]), int(row["heesch_holes"])))
    return rows, tally


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--catalogue", required=True, help="the run's catalogue (SQLAlchemy URL)")
    ap.add_argument("--grid", required=True, choices=sorted(set(PEER_GRID)), help="the grid")
    ap.add_argument("--cells", type=int, required=True, help="cells per form")
    ap.add_argument("--cache", help="heesch-sat's cache folder (default: the user cache, tilekit/heesch-sat)")
    ap.add_argument("--jobs", type=int, default=2, help="heesch-sat processes side by side")
    ap.add_argument("--every", type=int, default=1, help="every K-th non-tiler only (a spread sample; default all)")
    ap.add_argument("--max-level", type=int, default=7, help="heesch-sat's -maxlevel (its default 7)")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    grid = get_grid(args.grid)
    sat = cache_dir(args.cache) / "sat"
    if not sat.exists():
        raise SystemExit(f"no heesch-sat binary at {sat}: run benchmarks/bench_heesch_sat.py --build first")
    try:
        rows, tally = stored_nontilers(args.catalogue, grid.name, args.cells)
    except TilekitError as exc:
        raise SystemExit(f"cannot read the polyform rows of {args.catalogue}: {str(exc).splitlines()[0]}") from None
    rows = rows[::max(1, args.every)]
    if not rows:
        raise SystemExit(f"no hole-free non-tiling {args.cells}-forms of the {grid.name} grid in {args.catalogue}")
    print(f"load before: {os.getloadavg()}; the run's {args.cells}-forms: {dict(sorted(tally.items()))}; "
          f"{len(rows)} hole-free non-tilers to check (every {max(1, args.every)})", flush=True)
    lines = [peer_line(cells, grid) for _, cells, _, _ in rows]
    jobs = max(1, args.jobs)
    cmd = [str(sat), "-hh", "-maxlevel", str(args.max_level)]
    start = time.time()
    with ThreadPoolExecutor(jobs) as pool:
        cpu, verdicts = run_whole(cmd, lines, jobs, pool)
    ours = [("~", hc, hh) for _, _, hc, hh in rows]
    decided = [i for i, v in enumerate(verdicts) if v[0] == "~"]
    differ = [i for i in decided if verdicts[i] != ours[i]]
    print(f"load after: {os.getloadavg()}; heesch-sat {cpu:.1f} s CPU in {time.time() - start:.0f} s wall, "
          f"{jobs} processes")
    for name, got in (("stored", ours), ("heesch-sat", verdicts)):
        for what, col in (("Hc", 1), ("Hh", 2)):
            per = Counter(v[col] for v in got if v[0] == "~")
            print(f"  {name} {what} per value: {dict(sorted(per.items()))}")
    print(f"verdicts: heesch-sat decided {len(decided)} of {len(rows)}; they differ on {len(differ)}")
    for i in [i for i, v in enumerate(verdicts) if v[0] != "~"][:10]:
        print(f"  undecided by heesch-sat: {rows[i][0]} {verdicts[i]}")
    for i in differ[:10]:
        print(f"  differs: {rows[i][0]} stored {ours[i][1:]} heesch-sat {verdicts[i][1:]}")
    if differ:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
