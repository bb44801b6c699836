"""Screenshots of the web pages for docs/web.md: python docs/images/make_web_screenshots.py URL.

Drives Debian's chromium through Playwright against a running ``tilekit serve``.
"""

from __future__ import annotations

import sys
from pathlib import Path

from playwright.sync_api import sync_playwright

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
HERE = Path(__file__).parent

PAGES = [
    ("web-search.png", "/?family=archimedean", None),
    ("web-tiling.png", "/tiling/IH16", None),
    ("web-family.png", "/family/isohedral", None),
    ("web-editor.png", "/editor/IH21", "#editor[data-state=ok]"),
    ("web-editor-types.png", "/editor", None),
    ("web-editor-split.png", "/editor/IH1?params=0.12,0.5,0.15,0.6&edge=a=0.2,0.1:0.4,0.12:0.6,-0.1:0.8,-0.05"
     "&edge=b=0.25,-0.1:0.5,-0.1:0.6,0.1:0.8,0.05&edge=c=0.2,0.1:0.4,0.1:0.6,0.1:0.8,0.05"
     "&set=split=0.4,3.6;0,0:0.3,0.15:0.7,-0.1:1,0", "#editor[data-state=ok]"),
    ("web-penrose.png", "/penrose", "#penrose[data-state=ok]"),
    ("web-curved-editor.png", "/curved/edit/curved-ih-5-4-5?edge=a=0,0:0.2,0.12:0.36,0.02:1,0"
     "&edge=c=0,0:0.22,0.18:0.5,-0.16:0.8,0.1:1,0", "#curved[data-state=ok]"),
    ("web-curved-stereographic.png", "/curved/truncated-icosahedron?view=stereographic", "#curved[data-state=ok]"),
    ("web-run.png", "/runs/2?limit=12", None),
    # a catalogue with the polyominoes classified to 8 cells (run 2): a non-tiler's record
    ("web-polyform.png", "/tiling/.x...%2F.x...%2Fxx...%2F.xxxx", None),
    ("web-polyominoes.png", "/family/polyomino?where=tiles%3Dfalse&view=table", None),
]


def shape_edges(page) -> None:
    """Give every edge of the editor a point and drag it, as a user would."""
    for i in range(page.locator(".edge .add-point").count()):
        page.locator(".edge .add-point").nth(i).click()
        handle = page.locator(".edge").nth(i).locator(".handle").first
        box = handle.bounding_box()
        x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(x + 12 * (-1) ** i, y - 10, steps=4)
        page.mouse.up()
    page.wait_for_timeout(800)
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)


def drag_curved_handle(page) -> None:
    """Drag the curved tile editor's first handle of edge c up, as a user would."""
    handle = page.locator("#edge-c .handle").first
    box = handle.bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 6, y - 14, steps=4)
    page.mouse.up()
    page.wait_for_timeout(1500)
    page.wait_for_function("() => !document.querySelector('#curved').dataset.busy", timeout=20000)


def main(base: str, only: list[str]) -> None:
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=FLAGS, headless=True)
        page = browser.new_page(viewport={"width": 1280, "height": 860})
        for name, path, ready in PAGES:
            if only and name not in only:
                continue
            page.goto(base + path, wait_until="networkidle")
            if ready:
                page.wait_for_selector(ready, timeout=20000)
            if name == "web-editor.png":
                shape_edges(page)
            if name == "web-curved-editor.png":
                drag_curved_handle(page)
            page.evaluate("window.scrollTo(0, 0)")
            page.wait_for_timeout(300)
            # the split panel is below the edge widgets, the curved editor's links below the disc:
            # the whole page
            page.screenshot(path=str(HERE / name), full_page=name in ("web-editor-split.png", "web-curved-editor.png",
                                                                   "web-curved-stereographic.png"))
            print("wrote", HERE / name)
        browser.close()


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "http://127.0.0.1:8000", sys.argv[2:])
