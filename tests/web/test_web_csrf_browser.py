"""Chromium against a --writable server (issue 30): a page on another origin that auto-submits
a form at the cancel endpoint does not cancel the run; the app's own cancel button does."""

from __future__ import annotations

import pytest
from cliutil import serving

pytest.importorskip("playwright")

ATTACK = """<!doctype html><html><body>
<form id="f" method="POST" action="{action}" enctype="{enctype}">
<input type="hidden" name="{name}" value="{value}"></form>
<script>document.getElementById("f").submit();</script></body></html>"""


@pytest.fixture(scope="module")
def writable_server(web_catalogue):
    from tilekit.web import create_app

    app = create_app(catalogue=web_catalogue, writable=True, bind_host="127.0.0.1")
    with serving(app) as url:
        yield url


@pytest.mark.parametrize(("enctype", "name", "value"), [
    ("application/x-www-form-urlencoded", "x", "1"),
    ("text/plain", '{"a":"', '"}'),  # the classic text/plain body that reads as JSON
    ("multipart/form-data", "x", "1"),
])
def test_cross_origin_form_does_not_cancel_the_run(browser, writable_server, web_catalogue, enctype, name, value):
    cat = web_catalogue
    run_id = cat.create_run("demo", {"n": 1}, [{"i": 0}])
    owner = cat.start_worker(run_id, "csrf-test")
    context = browser.new_context()
    try:
        before = cat.run(run_id).status
        assert before != "cancelled"
        action = f"{writable_server}/api/runs/{run_id}/cancel"
        html = ATTACK.format(action=action, enctype=enctype, name=name, value=value)
        # http://attacker.test is another origin; Playwright answers for it, so no DNS is needed
        context.route("http://attacker.test/**", lambda route: route.fulfill(
            status=200, content_type="text/html", body=html))
        page = context.new_page()
        with page.expect_response(lambda r: r.url == action) as answer:
            page.goto("http://attacker.test/page.html")
        response = answer.value
        assert response.request.method == "POST"
        assert response.status == 403, (response.status, response.text())  # it reached the server
        assert "cross-origin request refused" in response.json()["error"]
        assert cat.run(run_id).status == before

        # the control: the app's own page, same origin, cancels with its button
        own = context.new_page()
        own.goto(f"{writable_server}/runs/{run_id}")
        with own.expect_response(lambda r: r.url == action) as answer:
            own.click("#cancel")
        assert answer.value.status == 200
        assert cat.run(run_id).status == "cancelled"
    finally:
        context.close()
        cat.finish_worker(owner)
        cat.delete_run(run_id)
