"""The substitution family's page in ``tilekit serve`` (tilekit_web_routes): the Penrose
quasivertex editor ``/penrose`` (§6.3, Figure 6.13; its script in static/), over the render
API of ``penrose-p3``. The web layer knows it only as this plugin's contribution."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from tilekit.plugins import WebRoute
from tilekit.web.pages import esc

#: The name this plugin's static files are served under (/static/plugins/substitution/).
STATIC = "substitution"
STATIC_DIR = Path(__file__).with_name("static")
#: The tiling the editor shapes.
EDITED = "penrose-p3"


def penrose_page(request: Any, web: Any) -> str:
    """The Penrose quasivertex editor (the P3 rhombs' edges shaped by r1, θ1, r2, θ2)."""
    rows = "".join(
        f'<label>{esc(k)} <input type="range" id="{esc(k)}" min="{lo}" max="{hi}" step="{st}" value="{v}">'
        f'<output id="{esc(k)}-out">{v}</output></label>'
        for k, lo, hi, st, v in (("r1", 0, 0.5, 0.005, 0.15), ("theta1", -90, 90, 1, 20),
                                 ("r2", 0, 0.5, 0.005, 0.1), ("theta2", -90, 90, 1, -15), ("extent", 2, 8, 0.5, 4)))
    body = f"""<h1>Penrose quasivertex editor</h1>
<p>The P3 rhombs with the quasivertex parameters (r1, θ1, r2, θ2) of §6.3 (Figure 6.13), drawn
on a substituted patch covering the square of half-width <i>extent</i> (the depth follows). Shapes that would self-intersect are refused with the reason.</p>
<div class="editor" id="penrose"><div class="controls">{rows}
<p><a id="export-svg" href="#" download="penrose.svg">export SVG</a>
<a id="export-spec" href="#" download="penrose.json">export spec</a></p>
<p class="error" id="error" role="alert"></p></div><div class="view" id="view"></div></div>"""
    return web.page("Penrose editor", body, scripts=["live.js", f"plugins/{STATIC}/penrose.js"])


ROUTES = (WebRoute("/penrose", penrose_page),)


def tiling_links(name: str, tiling: Any) -> list[tuple[str, str]]:
    """The editor link on the page of the P3 tiling."""
    return [("/penrose", "open in the Penrose quasivertex editor")] if name == EDITED else []
