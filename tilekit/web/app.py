"""The Starlette application: pages over the JSON API, request limits, security headers.

``create_app(catalogue_url=None, *, writable=False, max_tiles=20_000)``; ``tilekit serve``
runs it with uvicorn. One catalogue is opened per app and shared by the worker threads
(SQLAlchemy's pool); renders are cached by spec hash (:class:`tilekit.web.service.Renderer`).
The plugins bring their own pages, menu links, tiling-page links, result cells and static
files through the ``tilekit_web_*`` hooks (tilekit/hookspecs.py): this module names no family.
"""

from __future__ import annotations

import contextlib
import html
import json
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.middleware import Middleware
from starlette.middleware.gzip import GZipMiddleware
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

import tilekit.api
from tilekit.catalogue import open_catalogue, run_json
from tilekit.errors import NotFoundError, ParameterError, PluginError, TilekitError
from tilekit.limits import refuse_over_memory
from tilekit.plugins import WebRoute, families, get_plugin_manager
from tilekit.web import api, executor, pages
from tilekit.web.browse import Browser, csv_text, listing_csv, listing_json
from tilekit.web.cache import DEFAULT_CACHE_BYTES
from tilekit.web.executor import Busy, RenderPool, RenderTimeout, resident_bytes
from tilekit.web.guard import Guard
from tilekit.web.limits import DEFAULT_MAX_TILES
from tilekit.web.service import Renderer, normalise_options

STATIC = Path(__file__).with_name("static")
MAX_QUERY = 8 * 1024
MAX_PATH = 2 * 1024
CSP = ("default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' data: blob:; "
       "connect-src 'self'; object-src 'none'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'")


class State:
    """What the routes share: the catalogue (opened on first use), the renderer, the mode."""

    def __init__(self, url: str | None, writable: bool, max_tiles: int, catalogue: Any = None,
                 pm: Any = None, pool: RenderPool | None = None, cache_bytes: int = DEFAULT_CACHE_BYTES) -> None:
        self.url = url
        self.pm = pm
        self.writable = writable
        self.max_tiles = max_tiles
        self.pool = pool
        self.cache_bytes = cache_bytes
        self._catalogue = catalogue
        self._renderer: Renderer | None = None
        self._browser: Browser | None = None
        self._lock = threading.Lock()
        self.sse_interval = 0.5
        self.sse_seconds = 600.0

    @property
    def catalogue(self) -> Any:
        with self._lock:
            if self._catalogue is None:
                self._catalogue = open_catalogue(self.url, pm=self.pm)
            return self._catalogue

    @property
    def renderer(self) -> Renderer:
        cat = self.catalogue
        with self._lock:
            if self._renderer is None:
                self._renderer = Renderer(cat, self.max_tiles, self.cache_bytes, self.pool)
            return self._renderer

    @property
    def browser(self) -> Browser:
        """The listings of the catalogue (tilekit.web.browse): totals, facets, pages."""
        cat = self.catalogue
        with self._lock:
            if self._browser is None:
                self._browser = Browser(cat)
            return self._browser

    def close(self) -> None:
        if self.pool is not None:
            self.pool.close()
        if self._catalogue is not None:
            self._catalogue.close()

    # what a plugin's view uses (tilekit_web_routes) -------------------------------------
    def page(self, title: str, body: str, *, scripts: Any = ()) -> str:
        """A page in the site's layout (navigation, style sheet, ``scripts`` under /static/)."""
        return pages.layout(title, body, scripts=scripts, writable=self.writable)

    def render_options(self, request: Request, own: tuple[str, ...] = ()) -> dict[str, Any]:
        """The render API's options from the request's query string, typed and checked; the
        keys in ``own`` are the view's own (it reads them itself), left out rather than refused."""
        raw = api.render_options(request, None)
        return normalise_options({k: v for k, v in raw.items() if k not in own})

    def query_int(self, request: Request, key: str, default: int, lo: int, hi: int) -> int:
        """A whole-number query parameter in [lo, hi] (ParseError / ParameterError otherwise)."""
        return api._int(request, key, default, lo, hi)

    @staticmethod
    def one_line(exc: BaseException) -> str:
        """An error as the one line the API and the command line show."""
        return api.one_line(exc)


class Limits:
    """ASGI middleware: request line and body size limits, security headers on every answer."""

    def __init__(self, app: Any, max_body: int = api.MAX_BODY) -> None:
        self.app = app
        self.max_body = max_body

    async def __call__(self, scope: dict, receive: Any, send: Any) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        problem = None
        if len(scope.get("query_string", b"")) > MAX_QUERY:
            problem = (414, f"query string over {MAX_QUERY} bytes")
        elif len(scope.get("path", "")) > MAX_PATH:
            problem = (414, f"path over {MAX_PATH} bytes")
        else:
            for key, value in scope.get("headers", []):
                if key == b"content-length":
                    if not value.isdigit() or int(value) > self.max_body:
                        problem = (413, f"request body over {self.max_body} bytes")
        if problem is not None:
            response = JSONResponse({"error": problem[1], "status": problem[0]}, status_code=problem[0])
            await response(scope, receive, _headers(send))
            return
        await self.app(scope, receive, _headers(send))


def _headers(send: Any) -> Any:
    async def wrapped(message: dict) -> None:
        if message["type"] == "http.response.start":
            headers = list(message.get("headers", []))
            names = {k.lower() for k, _ in headers}
            for k, v in ((b"content-security-policy", CSP.encode()), (b"x-content-type-options", b"nosniff"),
                         (b"referrer-policy", b"no-referrer"), (b"x-frame-options", b"DENY")):
                if k not in names:
                    headers.append((k, v))
            message = {**message, "headers": headers}
        await send(message)

    return wrapped


def _nav(links: Any) -> str:
    return "".join(f'<a href="{html.escape(str(href))}">{html.escape(str(label))}</a>' for href, label in links)


def plugin_view(route: WebRoute, state: State, html_page: Callable[..., HTMLResponse]) -> Any:
    """A plugin's ``view(request, web)`` as a Starlette endpoint: run in the thread pool; a str
    is a page, a dict or list JSON, a Response itself; a TilekitError the site's error page
    (under /api/ the API's JSON error)."""
    is_api = route.path.startswith("/api/")

    async def handler(request: Request) -> Response:
        try:
            out = await run_in_threadpool(route.view, request, state)
        except TilekitError as exc:
            if is_api:
                return api.error_response(exc)
            code = api.status_of(exc)
            return html_page(pages.error_page(api.one_line(exc), code), code)
        except (ValueError, TypeError) as exc:
            if not is_api:
                raise
            return api.error_response(f"bad request: {api.one_line(exc)}", 400)
        if isinstance(out, Response):
            return out
        if isinstance(out, dict | list):
            return JSONResponse(out)
        return html_page(str(out))

    handler.__name__ = getattr(route.view, "__name__", "plugin_view")
    return handler


def create_app(catalogue_url: str | None = None, *, writable: bool = False, max_tiles: int = DEFAULT_MAX_TILES,
               catalogue: Any = None, bind_host: str | None = None, allow_hosts: Any = (),
               render_workers: int = 0, render_queue: int | None = None, render_seconds: float | None = None,
               cache_bytes: int = DEFAULT_CACHE_BYTES, worker_bytes: int | None = None) -> Any:
    """The ASGI app for one catalogue (``catalogue`` may be an open Catalogue, for tests).

    ``bind_host`` (with ``allow_hosts``) turns on the Host check of :mod:`tilekit.web.guard`;
    ``render_workers`` > 0 draws renders in that many worker processes with a wall-clock
    budget of ``render_seconds`` (:mod:`tilekit.web.executor`; they open ``catalogue_url``, or
    the open catalogue's own URL, and load the installed plugins); 0 draws in the request's
    thread, still at most ``1 + render_queue`` at once. ``cache_bytes`` bounds the render cache.
    """
    pm = catalogue.pm if catalogue is not None else get_plugin_manager()
    # estimate first: each worker may grow to its recycling bound and the cache to its own
    recycle = executor.DEFAULT_RECYCLE_BYTES if worker_bytes is None else worker_bytes
    refuse_over_memory("bytes of render workers and cache", render_workers * recycle + cache_bytes, 1,
                       "ask for fewer --render-workers, a smaller --worker-mb or --cache-mb")
    pool = _pool(catalogue_url, catalogue, max_tiles, render_workers, render_queue, render_seconds, worker_bytes)
    state = State(catalogue_url, writable, max_tiles, catalogue, pm, pool, cache_bytes)
    hook = pm.hook
    plugin_routes = [r for rs in hook.tilekit_web_routes(web=state) for r in (rs or [])]
    nav = _nav([link for links in reversed(hook.tilekit_web_menu_links(web=state)) for link in (links or [])])
    statics = [item for items in hook.tilekit_web_static() for item in (items or [])]
    for name, folder in statics:
        if not Path(folder).is_dir():  # Starlette would raise deep inside the app's construction
            raise PluginError(f"plugin static files {name!r}: folder {folder} does not exist "
                              "(tilekit_web_static must name a folder of the installed package)")

    def _html(text: str, status: int = 200) -> HTMLResponse:
        return HTMLResponse(text.replace(pages.NAV_SLOT, nav), status_code=status)

    def page(fn: Any) -> Any:
        async def handler(request: Request) -> Response:
            try:
                return await run_in_threadpool(fn, request)
            except TilekitError as exc:
                if request.query_params.get("_format") in ("json", "csv") or request.path_params.get("fmt"):
                    return api.error_response(exc)  # a JSON or CSV view answers in JSON
                code = api.status_of(exc)
                response = _html(pages.error_page(api.one_line(exc), code), code)
                if getattr(exc, "retry_after", None):
                    response.headers["Retry-After"] = str(exc.retry_after)  # type: ignore[attr-defined]
                return response

        handler.__name__ = fn.__name__
        return handler

    def cell(table: str | None, column: str, value: Any, row: Any) -> str | None:
        return hook.tilekit_web_render_cell(table=table, column=column, value=value, row=row)

    def out_format(request: Request) -> str:
        """html, json or csv: a ``.json`` / ``.csv`` path suffix or ``?_format=``."""
        fmt = request.path_params.get("fmt") or request.query_params.get("_format") or "html"
        if fmt not in ("html", "json", "csv"):
            raise ParameterError(f"_format {fmt[:20]!r} must be html, json or csv")
        return fmt

    def view_of(request: Request) -> str:
        view = request.query_params.get("view") or "grid"
        if view not in ("grid", "table"):
            raise ParameterError(f"view {view[:20]!r} must be grid or table")
        return view

    def link_query(request: Request) -> dict[str, Any]:
        """The request's query as links keep it (offset and _format left to the links)."""
        q = request.query_params
        return {k: q.getlist(k) if k == "where" else q[k] for k in q if k not in ("offset", "_format")}

    def listing_response(request: Request, listing: Any, name: str) -> Response | None:
        fmt = out_format(request)
        if fmt == "json":
            return JSONResponse(listing_json(listing, api.entry_json))
        if fmt == "csv":
            return Response(listing_csv(listing), media_type="text/csv; charset=utf-8",
                            headers={"Content-Disposition": f'inline; filename="{name}.csv"'})
        return None

    def key_rows() -> list[tuple[str, str, tuple[str, ...], str, str]]:
        return [(k.key, k.type, k.families, k.example, k.meaning) for k in state.catalogue.key_table()]

    @page
    def search(request: Request) -> Response:
        q = request.query_params
        form: dict[str, Any] = {k: q.get(k) for k in ("family", "text", "periodic", "edge_to_edge", "range_key",
                                                      "range_min", "range_max", "order")}
        form["where"] = [w for w in q.getlist("where") if w.strip()]
        fams = sorted(state.catalogue_families())
        try:
            view = view_of(request)
            args = api.query_args(request)
            limit = api._int(request, "limit", 48, 1, api.MAX_PAGE)
            offset = api._int(request, "offset", 0, 0, 2**62)
            listing = state.browser.listing(args["family"], args["where"], args["text"], args["order_by"],
                                            offset, limit)
            answer = listing_response(request, listing, "tilings")
            if answer is not None:
                return answer
            return _html(pages.search_page(form, fams, listing, None, view, link_query(request), key_rows()))
        except TilekitError as exc:
            code = api.status_of(exc)
            if request.query_params.get("_format") in ("json", "csv"):
                return api.error_response(exc)
            return _html(pages.search_page(form, fams, None, api.one_line(exc), "grid", {}, key_rows()), code)

    def catalogue_families() -> list[str]:
        return list(families(state.catalogue.pm))

    state.catalogue_families = catalogue_families  # type: ignore[attr-defined]

    def lookup(name: str) -> Any:
        return api.lookup(state.catalogue, name)

    @page
    def tiling(request: Request) -> Response:
        entry = lookup(request.path_params["name"])
        if out_format(request) != "html":
            out = api.entry_json(entry)
            out["spec"] = json.loads(json.dumps(entry.spec, default=str))
            return JSONResponse(out)
        q = request.query_params
        chosen = {k: q[k] for k in ("region", "depth") if q.get(k, "").strip()}
        svg = describe = problem = view_problem = None
        links: list[tuple[str, str]] = []
        region = None
        prototiles: list[Any] = []
        try:
            t = state.renderer.base_tiling(entry.name)
            describe = t.describe()
            region = t.default_region().bounds
            prototiles = list(t.prototiles)[:12]
            if chosen:
                try:
                    _, svg, _ = state.renderer.render(entry.name, {"size": 640, **chosen})
                except TilekitError as exc:
                    view_problem = api.one_line(exc)
            if svg is None:
                _, svg, _ = state.renderer.render(entry.name, {"size": 640})
            for offered in reversed(hook.tilekit_web_tiling_links(web=state, name=entry.name, tiling=t)):
                links.extend(offered or [])
        except TilekitError as exc:
            problem = api.one_line(exc)
        return _html(pages.tiling_page(entry, svg, describe, problem, links, chosen=chosen, region=region,
                                       view_problem=view_problem, prototiles=prototiles))

    @page
    def thumb(request: Request) -> Response:
        name = request.path_params["name"]
        try:
            t, svg, _ = state.renderer.render(name, {"size": 160}, thumbnail=True)
            etag = '"' + state.renderer.spec_hash(t) + '"'
        except (Busy, RenderTimeout):
            raise  # a busy server is a 503/504, not a placeholder a browser would cache
        except TilekitError as exc:
            lookup(name)  # an unknown name is a 404, a tiling without geometry a placeholder
            svg = _placeholder(api.one_line(exc))
            etag = None
        headers = {"Cache-Control": "public, max-age=3600"}
        if etag:
            headers["ETag"] = etag
            if request.headers.get("if-none-match") == etag:
                return Response(status_code=304, headers=headers)
        return Response(svg, media_type="image/svg+xml", headers=headers)

    @page
    def families_view(request: Request) -> Response:
        counts = state.browser.counts()  # what each family's page lists
        rows = [(n, f.summary, counts.get(n, 0)) for n, f in sorted(families(state.catalogue.pm).items())]
        fmt = out_format(request)
        if fmt == "json":
            return JSONResponse({"families": [{"name": n, "summary": s, "tilings": c} for n, s, c in rows],
                                 "total": sum(c for _, _, c in rows)})
        if fmt == "csv":
            return Response(csv_text(({"family": n, "summary": s, "tilings": c} for n, s, c in rows),
                                     ["family", "summary", "tilings"]), media_type="text/csv; charset=utf-8")
        return _html(pages.families_page(rows))

    @page
    def family(request: Request) -> Response:
        name = request.path_params["name"]
        fams = families(state.catalogue.pm)
        if name not in fams:
            raise NotFoundError("family", name, fams)
        view = view_of(request)
        limit = api._int(request, "limit", 48, 1, api.MAX_PAGE)
        offset = api._int(request, "offset", 0, 0, 2**62)
        q = request.query_params
        listing = state.browser.listing(name, [w for w in q.getlist("where") if w.strip()], q.get("text") or None,
                                        q.get("order") or "name", offset, limit)
        answer = listing_response(request, listing, name)
        if answer is not None:
            return answer
        fam = fams[name]
        return _html(pages.family_page(name, fam.summary, fam.description or "", listing, view, link_query(request)))

    @page
    def runs(request: Request) -> Response:
        items = tilekit.api.run_data(state.catalogue)
        fmt = out_format(request)
        if fmt == "json":
            return JSONResponse({"runs": items})
        if fmt == "csv":
            cols = ["id", "kind", "status", "chunks_done", "chunks_total", "rows", "seconds", "created_at", "finished_at"]
            return Response(csv_text(items, cols), media_type="text/csv; charset=utf-8")
        return _html(pages.runs_page(items))

    @page
    def run(request: Request) -> Response:
        run_id = api._run_id(request)
        info = run_json(state.catalogue.run(run_id))
        page_data = api.results_page(state, run_id, request)
        fmt = out_format(request)
        if fmt == "json":
            return JSONResponse({"run": info, "results": page_data})
        if fmt == "csv":
            return Response(csv_text(page_data["rows"], page_data["columns"]), media_type="text/csv; charset=utf-8")
        rt = state.catalogue.result_tables.get(page_data.get("table") or "")
        if rt is not None and rt.family:
            column = rt.name_column or rt.key[0]

            def link(row: Any) -> str | None:
                value = row.get(column)
                return value if isinstance(value, str) and value else None
        else:
            known = set(state.catalogue.names()) if page_data["rows"] else set()

            def link(row: Any) -> str | None:
                value = row.get("name")
                return value if isinstance(value, str) and value in known else None
        return _html(pages.run_page(info, page_data, state.writable, cell, link))

    api_lines = [(",".join(r.methods), r.path, r.doc) for r in plugin_routes if r.path.startswith("/api/") and r.doc]

    async def api_doc(request: Request) -> Response:
        return _html(pages.api_page(api_lines))

    async def health(request: Request) -> Response:
        """Liveness for monitors: answered on the event loop, touching neither the catalogue
        nor the render workers (so it answers while every render slot is busy)."""
        out: dict[str, Any] = {"status": "ok", "rss_mb": round(resident_bytes() / 2**20, 1)}
        if state.pool is not None:
            out["renders"] = state.pool.snapshot()
        if state._renderer is not None:
            cache = state._renderer.cache
            out["cache"] = {"entries": len(cache), "bytes": cache.bytes, "max_bytes": cache.max_bytes}
        return JSONResponse(out, headers={"Cache-Control": "no-store"})

    async def not_found(request: Request, exc: Exception) -> Response:
        code = getattr(exc, "status_code", 404)
        detail = getattr(exc, "detail", "not found")
        if request.url.path.startswith("/api/"):
            return JSONResponse({"error": f"{detail}: {request.url.path}", "status": code}, status_code=code)
        return _html(pages.error_page(f"{detail}: {request.url.path}", code), code)

    routes = [
        Route("/", search),
        Route("/tiling/{name:path}", tiling),  # a name may hold "/" (a polyomino's rows)
        Route("/thumb/{name:path}.svg", thumb),
        Route("/families", families_view),
        Route("/families.{fmt:str}", families_view),
        Route("/family/{name:str}.{fmt:str}", family),
        Route("/family/{name:str}", family),
        Route("/runs", runs),
        Route("/runs/{run_id:str}", run),
        Route("/api", api_doc),
        Route("/health", health),
        *api.routes(state),
        Route("/favicon.ico", lambda r: Response(status_code=204)),
        # the plugins' pages after the app's own (an app path wins), their files before /static
        *(Route(r.path, plugin_view(r, state, _html), methods=list(r.methods)) for r in plugin_routes),
        *api.path_routes(state),  # names with "/", after the plugins' /api/tiling/NAME/... pages
        *(Mount(f"/static/plugins/{name}", app=StaticFiles(directory=str(folder))) for name, folder in statics),
        Mount("/static", app=StaticFiles(directory=str(STATIC)), name="static"),
    ]
    @contextlib.asynccontextmanager
    async def lifespan(app: Any) -> Any:
        if state.pool is not None:
            state.pool.warm()
        yield
        state.close()

    middleware = [Middleware(Guard, bind_host=bind_host, allow_hosts=tuple(allow_hosts)),
                  # SVG and HTML go out gzip-compressed (level 5: most of level 9's gain, a third of its time)
                  Middleware(GZipMiddleware, minimum_size=1024, compresslevel=5)]
    app = Starlette(routes=routes, exception_handlers={404: not_found, 405: not_found}, lifespan=lifespan,
                    middleware=middleware)
    app.state.tilekit = state
    return Limits(app)


def _pool(url: str | None, catalogue: Any, max_tiles: int, workers: int, queue_size: int | None,
          seconds: float | None, worker_bytes: int | None) -> RenderPool:
    if workers > 0 and url is None and catalogue is not None:
        url = catalogue.engine.url.render_as_string(hide_password=False)
        if catalogue.path is None and url.startswith("sqlite"):  # in memory: no other process can open it
            workers = 0
    return RenderPool(url, max_tiles, workers=workers,
                      queue_size=executor.DEFAULT_QUEUE if queue_size is None else queue_size,
                      seconds=executor.DEFAULT_SECONDS if seconds is None else seconds,
                      recycle_bytes=executor.DEFAULT_RECYCLE_BYTES if worker_bytes is None else worker_bytes)


def _placeholder(message: str) -> str:
    text = html.escape(message[:60])
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="160" height="160" viewBox="0 0 160 160">'
            '<rect width="160" height="160" fill="#f3f3f3"/><text x="80" y="80" font-size="10" '
            f'text-anchor="middle" fill="#888">no geometry</text><title>{text}</title></svg>')


def dumps(value: Any) -> str:
    return json.dumps(value, default=str)
