"""Thumbnail load test of ``tilekit serve`` on loopback: 200 catalogue entries, p50/p95.

Run: python benchmarks/bench_web.py [--count 200] [--cap 30] [--concurrency 4]

A fresh SQLite catalogue gets the shipped tilings (136) plus isohedral tilings with nudged
parameters (what a search would store) up to --count entries; ``tilekit serve`` runs in a
subprocess on 127.0.0.1 (a free port) and httpx fetches /thumb/NAME.svg for every entry:
once cold (rendered by tilekit), once warm (served from the spec-hash cache), then warm
again from --concurrency client threads. Each pass stops at --cap seconds (the figures say
how many requests finished). Prints a Markdown table for docs/benchmarks.md.
"""

from __future__ import annotations

import argparse
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import httpx

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def make_catalogue(path: Path, count: int) -> None:
    from tilekit import open_catalogue
    from tilekit.errors import TilekitError
    from tilekit.plugins import CatalogueRecord
    from tilekit.plugins.isohedral.engine import IsohedralTiling

    cat = open_catalogue(str(path))
    extra = []
    for factor in (1.05, 0.95, 1.1, 0.9):
        for ih in range(1, 94):
            if cat.count() + len(extra) >= count:
                break
            try:
                t = IsohedralTiling(ih)
                if not t.params:
                    continue
                params = [p * factor for p in t.params]
                IsohedralTiling(ih, params)
            except TilekitError:
                continue
            extra.append(CatalogueRecord("isohedral", f"{t.name}-x{factor:g}", {"ih": ih, "params": params},
                                         f"{t.name} with parameters x{factor:g}", {"ih": ih, "bench": True}))
    cat.upsert(extra)
    cat.close()


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def percentile(xs: list[float], q: float) -> float:
    xs = sorted(xs)
    return xs[min(len(xs) - 1, max(0, round(q * (len(xs) - 1))))]


def one_pass(client: httpx.Client, names: list[str], cap: float, workers: int = 1) -> tuple[list[float], float, int]:
    times: list[float] = []
    bad = 0
    start = time.perf_counter()

    def fetch(name: str) -> tuple[float, int]:
        if time.perf_counter() - start > cap:
            return -1.0, 0
        t0 = time.perf_counter()
        r = client.get(f"/thumb/{name}.svg")
        return time.perf_counter() - t0, r.status_code

    if workers == 1:
        results = [fetch(n) for n in names]
    else:
        with ThreadPoolExecutor(workers) as pool:
            results = list(pool.map(fetch, names))
    for dt, status in results:
        if dt < 0:
            continue
        times.append(dt)
        if status != 200:
            bad += 1
    return times, time.perf_counter() - start, bad


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--cap", type=float, default=30.0, help="seconds per pass at most")
    ap.add_argument("--concurrency", type=int, default=4)
    return ap


def main() -> None:
    args = build_parser().parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        db = Path(tmp) / "bench.sqlite"
        make_catalogue(db, args.count)
        port = free_port()
        exe = [sys.executable, "-c", "from tilekit.cli import main; main()"]
        proc = subprocess.Popen(exe + ["--catalogue", str(db), "serve", "--port", str(port)],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env={**os.environ})
        try:
            base = f"http://127.0.0.1:{port}"
            with httpx.Client(base_url=base, timeout=30) as client:
                deadline = time.monotonic() + 60
                while True:
                    try:
                        client.get("/api/families")
                        break
                    except httpx.TransportError:
                        if time.monotonic() > deadline or proc.poll() is not None:
                            raise SystemExit("server did not start") from None
                        time.sleep(0.2)
                names = [i["name"] for i in client.get("/api/query", params={"limit": 200}).json()["items"]]
                names = names[: args.count]
                rows = []
                for label, workers in (("cold (rendered)", 1), ("warm (cached)", 1),
                                       (f"warm, {args.concurrency} clients", args.concurrency)):
                    times, wall, bad = one_pass(client, names, args.cap, workers)
                    rows.append((label, len(times), bad, wall, statistics.median(times), percentile(times, 0.95),
                                 max(times)))
        finally:
            proc.terminate()
            proc.wait(10)
    load = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    print(f"{len(names)} entries, cap {args.cap:g} s per pass; uptime: {load}\n")
    print("| pass | requests | non-200 | wall s | p50 ms | p95 ms | max ms |")
    print("|---|---|---|---|---|---|---|")
    for label, n, bad, wall, p50, p95, mx in rows:
        print(f"| {label} | {n} | {bad} | {wall:.2f} | {1000 * p50:.1f} | {1000 * p95:.1f} | {1000 * mx:.1f} |")


if __name__ == "__main__":
    main()
