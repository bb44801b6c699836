"""SIGTERM as an exception, so that a run stops on it as on Ctrl-C, and a window in which both
wait (no heavy imports here: the command line installs it before anything else is loaded)."""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator
from typing import Any


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread (exit status 143, where Ctrl-C's is 130)."""


@contextlib.contextmanager
def sigterm_raises() -> Iterator[None]:
    """While active, SIGTERM raises :class:`Terminated` in the main thread."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum: int, frame: object) -> None:
        raise Terminated()

    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


_SIGNALS = (signal.SIGINT, signal.SIGTERM)
#: while a ``deferred()`` block runs in the main thread: the handlers it replaced, and the
#: signals that arrived meanwhile
_saved: dict[int, Any] = {}
_pending: list[int] = []


def _deliver(signum: int, handler: Any) -> None:
    """Act on ``signum`` as ``handler`` (the one a deferred block replaced) would have."""
    if callable(handler):
        handler(signum, None)  # Python's Ctrl-C handler or sigterm_raises': raises
    elif handler == signal.SIG_DFL:
        signal.raise_signal(signum)  # the handlers are back: the default action (exit)


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """Ctrl-C and SIGTERM arriving inside the block take effect when it ends (or at a
    :func:`checkpoint` inside it), as they would have at once.

    For catalogue writes: an interrupt inside a commit or a connection's return to the pool
    can leave SQLite's write lock held by a connection that the unwinding exception keeps
    alive, and the clean-up writes that follow (giving leases back) then wait for that lock.
    Main thread only (signals are handled there); elsewhere, and when nested, it does nothing.
    """
    if _saved or threading.current_thread() is not threading.main_thread():
        yield
        return

    def note(signum: int, frame: object) -> None:
        if signum not in _pending:
            _pending.append(signum)

    for signum in _SIGNALS:
        _saved[signum] = signal.signal(signum, note)
    try:
        yield
    finally:
        saved = dict(_saved)
        _saved.clear()
        for signum, handler in saved.items():
            signal.signal(signum, handler)
        arrived, _pending[:] = list(_pending), []
        for signum in arrived:
            _deliver(signum, saved[signum])


def checkpoint() -> None:
    """Inside :func:`deferred`: act on a signal that arrived, now, if its handler raises (a
    default action waits for the block's end). For places where nothing is held yet (waiting
    for another process's write lock), so that Ctrl-C is not held up."""
    if threading.current_thread() is not threading.main_thread():
        return
    for signum in list(_pending):
        handler = _saved.get(signum)
        if callable(handler):
            _pending.remove(signum)
            handler(signum, None)
