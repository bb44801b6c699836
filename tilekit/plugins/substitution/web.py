"""The substitution family's page in ``tilekit serve`` (tilekit_web_routes): the Penrose
quasivertex editor ``/penrose`` (§6.3, Figure 6.13; its script in static/), over the render
API of ``penrose-p3``. The web layer knows it only as this plugin's contribution."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from tilekit.plugins import WebRoute
from tilekit.plugins.substitution import quasivertex as qv
from tilekit.web.pages import esc

#: The name this plugin's static files are served under (/static/plugins/substitution/).
STATIC = "substitution"
STATIC_DIR = Path(__file__).with_name("static")
#: The tiling the editor shapes.
EDITED = "penrose-p3"
#: The editor's opening values (Figure 6.13's kind of shape).
START = qv.QuasivertexParams(r1=0.15, theta1=20.0, r2=0.1, theta2=-15.0)
#: The r sliders' domain (edge lengths); within it each is limited to its admissible range.
R_DOMAIN = (0.0, 1.0)
#: The r sliders' step; admissible ends are rounded inward to it.
R_STEP = 0.001


def r_ranges(params: qv.QuasivertexParams) -> dict[str, list[float] | None]:
    """For r1 and r2: the slider range [lo, hi] (a multiple of R_STEP inside the admissible
    run of :func:`~.quasivertex.admissible_range`, the other three parameters fixed), or None
    when no value of it makes both rhombs simple."""
    out: dict[str, list[float] | None] = {}
    for name in ("r1", "r2"):
        run = qv.admissible_range(params, name, *R_DOMAIN)
        if run is None:
            out[name] = None
            continue
        lo = round(math.ceil(run[0] / R_STEP - 1e-9) * R_STEP, 6)
        hi = round(math.floor(run[1] / R_STEP + 1e-9) * R_STEP, 6)
        out[name] = [lo, hi] if lo <= hi else None
    return out


def ranges_api(request: Any, web: Any) -> dict[str, Any]:
    """``/api/penrose/range?r1=..&theta1=..&r2=..&theta2=..``: the r sliders' admissible ranges."""
    options = web.render_options(request)
    params = qv.QuasivertexParams.from_options({k: options[k] for k in qv.PARAM_NAMES if k in options})
    return {"params": params.as_dict(), **r_ranges(params)}


def penrose_page(request: Any, web: Any) -> str:
    """The Penrose quasivertex editor (the P3 rhombs' edges shaped by r1, θ1, r2, θ2); the r
    sliders are limited to the values that keep both rhombs simple (:func:`r_ranges`)."""
    ranges = r_ranges(START)
    r1 = ranges["r1"] or list(R_DOMAIN)
    r2 = ranges["r2"] or list(R_DOMAIN)
    rows = "".join(
        f'<label>{esc(k)} <input type="range" id="{esc(k)}" min="{lo:g}" max="{hi:g}" step="{st:g}" value="{v:g}">'
        f'<output id="{esc(k)}-out">{v:g}</output></label>'
        for k, lo, hi, st, v in (("r1", r1[0], r1[1], R_STEP, START.r1), ("theta1", -90, 90, 1, START.theta1),
                                 ("r2", r2[0], r2[1], R_STEP, START.r2), ("theta2", -90, 90, 1, START.theta2),
                                 ("extent", 2, 8, 0.5, 4)))
    body = f"""<h1>Penrose quasivertex editor</h1>
<p>The P3 rhombs with the quasivertex parameters (r1, θ1, r2, θ2) of §6.3 (Figure 6.13), drawn
on a substituted patch covering the square of half-width <i>extent</i> (the depth follows). The r
sliders reach only the values that keep both rhombs simple for the other three; an angle that
makes them self-intersect is refused with the reason (the exports keep the last tiling drawn).</p>
<div class="editor" id="penrose"><div class="controls">{rows}
<p><a id="export-svg" href="#" download="penrose.svg">export SVG</a>
<a id="export-spec" href="#" download="penrose.json">export spec</a></p>
<p class="error" id="error" role="alert"></p></div><div class="view" id="view"></div></div>"""
    return web.page("Penrose editor", body, scripts=["live.js", f"plugins/{STATIC}/penrose.js"])


ROUTES = (
    WebRoute("/penrose", penrose_page),
    WebRoute("/api/penrose/range", ranges_api,
             doc="the Penrose editor's admissible r1 and r2 ranges for ?r1=&theta1=&r2=&theta2="),
)


def tiling_links(name: str, tiling: Any) -> list[tuple[str, str]]:
    """The editor link on the page of the P3 tiling."""
    return [("/penrose", "open in the Penrose quasivertex editor")] if name == EDITED else []
