"""Families bring their own web pages (issue 29): the demo third-party plugin of
tests/data/tilekit-demo-family adds a page, a menu link, a link from its tilings' pages, result
cells that link to its page, and a script, through the tilekit_web_* hooks; tilekit.web names
no family. The built-in editors arrive the same way (test_web_api, test_web_browser)."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

pytest.importorskip("starlette")

DEMO_SRC = Path(__file__).parents[1] / "data" / "tilekit-demo-family" / "src"


@pytest.fixture(scope="module")
def demo_app(tmp_path_factory):
    """An app over a catalogue whose plugin manager has the built-in families and the demo
    family (imported from its source folder, as pip would register its entry point), with a
    finished brick-sizes run."""
    from tilekit import open_catalogue
    from tilekit.plugins import make_plugin_manager
    from tilekit.search import run_search
    from tilekit.web import create_app

    sys.path.insert(0, str(DEMO_SRC))
    try:
        import tilekit_demo_family

        pm = make_plugin_manager(extra_plugins=[tilekit_demo_family])
        cat = open_catalogue(str(tmp_path_factory.mktemp("demo-web") / "catalogue.sqlite"), pm=pm)
        run_id = run_search(cat, "brick-sizes", {"max_area": 6}, pm=pm)
        app = create_app(catalogue=cat)
        app.demo_run = run_id  # type: ignore[attr-defined]
        yield app
        cat.close()
    finally:
        sys.path.remove(str(DEMO_SRC))
        sys.modules.pop("tilekit_demo_family", None)


@pytest.fixture(scope="module")
def demo_client(demo_app):
    from starlette.testclient import TestClient

    with TestClient(demo_app) as c:
        yield c


@pytest.fixture(scope="module")
def demo_server(demo_app):
    from cliutil import serving

    with serving(demo_app) as url:
        yield url


def test_the_plugin_page_draws_a_valid_wall(demo_client):
    r = demo_client.get("/bricks", params={"a": 3, "b": 1, "shift": 0.25})
    assert r.status_code == 200 and "text/html" in r.headers["content-type"]
    assert "Brick wall 3 x 1, rows shifted by 0.25" in r.text
    # the page is in the site's layout, with every plugin's menu link (built-in ones first)
    nav = re.search(r"<nav>(.*?)</nav>", r.text, re.S).group(1)
    assert re.findall(r'href="([^"]+)"', nav) == ["/", "/families", "/runs", "/editor", "/penrose", "/multigrid",
                                                      "/curved?p=7&amp;q=3", "/bricks", "/api"]
    # the wall it draws is a tiling: the same patch passes the core's gap/overlap check
    from tilekit_demo_family import PAGE_BRICKS, BrickWall

    wall = BrickWall(3, 1, 0.25)
    region = (0.0, 0.0, PAGE_BRICKS * 3.0, PAGE_BRICKS * 1.0)
    patch = wall.patch(region)
    assert patch.validate(region).ok
    assert f'data-bricks="{len(patch)}"' in r.text


@pytest.mark.parametrize("query, message", [
    ({"a": -1}, "brick sides must be positive"),
    ({"shift": 1.5}, "shift must be in [0, 1)"),
    ({"a": "x"}, "a, b and shift are numbers"),
    ({"a": "inf"}, "the numbers must be finite"),
    ({"a": 5000, "b": 1}, "the sides may be at most 1000 times apart"),
])
def test_a_bad_query_is_the_sites_error_page(demo_client, query, message):
    r = demo_client.get("/bricks", params=query)
    assert r.status_code == 400
    assert 'id="error"' in r.text and message in r.text.replace("&#x27;", "'")


def test_tiling_page_and_result_rows_link_to_the_plugin_page(demo_client, demo_app):
    page = demo_client.get("/tiling/running-bond").text
    assert re.search(r'<a id="edit" href="/bricks\?a=2&amp;b=1&amp;shift=0.5">open in the brick wall page</a>', page)
    # an isohedral tiling's page offers the isohedral editor only
    iso = demo_client.get("/tiling/IH16").text
    assert re.findall(r'<a id="edit[^"]*" href="([^"]+)"', iso) == ["/editor/IH16"]
    run = demo_client.get(f"/runs/{demo_app.demo_run}").text
    # brick-sizes up to area 6: 1x1, 2x1, 3x1, 4x1, 2x2, 5x1, 6x1, 3x2 (a >= b, a * b <= 6)
    links = re.findall(r'<a class="brick" href="([^"]+)">([^<]+)</a>', run)
    assert sorted(n for _, n in links) == sorted(
        f"bricks-{a}x{b}-0.5" for a, b in [(1, 1), (2, 1), (3, 1), (4, 1), (2, 2), (5, 1), (6, 1), (3, 2)])
    assert all(href == f"/bricks?a={n.split('-')[1].split('x')[0]}&amp;b={n.split('x')[1].split('-')[0]}&amp;shift=0.5"
               for href, n in links)


def test_the_plugin_script_is_served_from_its_package(demo_client):
    r = demo_client.get("/static/plugins/demo_bricks/bricks.js")
    assert r.status_code == 200 and "bricks drawn" in r.text
    assert demo_client.get("/static/plugins/demo_bricks/../../style.css").status_code in (200, 404)
    assert demo_client.get("/static/plugins/demo_bricks/nothing.js").status_code == 404


def test_chromium_opens_the_plugin_page_from_the_menu(browser, demo_server):
    context = browser.new_context(base_url=demo_server, viewport={"width": 1280, "height": 900})
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    try:
        page.goto("/")
        page.click("nav >> text=brick walls")
        page.wait_for_selector("#wall svg")
        assert page.evaluate("location.pathname") == "/bricks"
        assert page.text_content("#bricks-title") == "Brick wall 2 x 1, rows shifted by 0.5"
        # the plugin's own script ran (served from its package at /static/plugins/demo_bricks/)
        page.wait_for_function("() => document.getElementById('count').textContent.endsWith('bricks drawn')")
        drawn = int(page.get_attribute("#wall", "data-bricks"))
        assert drawn > 0 and page.text_content("#count") == f"{drawn} bricks drawn"
        # from a tiling's page to the plugin page
        page.goto("/tiling/running-bond")
        page.click("#edit")
        page.wait_for_selector("#wall svg")
        assert page.evaluate("location.pathname + location.search") == "/bricks?a=2&b=1&shift=0.5"
        assert errors == []
    finally:
        context.close()


def test_a_plugin_naming_a_missing_static_folder_is_one_plugin_error(tmp_path):
    """A plugin whose tilekit_web_static names no folder (a package installed without its data,
    or half uninstalled) stops the app with one line naming the plugin and the folder, not
    Starlette's RuntimeError from deep inside the app's construction."""
    import tilekit
    from tilekit import open_catalogue
    from tilekit.errors import PluginError
    from tilekit.plugins import make_plugin_manager
    from tilekit.web import create_app

    missing = tmp_path / "gone" / "static"

    class NoStatic:
        @tilekit.hookimpl
        def tilekit_web_static(self):
            return [("nostatic", missing)]

    pm = make_plugin_manager(extra_plugins=[NoStatic()])
    cat = open_catalogue(f"sqlite:///{tmp_path / 'c.sqlite'}", pm=pm, seed=False)
    try:
        with pytest.raises(PluginError) as err:
            create_app(catalogue=cat)
    finally:
        cat.close()
    assert "\n" not in str(err.value) and "'nostatic'" in str(err.value) and str(missing) in str(err.value)
