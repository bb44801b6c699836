"""Start-up of the command line as whole processes, against ``python -c pass``.

    python benchmarks/bench_startup.py --runs 7

Runs, in turn, ``python -c pass`` (the floor any Python command pays), ``tilekit --help`` and
warm ``tilekit list`` commands on a scratch SQLite catalogue (opened and seeded once before the
rounds), read through ``sqlite3`` and, with ``TILEKIT_READ_PATH=full``, through SQLAlchemy,
each as a child process after one warm-up; prints min and median of its CPU seconds (user + sys from ``os.wait4``) and wall seconds, and the ratio to ``python -c pass``
round by round. ``--base DIR`` also times another checkout of tilekit (``PYTHONPATH=DIR``, its
own catalogue), e.g. ``git archive main | tar -x -C /tmp/base`` for a before/after table.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def run(cmd: list[str], env: dict[str, str]) -> tuple[float, float]:
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"{' '.join(cmd)} failed")
    return usage.ru_utime + usage.ru_stime, wall


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--base", help="another tilekit checkout to time as well (PYTHONPATH)")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="tilekit-startup-"))
    py = sys.executable
    cli = "from tilekit.cli import main; main()"
    variants = {"": {}}
    if args.base:
        variants["base "] = {"PYTHONPATH": str(Path(args.base).resolve())}
    commands: dict[str, tuple[list[str], dict[str, str]]] = {
        "python -c pass": ([py, "-c", "pass"], dict(os.environ)),
        # the floor of any command that reads the catalogue through SQLAlchemy
        "python -c 'import sqlalchemy'": ([py, "-c", "import sqlalchemy"], dict(os.environ)),
    }
    for label, extra in variants.items():
        env = dict(os.environ, **extra)
        env["TILEKIT_CATALOGUE"] = f"sqlite:///{tmp / (label.strip() or 'this')}.sqlite"
        env.pop("TILEKIT_PLUGINS", None)
        subprocess.run([py, "-c", cli, "list", "--count"], env=env, check=True, stdout=subprocess.DEVNULL)  # seed
        commands[f"{label}tilekit --help"] = ([py, "-c", cli, "--help"], env)
        commands[f"{label}tilekit list --where polygons=6"] = ([py, "-c", cli, "list", "--where", "polygons=6"], env)
        commands[f"{label}tilekit list --family polyomino --where cells=8 --count"] = (
            [py, "-c", cli, "list", "--family", "polyomino", "--where", "cells=8", "--count"], env)
        arch = ["list", "--family", "archimedean", "--where", "polygons=6", "--count"]
        commands[f"{label}tilekit {' '.join(arch)}"] = ([py, "-c", cli, *arch], env)
        # the same two lists opened through SQLAlchemy (the read path before tilekit.catalogue.reading)
        full = dict(env, TILEKIT_READ_PATH="full")
        commands[f"{label}TILEKIT_READ_PATH=full tilekit list --where polygons=6"] = (
            [py, "-c", cli, "list", "--where", "polygons=6"], full)
        commands[f"{label}TILEKIT_READ_PATH=full tilekit {' '.join(arch)}"] = ([py, "-c", cli, *arch], full)
    try:
        # the two read paths give the same output, byte for byte, before their times count
        for name, (cmd, env) in commands.items():
            if name.startswith(("TILEKIT_READ_PATH=full", "base TILEKIT_READ_PATH=full")):
                fast = name.replace("TILEKIT_READ_PATH=full ", "")
                same = [subprocess.run(c, env=e, capture_output=True, check=True).stdout
                        for c, e in (commands[fast], (cmd, env))]
                if same[0] != same[1] or not same[0]:
                    raise SystemExit(f"{name}: output differs from {fast}")
        times: dict[str, list[tuple[float, float]]] = {k: [] for k in commands}
        for cmd, env in commands.values():  # warm-up
            run(cmd, env)
        print(f"load before: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
        for _ in range(args.runs):
            for name, (cmd, env) in commands.items():
                times[name].append(run(cmd, env))
        print(f"load after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    floor = times["python -c pass"]
    print("| command | CPU s (min / median) | wall s (min / median) | CPU / `python -c pass` (min / median) |")
    print("|---|---|---|---|")
    for name, ts in times.items():
        cpu, wall = [c for c, _ in ts], [w for _, w in ts]
        ratio = [c / f for (c, _), (f, _) in zip(ts, floor)]
        print(f"| `{name}` | {min(cpu):.3f} / {statistics.median(cpu):.3f} | {min(wall):.3f} / "
              f"{statistics.median(wall):.3f} | {min(ratio):.1f} / {statistics.median(ratio):.1f} |")


if __name__ == "__main__":
    main()
