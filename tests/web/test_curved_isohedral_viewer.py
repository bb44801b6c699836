"""The curved-space viewer on curved-isohedral records (/curved/curved-ih-P-Q-N): the payload
carries the perfect colouring and only symmetries that keep it (proper Lorentz maps, each
carrying every face it moves onto a face of the same colour), so a drag that rebases the view
never changes a tile's colour; in chromium long drags rebase and the disc stays covered."""

from __future__ import annotations

import numpy as np
import pytest

from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling


def _faces(body: dict) -> list[np.ndarray]:
    pts = np.array(body["points"]).reshape(-1, 3)
    out, at = [], 0
    for n in body["sizes"]:
        out.append(pts[at:at + n])
        at += n
    return out


def test_isohedral_record_payload_keeps_its_colours_under_the_rebasing_symmetries(client):
    answer = client.get("/api/curved/curved-ih-4-5-2")      # [abab; ba]: U edges, group 5*2, five colours
    body = answer.json()
    assert answer.status_code == 200, body
    assert body["geometry"] == "hyperbolic"
    colours = np.array(body["colour"])
    t = CurvedIsohedralTiling(4, 5, symbol="[abab; ba]")
    assert len(set(colours.tolist())) == t.colour_count == 5
    j = np.diag([1.0, 1.0, -1.0])
    syms = np.array(body["symmetries"]).reshape(-1, 3, 3)
    assert len(syms) > 5
    assert np.allclose(syms.transpose(0, 2, 1) @ j @ syms, j, atol=1e-6) and (np.linalg.det(syms) > 0).all()
    centres = np.array([f.sum(axis=0) / np.sqrt(-(f.sum(axis=0) @ j @ f.sum(axis=0))) for f in _faces(body)])
    near = centres[:, 2] < 20.0
    moved_total = 0
    for g in syms:
        img = centres[near] @ g.T
        d = np.abs(img[:, None, :] - centres[None, :, :]).max(axis=2)
        hit = d.min(axis=1) < 1e-6 * np.maximum(1.0, np.abs(img).max(axis=1))
        moved_total += int(hit.sum())
        assert (colours[near][hit] == colours[d.argmin(axis=1)[hit]]).all()
    assert moved_total > 100


def test_sphere_isohedral_record_opens(client):
    answer = client.get("/api/curved/curved-ih-4-3-5")
    body = answer.json()
    assert answer.status_code == 200, body
    assert body["geometry"] == "spherical" and len(body["sizes"]) == 6
    assert 'href="/curved/curved-ih-4-3-5"' in client.get("/tiling/curved-ih-4-3-5").text


pytest.importorskip("playwright")


def test_long_drags_on_an_isohedral_record_rebase_and_keep_the_disc_covered(page):
    errors: list[str] = []
    page.on("console", lambda msg: errors.append(msg.text) if msg.type == "error" else None)
    page.goto("/curved/curved-ih-5-4-5")
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    box = page.eval_on_selector("#disc", "s => { const r = s.getBoundingClientRect(); const v = s.viewBox.baseVal; "
                                "return [r.left, r.top, r.width, r.height, v.x, v.y, v.width, v.height]; }")
    left, top, w, h, vx, vy, vw, vh = box

    def px(x: float, y: float) -> tuple[float, float]:
        return left + (x - vx) / vw * w, top + (-y - vy) / vh * h

    for _ in range(2):
        n = int(page.get_attribute("#curved", "data-renders") or 0)
        page.mouse.move(*px(0.9, 0.05))
        page.mouse.down()
        page.mouse.move(*px(-0.9, -0.05), steps=8)
        page.mouse.up()
        page.wait_for_function("n => Number(document.querySelector('#curved').dataset.renders || 0) > n", arg=n,
                               timeout=20000)
    page.wait_for_timeout(100)
    assert int(page.get_attribute("#curved", "data-rebases") or 0) > 0
    for x, y in [(0.0, 0.0), (0.5, 0.5), (-0.6, 0.3)]:
        got = page.evaluate("p => { const e = document.elementFromPoint(p[0], p[1]); "
                            "return e && e.dataset.face !== undefined ? Number(e.dataset.face) : null; }",
                            list(px(x, y)))
        assert got is not None, (x, y)
    assert not page.js_errors and errors == []


def _box(page) -> list[float]:
    return page.eval_on_selector("#disc", "s => { const r = s.getBoundingClientRect(); const v = s.viewBox.baseVal; "
                                 "return [r.left, r.top, r.width, r.height, v.x, v.y, v.width, v.height]; }")


def _to_client(box, x: float, y: float) -> tuple[float, float]:
    """SVG point (x, y down) to client pixels."""
    left, top, w, h, vx, vy, vw, vh = box
    return left + (x - vx) / vw * w, top + (y - vy) / vh * h


def _to_svg(box, cx: float, cy: float) -> tuple[float, float]:
    left, top, w, h, vx, vy, vw, vh = box
    return vx + (cx - left) / w * vw, vy + (cy - top) / h * vh


def test_wheel_zooms_about_the_pointer_and_reset_restores(page):
    """Wheel up magnifies the drawing (the viewBox shrinks by the zoom factor) and the model
    point under the pointer stays under it; the view matrix is untouched (a zoom is not a
    motion); reset restores zoom 1."""
    page.goto("/curved/curved-ih-4-5-2")
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    view0 = page.get_attribute("#curved", "data-view")
    before = _box(page)
    target = (0.12, -0.2)
    cx, cy = _to_client(before, *target)
    page.mouse.move(cx, cy)
    for _ in range(4):
        page.mouse.wheel(0, -200)
    page.wait_for_function("() => Number(document.querySelector('#curved').dataset.zoom || 1) > 2", timeout=10000)
    zoom = float(page.get_attribute("#curved", "data-zoom"))
    after = _box(page)
    assert 2 < zoom <= 16
    assert abs(after[6] - before[6] / zoom) < 1e-6 * before[6]
    gx, gy = _to_svg(after, cx, cy)
    assert abs(gx - target[0]) < 1e-3 and abs(gy - target[1]) < 1e-3
    assert page.get_attribute("#curved", "data-view") == view0
    page.click("#reset")
    assert float(page.get_attribute("#curved", "data-zoom")) == 1.0
    assert not page.js_errors


def test_pinch_zooms_by_the_fingers_spread(page):
    """Two pointers moving apart from 100 to 250 pixels magnify by 2.5 about their midpoint."""
    page.goto("/curved/curved-ih-4-3-5")
    page.wait_for_selector("#curved[data-state=ok]", timeout=20000)
    before = _box(page)
    mx, my = _to_client(before, 0.1, 0.05)
    page.evaluate("""([mx, my]) => {
        const s = document.querySelector('#disc');
        const ev = (type, id, x) => s.dispatchEvent(new PointerEvent(type, {pointerId: id, clientX: x, clientY: my,
            bubbles: true, pointerType: 'touch', isPrimary: id === 1}));
        ev('pointerdown', 1, mx - 50); ev('pointerdown', 2, mx + 50);
        for (let k = 1; k <= 5; k++) { ev('pointermove', 1, mx - 50 - 15 * k); ev('pointermove', 2, mx + 50 + 15 * k); }
        ev('pointerup', 1, mx - 125); ev('pointerup', 2, mx + 125);
    }""", [mx, my])
    zoom = float(page.get_attribute("#curved", "data-zoom"))
    assert abs(zoom - 2.5) < 1e-6
    after = _box(page)
    gx, gy = _to_svg(after, mx, my)
    assert abs(gx - 0.1) < 1e-3 and abs(gy - 0.05) < 1e-3
    assert not page.js_errors
