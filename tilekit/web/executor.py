"""Renders off the event loop: a bounded pool of worker processes with a wall-clock budget.

:class:`RenderPool` runs a picklable call (a render, a PNG conversion) in one of ``workers``
processes. At most ``workers + queue`` calls are admitted at once; the next gets
:class:`Busy` (HTTP 503 with ``Retry-After``) at once, and a call that waited ``seconds`` for
a free worker gets it too. A call that runs past ``seconds`` of wall-clock time gets
:class:`RenderTimeout` (HTTP 504) and its worker is killed, so a solver cannot hold a CPU or
its memory past the budget; a worker whose resident memory grew past ``recycle_bytes`` is
replaced after its call, so memory comes back to the system. Calls of a key (a tiling's
name) that once ran past half the budget share a slow lane of ``workers - 1`` slots, so a run
of solver renders leaves a worker to the quick ones. The health check and every
other request keep their event loop and their GIL: the work runs in another process.

``workers=0`` runs the calls in the calling thread with the same admission limit, but no
budget (a thread cannot be stopped): the mode of an app whose catalogue a child process
cannot open (an in-memory SQLite database) or whose plugins were registered by hand.
"""

from __future__ import annotations

import contextlib
import os
import queue
import socket
import subprocess
import sys
import threading
import time
from collections import OrderedDict
from collections.abc import Callable
from typing import Any

from tilekit.errors import TilekitError

#: Worker processes ``tilekit serve`` starts (``--render-workers``): one per core, at most 4.
DEFAULT_WORKERS = max(1, min(4, os.cpu_count() or 1))
#: Calls that may wait for a worker besides those running (``--render-queue``).
DEFAULT_QUEUE = 8
#: Wall-clock seconds one render may run (``--render-seconds``), and may wait for a worker.
DEFAULT_SECONDS = 20.0
#: A worker whose resident set exceeds this after a call is replaced (``--worker-mb``).
DEFAULT_RECYCLE_BYTES = 768 << 20
#: Seconds a new worker may take to import tilekit and open the catalogue.
START_SECONDS = 120.0


class Busy(TilekitError):
    """Every render slot is taken (HTTP 503; ``retry_after`` seconds)."""

    http_status = 503

    def __init__(self, message: str, retry_after: int) -> None:
        super().__init__(message)
        self.retry_after = int(retry_after)


class RenderTimeout(TilekitError):
    """A render ran past its wall-clock budget and was stopped (HTTP 504)."""

    http_status = 504


class WorkerError(TilekitError):
    """An error a worker process answered with, carrying its HTTP status and extra fields."""

    def __init__(self, message: str, status: int, extra: dict[str, Any] | None = None) -> None:
        super().__init__(message)
        self.http_status = int(status)
        self.extra = dict(extra or {})


def resident_bytes(pid: int | str = "self") -> int:
    """The resident set size of a process from ``/proc/PID/statm`` (0 where there is none)."""
    try:
        with open(f"/proc/{pid}/statm") as fh:
            return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def _line(exc: BaseException) -> str:
    return "; ".join(s.strip() for s in str(exc).splitlines() if s.strip()) or type(exc).__name__


# --------------------------------------------------------------------------- the parent side


class _Worker:
    """One worker process (``python -c``, not multiprocessing's spawn, which re-runs the
    parent's ``__main__``) and a socket pair to it carrying pickled calls and answers."""

    def __init__(self, url: str | None, max_tiles: int, seconds: float = 0.0) -> None:
        from multiprocessing.connection import Connection

        ours, theirs = socket.socketpair()
        code = "from tilekit.web.worker import main; main()"
        try:
            self.process = subprocess.Popen(
                [sys.executable, "-c", code, str(theirs.fileno()), url or "", str(max_tiles), str(os.getpid()),
                 str(seconds)],
                pass_fds=(theirs.fileno(),), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL)
        finally:
            theirs.close()
        self.conn = Connection(ours.detach())
        if not self.conn.poll(START_SECONDS):
            self.kill()
            raise WorkerError(f"render worker did not start within {START_SECONDS:g} s", 503)
        try:
            first = self.conn.recv()
        except EOFError:
            self.kill()
            raise WorkerError("render worker exited while starting", 503) from None
        if first[0] != "ready":
            self.kill()
            raise WorkerError(first[2], first[1])

    def alive(self) -> bool:
        return self.process.poll() is None

    def kill(self) -> None:
        with contextlib.suppress(Exception):
            self.process.kill()
            self.process.wait(5)
        with contextlib.suppress(Exception):
            self.conn.close()


class RenderPool:
    """The bounded pool of the module docstring."""

    def __init__(self, catalogue_url: str | None, max_tiles: int, *, workers: int = DEFAULT_WORKERS,
                 queue_size: int = DEFAULT_QUEUE, seconds: float = DEFAULT_SECONDS,
                 recycle_bytes: int = DEFAULT_RECYCLE_BYTES) -> None:
        if workers < 0 or queue_size < 0 or not seconds > 0:
            raise ValueError("workers and queue_size must be >= 0 and seconds > 0")
        self.url = catalogue_url
        self.max_tiles = max_tiles
        self.workers = workers
        self.queue_size = queue_size
        self.seconds = float(seconds)
        self.recycle_bytes = int(recycle_bytes)
        self._slots = threading.BoundedSemaphore(max(1, workers) + queue_size)
        self._idle: queue.Queue[_Worker | None] = queue.Queue()
        for _ in range(max(1, workers)):
            self._idle.put(None)  # a worker is started on first use
        self._live: set[_Worker] = set()
        self._lock = threading.Lock()
        self.running = 0
        self._closed = False
        self._starting = 0
        self._slow: OrderedDict[str, None] = OrderedDict()  # keys whose calls ran long
        self._slow_lane = threading.BoundedSemaphore(max(1, workers - 1))
        self.stats = {"calls": 0, "busy": 0, "timeouts": 0, "recycled": 0, "started": 0}

    @property
    def retry_after(self) -> int:
        return max(1, int(round(self.seconds / 2)))

    def _busy(self, why: str) -> Busy:
        with self._lock:
            self.stats["busy"] += 1
        return Busy(f"the server is busy ({why}); try again in {self.retry_after} s", self.retry_after)

    def call(self, fn: Callable[..., Any], *args: Any, local: Callable[[], Any] | None = None,
             what: str = "render", key: str | None = None) -> Any:
        """``fn(*args)`` in a worker (``local()`` in this thread when ``workers=0``), bounded as
        the module docstring says. ``fn`` and ``args`` must pickle. ``key`` (a tiling's name)
        marks calls alike: once one ran past half the budget, the key's calls share the slow
        lane (all workers but one), so slow renders cannot starve quick ones."""
        slow = key is not None and self.workers > 1 and self._is_slow(key)
        if slow and not self._slow_lane.acquire(blocking=False):
            raise self._busy(f"{what} ran long before, and {self.workers - 1} such renders are running; "
                             "the last worker is kept for quick ones")
        try:
            return self._call(fn, args, local, what, key)
        finally:
            if slow:
                self._slow_lane.release()

    def _is_slow(self, key: str) -> bool:
        with self._lock:
            return key in self._slow

    def _mark_slow(self, key: str) -> None:
        with self._lock:
            self._slow[key] = None
            self._slow.move_to_end(key)
            while len(self._slow) > 1024:
                self._slow.popitem(last=False)

    def _call(self, fn: Callable[..., Any], args: tuple, local: Callable[[], Any] | None, what: str,
              key: str | None) -> Any:
        if not self._slots.acquire(blocking=False):
            raise self._busy(f"{max(1, self.workers) + self.queue_size} renders running or waiting")
        try:
            worker = self._wait_for_worker()
            keep: _Worker | None = None
            with self._lock:
                self.running += 1
                self.stats["calls"] += 1
            try:
                if self.workers == 0:
                    return local() if local is not None else fn(*args)
                started = time.monotonic()
                keep, value, error = self._run(worker, fn, args, what)
                if key is not None and (isinstance(error, RenderTimeout)
                                        or time.monotonic() - started > self.seconds / 2):
                    self._mark_slow(key)
            finally:
                with self._lock:
                    self.running -= 1
                if keep is None and self.workers > 0:
                    self._refill()  # a killed or recycled worker's successor starts now, not on the next call
                else:
                    self._idle.put(keep)
            if error is not None:
                raise error
            return value
        finally:
            self._slots.release()

    def _wait_for_worker(self) -> _Worker | None:
        """An idle worker (or a token to start one), waiting at most ``seconds``, longer while
        a worker is starting (at most START_SECONDS more): a start is not a busy server."""
        deadline = time.monotonic() + self.seconds
        while True:
            try:
                return self._idle.get(timeout=0.25)
            except queue.Empty:
                now = time.monotonic()
                if now > deadline and (self._starting == 0 or now > deadline + START_SECONDS):
                    raise self._busy(f"no render worker became free within {self.seconds:g} s") from None

    def _run(self, worker: _Worker | None, fn: Callable[..., Any], args: tuple,
             what: str) -> tuple[_Worker | None, Any, TilekitError | None]:
        """(the worker to keep or None, the value, the error to raise) of one call."""
        if worker is None or not worker.alive():
            if worker is not None:
                self._forget(worker)
            try:
                worker = _Worker(self.url, self.max_tiles, self.seconds)
            except WorkerError as exc:
                return None, None, exc
            with self._lock:
                self._live.add(worker)
                self.stats["started"] += 1
        try:
            worker.conn.send((fn, args))
        except (OSError, ValueError):
            self._forget(worker)
            return None, None, WorkerError(f"{what}: the render worker went away; try again", 503)
        if not worker.conn.poll(self.seconds):
            self._forget(worker)
            with self._lock:
                self.stats["timeouts"] += 1
            return None, None, RenderTimeout(
                f"{what} ran past the {self.seconds:g} s budget and was stopped "
                "(tilekit serve --render-seconds); ask for a smaller region, depth or size")
        try:
            reply = worker.conn.recv()
        except (EOFError, OSError):
            self._forget(worker)
            return None, None, WorkerError(
                f"{what}: the render worker died (out of memory?); ask for a smaller region", 503)
        if reply[0] != "ok":
            _, status, message, extra = reply
            return worker, None, WorkerError(message, status, extra)
        if reply[2] > self.recycle_bytes:  # its memory goes back to the system with it
            self._forget(worker)
            with self._lock:
                self.stats["recycled"] += 1
            return None, reply[1], None
        return worker, reply[1], None

    def _refill(self) -> None:
        with self._lock:
            self._starting += 1

        def start() -> None:
            worker: _Worker | None = None
            if not self._closed:
                with contextlib.suppress(WorkerError):
                    worker = _Worker(self.url, self.max_tiles, self.seconds)
                if worker is not None:
                    with self._lock:
                        self._live.add(worker)
                        self.stats["started"] += 1
                    if self._closed:
                        self._forget(worker)
                        worker = None
            self._idle.put(worker)
            with self._lock:
                self._starting -= 1

        threading.Thread(target=start, daemon=True, name="tilekit-render-start").start()

    def warm(self) -> None:
        """Start the workers now, in the background (the app's start-up), so the first
        renders do not wait for Python to import tilekit in each."""
        if self.workers == 0:
            return
        taken = 0
        while True:
            try:
                worker = self._idle.get_nowait()
            except queue.Empty:
                break
            if worker is None:
                taken += 1
            else:
                self._idle.put(worker)
                break
        for _ in range(taken):
            self._refill()

    def _forget(self, worker: _Worker) -> None:
        worker.kill()
        with self._lock:
            self._live.discard(worker)

    def close(self) -> None:
        """Stop every worker (the app's shutdown)."""
        self._closed = True
        with self._lock:
            live = list(self._live)
            self._live.clear()
        for w in live:
            w.kill()

    def snapshot(self) -> dict[str, Any]:
        """What ``/health`` reports: workers, running calls, counters, resident memory."""
        with self._lock:
            live = list(self._live)
            out = {"workers": self.workers, "queue": self.queue_size, "seconds": self.seconds,
                   "running": self.running, **self.stats}
        out["worker_rss_mb"] = [round(resident_bytes(w.process.pid) / 2**20, 1) for w in live if w.process.pid]
        return out

