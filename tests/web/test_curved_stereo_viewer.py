"""The sphere viewer's stereographic view (/curved/NAME?view=stereographic, issue 35) in chromium:
every face drawn once, the one holding the projection's pole as the outside; every piece of an
outline drawn as SVG arcs of the circle that is the image of its great circle (a stereographic
projection takes circles on the sphere to circles or lines: Needham, *Visual Complex Analysis*,
§3.IV, or Coxeter, *Introduction to Geometry*, §6.9), checked on the paths read back from the
DOM against the page's rotation and tilekit's own projection (model.stereographic); a vertex
shared by neighbouring faces drawn at the same point in both; a drag turns the sphere by the
rotation taking the sphere point under the drag's start to the one under its end; switching
views keeps the rotation and the address bar says the view; a bad ``view`` is a one-line 400."""

from __future__ import annotations

import re

import numpy as np
import pytest
from test_curved_viewer import _face_at, _pixels

from tilekit.plugins.curved import model
from tilekit.plugins.curved.render import circle_through

pytest.importorskip("playwright")

CMD = re.compile(r"([MLA])([^MLAZ]*)")


def _view(page) -> np.ndarray:
    return np.array([float(x) for x in page.get_attribute("#curved", "data-view").split(",")]).reshape(3, 3)


def _open(page, url: str) -> list[str]:
    errors: list[str] = []
    page.on("console", lambda msg: errors.append(msg.text) if msg.type == "error" else None)
    page.goto(url)
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    return errors


def _paths(page) -> dict[int, tuple[str, str | None]]:
    got = page.eval_on_selector_all("#disc path", "els => els.map(e => [Number(e.dataset.face), e.getAttribute('d'), "
                                    "e.dataset.tile || null])")
    return {face: (d, tile) for face, d, tile in got}


def _commands(d: str, outside: bool) -> tuple[np.ndarray, list[tuple[str, list[float]]]]:
    """A face's path: its start point and its commands (letter, numbers), y up; the outside's
    frame (its first subpath) left off."""
    if outside:
        d = d.split("Z", 1)[1]
    cmds = [(c, [float(x) for x in args.split()]) for c, args in CMD.findall(d)]
    (c0, start), rest = cmds[0], cmds[1:]
    assert c0 == "M"
    return np.array([start[0], -start[1]]), rest


def _flip(n: list[float]) -> np.ndarray:
    return np.array([n[-2], -n[-1]])


def _sphere_from_plane(p: np.ndarray, scale: float) -> np.ndarray:
    """The inverse of model.stereographic (scaled): the sphere point drawn at plane point p."""
    u = np.asarray(p) / scale
    r2 = (u * u).sum()
    return np.array([2 * u[0], 2 * u[1], 1 - r2]) / (1 + r2)


def _check_drawing(page, client, name: str) -> None:
    """Every face once, one outside; each outline point drawn where tilekit's projection of the
    turned sphere puts it; each piece two SVG arcs of the circle through its projected ends and
    geodesic midpoint, on which a further point of that geodesic lies; shared vertices coincide."""
    body = client.get(f"/api/curved/{name}").json()
    sizes = body["sizes"]
    pts = np.array(body["points"]).reshape(-1, 3)
    view, scale = _view(page), float(page.get_attribute("#curved", "data-equator"))
    paths = _paths(page)
    assert sorted(paths) == list(range(len(sizes)))
    outside = [f for f, (_, tile) in paths.items() if tile == "outside"]
    assert len(outside) == 1 and page.get_attribute("#curved", "data-outside") == str(outside[0])
    # the outside holds the pole (0, 0, -1) of the view: its centre is the nearest to it
    offsets = np.cumsum([0, *sizes])
    turned = pts @ view.T
    centres = np.array([turned[offsets[f]:offsets[f + 1]].mean(axis=0) for f in range(len(sizes))])
    assert int(np.argmin(centres[:, 2])) == outside[0]
    drawn, arcs = {}, 0
    for f, k in enumerate(sizes):
        q = turned[offsets[f]:offsets[f + 1]]
        want = model.stereographic(q) * scale
        start, cmds = _commands(paths[f][0], f == outside[0])
        a, b = q, np.roll(q, -1, axis=0)
        mid = (a + b) / np.linalg.norm(a + b, axis=1, keepdims=True)
        quarter = (a + mid) / np.linalg.norm(a + mid, axis=1, keepdims=True)
        pa, pm, pb = (model.stereographic(x) * scale for x in (a, mid, b))
        centre, radius, straight = circle_through(pa, pm, pb)
        ends, at = [start], 0
        for i in range(k):
            if straight[i]:  # its great circle passes through the pole: a line
                assert cmds[at][0] == "L"
                ends.append(_flip(cmds[at][1]))
                at += 1
                continue
            (c1, n1), (c2, n2) = cmds[at], cmds[at + 1]
            at += 2
            assert c1 == c2 == "A" and n1[:5] == n2[:5]
            # the drawn radius is the circle's, through the projected midpoint, and a point a
            # quarter along the geodesic lies on that circle; sweep 0 is counter-clockwise in the
            # model plane (y is flipped in SVG), the small arc
            assert np.isclose(n1[0], radius[i], rtol=1e-5, atol=2e-6) and n1[0] == n1[1] and n1[3] == 0
            assert np.allclose(_flip(n1), pm[i], atol=2e-6, rtol=1e-6)
            assert np.isclose(np.linalg.norm(model.stereographic(quarter[i]) * scale - centre[i]), radius[i], rtol=1e-7)
            u, w = pm[i] - pa[i], pb[i] - pm[i]
            ccw = u[0] * w[1] - u[1] * w[0] > 0
            assert n1[4] == (0 if ccw else 1)
            ends.append(_flip(n2))
            arcs += 1
        assert at == len(cmds)
        ends = np.array(ends)
        assert np.allclose(ends[:k], want, atol=2e-6, rtol=1e-6) and np.allclose(ends[k], ends[0], atol=2e-6)
        drawn[f] = ends[:k]
    assert arcs > sum(sizes) / 2  # most pieces are arcs (a line only where a great circle meets the pole)
    # neighbouring faces: a model vertex of two faces is drawn at the same point in both (1e-6)
    shared = 0
    for f in range(len(sizes)):
        for g in range(f + 1, len(sizes)):
            pf, pg = pts[offsets[f]:offsets[f + 1]], pts[offsets[g]:offsets[g + 1]]
            close = np.linalg.norm(pf[:, None] - pg[None], axis=2) < 1e-8
            for i, j in zip(*np.nonzero(close), strict=True):
                assert np.abs(drawn[f][i] - drawn[g][j]).max() <= 1e-6 + 1e-12
                shared += 1
    assert shared >= len(sizes)


@pytest.mark.parametrize(("name", "faces"), [("cube", 6), ("icosahedron", 20), ("truncated-icosahedron", 32),
                                           ("pentagonal-icositetrahedron", 24), ("curved-ih-4-3-1", 6)])
def test_stereographic_view_draws_every_face_once_with_true_arcs(page, client, name, faces):
    """Face counts: the cube 6, the icosahedron 20 (Coxeter, *Regular Polytopes*, table I), the
    truncated icosahedron 12 + 20 and the pentagonal icositetrahedron 24 (the snub cube's 24
    vertices; Cundy and Rollett, *Mathematical Models*, §3.7), and the cube's faces with shaped
    edges (curved-ih-4-3-1: pieces of geodesics between many outline points, not convex)."""
    errors = _open(page, f"/curved/{name}?view=stereographic")
    assert page.get_attribute("#curved", "data-projection") == "stereographic"
    assert page.eval_on_selector("#projection", "s => s.value") == "stereographic"
    assert page.eval_on_selector_all("#disc path[data-face]", "els => els.length") == faces
    _check_drawing(page, client, name)
    assert not page.js_errors and errors == []


def test_stereographic_drag_turns_the_sphere_and_zoom_keeps_the_faces(page, client):
    errors = _open(page, "/curved/cube?view=stereographic")
    before, v0 = _paths(page), _view(page)
    scale = float(page.get_attribute("#curved", "data-equator"))
    a, b = np.array([0.3, -0.2]), np.array([-0.45, 0.5])  # b's sphere point is on the far side
    (ax, ay), (bx, by) = _pixels(page, [a, b])
    n = int(page.get_attribute("#curved", "data-renders") or 0)
    page.mouse.move(ax, ay)
    page.mouse.down()
    page.mouse.move(bx, by, steps=12)
    page.mouse.up()
    page.wait_for_function("n => Number(document.querySelector('#curved').dataset.renders || 0) > n", arg=n)
    page.wait_for_timeout(100)
    v = _view(page)
    r = v @ v0.T
    pa, pb = _sphere_from_plane(a, scale), _sphere_from_plane(b, scale)
    assert pb[2] < 0 and np.allclose(r @ pa, pb, atol=1e-6) and np.allclose(r @ r.T, np.eye(3), atol=1e-9)
    after = _paths(page)
    assert len(after) == 6 and all(after[f][0] != before[f][0] for f in range(6))
    _check_drawing(page, client, "cube")
    # the wheel magnifies the view about the pointer: the same six faces, a smaller viewBox
    box = page.eval_on_selector("#disc", "s => s.viewBox.baseVal.width")
    page.mouse.move(ax, ay)
    page.mouse.wheel(0, -400)
    page.wait_for_function("w => document.querySelector('#disc').viewBox.baseVal.width < w", arg=box)
    assert float(page.get_attribute("#curved", "data-zoom")) > 1
    assert page.eval_on_selector_all("#disc path[data-face]", "els => els.length") == 6
    assert not page.js_errors and errors == []


def test_switching_views_keeps_the_rotation_and_the_url_says_the_view(page, client):
    errors = _open(page, "/curved/icosahedron")
    assert page.get_attribute("#curved", "data-projection") == "orthographic"
    (ax, ay), (bx, by) = _pixels(page, [(0.2, 0.1), (-0.3, 0.25)])
    page.mouse.move(ax, ay)
    page.mouse.down()
    page.mouse.move(bx, by, steps=8)
    page.mouse.up()
    page.wait_for_timeout(200)
    v = page.get_attribute("#curved", "data-view")
    centre = _pixels(page, [(0.0, 0.0)])[0]
    front = _face_at(page, centre)
    assert front is not None
    page.select_option("#projection", "stereographic")
    page.wait_for_function("() => document.querySelector('#curved').dataset.outside !== undefined")
    assert page.get_attribute("#curved", "data-view") == v  # the same rotation
    assert _face_at(page, _pixels(page, [(0.0, 0.0)])[0]) == front  # the same face at the screen's centre
    assert page.url.endswith("/curved/icosahedron?view=stereographic")
    _check_drawing(page, client, "icosahedron")
    page.goto(page.url)  # the address reopens the same view
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    assert page.get_attribute("#curved", "data-projection") == "stereographic"
    assert page.eval_on_selector_all("#disc path[data-tile=outside]", "els => els.length") == 1
    page.select_option("#projection", "orthographic")
    page.wait_for_function("() => document.querySelector('#curved').dataset.outside === undefined")
    assert page.url.endswith("/curved/icosahedron")
    assert page.eval_on_selector_all("#disc path[data-tile=outside]", "els => els.length") == 0
    assert not page.js_errors and errors == []


def test_the_sphere_editor_keeps_the_stereographic_view(page):
    """The tile editor of a sphere record draws in the same views; its address bar keeps ?view=."""
    errors = _open(page, "/curved/edit/pentagonal-icositetrahedron?view=stereographic")
    assert page.eval_on_selector_all("#disc path[data-face]", "els => els.length") == 24
    assert page.eval_on_selector_all("#disc path[data-tile=outside]", "els => els.length") == 1
    assert "view=stereographic" in page.url and "edge=" in page.url
    assert not page.js_errors and errors == []


def test_bad_view_values_are_one_line_400s(client):
    bad = client.get("/curved/cube?view=mercator")
    assert bad.status_code == 400
    assert ("view &#x27;mercator&#x27;: a sphere is drawn orthographic (default) or stereographic, "
            "view=orthographic or view=stereographic") in bad.text
    hyper = client.get("/curved/hyperbolic-7-3?view=stereographic")
    assert hyper.status_code == 400 and "view=poincare" in hyper.text
    assert client.get("/curved/hyperbolic-7-3?view=poincare").status_code == 200
    assert client.get("/curved/edit/pentagonal-icositetrahedron?view=x").status_code == 400
    ok = client.get("/curved/cube?view=stereographic")
    assert ok.status_code == 200 and 'data-projection="stereographic"' in ok.text
    assert '<option value="stereographic" selected>' in ok.text
    assert 'id="projection"' not in client.get("/curved/hyperbolic-7-3").text
    # the data API is the same in either view (the page projects it)
    assert client.get("/api/curved/cube").json() == client.get("/api/curved/cube?view=stereographic").json()
