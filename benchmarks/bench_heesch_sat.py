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

The shapes: the 1,390 hole-free non-tiling 10-ominoes (OEIS A054361; Kaplan, "Heesch numbers of
unmarked polyforms", 2022, Table 1 gives their Hc: 747 / 642 / 1 for Hc = 0 / 1 / 2). They are
found once with tilekit (free 10-ominoes without holes, not isohedral by the boundary-word
test, and proved non-tilers by :func:`heesch`) and kept in the cache folder.

Timing is CPU time (user + system), so that other jobs on a shared machine change it little:
tilekit's per shape by ``time.process_time`` around each call, heesch-sat's as a child process
per shape (the child's own rusage, from ``os.wait4``) less the median CPU time of the same binary
on an empty input (its start-up), and its total as the CPU time of processes over the whole file
(cut into ``--jobs`` parts run side by side; their CPU times are summed). Each is the
minimum over ``--runs`` rounds; the medians and totals of those minima are compared.

    python benchmarks/bench_heesch_sat.py --build [--source PATH]
    python benchmarks/bench_heesch_sat.py --runs 3 [--solver glucose4] [--limit N]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tilekit.lattice import SQUARE, enumerate_free  # noqa: E402
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

def nontilers_10(cache: Path) -> list[tuple[np.ndarray, int]]:
    """The 1,390 hole-free non-tiling 10-ominoes (cells in tilekit's fine coordinates) with
    the Hc tilekit's proof gives; computed once (minutes) and cached."""
    path = cache / "nontilers10.json"
    if not path.exists():
        print("finding the hole-free non-tiling 10-ominoes with tilekit (once; minutes)", flush=True)
        polys, flags, _ = enumerate_free(SQUARE, 10, with_holes=True)
        out = []
        for cells, holey in zip(polys, flags):
            if len(cells) != 10 or holey or analyse(SQUARE, cells, construct=False)["isohedral"]:
                continue
            r = heesch(SQUARE, cells, max_level=3)
            if r.decided:
                out.append([cells.tolist(), r.hc])
        path.write_text(json.dumps(out))
    data = json.loads(path.read_text())
    shapes = [(np.array(c, dtype=np.int64), int(hc)) for c, hc in data]
    hist: dict[int, int] = {}
    for _, hc in shapes:
        hist[hc] = hist.get(hc, 0) + 1
    if len(shapes) != A054361_10 or hist != KAPLAN_HC_10:
        raise SystemExit(f"the cached shapes differ from A054361 / Kaplan's Table 1: {len(shapes)} shapes, Hc {hist}")
    return shapes


def peer_line(cells: np.ndarray) -> str:
    """A shape as heesch-sat's input record (unclassified): ``O?`` and the square cells."""
    xy = (cells - 1) // 2
    return "O?" + "".join(f" {x} {y}" for x, y in xy.tolist()) + "\n"


def parse_peer(text: str) -> list[int | None]:
    """Hc per record of heesch-sat's output (None: not decided, e.g. inconclusive)."""
    lines = text.splitlines()
    out: list[int | None] = []
    i = 0
    while i < len(lines):
        head = lines[i + 1].split() if i + 1 < len(lines) else []
        out.append(int(head[1]) if head and head[0] == "~" else None)
        patches = int(head[-1]) if head and head[-1].isdigit() else 0
        i += 2
        for _ in range(patches):
            i += 1 + int(lines[i])
    return out


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


def run_peer(sat: Path, shapes: list, runs: int, max_level: int, jobs: int) -> tuple[np.ndarray, list[float], float, list]:
    """heesch-sat per shape (a process each, ``jobs`` at a time; each child's own CPU time)
    and in total (the file cut into ``jobs`` parts, one process each, CPU times summed)."""
    from concurrent.futures import ThreadPoolExecutor

    cmd = [str(sat), "-maxlevel", str(max_level)]
    empty = statistics.median(child_cpu(cmd, "")[0] for _ in range(max(5, runs)))
    per = np.full((runs, len(shapes)), np.inf)
    totals = []
    verdicts: list = []
    lines = [peer_line(c) for c, _ in shapes]
    parts = ["".join(lines[i::jobs]) for i in range(jobs)]
    with ThreadPoolExecutor(jobs) as pool:
        for r in range(runs):
            done = list(pool.map(lambda line: child_cpu(cmd, line), lines))
            per[r] = [max(0.0, cpu - empty) for cpu, _ in done]
            if r == 0:
                for _, out in done:
                    verdicts.extend(parse_peer(out))
            whole = list(pool.map(lambda part: child_cpu(cmd, part), parts))
            totals.append(sum(cpu for cpu, _ in whole))
            if r == 0:
                again = [None] * len(lines)
                for i, (_, out) in enumerate(whole):
                    again[i::jobs] = parse_peer(out)
                if again != verdicts:
                    raise SystemExit("heesch-sat answered differently on the whole file and shape by shape")
    return per.min(axis=0), totals, empty, verdicts


def run_tilekit(shapes: list, runs: int, max_level: int, solver: str) -> tuple[np.ndarray, list[float], list]:
    hole_free_heesch(SQUARE, shapes[0][0], max_level=max_level, solver=solver)  # compile and import once
    per = np.full((runs, len(shapes)), np.inf)
    answers: list = []
    for r in range(runs):
        for i, (cells, _) in enumerate(shapes):
            t = time.process_time()
            res = hole_free_heesch(SQUARE, cells, max_level=max_level, solver=solver)
            per[r, i] = time.process_time() - t
            if r == 0:
                answers.append(res.hc)
    return per.min(axis=0), per.sum(axis=1).tolist(), answers


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", action="store_true", help="build heesch-sat's sat into the cache folder")
    ap.add_argument("--source", help="a local clone or bare git directory of heesch-sat (default: clone from GitHub)")
    ap.add_argument("--cache", help="cache folder (default: the user cache, tilekit/heesch-sat)")
    ap.add_argument("--runs", type=int, default=3, help="rounds; per shape the minimum is kept")
    ap.add_argument("--limit", type=int, default=0, help="only the first N shapes (a quick look)")
    ap.add_argument("--every", type=int, default=1, help="every K-th shape only (a sample spread over the set)")
    ap.add_argument("--solver", default=HC_SOLVER, help="tilekit's SAT solver")
    ap.add_argument("--jobs", type=int, default=2, help="heesch-sat processes at a time (CPU time is per process)")
    ap.add_argument("--max-level", type=int, default=7, help="both tools stop after this many coronas (heesch-sat's default 7)")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    cache = cache_dir(args.cache)
    sat = cache / "sat"
    if args.build or not sat.exists():
        if not args.build:
            raise SystemExit(f"no heesch-sat binary in {cache}: run with --build first")
        build(cache, args.source)
    shapes = nontilers_10(cache)
    shapes = shapes[::max(1, args.every)]
    if args.limit:
        shapes = shapes[:args.limit]
    print(f"load before: {os.getloadavg()}; {len(shapes)} hole-free non-tiling 10-ominoes; "
          f"heesch-sat {(cache / 'commit.txt').read_text().strip()[:7] if (cache / 'commit.txt').exists() else '?'}",
          flush=True)
    ours, our_totals, answers = run_tilekit(shapes, args.runs, args.max_level, args.solver)
    peer, peer_totals, empty, verdicts = run_peer(sat, shapes, args.runs, args.max_level, args.jobs)
    decided = [i for i, v in enumerate(verdicts) if v is not None]
    differ = [i for i in decided if verdicts[i] != answers[i]]
    known = [i for i, (_, hc) in enumerate(shapes) if answers[i] != hc]
    print(f"load after: {os.getloadavg()}")
    print(f"verdicts: heesch-sat decided {len(decided)} of {len(shapes)}; Hc differs on {len(differ)}; "
          f"tilekit's Hc differs from its own proof on {len(known)}")
    for i in differ[:10]:
        print(f"  differs: {peer_line(shapes[i][0]).strip()} tilekit {answers[i]} heesch-sat {verdicts[i]}")
    om, pm = statistics.median(ours), statistics.median(peer)
    print(f"per shape, CPU ms (min of {args.runs} rounds): tilekit median {1000 * om:.1f}, "
          f"heesch-sat median {1000 * pm:.1f} (start-up {1000 * empty:.1f} ms subtracted); "
          f"heesch-sat / tilekit {pm / om:.2f}")
    print(f"total CPU s: tilekit min {min(our_totals):.2f} median {statistics.median(our_totals):.2f}; "
          f"heesch-sat (whole file) min {min(peer_totals):.2f} median {statistics.median(peer_totals):.2f}; "
          f"heesch-sat / tilekit {min(peer_totals) / min(our_totals):.2f} (min), "
          f"{statistics.median(peer_totals) / statistics.median(our_totals):.2f} (median)")
    for hc in sorted({hc for _, hc in shapes}):
        at = [i for i, (_, h) in enumerate(shapes) if h == hc]
        print(f"  Hc = {hc}: {len(at)} shapes, median ms tilekit {1000 * statistics.median(ours[at]):.1f}, "
              f"heesch-sat {1000 * statistics.median(peer[at]):.1f}")
    if differ:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
