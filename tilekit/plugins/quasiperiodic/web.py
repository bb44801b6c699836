"""The quasiperiodic family's page in ``tilekit serve`` (tilekit_web_routes): ``/multigrid``,
de Bruijn's multigrid with a slider per grid offset gamma_j (§6.3, §7.2: moving the offsets
slides the grids and re-forms the rhombs), over the render API's ``set=gamma=...``. Its
script is in static/; the web layer knows the page only as this plugin's contribution."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from tilekit.plugins import WebRoute
from tilekit.web.pages import esc

#: The name this plugin's static files are served under (/static/plugins/quasiperiodic/).
STATIC = "quasiperiodic"
STATIC_DIR = Path(__file__).with_name("static")
FAMILY = "quasiperiodic"


def multigrid_page(request: Any, web: Any) -> str:
    """One select for the catalogue's multigrid tilings, a slider per offset (made by the
    script from the chosen record's gamma), the extent of the square drawn."""
    names = [e.name for e in web.catalogue.query(family=FAMILY)]
    chosen = request.query_params.get("name", "multigrid-5")
    if chosen not in names and names:
        chosen = names[0]
    options = "".join(f'<option value="{esc(n)}"{" selected" if n == chosen else ""}>{esc(n)}</option>'
                      for n in names)
    body = f"""<h1>Multigrid offsets</h1>
<p>de Bruijn's multigrid (§6.3): the grids of parallel lines, one per slider, shifted by their
offsets gamma<sub>j</sub>; every crossing of two lines is a rhomb. Offsets whose lines meet three
at a point (a singular multigrid) are refused with the reason.</p>
<div class="editor" id="multigrid"><div class="controls">
<label>tiling <select id="tiling">{options}</select></label>
<div id="offsets"></div>
<label>extent <input type="range" id="extent" min="2" max="12" step="0.5" value="5"><output id="extent-out">5</output></label>
<p><a id="export-svg" href="#" download="multigrid.svg">export SVG</a></p>
<p class="error" id="error" role="alert"></p></div><div class="view" id="view"></div></div>"""
    return web.page("Multigrid offsets", body, scripts=["live.js", f"plugins/{STATIC}/multigrid.js"])


ROUTES = (WebRoute("/multigrid", multigrid_page),)


def tiling_links(name: str, tiling: Any) -> list[tuple[str, str]]:
    """The offsets page on the page of every multigrid tiling."""
    return [(f"/multigrid?name={name}", "move its grid offsets")] if getattr(tiling, "family", "") == FAMILY else []
