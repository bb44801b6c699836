"""The JSON API under ``/api/`` (documented in docs/web.md).

Every error is a JSON body ``{"error": "<the CLI's one line>", "status": N}``: 400 for a bad
filter, value or shape, 404 for an unknown name, 403 for a write to a read-only server, 405,
413 for a render over the tile limit or an oversize request, 503 when the catalogue fails.
"""

from __future__ import annotations

import asyncio
import itertools
import json
import time
from collections.abc import Callable
from typing import Any

from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import JSONResponse, Response, StreamingResponse
from starlette.routing import Route

import tilekit.api
from tilekit.catalogue import run_json
from tilekit.errors import (
    CatalogueError,
    GeometryError,
    NotFoundError,
    ParameterError,
    ParseError,
    SolverLimit,
    TilekitError,
)
from tilekit.plugins import families as fams
from tilekit.schema import parse_json
from tilekit.web.limits import RenderTooLarge
from tilekit.web.service import normalise_options, query_options

MAX_PAGE = 200
MAX_BODY = 64 * 1024
#: Digits of the longest integer a JSON body may hold (checked before Python converts it).
MAX_INT_DIGITS = 30
TERMINAL = ("done", "failed", "cancelled", "interrupted")


class Forbidden(TilekitError):
    """A write to a server started without --writable."""


class BodyTooLarge(TilekitError):
    """A request body over the limit (HTTP 413)."""


def one_line(message: Any) -> str:
    return "; ".join(line.strip() for line in str(message).splitlines() if line.strip())


def status_of(exc: BaseException) -> int:
    own = getattr(exc, "http_status", None)  # the render pool's Busy (503), RenderTimeout (504), ...
    if isinstance(own, int):
        return own
    if isinstance(exc, SolverLimit):  # a solver's own budget ran out: not the request's fault
        return 504
    if isinstance(exc, RenderTooLarge | BodyTooLarge):
        return 413
    if isinstance(exc, NotFoundError):
        # an unknown tiling, family or run is 404; an unknown filter or order key is a bad query
        return 404 if exc.what in ("tiling", "family", "run", "search", "result table") else 400
    if isinstance(exc, Forbidden):
        return 403
    if isinstance(exc, ParseError | ParameterError | GeometryError):
        return 400
    if isinstance(exc, CatalogueError):
        return 503
    return 400


def error_response(exc: BaseException | str, status: int | None = None) -> JSONResponse:
    if isinstance(exc, str):
        return JSONResponse({"error": exc, "status": status or 400}, status_code=status or 400)
    code = status or status_of(exc)
    body: dict[str, Any] = {"error": one_line(exc), "status": code}
    if isinstance(exc, RenderTooLarge):
        body["estimate"], body["limit"] = exc.estimate, exc.limit
    body.update(getattr(exc, "extra", None) or {})
    retry = getattr(exc, "retry_after", None)
    return JSONResponse(body, status_code=code, headers={"Retry-After": str(retry)} if retry else None)


def endpoint(fn: Callable[..., Any]) -> Callable[[Request], Any]:
    """Run a blocking handler in the thread pool; TilekitError -> a JSON error."""

    async def handler(request: Request) -> Response:
        try:
            return await run_in_threadpool(fn, request)
        except TilekitError as exc:
            return error_response(exc)
        except (ValueError, TypeError) as exc:  # a value the typed parsers did not catch
            return error_response(f"bad request: {one_line(exc)}", 400)

    handler.__name__ = fn.__name__
    return handler


# --------------------------------------------------------------------------- helpers


def _int(request: Request, key: str, default: int, lo: int, hi: int) -> int:
    raw = request.query_params.get(key)
    if raw in (None, ""):
        return default
    if not raw.isdigit():
        raise ParseError(f"{key} {raw[:40]!r} is not a whole number >= 0")
    if len(raw) > 100 or len(raw.lstrip("0")) > 40:  # before int(): no 5,000-digit conversions
        raise ParameterError(f"{key} of {len(raw):,} digits must be between {lo} and {hi}")
    value = int(raw)
    if not lo <= value <= hi:
        raise ParameterError(f"{key} {value} must be between {lo} and {hi}")
    return value


def query_args(request: Request) -> dict[str, Any]:
    """family, where (repeatable), text, order: the catalogue's typed filters, never SQL."""
    q = request.query_params
    where = [w.strip() for w in q.getlist("where") if w.strip()]
    # the search form's typed fields, turned into the same filter expressions
    for key in ("periodic", "edge_to_edge"):
        if q.get(key) in ("true", "false"):
            where.append(f"{key}={q[key]}")
    rkey = (q.get("range_key") or "").strip()
    for op, field in ((">=", "range_min"), ("<=", "range_max")):
        value = (q.get(field) or "").strip()
        if value:
            if not rkey:
                raise ParameterError(f"{field} needs a range_key (the property to compare)")
            where.append(f"{rkey}{op}{value}")
    if len(where) > 32:
        raise ParameterError(f"at most 32 filters, got {len(where)}")
    return {
        "family": q.get("family") or None,
        "where": where,
        "text": q.get("text") or None,
        "order_by": q.get("order") or "name",
    }


def lookup(cat: Any, name: str) -> Any:
    """The entry a page or API path names: a result row by its own name first (what the
    listings link to; a shipped record may hold the same text as an alias), then the
    catalogue's lookup; an unknown name is a 404, also when a plugin's notation reader (a
    D-symbol, a GomJau-Hogg string) refuses it as malformed."""
    row = cat.result_entry(name)
    if row is not None:
        return row
    try:
        return cat.get(name)
    except ParseError as exc:
        missing = NotFoundError("tiling", name)
        missing.args = (f"unknown tiling {name[:80]!r} ({one_line(exc)})",)
        raise missing from None


def entry_json(entry: Any, spec_hash: str | None = None) -> dict[str, Any]:
    out = {"name": entry.name, "family": entry.family, "title": entry.title,
           "aliases": list(entry.aliases or []), "properties": entry.properties}
    if spec_hash:
        out["spec_hash"] = spec_hash
    return json.loads(json.dumps(out, default=str))


def run_query(state: Any, request: Request) -> dict[str, Any]:
    args = query_args(request)
    limit = _int(request, "limit", 24, 0, MAX_PAGE)
    offset = _int(request, "offset", 0, 0, 2**62)
    # the pages' listing (tilekit.web.browse): result-table families included, filters on
    # the families that have their keys, so totals agree with /families
    listing = state.browser.listing(args["family"], args["where"], args["text"], args["order_by"], offset, limit,
                                    facets=False)
    return {"total": listing.total, "offset": offset, "limit": limit, "counts": listing.counts,
            "items": [entry_json(e) for e in listing.entries], "query": args}


def render_options(request: Request, body: dict[str, Any] | None) -> dict[str, Any]:
    if body is not None:
        return body
    return query_options(request.query_params.multi_items())


async def read_json(request: Request) -> dict[str, Any]:
    size = 0
    chunks = []
    async for chunk in request.stream():
        size += len(chunk)
        if size > MAX_BODY:
            raise BodyTooLarge(f"request body over {MAX_BODY} bytes")
        chunks.append(chunk)
    # bounded nesting, finite numbers, integers of at most 30 digits (2**62 has 19)
    data = parse_json(b"".join(chunks) or b"{}", "request body", max_int_digits=MAX_INT_DIGITS)
    if not isinstance(data, dict):
        raise ParseError("request body must be a JSON object")
    return data


# --------------------------------------------------------------------------- routes


def routes(state: Any) -> list[Route]:
    cat = lambda: state.catalogue  # noqa: E731

    @endpoint
    def families(request: Request) -> Response:
        data = []
        counts = state.browser.counts()  # as /family/NAME lists them
        for name, fam in sorted(fams(cat().pm).items()):
            data.append({"name": name, "summary": fam.summary, "tilings": counts.get(name, 0)})
        return JSONResponse({"families": data})

    @endpoint
    def query(request: Request) -> Response:
        return JSONResponse(run_query(state, request))

    @endpoint
    def tiling(request: Request) -> Response:
        rec = tilekit.api.record(cat(), request.path_params["name"], get=lambda name: lookup(cat(), name),
                                 build=lambda entry: state.renderer.base_tiling(entry.name))
        out = entry_json(rec.entry)
        out["spec"] = json.loads(json.dumps(rec.entry.spec, default=str))
        if rec.tiling is None:
            out["describe"] = None
            out["geometry_error"] = one_line(rec.error)
        else:
            out["describe"] = rec.tiling.describe()
            out["spec_hash"] = state.renderer.spec_hash(rec.tiling)
        return JSONResponse(out)

    def _render(request: Request, body: dict[str, Any] | None) -> Response:
        raw = render_options(request, body)
        name = request.path_params.get("name") or raw.get("name")
        if not name or not isinstance(name, str):
            raise ParameterError("render needs a tiling name (see /api/query)")
        fmt = str(raw.get("format") or "svg")
        if fmt not in ("svg", "png", "json"):
            raise ParameterError(f"format {fmt!r} must be svg, png or json")
        tiling, svg, estimate = state.renderer.render(name, raw)
        if fmt == "json":
            data: dict[str, Any] = {"name": tiling.name, "family": tiling.family, "spec": tiling.spec(),
                                    "svg": svg, "estimate": estimate}
            outline = getattr(getattr(tiling, "prototiles", [None])[0], "outline", None)
            if outline is not None:
                data["outline"] = [[round(x, 9), round(y, 9)] for x, y in outline.tolist()]
            return JSONResponse(json.loads(json.dumps(data, default=str)))
        if fmt == "png":
            png = svg_to_png(state, svg)
            return Response(png, media_type="image/png", headers=_download(request, name, "png"))
        return Response(svg, media_type="image/svg+xml", headers=_download(request, name, "svg"))

    @endpoint
    def render_get(request: Request) -> Response:
        return _render(request, None)

    async def render_post(request: Request) -> Response:
        try:
            body = await read_json(request)
        except TilekitError as exc:
            return error_response(exc)
        return await endpoint(lambda r: _render(r, body))(request)

    @endpoint
    def spec(request: Request) -> Response:
        raw = render_options(request, None)
        name = request.path_params["name"]

        tiling = state.renderer.build(name, normalise_options(raw))
        data = {"family": tiling.family, "name": tiling.name, "spec": tiling.spec()}
        return JSONResponse(json.loads(json.dumps(data, default=str)), headers=_download(request, name, "json"))

    @endpoint
    def runs(request: Request) -> Response:
        return JSONResponse({"runs": tilekit.api.run_data(cat())})

    @endpoint
    def run(request: Request) -> Response:
        out = tilekit.api.run_data(cat(), _run_id(request), results=False)[0]
        return JSONResponse(json.loads(json.dumps(out, default=str)))

    @endpoint
    def run_results(request: Request) -> Response:
        return JSONResponse(results_page(state, _run_id(request), request))

    async def run_events(request: Request) -> Response:
        try:
            run_id = _run_id(request)
            await run_in_threadpool(cat().run, run_id)
        except TilekitError as exc:
            return error_response(exc)

        async def stream() -> Any:
            deadline = time.monotonic() + state.sse_seconds
            last = None
            while time.monotonic() < deadline:
                info = await run_in_threadpool(cat().run, run_id)
                data = json.dumps(run_json(info))
                if data != last:
                    yield f"event: progress\ndata: {data}\n\n"
                    last = data
                if info.status in TERMINAL:
                    yield f"event: end\ndata: {data}\n\n"
                    return
                if await request.is_disconnected():
                    return
                await asyncio.sleep(state.sse_interval)
            yield "event: timeout\ndata: {}\n\n"

        return StreamingResponse(stream(), media_type="text/event-stream",
                                 headers={"Cache-Control": "no-cache"})

    @endpoint
    def cancel(request: Request) -> Response:
        if not state.writable:
            raise Forbidden("this catalogue is served read-only; start tilekit serve with --writable to change runs")
        info = cat().cancel_run(_run_id(request))

        return JSONResponse(run_json(info))

    state.api_views = {"tiling": tiling, "spec": spec, "render": render_get}
    return [
        Route("/api/families", families),
        Route("/api/query", query),
        Route("/api/tiling/{name:str}", tiling),
        Route("/api/tiling/{name:str}/spec", spec),
        Route("/api/render/{name:str}", render_get, methods=["GET"]),
        Route("/api/render", render_get, methods=["GET"]),
        Route("/api/render", render_post, methods=["POST"]),
        Route("/api/runs", runs),
        Route("/api/runs/{run_id:str}", run),
        Route("/api/runs/{run_id:str}/results", run_results),
        Route("/api/runs/{run_id:str}/events", run_events),
        Route("/api/runs/{run_id:str}/cancel", cancel, methods=["POST"]),
    ]


def path_routes(state: Any) -> list[Route]:
    """The tiling routes again for names holding "/" (``{name:path}``), placed after the
    plugins' routes so that their ``/api/tiling/NAME/...`` pages still match first."""
    views = state.api_views
    return [
        Route("/api/tiling/{name:path}/spec", views["spec"]),
        Route("/api/tiling/{name:path}", views["tiling"]),
        Route("/api/render/{name:path}", views["render"], methods=["GET"]),
    ]


def svg_to_png(state: Any, svg: str) -> bytes:
    """cairosvg's PNG of ``svg``, in the render pool when the app has one (a large SVG's
    conversion holds a CPU and the interpreter for seconds)."""
    import cairosvg

    pool = getattr(state.renderer, "pool", None)
    if pool is None or pool.workers == 0:
        return cairosvg.svg2png(bytestring=svg.encode("utf-8"))
    return pool.call(_png_job, svg, what="PNG conversion")


def _png_job(svg: str) -> bytes:
    import cairosvg

    return cairosvg.svg2png(bytestring=svg.encode("utf-8"))


def _download(request: Request, name: str, ext: str) -> dict[str, str]:
    if request.query_params.get("download") not in ("1", "true"):
        return {}
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in name)[:80] or "tiling"
    return {"Content-Disposition": f'attachment; filename="{safe}.{ext}"'}


def _run_id(request: Request) -> int:
    raw = request.path_params["run_id"]
    if not raw.isdigit() or len(raw) > 18:
        raise ParameterError(f"run id {raw!r} is not a run number (see /api/runs)")
    return int(raw)


def results_page(state: Any, run_id: int, request: Request) -> dict[str, Any]:
    """A page of a run's results: rows of the result table it wrote, else its JSON results."""
    cat = state.catalogue
    cat.run(run_id)  # NotFoundError for an unknown run
    limit = _int(request, "limit", 50, 0, MAX_PAGE)
    offset = _int(request, "offset", 0, 0, 2**62)
    for rt in cat.result_tables.values():
        if "run_id" not in rt.table.c:
            continue
        where = [f"run_id={run_id}"]
        total = cat.count_result_rows(rt, where)
        if total:
            rows = list(cat.iter_result_rows(rt, where, None, None, limit, offset))
            return json.loads(json.dumps({"table": rt.name, "total": total, "offset": offset, "limit": limit,
                                          "columns": [c.name for c in rt.table.c], "rows": rows}, default=str))
    rows = list(itertools.islice(cat.iter_results(run_id), offset, offset + limit))
    total = sum(1 for _ in cat.iter_results(run_id))
    columns = sorted({k for r in rows if isinstance(r, dict) for k in r})
    return json.loads(json.dumps({"table": None, "total": total, "offset": offset, "limit": limit,
                                  "columns": columns, "rows": rows}, default=str))
