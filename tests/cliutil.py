"""Helpers the tests share by import (tests/ is on sys.path through its conftest.py): a
module of its own, because ``from conftest import ...`` finds whichever conftest.py was
loaded last (tests/web has one too)."""

from __future__ import annotations

import contextlib
import os
import socket
import threading
import time

import pytest

ENV = "TILEKIT_TEST_POSTGRES"


def assert_one_line_error(result, fragment: str = "") -> None:
    """A click result that failed the project's way: exit 2, one stderr line ``error: ...``
    containing ``fragment``, no traceback."""
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr
    assert "Traceback" not in result.output
    assert fragment in lines[0], lines[0]


def postgres_server(config) -> str | None:
    return config.getoption("--postgres") or os.environ.get(ENV) or None


class CatalogueCLI:
    """The command line on one fresh SQLite catalogue: ``run(*args)`` invokes it in-process,
    ``count(family, *where)`` is ``tilekit list --family F --count --where ...`` as an int."""

    def __init__(self, url: str) -> None:
        self.url = url

    def run(self, *args: str):
        from click.testing import CliRunner

        from tilekit.cli import cli

        return CliRunner().invoke(cli, ["--catalogue", self.url, *args], catch_exceptions=False)

    def count(self, family: str, *where: str) -> int:
        args = ["list", "--family", family, "--count"]
        for w in where:
            args += ["--where", w]
        r = self.run(*args)
        assert r.exit_code == 0, r.output
        return int(r.output.split()[-1])


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def serving(app, make_config=None):
    """uvicorn on 127.0.0.1 with a free port, in a thread; yields the base URL.
    ``make_config(app, host=, port=)`` builds the uvicorn.Config (default: uvicorn's own)."""
    import uvicorn

    port = free_port()
    if make_config is None:
        config = uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning")
    else:
        config = make_config(app, host="127.0.0.1", port=port)
    server = uvicorn.Server(config)
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 20
    while not server.started:
        if time.monotonic() > deadline or not thread.is_alive():
            pytest.fail("uvicorn did not start within 20 s")
        time.sleep(0.05)
    try:
        yield f"http://127.0.0.1:{port}"
    finally:
        server.should_exit = True
        thread.join(10)
