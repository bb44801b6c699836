"""The run layer: chunk overhead, result rows written per second (SQLite and PostgreSQL)
against a plain SQLAlchemy bulk insert of the same rows, a 10^6-row streamed export against a
plain sqlite3 + csv peer, and the speed-up of two workers on CPU-bound chunks.

Run: python benchmarks/bench_runs.py [--postgres URL] [--rows 1000000] [--repeat 5]
(prints Markdown tables for docs/benchmarks.md; the export figures are whole processes under
/usr/bin/time -v, so peak memory is the process's maximum resident set size).
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import sqlalchemy as sa

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import tilekit  # noqa: E402
from tilekit.catalogue import open_catalogue  # noqa: E402
from tilekit.plugins import ChunkResult, ResultTable, Search, SearchParam, make_plugin_manager  # noqa: E402
from tilekit.search import run_search  # noqa: E402

METADATA = sa.MetaData()
ROWS = sa.Table(
    "bench_rows", METADATA,
    sa.Column("code", sa.String(40), primary_key=True),
    sa.Column("cells", sa.Integer, index=True),
    sa.Column("holes", sa.Boolean),
    sa.Column("symmetry", sa.String(8)),
    sa.Column("weight", sa.Float),
    sa.Column("run_id", sa.Integer),
)
SYMS = ("C1", "C2", "C4", "D1", "D2", "D4")


def make_rows(chunk: int, per_chunk: int) -> list[dict]:
    base = chunk * per_chunk
    return [{"code": f"r{base + i:09d}", "cells": (base + i) % 17, "holes": (base + i) % 7 == 0,
             "symmetry": SYMS[(base + i) % 6], "weight": (base + i) * 0.5} for i in range(per_chunk)]


def rows_chunks(params):
    return ({"i": i} for i in range(params["chunks"]))


def rows_run_chunk(params, chunk):
    return ChunkResult(rows={"bench_rows": make_rows(int(chunk["i"]), params["per_chunk"])},
                       counts={"rows": params["per_chunk"]})


def spin_run_chunk(params, chunk):
    """CPU-bound: about ``work`` seconds of pure-Python arithmetic."""
    end = time.process_time() + params["work"]
    x = 0
    while time.process_time() < end:
        for k in range(2000):
            x += k * k
    return ChunkResult(counts={"spins": 1})


class BenchPlugin:
    @tilekit.hookimpl
    def tilekit_searches(self):
        return [
            Search("bench-rows", "rows into a result table", "bench", [
                SearchParam("chunks", int, 10, min=1), SearchParam("per_chunk", int, 1000, min=0)],
                rows_chunks, rows_run_chunk),
            Search("bench-spin", "CPU-bound chunks", "bench", [
                SearchParam("chunks", int, 10, min=1), SearchParam("work", float, 0.1, min=0.0)],
                rows_chunks, spin_run_chunk),
        ]

    @tilekit.hookimpl
    def tilekit_result_tables(self):
        return [ResultTable(ROWS, key=("code",), family="bench", name_column="code")]


def pm():
    os.environ["TILEKIT_PLUGINS"] = "none"
    try:
        return make_plugin_manager([BenchPlugin()])
    finally:
        del os.environ["TILEKIT_PLUGINS"]


def fresh(url_factory):
    url = url_factory()
    cat = open_catalogue(url, pm=pm())
    METADATA.create_all(cat.engine)  # the benchmark's table (a plugin would ship a migration)
    return url, cat


def med(xs):
    return statistics.median(xs), min(xs)


def bench_overhead(url_factory, repeat):
    out = []
    for _ in range(repeat):
        url, cat = fresh(url_factory)
        t = time.perf_counter()
        run_search(cat, "bench-rows", {"chunks": 400, "per_chunk": 0}, pm=cat.pm)
        out.append((time.perf_counter() - t) / 400 * 1000)
        cat.close()
    return med(out)


def bench_rows(url_factory, repeat, total=200_000, per_chunk=5000):
    ours, peer = [], []
    for _ in range(repeat):
        url, cat = fresh(url_factory)
        t = time.perf_counter()
        run_search(cat, "bench-rows", {"chunks": total // per_chunk, "per_chunk": per_chunk}, pm=cat.pm)
        ours.append(total / (time.perf_counter() - t))
        with cat.engine.connect() as conn:
            assert conn.execute(sa.select(sa.func.count()).select_from(ROWS)).scalar_one() == total
        # the peer: the same rows, the same upsert by key (so a repeated chunk doubles nothing),
        # one executemany per chunk in a transaction each, written with plain SQLAlchemy Core
        with cat.engine.begin() as conn:
            conn.execute(ROWS.delete())
        if cat.engine.dialect.name == "postgresql":
            from sqlalchemy.dialects.postgresql import insert
        else:
            from sqlalchemy.dialects.sqlite import insert
        ins = insert(ROWS)
        upsert = ins.on_conflict_do_update(index_elements=["code"],
                                           set_={c: ins.excluded[c] for c in ("cells", "holes", "symmetry", "weight")})
        t = time.perf_counter()
        for i in range(total // per_chunk):
            with cat.engine.begin() as conn:
                conn.execute(upsert, make_rows(i, per_chunk))
        peer.append(total / (time.perf_counter() - t))
        cat.close()
    return med(ours), med(peer)


def timed_process(cmd, env=None):
    res = subprocess.run(["/usr/bin/time", "-v", *cmd], capture_output=True, text=True, env=env)
    if res.returncode != 0:
        raise SystemExit(res.stderr[-2000:])
    wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", res.stderr)
    h, m, s = wall.groups()
    seconds = int(h or 0) * 3600 + int(m) * 60 + float(s)
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", res.stderr).group(1))
    return seconds, rss / 1024


PEER_EXPORT = """
import csv, sqlite3, sys
conn = sqlite3.connect(sys.argv[1])
with open(sys.argv[2], "w", newline="") as fh:
    w = csv.writer(fh)
    cur = conn.execute("SELECT * FROM bench_rows ORDER BY code")
    w.writerow([d[0] for d in cur.description])
    for row in cur:
        w.writerow(row)
"""

OUR_EXPORT = """
import os, sys
sys.path.insert(0, {root!r})
sys.path.insert(0, {bench!r})
import bench_runs
from tilekit.catalogue import open_catalogue
cat = open_catalogue(sys.argv[1], pm=bench_runs.pm(), seed=False)
print(cat.export(sys.argv[2], sys.argv[3], family="bench"))
"""


def bench_export(n_rows, repeat):
    tmp = Path(tempfile.mkdtemp())
    url, cat = fresh(lambda: f"sqlite:///{tmp / 'export.sqlite'}")
    per = 50_000
    with cat.engine.begin() as conn:
        for i in range(n_rows // per):
            conn.execute(ROWS.insert(), make_rows(i, per))
    cat.close()
    root = str(Path(__file__).resolve().parents[1])
    ours_py = OUR_EXPORT.format(root=root, bench=str(Path(__file__).resolve().parent))
    results = {}
    for fmt in ("csv", "jsonl"):
        runs = [timed_process([sys.executable, "-c", ours_py, url, str(tmp / f"out.{fmt}"), fmt]) for _ in range(repeat)]
        results[f"tilekit {fmt}"] = (statistics.median(r[0] for r in runs), min(r[0] for r in runs),
                                     statistics.median(r[1] for r in runs))
    runs = [timed_process([sys.executable, "-c", PEER_EXPORT, str(tmp / "export.sqlite"), str(tmp / "peer.csv")])
            for _ in range(repeat)]
    results["sqlite3 + csv peer"] = (statistics.median(r[0] for r in runs), min(r[0] for r in runs),
                                     statistics.median(r[1] for r in runs))
    lines = (tmp / "out.csv").read_text().count("\n")
    assert lines == n_rows + 1, lines
    assert (tmp / "peer.csv").read_text().count("\n") == n_rows + 1
    return results


def bench_workers(repeat, chunks=16, work=0.25):
    tmp = Path(tempfile.mkdtemp())
    out = {}
    for label, executor, workers in (("1 worker (local)", "local", None), ("2 workers (process)", "process", 2)):
        times = []
        for r in range(repeat):
            url, cat = fresh(lambda r=r, label=label: f"sqlite:///{tmp / f'{label[0]}-{r}.sqlite'}")
            t = time.perf_counter()
            run_search(cat, "bench-spin", {"chunks": chunks, "work": work}, executor=executor, workers=workers,
                       pm=cat.pm)
            times.append(time.perf_counter() - t)
            cat.close()
        out[label] = med(times)
    return out


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--postgres", default=os.environ.get("TILEKIT_TEST_POSTGRES"))
    ap.add_argument("--rows", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    return ap


def main() -> None:
    args = build_parser().parse_args()
    tmp = Path(tempfile.mkdtemp())
    counter = iter(range(10_000))
    backends = {"SQLite": lambda: f"sqlite:///{tmp / f'c{next(counter)}.sqlite'}"}
    if args.postgres:
        admin = sa.create_engine(args.postgres, isolation_level="AUTOCOMMIT")

        def pg_url():
            name = f"tilekit_bench_{next(counter)}_{os.getpid()}"
            with admin.connect() as conn:
                conn.execute(sa.text(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)'))
                conn.execute(sa.text(f'CREATE DATABASE "{name}"'))
            return sa.engine.make_url(args.postgres).set(database=name).render_as_string(hide_password=False)

        backends["PostgreSQL"] = pg_url
    print(f"load: {os.getloadavg()}")
    print("\n| backend | chunk overhead, ms/chunk (median, min) | tilekit rows/s (median, min) | plain upsert rows/s | ratio |")
    print("|---|---|---|---|---|")
    for name, factory in backends.items():
        over = bench_overhead(factory, args.repeat)
        ours, peer = bench_rows(factory, args.repeat)
        print(f"| {name} | {over[0]:.2f}, {over[1]:.2f} | {ours[0]:,.0f}, {ours[1]:,.0f} | {peer[0]:,.0f}, {peer[1]:,.0f} "
              f"| {ours[0] / peer[0]:.2f} |")
    print(f"\n| export of {args.rows:,} rows | wall s (median, min) | peak RSS MiB |")
    print("|---|---|---|")
    for label, (m, lo, rss) in bench_export(args.rows, max(1, args.repeat // 2)).items():
        print(f"| {label} | {m:.1f}, {lo:.1f} | {rss:.0f} |")
    print("\n| 16 CPU-bound chunks of 0.25 s | wall s (median, min) |")
    print("|---|---|")
    for label, (m, lo) in bench_workers(max(1, args.repeat // 2)).items():
        print(f"| {label} | {m:.2f}, {lo:.2f} |")
    print(f"\nload after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
