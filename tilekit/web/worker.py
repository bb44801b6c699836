"""A render worker process of :mod:`tilekit.web.executor` (started as ``python -c "from
tilekit.web.worker import main; main()"``): it opens its own catalogue, builds a
:class:`tilekit.web.service.Renderer` without a cache, and answers pickled calls on its
socket — a value, or a failure as (HTTP status, one line) — until the server goes away.
The parent side never imports this module, so the web layer has no import circle."""

from __future__ import annotations

import contextlib
import os
import sys
import threading
import time
from typing import Any

from tilekit.errors import TilekitError
from tilekit.web.executor import _line, resident_bytes


def main() -> None:
    """A worker's main (``python -c``): argv is the socket's descriptor, the catalogue URL
    ('' for the default catalogue), the tile limit and the server's process id."""
    from multiprocessing.connection import Connection

    fd, url, max_tiles, parent = sys.argv[1:5]
    seconds = float(sys.argv[5]) if len(sys.argv) > 5 else 0.0
    _die_with(int(parent))
    _child_main(Connection(int(fd)), url or None, int(max_tiles), seconds)


def _die_with(parent: int) -> None:
    """End this worker when the server process ends, however it ends: a worker still importing
    tilekit would otherwise outlive it, holding its stderr. (Linux's parent-death signal
    follows the thread that started the worker, not the process, so a watcher polls.)"""

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.5)
        os._exit(0)

    threading.Thread(target=watch, daemon=True, name="tilekit-render-watch").start()


def _child_main(conn: Any, url: str | None, max_tiles: int, seconds: float = 0.0) -> None:
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the server's Ctrl-C stops the parent; it ends us
    # A render past twice its budget ends this process from the kernel (SIGALRM's default
    # action): the server kills a late worker itself, but when the server is gone, a solver
    # holding the GIL would keep _die_with's thread from ever running.
    signal.signal(signal.SIGALRM, signal.SIG_DFL)
    alarm = int(2 * seconds) + 5 if seconds > 0 else 0
    try:
        # start-up cost: imported after _die_with watches the server (an import takes seconds)
        from tilekit.catalogue import open_catalogue
        from tilekit.web.api import status_of
        from tilekit.web.service import WORKER, Renderer

        WORKER["renderer"] = Renderer(open_catalogue(url), max_tiles, cache_bytes=0)
    except BaseException as exc:  # noqa: BLE001 - reported to the parent as one line
        with contextlib.suppress(OSError):
            conn.send(("error", 503, f"render worker could not start: {_line(exc)}", {}))
        return
    try:
        conn.send(("ready",))
    except OSError:  # the server stopped while this worker started
        return
    while True:
        try:
            fn, args = conn.recv()
        except (EOFError, OSError):
            return
        try:
            signal.alarm(alarm)
            out = fn(*args)
            signal.alarm(0)
            reply: tuple = ("ok", out, resident_bytes())
        except TilekitError as exc:
            extra = {k: getattr(exc, k) for k in ("estimate", "limit") if hasattr(exc, k)}
            reply = ("error", status_of(exc), _line(exc), extra)
        except (ValueError, TypeError) as exc:
            reply = ("error", 400, f"bad request: {_line(exc)}", {})
        except MemoryError:
            reply = ("error", 503, "the render ran out of memory; ask for a smaller region or depth", {})
        except Exception as exc:  # noqa: BLE001 - a bug: answered as 500, the worker lives on
            reply = ("error", 500, f"render failed: {type(exc).__name__}: {_line(exc)}", {})
        signal.alarm(0)
        try:
            conn.send(reply)
        except (OSError, ValueError):
            return
