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


def test_multigrid_offsets_slide_the_grids(page):
    """The quasiperiodic plugin's page (through tilekit_web_routes): a slider per offset of the
    chosen record (five for the pentagrid, four for the 4-grid of n = 8); moving one re-forms
    the rhombs; offsets whose lines meet three at a point are refused with the reason."""
    page.goto("/multigrid?name=multigrid-5")
    page.wait_for_selector("#multigrid[data-state=ok]", timeout=20000)
    assert page.locator("#offsets input").count() == 5
    before = outline(page)
    n = renders(page, "#multigrid")
    page.locator("#gamma0").fill("0.5")
    wait_render(page, n, "#multigrid")
    assert outline(page) != before and page.get_attribute("#multigrid", "data-gamma").startswith("0.5,")
    for j in range(5):
        page.locator(f"#gamma{j}").fill("0")
    page.wait_for_selector("#multigrid[data-state=refused]", timeout=20000)
    assert "singular" in page.inner_text("#error")
    n = renders(page, "#multigrid")
    page.select_option("#tiling", "multigrid-8")
    wait_render(page, n, "#multigrid")
    assert page.locator("#offsets input").count() == 4
    assert not page.js_errors


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


# --------------------------------------------------------------------------- the editor's URL

#: A non-default IH21 (edges S J J J J; shape classes a (S), b and d (J)) with 17-digit params.
IH21_SPEC = {"ih": 21, "params": [0.11, 0.6600000000000001],
             "edges": {"a": "0,0:0.3,0.15:0.6,0.1:1,0", "b": "0,0:0.5,0.1:1,0", "d": "0,0:0.25,-0.05:0.4,-0.08:1,0"}}


def svg_paths(svg: str) -> str:
    root = ET.fromstring(svg)
    return "|".join(p.get("d") for p in root.iter("{http://www.w3.org/2000/svg}path"))


def page_spec(page) -> dict:
    return json.loads(page.get_attribute("#editor", "data-spec"))


def test_editor_opens_the_tiling_its_url_configures(page, tmp_path):
    from urllib.parse import parse_qs, urlsplit

    from tilekit.plugins.isohedral.engine import unmarked_from_spec
    from tilekit.plugins.isohedral.spec import editor_path, editor_query

    expected = unmarked_from_spec(IH21_SPEC).spec()
    renders_asked: list[str] = []
    page.on("request", lambda r: renders_asked.append(r.url) if "/api/render/" in r.url else None)
    page.goto(editor_path(IH21_SPEC))
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    assert page_spec(page) == expected
    # the page's spec is the API's for the same query
    api = page.request.get(f"/api/tiling/IH21/spec?{editor_query(IH21_SPEC)}").json()
    assert api["spec"] == expected
    # the sliders show the values (chromium serialises a range input's value to ~15 digits;
    # the exact ones are the page's spec above), the edge widgets the control points (S: half)
    assert [float(page.input_value(f"#param-{i}")) for i in range(2)] == pytest.approx(expected["params"], abs=1e-14)
    assert page.inner_text("#params") == "v0 0.11\nv1 0.66"
    for label, scale in (("a", 0.5), ("b", 1.0), ("d", 1.0)):
        interior = [tuple(map(float, p.split(","))) for p in expected["edges"][label].split(":")[1:-1]]
        handles = page.eval_on_selector_all(f"#edge-{label} .handle",
                                            "els => els.map(e => [Number(e.getAttribute('cx')), Number(e.getAttribute('cy'))])")
        assert handles == [[scale * x, scale * y] for x, y in interior]
    assert page.inner_text("#error") == ""
    # the tiling drawn is /api/render's for the same query and the page's region and size
    asked = parse_qs(urlsplit(renders_asked[-1]).query)
    assert asked["params"] == ["0.11,0.6600000000000001"] and len(asked["edge"]) == 3
    ref = page.request.get(f"/api/render/IH21?{editor_query(IH21_SPEC)}&region={asked['region'][0]}"
                           "&size=720&format=json").json()
    assert ref["spec"] == expected and outline(page) == svg_paths(ref["svg"])
    # the address bar and the link name the tiling on screen; the link reopens it
    link = page.get_attribute("#permalink", "href")
    assert link.startswith("/editor/IH21?params=0.11,0.6600000000000001&edge=a=0,0:0.3,0.15:0.6,0.1:1,0&")
    assert page.evaluate("location.pathname + location.search") == link
    # export spec writes the same spec
    with page.expect_download() as dl:
        page.click("#export-spec")
    dl.value.save_as(tmp_path / "spec.json")
    assert json.loads((tmp_path / "spec.json").read_text())["spec"] == expected

    # an edit moves the link; the link opens the edited tiling
    n = renders(page)
    page.locator("#param-0").fill("0.12")
    wait_render(page, n)
    edited = page_spec(page)
    assert edited["params"] == [0.12, 0.6600000000000001] and edited["edges"] == expected["edges"]
    link = page.get_attribute("#permalink", "href")
    assert "params=0.12,0.6600000000000001&" in link
    assert page.evaluate("location.pathname + location.search") == link
    page.goto(link)
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    assert page_spec(page) == edited
    # reset returns to the type's defaults (not the URL's tiling), and so does the address
    n = renders(page)
    page.click("#reset")
    wait_render(page, n)
    assert page_spec(page) == {"ih": 21, "params": [0.104512294489, 0.65]}
    assert page.evaluate("location.pathname + location.search") == "/editor/IH21"
    assert not page.js_errors


@pytest.mark.parametrize("query", ["params=0.1,abc", "edge=b=0,0:0.5,3:1,0"], ids=["unparsable", "refused"])
def test_editor_url_the_api_refuses_shows_its_line_and_the_defaults(page, query):
    line = page.request.get(f"/api/tiling/IH21/spec?{query}").json()["error"]
    assert line.startswith(("params 'abc'", "IH21: edge 2 (label 'b') and edge 4 (label 'd') cross"))
    page.goto(f"/editor/IH21?{query}")
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    assert page.inner_text("#error") == line
    default = {"ih": 21, "params": [0.104512294489, 0.65]}
    assert page_spec(page) == default
    assert [float(page.input_value(f"#param-{i}")) for i in range(2)] == default["params"]
    assert page.locator("#edges .handle").count() == 0
    ref = page.request.get("/api/render/IH21?format=json&size=720&region="
                           + page.evaluate("new URL(document.getElementById('export-svg').href).searchParams"
                                           ".get('region')")).json()
    assert outline(page) == svg_paths(ref["svg"])
    # the address falls back to the defaults too; the next valid edit clears the line
    assert page.evaluate("location.pathname + location.search") == "/editor/IH21"
    n = renders(page)
    page.locator("#param-1").fill("0.66")
    wait_render(page, n)
    assert page.inner_text("#error") == "" and page_spec(page)["params"] == [0.104512294489, 0.66]
    assert not page.js_errors
