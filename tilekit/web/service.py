"""The service layer behind the pages and the API: options -> tiling -> bounded SVG/PNG.

It mirrors ``tilekit render``: a catalogue tiling, ``configure(**options)`` with params,
edges, depth and the family's own settings, a region (default: the tiling's own), the
palette; then :func:`tilekit.web.limits.check_render_size` before any patch is built.
"""

from __future__ import annotations

import hashlib
import json
import threading
from collections import OrderedDict
from collections.abc import Iterable, Mapping
from typing import Any

from tilekit.cli import parse_region as cli_parse_region
from tilekit.errors import ParameterError, ParseError
from tilekit.geometry import as_region
from tilekit.plugins.isohedral.engine import IsohedralTiling, shape_classes
from tilekit.plugins.isohedral.metamorphosis import metamorphosis
from tilekit.plugins.isohedral.shapes import parse_edge_option
from tilekit.render import PALETTE, parse_palette, patch_to_svg
from tilekit.schema import finite_number
from tilekit.web.limits import DEFAULT_MAX_TILES, RenderTooLarge, check_render_size

#: Options a render request may carry besides the tiling's name.
RENDER_KEYS = ("params", "edges", "depth", "region", "colours", "colouring", "size", "r1", "theta1", "r2",
               "theta2", "seed", "labels")
MAX_SIZE = 2000
MAX_EDGES = 32
MAX_POINTS = 64




def _numbers(value: Any, what: str) -> list[float]:
    if isinstance(value, str):
        value = [v for v in value.split(",") if v.strip()]
    if not isinstance(value, list | tuple):
        raise ParseError(f"{what} {value!r} is not a list of numbers")
    if len(value) > 64:
        raise ParameterError(f"{what}: at most 64 numbers, got {len(value)}")
    return [finite_number(v, what) for v in value]


def parse_region(value: Any) -> tuple[float, float, float, float] | None:
    """A region from ``x0,y0,x1,y1`` text or a list of four numbers: the command line's
    ``--region`` parser (the same bounds and messages)."""
    if value is None or value == "":
        return None
    if not isinstance(value, str):
        value = ",".join(str(finite_number(v, "region")) for v in (value if isinstance(value, list | tuple) else [value]))
    return cli_parse_region(value)


def query_options(items: Iterable[tuple[str, str]]) -> dict[str, Any]:
    """Raw render options from a query string's (key, value) pairs, in order.

    ``edge``/``edges`` repeat (one ``LABEL=x,y:x,y:...`` each) and become a list;
    ``param``/``params`` repeat and are joined with commas; any other key keeps its last value.
    With :func:`normalise_options` this is the parser of ``/api/render/NAME``,
    ``/api/tiling/NAME/spec`` and the editor page ``/editor/IHn``; its inverse for isohedral
    tilings is :func:`tilekit.plugins.isohedral.spec.editor_query`.
    """
    raw: dict[str, Any] = {}
    params: list[str] = []
    for key, value in items:
        if key in ("edge", "edges"):
            raw.setdefault("edges", []).append(value)
        elif key in ("param", "params"):
            params.append(value)
            raw["params"] = ",".join(params)
        else:
            raw[key] = value
    return raw


def normalise_options(raw: Mapping[str, Any]) -> dict[str, Any]:
    """Typed render options from a JSON body or a query string (unknown keys refused)."""
    unknown = sorted(set(raw) - set(RENDER_KEYS) - {"name", "format", "download"})
    if unknown:
        raise ParameterError(f"unknown render option(s) {', '.join(map(repr, unknown))}; valid: {', '.join(RENDER_KEYS)}")
    out: dict[str, Any] = {}
    if raw.get("params") not in (None, "", []):
        out["params"] = _numbers(raw["params"], "params")
    edges = raw.get("edges")
    if edges not in (None, "", []):
        if isinstance(edges, str):
            edges = [edges]
        if isinstance(edges, Mapping):
            edges = [f"{k}={v}" for k, v in edges.items()]
        if not isinstance(edges, list | tuple) or not all(isinstance(e, str) for e in edges):
            raise ParseError("edges must be a list of 'LABEL=x,y:x,y:...' strings")
        if len(edges) > MAX_EDGES or any(e.count(":") > MAX_POINTS for e in edges):
            raise ParameterError(f"at most {MAX_EDGES} edges of {MAX_POINTS} points each")
        out["edges"] = list(edges)
    if raw.get("depth") not in (None, ""):
        d = raw["depth"]
        if isinstance(d, bool) or not (isinstance(d, int) or (isinstance(d, str) and d.strip().isdigit())):
            raise ParseError(f"depth {d!r} is not a whole number >= 0")
        out["depth"] = int(d)
    for key in ("r1", "theta1", "r2", "theta2"):
        if raw.get(key) not in (None, ""):
            out[key] = finite_number(raw[key], key)
    for key in ("colouring", "seed"):
        if raw.get(key) not in (None, ""):
            out[key] = str(raw[key])[:200]
    return out


class Renderer:
    """Builds and renders tilings for one catalogue, with an LRU cache keyed by spec hash."""

    def __init__(self, catalogue: Any, max_tiles: int = DEFAULT_MAX_TILES, cache_size: int = 1024) -> None:
        self.catalogue = catalogue
        self.max_tiles = max_tiles
        self.cache_size = cache_size
        self._cache: OrderedDict[str, str] = OrderedDict()
        self._tilings: OrderedDict[str, Any] = OrderedDict()
        self._lock = threading.Lock()

    # tilings ----------------------------------------------------------------
    def base_tiling(self, name: str) -> Any:
        with self._lock:
            hit = self._tilings.get(name)
            if hit is not None:
                self._tilings.move_to_end(name)
                return hit
        tiling = self.catalogue.tiling(name)
        with self._lock:
            self._tilings[name] = tiling
            while len(self._tilings) > 256:
                self._tilings.popitem(last=False)
        return tiling

    def build(self, name: str, options: Mapping[str, Any]) -> Any:
        tiling = self.base_tiling(name)
        conf = {k: v for k, v in options.items() if k in ("params", "edges", "depth", "r1", "theta1", "r2",
                                                           "theta2", "colouring", "seed")}
        if conf:
            tiling = tiling.configure(**conf)
        return tiling

    # rendering --------------------------------------------------------------
    def render(self, name: str, raw: Mapping[str, Any], *, thumbnail: bool = False) -> tuple[Any, str, int]:
        """(tiling, SVG text, tile estimate) for a tiling and raw options; bounded."""

        options = normalise_options(raw)
        size = int(finite_number(raw.get("size", 240 if thumbnail else 800), "size"))
        if not 16 <= size <= MAX_SIZE:
            raise ParameterError(f"size {size} must be between 16 and {MAX_SIZE} pixels")
        palette = parse_palette(raw.get("colours")) if raw.get("colours") not in (None, "") else None
        labels = str(raw.get("labels", "")).lower() in ("1", "true", "yes", "on")
        tiling = self.build(name, options)
        box = parse_region(raw.get("region"))
        area = as_region(box) if box is not None else tiling.default_region()
        key = self.key(tiling, box, size, palette, labels, thumbnail)
        with self._lock:
            hit = self._cache.get(key)
            if hit is not None:
                self._cache.move_to_end(key)
                return tiling, hit, -1
        estimate = check_render_size(tiling, area, options.get("depth"), self.max_tiles)
        patch = tiling.patch(area)
        if len(patch) > self.max_tiles:  # the estimate was low: refuse all the same

            raise RenderTooLarge(len(patch), self.max_tiles, tiling.name or name)
        svg = patch_to_svg(patch, palette=palette, labels=labels, region=area, size=size)
        with self._lock:
            self._cache[key] = svg
            while len(self._cache) > self.cache_size:
                self._cache.popitem(last=False)
        return tiling, svg, estimate

    @staticmethod
    def key(tiling: Any, box: Any, size: int, palette: Any, labels: bool, thumbnail: bool) -> str:
        spec = {"family": tiling.family, "name": tiling.name, "spec": tiling.spec()}
        blob = json.dumps([spec, box, size, palette, labels, thumbnail], sort_keys=True, default=str)
        return hashlib.sha256(blob.encode()).hexdigest()

    def spec_hash(self, tiling: Any) -> str:
        blob = json.dumps({"family": tiling.family, "name": tiling.name, "spec": tiling.spec()},
                          sort_keys=True, default=str)
        return hashlib.sha256(blob.encode()).hexdigest()[:16]


def editor_info(tiling: Any) -> dict[str, Any]:
    """What the isohedral editor needs: parameters, edge shape classes with their kinds."""

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
    }


def parquet_svg(renderer: Renderer, name: str, edges: list[str], columns: int = 12, rows: int = 4,
                palette: Any = None, size: int = 1200) -> str:
    """SVG of :func:`parquet_tiles` clipped to the strip."""
    import html as _html


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
        out.append(f'<path fill="{_html.escape(palette[c % len(palette)])}" d="{" ".join(by_colour[c])}"/>')
    out.append("</g></svg>")
    return "\n".join(out)


def parquet_tiles(renderer: Renderer, name: str, edges: list[str], columns: int = 12,
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
    import numpy as np

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
