"""Fixtures of the web tests: one seeded SQLite catalogue with a run, the app, a live server."""

from __future__ import annotations

import os

import pytest
from cliutil import serving

pytest.importorskip("starlette")


def _seed_run(cat) -> int:
    """A finished run with 30 JSON results, and a running one (for the live progress page)."""
    from tilekit.plugins import ChunkResult

    run_id = cat.create_run("demo", {"n": 3}, [{"i": i} for i in range(3)])
    owner = cat.start_worker(run_id, "web-tests")
    while True:
        got = cat.claim(run_id, owner, 3)
        if not got:
            break
        for index, _spec in got:
            rows = [{"chunk": index, "k": k, "label": f"<b>r{index}-{k}</b>"} for k in range(10)]
            cat.record_chunk(run_id, index, ChunkResult(results=rows, counts={"found": 10}), 0.01, owner=owner)
    cat.finish_worker(owner)
    cat.finish_run(run_id, "done", summary={"found": 30})
    return run_id


@pytest.fixture(scope="session")
def web_catalogue(tmp_path_factory):
    from tilekit import open_catalogue

    path = tmp_path_factory.mktemp("web") / "catalogue.sqlite"
    cat = open_catalogue(str(path))
    run_id = _seed_run(cat)
    cat.web_test_run = run_id  # type: ignore[attr-defined]
    yield cat
    cat.close()


@pytest.fixture(scope="session")
def species_catalogue(tmp_path_factory):
    """A catalogue with a finished vertex-species run, apart from ``web_catalogue``: the run's
    result rows share names with shipped records (``3^3.6^2``), which other files' tests of the
    shared catalogue must not meet. Yields (catalogue, run id)."""
    from tilekit import open_catalogue
    from tilekit.search import run_search

    cat = open_catalogue(str(tmp_path_factory.mktemp("species") / "catalogue.sqlite"))
    run_id = run_search(cat, "vertex-species")
    yield cat, run_id
    cat.close()


@pytest.fixture(scope="session")
def species_client(species_catalogue):
    from starlette.testclient import TestClient

    from tilekit.web import create_app

    with TestClient(create_app(catalogue=species_catalogue[0])) as c:
        yield c


@pytest.fixture(scope="session")
def app(web_catalogue):
    from tilekit.web import create_app

    return create_app(catalogue=web_catalogue)


@pytest.fixture(scope="session")
def client(app):
    from starlette.testclient import TestClient

    with TestClient(app) as c:
        yield c


@pytest.fixture(scope="session")
def live_server(app):
    """The session's app served (see :func:`serving`)."""
    with serving(app) as url:
        yield url


CHROMIUM = "/usr/bin/chromium"
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


@pytest.fixture(scope="session")
def browser():
    """Debian's chromium through Playwright (its own browser download is not used)."""
    if not os.path.exists(CHROMIUM):
        pytest.fail(f"the browser tests need {CHROMIUM}: README's test command installs it (.ci/services.sh)")
    from playwright import sync_api
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=FLAGS, headless=True)
        yield b
        b.close()


@pytest.fixture
def page(browser, live_server):
    context = browser.new_context(base_url=live_server, viewport={"width": 1280, "height": 900},
                                  accept_downloads=True)
    pg = context.new_page()
    errors: list[str] = []
    pg.on("pageerror", lambda exc: errors.append(str(exc)))
    pg.js_errors = errors  # type: ignore[attr-defined]
    yield pg
    context.close()
