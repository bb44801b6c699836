"""The curved plugin's pages in ``tilekit serve`` (tilekit_web_routes, docs/web.md): the
curved-space viewer, ``/curved/NAME`` for every record of the spherical, hyperbolic,
curved and curved-isohedral families and ``/curved?p=7&q=3`` for any {p, q}, with its data at
``/api/curved/NAME`` and ``/api/curved?p=..&q=..``.

The page gets the patch once, as model coordinates (the hyperboloid's (x, y, t) or the
sphere's (x, y, z)), and its script (static/viewer.js) moves the view client-side: a drag in
the Poincaré disc composes the hyperbolic translation taking the drag's start point to its
end point onto the view (a Lorentz matrix acting on the hyperboloid points, then drawn as
true arcs); a drag on the sphere composes the rotation taking the start point to the end
point, in orthographic or stereographic view (``?view=``, :func:`view_mode`; the stereographic
view projects from the point opposite the screen's centre with render.py's conventions, every
edge a true arc, the face holding that point drawn as the outside). Tiles beyond the patch
are never needed: the payload carries the tiling's symmetries that move the disc's centre a
short way, and whenever the point under the screen's centre is farther than ``rebase`` from
the patch's centre the script folds one of them into the view (V <- V g): the tiling is
g-invariant, so the picture is unchanged and the patch again surrounds the screen's centre. The web layer knows these pages only as this
plugin's contribution."""

from __future__ import annotations

import json
import math
import shlex
from pathlib import Path
from typing import Any
from urllib.parse import quote

import numpy as np

from tilekit.errors import ParameterError, TilekitError
from tilekit.incidence import shape_classes
from tilekit.plugins import WebRoute
from tilekit.plugins.curved import CURVED, CURVED_ISOHEDRAL, HYPERBOLIC, SPHERICAL, regular
from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling
from tilekit.plugins.curved.laves import LavesTiling
from tilekit.plugins.curved.model import check_pq
from tilekit.plugins.curved.render import DEFAULT_PALETTE
from tilekit.plugins.curved.shaped import parse_edges
from tilekit.plugins.curved.starlaves import StarLavesTiling
from tilekit.web.pages import esc, name_path
from tilekit.web.service import query_options

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
#: Points per edge of a sphere face's outline (edges are drawn as polylines in orthographic
#: view; in stereographic view each piece between two of them as the true arc of its image).
SPHERE_SAMPLES = 8
#: The viewer's views (``?view=``), the default first: the sphere's two projections (as the
#: CLI's ``--set plane=``), and the hyperbolic viewer's one.
SPHERE_VIEWS = ("orthographic", "stereographic")
HYPERBOLIC_VIEWS = ("poincare",)


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


def view_data(tiling: Any, max_tiles: int, sizer: Any = None) -> dict[str, Any]:
    """What the viewer draws: per face its corners (hyperbolic) or sampled outline (sphere)
    on the model, flat, with the faces' sizes and colours (by kind of face); for a hyperbolic tiling the
    patch's radius and the symmetries for rebasing (row-major 3x3 each). The radius is chosen
    by ``sizer``'s face estimates (default the tiling's own): the editor passes the record, whose
    estimates are the shaped tiling's (they depend on the group only) and cost no tile rebuilt."""

    if getattr(tiling, "family", "") not in FAMILIES:
        raise ParameterError(f"{tiling.name} is a {getattr(tiling, 'family', '?')} tiling; the curved-space viewer "
                             f"draws the {', '.join(FAMILIES)} families")
    hyperbolic = bool(tiling.hyperbolic)
    out: dict[str, Any] = {"name": tiling.name, "geometry": HYPERBOLIC if hyperbolic else SPHERICAL,
                           "palette": list(DEFAULT_PALETTE)}
    if hyperbolic:
        radius = _radius_for(tiling if sizer is None else sizer, min(VIEW_FACES, max_tiles))
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
    # the face placed by the identity: the prototile itself (the tile editor marks it)
    out["home"] = int(np.abs(patch.transform - np.eye(3)).sum(axis=(1, 2)).argmin())
    out["points"] = np.round(flat.reshape(-1), 10).tolist()
    # colour by the kind of face, which the symmetries keep (a layer colouring would jump when
    # the view is rebased); an isohedral tiling by its perfect colouring, whose rebasing
    # symmetries keep the colours (CurvedIsohedralTiling.symmetries); a shaped Laves tiling of
    # the sphere (never rebased) by its perfect colouring too
    perfect = tiling.family == CURVED_ISOHEDRAL or (
        not hyperbolic and getattr(tiling, "edge_shapes", None) is not None and patch.colour is not None)
    out["colour"] = (patch.colour if perfect else kinds).tolist()
    if hyperbolic:
        sym = symmetries(tiling, SYMMETRY_REACH)
        out["symmetries"] = np.round(sym.reshape(-1), 12).tolist()
    return out


def view_mode(request: Any, hyperbolic: bool) -> str:
    """The page's view from ``?view=`` (SPHERE_VIEWS or HYPERBOLIC_VIEWS, the first by default);
    a one-line error naming the valid values otherwise."""
    got = request.query_params.get("view")
    valid = HYPERBOLIC_VIEWS if hyperbolic else SPHERE_VIEWS
    if got is None or got == "":
        return valid[0]
    if got not in valid:
        if hyperbolic:
            raise ParameterError(f"view {got[:40]!r}: a hyperbolic tiling is drawn in the Poincaré disc, view=poincare "
                                 f"({', '.join(SPHERE_VIEWS)} are the sphere's)")
        raise ParameterError(f"view {got[:40]!r}: a sphere is drawn {SPHERE_VIEWS[0]} (default) or {SPHERE_VIEWS[1]}, "
                             f"view={SPHERE_VIEWS[0]} or view={SPHERE_VIEWS[1]}")
    return got


def projection_control(mode: str) -> str:
    """The sphere page's control switching between its views (viewer.js reads and follows it)."""
    options = "".join(f'<option value="{v}"{" selected" if v == mode else ""}>{v}</option>' for v in SPHERE_VIEWS)
    return f'<label>view <select id="projection" autocomplete="off">{options}</select></label>'


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
    mode = view_mode(request, hyperbolic)
    how = ("Drag to translate the Poincaré disc: the view moves by the hyperbolic translation taking the point "
           "under the pointer where the drag began to where it is now." if hyperbolic else
           "Drag to turn the sphere: the rotation taking the point under the pointer where the drag began to "
           "where it is now. The stereographic view projects from the point opposite the screen's centre; the "
           "face holding that point is drawn as the outside.") + \
        " The wheel or a two-finger pinch zooms about the pointer (1x to 16x)."
    control = "" if hyperbolic else " " + projection_control(mode)
    editor = ""
    if name is not None and not isinstance(shape_symbol(tiling), str):
        editor = f' <a id="edit" href="/curved/edit/{esc(name_path(name))}">Shape its tiles in the tile editor.</a>'
    body = f"""<h1>{heading}</h1>
<p>{esc(getattr(tiling, 'title', '') or tiling.describe())}{editor}</p>
<p>{esc(how)} <button type="button" id="reset">reset view</button>{control}</p>
<div class="curved-viewer" id="curved" data-src="{esc(src)}" data-state="loading" data-projection="{esc(mode)}">
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
    """The viewer on the page of every spherical, hyperbolic and curved tiling; the tile editor
    on those with edges to shape."""
    if getattr(tiling, "family", "") not in FAMILIES:
        return []
    out = [(f"/curved/{name_path(name)}", "open in the curved-space viewer (drag to move)")]
    if not isinstance(shape_symbol(tiling), str):
        out.append((f"/curved/edit/{name_path(name)}", "shape its tiles in the tile editor (Escher-like)"))
    return out


# --------------------------------------------------------------------------- the tile editor
#
# /curved/edit/NAME: Escher-like tiles on the sphere and the hyperbolic plane (issue 35). One
# edge widget per shape class of the tile's incidence symbol (tilekit/web/static/edgewidget.js,
# the planar editor's), the tiling drawn by the viewer's script from /api/curved/edit/NAME,
# which builds it through the family's ``edges`` option: the geometry exists once, in Python.

#: Faces of the editor's hyperbolic patch (the whole patch is sent again at every edit).
EDIT_FACES = 500
#: The range of a handle, as the edge widget clamps it: x in [-0.5, 1.5], y in [-1, 1] on the
#: unit segment (the API refuses a point outside it).
#: Model points the editor sends at most (three numbers each: about 6 MB of JSON), and the
#: fewest faces it draws of a hyperbolic tiling: a tile of more outline points than that allows
#: (edges of many points) is refused with a one-line error rather than sent.
EDIT_POINTS = 250_000
EDIT_MIN_FACES = 40
#: Points a shape may have between its ends in the editor (a request rebuilds the tile up to
#: three times, and the tile's triangulation grows faster than its outline's points squared).
EDIT_MAX_POINTS = 16
EDIT_X = (-0.5, 1.5)
EDIT_Y = (-1.0, 1.0)


def shape_symbol(tiling: Any) -> tuple[Any, Any] | str:
    """(incidence symbol, label order) whose shape classes ``edges`` names for an editable
    tiling (a curved-isohedral one; a curved Laves one or a vertex-star dual under a group whose
    symbol has J, S or U edges: the rotations, a snub's dual, a star dual's S edges), or the
    one-line reason it has nothing to edit."""
    if isinstance(tiling, CurvedIsohedralTiling):
        symbol, order = tiling.symbol, None
    elif isinstance(tiling, (LavesTiling, StarLavesTiling)):
        symbol, order = tiling.tile_symbol, tiling.label_order
    else:
        return (f"{tiling.name} is a {getattr(tiling, 'family', '?')} tiling; the tile editor shapes the "
                f"{CURVED_ISOHEDRAL} tilings, the curved Laves tilings and the vertex-star duals (under a group "
                "whose tile has edges off its mirrors)")
    if shape_classes(symbol, order):
        return symbol, order
    if order is not None:
        return (f"{tiling.name}: under its group every edge of the tile lies on a mirror (an I edge, straight), "
                "so there is nothing to shape; shaped edges need group=rotations or a snub's dual")
    return f"{tiling.name}: every edge of incidence symbol {symbol} is an I edge (straight): nothing to shape"


def edited(tiling: Any, raw: Any) -> Any:
    """``tiling`` with the edge shapes of the query ``raw`` (:func:`tilekit.web.service.query_options`:
    ``edge=LABEL=SHAPE``, repeated; the family's ``edges`` text per label), the others at the
    family's defaults; every point within EDIT_X x EDIT_Y. One-line errors: a key other than
    edge, a malformed shape, an unknown label, a point out of range, a tile that crosses itself."""
    found = shape_symbol(tiling)
    if isinstance(found, str):
        raise ParameterError(found)
    unknown = sorted(set(raw) - {"edges"})
    if unknown:
        raise ParameterError(f"unknown editor option {unknown[0][:20]!r}; the editor's query is edge=LABEL=x,y:x,y:... "
                             "(one per shape class)")
    edges = raw.get("edges") or []
    if len(edges) > 64:
        raise ParameterError(f"{len(edges)} edge options; give one per shape class (at most 64)")
    shapes = parse_edges(list(edges))
    for label, shape in shapes.items():
        pts = shape.points
        inner = len(shape.path()) - 2
        if inner > EDIT_MAX_POINTS:
            raise ParameterError(f"edge {label!r} has {inner} points between its ends{' once flattened' if shape.smooth else ''}; "
                                 f"the editor takes at most {EDIT_MAX_POINTS}")
        if not ((pts[:, 0] >= EDIT_X[0]) & (pts[:, 0] <= EDIT_X[1]) & (pts[:, 1] >= EDIT_Y[0])
                & (pts[:, 1] <= EDIT_Y[1])).all():
            raise ParameterError(f"edge {label!r}: the editor takes points with x in [{EDIT_X[0]:g}, {EDIT_X[1]:g}] "
                                 f"and y in [{EDIT_Y[0]:g}, {EDIT_Y[1]:g}] (the edge widget's range)")
    if not shapes and getattr(tiling, "edge_shapes", None) is not None:
        return tiling
    return tiling.configure(edges=shapes)


def edge_query(tiling: Any) -> list[str]:
    """``LABEL=SHAPE`` per shape class (exact EdgeShape text): the editor's query, which reopens
    the tiling exactly."""
    return [f"{label}={shape.to_text(exact=True)}" for label, shape in tiling.edge_shapes.items()]


def edge_classes(tiling: Any) -> list[dict[str, Any]]:
    """Per shape class of an editable tiling's symbol (:func:`shape_symbol`): its label, kind
    (J, U, S), smoothness, control points and the tile's edges it shapes (1-based, its partner's
    included): what the edge widgets start from."""
    symbol, order = shape_symbol(tiling)  # type: ignore[misc]
    adj = symbol.adjacent_map()
    out = []
    for label in shape_classes(symbol, order):
        shape = tiling.edge_shapes[label]
        pair = {label, adj[label][0]}
        out.append({"label": label, "kind": symbol.label_kind(label), "smooth": shape.smooth,
                    "points": shape.points.tolist(),
                    "tile_edges": [i + 1 for i, (lab, _) in enumerate(symbol.edges) if lab in pair]})
    return out


def edit_data(name: str, tiling: Any, max_tiles: int, record: Any = None) -> dict[str, Any]:
    """The viewer's data (:func:`view_data`, the patch's radius sized on ``record``, the tiling
    before its edit, when given) of the record ``name`` shaped as ``tiling``, with
    ``edges`` (:func:`edge_classes`), ``query``: the editor's query of the tiling (one
    ``LABEL=SHAPE`` per class); ``link`` the editor's URL, ``svg`` the render API's download and
    ``cli`` the command that renders it (each reopens exactly this tiling)."""
    per_tile = len(tiling.prototiles[0].points)
    faces = min(EDIT_FACES, max_tiles, EDIT_POINTS // per_tile)
    least = EDIT_MIN_FACES if tiling.hyperbolic else math.ceil(tiling.estimate_tiles())
    if faces < least:
        raise ParameterError(f"the shaped tile has {per_tile:,} outline points, and {least} tiles of it are over the "
                             f"editor's {EDIT_POINTS:,} points; give the edges fewer points")
    out = view_data(tiling, faces, record)
    out["edges"] = edge_classes(tiling)
    out["query"] = edge_query(tiling)
    query = _query_text(out["query"])
    out["link"] = f"/curved/edit/{name_path(name)}?{query}"
    out["svg"] = f"/api/render/{name_path(name)}?{query}&download=1"
    out["cli"] = " ".join(["tilekit render", shlex.quote(name), *(f"--edge {shlex.quote(e)}" for e in out["query"]),
                           "-o", shlex.quote(f"{name}.svg")])
    return out


def _edit_target(request: Any, web: Any) -> tuple[str, Any]:
    name = request.path_params["name"]
    return name, web.renderer.base_tiling(name)


def edit_api(request: Any, web: Any) -> dict[str, Any]:
    """/api/curved/edit/NAME?edge=..: the editor's data, or a 400 with the one-line reason."""
    name, base = _edit_target(request, web)
    return edit_data(name, edited(base, query_options(request.query_params.multi_items())), web.max_tiles, base)


def _query_text(edges: list[str]) -> str:
    """``edge=..&edge=..`` with the shapes' , : = left readable."""
    return "&".join("edge=" + quote(e, safe=",:=") for e in edges)


def edit_page(request: Any, web: Any) -> str:
    """The tile editor of one record: /curved/edit/NAME?edge=LABEL=SHAPE&... (a refused query
    shows its one line and the record's shapes)."""
    name, base = _edit_target(request, web)
    heading = f'<a href="/tiling/{esc(name_path(name))}">{esc(name)}</a>'
    found = shape_symbol(base)
    if isinstance(found, str):
        other = f"{name}-rotations"
        try:
            chiral = shape_symbol(web.renderer.base_tiling(other))
        except TilekitError:
            chiral = "none"
        hint = (f' <a href="/curved/edit/{esc(name_path(other))}">Edit {esc(other)}</a> (its rotation group) instead.'
                if not isinstance(chiral, str) else "")
        body = (f"<h1>tile editor: {heading}</h1>\n<p class=\"error\" id=\"notice\" role=\"alert\">{esc(found)}</p>"
                f"<p>{hint} <a href=\"/curved/{esc(name_path(name))}\">Open it in the viewer.</a></p>")
        return web.page(f"tile editor: {name}", body)
    notice = ""
    mode = view_mode(request, bool(base.hyperbolic))  # the view is the page's, not the tiling's
    try:
        tiling = edited(base, query_options([kv for kv in request.query_params.multi_items() if kv[0] != "view"]))
    except TilekitError as exc:
        notice = web.one_line(exc)
        tiling = edited(base, {})
    edges = edge_query(tiling)
    info = {"name": name, "edges": edge_classes(tiling)}
    how = ("Drag a handle in an edge's widget to reshape that edge class; the tiling is rebuilt on the server "
           "(the family's edges option) and redrawn. Drag the picture to move the view"
           + (" (a hyperbolic translation)." if tiling.hyperbolic else " (a rotation of the sphere)."))
    body = f"""<h1>tile editor: {heading}</h1>
<p>{esc(getattr(tiling, 'title', '') or tiling.describe())}</p>
<p>{esc(how)} J edges are free curves, U and S edges a half completed by the mirror or the half-turn,
I edges stay straight. <button type="button" id="reset">reset view</button>
<button type="button" id="defaults">defaults</button>{"" if tiling.hyperbolic else " " + projection_control(mode)}</p>
<p class="error" id="notice" role="alert">{esc(notice)}</p>
<div class="editor curved-editor">
<div class="edges" id="edges"></div>
<div class="curved-viewer" id="curved" data-src="/api/curved/edit/{esc(name_path(name))}?{esc(_query_text(edges))}"
 data-state="loading" data-info="{esc(json.dumps(info))}" data-mark-home="" data-projection="{esc(mode)}">
<div class="view" id="view"></div><p id="status"></p><p class="error" id="error" role="alert"></p></div>
</div>
<p><a id="link" href="#">link to this tiling</a> · <a id="svg" href="#" download>export SVG</a> ·
<a href="/curved/{esc(name_path(name))}">viewer</a></p>
<p>The command line: <code id="cli"></code></p>"""
    return web.page(f"tile editor: {name}", body,
                    scripts=["edgewidget.js", f"plugins/{STATIC}/viewer.js", f"plugins/{STATIC}/editor.js"])


ROUTES = (*ROUTES,
          WebRoute("/curved/edit/{name:str}", edit_page),
          WebRoute("/api/curved/edit/{name:str}", edit_api, doc="the curved tile editor's data: the viewer's "
                   "patch of a curved-isohedral or chiral Laves record shaped by edge=LABEL=SHAPE (repeated), "
                   "with each shape class's points"))
