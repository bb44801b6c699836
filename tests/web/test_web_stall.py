"""Renders that cannot stall the server (issue 30): worker processes with a wall-clock budget
and an admission limit, a byte-bounded cache, and uvicorn's limits against slow clients."""

from __future__ import annotations

import concurrent.futures
import gzip
import json
import os
import socket
import threading
import time

import httpx
import pytest
from cliutil import serving

from tilekit.web.cache import ByteLRU
from tilekit.web.executor import Busy, RenderPool, RenderTimeout, WorkerError

#: Kari's 14 tiles (Discrete Math. 160, 1996): aperiodic, no scanline or random-access fill, so
#: a 100 x 100 patch (10,000 tiles, inside the 20,000-tile limit) goes to the SAT solver.
KARI = {"region": "0,0,100,100", "size": 400}


def served(app, **config):
    """``app`` under uvicorn as ``tilekit serve`` configures it, on a free loopback port."""
    from tilekit.web.server import uvicorn_config

    return serving(app, lambda app, **where: uvicorn_config(app, **where, **config))


def _url(cat) -> str:
    return cat.engine.url.render_as_string(hide_password=False)


# --------------------------------------------------------------------------- the pool itself


def test_pool_budget_kills_the_worker_and_errors_keep_it(web_catalogue):
    pool = RenderPool(_url(web_catalogue), 20_000, workers=1, queue_size=0, seconds=1.5)
    try:
        pid = pool.call(os.getpid)
        assert pid != os.getpid() and pool.call(os.getpid) == pid  # one worker, reused
        with pytest.raises(WorkerError) as info:
            pool.call(int, "x")  # an error in the worker is the request's 400; the worker lives
        assert info.value.http_status == 400 and "invalid literal" in str(info.value)
        assert pool.call(os.getpid) == pid
        t0 = time.monotonic()
        with pytest.raises(RenderTimeout, match="past the 1.5 s budget"):
            pool.call(time.sleep, 60)
        assert time.monotonic() - t0 < 3
        deadline = time.monotonic() + 5
        while _alive(pid) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not _alive(pid)  # killed: the sleep does not hold a CPU or memory past the budget
        assert _call_when_started(pool, os.getpid) != pid and pool.stats["timeouts"] == 1
    finally:
        pool.close()


@pytest.mark.slow
def test_slow_keys_share_a_lane_and_leave_a_worker_to_quick_ones(web_catalogue):
    pool = RenderPool(_url(web_catalogue), 20_000, workers=2, queue_size=4, seconds=2.0)
    try:
        pool.warm()
        _call_when_started(pool, os.getpid)
        pool.call(time.sleep, 1.2, key="kari")  # past half the budget: 'kari' is slow from now on
        gate = threading.Thread(target=pool.call, args=(time.sleep, 1.5), kwargs={"key": "kari"})
        gate.start()
        time.sleep(0.3)
        with pytest.raises(Busy, match="ran long before"):  # the slow lane (2 - 1 workers) is full
            pool.call(time.sleep, 0.1, key="kari")
        t0 = time.monotonic()
        assert pool.call(os.getpid, key="quick") != os.getpid()  # answered by a worker ...
        assert time.monotonic() - t0 < 1.0  # the other worker was free for it
        gate.join()
        assert pool.call(os.getpid, key="kari") > 0  # the lane is free again
    finally:
        pool.close()


def _call_when_started(pool, fn, *args):
    """A call once the successor of a killed worker has started (a start takes a few seconds,
    longer than this test's 1.5 s wait for a free worker)."""
    deadline = time.monotonic() + 60
    while True:
        try:
            return pool.call(fn, *args)
        except Busy:
            assert time.monotonic() < deadline


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().split(") ")[1][0] != "Z"
    except OSError:
        return False


def test_pool_admits_workers_plus_queue_then_says_busy():
    pool = RenderPool(None, 1, workers=0, queue_size=1, seconds=5)  # in-thread mode: 1 + 1 slots
    gate = threading.Event()
    with concurrent.futures.ThreadPoolExecutor(2) as ex:
        first = ex.submit(pool.call, gate.wait, 10)
        second = ex.submit(pool.call, gate.wait, 10)
        time.sleep(0.3)
        with pytest.raises(Busy) as info:
            pool.call(gate.wait, 10)
        assert info.value.retry_after >= 1 and "busy" in str(info.value)
        gate.set()
        assert first.result(5) and second.result(5)
    assert pool.call(lambda: 7) == 7 and pool.stats["busy"] == 1


def test_worker_past_its_memory_bound_is_replaced(web_catalogue):
    pool = RenderPool(_url(web_catalogue), 20_000, workers=1, queue_size=0, seconds=30, recycle_bytes=1)
    try:
        a = pool.call(os.getpid)
        b = pool.call(os.getpid)
        assert a != b and pool.stats["recycled"] >= 1
    finally:
        pool.close()


# --------------------------------------------------------------------------- the cache


def test_render_cache_is_bounded_by_bytes():
    import sys

    cache = ByteLRU(10_000)
    for i in range(100):
        cache.put(f"k{i}", "x" * 900)
        assert cache.bytes <= 10_000
    assert cache.bytes == sum(sys.getsizeof("x" * 900) for _ in range(len(cache)))
    assert cache.get("k99") is not None and cache.get("k0") is None  # least recently used went first
    assert not cache.put("big", "y" * 3000)  # over a quarter of the bound: not kept
    cache.get("k92")
    cache.put("new", "z" * 900)
    assert cache.get("k92") is not None  # a hit is recent again


def test_renderer_cache_holds_at_most_its_bytes(web_catalogue):
    from tilekit.web.service import Renderer

    r = Renderer(web_catalogue, cache_bytes=50_000)
    sizes = []
    for size in range(100, 400, 20):
        _, svg, _ = r.render("3.4.6.4", {"size": size, "region": "-6,-6,6,6"})
        sizes.append(len(svg))
        assert r.cache.bytes <= 50_000
    assert sum(sizes) > 50_000 >= r.cache.bytes > 30_000  # it dropped some, kept others


# --------------------------------------------------------------------------- a real server


@pytest.fixture(scope="module")
def stall_app(web_catalogue):
    from tilekit.web import create_app

    return create_app(catalogue=web_catalogue, render_workers=1, render_queue=0, render_seconds=2.0,
                      bind_host="127.0.0.1")


def _worker_started(http) -> None:
    deadline = time.monotonic() + 60
    while not http.get("/health").json()["renders"]["worker_rss_mb"]:
        assert time.monotonic() < deadline, "the render worker did not start"
        time.sleep(0.1)


@pytest.mark.slow
def test_health_answers_while_solver_renders_fill_every_slot(stall_app):
    """Six concurrent 100 x 100 Kari renders on one worker with no queue: one runs and is
    stopped at the 2 s budget (504, not a 400 after a minute), five are refused at once (503
    with Retry-After); /health answers in under 1 s throughout. The full 42-render case is
    tests/web/test_web_load.py and benchmarks/bench_web_load.py."""
    with served(stall_app) as url, httpx.Client(base_url=url, timeout=60) as http:
        _worker_started(http)
        with concurrent.futures.ThreadPoolExecutor(6) as ex:
            futures = [ex.submit(http.get, "/api/render/kari-14", params={**KARI, "seed": i}) for i in range(6)]
            waits = []
            while not all(f.done() for f in futures):
                t0 = time.monotonic()
                assert http.get("/health").status_code == 200
                waits.append(time.monotonic() - t0)
                time.sleep(0.1)
            answers = [f.result() for f in futures]
        codes = sorted(r.status_code for r in answers)
        assert codes == [503] * 5 + [504], codes
        timed_out = next(r for r in answers if r.status_code == 504)
        assert "past the 2 s budget" in timed_out.json()["error"]
        assert all(int(r.headers["retry-after"]) >= 1 for r in answers if r.status_code == 503)
        assert len(waits) >= 5 and max(waits) < 1.0, waits
        # the killed worker's successor takes the next render: a small one of the same set answers
        # (method=solver: 'auto' first spends up to 10 s in a fresh process looking for a torus unit)
        _worker_started(http)
        r = http.get("/api/render/kari-14", params={"region": "0,0,6,6", "size": 120, "set": "method=solver"})
        assert r.status_code == 200 and r.text.startswith("<svg")


def test_slow_clients_are_cut_off_and_svgs_go_out_gzipped(web_catalogue):
    from tilekit.web import create_app

    app = create_app(catalogue=web_catalogue, bind_host="127.0.0.1")
    with served(app, head_seconds=1.0, keep_alive=1) as url:
        port = int(url.rsplit(":", 1)[1])
        # a header line every 0.3 s never completes a head: closed after about a second
        with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
            s.sendall(b"GET /health HTTP/1.1\r\nHost: 127.0.0.1\r\n")
            t0 = time.monotonic()
            closed = False
            while time.monotonic() - t0 < 4:
                try:
                    s.sendall(b"X-Slow: 1\r\n")
                    s.settimeout(0.3)
                    if s.recv(100) == b"":
                        closed = True
                        break
                except TimeoutError:
                    continue
                except OSError:
                    closed = True
                    break
            assert closed and time.monotonic() - t0 < 2.5
        # a connection that never sends a byte is closed too
        with socket.create_connection(("127.0.0.1", port), timeout=4) as s:
            t0 = time.monotonic()
            assert s.recv(100) == b"" and time.monotonic() - t0 < 2.5
        # a 1 MB query string (over httpx's own URL limit, so by hand): the app's JSON 414,
        # not h11's plain-text 400 and a reset
        with socket.create_connection(("127.0.0.1", port), timeout=10) as s:
            s.sendall(b"GET /api/query?where=" + b"a" * 1_000_000 + b" HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                      b"Connection: close\r\n\r\n")
            answer = b""
            while chunk := s.recv(65536):
                answer += chunk
        head, _, body = answer.partition(b"\r\n\r\n")
        assert head.startswith(b"HTTP/1.1 414 ") and b"content-type: application/json" in head.lower()
        assert json.loads(body) == {"error": "query string over 8192 bytes", "status": 414}
        with httpx.Client(base_url=url, timeout=10) as http:
            r = http.get("/api/render/3.4.6.4", params={"size": 800, "region": "-12,-12,12,12"},
                         headers={"accept-encoding": "gzip"})
            assert r.status_code == 200 and r.headers["content-encoding"] == "gzip"
            assert r.text.startswith("<svg")  # httpx decompressed it
            raw = int(r.headers["content-length"])
            assert raw * 3 < len(r.content), (raw, len(r.content))
            assert gzip.decompress(gzip.compress(r.content)) == r.content
            assert http.get("/health", headers={"host": "evil.example"}).status_code == 421
