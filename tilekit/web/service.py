"""The service layer behind the pages and the API: request options -> tiling -> bounded SVG.

Request parsing (query strings, JSON bodies) and the render cache live here; the tiling is
configured and drawn by the calls ``tilekit render`` makes (:func:`tilekit.api.configure`,
:func:`tilekit.api.render_svg`: the estimate checked against the server's tile limit before any
patch is built, a refusal being :class:`tilekit.web.limits.RenderTooLarge`, HTTP 413).
"""

from __future__ import annotations

import hashlib
import json
import math
import threading
from collections import OrderedDict
from collections.abc import Iterable, Mapping
from typing import Any

from tilekit import api
from tilekit.errors import ParameterError, ParseError, TilekitError
from tilekit.render import parse_palette
from tilekit.schema import finite_number
from tilekit.text import parse_region as text_region
from tilekit.text import parse_settings
from tilekit.web.cache import DEFAULT_CACHE_BYTES, ByteLRU
from tilekit.web.limits import DEFAULT_MAX_TILES, RenderTooLarge

#: Options a render request may carry besides the tiling's name.
RENDER_KEYS = ("params", "edges", "depth", "region", "colours", "colouring", "size", "r1", "theta1", "r2",
               "theta2", "seed", "labels", "set")
#: ``set=KEY=VALUE`` options (the command line's ``--set``: a family's own options) per request.
MAX_SETTINGS = 16
MAX_SIZE = 2000
MAX_EDGES = 32
MAX_POINTS = 64
#: Colours one render request may name.
MAX_PALETTE = 64


def _number(value: Any, what: str) -> float:
    """A finite number from a JSON number or numeric text; ``true``/``false`` are not numbers."""
    if isinstance(value, bool):
        raise ParseError(f"{what} {str(value).lower()} is a boolean, not a number")
    if isinstance(value, str) and len(value) > 100:
        raise ParseError(f"{what} of {len(value):,} characters is not a number (at most 100)")
    return finite_number(value, what)


def _numbers(value: Any, what: str) -> list[float]:
    if isinstance(value, str):
        value = [v for v in value.split(",") if v.strip()]
    if not isinstance(value, list | tuple):
        raise ParseError(f"{what} {value!r} is not a list of numbers")
    if len(value) > 64:
        raise ParameterError(f"{what}: at most 64 numbers, got {len(value)}")
    return [_number(v, what) for v in value]


def _palette(value: Any) -> tuple[str, ...] | None:
    """``colours``: 'red,#00ff00' text or a list of colour strings (parse_palette checks each)."""
    if value in (None, "", []):
        return None
    if isinstance(value, list | tuple):
        if not all(isinstance(c, str) for c in value):
            raise ParseError("colours must be a list of colour strings or 'red,#00ff00,...' text")
        if len(value) > MAX_PALETTE:
            raise ParameterError(f"colours: at most {MAX_PALETTE} colours, got {len(value)}")
    elif not isinstance(value, str):
        raise ParseError(f"colours {str(value)[:40]} is a {type(value).__name__}; give a list of colour strings "
                         "or 'red,#00ff00,...' text")
    elif len(value) > MAX_PALETTE * 32:
        raise ParameterError(f"colours: at most {MAX_PALETTE * 32} characters")
    return parse_palette(value)


def parse_region(value: Any) -> tuple[float, float, float, float] | None:
    """A region from ``x0,y0,x1,y1`` text or a list of four numbers: the command line's
    ``--region`` parser (the same bounds and messages)."""
    if value is None or value == "":
        return None
    if not isinstance(value, str):
        value = ",".join(str(_number(v, "region")) for v in (value if isinstance(value, list | tuple) else [value]))
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
            raise ParseError(f"depth {str(d)[:40]!r} is not a whole number >= 0")
        if len(str(d).strip()) > 6:  # before int(): Python refuses over 4,300 digits with its own words
            raise ParameterError(f"depth of {len(str(d).strip()):,} digits is out of range; give a whole number "
                                 "0..999999 (the tile limit bounds it further)")
        out["depth"] = int(d)
    for key in ("r1", "theta1", "r2", "theta2"):
        if raw.get(key) not in (None, ""):
            out[key] = _number(raw[key], key)
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


def _too_large(name: str) -> Any:
    """The web's refusal of a render over the tile limit: RenderTooLarge (HTTP 413)."""

    def refuse(count: float, limit: int, what: str) -> None:
        raise RenderTooLarge(int(count), limit, what or name)

    return refuse


class Renderer:
    """Builds and renders tilings for one catalogue, with an LRU cache keyed by spec hash."""

    def __init__(self, catalogue: Any, max_tiles: int = DEFAULT_MAX_TILES, cache_bytes: int = DEFAULT_CACHE_BYTES,
                 pool: Any = None) -> None:
        self.catalogue = catalogue
        self.max_tiles = max_tiles
        self.cache = ByteLRU(cache_bytes)
        #: a :class:`tilekit.web.executor.RenderPool` that draws cache misses, or None (this thread)
        self.pool = pool
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
        # has the name as an alias: the row is what the listings link to (its witness, verdict).
        # A row whose family draws nothing (a hyperbolic vertex type found by the vertex-species
        # search) shows the shipped record of that name (the curved family's tiling) instead.
        found = getattr(self.catalogue, "result_entry", None)
        row = found(name) if found else None
        if row is None:
            tiling = self.catalogue.tiling(name)
        else:
            try:
                tiling = self.catalogue.tiling(row)
            except TilekitError as exc:
                try:
                    tiling = self.catalogue.tiling(name)
                except TilekitError:
                    raise exc from None
        with self._lock:
            self._tilings[name] = tiling
            while len(self._tilings) > 256:
                self._tilings.popitem(last=False)
        return tiling

    def build(self, name: str, options: Mapping[str, Any]) -> Any:
        """The catalogue tiling ``name`` configured by typed options (:func:`normalise_options`)."""
        return api.configure(self.base_tiling(name), options)

    # rendering --------------------------------------------------------------
    def render(self, name: str, raw: Mapping[str, Any], *, thumbnail: bool = False) -> tuple[Any, str, int]:
        """(tiling, SVG text, tile estimate) for a tiling and raw options; bounded."""

        options = normalise_options(raw)
        size_value = _number(raw.get("size", 240 if thumbnail else 800), "size")
        if not 16 <= size_value <= MAX_SIZE:
            raise ParameterError(f"size {size_value:g} must be between 16 and {MAX_SIZE} pixels")
        size = int(size_value)
        palette = _palette(raw.get("colours"))
        labels = str(raw.get("labels", "")).lower() in ("1", "true", "yes", "on")
        tiling = self.build(name, options)
        box = parse_region(raw.get("region"))
        key = self.key(tiling, box, size, palette, labels, thumbnail)
        hit = self.cache.get(key)
        if hit is not None:
            return tiling, hit, -1

        # the estimate is checked here, before a render slot is taken: an oversize request is 413,
        # never a 503 of a full pool
        box_, _ = api.tiling_region(tiling, box)
        estimate = float(tiling.estimate_tiles(box_))
        if not (math.isfinite(estimate) and estimate <= self.max_tiles):
            _too_large(name)(estimate if math.isfinite(estimate) else 2**62, self.max_tiles, tiling.name or name)

        def draw() -> tuple[str, int]:
            picture = api.render_svg(tiling, box, max_tiles=self.max_tiles, too_large=_too_large(name),
                                     estimate=estimate, palette=palette, labels=labels, size=size)
            return picture.svg, picture.estimate

        if self.pool is None:
            svg, estimate = draw()
        else:  # off this process, bounded in time and in number (tilekit.web.executor)
            svg, estimate = self.pool.call(render_job, name, dict(raw), thumbnail, local=draw,
                                           what=f"render of {name!r}", key=name)
        self.cache.put(key, svg)
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


#: The renderer of a render worker process (set by :mod:`tilekit.web.worker` at its start).
WORKER: dict[str, Any] = {}


def render_job(name: str, raw: dict[str, Any], thumbnail: bool) -> tuple[str, int]:
    """In a worker: (SVG, estimate) of ``Renderer.render`` over the worker's own catalogue."""
    _, svg, estimate = WORKER["renderer"].render(name, raw, thumbnail=thumbnail)
    return svg, estimate
