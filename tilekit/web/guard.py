"""ASGI middleware against cross-site requests and DNS rebinding (docs/web.md, "Security and limits").

:class:`Guard` refuses, before the app sees the request:

- a ``Host`` header that is not the address or name the server is bound to (421): a page on
  ``evil.example`` whose name an attacker re-points at 127.0.0.1 sends ``Host: evil.example``;
- a state-changing request (POST, PUT, PATCH, DELETE) from another origin (403): a browser
  marks it with ``Sec-Fetch-Site: cross-site``/``same-site`` or an ``Origin`` that differs
  from the ``Host`` (the rule of Go's ``http.CrossOriginProtection``); a request with neither
  header does not come from a browser page and passes;
- a state-changing request whose body is not JSON (415): ``text/plain``, form and multipart
  bodies are what an HTML form on another site can send without a CORS preflight.
"""

from __future__ import annotations

import ipaddress
from collections.abc import Iterable
from typing import Any
from urllib.parse import urlsplit

from starlette.responses import JSONResponse

#: Methods that may change state; every other method is read-only in this app.
UNSAFE_METHODS = frozenset({"POST", "PUT", "PATCH", "DELETE"})
#: Host names a server bound to a loopback or wildcard address answers to besides its literal.
LOOPBACK_NAMES = ("localhost",)


def _host_name(value: str) -> str | None:
    """The host part of a ``Host`` header (``name``, ``name:port``, ``[v6]:port``), lower-case;
    None when it is not one."""
    value = value.strip().lower()
    if not value or any(c in value for c in "/@?# \t"):
        return None
    if value.startswith("["):
        end = value.find("]")
        rest = value[end + 1:] if end > 0 else None
        if rest is None or (rest and not (rest.startswith(":") and rest[1:].isdigit())):
            return None
        return value[1:end]
    name, _, port = value.partition(":")
    if port and not port.isdigit():
        return None
    return name.rstrip(".")


def _ip(name: str) -> ipaddress.IPv4Address | ipaddress.IPv6Address | None:
    try:
        return ipaddress.ip_address(name)
    except ValueError:
        return None


def allowed_hosts(bind_host: str, extra: Iterable[str] = ()) -> tuple[frozenset[str], bool]:
    """(names, any_ip): the Host names a server bound to ``bind_host`` answers to, and whether
    any IP literal is accepted (a wildcard bind such as 0.0.0.0 serves every local address;
    DNS rebinding needs a name, never a literal)."""
    bind = bind_host.strip().lower().strip("[]")
    names = {bind, *(e.strip().lower().rstrip(".") for e in extra if e.strip())}
    ip = _ip(bind)
    any_ip = ip is not None and ip.is_unspecified
    if ip is None or ip.is_loopback or any_ip:
        names.update(LOOPBACK_NAMES)
    if ip is not None and (ip.is_loopback or any_ip):
        names.update({"127.0.0.1", "::1"})
    return frozenset(names), any_ip


class Guard:
    """The checks of this module's docstring around an ASGI app. ``bind_host=None`` leaves
    the Host check to whoever binds the socket (an embedding server); ``tilekit serve``
    passes its ``--host`` (and ``--allow-host`` names)."""

    def __init__(self, app: Any, bind_host: str | None = None, allow_hosts: Iterable[str] = ()) -> None:
        self.app = app
        self.hosts: frozenset[str] | None = None
        self.any_ip = False
        if bind_host is not None:
            self.hosts, self.any_ip = allowed_hosts(bind_host, allow_hosts)

    def host_ok(self, host: str | None) -> bool:
        if self.hosts is None:
            return True
        name = _host_name(host or "")
        if name is None:
            return False
        if name in self.hosts:
            return True
        return self.any_ip and _ip(name) is not None

    async def __call__(self, scope: dict, receive: Any, send: Any) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers: dict[bytes, bytes] = {}
        for key, value in scope.get("headers", []):
            headers.setdefault(key, value)
        host = headers.get(b"host", b"").decode("latin-1")
        problem = None
        if not self.host_ok(host):
            valid = ", ".join(sorted(self.hosts or ())) + (" or an IP address" if self.any_ip else "")
            problem = (421, f"Host {host[:80]!r} is not a name this server answers to ({valid}); "
                            "start tilekit serve with --allow-host NAME to add one")
        elif scope["method"] in UNSAFE_METHODS:
            problem = self.cross_origin(headers, host) or self.body_type(headers)
        if problem is not None:
            response = JSONResponse({"error": problem[1], "status": problem[0]}, status_code=problem[0])
            await response(scope, receive, send)
            return
        await self.app(scope, receive, send)

    @staticmethod
    def cross_origin(headers: dict[bytes, bytes], host: str) -> tuple[int, str] | None:
        site = headers.get(b"sec-fetch-site", b"").decode("latin-1").strip().lower()
        if site:
            if site in ("same-origin", "none"):
                return None
            return 403, f"cross-origin request refused (Sec-Fetch-Site: {site[:20]}); writes come only from this site's own pages"
        origin = headers.get(b"origin")
        if origin is None:
            return None  # not sent by a browser page: a command-line client or a script
        text = origin.decode("latin-1").strip()
        parts = urlsplit(text) if text != "null" else None
        if parts is None or parts.scheme not in ("http", "https") or parts.netloc.lower() != host.strip().lower():
            return 403, f"cross-origin request refused (Origin {text[:80]!r} is not this server's {host[:80]!r})"
        return None

    @staticmethod
    def body_type(headers: dict[bytes, bytes]) -> tuple[int, str] | None:
        raw = headers.get(b"content-type")
        if raw is None:
            return None  # no body type: a body, if any, is read as JSON
        kind = raw.decode("latin-1").split(";")[0].strip().lower()
        if kind == "application/json" or (kind.startswith("application/") and kind.endswith("+json")):
            return None
        return 415, f"request body of type {kind[:60]!r} refused; send application/json"
