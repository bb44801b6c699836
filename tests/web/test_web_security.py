"""Cross-site writes, DNS rebinding and hostile input (issue 30, "Security and robustness"):
each case answers the right status with a one-line JSON error and changes nothing."""

from __future__ import annotations

import json
import logging

import pytest

from tilekit.web.guard import _host_name, allowed_hosts


@pytest.fixture
def guarded(web_catalogue):
    """A writable app bound (as ``tilekit serve`` binds it) to 127.0.0.1, and a fresh run."""
    from starlette.testclient import TestClient

    from tilekit.web import create_app

    run_id = web_catalogue.create_run("demo", {"n": 1}, [{"i": 0}])
    app = create_app(catalogue=web_catalogue, writable=True, bind_host="127.0.0.1", allow_hosts=["tiles.lan"])
    with TestClient(app, base_url="http://127.0.0.1:8000") as c:
        yield c, run_id
    web_catalogue.delete_run(run_id)


def _status(cat, run_id):
    return cat.run(run_id).status


def _one_line(r, status, fragment=""):
    assert r.status_code == status, (r.status_code, r.text)
    body = r.json()
    assert body["status"] == status and "\n" not in body["error"] and fragment in body["error"], body


# --------------------------------------------------------------------------- Host (DNS rebinding)


@pytest.mark.parametrize(("host", "ok"), [
    ("127.0.0.1:8000", True), ("localhost:8000", True), ("LOCALHOST", True), ("[::1]:8000", True),
    ("tiles.lan:8000", True),  # --allow-host
    ("evil.example", False), ("evil.example:8000", False), ("127.0.0.1.evil.example", False),
    ("10.0.0.7:8000", False),  # bound to loopback: another address is not this server
    ("", False), ("127.0.0.1:80x", False), ("user@127.0.0.1", False),
])
def test_host_header_must_name_the_bound_address(guarded, web_catalogue, host, ok):
    c, _ = guarded
    r = c.get("/api/families", headers={"host": host})
    if ok:
        assert r.status_code == 200, r.text
    else:
        _one_line(r, 421, "is not a name this server answers to")


def test_wildcard_bind_takes_any_address_but_no_foreign_name():
    names, any_ip = allowed_hosts("0.0.0.0", ["tiles.lan"])
    assert any_ip and {"localhost", "tiles.lan"} <= names
    from tilekit.web.guard import Guard

    g = Guard(None, "0.0.0.0")
    assert g.host_ok("192.168.1.20:8000") and g.host_ok("[fe80::1]:8000") and g.host_ok("localhost")
    assert not g.host_ok("evil.example:8000") and not g.host_ok("192.168.1.20.nip.io")
    # a server bound to a name answers to that name only (and loopback's own names)
    g = Guard(None, "tiles.example.org")
    assert g.host_ok("tiles.example.org:8000") and not g.host_ok("evil.example")
    assert _host_name("[::1]:80") == "::1" and _host_name("[::1]x") is None and _host_name("a b") is None


def test_without_bind_host_the_embedding_server_checks_hosts(client):
    """create_app without bind_host (a library embedding, the other tests' clients): no Host check."""
    assert client.get("/api/families", headers={"host": "anything.example"}).status_code == 200


# --------------------------------------------------------------------------- cross-site writes


@pytest.mark.parametrize("headers", [
    {"origin": "http://evil.example"},
    {"origin": "null"},  # a sandboxed frame or a file: page
    {"origin": "http://127.0.0.1:8001"},  # another port is another origin
    {"sec-fetch-site": "cross-site"},
    {"sec-fetch-site": "same-site", "origin": "http://127.0.0.1:8000"},  # Sec-Fetch-Site decides
])
def test_cross_origin_cancel_is_refused_and_the_run_lives(guarded, web_catalogue, headers):
    c, run_id = guarded
    before = _status(web_catalogue, run_id)
    r = c.post(f"/api/runs/{run_id}/cancel", headers=headers)
    _one_line(r, 403, "cross-origin request refused")
    assert _status(web_catalogue, run_id) == before != "cancelled"


@pytest.mark.parametrize("ctype", ["text/plain", "application/x-www-form-urlencoded",
                                   "multipart/form-data; boundary=x", "text/plain;charset=UTF-8"])
def test_form_and_text_bodies_are_refused_where_json_is_expected(guarded, web_catalogue, ctype):
    c, run_id = guarded
    r = c.post(f"/api/runs/{run_id}/cancel", content=b"x=1", headers={"content-type": ctype})
    _one_line(r, 415, "send application/json")
    assert _status(web_catalogue, run_id) != "cancelled"
    r = c.post("/api/render", content=json.dumps({"name": "4^4"}), headers={"content-type": ctype})
    _one_line(r, 415, ctype.split(";")[0])


def test_same_origin_writes_and_json_bodies_pass(guarded, web_catalogue):
    """The control: the app's own page (same origin) and a script (no Origin) still write."""
    c, run_id = guarded
    r = c.post("/api/render", json={"name": "4^4", "size": 64}, headers={"origin": "http://127.0.0.1:8000"})
    assert r.status_code == 200 and r.text.startswith("<svg")
    r = c.post("/api/render", content=json.dumps({"name": "4^4", "size": 64}),
               headers={"content-type": "application/vnd.api+json", "sec-fetch-site": "same-origin"})
    assert r.status_code == 200
    r = c.post(f"/api/runs/{run_id}/cancel", headers={"sec-fetch-site": "same-origin",
                                                      "origin": "http://127.0.0.1:8000"})
    assert r.status_code == 200 and _status(web_catalogue, run_id) == "cancelled"


def test_reads_from_other_sites_are_not_writes(guarded):
    """GET is never state-changing here: an <img> on another site may load a thumbnail."""
    c, _ = guarded
    r = c.get("/thumb/4^4.svg", headers={"sec-fetch-site": "cross-site", "origin": "http://evil.example"})
    assert r.status_code == 200


# --------------------------------------------------------------------------- hostile input


def test_deep_nesting_is_one_line_and_leaves_no_recursion_error(client, caplog, capsys):
    caplog.set_level(logging.DEBUG)
    body = b'{"name": "4^4", "params": ' + b"[" * 30_000 + b"]" * 30_000 + b"}"
    r = client.post("/api/render", content=body, headers={"content-type": "application/json"})
    _one_line(r, 400, "nest more than")
    logged = caplog.text + "".join(capsys.readouterr())
    assert "RecursionError" not in logged and "Traceback" not in logged


@pytest.mark.parametrize(("body", "fragment"), [
    ({"name": "IH16", "size": True}, "size true is a boolean, not a number"),
    ({"name": "IH16", "params": [True, False]}, "params true is a boolean, not a number"),
    ({"name": "penrose-p3", "r1": False}, "r1 false is a boolean"),
    ({"name": "4^4", "region": [True, 0, 3, 3]}, "region true is a boolean"),
    ({"name": "IH16", "colours": 5}, "colours 5 is a int; give a list of colour strings"),
    ({"name": "IH16", "colours": [1, 2]}, "colours must be a list of colour strings"),
    ({"name": "IH16", "colours": {"a": "red"}}, "is a dict; give a list of colour strings"),
    ({"name": "IH16", "size": "9" * 5000}, "size of 5,000 characters is not a number"),
    ({"name": "penrose-p3", "depth": "9" * 5000}, "depth of 5,000 digits is out of range"),
])
def test_wrong_types_are_400_naming_the_expected_type(client, body, fragment):
    r = client.post("/api/render", json=body)
    _one_line(r, 400, fragment)


def test_a_5000_digit_number_gets_our_message(client):
    """Python refuses int('9' * 5000) in its own words ('Exceeds the limit (4300 digits) ...');
    the API counts the digits first."""
    raw = b'{"name": "penrose-p3", "depth": ' + b"9" * 5000 + b"}"
    r = client.post("/api/render", content=raw, headers={"content-type": "application/json"})
    _one_line(r, 400, "request body: an integer of 5,000 digits is out of range (at most 30)")
    assert "4300" not in r.text and "sys.set_int_max_str_digits" not in r.text
    r = client.get("/api/render/penrose-p3", params={"depth": "9" * 5000})
    _one_line(r, 400, "depth of 5,000 digits is out of range")
    r = client.get("/api/query", params={"offset": "9" * 5000})
    _one_line(r, 400, "offset of 5,000 digits must be between 0 and 4611686018427387904")


def test_offset_2_to_the_62_is_accepted(client, web_catalogue):
    """docs/web.md documents offset up to 2**62: a page past the end is empty, not an error."""
    big = str(2**62)
    r = client.get("/api/query", params={"offset": big, "limit": 5})
    assert r.status_code == 200 and r.json()["items"] == [] and r.json()["offset"] == 2**62
    r = client.get(f"/api/runs/{web_catalogue.web_test_run}/results", params={"offset": big})
    assert r.status_code == 200 and r.json()["rows"] == [] and r.json()["total"] == 30
    assert client.get("/family/archimedean", params={"offset": big}).status_code == 200
    _one_line(client.get("/api/query", params={"offset": str(2**62 + 1)}), 400, "must be between 0 and")


def test_query_string_over_the_limit_is_our_json_414(client):
    r = client.get("/api/query?where=" + "a" * 20_000)
    _one_line(r, 414, "query string over 8192 bytes")
    assert r.headers["content-type"] == "application/json"
