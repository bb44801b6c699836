"""The catalogue pages as a product (issue 30): stable URLs for names with "/", totals that
agree between /families, /family/X, the all listing and the API, facets, sorting, numbered
pages, JSON and CSV of every listing, run pages and tiling pages.

One catalogue of this module: the shipped records plus the polyominoes classified to 7 cells
(a real polyomino-classify run, whose rows live in the plugin's result table and whose names
are codes such as ``.x../xx../.x..``).
"""

from __future__ import annotations

import csv
import io
import re
from collections import Counter
from urllib.parse import quote

import pytest

pytest.importorskip("starlette")

#: Free polyominoes with n = 1..7 cells (OEIS A000105).
FREE = {1: 1, 2: 1, 3: 2, 4: 5, 5: 12, 6: 35, 7: 108}
#: Polyominoes that tile the plane, n = 1..7 (A054359: 104 at n = 7; every smaller one tiles);
#: the 4 non-tilers of 7 cells (A054360), 3 hole-free (A054361) with Heesch numbers 1, 1, 0
#: (Kaplan 2022, Table 1: Hc = 0 for one, 1 for two).
TILERS_7 = 104
HEESCH_7 = Counter({1: 2, 0: 1})


@pytest.fixture(scope="module")
def browse_catalogue(tmp_path_factory):
    from tilekit import open_catalogue
    from tilekit.search import run_search

    cat = open_catalogue(str(tmp_path_factory.mktemp("browse") / "catalogue.sqlite"))
    cat.browse_run = run_search(cat, "polyomino-classify", {"max_cells": 7})  # type: ignore[attr-defined]
    yield cat
    cat.close()


@pytest.fixture(scope="module")
def bc(browse_catalogue):
    from starlette.testclient import TestClient

    from tilekit.web import create_app

    with TestClient(create_app(catalogue=browse_catalogue)) as c:
        yield c


def rows(cat, where=()):
    return list(cat.iter_result_rows("polyominoes", list(where)))


def test_every_listed_polyomino_has_a_page_and_a_thumbnail(bc, browse_catalogue):
    """All 164 polyominoes to 7 cells are listed; each link round-trips, "/" in the name or not."""
    listing = bc.get("/family/polyomino.json", params={"limit": 200}).json()
    assert listing["total"] == sum(FREE.values()) == 164
    names = [item["name"] for item in listing["items"]]
    assert sorted(n for n in names if "/" not in n) == ["x" * k for k in range(1, 8)]  # one row: the straight ones
    page = bc.get("/family/polyomino", params={"limit": 200, "view": "table"}).text
    hrefs = set(re.findall(r'href="(/tiling/[^"]+)"', page))
    thumbs = set(re.findall(r'src="(/thumb/[^"]+\.svg)"', page))
    assert len(hrefs) == len(thumbs) == 164
    for name in names[::9]:
        path = "/tiling/" + quote(name, safe="")
        assert path in hrefs
        r = bc.get(path)
        assert r.status_code == 200 and f"<h1>{name}</h1>" in r.text
        assert bc.get("/thumb/" + quote(name, safe="") + ".svg").text.startswith("<svg")
        assert bc.get("/api/tiling/" + quote(name, safe="")).json()["name"] == name
        spec = bc.get("/api/tiling/" + quote(name, safe="") + "/spec").json()
        assert spec["spec"]["code"] == name
        assert bc.get("/api/render/" + quote(name, safe=""), params={"size": 64}).status_code == 200
    # the isohedral plugin's /api/tiling/NAME/editor still wins over the "/"-name route
    assert "params" in bc.get("/api/tiling/IH16/editor").json()


def test_counts_agree_everywhere(bc, browse_catalogue):
    cat = browse_catalogue
    fams = bc.get("/families.json").json()
    api = {f["name"]: f["tilings"] for f in bc.get("/api/families").json()["families"]}
    every = bc.get("/", params={"_format": "json", "limit": 1}).json()
    assert {f["name"]: f["tilings"] for f in fams["families"]} == api
    assert fams["total"] == every["total"] == sum(api.values())
    for name, n in api.items():
        assert bc.get(f"/family/{name}.json", params={"limit": 1}).json()["total"] == n
        assert every["counts"].get(name, 0) == n
        assert bc.get("/api/query", params={"family": name, "limit": 0}).json()["total"] == n
    # the independent counts: the result table's rows, the other families' records
    assert api["polyomino"] == cat.count_result_rows("polyominoes") == 164
    assert api["archimedean"] == cat.count("archimedean")
    assert f"{fams['total']:,}" in bc.get("/families").text


def test_heesch_filter_without_a_family(bc, browse_catalogue):
    """``heesch>=0`` names a result-table column: it applies to the polyominoes alone."""
    expected = [r for r in rows(browse_catalogue) if r["heesch"] is not None]
    assert Counter(r["heesch"] for r in expected) == HEESCH_7
    got = bc.get("/", params={"where": "heesch>=0", "_format": "json"}).json()
    assert got["total"] == len(expected) == 3 and got["counts"] == {"polyomino": 3}
    assert sorted(i["name"] for i in got["items"]) == sorted(r["code"] for r in expected)
    assert bc.get("/api/query", params={"where": "heesch>=1"}).json()["total"] == 2
    html = bc.get("/", params={"where": "heesch>=1"})
    assert html.status_code == 200 and "2 matches" in html.text
    bad = bc.get("/", params={"where": "heesh>=1", "_format": "json"})
    assert bad.status_code == 400 and "unknown property 'heesh'" in bad.json()["error"]


def test_facet_counts_match_their_filters(bc, browse_catalogue):
    page = bc.get("/family/polyomino.json", params={"limit": 1}).json()
    cells = dict(page["facets"]["cells"])
    assert cells == FREE  # A000105
    tiles = dict(page["facets"]["tiles"])
    assert tiles == {"true": 164 - 4, "false": 4} and tiles["true"] - (164 - 108) == TILERS_7
    for key in ("cells", "symmetry", "tiles", "heesch"):
        for value, count in page["facets"][key]:
            text = str(value).lower() if isinstance(value, bool) else str(value)
            total = bc.get("/family/polyomino.json", params={"where": f"{key}={text}", "limit": 1}).json()["total"]
            assert total == count, (key, value)
    # the all listing's facets add the families up; its family facet is the counts
    every = bc.get("/", params={"_format": "json", "limit": 1}).json()
    assert dict(every["facets"]["family"]) == every["counts"]
    assert dict(every["facets"]["cells"]) == FREE
    # the HTML: a facet value is a link adding its filter, a chosen one a link removing it
    html = bc.get("/family/polyomino", params={"where": "cells=5"}).text
    assert 'href="/family/polyomino?where=cells%3D5&amp;where=symmetry%3DC1"' in html or "symmetry" in html
    assert re.search(r'<li class="chosen"><a href="/family/polyomino" data-facet="cells" data-value="5">', html)


def test_sorting_paging_and_formats(bc, browse_catalogue):
    got = bc.get("/family/polyomino.json", params={"order": "-cells", "limit": 50}).json()
    cells = [i["properties"]["cells"] for i in got["items"]]
    assert cells == sorted(cells, reverse=True) and cells[0] == 7
    html = bc.get("/family/polyomino", params={"limit": 20, "offset": 60}).text
    assert "164 matches; 61–80 shown" in html and "page 4 of 9" in html
    assert '<b aria-current="page">4</b>' in html and 'href="/family/polyomino?limit=20&amp;offset=160">9</a>' in html
    text = bc.get("/family/polyomino.csv", params={"limit": 7, "order": "cells"}).text
    table = list(csv.DictReader(io.StringIO(text)))
    assert len(table) == 7 and table[0]["name"] == "x" and table[0]["cells"] == "1"
    assert bc.get("/", params={"_format": "csv", "family": "archimedean", "limit": 200}).text.count("\n") == 1 + 12
    bad = bc.get("/family/polyomino", params={"_format": "xml"})
    assert bad.status_code == 400 and "_format &#x27;xml&#x27; must be html, json or csv" in bad.text
    bad = bc.get("/family/polyomino.json", params={"order": "nope"})
    assert bad.status_code == 400 and bad.json()["error"].startswith("unknown order key 'nope'")
    assert bc.get("/family/polyomino", params={"view": "cards"}).status_code == 400


def test_page_numbers():
    from tilekit.web.pages import page_numbers

    assert page_numbers(1, 1) == [1]
    assert page_numbers(1, 12) == [1, 2, 3, None, 12]
    assert page_numbers(6, 12) == [1, None, 4, 5, 6, 7, 8, None, 12]
    assert page_numbers(12, 12) == [1, None, 10, 11, 12]


def test_run_page_is_a_table_with_links(bc, browse_catalogue):
    run_id = browse_catalogue.browse_run
    html = bc.get(f"/runs/{run_id}", params={"limit": 40}).text
    assert "None" not in html and not re.search(r"\d\.\d{7,}", html)  # no None, no float noise
    per_n = re.search(r'<table class="list summary" id="per-n">(.*?)</table>', html).group(1)
    head = re.findall(r"<th>([a-z_]+)</th>", per_n.split("</tr>")[0])
    free = head.index("free") - 1  # the first head is n's
    for n, count in FREE.items():
        row = re.search(rf"<tr><th>{n}</th>(.*?)</tr>", per_n).group(1)
        assert re.findall(r"<td>([^<]*)</td>", row)[free] == str(count)
    assert '<svg class="chart"' in html
    links = set(re.findall(r'href="(/tiling/[^"]+)"', html))
    assert len(links) == 40
    for link in sorted(links)[:5]:
        assert bc.get(link).status_code == 200
    assert "164 matches; 1–40 shown" in html and "page 1 of 5" in html
    assert bc.get(f"/runs/{run_id}", params={"_format": "json"}).json()["results"]["total"] == 164


def test_tiling_page_view_control_legend_and_shapes(bc):
    non_tiler = bc.get("/", params={"where": "heesch=1", "_format": "json"}).json()["items"][0]["name"]
    html = bc.get("/tiling/" + quote(non_tiler, safe="")).text
    assert 'id="verdict">does not tile: Heesch number 1' in html
    assert 'id="legend"' in html and 'id="prototiles"' in html and "coloured by corona" in html
    html = bc.get("/tiling/IH16", params={"region": "0,0,2,2"}).text
    assert 'value="0,0,2,2"' in html and 'href="/api/render/IH16?region=0%2C0%2C2%2C2&amp;download=1"' in html
    big = bc.get("/tiling/3.4.6.4", params={"region": "0,0,5000,5000"})
    assert big.status_code == 200 and "the limit is 20,000 per request" in big.text and 'id="figure"' in big.text
    bad = bc.get("/tiling/IH16", params={"depth": "x"}).text
    assert "depth &#x27;x&#x27; is not a whole number" in bad
    assert bc.get("/tiling/%3Cnope%3E").status_code == 404


def test_tiling_pages_draw_the_familys_own_picture(bc):
    """The page draws through the tiling's render_svg: Kari's 14 Wang tiles (Discrete Math. 160,
    1996; edge colours 0..7, docs FACTS) show each side in its edge colour, 8 fills in all, not
    one fill per tile; a hyperbolic {4,5} is drawn with true circular arcs (SVG ``A``)."""
    html = bc.get("/tiling/kari-14").text
    figure = re.search(r'<figure class="large" id="figure">(.*?)</figure>', html, re.S).group(1)
    assert len(set(re.findall(r'fill="(#[0-9a-f]{6})"', figure))) == 8
    html = bc.get("/tiling/" + quote("{4,5}", safe="")).text
    figure = re.search(r'<figure class="large" id="figure">(.*?)</figure>', html, re.S).group(1)
    assert re.search(r'd="[^"]* A', figure)
