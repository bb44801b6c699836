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

    for _ in range(3):
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
