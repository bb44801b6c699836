"""The bounded load test of issue 30 against a real ``tilekit serve`` (benchmarks/bench_web_load.py):
16 clients, 2,000 requests mixing cached pages, uncached, solver and oversize renders; then 42
concurrent 100 x 100 Kari renders while /health is asked."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
#: The memory bound docs/web.md states for the default pool: the parent (catalogue, 128 MiB
#: cache, answers in flight) plus two workers recycled past 768 MiB, each with one render on top.
MEMORY_BOUND_MB = 2048


def _bench():
    spec = importlib.util.spec_from_file_location("bench_web_load", ROOT / "benchmarks" / "bench_web_load.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.slow
def test_load_mix_and_wang_stall(web_catalogue):
    bench = _bench()
    with bench.serve(str(web_catalogue.path), "--render-seconds", "20", "--render-workers", "2") as (url, proc):
        out = bench.load(url, proc.pid, clients=16, requests=2000)
        assert out["errors"] == []  # every request answered: no reset, no timeout
        answered = sum(sum(c.values()) for c in out["codes"].values())
        assert answered == 2000
        for kind, codes in out["codes"].items():
            assert set(codes) <= bench.ALLOWED, (kind, codes)
        assert out["codes"]["cached"] == {200: len(out["times"]["cached"])}
        assert bench._pct(out["times"]["cached"], 0.95) < 0.3, sorted(out["times"]["cached"])[-20:]
        assert set(out["codes"]["oversize"]) == {413}
        assert 200 in out["codes"]["uncached"]
        assert sum(out["peak"][:2]) < MEMORY_BOUND_MB, out["peak"]

        stall = bench.stall(url, proc.pid, 42)
        assert set(stall["codes"]) <= {503, 504} and sum(stall["codes"].values()) == 42, stall["codes"]
        assert stall["health_max"] < 1.0, stall
        assert sum(stall["peak"][:2]) < MEMORY_BOUND_MB, stall["peak"]
