"""``tilekit serve``: the web app (tilekit.web) under uvicorn, loopback unless --host says otherwise."""

from __future__ import annotations

from typing import Any

import click

from tilekit.cli.base import (
    State,
    cli,
    pass_state,
)
from tilekit.cli_types import BoundedInt, FiniteFloat
from tilekit.errors import ParameterError
from tilekit.web import executor  # stdlib-only modules: the defaults shown in --help
from tilekit.web.cache import DEFAULT_CACHE_BYTES
from tilekit.web.limits import HEAD_SECONDS

# --------------------------------------------------------------------------- serve (issue 16)
# A self-contained block: the web catalogue and editor of tilekit.web (docs/web.md).


@cli.command()
@click.option("--host", default="127.0.0.1", show_default=True, help="Interface to bind (loopback unless told otherwise).")
@click.option("--port", default=8000, show_default=True, type=click.IntRange(min=0, max=65535), help="TCP port.")
@click.option("--writable", is_flag=True, help="Allow the write endpoints (cancel a run); read-only otherwise.")
@click.option("--max-tiles", default=20_000, show_default=True, type=click.IntRange(min=1), help="Tiles one render request may draw.")
@click.option("--allow-host", multiple=True, metavar="NAME",
              help="Another Host name to answer to (repeatable); others get 421 (DNS rebinding).")
@click.option("--render-workers", default=executor.DEFAULT_WORKERS, show_default=True, type=BoundedInt(0, 64),
              help="Worker processes that draw renders (0: in the request's thread, without a time budget).")
@click.option("--render-queue", default=executor.DEFAULT_QUEUE, show_default=True, type=BoundedInt(0, 1000),
              help="Renders that may wait for a worker; more get 503 with Retry-After.")
@click.option("--render-seconds", default=executor.DEFAULT_SECONDS, show_default=True, type=FiniteFloat(86_400, min=0.1),
              help="Wall-clock budget of one render (and of its wait for a worker); past it: 504.")
@click.option("--cache-mb", default=DEFAULT_CACHE_BYTES >> 20, show_default=True, type=BoundedInt(0, 1 << 20),
              help="Memory the render cache may hold (MiB).")
@click.option("--worker-mb", default=executor.DEFAULT_RECYCLE_BYTES >> 20, show_default=True, type=BoundedInt(64, 1 << 20),
              help="A render worker whose resident memory passes this (MiB) is replaced after its render.")
@click.option("--head-seconds", default=HEAD_SECONDS, show_default=True, type=FiniteFloat(3600, min=0.5),
              help="Seconds a client has to send a request's headers before the connection is closed.")
@pass_state
def serve(state: State, host: str, port: int, writable: bool, max_tiles: int, allow_host: tuple[str, ...],
          render_workers: int, render_queue: int, render_seconds: float, cache_mb: int, worker_mb: int,
          head_seconds: float) -> None:
    """Serve the web catalogue, tiling pages and the isohedral editor (needs the web extra).

    Example: tilekit serve --port 8000, then open http://127.0.0.1:8000/
    """
    from tilekit.errors import optional

    for module in ("starlette", "uvicorn"):  # the web extra, checked before anything starts
        optional(module, "web", "tilekit serve")
    import uvicorn

    from tilekit.web import create_app
    state.catalogue()  # open (and migrate) before binding: a bad catalogue is one line, exit 2
    sock = _listening_socket(host, port)  # a bad --host or a taken port: one line, exit 2
    app = create_app(state.url, writable=writable, max_tiles=max_tiles, catalogue=state.catalogue(),
                     bind_host=host, allow_hosts=allow_host, render_workers=render_workers,
                     render_queue=render_queue, render_seconds=render_seconds, cache_bytes=cache_mb << 20,
                     worker_bytes=worker_mb << 20)
    bound = sock.getsockname()[1]
    shown = f"[{host}]" if ":" in host else host
    click.echo(f"serving {state.catalogue().url} on http://{shown}:{bound}/ ({'writable' if writable else 'read-only'})", err=True)
    from tilekit.web.server import uvicorn_config

    uvicorn.Server(uvicorn_config(app, head_seconds=head_seconds)).run(sockets=[sock])


def _listening_socket(host: str, port: int) -> Any:
    """A TCP socket bound to ``host``:``port`` and listening, or a ParameterError naming
    the host or port and why (not an address, not this machine's, in use): uvicorn would
    otherwise log its own line and exit 3, or raise UnicodeError on a non-ASCII name."""
    import ipaddress
    import re
    import socket

    what = f"--host {host[:60]!r}"
    try:
        ipaddress.ip_address(host)
    except ValueError:
        if re.fullmatch(r"[0-9.]+", host):
            raise ParameterError(f"{what} is not an IPv4 address (four numbers 0..255, e.g. 127.0.0.1)") from None
        try:
            host.encode("idna")
        except UnicodeError:
            raise ParameterError(f"{what} is not a valid host name; give an IP address such as 127.0.0.1 "
                                 "or a name of letters, digits, '-' and '.'") from None
    try:
        family, kind, proto, _, address = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM,
                                                             flags=socket.AI_PASSIVE)[0]
    except (OSError, UnicodeError, ValueError) as exc:
        raise ParameterError(f"{what} cannot be resolved to an address of this machine "
                             f"({getattr(exc, 'strerror', None) or exc})") from None
    sock = socket.socket(family, kind, proto)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(address)
        sock.listen(2048)
    except OSError as exc:
        sock.close()
        raise ParameterError(f"cannot serve on {host}:{port}: {exc.strerror or exc}") from None
    return sock


# commands kept in their own module (keys, prototile), registered here
