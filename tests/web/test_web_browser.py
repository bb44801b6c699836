"""Browser tests: Debian's chromium driven by Playwright against uvicorn on 127.0.0.1.

A missing /usr/bin/chromium is a failure (see conftest.py); README's test command installs it
(.ci/services.sh).
"""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest

pytest.importorskip("playwright")


def outline(page) -> str:
    return page.eval_on_selector_all("#view svg path", "els => els.map(e => e.getAttribute('d')).join('|')")


def renders(page, selector: str = "#editor") -> int:
    return int(page.get_attribute(selector, "data-renders") or 0)


def wait_render(page, before: int, selector: str = "#editor") -> None:
    page.wait_for_function(
        f"n => Number(document.querySelector('{selector}').dataset.renders || 0) > n && "
        f"!document.querySelector('{selector}').dataset.busy", arg=before, timeout=20000)


def test_search_page_shows_thumbnails_for_a_filter(page):
    page.goto("/?family=archimedean&where=polygons%3D6")
    cards = page.locator("#grid .card")
    assert cards.count() == 6 and "6 matches" in page.inner_text("#count")
    page.wait_for_function("() => [...document.querySelectorAll('img.thumb')].every(i => i.complete && i.naturalWidth > 0)",
                           timeout=30000)
    assert set(page.eval_on_selector_all("#grid .card", "els => els.map(e => e.dataset.name)")) >= {"3.4.6.4", "6^3"}
    assert not page.js_errors


def test_tiling_page_shows_its_svg(page):
    page.goto("/tiling/IH16")
    assert page.locator("#figure svg").count() == 1
    assert page.locator("#figure svg path").count() >= 3
    assert "[a+b+c+c-b-a-; a-c+b+]" in page.inner_text("#describe")
    assert page.locator("#properties").inner_text().count("topology") == 1
    assert page.get_attribute("#dl-svg", "href") == "/api/render/IH16?download=1"


def test_editor_slider_changes_outline_and_export_downloads_svg(page, tmp_path):
    page.goto("/editor/IH16")
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    before = outline(page)
    n = renders(page)
    page.locator("#param-0").fill("0.3")
    wait_render(page, n)
    after = outline(page)
    assert after and after != before
    spec = json.loads(page.get_attribute("#editor", "data-spec"))
    assert spec["ih"] == 16 and abs(spec["params"][0] - 0.3) <= 0.001  # the slider's step

    # an edge control point: add one, then drag it; the tile outline follows
    n = renders(page)
    page.click(".edge .add-point")
    wait_render(page, n)
    shaped = outline(page)
    assert shaped != after
    handle = page.locator("#edge-b .handle").first
    box = handle.bounding_box()
    n = renders(page)
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.down()
    page.mouse.move(box["x"] + box["width"] / 2 + 10, box["y"] - 12, steps=4)
    page.mouse.up()
    wait_render(page, n)
    assert outline(page) != shaped
    assert '"edges"' in page.get_attribute("#editor", "data-spec")

    with page.expect_download() as dl:
        page.click("#export-svg")
    path = tmp_path / "export.svg"
    dl.value.save_as(path)
    root = ET.parse(path).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert len(root.findall(".//{http://www.w3.org/2000/svg}path")) >= 3
    with page.expect_download() as dl:
        page.click("#export-spec")
    spec = (tmp_path / "spec.json")
    dl.value.save_as(spec)
    data = json.loads(spec.read_text())
    assert data["spec"]["ih"] == 16 and "b" in data["spec"]["edges"]
    assert not page.js_errors


def test_editor_refuses_crossing_edges_with_the_reason(page):
    page.goto("/editor/IH12")
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    shown = outline(page)
    n = renders(page)
    page.locator("#param-0").fill(page.get_attribute("#param-0", "min"))  # v0 < 0: inside out
    wait_render(page, n)
    assert page.get_attribute("#editor", "data-state") == "refused"
    assert "IH12: parameters" in page.inner_text("#error") and "self-intersecting" in page.inner_text("#error")
    assert outline(page) == shown  # the last valid tiling stays on screen


def test_penrose_editor_refuses_self_intersection(page):
    page.goto("/penrose")
    page.wait_for_selector("#penrose[data-state=ok]", timeout=20000)
    before = outline(page)
    n = renders(page, "#penrose")
    page.locator("#r1").fill("0.3")
    wait_render(page, n, "#penrose")
    assert outline(page) != before
    for key, value in (("r1", "0.5"), ("theta1", "80"), ("r2", "0.5")):
        page.locator(f"#{key}").fill(value)
    page.wait_for_selector("#penrose[data-state=refused]", timeout=20000)
    assert "self-intersect" in page.inner_text("#error")


def test_hostile_query_string_is_shown_escaped(page):
    dialogs = []
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    evil = "<script>alert(1)</script>\"'><img src=x onerror=alert(2)>"
    page.goto("/", wait_until="load")
    page.goto("/?text=" + evil.replace("<", "%3C").replace(">", "%3E").replace('"', "%22").replace("'", "%27")
              .replace(" ", "%20") + "&where=name~%3Cscript%3E")
    assert page.input_value("input[name=text]") == evil
    assert page.input_value("input[name=where] >> nth=0") == "name~<script>"
    assert page.locator("img[src=x]").count() == 0 and page.locator("main script").count() == 0
    page.goto("/?where=%3Cscript%3Ealert(3)%3C/script%3E%3D1")
    assert "<script>alert(3)</script>" in page.inner_text("#error")
    page.wait_for_timeout(200)
    assert dialogs == [] and not page.js_errors


def test_run_page_live_progress(page, web_catalogue):
    from tilekit.plugins import ChunkResult

    cat = web_catalogue
    run_id = cat.create_run("demo", {"n": 2}, [{"i": 0}, {"i": 1}])
    owner = cat.start_worker(run_id, "browser-test")
    try:
        page.goto(f"/runs/{run_id}")
        assert page.inner_text("#status") == "running"
        for index, _ in cat.claim(run_id, owner, 2):
            cat.record_chunk(run_id, index, ChunkResult(results=[{"i": index}]), 0.01, owner=owner)
        cat.finish_worker(owner)
        cat.finish_run(run_id, "done")
        page.wait_for_function("() => document.querySelector('#status') && "
                               "document.querySelector('#status').textContent === 'done'", timeout=20000)
        page.wait_for_selector("#results td", timeout=20000)
        assert page.inner_text("#chunks") == "2/2"
    finally:
        cat.delete_run(run_id)


def test_editor_parquet_export(page, tmp_path):
    page.goto("/editor/IH61")
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    n = renders(page)
    page.click(".edge .add-point")
    wait_render(page, n)
    assert page.is_visible("#export-parquet")
    with page.expect_download() as dl:
        page.click("#export-parquet")
    path = tmp_path / "parquet.svg"
    dl.value.save_as(path)
    root = ET.parse(path).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert len(root.findall(".//{http://www.w3.org/2000/svg}path")) == 2  # one per colour
