"""uvicorn as ``tilekit serve`` runs it: timeouts against slow clients, bounded request heads.

uvicorn closes a keep-alive connection ``timeout_keep_alive`` seconds after a response, but
a connection that has sent part of a request head (a header line every few seconds) or
nothing at all is kept for ever. :class:`HeadTimeoutProtocol` closes one whose request head
is not complete ``head_seconds`` after its first byte (or after the connection opened).
Heads up to ``MAX_HEAD_BYTES`` reach the app, so a long query string gets the app's own
414 JSON answer instead of h11's plain-text 400 and a reset.
"""

from __future__ import annotations

import asyncio
from typing import Any

import h11
from uvicorn.protocols.http.h11_impl import H11Protocol

from tilekit.web.limits import (
    GRACEFUL_SECONDS,
    HEAD_SECONDS,
    KEEP_ALIVE_SECONDS,
    MAX_CONNECTIONS,
    MAX_HEAD_BYTES,
)


class HeadTimeoutProtocol(H11Protocol):
    """uvicorn's h11 protocol with a deadline for each request head (see the module docstring)."""

    head_seconds = HEAD_SECONDS

    def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
        self._head_timer: asyncio.TimerHandle | None = None
        super().connection_made(transport)
        self._arm_head()

    def _arm_head(self) -> None:
        if self._head_timer is None:
            self._head_timer = self.loop.call_later(self.head_seconds, self._head_expired)

    def _disarm_head(self) -> None:
        if self._head_timer is not None:
            self._head_timer.cancel()
            self._head_timer = None

    def data_received(self, data: bytes) -> None:
        super().data_received(data)
        if self.conn.their_state is h11.IDLE and not self.transport.is_closing():
            self._arm_head()  # part of a head (or of the next one on a kept-alive connection)
        else:
            self._disarm_head()

    def on_response_complete(self) -> None:
        super().on_response_complete()  # the keep-alive timer now guards the idle connection
        self._disarm_head()

    def connection_lost(self, exc: Exception | None) -> None:
        self._disarm_head()
        super().connection_lost(exc)

    def _head_expired(self) -> None:
        self._head_timer = None
        if self.conn.their_state is h11.IDLE and not self.transport.is_closing():
            self.logger.info("closing a connection whose request head took over %g s", self.head_seconds)
            self.transport.close()


def uvicorn_config(app: Any, *, head_seconds: float = HEAD_SECONDS, keep_alive: int = KEEP_ALIVE_SECONDS,
                   max_connections: int = MAX_CONNECTIONS, **kwargs: Any) -> Any:
    """A ``uvicorn.Config`` for ``app`` with this module's limits (``kwargs`` pass through)."""
    import uvicorn

    protocol = type("HeadTimeoutProtocol", (HeadTimeoutProtocol,), {"head_seconds": float(head_seconds)})
    kwargs.setdefault("log_level", "warning")
    return uvicorn.Config(app, http=protocol, timeout_keep_alive=keep_alive, h11_max_incomplete_event_size=MAX_HEAD_BYTES,
                          limit_concurrency=max_connections, timeout_graceful_shutdown=GRACEFUL_SECONDS, **kwargs)
