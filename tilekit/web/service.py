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

from tilekit.errors import ParameterError, ParseError
from tilekit.geometry import as_region
from tilekit.render import parse_palette
from tilekit.schema import finite_number
from tilekit.text import parse_region as text_region
from tilekit.text import parse_settings
from tilekit.web.limits import DEFAULT_MAX_TILES, RenderTooLarge, check_render_size

#: Options a render request may carry besides the tiling's name.
RENDER_KEYS = ("params", "edges", "depth", "region", "colours", "colouring", "size", "r1", "theta1", "r2",
               "theta2", "seed", "labels", "set")
#: ``set=KEY=VALUE`` options (the command line's ``--set``: a family's own options) per request.
MAX_SETTINGS = 16
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
    return text_region(value)


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
        elif key == "set":
            raw.setdefault("set", []).append(value)
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
    settings = raw.get("set")
    if settings not in (None, "", []):
        if isinstance(settings, Mapping):
            settings = [f"{k}={v}" for k, v in settings.items()]
        if isinstance(settings, str):
            settings = [settings]
        if not isinstance(settings, list | tuple) or not all(isinstance(s, str) for s in settings):
            raise ParseError("set must be 'KEY=VALUE' strings (a family's own options, as --set on the command line)")
        if len(settings) > MAX_SETTINGS or any(len(s) > 1000 for s in settings):
            raise ParameterError(f"at most {MAX_SETTINGS} set=KEY=VALUE options of 1000 characters each")
        reserved = sorted(set(parse_settings(settings)) & set(RENDER_KEYS))
        if reserved:
            raise ParameterError(f"set={reserved[0]}=...: give {reserved[0]} as its own option, not through set")
        out["settings"] = parse_settings(settings)
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
        # a result row's own name (a polyomino's code) is that row, even where a shipped record
        # has the name as an alias: the row is what the listings link to (its witness, verdict)
        found = getattr(self.catalogue, "result_entry", None)
        tiling = self.catalogue.tiling((found(name) if found else None) or name)
        with self._lock:
            self._tilings[name] = tiling
            while len(self._tilings) > 256:
                self._tilings.popitem(last=False)
        return tiling

    def build(self, name: str, options: Mapping[str, Any]) -> Any:
        tiling = self.base_tiling(name)
        conf = {k: v for k, v in options.items() if k in ("params", "edges", "depth", "r1", "theta1", "r2",
                                                           "theta2", "colouring", "seed")}
        conf.update(options.get("settings", {}))  # the family checks its own options
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
        # the family's own picture where it has one (Wang tiles' four edge colours, true arcs)
        svg = tiling.render_svg(patch, palette=palette, labels=labels, region=area, size=size)
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
