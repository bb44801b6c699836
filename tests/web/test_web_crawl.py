"""Issue 30's acceptance crawl: Debian's chromium (Playwright) starts at ``/`` and follows every
same-origin link of a catalogue holding every family, with the polyominoes classified to 8
cells (533 result rows, names such as ``.x../xx../.x..``) and the k-uniform tilings to k = 3,
and finds no 4xx/5xx answer (pages, their images, scripts and style sheets, and the JSON, CSV,
SVG and PNG links), no console error (a Content-Security-Policy violation is one) and no page
wider than the window (a long D-symbol wraps).

The crawl is bounded (``TILEKIT_CRAWL_PAGES`` pages, 220 by default, and as many other links:
downloads, data views and the pictures' sources, fetched on their own)
and deduplicated; it prefers links of a kind it has seen least (a route and the query keys it
carries), so facets, sorting, numbered pages, table views, tiling pages, their region control
and run pages are all reached within the bound.
"""

from __future__ import annotations

import os
from urllib.parse import parse_qsl, urljoin, urlsplit

import pytest
from cliutil import serving

pytest.importorskip("playwright")
from playwright.sync_api import TimeoutError as PlaywrightTimeout  # noqa: E402

PAGES = int(os.environ.get("TILEKIT_CRAWL_PAGES", "220"))
WIDTH = 1280


@pytest.fixture(scope="module")
def full_site(tmp_path_factory):
    from tilekit import open_catalogue
    from tilekit.search import run_search
    from tilekit.web import create_app

    cat = open_catalogue(str(tmp_path_factory.mktemp("crawl") / "catalogue.sqlite"))
    run_search(cat, "polyomino-classify", {"max_cells": 8})
    for k in (1, 2, 3):
        run_search(cat, "k-uniform", {"k": k})
    # the crawl checks links, not capacity (tests/web/test_web_load.py does): thumbnails drawn
    # one at a time may wait longer than the default 20 s for a slot, and a table page asks for
    # more at once than the default queue (8) holds
    with serving(create_app(catalogue=cat, render_seconds=300, render_queue=64)) as url:
        yield cat, url
    cat.close()


def kind(url: str) -> tuple[str, frozenset[str]]:
    """What sort of link a URL is: its first path segment and the query keys it carries."""
    parts = urlsplit(url)
    first = "/" + parts.path.strip("/").split("/")[0]
    return first, frozenset(k for k, _ in parse_qsl(parts.query))


def is_file(url: str) -> bool:
    """A link that downloads or answers data rather than a page."""
    parts = urlsplit(url)
    query = dict(parse_qsl(parts.query))
    return (parts.path.startswith(("/api/", "/thumb/", "/static/")) or parts.path.endswith((".json", ".csv", ".svg"))
            or "download" in query or query.get("_format") in ("json", "csv"))


@pytest.mark.slow
def test_crawl_from_the_front_page_finds_no_error(full_site, browser):
    cat, base = full_site
    assert cat.count_result_rows("polyominoes") == 533  # A000105 to n = 8: 1+1+2+5+12+35+108+369
    # A068599: 20 2-uniform and 61 3-uniform tilings (22 + 39 by vertex types, tes-catalog)
    assert [cat.count_matching("k-uniform", [f"k={k}"]) for k in (2, 3)] == [20, 61]
    context = browser.new_context(base_url=base, viewport={"width": WIDTH, "height": 900})
    page = context.new_page()
    page.set_default_timeout(120_000)  # a page of 48 thumbnails on a loaded 2-core machine
    problems: list[str] = []
    here = {"url": "/"}
    page.on("console", lambda m: problems.append(f"console {m.type} on {here['url']}: {m.text}")
            if m.type == "error" else None)
    page.on("pageerror", lambda exc: problems.append(f"script error on {here['url']}: {exc}"))
    page.on("response", lambda r: problems.append(f"{r.status} for {r.url} (on {here['url']})")
            if r.status >= 400 else None)

    seen = {"/"}
    pending = ["/"]
    visits: dict[tuple[str, frozenset[str]], int] = {}
    pages = files = 0
    kinds = set()
    while pending and pages < PAGES:
        pending.sort(key=lambda u: visits.get(kind(u), 0))  # stable: the least seen kind, then first found
        url = pending.pop(0)
        visits[kind(url)] = visits.get(kind(url), 0) + 1
        if is_file(url):
            if files >= PAGES:
                continue
            r = context.request.get(url, timeout=120_000)  # may queue behind thumbnails, as pages do
            files += 1
            if r.status >= 400:
                problems.append(f"{r.status} for {url}")
            continue
        here["url"] = url
        answer = page.goto(url, wait_until="domcontentloaded")
        pages += 1
        kinds.add(kind(url)[0])
        assert answer is not None
        if answer.status >= 400:
            problems.append(f"{answer.status} for {url}")
            continue
        try:  # the pictures in view; those still loading are fetched below as links
            page.wait_for_load_state("load", timeout=15_000)
        except PlaywrightTimeout:
            pass
        wide = page.evaluate("document.documentElement.scrollWidth")
        if wide > WIDTH + 1:
            problems.append(f"{url} is {wide} px wide in a {WIDTH}-px window")
        for href in page.eval_on_selector_all("a[href], img[src]",
                                              "els => els.map(e => e.getAttribute('href') || e.getAttribute('src'))"):
            full = urljoin(base + url, href)
            if not full.startswith(base + "/"):
                continue
            rel = full[len(base):].split("#")[0]
            if rel and rel not in seen:
                seen.add(rel)
                pending.append(rel)
    context.close()
    assert not problems, "\n".join(problems[:20])
    assert pages == PAGES or not pending
    # the crawl reached every kind of page the site has
    assert {"/", "/tiling", "/family", "/families", "/runs"} <= kinds, kinds
