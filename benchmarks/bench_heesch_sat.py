"""Hole-free Heesch numbers (Hc) side by side with Kaplan's heesch-sat, one core each.

The peer is Kaplan's own tool (github.com/isohedral/heesch-sat, C++ with CryptoMiniSat 5), run
in its default mode, which computes Hc alone (no ``-hh``, no ``-isohedral``); tilekit runs
:func:`tilekit.plugins.polyomino.heesch.hole_free_heesch` on the same shapes in this process.
Both answer per shape; the Hc values are checked equal wherever heesch-sat decides.

heesch-sat is never committed here. ``--build`` fetches its source (``git clone`` of the public
repository, or ``--source`` pointing at a local clone or bare git directory), applies the small
Makefile patch ``heesch_sat_makefile.patch`` (its Makefile is written for macOS: clang++ with libc++, the MacPorts
prefix, ``-rpath``), and builds ``sat`` into the cache folder. It needs a C++17 compiler,
``make``, ``patch`` and Debian's ``libcryptominisat5-dev`` and ``libboost-dev``.

Two modes (``--mode``):

- ``hc`` (the default on the square grid): the hole-free non-tilers of ``--cells`` cells, found
  once with tilekit (free forms without holes, not isohedral by the boundary-word test, proved
  non-tilers by :func:`heesch`) and kept in the cache folder; by default the 1,390 non-tiling
  10-ominoes (OEIS A054361; Kaplan, "Heesch numbers of unmarked polyforms", 2022, Table 1 gives
  their Hc: 747 / 642 / 1 for Hc = 0 / 1 / 2, checked). heesch-sat's default mode (Hc alone)
  against :func:`hole_free_heesch`; with ``--hh``, ``sat -hh`` against :func:`heesch` (Hc, Hh
  and the proof), the pairs checked equal (Kaplan's Tables 2-6 come from ``sat -hh``);
- ``classify`` (the default on the other grids): every hole-free free form of ``--cells`` cells
  (``--sample K`` draws K of them at random, ``--seed``), ``sat -isohedral`` (its isohedral
  test, then Hc up to ``--max-level``, "inconclusive" for a form surrounded that often) against
  tilekit's boundary-word test (:func:`analyse`) and, when that finds no isohedral tiling,
  :func:`hole_free_heesch` to the same level. Verdicts (isohedral / Hc / surrounded) are
  checked equal wherever heesch-sat decides.

Grids: square (``O``), hex (``H``), iamond (``I``) and kite (``K``) cells are written in
heesch-sat's coordinates (hex: tilekit's fine coordinates / 3; iamond: less (1, 1); kite: the
30-degree turn and scaling by 1/sqrt(3) taking tilekit's kite at (1, 1) to heesch-sat's at (1, 0)).

Timing is CPU time (user + system), so that other jobs on a shared machine change it little:
tilekit's per shape by ``time.process_time`` around each call, heesch-sat's as a child process
per shape (the child's own rusage, from ``os.wait4``) less the median CPU time of the same binary
on an empty input (its start-up), and its total as the CPU time of processes over the whole file
(cut into ``--jobs`` parts run side by side; their CPU times are summed). Each is the
minimum over ``--runs`` rounds; the medians and totals of those minima are compared.

    python benchmarks/bench_heesch_sat.py --build [--source PATH]
    python benchmarks/bench_heesch_sat.py --runs 3 [--solver glucose4] [--limit N]
    python benchmarks/bench_heesch_sat.py --grid hex --cells 9 --runs 1 [--sample 500]
    python benchmarks/bench_heesch_sat.py --grid hex --cells 7 --hh --runs 1
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tilekit.lattice import SQUARE, Grid, encode, enumerate_free, get_grid  # noqa: E402
from tilekit.plugins.polyomino.heesch import HC_SOLVER, heesch, hole_free_heesch  # noqa: E402
from tilekit.plugins.polyomino.isohedral import analyse  # noqa: E402

REPO = "https://github.com/isohedral/heesch-sat"
#: heesch-sat's Makefile (for macOS) made to build on Debian, applied with ``patch`` at build time
MAKEFILE_PATCH = Path(__file__).with_name("heesch_sat_makefile.patch")
#: Kaplan 2022, Table 1, n = 10: hole-free non-tilers by Hc
KAPLAN_HC_10 = {0: 747, 1: 642, 2: 1}
A054361_10 = 1390


def cache_dir(arg: str | None) -> Path:
    if arg:
        path = Path(arg)
    else:
        from platformdirs import user_cache_dir

        path = Path(user_cache_dir("tilekit")) / "heesch-sat"
    path.mkdir(parents=True, exist_ok=True)
    return path


# --------------------------------------------------------------------------- building the peer

def check_build_tools() -> None:
    missing = [tool for tool in ("g++", "make", "patch", "git") if shutil.which(tool) is None]
    headers = {"libcryptominisat5-dev": "/usr/include/cryptominisat5/cryptominisat.h",
               "libboost-dev": "/usr/include/boost/version.hpp"}
    absent = [pkg for pkg, header in headers.items() if not Path(header).exists()]
    if missing or absent:
        raise SystemExit("cannot build heesch-sat: " + "; ".join(
            ([f"missing tools: {', '.join(missing)}"] if missing else [])
            + ([f"missing packages: apt-get install {' '.join(absent)}"] if absent else [])))


def build(cache: Path, source: str | None) -> Path:
    """Build heesch-sat's ``sat`` into ``cache`` and return its path."""
    check_build_tools()
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "heesch-sat"
        origin = source or REPO
        if source and (Path(source) / "HEAD").exists() and not (Path(source) / ".git").exists():
            # a bare git directory: export its HEAD
            src.mkdir()
            archive = subprocess.run(["git", f"--git-dir={source}", "archive", "HEAD"], check=True,
                                     capture_output=True).stdout
            subprocess.run(["tar", "-x", "-C", str(src)], input=archive, check=True)
            commit = subprocess.run(["git", f"--git-dir={source}", "rev-parse", "HEAD"], check=True,
                                    capture_output=True, text=True).stdout.strip()
        else:
            subprocess.run(["git", "clone", "--quiet", origin, str(src)], check=True)
            commit = subprocess.run(["git", "-C", str(src), "rev-parse", "HEAD"], check=True,
                                    capture_output=True, text=True).stdout.strip()
        subprocess.run(["patch", "-p1", "--quiet", "-i", str(MAKEFILE_PATCH)], cwd=src, check=True)
        print(f"building heesch-sat {commit[:7]} (sat only; a minute or so)", flush=True)
        subprocess.run(["make", "-s", "sat"], cwd=src / "src", check=True, stderr=subprocess.DEVNULL)
        target = cache / "sat"
        shutil.copy2(src / "src" / "sat", target)
        (cache / "commit.txt").write_text(commit + "\n")
    print(f"built {target} from heesch-sat {commit}")
    return target


# --------------------------------------------------------------------------- the shapes

def hole_free_forms(grid: Grid, n: int) -> list[np.ndarray]:
    """Every hole-free free n-form of ``grid`` (from every cell type's root, each form once)."""
    seen: set[str] = set()
    out = []
    for root in range(len(grid.roots)):
        polys, flags, _ = enumerate_free(grid, n, root=root, maxsize=n, with_holes=True)
        for cells, holey in zip(polys, flags):
            code = encode(grid, cells)
            if len(cells) == n and not holey and code not in seen:
                seen.add(code)
                out.append(cells)
    return out


def nontilers(cache: Path, grid: Grid, n: int) -> list[tuple[np.ndarray, int]]:
    """The hole-free non-tiling n-forms (cells in tilekit's fine coordinates) with the Hc
    tilekit's proof gives; computed once (minutes) and cached. The 10-ominoes are checked
    against A054361 and Kaplan's Table 1."""
    path = cache / ("nontilers10.json" if (grid.name, n) == ("square", 10) else f"nontilers-{grid.name}-{n}.json")
    if not path.exists():
        print(f"finding the hole-free non-tiling {n}-forms of the {grid.name} grid with tilekit (once; minutes)",
              flush=True)
        out = []
        for cells in hole_free_forms(grid, n):
            if analyse(grid, cells, construct=False)["isohedral"]:
                continue
            r = heesch(grid, cells, max_level=5)
            if r.decided:
                out.append([cells.tolist(), r.hc])
        path.write_text(json.dumps(out))
    data = json.loads(path.read_text())
    shapes = [(np.array(c, dtype=np.int64), int(hc)) for c, hc in data]
    hist: dict[int, int] = {}
    for _, hc in shapes:
        hist[hc] = hist.get(hc, 0) + 1
    if (grid.name, n) == ("square", 10) and (len(shapes) != A054361_10 or hist != KAPLAN_HC_10):
        raise SystemExit(f"the cached shapes differ from A054361 / Kaplan's Table 1: {len(shapes)} shapes, Hc {hist}")
    return shapes


#: heesch-sat's one-letter grid codes
PEER_GRID = {"square": "O", "hex": "H", "iamond": "I", "kite": "K"}


def peer_cells(grid: Grid, cells: np.ndarray) -> np.ndarray:
    """tilekit's fine cell coordinates -> heesch-sat's."""
    c = np.asarray(cells, dtype=np.int64)
    if grid.name == "square":
        return (c - 1) // 2
    if grid.name == "hex":
        return c // 3
    if grid.name == "iamond":
        return c - 1
    if grid.name == "kite":
        u, v = c[:, 0], c[:, 1]
        return np.stack([(2 * u + v) // 3, (v - u) // 3], axis=1)
    raise SystemExit(f"no heesch-sat coordinates for the {grid.name} grid here (square, hex, iamond, kite)")


def peer_line(cells: np.ndarray, grid: Grid = SQUARE) -> str:
    """A shape as heesch-sat's input record (unclassified): the grid letter, ``?`` and the cells."""
    xy = peer_cells(grid, cells)
    return PEER_GRID[grid.name] + "?" + "".join(f" {x} {y}" for x, y in xy.tolist()) + "\n"


def parse_verdicts(text: str) -> list[tuple]:
    """heesch-sat's verdict per record: ``("~", hc, hh)`` for a non-tiler, ``("I",)`` isohedral,
    ``("!",)`` inconclusive (surrounded to the level limit), ``("?",)`` anything else."""
    lines = text.splitlines()
    out: list[tuple] = []
    i = 0
    while i < len(lines):
        head = lines[i + 1].split() if i + 1 < len(lines) else []
        kind = head[0][0] if head else "?"
        out.append(("~", int(head[1]), int(head[2])) if kind == "~" else (kind if kind in "I!" else "?",))
        patches = int(head[-1]) if head and head[-1].isdigit() else 0
        i += 2
        for _ in range(patches):
            i += 1 + int(lines[i])
    return out


def parse_peer(text: str) -> list[int | None]:
    """Hc per record of heesch-sat's output (None: not decided, e.g. inconclusive)."""
    return [v[1] if v[0] == "~" else None for v in parse_verdicts(text)]


# --------------------------------------------------------------------------- timing

def child_cpu(cmd: list[str], stdin: str) -> tuple[float, str]:
    """CPU seconds (user + system) of one child process, from its own rusage, and its output."""
    with tempfile.TemporaryFile("w+") as out:
        proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=out, stderr=subprocess.DEVNULL, text=True)
        proc.stdin.write(stdin)
        proc.stdin.close()
        _, status, usage = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode:
            raise SystemExit(f"heesch-sat exited with {proc.returncode}")
        out.seek(0)
        return usage.ru_utime + usage.ru_stime, out.read()


def run_whole(cmd: list[str], lines: list[str], jobs: int, pool) -> tuple[float, list]:
    """heesch-sat over the whole file, cut into ``jobs`` interleaved parts run side by side on
    ``pool``: the CPU seconds summed over the parts, and the verdicts in the lines' order."""
    done = list(pool.map(lambda part: child_cpu(cmd, part), ["".join(lines[i::jobs]) for i in range(jobs)]))
    verdicts: list = [None] * len(lines)
    for i, (_, out) in enumerate(done):
        verdicts[i::jobs] = parse_verdicts(out)
    return sum(cpu for cpu, _ in done), verdicts


def run_peer(sat: Path, lines: list[str], runs: int, max_level: int, jobs: int,
             flags: tuple[str, ...] = ()) -> tuple[np.ndarray, list[float], float, list]:
    """heesch-sat per shape (a process each, ``jobs`` at a time; each child's own CPU time)
    and in total (the file cut into ``jobs`` parts, one process each, CPU times summed)."""
    from concurrent.futures import ThreadPoolExecutor

    cmd = [str(sat), *flags, "-maxlevel", str(max_level)]
    empty = statistics.median(child_cpu(cmd, "")[0] for _ in range(max(5, runs)))
    per = np.full((runs, len(lines)), np.inf)
    totals = []
    verdicts: list = []
    with ThreadPoolExecutor(jobs) as pool:
        for r in range(runs):
            done = list(pool.map(lambda line: child_cpu(cmd, line), lines))
            per[r] = [max(0.0, cpu - empty) for cpu, _ in done]
            if r == 0:
                for _, out in done:
                    verdicts.extend(parse_verdicts(out))
            total, again = run_whole(cmd, lines, jobs, pool)
            totals.append(total)
            if r == 0:
                if again != verdicts:
                    raise SystemExit("heesch-sat answered differently on the whole file and shape by shape")
    return per.min(axis=0), totals, empty, verdicts


def tilekit_answer(grid: Grid, cells: np.ndarray, mode: str, hh: bool, max_level: int, solver: str) -> tuple:
    """tilekit's verdict in heesch-sat's terms (see :func:`parse_verdicts`)."""
    if mode == "classify" and analyse(grid, cells, construct=False)["isohedral"]:
        return ("I",)
    if hh:
        r = heesch(grid, cells, max_level=max_level)
        return ("~", r.hc, r.hh) if r.decided else ("!",)
    r = hole_free_heesch(grid, cells, max_level=max_level, solver=solver)
    return ("!",) if r.hc is None else ("~", r.hc)


def run_tilekit(grid: Grid, shapes: list[np.ndarray], runs: int, mode: str, hh: bool, max_level: int,
                solver: str) -> tuple[np.ndarray, list[float], list]:
    tilekit_answer(grid, shapes[0], mode, hh, max_level, solver)  # compile and import once
    per = np.full((runs, len(shapes)), np.inf)
    answers: list = []
    for r in range(runs):
        for i, cells in enumerate(shapes):
            t = time.process_time()
            res = tilekit_answer(grid, cells, mode, hh, max_level, solver)
            per[r, i] = time.process_time() - t
            if r == 0:
                answers.append(res)
    return per.min(axis=0), per.sum(axis=1).tolist(), answers


def same(ours: tuple, peer: tuple, hh: bool) -> bool:
    """Equal verdicts (Hc alone unless ``hh``)."""
    return ours[:3] == peer[:3] if hh else ours[:2] == peer[:2]


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", action="store_true", help="build heesch-sat's sat into the cache folder")
    ap.add_argument("--source", help="a local clone or bare git directory of heesch-sat (default: clone from GitHub)")
    ap.add_argument("--cache", help="cache folder (default: the user cache, tilekit/heesch-sat)")
    ap.add_argument("--grid", default="square", choices=sorted(PEER_GRID), help="the grid (default square)")
    ap.add_argument("--cells", type=int, default=None,
                    help="cells per form (default 10 on the square grid; required on the others)")
    ap.add_argument("--mode", choices=("hc", "classify"), default=None,
                    help="hc: Hc of the proved non-tilers (default on the square grid); classify: every hole-free "
                         "form, isohedral test then Hc (default on the others)")
    ap.add_argument("--hh", action="store_true", help="hc mode: Hc and Hh (sat -hh against heesch())")
    ap.add_argument("--sample", type=int, default=0, help="K forms drawn at random (--seed) instead of all")
    ap.add_argument("--seed", type=int, default=28, help="the sample's random seed")
    ap.add_argument("--runs", type=int, default=3, help="rounds; per shape the minimum is kept")
    ap.add_argument("--limit", type=int, default=0, help="only the first N shapes (a quick look)")
    ap.add_argument("--every", type=int, default=1, help="every K-th shape only (a sample spread over the set)")
    ap.add_argument("--solver", default=HC_SOLVER, help="tilekit's SAT solver")
    ap.add_argument("--jobs", type=int, default=2, help="heesch-sat processes at a time (CPU time is per process)")
    ap.add_argument("--max-level", type=int, default=7, help="both tools stop after this many coronas (heesch-sat's default 7)")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    grid = get_grid(args.grid)
    n = args.cells or (10 if grid.name == "square" else 0)
    if not 1 <= n <= 16:
        raise SystemExit(f"--cells must be between 1 and 16 (required on the {grid.name} grid)")
    mode = args.mode or ("hc" if grid.name == "square" else "classify")
    if args.hh and mode != "hc":
        raise SystemExit("--hh goes with --mode hc")
    cache = cache_dir(args.cache)
    sat = cache / "sat"
    if args.build or not sat.exists():
        if not args.build:
            raise SystemExit(f"no heesch-sat binary in {cache}: run with --build first")
        build(cache, args.source)
    if mode == "hc":
        found = nontilers(cache, grid, n)
        shapes = [c for c, _ in found]
        known = [hc for _, hc in found]
        what = f"hole-free non-tiling {n}-forms"
    else:
        shapes = hole_free_forms(grid, n)
        known = [None] * len(shapes)
        what = f"hole-free {n}-forms"
    picked = list(range(len(shapes)))
    if args.sample and args.sample < len(shapes):
        picked = sorted(random.Random(args.seed).sample(picked, args.sample))
        what += f" (a random sample, seed {args.seed}, of {len(shapes)})"
    picked = picked[::max(1, args.every)]
    if args.limit:
        picked = picked[:args.limit]
    shapes = [shapes[i] for i in picked]
    known = [known[i] for i in picked]
    print(f"load before: {os.getloadavg()}; {len(shapes)} {what} of the {grid.name} grid, mode {mode}"
          f"{' with Hh' if args.hh else ''}, max level {args.max_level}; heesch-sat "
          f"{(cache / 'commit.txt').read_text().strip()[:7] if (cache / 'commit.txt').exists() else '?'}", flush=True)
    ours, our_totals, answers = run_tilekit(grid, shapes, args.runs, mode, args.hh, args.max_level, args.solver)
    flags = ("-isohedral",) if mode == "classify" else ("-hh",) if args.hh else ()
    lines = [peer_line(c, grid) for c in shapes]
    peer, peer_totals, empty, verdicts = run_peer(sat, lines, args.runs, args.max_level, args.jobs, flags)
    decided = [i for i, v in enumerate(verdicts) if v[0] in "~I"]
    differ = [i for i in decided if not same(answers[i], verdicts[i], args.hh)]
    own = [i for i, hc in enumerate(known) if hc is not None and answers[i][:2] != ("~", hc)]
    print(f"load after: {os.getloadavg()}")
    kinds = {"I": "isohedral", "~": "non-tilers", "!": "surrounded to the level limit", "?": "other"}
    for name, got in (("tilekit", answers), ("heesch-sat", verdicts)):
        tally = {kinds[k]: sum(1 for v in got if v[0] == k) for k in kinds if any(v[0] == k for v in got)}
        print(f"  {name}: {tally}")
    print(f"verdicts: heesch-sat decided {len(decided)} of {len(shapes)}; they differ on {len(differ)}"
          + (f"; tilekit's Hc differs from its own proof on {len(own)}" if mode == "hc" else ""))
    for i in differ[:10]:
        print(f"  differs: {peer_line(shapes[i], grid).strip()} ({encode(grid, shapes[i])}) tilekit {answers[i]} "
              f"heesch-sat {verdicts[i]}")
    om, pm = statistics.median(ours), statistics.median(peer)
    print(f"per shape, CPU ms (min of {args.runs} rounds): tilekit median {1000 * om:.1f}, "
          f"heesch-sat median {1000 * pm:.1f} (start-up {1000 * empty:.1f} ms subtracted); "
          f"heesch-sat / tilekit {pm / max(om, 1e-9):.2f}")
    print(f"total CPU s: tilekit min {min(our_totals):.2f} median {statistics.median(our_totals):.2f}; "
          f"heesch-sat (whole file) min {min(peer_totals):.2f} median {statistics.median(peer_totals):.2f}; "
          f"heesch-sat / tilekit {min(peer_totals) / min(our_totals):.2f} (min), "
          f"{statistics.median(peer_totals) / statistics.median(our_totals):.2f} (median)")
    groups: dict[tuple, list[int]] = {}
    for i, v in enumerate(answers):
        groups.setdefault(v[:2], []).append(i)
    for key in sorted(groups, key=str):
        at = groups[key]
        label = {"I": "isohedral", "!": "surrounded"}.get(key[0], f"Hc = {key[1] if len(key) > 1 else '?'}")
        print(f"  tilekit {label}: {len(at)} shapes, median ms tilekit {1000 * statistics.median(ours[at]):.1f}, "
              f"heesch-sat {1000 * statistics.median(peer[at]):.1f}; total s tilekit {ours[at].sum():.2f}, "
              f"heesch-sat {peer[at].sum():.2f}")
    if args.hh and mode == "hc":
        for what_, col in (("Hc", 1), ("Hh", 2)):
            tally: dict[int, int] = {}
            for v in answers:
                tally[v[col]] = tally.get(v[col], 0) + 1
            print(f"  tilekit {what_} per value: {dict(sorted(tally.items()))}")
    if differ:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
