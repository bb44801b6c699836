"""The JSON API and the pages through Starlette's ASGI test client (no network)."""

from __future__ import annotations

import json
import re

import pytest


def test_query_filters_and_paging(client):
    r = client.get("/api/query", params={"family": "archimedean", "limit": 5})
    assert r.status_code == 200
    body = r.json()
    assert body["total"] == 11 or body["total"] >= 11
    assert len(body["items"]) == 5 and body["offset"] == 0 and body["limit"] == 5
    names = [i["name"] for i in body["items"]]
    page2 = client.get("/api/query", params={"family": "archimedean", "limit": 5, "offset": 5}).json()
    assert not set(names) & {i["name"] for i in page2["items"]}
    assert page2["total"] == body["total"]

    r = client.get("/api/query", params=[("where", "polygons=6"), ("where", "polygons!=3")])
    names = {i["name"] for i in r.json()["items"]}
    assert "4.6.12" in names and "3.4.6.4" not in names
    assert all(6 in i["properties"]["sides"] for i in r.json()["items"])

    # the form's typed fields become the same filters
    r = client.get("/api/query", params={"family": "isohedral", "range_key": "parameters", "range_min": "2",
                                         "range_max": "2", "limit": 200})
    assert r.json()["total"] > 0
    assert all(i["properties"]["parameters"] == 2 for i in r.json()["items"])
    r = client.get("/api/query", params={"periodic": "false", "limit": 200})
    assert r.json()["total"] > 0 and all(i["properties"]["periodic"] is False for i in r.json()["items"])
    r = client.get("/api/query", params={"text": "penrose"})
    assert r.json()["total"] >= 1


@pytest.mark.parametrize(("params", "status", "needle"), [
    ({"where": "polygon=6"}, 400, "unknown property 'polygon'; did you mean 'polygons'"),
    ({"where": "polygons>=abc"}, 400, "polygons"),
    ({"where": "=3"}, 400, ""),
    ({"family": "isohedra"}, 404, "unknown family 'isohedra'"),
    ({"limit": "1000"}, 400, "limit 1000 must be between 0 and 200"),
    ({"offset": "-1"}, 400, "offset"),
    ({"range_min": "3"}, 400, "range_key"),
])
def test_query_errors_are_one_line_json(client, params, status, needle):
    r = client.get("/api/query", params=params)
    assert r.status_code == status, r.text
    body = r.json()
    assert body["status"] == status and "\n" not in body["error"] and needle in body["error"]


def test_sql_in_a_filter_is_only_a_value(client, web_catalogue):
    hostile = "name=x'; DROP TABLE tilings; --"
    r = client.get("/api/query", params={"where": hostile})
    assert r.status_code == 200 and r.json()["total"] == 0
    assert web_catalogue.count() > 100


def test_tiling_and_unknown_name(client):
    r = client.get("/api/tiling/IH16")
    assert r.status_code == 200
    body = r.json()
    assert body["properties"]["topology"] == "3^6" and body["spec"]["ih"] == 16
    assert "incidence symbol" in body["describe"].lower() or "[a+b+c+c-b-a-; a-c+b+]" in body["describe"]
    assert re.fullmatch(r"[0-9a-f]{16}", body["spec_hash"])
    r = client.get("/api/tiling/4.4.4.4x")  # (4.4.4.5 is a name now: the hyperbolic 4 5 | 2)
    assert r.status_code == 404
    assert r.json()["error"].startswith("unknown tiling '4.4.4.4x'; did you mean '4.4.4.4'")
    assert client.get("/api/nothing").status_code == 404
    assert client.get("/api/nothing").json()["status"] == 404


def test_render_svg_png_json_and_spec(client):
    r = client.get("/api/render/IH16", params={"params": "0.25", "edge": "b=0,0:0.3,0.2:1,0", "size": 300})
    assert r.status_code == 200 and r.headers["content-type"].startswith("image/svg+xml")
    assert r.text.startswith("<svg") and r.text.rstrip().endswith("</svg>")
    j = client.get("/api/render/IH16", params={"params": "0.25", "edge": "b=0,0:0.3,0.2:1,0", "format": "json"}).json()
    assert j["spec"] == {"ih": 16, "params": [0.25], "edges": {"b": "0,0:0.3,0.2:1,0"}}
    assert len(j["outline"]) > 6
    r = client.get("/api/render/4^4", params={"format": "png", "size": 64, "download": "1"})
    assert r.status_code == 200 and r.content[:8] == b"\x89PNG\r\n\x1a\n"
    assert r.headers["content-disposition"] == 'attachment; filename="4_4.png"'
    r = client.post("/api/render", json={"name": "penrose-p3", "r1": 0.15, "theta1": 20, "r2": 0.1,
                                         "theta2": -15, "region": [-3, -3, 3, 3], "format": "json"})
    assert r.status_code == 200 and r.json()["spec"]["r1"] == 0.15
    r = client.get("/api/tiling/IH16/spec", params={"params": "0.3", "download": "1"})
    assert r.json() == {"family": "isohedral", "name": "IH16", "spec": {"ih": 16, "params": [0.3]}}
    assert "attachment" in r.headers["content-disposition"]


@pytest.mark.parametrize(("params", "status", "needle"), [
    ({"region": "-500,-500,500,500"}, 413, "tiles; the limit is 20,000 per request"),
    ({"params": "0.2,0.3"}, 400, "IH16 takes 1 parameter(s)"),
    ({"edge": "z=0,0:1,0"}, 400, "no edge label 'z'"),
    ({"edge": "b=0,0:0.5,2:0.5,-2:1,0"}, 400, "IH16"),
    ({"region": "1,2,3"}, 400, "four numbers"),
    ({"params": "nan"}, 400, "not a finite number"),
    ({"size": "100000"}, 400, "size 100000 must be between 16 and 2000"),
    ({"format": "gif"}, 400, "format 'gif'"),
    ({"bogus": "1"}, 400, "unknown render option(s) 'bogus'"),
])
def test_render_errors(client, params, status, needle):
    r = client.get("/api/render/IH16", params=params)
    assert r.status_code == status, r.text
    body = r.json()
    assert needle in body["error"] and "\n" not in body["error"] and body["status"] == status


def test_oversize_render_names_estimate_and_limit(client):
    r = client.get("/api/render/penrose-p3", params={"depth": 14})
    assert r.status_code == 413
    body = r.json()
    assert body["limit"] == 20_000 and body["estimate"] > 20_000
    assert f"{body['estimate']:,}" in body["error"]


def test_quasivertex_self_intersection_refused_with_reason(client):
    r = client.get("/api/render/penrose-p3", params={"r1": 0.9, "theta1": 80, "r2": 0.9, "theta2": -10})
    assert r.status_code == 400
    assert "self-intersect" in r.json()["error"] and "r1 must lie in" in r.json()["error"]


def test_request_size_limits(client):
    r = client.post("/api/render", content=b"{" + b" " * 70_000 + b"}", headers={"content-type": "application/json"})
    assert r.status_code == 413 and "request body over" in r.json()["error"]
    r = client.get("/api/query?where=" + "a" * 9000)
    assert r.status_code == 414
    r = client.post("/api/render", content=b"[1, 2]")
    assert r.status_code == 400 and r.json()["error"] == "request body must be a JSON object"
    r = client.post("/api/render", content=b"{nope")
    assert r.status_code == 400 and r.json()["error"].startswith("request body: not valid JSON")
    # nesting that would exhaust the parser's recursion (a 500 before issue 27): one line, 400
    r = client.post("/api/render", content=b'{"a":' + b"[" * 30_000 + b"]" * 30_000 + b"}")
    assert r.status_code == 400 and "nest more than" in r.json()["error"]


def test_no_write_endpoint_without_writable(client, web_catalogue, app):
    run_id = web_catalogue.web_test_run
    r = client.post(f"/api/runs/{run_id}/cancel")
    assert r.status_code == 403 and "--writable" in r.json()["error"]
    assert client.delete(f"/api/runs/{run_id}").status_code == 405
    assert client.get(f"/api/runs/{run_id}/cancel").status_code == 405


def test_writable_server_cancels(web_catalogue):
    from starlette.testclient import TestClient

    from tilekit.web import create_app

    run_id = web_catalogue.create_run("demo", {"n": 1}, [{"i": 0}])
    with TestClient(create_app(catalogue=web_catalogue, writable=True)) as c:
        r = c.post(f"/api/runs/{run_id}/cancel")
        assert r.status_code == 200 and r.json()["status"] == "cancelled"
    web_catalogue.delete_run(run_id)


def test_runs_results_paging_and_events(client, web_catalogue):
    run_id = web_catalogue.web_test_run
    runs = client.get("/api/runs").json()["runs"]
    assert run_id in [r["id"] for r in runs]
    info = client.get(f"/api/runs/{run_id}").json()
    assert info["status"] == "done" and info["chunks_done"] == 3
    page = client.get(f"/api/runs/{run_id}/results", params={"limit": 12, "offset": 24}).json()
    assert page["total"] == 30 and len(page["rows"]) == 6 and set(page["columns"]) == {"chunk", "k", "label"}
    assert client.get("/api/runs/999999").status_code == 404
    assert client.get("/api/runs/abc").status_code == 400
    with client.stream("GET", f"/api/runs/{run_id}/events") as r:
        text = "".join(r.iter_text())
    assert "event: progress" in text and "event: end" in text
    data = json.loads(text.split("event: end\ndata: ")[1].split("\n")[0])
    assert data["status"] == "done"


def test_thumbnails_cached_by_spec_hash(client):
    r1 = client.get("/thumb/3.4.6.4.svg")
    assert r1.status_code == 200 and r1.headers["content-type"].startswith("image/svg+xml")
    etag = r1.headers["etag"]
    r2 = client.get("/thumb/3.4.6.4.svg", headers={"if-none-match": etag})
    assert r2.status_code == 304
    assert client.get("/thumb/no-such-tiling.svg").status_code == 404


@pytest.mark.parametrize("path", ["/", "/?family=isohedral", "/tiling/IH16", "/tiling/penrose-p3", "/families",
                                  "/family/isohedral", "/runs", "/editor", "/editor/IH41", "/penrose", "/api"])
def test_pages_render(client, path):
    r = client.get(path)
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/html")
    assert "content-security-policy" in r.headers and "script-src 'self'" in r.headers["content-security-policy"]


def test_run_page_escapes_results(client, web_catalogue):
    r = client.get(f"/runs/{web_catalogue.web_test_run}", params={"limit": 10})
    assert r.status_code == 200
    assert "&lt;b&gt;r0-0&lt;/b&gt;" in r.text and "<b>r0-0</b>" not in r.text


def test_hostile_query_string_is_escaped(client):
    evil = "<script>alert(1)</script>\"'"
    r = client.get("/", params={"text": evil, "where": f"name~{evil}", "family": ""})
    assert r.status_code == 200
    assert "<script>alert" not in r.text
    assert "&lt;script&gt;alert(1)&lt;/script&gt;&quot;&#x27;" in r.text
    r = client.get("/", params={"where": f"{evil}=1"})
    assert r.status_code == 400 and "<script>alert" not in r.text
    r = client.get("/tiling/" + evil)
    assert r.status_code == 404 and "<script>alert" not in r.text


def test_parquet_deformation_is_a_tiling(client, app):
    """Exercise 5.13: the strip's tiles evolve from squares to the keyframe, edge-to-edge."""
    import shapely

    from tilekit.plugins.isohedral.web import parquet_tiles

    state = app.app.state.tilekit
    tiles, width, height = parquet_tiles(state.renderer, "IH61", ["a=0,0:0.3,0.3:0.7,-0.2:1,0"], 8, 3)
    polys = [shapely.Polygon(p) for _, p in tiles]
    assert all(p.is_valid for p in polys)
    strip = shapely.box(0, 0, width, height)
    inside = [p.intersection(strip) for p in polys]
    assert abs(sum(p.area for p in inside) - strip.area) < 1e-6 * strip.area  # no overlaps ...
    assert abs(shapely.union_all(inside).area - strip.area) < 1e-6 * strip.area  # ... and no gaps
    left = min(polys, key=lambda p: p.centroid.x)
    right = max(polys, key=lambda p: p.centroid.x)
    assert len(left.exterior.coords) < len(right.exterior.coords) or left.length < right.length

    r = client.get("/api/parquet/IH61", params={"edge": "a=0,0:0.3,0.3:0.7,-0.2:1,0", "download": "1"})
    assert r.status_code == 200 and r.text.startswith("<svg") and "attachment" in r.headers["content-disposition"]
    r = client.get("/api/parquet/IH16")
    assert r.status_code == 400 and "fixed square tiling vertices" in r.json()["error"]
    r = client.get("/api/parquet/IH61", params={"columns": "100"})
    assert r.status_code == 400


def test_run_results_paged_from_the_result_table(species_catalogue, species_client):
    """A real vertex-species run writes the archimedean plugin's vertex_species table (on a
    catalogue of its own, see conftest.species_catalogue)."""
    cat, run_id = species_catalogue
    client = species_client
    total = cat.count_result_rows("vertex_species", [f"run_id={run_id}"])
    first = client.get(f"/api/runs/{run_id}/results", params={"limit": 50}).json()
    assert first["table"] == "vertex_species" and first["total"] == total > 50
    assert len(first["rows"]) == 50 and all(r["run_id"] == run_id for r in first["rows"])
    last = client.get(f"/api/runs/{run_id}/results", params={"limit": 50, "offset": total - 10}).json()
    assert len(last["rows"]) == 10
    assert not {r["vertex_type"] for r in first["rows"]} & {r["vertex_type"] for r in last["rows"]}
    page = client.get(f"/runs/{run_id}", params={"offset": 50, "limit": 25})
    assert page.status_code == 200 and "vertex_species" in page.text
    assert f"{total:,} matches; 51–75 shown" in page.text


def test_a_familys_own_options_go_through_set(client):
    """``set=KEY=VALUE`` is the command line's ``--set``: the multigrid's offsets gamma (§6.3)
    reach the family, which checks them; a key the family does not take, a render option
    smuggled through ``set`` and a singular multigrid are one-line 400s."""
    r = client.get("/api/render/multigrid-5", params={"set": "gamma=0.1,0.2,0.3,0.1,0.3", "format": "json",
                                                      "region": "-3,-3,3,3", "size": 200})
    assert r.status_code == 200 and r.json()["spec"]["gamma"] == [0.1, 0.2, 0.3, 0.1, 0.3]
    other = client.get("/api/render/multigrid-5", params={"format": "json", "region": "-3,-3,3,3", "size": 200})
    assert other.json()["svg"] != r.json()["svg"]
    for params, text in (({"set": "gamma=0,0,0,0,0"}, "singular"), ({"set": "gamma=x"}, "not a number"),
                         ({"set": "size=9"}, "give size as its own option"), ({"set": "nonsense"}, "KEY=VALUE")):
        r = client.get("/api/render/multigrid-5", params={**params, "format": "json"})
        assert r.status_code == 400 and text in r.json()["error"] and "\n" not in r.json()["error"]
    r = client.get("/api/render/IH16", params={"set": "foo=1", "format": "json"})
    assert r.status_code == 400 and "does not take option 'foo'" in r.json()["error"]
