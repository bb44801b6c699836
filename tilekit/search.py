"""Search runs: validate parameters, split into chunks, and work the chunks through leases.

Every worker — this process (``local``), each process of a pool (``process``), each task on a
dask cluster (``dask``), or another ``tilekit search --resume RUN`` on any machine — runs the
same loop (:func:`work`): claim a chunk (a lease in the catalogue), compute it, record its
results, rows, records and done mark in one transaction, repeat. A heartbeat thread keeps its
leases alive; a worker that dies leaves leases that expire and are claimed again, so a run
is never computed twice in the ordinary case, loses nothing when killed, and any number of
processes can work on it together. Ctrl-C and SIGTERM stop a run within a second or two,
keeping every recorded chunk (:class:`Interrupted`).
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import signal
import sys
import threading
import time
import uuid
from collections.abc import Callable, Iterable, Mapping
from typing import Any

import pluggy

from tilekit.catalogue import Catalogue, auto_type, lease_seconds, open_catalogue
from tilekit.errors import NotFoundError, ParameterError, SearchError, TilekitError
from tilekit.limits import refuse_over_memory
from tilekit.plugins import ChunkResult, Search, get_plugin_manager, get_search
from tilekit.signals import Terminated, deferred, sigterm_raises

__all__ = ["EXECUTORS", "Terminated", "describe_params", "run_search", "validate_params", "work"]

EXECUTORS: tuple[str, ...] = ("local", "process", "dask")

#: ``progress(done, total)`` is called at the start and whenever the number of done chunks changes.
Progress = Callable[[int, int], None]

#: How often a waiting worker or a coordinator looks at the catalogue again (seconds).
POLL_SECONDS = 0.2


# --------------------------------------------------------------------------- parameters


def _coerce(search: Search, name: str, typ: type, value: Any) -> Any:
    if value is None:
        return None
    where = f"search {search.name!r}: parameter {name!r}"
    if typ is bool:
        if isinstance(value, bool):
            return value
        if isinstance(value, str) and isinstance(auto_type(value), bool):
            return auto_type(value)
        raise ParameterError(f"{where} takes true or false, got {value!r}")
    if typ is int:
        if isinstance(value, bool):
            raise ParameterError(f"{where} takes an integer, got {value!r}")
        if isinstance(value, int):
            return value
        if isinstance(value, float) and value.is_integer():
            return int(value)
        if isinstance(value, str):
            try:
                parsed = auto_type(value)
            except TilekitError:
                parsed = None
            if isinstance(parsed, int) and not isinstance(parsed, bool):
                return int(parsed)
        raise ParameterError(f"{where} takes an integer, got {value!r}")
    if typ is float:
        if isinstance(value, bool):
            raise ParameterError(f"{where} takes a number, got {value!r}")
        try:
            number = float(value)
        except (TypeError, ValueError, OverflowError):
            raise ParameterError(f"{where} takes a number, got {value!r}") from None
        if not math.isfinite(number):
            raise ParameterError(f"{where} takes a finite number, got {value!r}")
        return number
    if typ is str:
        if isinstance(value, str):
            return value
        raise ParameterError(f"{where} takes text, got {value!r}")
    return typ(value)


def _in_range(search: Search, p: Any, value: Any) -> None:
    where = f"search {search.name!r}: parameter {p.name!r}"
    if p.choices is not None and value not in p.choices:
        close = str(NotFoundError(f"{p.name} value", str(value), list(p.choices)))
        if "valid:" not in close and len(p.choices) <= 20:
            close += "; valid: " + ", ".join(map(str, p.choices))
        raise ParameterError(f"search {search.name!r}: {close}")
    if isinstance(value, int | float) and not isinstance(value, bool):
        low, high = p.min, p.max
        if (low is not None and value < low) or (high is not None and value > high):
            shown = " to ".join(str(b) for b in (low, high) if b is not None)
            span = (f"from {low} to {high}" if low is not None and high is not None
                    else f"at least {low}" if low is not None else f"at most {high}")
            raise ParameterError(f"{where} takes a value {span}, got {value}" if shown else where)


def validate_params(search: Search, params: Mapping[str, Any] | None) -> dict[str, Any]:
    """Check ``params`` against the search's SearchParams: names, required ones, types,
    ranges and choices.

    Returns the complete parameter dict (defaults filled in). Raises ParameterError naming
    the offending parameter and what is valid.
    """
    params = dict(params or {})
    declared = {p.name: p for p in search.params}
    for key in params:
        if key not in declared:
            close = NotFoundError("parameter", key, declared)
            raise ParameterError(f"search {search.name!r}: {close}") from None
    out: dict[str, Any] = {}
    for p in search.params:
        value = params.get(p.name, p.default)
        if value is None and p.required:
            raise ParameterError(
                f"search {search.name!r} needs the parameter {p.name!r}"
                + (f" ({p.help})" if p.help else "")
            )
        value = _coerce(search, p.name, p.type, value)
        if value is not None:
            _in_range(search, p, value)
        out[p.name] = value
    return out


def describe_params(search: Search) -> Iterable[str]:
    """One line per parameter: ``name (type, default, range): help``."""
    for p in search.params:
        default = "required" if p.required else f"default {p.default!r}"
        extra = ""
        if p.choices is not None:
            extra = ", one of " + "/".join(map(str, p.choices))
        elif p.min is not None or p.max is not None:
            extra = f", {p.min if p.min is not None else ''}..{p.max if p.max is not None else ''}"
        yield f"{p.name} ({p.type.__name__}, {default}{extra}): {p.help}"


# --------------------------------------------------------------------------- the worker loop


class _ChunkFailed(Exception):
    """A chunk's run_chunk raised ``error`` (an ordinary exception, not an interrupt)."""

    def __init__(self, index: int, error: BaseException) -> None:
        super().__init__(index, error)
        self.index = index
        self.error = error

    def message(self) -> str:
        cause = self.error
        return f"{type(cause).__name__}: {' '.join(str(cause).split())}"


class _Heartbeat(threading.Thread):
    """Refreshes a worker's heartbeat and leases every third of the lease time; sets
    ``stop`` when the worker is asked to stop or the run ended meanwhile."""

    def __init__(self, catalogue: Catalogue, owner: str) -> None:
        super().__init__(name=f"tilekit-heartbeat-{owner}", daemon=True)
        self.catalogue = catalogue
        self.owner = owner
        self.stop = threading.Event()
        self._end = threading.Event()

    def run(self) -> None:
        interval = lease_seconds() / 3.0
        while not self._end.wait(interval):
            try:
                if self.catalogue.heartbeat(self.owner):
                    self.stop.set()
            except Exception:  # a busy database: try again at the next beat
                continue

    def end(self) -> None:
        self._end.set()


def work(
    catalogue: Catalogue,
    run_id: int,
    search: Search,
    params: Mapping[str, Any],
    session: str,
    *,
    on_record: Callable[[int], None] | None = None,
) -> int:
    """Work on a run until nothing is left to claim: claim, compute, record. Returns the
    number of chunks this worker recorded.

    Waits (polling) while the only chunks left are leased by other live workers, and claims
    them when their leases expire. A chunk that raises releases its lease, marks the run
    failed and raises :class:`_ChunkFailed`; an interrupt releases the lease and propagates.
    """
    owner = _patiently(catalogue.start_worker, run_id, session)
    beat = _Heartbeat(catalogue, owner)
    beat.start()
    recorded = 0
    try:
        while not beat.stop.is_set():
            claimed = _patiently(catalogue.claim, run_id, owner)
            if claimed is None:
                break
            if not claimed:
                beat.stop.wait(POLL_SECONDS)
                continue
            for index, chunk in claimed:
                started = time.perf_counter()
                try:
                    result = search.run_chunk(params, chunk)
                except Exception as exc:
                    raise _ChunkFailed(index, exc) from exc
                if not isinstance(result, ChunkResult):
                    raise _ChunkFailed(index, SearchError(
                        f"search {search.name!r}: run_chunk returned {type(result).__name__} "
                        f"for chunk {index}, not a ChunkResult"))
                spent = time.perf_counter() - started
                if _patiently(catalogue.record_chunk, run_id, index, result, spent, owner=owner):
                    recorded += 1
                if on_record is not None:
                    on_record(index)
    except _ChunkFailed as exc:
        with contextlib.suppress(TilekitError):
            catalogue.finish_run(run_id, "failed", error=f"{exc.message()} in chunk {exc.index}")
        raise
    finally:
        beat.end()
        _patiently(catalogue.finish_worker, owner)
    return recorded


def _locked(exc: BaseException) -> bool:
    """A SQLite catalogue whose write lock another process held past the busy timeout."""
    text = str(exc)
    return "database is locked" in text or "database table is locked" in text


def _patiently(call: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
    """``call(*args, **kwargs)``, retried while the catalogue is locked by other writers (many workers on
    one SQLite file), for up to a lease time: the heartbeat keeps this worker's leases alive
    meanwhile, so waiting loses nothing, where giving up would kill the worker."""
    deadline = time.monotonic() + lease_seconds()
    pause = POLL_SECONDS
    while True:
        try:
            with deferred():  # a signal waits for the write to end: no lock is left held
                return call(*args, **kwargs)
        except TilekitError as exc:
            if not _locked(exc) or time.monotonic() + pause > deadline:
                raise
        time.sleep(pause)
        pause = min(2.0, pause * 1.5)


# --------------------------------------------------------------------------- executors


def _set_parent_death_signal() -> None:
    """Linux: the kernel sends this process SIGKILL when its parent dies, so pool workers
    never outlive the run that started them (not even a SIGKILLed one)."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # not Linux: the getppid watch below still applies
        pass


def _child_main(url: str, run_id: int, session: str, search: Search, params: Mapping[str, Any],
                pm: pluggy.PluginManager, parent: int) -> None:
    """A pool process: ignore Ctrl-C (the parent handles it), die with the parent, work."""
    _set_parent_death_signal()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if os.getppid() != parent:
        os._exit(1)

    def watch() -> None:
        while True:
            time.sleep(1.0)
            if os.getppid() != parent:
                os._exit(1)

    threading.Thread(target=watch, daemon=True).start()

    try:
        catalogue = _patiently(open_catalogue, url, seed=False, migrate=False, pm=pm)
    except TilekitError as exc:
        print(f"error: worker {os.getpid()}: {' '.join(str(exc).split())}", file=sys.stderr)
        os._exit(2)
    try:
        work(catalogue, run_id, search, params, session)
    except _ChunkFailed:
        os._exit(3)
    except TilekitError as exc:  # the catalogue failed this worker: one line, not a traceback
        print(f"error: worker {os.getpid()}: {' '.join(str(exc).split())}", file=sys.stderr)
        os._exit(2)
    finally:
        catalogue.close()


class _Monitor:
    """Reports progress: counted here for chunks this process records, read from the
    catalogue (at most every POLL_SECONDS) while workers elsewhere record them."""

    def __init__(self, catalogue: Catalogue, run_id: int, progress: Progress | None, done: int, total: int) -> None:
        self.catalogue = catalogue
        self.run_id = run_id
        self.progress = progress
        self.done = done
        self.total = total
        self.read_at = 0.0

    def recorded(self, _index: int) -> None:
        """A chunk recorded in this process (others' chunks are counted at the next read)."""
        self.done += 1
        if self.progress is None:
            return
        now = time.monotonic()
        if now - self.read_at >= 1.0:
            self.read_at = now
            self.done = max(self.done, self.catalogue.chunks_done(self.run_id))
        self.progress(min(self.done, self.total), self.total)

    def poll(self) -> None:
        if self.progress is None:
            return
        self.read_at = time.monotonic()
        done = self.catalogue.chunks_done(self.run_id)
        if done != self.done:
            self.done = done
            self.progress(done, self.total)


def _run_process(catalogue: Catalogue, run_id: int, search: Search, params: Mapping[str, Any],
                 session: str, workers: int | None, monitor: _Monitor) -> None:
    import multiprocessing

    if catalogue.path is None and catalogue.engine.url.get_backend_name() == "sqlite":
        raise ParameterError("the process executor needs a catalogue file or server, not an in-memory database")
    ctx = multiprocessing.get_context("fork" if hasattr(os, "fork") else "spawn")
    url = catalogue.engine.url.render_as_string(hide_password=False)
    count = workers or os.cpu_count() or 1
    procs = [ctx.Process(target=_child_main, name=f"tilekit-worker-{i}",
                         args=(url, run_id, session, search, params, catalogue.pm, os.getpid()),
                         daemon=True)
             for i in range(count)]
    try:
        for proc in procs:
            proc.start()
        while any(proc.is_alive() for proc in procs):
            monitor.poll()
            time.sleep(POLL_SECONDS)
        monitor.poll()
    finally:
        for proc in procs:
            if proc.is_alive():
                proc.terminate()
        deadline = time.monotonic() + 1.0
        for proc in procs:
            proc.join(max(0.0, deadline - time.monotonic()))
            if proc.is_alive():
                proc.kill()
                proc.join(0.5)
    if any(proc.exitcode not in (0, None) for proc in procs):
        info = catalogue.run(run_id)
        if info.status != "failed":
            raise SearchError(f"a worker of run {run_id} exited with status "
                              f"{[p.exitcode for p in procs if p.exitcode]}")


def _dask_worker(url: str, run_id: int, session: str, name: str, params: Mapping[str, Any]) -> int:
    """A dask task: open the catalogue on the worker and work on the run through leases."""
    catalogue = open_catalogue(url, seed=False, migrate=False)
    try:
        return work(catalogue, run_id, get_search(name, catalogue.pm), params, session)
    except _ChunkFailed as exc:
        raise SearchError(f"{exc.message()} in chunk {exc.index}") from None
    finally:
        catalogue.close()


def _dask_client(workers: int | None, scheduler: str | None) -> Any:
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise SearchError(
            "the dask executor needs dask.distributed; install it with: pip install 'tilekit[dask]'"
        ) from None
    address = scheduler or os.environ.get("TILEKIT_DASK_SCHEDULER")
    if address:
        _reach_scheduler(address)
        try:
            return Client(address, timeout=SCHEDULER_CONNECT_SECONDS), None
        except (OSError, ValueError, TypeError) as exc:  # TimeoutError is an OSError
            raise _NoExecutor(f"cannot use the dask scheduler {address[:80]!r}: {_one_line(exc)}") from None
    # the cluster's processes inherit "ignore Ctrl-C", so an interrupt reaches only us
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if _main_thread() else None
    try:
        cluster = LocalCluster(n_workers=workers or 1, threads_per_worker=1, processes=True,
                               dashboard_address=":0", silence_logs=logging.CRITICAL)
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)
    return Client(cluster), cluster


#: Seconds to wait for a dask scheduler to answer (distributed's own default is 30).
SCHEDULER_CONNECT_SECONDS = 10.0


class _NoExecutor(SearchError):
    """The executor could not start (an unreachable or malformed scheduler address): a run
    this call created is removed again rather than left queued."""


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())[:200] or type(exc).__name__


def _reach_scheduler(address: str) -> None:
    """A scheduler address that is not an address, or a TCP one nobody listens on, is one
    line at once (distributed raises a ValueError for the first, and retries the second
    until its connect timeout)."""
    try:
        from distributed.comm import parse_address
        from distributed.comm.addressing import parse_host_port

        scheme, location = parse_address(address)
        if scheme not in ("tcp", "tls"):
            return
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise _NoExecutor(f"--scheduler {address[:80]!r} is not a scheduler address "
                          f"(e.g. tcp://10.0.0.5:8786): {_one_line(exc)}") from None
    import socket

    try:
        socket.create_connection((host, int(port)), timeout=SCHEDULER_CONNECT_SECONDS).close()
    except (OSError, ValueError, UnicodeError) as exc:
        raise _NoExecutor(f"cannot reach the dask scheduler at {address[:80]!r}: "
                          f"{getattr(exc, 'strerror', None) or _one_line(exc)}") from None


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


def _run_dask(catalogue: Catalogue, run_id: int, search: Search, params: Mapping[str, Any],
              session: str, workers: int | None, scheduler: str | None, monitor: _Monitor) -> None:
    if catalogue.path is None and catalogue.engine.url.get_backend_name() == "sqlite":
        raise ParameterError("the dask executor needs a catalogue file or server, not an in-memory database")
    client, cluster = _dask_client(workers, scheduler)
    url = catalogue.engine.url.render_as_string(hide_password=False)
    futures: list[Any] = []
    local_pids: list[int] = []
    try:
        if cluster is not None:  # our own cluster's processes: ended for sure when we end
            local_pids = [int(p) for p in client.run(os.getpid).values() if int(p) != os.getpid()]
        count = workers or max(1, len(client.scheduler_info().get("workers", {})))
        futures = [client.submit(_dask_worker, url, run_id, session, search.name, dict(params),
                                 pure=False, key=f"tilekit-{session}-{i}") for i in range(count)]
        while not all(f.done() for f in futures):
            monitor.poll()
            time.sleep(POLL_SECONDS)
        monitor.poll()
        for f in futures:
            if f.status == "error":
                exc = f.exception()
                if catalogue.run(run_id).status != "failed":
                    raise SearchError(f"a dask worker of run {run_id} failed: {exc}")
    except BaseException:
        with contextlib.suppress(Exception):
            catalogue.stop_session(session)
        raise
    finally:
        logging.getLogger("distributed").setLevel(logging.CRITICAL)
        with contextlib.suppress(Exception):
            client.cancel(futures)
        with contextlib.suppress(Exception):
            client.close(timeout=2)
        if cluster is not None:
            with contextlib.suppress(Exception):
                cluster.close(timeout=2)
            for pid in local_pids:
                with contextlib.suppress(OSError):
                    os.kill(pid, signal.SIGKILL)


# --------------------------------------------------------------------------- run_search


#: Worker processes per CPU this machine runs at most (the process executor and a local dask
#: cluster): more only wait for each other, and each holds an interpreter with the library.
WORKERS_PER_CPU = 4
#: Peak bytes of one worker process (Python, NumPy, SQLAlchemy, the plugins and its chunks:
#: 75-76 MB RSS on vertex-species, 124 MB on k-uniform --k 2, 4 workers; docs/benchmarks.md
#: "Limits, measured").
WORKER_BYTES = 128 << 20


def max_workers(catalogue: Catalogue | None = None, executor: str = "process", scheduler: str | None = None) -> int:
    """The most workers a run may ask for: WORKERS_PER_CPU per CPU for processes of this
    machine, and as many for a SQLite catalogue whatever runs them (one file takes one
    writer at a time; every other worker waits for the lock)."""
    local = executor == "process" or (executor == "dask" and not (scheduler or os.environ.get("TILEKIT_DASK_SCHEDULER")))
    sqlite = catalogue is not None and catalogue.engine.url.get_backend_name() == "sqlite"
    if local or sqlite:
        return WORKERS_PER_CPU * (os.cpu_count() or 1)
    return 4096


def _check_workers(catalogue: Catalogue, executor: str, workers: int | None, scheduler: str | None) -> None:
    """Refuse (one line) more workers than the machine and the database can serve, before a
    run is created: ``max_workers``, and for local processes the memory they would take."""
    if workers is None or executor == "local":
        return
    cap = max_workers(catalogue, executor, scheduler)
    if workers > cap:
        where = "a SQLite catalogue" if catalogue.engine.url.get_backend_name() == "sqlite" else "this machine"
        raise ParameterError(
            f"--workers {workers} is more than {where} can serve: at most {cap} ({WORKERS_PER_CPU} per CPU, "
            f"{os.cpu_count() or 1} CPUs); give --workers {cap} or fewer"
        )
    if executor == "process" or cap < 4096:
        refuse_over_memory("worker processes", workers, WORKER_BYTES, hint="give fewer --workers")


def _check_executor(executor: str, workers: int | None, scheduler: str | None) -> None:
    if executor not in EXECUTORS:
        raise ParameterError(f"executor {executor!r} is not one of: {', '.join(EXECUTORS)}")
    if workers is not None and workers < 1:
        raise ParameterError(f"workers must be at least 1, got {workers}")
    if executor == "dask":  # fail before creating or touching a run if dask is missing
        try:
            import dask.distributed  # noqa: F401
        except ImportError:
            _dask_client(workers, scheduler)
        address = scheduler or os.environ.get("TILEKIT_DASK_SCHEDULER")
        if address:  # nor when its scheduler cannot be reached
            _reach_scheduler(address)


def run_search(
    catalogue: Catalogue,
    name: str | None,
    params: Mapping[str, Any] | None = None,
    executor: str = "local",
    workers: int | None = None,
    resume_run: int | None = None,
    progress: Progress | None = None,
    *,
    pm: pluggy.PluginManager | None = None,
    scheduler: str | None = None,
    on_run: Callable[[int], None] | None = None,
) -> int:
    """Run (or resume, or join) the search ``name`` and return the run id.

    A new run validates ``params`` (types, ranges, choices) before anything is stored, then
    stores the chunks and works them. ``resume_run`` works on an earlier run with its stored
    parameters: an interrupted or failed run continues, a run that other workers are
    working on is joined (leases keep them from computing a chunk twice). Chunks run with
    ``executor``: ``local`` (in-process), ``process`` (``workers`` processes) or ``dask``
    (``scheduler`` address, ``$TILEKIT_DASK_SCHEDULER``, or a local cluster of ``workers``).
    The run ends ``done``; ``failed`` (SearchError) if a chunk raised; on Ctrl-C or SIGTERM
    the recorded chunks are kept, the run reads ``interrupted`` and the interrupt
    (KeyboardInterrupt, or :class:`Terminated`) propagates. ``on_run(run_id)`` is called
    once the run exists; ``progress(done, total)`` at the start and as chunks are recorded.
    """
    pm = pm or catalogue._pm or get_plugin_manager()
    _check_executor(executor, workers, scheduler)
    _check_workers(catalogue, executor, workers, scheduler)
    created: int | None = None

    if resume_run is not None:
        info = catalogue.run(resume_run)
        if name is not None and name != info.kind:
            raise SearchError(f"run {info.id} is a {info.kind!r} search, not {name!r}")
        search = get_search(info.kind, pm)
        try:
            stored = validate_params(search, info.params)
        except ParameterError as exc:
            raise SearchError(f"run {info.id} was stored with parameters this version refuses: {exc}") from None
        if params is not None and validate_params(search, params) != stored:
            raise SearchError(
                f"run {info.id} was started with {stored}; resume it without new parameters"
            )
        if info.status == "cancelled":
            raise SearchError(f"run {info.id} was cancelled; start a new run (runs delete {info.id} removes it)")
        params = stored
        run_id = info.id
        if info.status == "failed":
            catalogue.reopen_run(run_id)
        if on_run:
            on_run(run_id)
        if info.status == "done":
            if progress:
                progress(info.chunks_done, info.chunks_total)
            return run_id
    else:
        if name is None:
            raise ParameterError("run_search needs a search name or a run to resume")
        search = get_search(name, pm)
        params = validate_params(search, params)
        try:
            chunks = search.chunks(params)
            run_id = catalogue.create_run(search.name, params, chunks)
        except TilekitError:
            raise
        except Exception as exc:
            raise SearchError(f"search {search.name!r} could not split its work: {exc}") from exc
        created = run_id
        if on_run:
            on_run(run_id)

    session = uuid.uuid4().hex
    info = catalogue.run(run_id)
    if progress:
        progress(info.chunks_done, info.chunks_total)
    monitor = _Monitor(catalogue, run_id, progress, info.chunks_done, info.chunks_total)
    with sigterm_raises():
        try:
            if executor == "local":
                work(catalogue, run_id, search, params, session, on_record=monitor.recorded)
            elif executor == "process":
                _run_process(catalogue, run_id, search, params, session, workers, monitor)
            else:
                _run_dask(catalogue, run_id, search, params, session, workers, scheduler, monitor)
        except KeyboardInterrupt:  # Ctrl-C, or SIGTERM (Terminated)
            _close_session(catalogue, session)
            with contextlib.suppress(TilekitError):
                catalogue.finish_run(run_id, "interrupted", error="interrupted")
            raise
        except _NoExecutor:
            _close_session(catalogue, session)
            if created is not None and catalogue.run(created).chunks_done == 0:
                with contextlib.suppress(TilekitError):
                    catalogue.delete_run(created)  # nothing was done: leave no queued run behind
            raise
        except _ChunkFailed as exc:
            raise SearchError(
                f"run {run_id} ({search.name}) failed in chunk {exc.index}: {exc.message()}; "
                f"fix the cause and resume it (tilekit search {search.name} --resume {run_id})"
            ) from exc.error
        except SearchError:
            _close_session(catalogue, session)
            info = catalogue.run(run_id)
            if info.status == "failed" and info.error:
                raise SearchError(
                    f"run {run_id} ({search.name}) failed: {info.error}; "
                    f"fix the cause and resume it (tilekit search {search.name} --resume {run_id})"
                ) from None
            raise
        _close_session(catalogue, session)
        return _finish(catalogue, run_id, search, params)


def _close_session(catalogue: Catalogue, session: str) -> None:
    """Release the leases of every worker of this session (dead pool processes included)."""
    with contextlib.suppress(TilekitError):
        for owner in catalogue.session_owners(session):
            catalogue.finish_worker(owner)


def _finish(catalogue: Catalogue, run_id: int, search: Search, params: Mapping[str, Any]) -> int:
    """After this session's workers stopped: a run with every chunk done is summarised and
    marked done; a failed or cancelled one says so; otherwise other workers still hold it."""
    info = catalogue.run(run_id)
    if info.status == "failed":
        raise SearchError(
            f"run {run_id} ({search.name}) failed: {info.error}; "
            f"fix the cause and resume it (tilekit search {search.name} --resume {run_id})"
        )
    if info.status in ("cancelled", "done"):
        return run_id
    if info.chunks_done < info.chunks_total:
        return run_id  # stopped while other workers hold the remaining chunks
    try:
        summary = _summarize(catalogue, search, params, run_id)
    except TilekitError as exc:
        catalogue.finish_run(run_id, "failed", error=str(exc))
        raise
    catalogue.finish_run(run_id, "done", summary=summary)
    return run_id


def _natural(key: str) -> tuple[Any, ...]:
    """``fixed_9`` before ``fixed_10``: counts sort by their words, then their numbers."""
    import re

    return tuple(int(part) if part.isdigit() else part for part in re.split(r"(\d+)", key))


def _summarize(catalogue: Catalogue, search: Search, params: Mapping[str, Any], run_id: int) -> dict[str, Any]:
    counts = dict(sorted(catalogue.run_counts(run_id).items(), key=lambda kv: _natural(kv[0])))
    if search.summarize is None:
        info = catalogue.run(run_id)
        n_results = sum(1 for _ in catalogue.iter_results(run_id))
        out: dict[str, Any] = {"results": n_results}
        if info.rows > n_results:
            out["rows"] = info.rows - n_results
        return {**out, **counts}
    try:
        summary = search.summarize(params, catalogue.results(run_id))
    except TilekitError:
        raise
    except Exception as exc:
        raise SearchError(f"search {search.name!r} could not summarise its results: {exc}") from exc
    return {**dict(summary or {}), **counts}
