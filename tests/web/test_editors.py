"""The editors as a user meets them (issue 30's "Editors" items): the type picker shows each
isohedral type's picture grouped by topology, the Penrose r sliders reach only admissible
values, exports after a refused edit give the last tiling drawn, drags put no float noise in
the URL, a rotated view has no blank corners, and a 420-px-wide screen keeps the tiling usable."""

from __future__ import annotations

import io
import json
import re
from urllib.parse import parse_qsl, urlsplit

import numpy as np
import pytest
from test_editor_split import drag
from test_web_browser import renders, wait_render

from tilekit.errors import ParameterError
from tilekit.plugins.isohedral.engine import IsohedralTiling
from tilekit.plugins.isohedral.templates import get_template
from tilekit.plugins.isohedral.web import picture_edges
from tilekit.plugins.substitution import quasivertex as qv

#: Grünbaum and Shephard number the isohedral types by topological type (Tilings and Patterns,
#: §6.2; Kaplan 2009, Appendix A): IH1-20 [3^6], IH21 [3^4.6], IH22-26 [3^3.4^2], IH27-29
#: [3^2.4.3.4], IH30-32 [3.4.6.4], IH33-37 [3.6.3.6], IH38-40 [3.12^2], IH41-76 [4^4], IH77
#: [4.6.12], IH78-82 [4.8^2], IH83-93 [6^3]: the 11 Laves tilings. The picker leaves out the
#: 12 marked types (IH19, 35, 48, 60, 63, 65, 70, 75, 80, 87, 89, 92).
TOPOLOGIES = [("3^6", 1, 20), ("3^4.6", 21, 21), ("3^3.4^2", 22, 26), ("3^2.4.3.4", 27, 29), ("3.4.6.4", 30, 32),
              ("3.6.3.6", 33, 37), ("3.12^2", 38, 40), ("4^4", 41, 76), ("4.6.12", 77, 77), ("4.8^2", 78, 82),
              ("6^3", 83, 93)]
MARKED = {19, 35, 48, 60, 63, 65, 70, 75, 80, 87, 89, 92}


def test_editor_picker_shows_each_types_picture_grouped_by_topology(client):
    html = client.get("/editor").text
    sections = re.findall(r'<section class="topology" data-topology="([^"]+)">(.*?)</section>', html, re.S)
    assert [t for t, _ in sections] == [t for t, _, _ in TOPOLOGIES]
    for (topology, body), (_, lo, hi) in zip(sections, TOPOLOGIES, strict=True):
        ihs = [int(i) for i in re.findall(r'href="/editor/IH(\d+)"', body)]
        assert ihs == [i for i in range(lo, hi + 1) if i not in MARKED]
        assert all(get_template(i).topology == topology for i in ihs)
        assert re.findall(r'src="/editor/picture/IH(\d+)\.svg"', body) == [str(i) for i in ihs]
    assert len(re.findall(r'class="ih-card"', html)) == 81
    for ih in (1, 21, 41, 93):  # a picture of each of a few groups is served
        r = client.get(f"/editor/picture/IH{ih}.svg")
        assert r.status_code == 200 and r.headers["content-type"].startswith("image/svg+xml") and "<path" in r.text
    assert client.get("/editor/picture/IH19.svg").status_code == 400  # a marked type: no template


def test_every_types_picture_is_a_valid_tiling_showing_its_edge_kinds():
    """The picker's shape on every J, U and S edge gives each of the 81 unmarked types a valid
    tiling (Patch.validate) whose tile differs from the straight one exactly when the type has
    a non-I edge (IH types with only I edges keep the Laves tile)."""
    for ih in range(1, 94):
        if ih in MARKED:
            continue
        base = IsohedralTiling(ih)
        edges = picture_edges(base)
        tiling = base.configure(edges=edges)
        region = tiling.default_region()
        assert tiling.patch(region).validate(region).ok, ih
        straight = len(np.asarray(base.prototile.outline))
        assert (len(np.asarray(tiling.prototile.outline)) > straight) == bool(edges), ih


# --------------------------------------------------------------------------- Penrose r ranges


def test_penrose_r_ranges_are_the_admissible_values(client):
    """The r1 slider's end is where a rhomb starts to self-intersect, computed for the other
    three parameters: valid at the end, refused just past it, and different for another θ1."""
    body = client.get("/api/penrose/range", params={"r1": 0.15, "theta1": 20, "r2": 0.1, "theta2": -15}).json()
    lo, hi = body["r1"]
    assert lo == 0.0 and 0.3 < hi < 1.0
    qv.validate_params(qv.QuasivertexParams(hi, 20, 0.1, -15))
    with pytest.raises(ParameterError, match="self-intersect"):
        qv.validate_params(qv.QuasivertexParams(hi + 0.0012, 20, 0.1, -15))  # step 0.001 + bisection 1e-4
    page = client.get("/penrose").text
    assert re.search(rf'id="r1" min="0" max="{hi:g}" step="0.001"', page)
    other = client.get("/api/penrose/range", params={"r1": 0.1, "theta1": -30, "r2": 0.1, "theta2": -15}).json()
    assert other["r1"][1] < hi
    qv.validate_params(qv.QuasivertexParams(other["r1"][1], -30, 0.1, -15))
    with pytest.raises(ParameterError):
        qv.validate_params(qv.QuasivertexParams(other["r1"][1] + 0.0012, -30, 0.1, -15))
    bad = client.get("/api/penrose/range", params={"r1": "x"})
    assert bad.status_code == 400 and "r1" in bad.json()["error"]


pytest.importorskip("playwright")


def test_penrose_slider_stops_at_the_admissible_end_and_exports_the_last_tiling(page, tmp_path):
    page.goto("/penrose")
    page.wait_for_selector("#penrose[data-state=ok]", timeout=20000)
    top = page.get_attribute("#r1", "max")
    n = renders(page, "#penrose")
    page.locator("#r1").fill("1")  # past the end: the slider stays at the admissible end
    wait_render(page, n, "#penrose")
    assert page.input_value("#r1") == top and page.get_attribute("#penrose", "data-state") == "ok"
    drawn = json.loads(page.request.get(page.get_attribute("#export-spec", "href")).text())["spec"]
    page.locator("#theta1").fill("-30")  # with r1 at its end for θ1 = 20, θ1 = -30 is refused
    page.wait_for_selector("#penrose[data-state=refused]", timeout=20000)
    assert "self-intersect" in page.inner_text("#error") and "last tiling drawn" in page.inner_text("#error")
    with page.expect_download() as dl:
        page.click("#export-spec")
    path = tmp_path / "p3.json"
    dl.value.save_as(path)
    spec = json.loads(path.read_text())["spec"]
    assert spec == drawn and spec["r1"] == float(top) and spec["theta1"] == 20
    assert not page.js_errors


# --------------------------------------------------------------------------- isohedral editor


def test_dragged_values_reach_the_url_with_fixed_decimals(page):
    page.goto("/editor/IH16")
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    box = page.locator("#param-0").bounding_box()
    n = renders(page)
    page.mouse.click(box["x"] + 0.37 * box["width"], box["y"] + box["height"] / 2)
    wait_render(page, n)
    page.click(".edge .add-point")
    n = renders(page)
    drag(page, "#edge-b .handle >> nth=0", 7.3, -5.1, panel="#edge-b")
    wait_render(page, n)
    query = dict(parse_qsl(urlsplit(page.evaluate("location.href")).query))
    numbers = re.findall(r"-?\d+(?:\.\d+)?", query["params"] + " " + query["edge"].split("=", 1)[1])
    assert len(numbers) >= 7 and all(len(x.partition(".")[2]) <= 4 for x in numbers), query
    spec = json.loads(page.get_attribute("#editor", "data-spec"))
    assert spec["params"][0] == float(query["params"])
    assert not page.js_errors


def corner_pixels(page) -> list[tuple[int, ...]]:
    from PIL import Image

    img = Image.open(io.BytesIO(page.locator("#view").screenshot())).convert("RGB")
    w, h = img.size
    return [img.getpixel((x, y)) for x in (3, w - 4) for y in (3, h - 4)]


@pytest.mark.parametrize("angle", [30, 45, -60])
def test_rotated_view_has_no_blank_corners(page, angle):
    """IH16's default tiles are filled in the palette's colours (none white): every corner of
    the turned view shows a tile."""
    page.goto("/editor/IH16")
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    assert all(p != (255, 255, 255) for p in corner_pixels(page))
    n = renders(page)
    page.locator("#rotate").fill(str(angle))
    wait_render(page, n)
    assert all(p != (255, 255, 255) for p in corner_pixels(page)), corner_pixels(page)
    assert not page.js_errors


def test_a_420_px_screen_keeps_the_tiling_usable(browser, live_server):
    context = browser.new_context(base_url=live_server, viewport={"width": 420, "height": 860}, is_mobile=True,
                                  has_touch=True)
    page = context.new_page()
    try:
        page.goto("/editor/IH41")
        page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
        view = page.locator("#view").bounding_box()
        assert view["width"] >= 340 and view["height"] >= 340 and view["y"] < 400  # above the controls
        assert page.evaluate("document.documentElement.scrollWidth") <= 420  # no sideways scrolling
        n = renders(page)
        page.locator("#param-0").fill("0.3")  # the controls below still work
        wait_render(page, n)
        assert page.get_attribute("#editor", "data-state") == "ok"
        page.goto("/penrose")
        page.wait_for_selector("#penrose[data-state=ok]", timeout=20000)
        assert page.locator("#view").bounding_box()["width"] >= 340
    finally:
        context.close()


# --------------------------------------------------------------------------- Penrose editor on P2


def test_penrose_editor_serves_the_kite_and_dart(client):
    """/penrose?tiling=p2 edits penrose-p2 (the page names its system for the script); its r
    ranges are the kite and dart's admissible values, not the rhombs'; a bad tiling is one line."""
    page = client.get("/penrose", params={"tiling": "p2"}).text
    assert 'data-system="penrose-p2"' in page and "kite and dart" in page
    body = client.get("/api/penrose/range", params={"tiling": "p2", "r1": 0.15, "theta1": 20, "r2": 0.1,
                                                    "theta2": -15}).json()
    assert body["system"] == "penrose-p2"
    hi = body["r1"][1]
    qv.validate_params(qv.QuasivertexParams(hi, 20, 0.1, -15), "penrose-p2")
    with pytest.raises(ParameterError, match="self-intersect"):
        qv.validate_params(qv.QuasivertexParams(hi + 0.0012, 20, 0.1, -15), "penrose-p2")
    p3 = client.get("/api/penrose/range", params={"r1": 0.15, "theta1": 20, "r2": 0.1, "theta2": -15}).json()
    assert p3["r1"] != body["r1"]
    bad = client.get("/api/penrose/range", params={"tiling": "p7"})
    assert bad.status_code == 400 and "valid: p3, p2" in bad.json()["error"]
    assert "/penrose?tiling=p2" in client.get("/tiling/penrose-p2").text


def test_penrose_editor_on_p2_draws_and_exports_a_spec_that_reopens(page, tmp_path):
    """In chromium: the P2 editor draws, follows a slider, and its exported spec rebuilds the
    same kite and dart (a validated patch with the §6.3 pairs on every shared piece)."""
    from tilekit.plugins.substitution import from_spec

    page.goto("/penrose?tiling=p2")
    page.wait_for_selector("#penrose[data-state=ok]", timeout=20000)
    n = renders(page, "#penrose")
    page.locator("#theta2").fill("-30")
    wait_render(page, n, "#penrose")
    assert page.get_attribute("#penrose", "data-state") == "ok"
    with page.expect_download() as dl:
        page.click("#export-spec")
    path = tmp_path / "p2.json"
    dl.value.save_as(path)
    spec = json.loads(path.read_text())["spec"]
    assert spec["system"] == "penrose-p2" and spec["theta2"] == -30
    rebuilt = from_spec(spec)
    assert [len(p.outline) for p in rebuilt.prototiles] == [10, 10]
    patch = rebuilt.patch((-3.0, -3.0, 3.0, 3.0))
    assert patch.validate((-2.0, -2.0, 2.0, 2.0))
    assert qv.matching_report(patch).ok
    assert not page.js_errors
