"""The curved plugin's viewer (/curved/NAME) in chromium: a drag in the Poincaré disc moves the
view by the hyperbolic translation taking the drag's start point to its end point, checked
against that Möbius map computed here in complex arithmetic (z -> (z + c)/(1 + conj(c) z)
conjugated, Beardon, *The Geometry of Discrete Groups*, §7.4), on the tiles' corners read back
from the DOM; a drag on the sphere turns it by the rotation taking start to end."""

from __future__ import annotations

import re

import numpy as np
import pytest

pytest.importorskip("playwright")

CMD = re.compile(r"([MLA])([^MLAZ]*)")


def corners(d: str) -> np.ndarray:
    """The disc points a viewer path visits (y up): M's point, then each A's or L's end point."""
    out = []
    for _cmd, args in CMD.findall(d):
        nums = [float(x) for x in args.split()]
        out.append((nums[-2], -nums[-1]))
    return np.array(out[:-1] if len(out) > 1 and np.allclose(out[0], out[-1]) else out)


def tau(c: complex, z: np.ndarray) -> np.ndarray:
    return (z + c) / (1 + np.conj(c) * z)


def translation(a: complex, b: complex, z: np.ndarray) -> np.ndarray:
    """The hyperbolic translation of the disc along the geodesic through a and b taking a to b."""
    w = tau(-a, np.array([b]))[0]
    return tau(a, tau(w, tau(-a, z)))


def _pixels(page, pts):
    box = page.eval_on_selector("#disc", "s => { const r = s.getBoundingClientRect(); const v = s.viewBox.baseVal; "
                                "return [r.left, r.top, r.width, r.height, v.x, v.y, v.width, v.height]; }")
    left, top, w, h, vx, vy, vw, vh = box
    return [(left + (x - vx) / vw * w, top + (-y - vy) / vh * h) for x, y in pts]


def _face_at(page, xy) -> int | None:
    got = page.evaluate("p => { const e = document.elementFromPoint(p[0], p[1]); "
                        "return e && e.dataset.face !== undefined ? Number(e.dataset.face) : null; }", list(xy))
    return got


def _console_errors(page) -> list[str]:
    """The console's error messages from now on (the page fixture records uncaught exceptions)."""
    errors: list[str] = []
    page.on("console", lambda msg: errors.append(msg.text) if msg.type == "error" else None)
    return errors


def _wait_render(page, before: int) -> None:
    page.wait_for_function("n => Number(document.querySelector('#curved').dataset.renders || 0) > n", arg=before,
                           timeout=20000)


def _drag(page, a, b, steps: int = 12) -> None:
    (ax, ay), (bx, by) = _pixels(page, [a, b])
    n = int(page.get_attribute("#curved", "data-renders") or 0)
    page.mouse.move(ax, ay)
    page.mouse.down()
    page.mouse.move(bx, by, steps=steps)
    page.mouse.up()
    _wait_render(page, n)
    page.wait_for_timeout(100)  # the last animation frame


def test_drag_translates_the_disc_by_the_mobius_map(page):
    console = _console_errors(page)
    page.goto("/curved/hyperbolic-7-3")
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    a, b = (0.21 + 0.13j), (-0.32 + 0.27j)
    under = _face_at(page, _pixels(page, [(a.real, a.imag)])[0])
    assert under is not None
    before = corners(page.get_attribute(f'#disc path[data-face="{under}"]', "d"))
    assert len(before) == 7  # a heptagon of {7,3}
    _drag(page, (a.real, a.imag), (b.real, b.imag))
    z = before[:, 0] + 1j * before[:, 1]
    want = translation(a, b, z)
    # the face now drawn with those corners (after any rebasing it may carry another index)
    ds = page.eval_on_selector_all("#disc path", "els => els.map(e => [Number(e.dataset.face), e.getAttribute('d')])")
    match = []
    for face, d in ds:
        c = corners(d)
        got = c[:, 0] + 1j * c[:, 1]
        if len(got) == 7 and np.abs(got[:, None] - want[None, :]).min(axis=0).max() < 2e-5:
            match.append(face)
    assert len(match) == 1
    # the tile under the drag's start is now under its end, and it was not there before
    assert _face_at(page, _pixels(page, [(b.real, b.imag)])[0]) == match[0]
    assert not np.allclose(np.abs(want - z), 0)
    assert not page.js_errors and console == []


def test_long_drags_rebase_by_symmetries_and_the_disc_stays_covered(page):
    """Drags far past the patch's radius: the view is rebased by the tiling's symmetries
    (data-rebases) and the screen's centre and a point near the rim are still on tiles
    whose corners lie on a regular heptagon (equal distances from their mean on the hyperboloid)."""
    console = _console_errors(page)
    page.goto("/curved/hyperbolic-7-3")
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    for _ in range(2):
        _drag(page, (0.9, 0.05), (-0.9, -0.05), steps=8)
    assert int(page.get_attribute("#curved", "data-rebases") or 0) > 0
    for xy in [(0.0, 0.0), (0.0, 0.93)]:
        face = _face_at(page, _pixels(page, [xy])[0])
        assert face is not None
        c = corners(page.get_attribute(f'#disc path[data-face="{face}"]', "d"))
        r2 = (c * c).sum(axis=1)
        hyp = np.column_stack([2 * c, 1 + r2]) / (1 - r2)[:, None]
        centre = hyp.sum(axis=0)
        centre /= np.sqrt(centre[2] ** 2 - centre[0] ** 2 - centre[1] ** 2)
        cosh = hyp[:, 2] * centre[2] - hyp[:, :2] @ centre[:2]
        assert len(c) == 7 and np.ptp(cosh) < 1e-4 * cosh.mean()
    assert not page.js_errors and console == []


def test_sphere_turns_by_the_rotation_from_start_to_end(page):
    console = _console_errors(page)
    page.goto("/curved/cube")
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    v0 = np.array([float(x) for x in page.get_attribute("#curved", "data-view").split(",")]).reshape(3, 3)
    a, b = (0.3, -0.2), (-0.25, 0.35)
    _drag(page, a, b)
    v = np.array([float(x) for x in page.get_attribute("#curved", "data-view").split(",")]).reshape(3, 3)
    r = v @ v0.T
    pa = np.array([a[0], a[1], np.sqrt(1 - a[0] ** 2 - a[1] ** 2)])
    pb = np.array([b[0], b[1], np.sqrt(1 - b[0] ** 2 - b[1] ** 2)])
    assert np.allclose(r @ pa, pb, atol=1e-6) and np.allclose(r @ r.T, np.eye(3), atol=1e-9)
    assert np.allclose(r @ np.cross(pa, pb), np.cross(pa, pb), atol=1e-6)  # the axis through both is fixed
    assert not page.js_errors and console == []


def test_viewer_api_sends_model_points_and_lorentz_symmetries(client):
    """The payload of a non-Wythoffian record: corners on the hyperboloid (x^2 + y^2 - t^2 = -1),
    symmetries in O(2,1) (g^T J g = J); bad {p,q}, and a record of another family, are one-line
    400s naming what is valid."""
    answer = client.get("/api/curved/3%5E3.6%5E2")
    body = answer.json()
    assert answer.status_code == 200, (answer.status_code, body)
    assert body["geometry"] == "hyperbolic" and set(body["sizes"]) == {3, 6}
    pts = np.array(body["points"]).reshape(-1, 3)
    assert len(pts) == sum(body["sizes"]) and np.allclose(pts[:, 0] ** 2 + pts[:, 1] ** 2 - pts[:, 2] ** 2, -1, atol=1e-6)
    j = np.diag([1.0, 1.0, -1.0])
    syms = np.array(body["symmetries"]).reshape(-1, 3, 3)
    assert len(syms) > 5 and np.allclose(syms.transpose(0, 2, 1) @ j @ syms, j, atol=1e-6)
    bad = client.get("/api/curved", params={"p": 2, "q": 3})
    assert bad.status_code == 400 and "p must be an integer 3..60, got 2" in bad.json()["error"]
    other = client.get("/curved/IH16")
    assert other.status_code == 400 and "draws the spherical, hyperbolic, curved, curved-isohedral families" in other.text
    assert 'href="/curved/3%5E3.6%5E2"' in client.get("/tiling/3%5E3.6%5E2").text


def test_a_hyperbolic_vertex_species_row_opens_the_curved_record(species_catalogue, species_client):
    """After `search vertex-species`, the name 3^3.6^2 is also a row of the vertex_species
    table (a hyperbolic type: the row's own family draws no plane tiling). The row's page and
    the viewer's data show the curved family's record of that name instead of an error (this
    failed whenever a test that runs the search shared the web app with this file)."""
    cat, _ = species_catalogue
    assert cat.result_entry("3^3.6^2").family == "vertex-species"
    answer = species_client.get("/api/curved/3%5E3.6%5E2")
    assert answer.status_code == 200 and answer.json()["geometry"] == "hyperbolic"
    page = species_client.get("/tiling/3%5E3.6%5E2")
    assert page.status_code == 200 and "no plane tiling" not in page.text and "<svg" in page.text
    # a non-Wythoffian type found by the pairing search (catalogue/curved/stars.toml, issue 35)
    assert cat.result_entry("4^2.6^2").family == "vertex-species"
    assert species_client.get("/api/curved/4%5E2.6%5E2").json()["geometry"] == "hyperbolic"
    page = species_client.get("/tiling/4%5E2.6%5E2")
    assert page.status_code == 200 and "<svg" in page.text
