"""The curved tile editor (/curved/edit/NAME, issue 35 item 3): Escher-like tiles on the sphere
and the hyperbolic plane shaped in the browser. The API builds the tiling through the family's
``edges`` option (the same EdgeShape text per label), so what it sends is checked against the
family's own tiling; its URL reopens the tiling exactly; bad edits are 400s with one line. In
chromium a handle dragged in an edge widget moves the drawn tile's edge point the way it moved
(into the tile), and the partner edge repeats it (the hop's image), while the server-side
tiling stays valid (``Patch.validate``)."""

from __future__ import annotations

import shlex
from urllib.parse import quote

import numpy as np
import pytest
from test_curved_viewer import corners

from tilekit.incidence import shape_classes
from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling
from tilekit.plugins.curved.shaped import chart
from tilekit.plugins.curved.web import edge_query

# [a+b+c+d+e+; a+b-d+c+e-] on {5,4}: edge 1 an S edge (a), edges 3 and 4 a J pair (c, d)
IH = "curved-ih-5-4-5"
SYMBOL = "[a+b+c+d+e+; a+b-d+c+e-]"
SHAPES = {"a": "0,0:0.2,0.1:0.35,0.05:1,0", "c": "0,0:0.3,0.2:0.6,-0.1:1,0"}


def _query(shapes: dict[str, str]) -> str:
    return "&".join("edge=" + quote(f"{k}={v}", safe=",:=") for k, v in shapes.items())


def _faces(body: dict) -> list[np.ndarray]:
    pts = np.array(body["points"]).reshape(-1, 3)
    bounds = np.cumsum([0, *body["sizes"]])
    return [pts[a:b] for a, b in zip(bounds[:-1], bounds[1:])]


def test_editor_data_is_the_family_tiling_shaped_by_the_query(client):
    """One widget per shape class of the incidence symbol (I edges none), with the kinds of
    §5.3.1; the home face is the family's own prototile for those shapes; the patch is valid."""
    answer = client.get(f"/api/curved/edit/{IH}?{_query(SHAPES)}")
    body = answer.json()
    assert answer.status_code == 200, body
    t = CurvedIsohedralTiling(5, 4, symbol=SYMBOL, edges=SHAPES)
    assert [e["label"] for e in body["edges"]] == shape_classes(t.symbol) == ["a", "c"]
    assert [e["kind"] for e in body["edges"]] == ["S", "J"]
    assert [e["tile_edges"] for e in body["edges"]] == [[1], [3, 4]]
    assert body["edges"][1]["points"] == [[0, 0], [0.3, 0.2], [0.6, -0.1], [1, 0]]
    home = _faces(body)[body["home"]]
    assert np.allclose(home, t.prototiles[0].points, atol=1e-9)
    assert t.configure(radius=2.0).patch().validate().ok


def test_editor_url_reopens_the_tiling_exactly(client):
    """Values with full double precision survive the link, the page's data and the API."""
    shapes = {"a": "0,0:0.1,0.30000000000000004:0.35,0.05:1,0", "c": "0,0:0.3,0.2:0.6,-0.1:1,0"}
    body = client.get(f"/api/curved/edit/{IH}?{_query(shapes)}").json()
    assert body["query"] == ["a=" + shapes["a"], "c=" + shapes["c"]]
    assert body["link"] == f"/curved/edit/{IH}?{_query(shapes)}"
    again = client.get(body["link"].replace("/curved/edit/", "/api/curved/edit/")).json()
    assert again["points"] == body["points"] and again["query"] == body["query"]
    page = client.get(body["link"])
    assert page.status_code == 200 and "0.30000000000000004" in page.text
    base = CurvedIsohedralTiling(5, 4, symbol=SYMBOL)
    assert edge_query(base.configure(edges=body["query"])) == body["query"]   # the family reads the query too
    svg = client.get(body["svg"])
    assert svg.status_code == 200 and svg.headers["content-type"].startswith("image/svg+xml")


def test_cli_command_renders_the_edited_tiling(client, tmp_path, monkeypatch):
    from click.testing import CliRunner

    from tilekit.cli import cli

    body = client.get(f"/api/curved/edit/{IH}?{_query(SHAPES)}").json()
    args = shlex.split(body["cli"])
    assert args[:2] == ["tilekit", "render"] and args[2] == IH
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, args[1:], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    assert (tmp_path / f"{IH}.svg").read_text().startswith("<svg")


@pytest.mark.parametrize("query, words", [
    ("edge=c=0.2,0.8:0.4,-0.8:0.6,0.8:0.8,-0.8", "cross"),              # self-intersecting tile
    ("edge=a=0.3,5", "y in [-1, 1]"),                                     # out of the widget's range
    ("edge=a=0.3,x", "not points"),                                       # malformed shape
    ("edge=z=0.3,0.1", "shaped edges are a, c"),                          # no such shape class
    ("edge=a=0.3,0.1&edge=a=0.2,0.1", "given twice"),
    ("colour=3", "unknown editor option"),
    ("edge=c=" + ":".join(f"{k / 18:.4f},0.01" for k in range(1, 18)), "at most 16"),  # bounded work per edit
])
def test_bad_edits_are_400_with_one_line(client, query, words):
    answer = client.get(f"/api/curved/edit/{IH}?{query}")
    assert answer.status_code == 400
    error = answer.json()["error"]
    assert words in error and "\n" not in error and "Traceback" not in error
    page = client.get(f"/curved/edit/{IH}?{query}")            # the page: the record's shapes and the line
    assert page.status_code == 200 and words in page.text.replace("&#x27;", "'")


def test_laves_records_under_rotations_edit_and_full_groups_say_why_not(client):
    answer = client.get("/api/curved/edit/%5B7%5E3%5D-rotations?edge=a=0.2,0.1:0.4,0.05")
    body = answer.json()
    assert answer.status_code == 200, body
    assert [(e["label"], e["kind"]) for e in body["edges"]] == [("a", "S")]
    assert body["geometry"] == "hyperbolic"
    sphere = client.get("/api/curved/edit/pentagonal-icositetrahedron").json()   # a snub's dual: chiral already
    assert sphere["geometry"] == "spherical" and len(sphere["sizes"]) == 24      # its 24 faces
    # coloured by its perfect colouring: the rotation group 432 (S4) onto Z2, 12 tiles a colour
    assert np.bincount(sphere["colour"]).tolist() == [12, 12]
    full = client.get("/api/curved/edit/%5B7%5E3%5D")
    assert full.status_code == 400 and "I edge" in full.json()["error"]
    page = client.get("/curved/edit/%5B7%5E3%5D")
    assert page.status_code == 200 and 'href="/curved/edit/%5B7%5E3%5D-rotations"' in page.text
    regular = client.get("/api/curved/edit/octahedron")                            # a regular tiling: no shapes
    assert regular.status_code == 400 and "the tile editor shapes" in regular.json()["error"]


def test_vertex_star_duals_edit_their_shapeable_edges(client):
    """[3^3.6^2] under its whole group 2*32 has incidence symbol [a+a-b+cb-; a+b-c] (edge kinds
    SSIII): the editor shapes its one S class; [4^2.6^2] under *3222 has I edges only."""
    answer = client.get("/api/curved/edit/%5B3%5E3.6%5E2%5D?edge=a=0.25,0.1:0.5,0")
    body = answer.json()
    assert answer.status_code == 200, body
    assert [(e["label"], e["kind"]) for e in body["edges"]] == [("a", "S")]
    assert body["geometry"] == "hyperbolic", body["query"]
    assert body["query"] == ["a=0,0:0.25,0.1:0.5,0:1,0"]      # the shape with its ends, exact
    straight = client.get("/api/curved/edit/%5B4%5E2.6%5E2%5D")
    assert straight.status_code == 400 and "I edge" in straight.json()["error"] and "\n" not in straight.json()["error"]


def test_tiling_and_viewer_pages_link_to_the_editor_where_it_applies(client):
    assert 'href="/curved/edit/curved-ih-5-4-5"' in client.get("/tiling/curved-ih-5-4-5").text
    assert 'href="/curved/edit/curved-ih-5-4-5"' in client.get("/curved/curved-ih-5-4-5").text
    assert 'href="/curved/edit/%5B5%5E4%5D-rotations"' in client.get("/tiling/%5B5%5E4%5D-rotations").text
    assert "/curved/edit/" not in client.get("/tiling/%5B5%5E4%5D").text


pytest.importorskip("playwright")


def _svg_box(page, selector: str) -> list[float]:
    return page.eval_on_selector(selector, "s => { const r = s.getBoundingClientRect(); const m = s.getScreenCTM(); "
                                 "return [r.left, r.top, m.a, m.d, m.e, m.f]; }")


def test_dragging_a_handle_moves_the_drawn_edge_and_its_partner(page, client):
    """Drag edge c's middle handle up (into the tile) by 0.15 of the unit segment: the home
    face drawn afterwards holds the chart of the new point on edge 3 (moved into the tile in the
    edge's frame) and its image on edge 4 under the hop across edge 3, and no longer the old
    ones; the drawing is the API's data for the new query, and the family's tiling is valid."""
    errors: list[str] = []
    page.on("console", lambda msg: errors.append(msg.text) if msg.type == "error" else None)
    page.goto(f"/curved/edit/{IH}?{_query(SHAPES)}")
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    page.wait_for_function("() => document.querySelector('#curved').dataset.query !== undefined", timeout=20000)
    before = page.get_attribute("#curved", "data-query")
    handle = page.locator("#edge-c circle.handle[data-index='1']")
    box = handle.bounding_box()
    x0, y0 = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    # the widget's scale: SVG units per pixel from its CTM (y flipped by the widget's group)
    _, _, sx, _, _, _ = _svg_box(page, "#edge-c")
    page.mouse.move(x0, y0)
    page.mouse.down()
    page.mouse.move(x0, y0 - 0.15 * sx, steps=6)
    page.mouse.up()
    page.wait_for_function("q => document.querySelector('#curved').dataset.query !== q "
                           "&& !document.querySelector('#curved').dataset.busy", arg=before, timeout=20000)
    query = page.get_attribute("#curved", "data-query").split("&")
    shapes = dict(item.split("=", 1) for item in query)
    new = [tuple(map(float, p.split(","))) for p in shapes["c"].split(":")]
    old = [(0.0, 0.0), (0.3, 0.2), (0.6, -0.1), (1.0, 0.0)]
    assert abs(new[1][0] - 0.3) < 0.02 and abs(new[1][1] - 0.35) < 0.02      # the handle went up by 0.15
    assert shapes["a"] == SHAPES["a"] and new[2] == old[2]
    assert f"edge=c={shapes['c']}" in page.url                                  # the address bar follows

    home = int(page.evaluate("() => { const e = document.querySelector('#disc path.home'); "
                             "return Number(e.dataset.face); }"))
    drawn = corners(page.get_attribute(f"#disc path[data-face='{home}']", "d"))
    t = CurvedIsohedralTiling(5, 4, symbol=SYMBOL, edges=shapes)
    body = client.get(f"/api/curved/edit/{IH}?{_query(shapes)}").json()
    face = _faces(body)[body["home"]]
    assert np.allclose(drawn, face[:, :2] / (1 + face[:, 2:3]), atol=2e-6)       # what the API sent is drawn

    g, f, length = t.polygon.geometry, t.frames[2], t.polygon.edge_length
    p_new, p_old = chart(g, f, length, np.array([new[1]]))[0], chart(g, f, length, np.array([old[1]]))[0]
    partner = np.linalg.inv(t.motions[2]) @ p_new                               # edge 4 repeats edge 3's point

    def disc(p: np.ndarray) -> np.ndarray:
        return p[:2] / (1 + p[2])

    def nearest(p: np.ndarray) -> float:
        return float(np.hypot(*(drawn - disc(p)).T).min())

    assert nearest(p_new) < 1e-5 and nearest(partner) < 1e-5
    assert nearest(p_old) > 5e-3 and nearest(np.linalg.inv(t.motions[2]) @ p_old) > 5e-3
    inv = np.linalg.inv(f)
    assert (inv @ p_new)[1] > (inv @ p_old)[1] + 0.05                             # into the tile, as dragged
    assert t.configure(radius=2.0).patch().validate().ok
    assert not page.js_errors and errors == []


def test_a_refused_url_shows_its_line_and_draws_the_record(page):
    page.goto(f"/curved/edit/{IH}?edge=a=0.3,5")
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    assert "y in [-1, 1]" in page.inner_text("#notice")
    assert page.locator("#edges .edge").count() == 2
    assert not page.js_errors
