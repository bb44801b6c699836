"""The curved plugin's pages in ``tilekit serve`` (tilekit_web_routes, docs/web.md): the
curved-space viewer, ``/curved/NAME`` for every record of the spherical, hyperbolic,
curved and curved-isohedral families and ``/curved?p=7&q=3`` for any {p, q}, with its data at
``/api/curved/NAME`` and ``/api/curved?p=..&q=..``.

The page gets the patch once, as model coordinates (the hyperboloid's (x, y, t) or the
sphere's (x, y, z)), and its script (static/viewer.js) moves the view client-side: a drag in
the Poincaré disc composes the hyperbolic translation taking the drag's start point to its
end point onto the view (a Lorentz matrix acting on the hyperboloid points, then drawn as
true arcs); a drag on the sphere composes the rotation taking the start point to the end
point (orthographic view). Tiles beyond the patch are never needed: the payload carries the
tiling's symmetries that move the disc's centre a short way, and whenever the point under
the screen's centre is farther than ``rebase`` from the patch's centre the script folds one
of them into the view (V <- V g): the tiling is g-invariant, so the picture is unchanged and
the patch again surrounds the screen's centre. The web layer knows these pages only as this
plugin's contribution."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.errors import ParameterError
from tilekit.plugins import WebRoute
from tilekit.plugins.curved import CURVED, CURVED_ISOHEDRAL, HYPERBOLIC, SPHERICAL, regular
from tilekit.plugins.curved.model import check_pq
from tilekit.plugins.curved.render import DEFAULT_PALETTE
from tilekit.web.pages import esc, name_path

#: The name this plugin's static files are served under (/static/plugins/curved/).
STATIC = "curved"
STATIC_DIR = Path(__file__).with_name("static")
FAMILIES = (SPHERICAL, HYPERBOLIC, CURVED, CURVED_ISOHEDRAL)
#: Faces the viewer's hyperbolic patch holds at most (its radius is the largest up to
#: MAX_VIEW_RADIUS within this count and the app's tile limit).
VIEW_FACES = 2500
MAX_VIEW_RADIUS = 6.0
#: Symmetries sent for rebasing: those moving the pole at most this far.
SYMMETRY_REACH = 3.0
#: Points per edge of a sphere face's outline (edges are drawn as polylines there).
SPHERE_SAMPLES = 8


def _radius_for(tiling: Any, budget: int) -> float:
    """The largest radius up to MAX_VIEW_RADIUS (to 0.05) whose face estimate is within budget."""
    lo, hi = 0.5, MAX_VIEW_RADIUS
    if tiling.configure(radius=hi).estimate_tiles() <= budget:
        return hi
    if tiling.configure(radius=lo).estimate_tiles() > budget:
        raise ParameterError(f"{tiling.name}: even a disc of radius {lo:g} holds more than {budget} faces, "
                             "the viewer's limit")
    while hi - lo > 0.05:
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if tiling.configure(radius=mid).estimate_tiles() <= budget else (lo, mid)
    return lo


def symmetries(tiling: Any, reach: float) -> np.ndarray:
    """(n, 3, 3) proper symmetries g of the hyperbolic ``tiling`` moving the pole at most
    ``reach`` (the identity among them): a regular tiling's tile transforms (its rotation
    group is simply transitive on the tiles), a Wythoffian one's cells, or the tiling's own
    ``symmetries(reach)``."""
    own = getattr(tiling, "symmetries", None)
    if callable(own):
        return np.asarray(own(reach))
    construction = getattr(tiling, "construction", None)
    if construction is not None:
        return construction.cells(reach)
    mats = tiling.configure(radius=reach).patch().transform
    return mats[mats[:, 2, 2] <= math.cosh(reach) * (1 + 1e-12)]


def view_data(tiling: Any, max_tiles: int) -> dict[str, Any]:
    """What the viewer draws: per face its corners (hyperbolic) or sampled outline (sphere)
    on the model, flat, with the faces' sizes and colours (by kind of face); for a hyperbolic tiling the
    patch's radius and the symmetries for rebasing (row-major 3x3 each)."""

    if getattr(tiling, "family", "") not in FAMILIES:
        raise ParameterError(f"{tiling.name} is a {getattr(tiling, 'family', '?')} tiling; the curved-space viewer "
                             f"draws the {', '.join(FAMILIES)} families")
    hyperbolic = bool(tiling.hyperbolic)
    out: dict[str, Any] = {"name": tiling.name, "geometry": HYPERBOLIC if hyperbolic else SPHERICAL,
                           "palette": list(DEFAULT_PALETTE)}
    if hyperbolic:
        radius = _radius_for(tiling, min(VIEW_FACES, max_tiles))
        tiling = tiling.configure(radius=radius)
        out["radius"] = radius
    else:
        tiling = tiling.configure(samples=SPHERE_SAMPLES)
    patch = tiling.patch()
    kinds = np.asarray(patch.prototile, dtype=np.int64)
    chosen = [proto.points[list(proto.corners)] if hyperbolic and proto.corners else proto.points
              for proto in patch.prototiles]
    sizes = np.array([len(c) for c in chosen], dtype=np.int64)[kinds]
    start = np.cumsum(sizes) - sizes  # each face's first row, faces in patch order
    flat = np.zeros((int(sizes.sum()), 3))
    by_proto = {id(proto): c for proto, c in zip(patch.prototiles, chosen, strict=True)}
    for _, idx, proto in patch.parts():
        corners = by_proto[id(proto)]
        v = np.matmul(patch.transform[idx], corners.T).transpose(0, 2, 1)
        flat[start[idx][:, None] + np.arange(len(corners))] = v
    out["sizes"] = sizes.tolist()
    out["points"] = np.round(flat.reshape(-1), 10).tolist()
    # colour by the kind of face, which the symmetries keep (a layer colouring would jump when
    # the view is rebased); an isohedral tiling by its perfect colouring, whose rebasing
    # symmetries keep the colours (CurvedIsohedralTiling.symmetries)
    out["colour"] = (patch.colour if tiling.family == CURVED_ISOHEDRAL else kinds).tolist()
    if hyperbolic:
        sym = symmetries(tiling, SYMMETRY_REACH)
        out["symmetries"] = np.round(sym.reshape(-1), 12).tolist()
    return out


def _tiling(request: Any, web: Any, name: str | None) -> Any:
    if name is not None:
        return web.renderer.base_tiling(name)

    p, q = (request.query_params.get(k, d) for k, d in (("p", "7"), ("q", "3")))
    return regular(*check_pq(p, q))


def data_api(request: Any, web: Any) -> dict[str, Any]:
    name = request.path_params.get("name")
    return view_data(_tiling(request, web, name), web.max_tiles)


def viewer_page(request: Any, web: Any) -> str:
    """The viewer of one record (``/curved/NAME``) or of {p, q} (``/curved?p=7&q=3``)."""
    name = request.path_params.get("name")
    tiling = _tiling(request, web, name)
    if getattr(tiling, "family", "") not in FAMILIES:
        raise ParameterError(f"{tiling.name} is a {getattr(tiling, 'family', '?')} tiling; the curved-space viewer "
                             f"draws the {', '.join(FAMILIES)} families")
    if name is not None:
        src = f"/api/curved/{name_path(name)}"
        heading = f'<a href="/tiling/{esc(name_path(name))}">{esc(name)}</a>'
    else:
        src = f"/api/curved?p={tiling.p}&q={tiling.q}"
        heading = esc(f"{{{tiling.p},{tiling.q}}}")
    hyperbolic = bool(tiling.hyperbolic)
    how = ("Drag to translate the Poincaré disc: the view moves by the hyperbolic translation taking the point "
           "under the pointer where the drag began to where it is now." if hyperbolic else
           "Drag to turn the sphere: the rotation taking the point under the pointer where the drag began to "
           "where it is now.") + " The wheel or a two-finger pinch zooms about the pointer (1x to 16x)."
    body = f"""<h1>{heading}</h1>
<p>{esc(getattr(tiling, 'title', '') or tiling.describe())}</p>
<p>{esc(how)} <button type="button" id="reset">reset view</button></p>
<div class="curved-viewer" id="curved" data-src="{esc(src)}" data-state="loading">
<div class="view" id="view"></div><p id="status"></p><p class="error" id="error" role="alert"></p></div>"""
    return web.page(f"viewer: {tiling.name}", body, scripts=[f"plugins/{STATIC}/viewer.js"])


ROUTES = (
    WebRoute("/curved", viewer_page),
    WebRoute("/curved/{name:str}", viewer_page),
    WebRoute("/api/curved", data_api, doc="the curved-space viewer's patch of {p,q} (?p=7&q=3): model "
             "coordinates, sizes, colours, symmetries"),
    WebRoute("/api/curved/{name:str}", data_api, doc="the curved-space viewer's patch of a spherical, "
             "hyperbolic or curved record"),
)


def tiling_links(name: str, tiling: Any) -> list[tuple[str, str]]:
    """The viewer on the page of every spherical, hyperbolic and curved tiling."""
    if getattr(tiling, "family", "") in FAMILIES:
        return [(f"/curved/{name_path(name)}", "open in the curved-space viewer (drag to move)")]
    return []
