"""Load, stall and memory test of ``tilekit serve`` on loopback (issue 30; docs/benchmarks.md).

Run: python benchmarks/bench_web_load.py [--clients 16] [--requests 2000] [--render-seconds 20]
         [--wang 42] [--memory 150] [--render-workers N] [--catalogue PATH]

``tilekit serve`` runs in a subprocess (its default render pool: --render-workers, a
--render-queue of 8, the given --render-seconds budget) over a fresh SQLite catalogue (or
--catalogue). Three parts, each printing a Markdown table:

1. load: --clients threads send --requests requests, a fixed mix of cached pages (thumbnails
   and tiling pages fetched once before), uncached renders (a size never asked before),
   solver renders (Kari's 14 Wang tiles on 100 x 100, which no budget here lets finish) and
   renders over the tile limit. Every answer must be 200, 413, 503 or 504 (no reset, no 500);
   p50/p95 per kind, the server's resident memory (parent and workers, /proc) at its peak;
2. stall: --wang concurrent 100 x 100 Kari renders while /health is asked every 0.1 s: the
   slowest health answer;
3. memory: --memory distinct renders near the 20,000-tile limit, one after another; the
   server's resident memory before, at its peak and after (the workers are recycled past
   --worker-mb, the cache is bounded by --cache-mb).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import random
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections import Counter, defaultdict
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import httpx

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

CACHED = ["/thumb/3.4.6.4.svg", "/thumb/4^4.svg", "/thumb/IH16.svg", "/thumb/penrose-p3.svg",
          "/thumb/3^6.svg", "/thumb/4.8.8.svg", "/tiling/IH41", "/tiling/4.6.12", "/api/families",
          "/api/query?family=archimedean"]
KARI = {"region": "0,0,100,100", "size": 400}
#: Allowed answers: 200, 413 (over the tile limit), 503 (busy), 504 (past the budget).
ALLOWED = {200, 413, 503, 504}


def rss_tree(pid: int) -> tuple[float, float]:
    """(parent MiB, workers MiB) of the server process and its children, from /proc."""
    from tilekit.web.executor import resident_bytes

    kids = []
    with contextlib.suppress(OSError):
        for task in os.listdir(f"/proc/{pid}/task"):
            with open(f"/proc/{pid}/task/{task}/children") as fh:
                kids += [int(k) for k in fh.read().split()]
    return resident_bytes(pid) / 2**20, sum(resident_bytes(k) for k in kids) / 2**20


@contextlib.contextmanager
def serve(catalogue: str, *options: str):
    """``tilekit serve`` on a free loopback port; yields (url, process)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    proc = subprocess.Popen([sys.executable, "-m", "tilekit", "--catalogue", catalogue, "serve", "--port", str(port),
                             *options], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    url = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 300
        while True:
            try:
                health = httpx.get(url + "/health", timeout=5).json()
                pool = health.get("renders") or {}
                if len(pool.get("worker_rss_mb", [])) >= pool.get("workers", 0):  # the workers are up
                    break
            except httpx.TransportError:
                pass
            if proc.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"tilekit serve did not start: {proc.stderr.read()[-2000:] if proc.stderr else ''}")
            time.sleep(0.2)
        yield url, proc
    finally:
        proc.terminate()
        try:
            proc.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()  # not communicate(): a render worker outliving the server may hold its stderr


def _pct(values: list[float], q: float) -> float:
    if not values:
        return float("nan")
    values = sorted(values)
    return values[min(len(values) - 1, int(round(q * (len(values) - 1))))]


class Sampler:
    """The server's memory every 0.2 s while a part runs (its peak)."""

    def __init__(self, pid: int) -> None:
        self.pid = pid
        self.peak = (0.0, 0.0, 0.0)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self._stop.is_set():
            parent, workers = rss_tree(self.pid)
            if parent + workers > self.peak[2]:
                self.peak = (parent, workers, parent + workers)
            self._stop.wait(0.2)

    def __enter__(self) -> Sampler:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()


def plan(requests: int, seed: int = 1) -> list[tuple[str, str, dict]]:
    """(kind, path, params) for each request: 70% cached, 20% uncached, 5% solver, 5% oversize."""
    rng = random.Random(seed)
    sizes = iter(rng.sample(range(120, 2000), 1880))
    out = []
    for i in range(requests):
        x = rng.random()
        if x < 0.70:
            out.append(("cached", rng.choice(CACHED), {}))
        elif x < 0.90:
            out.append(("uncached", "/api/render/3.4.6.4", {"size": next(sizes), "region": "-10,-10,10,10"}))
        elif x < 0.95:
            out.append(("solver", "/api/render/kari-14", {**KARI, "seed": i}))
        else:
            out.append(("oversize", "/api/render/penrose-p3", {"depth": 14}))
    return out


def load(url: str, pid: int, clients: int, requests: int) -> dict:
    """Part 1: the mix of :func:`plan` from ``clients`` threads."""
    with httpx.Client(base_url=url, timeout=120) as http:
        for path in CACHED:  # what "cached" means: asked once before (a first build on a
            for _ in range(5):  # loaded machine may run past the budget: ask again)
                r = http.get(path)
                if r.status_code == 200:
                    break
            assert r.status_code == 200, (path, r.status_code, r.text[:300])
    jobs = plan(requests)
    times: dict[str, list[float]] = defaultdict(list)
    codes: dict[str, Counter] = defaultdict(Counter)
    errors: list[str] = []
    local = threading.local()

    def one(job: tuple[str, str, dict]) -> None:
        kind, path, params = job
        if not hasattr(local, "http"):
            local.http = httpx.Client(base_url=url, timeout=120, headers={"accept-encoding": "gzip"})
        t0 = time.perf_counter()
        try:
            r = local.http.get(path, params=params)
        except httpx.HTTPError as exc:
            errors.append(f"{kind} {path}: {type(exc).__name__}")
            return
        times[kind].append(time.perf_counter() - t0)
        codes[kind][r.status_code] += 1

    t0 = time.perf_counter()
    with Sampler(pid) as mem, ThreadPoolExecutor(clients) as ex:
        list(ex.map(one, jobs))
    wall = time.perf_counter() - t0
    return {"wall": wall, "times": dict(times), "codes": {k: dict(v) for k, v in codes.items()}, "errors": errors,
            "peak": mem.peak, "after": rss_tree(pid)}


def stall(url: str, pid: int, renders: int) -> dict:
    """Part 2: ``renders`` concurrent Kari renders, /health every 0.1 s meanwhile."""
    waits: list[float] = []
    with httpx.Client(base_url=url, timeout=120) as http, Sampler(pid) as mem, ThreadPoolExecutor(renders) as ex:
        t0 = time.perf_counter()
        futures = [ex.submit(http.get, "/api/render/kari-14", params={**KARI, "seed": 1000 + i})
                   for i in range(renders)]
        while not all(f.done() for f in futures):
            h0 = time.perf_counter()
            assert http.get("/health").status_code == 200
            waits.append(time.perf_counter() - h0)
            time.sleep(0.1)
        codes = Counter(f.result().status_code for f in futures)
        wall = time.perf_counter() - t0
    return {"wall": wall, "codes": dict(codes), "health_max": max(waits), "health_p50": _pct(waits, 0.5),
            "health_n": len(waits), "peak": mem.peak, "after": rss_tree(pid)}


def memory(url: str, pid: int, count: int) -> dict:
    """Part 3: ``count`` distinct renders near the 20,000-tile limit (the 4^4 square grid on a
    138 x 138 region: 19,881 squares, each a new size so none is a cache hit)."""
    before = rss_tree(pid)
    codes: Counter = Counter()
    with httpx.Client(base_url=url, timeout=300) as http, Sampler(pid) as mem:
        t0 = time.perf_counter()
        for i in range(count):
            r = http.get("/api/render/4^4", params={"region": "0,0,138,138", "size": 1990 - i})
            codes[r.status_code] += 1
        wall = time.perf_counter() - t0
        health = http.get("/health").json()
    time.sleep(1.0)
    return {"wall": wall, "codes": dict(codes), "before": before, "peak": mem.peak, "after": rss_tree(pid),
            "cache": health.get("cache"), "renders": health.get("renders")}


def _mb(pair: tuple[float, ...]) -> str:
    return f"{pair[0]:,.0f} + {pair[1]:,.0f} MiB"


def build_parser() -> argparse.ArgumentParser:
    """The command's options (the docs' runner checks documented invocations against them)."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--clients", type=int, default=16)
    ap.add_argument("--requests", type=int, default=2000)
    ap.add_argument("--render-seconds", type=float, default=20.0)
    ap.add_argument("--wang", type=int, default=42)
    ap.add_argument("--memory", type=int, default=150)
    ap.add_argument("--render-workers", type=int, default=None,
                    help="tilekit serve's --render-workers (0: the in-thread renders of the app before issue 30)")
    ap.add_argument("--catalogue", help="an existing catalogue (default: a fresh SQLite file)")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        catalogue = args.catalogue or str(Path(tmp) / "load.sqlite")
        if not args.catalogue:
            from tilekit import open_catalogue

            open_catalogue(catalogue).close()  # migrated and seeded before the server starts
        options = ["--render-seconds", str(args.render_seconds)]
        if args.render_workers is not None:
            options += ["--render-workers", str(args.render_workers)]
        with serve(catalogue, *options) as (url, proc):
            print(f"tilekit serve {' '.join(options)}")
            print(f"uptime: {os.popen('uptime').read().strip()}")
            if args.requests:
                out = load(url, proc.pid, args.clients, args.requests)
                print(f"\n### load: {args.clients} clients, {args.requests} requests, {out['wall']:.1f} s\n")
                print("| kind | requests | statuses | p50 ms | p95 ms | max ms |\n|---|---|---|---|---|---|")
                for kind in ("cached", "uncached", "solver", "oversize"):
                    t = out["times"].get(kind, [])
                    print(f"| {kind} | {len(t)} | {out['codes'].get(kind, {})} | {_pct(t, .5) * 1e3:.0f} | "
                          f"{_pct(t, .95) * 1e3:.0f} | {max(t, default=float('nan')) * 1e3:.0f} |")
                bad = {k: c for k, v in out["codes"].items() for c in v if c not in ALLOWED}
                print(f"\nunanswered: {len(out['errors'])} {out['errors'][:5]}; other statuses: {bad or 'none'}")
                print(f"server memory (parent + workers): peak {_mb(out['peak'])}, after {_mb(out['after'])}")
            if args.wang:
                out = stall(url, proc.pid, args.wang)
                print(f"\n### stall: {args.wang} concurrent 100 x 100 kari-14 renders, {out['wall']:.1f} s\n")
                print(f"statuses {out['codes']}; /health asked {out['health_n']} times: median "
                      f"{out['health_p50'] * 1e3:.0f} ms, slowest {out['health_max'] * 1e3:.0f} ms; "
                      f"memory peak {_mb(out['peak'])}, after {_mb(out['after'])}")
            if args.memory:
                out = memory(url, proc.pid, args.memory)
                print(f"\n### memory: {args.memory} distinct 4^4 renders of 19,881 tiles, {out['wall']:.1f} s\n")
                print(f"statuses {out['codes']}; server memory before {_mb(out['before'])}, peak {_mb(out['peak'])}, "
                      f"after {_mb(out['after'])}; cache {out['cache']}; pool {out['renders']}")
            print(f"\nuptime: {os.popen('uptime').read().strip()}")


if __name__ == "__main__":
    main()
