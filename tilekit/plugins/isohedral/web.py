"""The isohedral family's pages in ``tilekit serve`` (tilekit_web_routes, docs/web.md): the
editor (exercise 5.12: ``/editor``, ``/editor/IHn?params=..&edge=..``, its script in static/),
``/api/tiling/NAME/editor`` (what the editor needs) and ``/api/parquet/IHn`` (a parquet
deformation, exercise 5.13). The web layer knows none of them by name: they are this plugin's
contributions through the hooks, like its commands."""

from __future__ import annotations

import html
import json
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.edgeshapes import parse_edge_option
from tilekit.errors import ParameterError, TilekitError
from tilekit.incidence import shape_classes
from tilekit.plugins import WebRoute
from tilekit.plugins.isohedral.engine import IsohedralTiling
from tilekit.plugins.isohedral.metamorphosis import metamorphosis
from tilekit.plugins.isohedral.split import SplitTiling
from tilekit.plugins.isohedral.templates import get_template
from tilekit.render import PALETTE, parse_palette
from tilekit.web.pages import esc, name_path, options
from tilekit.web.service import MAX_EDGES

#: The name this plugin's static files are served under (/static/plugins/isohedral/).
STATIC = "isohedral"
STATIC_DIR = Path(__file__).with_name("static")


def isohedral_types() -> list[tuple[str, str]]:
    """(name, title) of the 81 unmarked types, the ones the editor takes."""
    out = []
    for i in range(1, 94):
        t = get_template(i)
        if not t.marked:
            out.append((t.name, f"{t.name} ({getattr(t, 'topology', '')})"))
    return out


def editor_info(tiling: Any) -> dict[str, Any]:
    """What the isohedral editor needs: parameters, edge shape classes with their kinds, the
    tile's outline with the number of outline segments of each tiling edge (where a split's
    boundary positions lie, :mod:`.split`) and the split of a split tiling (else None)."""

    split = None
    if isinstance(tiling, SplitTiling):
        split = {"ends": list(tiling.ends), "points": tiling.path.points.tolist(), "smooth": bool(tiling.path.smooth)}
        tiling = tiling.base
    if not isinstance(tiling, IsohedralTiling):
        raise ParameterError(f"{tiling.name} is not an isohedral tiling; the editor takes IH1..IH93")
    t = tiling.template
    tv = tiling.parameterization
    edges = []
    for label in shape_classes(t.symbol):
        kind = t.symbol.label_kind(label)
        shape = tiling.edge_shapes.get(label)
        edges.append({
            "label": label,
            "kind": kind,
            "points": shape.points.tolist() if shape is not None else [[0.0, 0.0], [1.0, 0.0]],
            "smooth": bool(shape.smooth) if shape is not None else False,
        })
    return {
        "name": tiling.name,
        "ih": t.ih,
        "topology": t.topology,
        "parameterization": t.parameterization,
        "params": list(tiling.params),
        "default": list(tv.default),
        "edges": edges,
        "kinds": t.symbol.edge_kinds(),
        "colouring": str(tiling.colouring),
        "default_colouring": str(t.colouring),
        "spec": tiling.spec(),
        "region": list(tiling.default_region().bounds),
        "parquet": t.topology == "4^4" and tv.parameters == 0,
        "tile": {"outline": np.asarray(tiling.prototile.outline, dtype=float).tolist(),
                 "counts": [len(p) - 1 for p in tiling.edge_paths]},
        "split": split,
        "piece_colours": list(PALETTE[:2]),
    }


def parquet_svg(renderer: Any, name: str, edges: list[str], columns: int = 12, rows: int = 4,
                palette: Any = None, size: int = 1200) -> str:
    """SVG of :func:`parquet_tiles` clipped to the strip."""
    tiles, width, height = parquet_tiles(renderer, name, edges, columns, rows)
    palette = tuple(palette) if palette else PALETTE
    by_colour: dict[int, list[str]] = {}
    for colour, poly in tiles:
        d = "M" + " L".join(f"{x:.5g} {y:.5g}" for x, y in poly.tolist()) + "Z"
        by_colour.setdefault(colour, []).append(d)
    pad = 0.02 * width
    scale = size / (width + 2 * pad)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{round((height + 2 * pad) * scale)}" '
           f'viewBox="{-pad:.6g} {-(height + pad):.6g} {width + 2 * pad:.6g} {height + 2 * pad:.6g}">',
           f'<rect x="{-pad:.6g}" y="{-(height + pad):.6g}" width="{width + 2 * pad:.6g}" '
           f'height="{height + 2 * pad:.6g}" fill="#ffffff"/>',
           f'<clipPath id="strip"><rect x="0" y="0" width="{width:.6g}" height="{height:.6g}"/></clipPath>',
           f'<g transform="scale(1,-1)" clip-path="url(#strip)" stroke="#222" stroke-width="{1.2 / scale:.4g}" '
           'stroke-linejoin="round">']
    for c in sorted(by_colour):
        out.append(f'<path fill="{html.escape(palette[c % len(palette)])}" d="{" ".join(by_colour[c])}"/>')
    out.append("</g></svg>")
    return "\n".join(out)


def parquet_tiles(renderer: Any, name: str, edges: list[str], columns: int = 12,
                  rows: int = 4) -> tuple[list[tuple[int, Any]], float, float]:
    """A parquet deformation (exercise 5.13) of a 4^4 type with fixed square tiling vertices.

    The keyframes are the square (left) and the tile with ``edges`` (right). Every edge of
    every tile takes the shape ``t * shape`` (the keyframe's control points with their offsets
    from the straight edge scaled by t), where t is the x of the edge's midpoint across the
    strip. An edge shared by two tiles has one midpoint and so one shape: the strip is a true
    tiling whose tiles change from column to column. The transforms of the tiles do not
    depend on the edge shapes (the tiling vertices are fixed), so they come from one patch.
    Built by the isohedral family's general :func:`~tilekit.plugins.isohedral.metamorphosis.metamorphosis`.
    """
    if not (2 <= columns <= 40 and 1 <= rows <= 20):
        raise ParameterError(f"a parquet deformation takes 2..40 columns and 1..20 rows, not {columns} x {rows}")
    base = renderer.base_tiling(name)
    if not isinstance(base, IsohedralTiling) or base.template.topology != "4^4" or base.params:
        raise ParameterError(f"{name}: parquet deformations take the 4^4 types with fixed square tiling "
                             "vertices (TV35: IH55, IH61, IH62, IH71, IH73, IH76)")
    shapes = dict(parse_edge_option(e) for e in edges)
    keyframe = base.configure(edges=list(shapes.items()))  # validates the right-hand keyframe
    patch, (_, _, width, height) = metamorphosis(base, keyframe, columns, rows)
    tiles = [(int(patch.colour[k]), np.asarray(p.outline)) for k, p in enumerate(patch.prototiles)]
    return tiles, width, height


# --------------------------------------------------------------------------- pages


#: The picker's edge shape, on every J, U and S shape class: a J edge shows it whole, a U edge
#: its half mirrored, an S edge its half turned, so each type's picture shows its edge kinds
#: (all 81 unmarked types tile validly with it at their default parameters; a test checks).
PICTURE_SHAPE = "0,0:0.3,0.12:0.7,-0.06:1,0"


def picture_edges(tiling: IsohedralTiling) -> list[str]:
    """``LABEL=PICTURE_SHAPE`` for each shape class of the tiling's type that is not I."""
    symbol = tiling.template.symbol
    return [f"{label}={PICTURE_SHAPE}" for label in shape_classes(symbol) if symbol.label_kind(label) != "I"]


#: Names of polygons by their number of corners (the tile of a topology [3^6] has six).
POLYGONS = {3: "triangles", 4: "quadrilaterals", 5: "pentagons", 6: "hexagons"}


def topology_corners(topology: str) -> int:
    """The number of tiling vertices of a tile of Laves topology ``3^4.6`` (4 + 1 = 5)."""
    return sum(int(part.split("^")[1]) if "^" in part else 1 for part in topology.split("."))


def topology_groups() -> list[tuple[str, list[int]]]:
    """The unmarked types grouped by topological type (the Laves tiling of their tiling
    vertices, as Tactile's demos group them): (topology, [ih, ...]) in the order of
    Grünbaum and Shephard's numbering."""
    groups: dict[str, list[int]] = {}
    for i in range(1, 94):
        t = get_template(i)
        if not t.marked:
            groups.setdefault(t.topology, []).append(i)
    return list(groups.items())  # in the order of their first type (IH1: [3^6], ... IH83: [6^3])


def editor_pick_page(web: Any, groups: Sequence[tuple[str, Sequence[int]]]) -> str:
    """The editor's entry page: each type's picture (``/editor/picture/IHn.svg``: its tiling
    with :data:`PICTURE_SHAPE` on every shaped edge) and name, grouped by topology."""
    sections = []
    for topology, ihs in groups:
        corners = topology_corners(topology)
        cards = "".join(
            f'<a class="ih-card" href="/editor/IH{i}" title="IH{i}: {esc(get_template(i).symbol)}">'
            f'<img loading="lazy" alt="IH{i}" width="96" height="96" src="/editor/picture/IH{i}.svg"><span>IH{i}</span></a>'
            for i in ihs)
        sections.append(f'<section class="topology" data-topology="{esc(topology)}"><h2>[{esc(topology)}] '
                        f'{esc(POLYGONS.get(corners, f"{corners}-gons"))} <small>({len(ihs)} type'
                        f'{"s" if len(ihs) != 1 else ""})</small></h2><div class="ih-cards">{cards}</div></section>')
    return web.page("isohedral editor", "<h1>Isohedral editor</h1><p>Pick an isohedral type (exercise 5.12), "
                    "grouped by topological type: the Laves tiling its tiling vertices form, named by the "
                    "valences of a tile's corners (§5.3). The 12 marked types are not editable.</p>"
                    f'<div class="types" id="types">{"".join(sections)}</div>')


def editor_page(web: Any, info: Mapping[str, Any], types: Sequence[str], problem: str | None = None) -> str:
    """The isohedral editor on ``info`` (:func:`editor_info` of the tiling
    the URL configures); ``problem`` is the one line of a refused URL configuration."""
    data = esc(json.dumps(info))
    notice = f' data-notice="{esc(problem)}"' if problem else ""
    pick = options([(t, t) for t in types], info["name"])
    body = f"""<h1>Isohedral editor: {esc(info["name"])}</h1>
<div class="editor" id="editor" data-info="{data}"{notice}>
<div class="controls">
<label>type <select id="type">{pick}</select></label>
<p class="kinds">edges <code>{esc(info["kinds"])}</code>; tiling vertex parameterization {esc(info["parameterization"])}</p>
<h2>Tiling vertex parameters</h2><div id="params"></div>
<h2>Edge shapes</h2><p class="hint">Drag the handles; J edges are free, U edges mirror about their
midpoint's perpendicular, S edges turn half a turn about their midpoint, I edges stay straight
(§5.4). Double-click a segment to add a point, a handle to remove it.</p><div id="edges"></div>
<h2>Split</h2><p class="hint">A splitting path between two boundary points divides every tile
in two (a dihedral tiling, as <code>tilekit escherize GOAL_A GOAL_B</code> writes): drag the ends
along the boundary and the path's points; double-click a point to remove it.</p>
<div id="split"><svg id="split-svg" class="split-svg" hidden><g transform="scale(1,-1)"></g></svg>
<p><button type="button" id="split-add">split the tile</button>
<button type="button" id="split-point" hidden>add path point</button>
<button type="button" id="split-remove" hidden>remove the split</button></p>
<p class="hint"><code id="split-text"></code></p></div>
<h2>View</h2>
<label>zoom <input type="range" id="zoom" min="0.3" max="3" step="0.05" value="1"></label>
<label>rotate <input type="range" id="rotate" min="-180" max="180" step="1" value="0"></label>
<label>colours <select id="palette"><option value="">default</option>
<option value="#f4c27a,#7fb3d5,#e88a8a,#9ccc8f">warm</option>
<option value="#264653,#2a9d8f,#e9c46a,#f4a261,#e76f51">sea</option>
<option value="#ffffff,#dddddd,#bbbbbb,#999999">greys</option>
<option value="#ffffff">plain</option></select></label>
<label>colouring <input id="colouring" value="{esc(info["colouring"])}" size="22"></label>
<p><button type="button" id="reset">reset</button>
<a id="export-svg" href="#" download="tiling.svg">export SVG</a>
<a id="export-spec" href="#" download="tiling.json">export spec</a>
<a id="permalink" href="/editor/{esc(name_path(info["name"]))}" title="this tiling's editor URL (params, edges, colouring)">link</a>
<a id="export-parquet" href="#" download="parquet.svg" hidden>parquet deformation SVG</a></p>
<p class="error" id="error" role="alert">{esc(problem)}</p>
</div>
<div class="view" id="view"></div>
</div>"""
    return web.page(f"editor {info['name']}", body, scripts=["edgewidget.js", f"plugins/{STATIC}/editor.js"])


# --------------------------------------------------------------------------- views


def editor_pick(request: Any, web: Any) -> str:
    return editor_pick_page(web, topology_groups())


def editor(request: Any, web: Any) -> str:
    name = request.path_params["name"]
    t = web.renderer.base_tiling(name)
    if not isinstance(t, IsohedralTiling | SplitTiling):
        raise ParameterError(f"{name} is not an unmarked isohedral type; the editor takes IH1..IH93")
    # /editor/IHn?params=..&edge=..&colouring=..: the JSON API's query syntax and parser; a
    # query the API would refuse is shown as its one line over the type's defaults
    problem = None
    if request.query_params:
        try:
            t = web.renderer.build(name, web.render_options(request))
        except (TilekitError, ValueError, TypeError) as exc:
            problem = web.one_line(exc)
    return editor_page(web, editor_info(t), [n for n, _ in isohedral_types()], problem)


def picture(request: Any, web: Any) -> Any:
    """A type's picture for the picker: its tiling with the picker's shape on every J, U and S
    edge (a thumbnail through the renderer's cache)."""
    from starlette.responses import Response

    name = request.path_params["name"]
    base = web.renderer.base_tiling(name)
    if not isinstance(base, IsohedralTiling):
        raise ParameterError(f"{name} is not an unmarked isohedral type; pictures are of IH1..IH93's 81 unmarked types")
    _, svg, _ = web.renderer.render(name, {"size": 160, "edges": picture_edges(base)}, thumbnail=True)
    return Response(svg, media_type="image/svg+xml", headers={"Cache-Control": "public, max-age=3600"})


def editor_api(request: Any, web: Any) -> dict[str, Any]:
    tiling = web.renderer.build(request.path_params["name"], web.render_options(request))
    return editor_info(tiling)


def parquet(request: Any, web: Any) -> Any:
    from starlette.responses import Response

    q = request.query_params
    edges = q.getlist("edge")
    if len(edges) > MAX_EDGES:
        raise ParameterError(f"at most {MAX_EDGES} edges")
    name = request.path_params["name"]
    svg = parquet_svg(web.renderer, name, edges, web.query_int(request, "columns", 12, 2, 40),
                      web.query_int(request, "rows", 4, 1, 20),
                      parse_palette(q.get("colours")) if q.get("colours") else None)
    headers = {"Content-Disposition": f'attachment; filename="{name}-parquet.svg"'} if q.get("download") else {}
    return Response(svg, media_type="image/svg+xml", headers=headers)


ROUTES = (
    WebRoute("/editor", editor_pick),
    WebRoute("/editor/{name:str}", editor),
    WebRoute("/editor/picture/{name:str}.svg", picture),
    WebRoute("/api/tiling/{name:str}/editor", editor_api,
             doc="parameters and edge shape classes of an isohedral tiling"),
    WebRoute("/api/parquet/{name:str}", parquet,
             doc="a parquet deformation SVG (4^4 types with fixed square vertices): ?edge=&columns=12&rows=4"),
)


def tiling_links(name: str, tiling: Any) -> list[tuple[str, str]]:
    """The editor link on the page of an unmarked isohedral tiling."""
    if isinstance(tiling, IsohedralTiling):
        return [(f"/editor/{name_path(name)}", "open in the isohedral editor")]
    return []
