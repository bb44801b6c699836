"""The substitution family's page in ``tilekit serve`` (tilekit_web_routes): the Penrose
quasivertex editor ``/penrose`` (§6.3: P3's Figure 6.13, or with ``?tiling=p2`` the kite and
dart of quasivertex_p2.py; its script in static/), over the render API of ``penrose-p3`` /
``penrose-p2``. The web layer knows it only as this plugin's contribution."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from tilekit.errors import ParameterError
from tilekit.plugins import WebRoute
from tilekit.plugins.substitution import quasivertex as qv
from tilekit.web.pages import esc

#: The name this plugin's static files are served under (/static/plugins/substitution/).
STATIC = "substitution"
STATIC_DIR = Path(__file__).with_name("static")
#: The tilings the editor shapes, by the ``?tiling=`` value that picks them.
EDITED = qv.BY_TILING
#: What each one's tiles are called on the page.
TILE_WORDS = {"penrose-p3": ("the P3 rhombs", "both rhombs", "Figure 6.13"),
              "penrose-p2": ("the P2 kite and dart", "the kite and the dart", "derived from P2 patches")}
#: The editor's opening values (Figure 6.13's kind of shape).
START = qv.QuasivertexParams(r1=0.15, theta1=20.0, r2=0.1, theta2=-15.0)
#: The r sliders' domain (edge lengths); within it each is limited to its admissible range.
R_DOMAIN = (0.0, 1.0)
#: The r sliders' step; admissible ends are rounded inward to it.
R_STEP = 0.001


def edited_system(value: Any) -> str:
    """The system of ``?tiling=`` (p3 when absent), or a one-line ParameterError naming the valid ones."""
    key = "p3" if value is None else str(value).lower()
    if key not in EDITED:
        raise ParameterError(f"tiling={value!r} has no quasivertex editor; valid: {', '.join(EDITED)}")
    return EDITED[key]


def r_ranges(params: qv.QuasivertexParams, system: str = "penrose-p3") -> dict[str, list[float] | None]:
    """For r1 and r2: the slider range [lo, hi] (a multiple of R_STEP inside the admissible
    run of :func:`~.quasivertex.admissible_range`, the other three parameters fixed), or None
    when no value of it makes both tiles simple."""
    out: dict[str, list[float] | None] = {}
    for name in ("r1", "r2"):
        run = qv.admissible_range(params, name, *R_DOMAIN, system_name=system)
        if run is None:
            out[name] = None
            continue
        lo = round(math.ceil(run[0] / R_STEP - 1e-9) * R_STEP, 6)
        hi = round(math.floor(run[1] / R_STEP + 1e-9) * R_STEP, 6)
        out[name] = [lo, hi] if lo <= hi else None
    return out


def ranges_api(request: Any, web: Any) -> dict[str, Any]:
    """``/api/penrose/range?r1=..&theta1=..&r2=..&theta2=..[&tiling=p2]``: the r sliders' admissible ranges."""
    system = edited_system(request.query_params.get("tiling"))
    options = web.render_options(request, own=("tiling",))  # tiling: this API's own, not a render option
    params = qv.QuasivertexParams.from_options({k: options[k] for k in qv.PARAM_NAMES if k in options})
    return {"params": params.as_dict(), "system": system, **r_ranges(params, system)}


def penrose_page(request: Any, web: Any) -> str:
    """The Penrose quasivertex editor (the P3 rhombs', or with ?tiling=p2 the kite and dart's,
    edges shaped by r1, θ1, r2, θ2); the r sliders are limited to the values that keep both
    tiles simple (:func:`r_ranges`)."""
    system = edited_system(request.query_params.get("tiling"))
    tiles, both, source = TILE_WORDS[system]
    ranges = r_ranges(START, system)
    r1 = ranges["r1"] or list(R_DOMAIN)
    r2 = ranges["r2"] or list(R_DOMAIN)
    rows = "".join(
        f'<label>{esc(k)} <input type="range" id="{esc(k)}" min="{lo:g}" max="{hi:g}" step="{st:g}" value="{v:g}">'
        f'<output id="{esc(k)}-out">{v:g}</output></label>'
        for k, lo, hi, st, v in (("r1", r1[0], r1[1], R_STEP, START.r1), ("theta1", -90, 90, 1, START.theta1),
                                 ("r2", r2[0], r2[1], R_STEP, START.r2), ("theta2", -90, 90, 1, START.theta2),
                                 ("extent", 2, 8, 0.5, 4)))
    other = [f'<a href="/penrose?tiling={k}">{esc(v)}</a>' for k, v in EDITED.items() if v != system]
    body = f"""<h1>Penrose quasivertex editor</h1>
<p>{esc(tiles).capitalize()} with the quasivertex parameters (r1, θ1, r2, θ2) of §6.3 ({esc(source)}), drawn
on a substituted patch covering the square of half-width <i>extent</i> (the depth follows). The r
sliders reach only the values that keep {esc(both)} simple for the other three; an angle that
makes them self-intersect is refused with the reason (the exports keep the last tiling drawn).
Also: {", ".join(other)}.</p>
<div class="editor" id="penrose" data-system="{esc(system)}"><div class="controls">{rows}
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
    """The editor link on the pages of the P3 and P2 tilings."""
    keys = [k for k, v in EDITED.items() if v == name]
    return [(f"/penrose?tiling={keys[0]}" if keys[0] != "p3" else "/penrose",
             "open in the Penrose quasivertex editor")] if keys else []
