"""The run layer under real processes: leases shared by several workers, SIGKILL and resume,
Ctrl-C and SIGTERM, orphans, cancel and delete — on SQLite and on PostgreSQL.

The processes run ``tests/data/ticks.py``: the ``tilekit`` command line with the ``ticks``
test search (chunk i yields {"i": i, "square": i*i} and logs "i pid" to $TICKS_LOG, so every
computation is counted across processes).
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tilekit.catalogue import open_catalogue
from tilekit.catalogue.runs import HOST, pid_alive

TICKS = Path(__file__).parent / "data" / "ticks.py"


def start(url: str, *args: str, log: Path | None = None, lease: str = "3") -> subprocess.Popen:
    env = {**os.environ, "TILEKIT_LEASE_SECONDS": lease, "TILEKIT_PLUGINS": "archimedean"}
    if log is not None:
        env["TICKS_LOG"] = str(log)
    return subprocess.Popen([sys.executable, str(TICKS), "--catalogue", url, *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)


def reader(url: str):
    return open_catalogue(url, seed=False, migrate=False)


def wait_for(predicate, timeout: float = 60.0, step: float = 0.05):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(step)
    raise AssertionError("condition not reached in time")


def run_exists(url: str, run_id: int = 1):
    def check():
        try:
            with reader(url) as cat:
                return any(r.id == run_id for r in cat.runs())
        except Exception:
            return False
    return check


def chunks_done(url: str, run_id: int = 1) -> int:
    with reader(url) as cat:
        return cat.run(run_id).chunks_done


def worker_pids(url: str, run_id: int = 1) -> set[int]:
    import sqlalchemy as sa

    from tilekit.catalogue.tables import WORKERS

    with reader(url) as cat, cat.engine.connect() as conn:
        return {int(p) for p, h in conn.execute(
            sa.select(WORKERS.c.pid, WORKERS.c.host).where(WORKERS.c.run_id == run_id)) if h == HOST}


def expected(n: int) -> list[dict]:
    return [{"i": i, "square": i * i} for i in range(n)]


def logged(log: Path) -> list[int]:
    if not log.exists():
        return []
    return [int(line.split()[0]) for line in log.read_text().splitlines() if line.strip()]


@pytest.mark.slow
def test_sigkill_at_random_moments_then_resume_gives_exactly_the_rows(db_url, tmp_path):
    """SIGKILL a 2-worker process-pool run at random moments, four times, resuming each time;
    the finished run holds exactly the rows of an uninterrupted run (nothing lost, nothing
    doubled), reads interrupted while dead, and no pool worker outlives its parent by 5 s."""
    rng = random.Random(20261201)
    n = 48
    args = ["search", "ticks", "--chunks", str(n), "--sleep", "0.04", "--executor", "process", "--workers", "2"]
    log = tmp_path / "ticks.log"
    for attempt in range(4):
        proc = start(db_url, *(args if attempt == 0 else [*args[:2], "--resume", "1", *args[6:]]), log=log)
        wait_for(run_exists(db_url))
        time.sleep(rng.uniform(0.3, 1.2))
        proc.send_signal(signal.SIGKILL)
        proc.wait(10)
        pids = worker_pids(db_url) - {proc.pid}
        wait_for(lambda pids=pids: not any(pid_alive(p) for p in pids), timeout=5.0)  # no orphan
        with reader(db_url) as cat:
            info = cat.run(1)
            if info.chunks_done < n:  # not "running" for ever (queued: killed before it started)
                assert info.status == "interrupted" or (info.status == "queued" and info.started_at is None)
    done = start(db_url, "search", "ticks", "--resume", "1", "--executor", "process", "--workers", "2", log=log)
    out, err = done.communicate(timeout=120)
    assert done.returncode == 0, err
    with reader(db_url) as cat:
        info = cat.run(1)
        assert (info.status, info.chunks_done, info.chunks_total) == ("done", n, n)
        assert sorted(cat.results(1), key=lambda r: r["i"]) == expected(n)
        assert info.summary["ticks"] == n
        assert info.seconds > 0 and info.worker_seconds > 0
    assert set(logged(log)) == set(range(n))  # every chunk computed (a killed one again)


@pytest.mark.slow
def test_three_processes_work_one_run_and_compute_each_chunk_once(db_url, tmp_path):
    """One run, three `tilekit search` processes (the first creates it, two join with
    --resume): every chunk is computed exactly once and nobody sees 'database is locked'."""
    n = 60
    log = tmp_path / "ticks.log"
    first = start(db_url, "search", "ticks", "--chunks", str(n), "--sleep", "0.2", log=log)
    wait_for(run_exists(db_url))
    others = [start(db_url, "search", "ticks", "--resume", "1", log=log) for _ in range(2)]
    outputs = [p.communicate(timeout=120) for p in [first, *others]]
    for proc, (_out, err) in zip([first, *others], outputs):
        assert proc.returncode == 0, err
        assert "locked" not in err
    computed = logged(log)
    assert sorted(computed) == list(range(n))  # each chunk once
    assert len({line.split()[1] for line in log.read_text().splitlines()}) == 3  # all three worked
    with reader(db_url) as cat:
        info = cat.run(1)
        assert info.status == "done" and sorted(cat.results(1), key=lambda r: r["i"]) == expected(n)


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
@pytest.mark.parametrize("executor", ["local", "process"])
def test_ctrl_c_and_sigterm_keep_chunks_and_exit_cleanly(tmp_path, sig, code, executor):
    url = f"sqlite:///{tmp_path / 'c.sqlite'}"
    n = 200
    proc = start(url, "search", "ticks", "--chunks", str(n), "--sleep", "0.05",
                 "--executor", executor, "--workers", "2")
    wait_for(run_exists(url))
    wait_for(lambda: chunks_done(url) >= 3)
    sent = time.monotonic()
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=30)
    assert time.monotonic() - sent < 2.5
    assert proc.returncode == code, err
    lines = err.strip().splitlines()  # periodic progress lines "run 1: d/t chunks ...", then one error
    assert "Traceback" not in err and all(line.startswith("run 1: ") for line in lines[:-1]), err
    assert lines[-1].startswith("error: run 1 ") and "tilekit search ticks --resume 1" in lines[-1]
    with reader(url) as cat:
        info = cat.run(1)
        assert info.status == "interrupted" and 3 <= info.chunks_done < n
        assert info.chunks_leased == 0  # leases given back
        kept = info.chunks_done
        assert len(cat.results(1)) == kept
    done = start(url, "search", "ticks", "--resume", "1")
    assert done.wait(120) == 0
    with reader(url) as cat:
        assert sorted(cat.results(1), key=lambda r: r["i"]) == expected(n)


@pytest.mark.parametrize("sig, code, word", [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")])
def test_ctrl_c_while_the_catalogue_is_opening(tmp_path, sig, code, word):
    """Opening waits for another writer's lock; Ctrl-C (SIGTERM) then exits 130 (143) at once,
    one line."""
    import sqlite3

    path = tmp_path / "c.sqlite"
    # made by the same plugins as the child's (TILEKIT_PLUGINS), so that its migrations are
    # known to the child, which then waits for the lock (an unknown one is refused at once)
    made = start(f"sqlite:///{path}", "catalogue", "upgrade")
    assert made.wait(timeout=120) == 0, made.communicate()
    holder = sqlite3.connect(path, isolation_level=None)
    holder.execute("BEGIN IMMEDIATE")
    try:
        proc = start(f"sqlite:///{path}", "list", "--limit", "1")

        def opened() -> bool:  # the child has the catalogue file open: it is waiting for the lock
            try:
                return any(os.path.realpath(f"/proc/{proc.pid}/fd/{fd}") == str(path.resolve())
                           for fd in os.listdir(f"/proc/{proc.pid}/fd"))
            except OSError:
                return False

        wait_for(opened, timeout=60)
        time.sleep(0.5)
        assert proc.poll() is None  # still waiting for the lock
        sent = time.monotonic()
        proc.send_signal(sig)
        out, err = proc.communicate(timeout=10)
        assert time.monotonic() - sent < 2.0
    finally:
        holder.execute("ROLLBACK")
        holder.close()
    assert proc.returncode == code and err.strip() == f"error: {word}", err


def test_a_bad_parameter_creates_no_run(tmp_path):
    url = f"sqlite:///{tmp_path / 'c.sqlite'}"
    for args, fragment in [(["--chunks", "0"], "from 1 to 100000"), (["--sleep", "-1"], "from 0.0 to 60.0"),
                           (["--sleep", "nan"], "finite")]:
        proc = start(url, "search", "ticks", *args)
        out, err = proc.communicate(timeout=60)
        assert proc.returncode == 2 and fragment in err and len(err.strip().splitlines()) == 1, err
    with reader(url) as cat:
        assert cat.runs() == []


def test_cancel_stops_the_workers_and_delete_removes_the_run(tmp_path):
    url = f"sqlite:///{tmp_path / 'c.sqlite'}"
    proc = start(url, "search", "ticks", "--chunks", "400", "--sleep", "0.05", "--executor", "process",
                 "--workers", "2")
    wait_for(run_exists(url))
    wait_for(lambda: chunks_done(url) >= 2)
    cancelled = start(url, "runs", "cancel", "1")
    assert cancelled.wait(60) == 0
    out, err = proc.communicate(timeout=30)  # its workers stop after their current chunk
    assert proc.returncode == 0 and "run 1: ticks cancelled" in out, (out, err)
    with reader(url) as cat:
        info = cat.run(1)
        assert info.status == "cancelled" and info.chunks_done < 400 and info.workers_alive == 0
    again = start(url, "search", "ticks", "--resume", "1")
    _, err = again.communicate(timeout=60)
    assert again.returncode == 2 and "was cancelled" in err
    deleted = start(url, "runs", "delete", "1")
    out, _ = deleted.communicate(timeout=60)
    assert deleted.returncode == 0 and out.startswith("run 1 deleted")
    with reader(url) as cat:
        assert cat.runs() == []
    for args, fragment in [(["runs", "delete", "7"], "unknown run '7'"), (["runs", "cancle", "1"], "did you mean 'cancel'"),
                           (["runs", "99999999999999999999999"], "not a run number")]:
        bad = start(url, *args)
        _, err = bad.communicate(timeout=60)
        assert bad.returncode == 2 and fragment in err and len(err.strip().splitlines()) == 1, err


def test_concurrent_first_opens_of_a_new_catalogue(db_url):
    """Several processes opening (migrating and seeding) a fresh catalogue at once all
    succeed and seed it once (on PostgreSQL this failed with a duplicate key)."""
    procs = [subprocess.Popen([sys.executable, "-m", "tilekit.cli", "--catalogue", db_url, "list", "--count"],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              env={**os.environ, "TILEKIT_PLUGINS": "archimedean"}) for _ in range(4)]
    results = [p.communicate(timeout=180) for p in procs]
    for p, (out, err) in zip(procs, results):
        assert p.returncode == 0, err
        assert out.strip() == "24"  # 12 Archimedean (3^4.6 in both hands) + 12 Laves records


def _species_rows(cat) -> list[dict]:
    drop = {"run_id", "seconds"}
    return sorted(({k: v for k, v in row.items() if k not in drop} for row in cat.iter_result_rows("vertex_species")),
                  key=lambda r: r["vertex_type"])


@pytest.mark.slow
def test_dask_local_cluster_gives_the_rows_of_an_in_process_run(tmp_path, monkeypatch):
    """The same search in-process and on a 2-worker dask LocalCluster (whose workers claim
    chunks and write through leases themselves) stores the same rows and tilings."""
    pytest.importorskip("dask.distributed")
    from tilekit.search import run_search

    monkeypatch.setenv("TILEKIT_PLUGINS", "archimedean")
    from tilekit.plugins import reset_plugin_manager

    reset_plugin_manager()
    local_url = f"sqlite:///{tmp_path / 'local.sqlite'}"
    dask_url = f"sqlite:///{tmp_path / 'dask.sqlite'}"
    with open_catalogue(local_url) as local, open_catalogue(dask_url) as remote:
        a = run_search(local, "vertex-species", {})
        b = run_search(remote, "vertex-species", {}, executor="dask", workers=2)
        ia, ib = local.run(a), remote.run(b)
        assert ia.status == ib.status == "done" and ia.summary == ib.summary
        assert ia.summary["tiling_types"] == 11 and ia.summary["euclidean_species"] == 17
        rows = _species_rows(local)
        assert rows == _species_rows(remote)
        assert len(rows) + len(local.results(a)) == ia.rows  # table rows plus the JSON survivors
        assert [e.name for e in local.query(family="archimedean")] == [e.name for e in remote.query(family="archimedean")]
        import sqlalchemy as sa

        from tilekit.catalogue.tables import WORKERS

        with remote.engine.connect() as conn:  # the dask workers registered themselves
            pids = set(conn.execute(sa.select(WORKERS.c.pid).where(WORKERS.c.run_id == b)).scalars())
        assert os.getpid() not in pids and len(pids) >= 1
    reset_plugin_manager()


@pytest.mark.slow
def test_ctrl_c_with_the_dask_executor(tmp_path):
    """Ctrl-C during a dask run: exit 130, one error line and no tracebacks from the cluster,
    recorded chunks kept, the run interrupted, and no worker process of the local cluster left."""
    pytest.importorskip("dask.distributed")
    url = f"sqlite:///{tmp_path / 'c.sqlite'}"
    env = {**os.environ, "TILEKIT_PLUGINS": "archimedean", "TILEKIT_LEASE_SECONDS": "3"}
    proc = subprocess.Popen([sys.executable, "-m", "tilekit.cli", "--catalogue", url, "search", "vertex-species",
                             "--radius", "10", "--executor", "dask", "--workers", "2"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    wait_for(run_exists(url), timeout=120)
    wait_for(lambda: chunks_done(url) >= 2, timeout=120)
    pids = worker_pids(url)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=30)
    assert proc.returncode == 130, err
    assert "Traceback" not in err and err.strip().splitlines()[-1].startswith("error: run 1 interrupted"), err
    wait_for(lambda: not any(pid_alive(p) for p in pids), timeout=5.0)
    with reader(url) as cat:
        info = cat.run(1)
        assert info.status == "interrupted" and info.chunks_done >= 2 and info.chunks_leased == 0
