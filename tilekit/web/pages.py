"""HTML pages as plain Python string templates; every value goes through :func:`esc`.

No template engine: each page is a function returning text, and the only markup not built
here is the SVG that :func:`tilekit.render.patch_to_svg` writes (numbers and escaped
colours). Scripts come from /static only (the Content-Security-Policy forbids inline ones);
data for them travels in escaped ``data-`` attributes.
"""

from __future__ import annotations

import html
import json
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any
from urllib.parse import quote, urlencode


def esc(value: Any) -> str:
    return html.escape("" if value is None else str(value), quote=True)


def url(path: str, **params: Any) -> str:
    items = []
    for k, v in params.items():
        if v is None or v == "" or v == []:
            continue
        if isinstance(v, list | tuple):
            items.extend((k, str(x)) for x in v)
        else:
            items.append((k, str(v)))
    return path + ("?" + urlencode(items) if items else "")


def name_path(name: str) -> str:
    return quote(name, safe="")


def fmt_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, list | dict):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, float):
        return f"{value:.10g}"
    return str(value)


#: Where the app puts the plugins' menu links (tilekit_web_menu_links) in every page.
NAV_SLOT = "<!--plugin-nav-->"


def layout(title: str, body: str, *, scripts: Sequence[str] = (), writable: bool = False) -> str:
    js = "".join(f'<script src="/static/{esc(s)}" defer></script>' for s in scripts)
    mode = "writable" if writable else "read-only"
    return f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{esc(title)} · tilekit</title>
<link rel="stylesheet" href="/static/style.css">{js}
</head><body>
<header><a class="brand" href="/">tilekit</a>
<nav><a href="/">search</a><a href="/families">families</a><a href="/runs">runs</a>
{NAV_SLOT}<a href="/api">API</a></nav>
<span class="mode">catalogue {esc(mode)}</span></header>
<main>{body}</main>
</body></html>"""


def error_page(message: str, status: int) -> str:
    return layout(f"error {status}", f'<h1>Error {status}</h1><p class="error" id="error">{esc(message)}</p>')


def options(values: Iterable[tuple[str, str]], selected: str | None) -> str:
    return "".join(
        f'<option value="{esc(v)}"{" selected" if v == (selected or "") else ""}>{esc(label)}</option>'
        for v, label in values
    )


def grid(entries: Iterable[Any]) -> str:
    cards = []
    for e in entries:
        n = name_path(e.name)
        cards.append(
            f'<a class="card" href="/tiling/{esc(n)}" data-name="{esc(e.name)}">'
            f'<img class="thumb" loading="lazy" alt="{esc(e.name)}" width="160" height="160" '
            f'src="/thumb/{esc(n)}.svg">'
            f'<span class="name">{esc(e.name)}</span><span class="fam">{esc(e.family)}</span>'
            f'<span class="title">{esc(e.title)}</span></a>'
        )
    return f'<div class="grid" id="grid">{"".join(cards)}</div>' if cards else '<p id="none">no tilings match</p>'


def pager(path: str, query: Mapping[str, Any], total: int, offset: int, limit: int) -> str:
    parts = [f'<span class="count" id="count">{total:,} match{"" if total == 1 else "es"}'
             + (f"; {offset + 1}–{min(total, offset + limit)} shown" if total and limit else "") + "</span>"]
    if offset > 0:
        parts.append(f'<a rel="prev" href="{esc(url(path, **query, offset=max(0, offset - limit)))}">previous</a>')
    if offset + limit < total:
        parts.append(f'<a rel="next" href="{esc(url(path, **query, offset=offset + limit))}">next</a>')
    return f'<p class="pager">{" ".join(parts)}</p>'


def search_page(q: Mapping[str, Any], families: Sequence[str], result: Mapping[str, Any] | None,
                error: str | None, entries: Sequence[Any]) -> str:
    wheres = list(q.get("where") or []) + [""] * max(0, 3 - len(q.get("where") or []))
    tf = [("", "any"), ("true", "true"), ("false", "false")]
    where_inputs = "".join(
        f'<input name="where" value="{esc(w)}" placeholder="KEY=VALUE, KEY~TEXT, KEY>=N" size="26">' for w in wheres
    )
    form = f"""<form class="search" method="get" action="/" id="search">
<label>family <select name="family">{options([("", "all")] + [(f, f) for f in families], q.get("family"))}</select></label>
<label>text <input name="text" value="{esc(q.get("text"))}" placeholder="name, title, alias"></label>
<label>periodic <select name="periodic">{options(tf, q.get("periodic"))}</select></label>
<label>edge-to-edge <select name="edge_to_edge">{options(tf, q.get("edge_to_edge"))}</select></label>
<label>range <input name="range_key" value="{esc(q.get("range_key"))}" placeholder="property, e.g. k_hedral" size="14">
from <input name="range_min" value="{esc(q.get("range_min"))}" size="5"> to
<input name="range_max" value="{esc(q.get("range_max"))}" size="5"></label>
<fieldset><legend>filters (all must hold; see docs/catalogue.md)</legend>{where_inputs}</fieldset>
<label>order <input name="order" value="{esc(q.get("order") or "name")}" size="10"></label>
<button type="submit">search</button></form>"""
    body = "<h1>Search the catalogue</h1>" + form
    if error:
        body += f'<p class="error" id="error">{esc(error)}</p>'
    if result is not None:
        keep = {k: v for k, v in q.items() if k != "offset" and v not in (None, "", [])}
        body += pager("/", keep, result["total"], result["offset"], result["limit"])
        body += grid(entries)
    return layout("search", body)


def property_table(props: Mapping[str, Any]) -> str:
    rows = "".join(f"<tr><th>{esc(k)}</th><td>{esc(fmt_value(v))}</td></tr>" for k, v in props.items())
    return f'<table class="props" id="properties">{rows}</table>'


def tiling_page(entry: Any, svg: str | None, describe: str | None, problem: str | None,
                links: Sequence[tuple[str, str]] = ()) -> str:
    """A tiling's page; ``links`` are the (href, label) pairs plugins offer for it (an editor)."""
    n = esc(name_path(entry.name))
    head = f"<h1>{esc(entry.name)}</h1>"
    if entry.title:
        head += f'<p class="subtitle">{esc(entry.title)}</p>'
    meta = (f'<p>family <a href="/family/{esc(name_path(entry.family))}">{esc(entry.family)}</a>'
            + (f"; aliases {esc(', '.join(entry.aliases))}" if entry.aliases else "") + "</p>")
    downloads = (f'<p class="downloads">download <a id="dl-svg" href="/api/render/{n}?download=1">SVG</a> '
                 f'<a id="dl-png" href="/api/render/{n}?format=png&amp;download=1">PNG</a> '
                 f'<a id="dl-json" href="/api/tiling/{n}/spec?download=1">JSON spec</a>')
    for i, (href, label) in enumerate(links):
        downloads += f' · <a id="{"edit" if i == 0 else f"edit-{i}"}" href="{esc(href)}">{esc(label)}</a>'
    downloads += "</p>"
    figure = (f'<figure class="large" id="figure">{svg}</figure>' if svg
              else f'<p class="error" id="no-geometry">no geometry: {esc(problem)}</p>')
    text = f'<h2>Template / system</h2><pre id="describe">{esc(describe)}</pre>' if describe else ""
    spec = f'<h2>Spec</h2><pre id="spec">{esc(json.dumps(entry.spec, indent=1, default=str))}</pre>'
    return layout(entry.name, head + meta + downloads + '<div class="two">' + figure
                  + f'<div><h2>Properties</h2>{property_table(entry.properties)}{text}{spec}</div></div>')


def families_page(rows: Sequence[tuple[str, str, int]]) -> str:
    items = "".join(f'<tr><td><a href="/family/{esc(name_path(n))}">{esc(n)}</a></td><td>{esc(s)}</td>'
                    f"<td>{c:,}</td></tr>" for n, s, c in rows)
    return layout("families", f'<h1>Families</h1><table class="list" id="families"><tr><th>family</th>'
                  f"<th>summary</th><th>tilings</th></tr>{items}</table>")


def family_page(name: str, summary: str, description: str, total: int, offset: int, limit: int,
                entries: Sequence[Any]) -> str:
    body = f"<h1>Family {esc(name)}</h1><p>{esc(summary)}</p>"
    if description:
        body += f'<pre class="describe">{esc(description)}</pre>'
    body += pager(f"/family/{name_path(name)}", {}, total, offset, limit) + grid(entries)
    return layout(f"family {name}", body)


def runs_page(runs: Sequence[Mapping[str, Any]]) -> str:
    if not runs:
        return layout("runs", "<h1>Search runs</h1><p>no runs yet (tilekit search KIND)</p>")
    rows = "".join(
        f'<tr><td><a href="/runs/{esc(r["id"])}">{esc(r["id"])}</a></td><td>{esc(r["kind"])}</td>'
        f'<td>{esc(r["status"])}</td><td>{esc(r["chunks_done"])}/{esc(r["chunks_total"])}</td>'
        f'<td>{esc(r["rows"])}</td><td>{float(r["seconds"] or 0):.2f}</td></tr>' for r in runs)
    return layout("runs", '<h1>Search runs</h1><table class="list" id="runs"><tr><th>id</th><th>kind</th>'
                  f"<th>status</th><th>chunks</th><th>rows</th><th>seconds</th></tr>{rows}</table>")


def run_page(info: Mapping[str, Any], page: Mapping[str, Any], writable: bool,
             cell: Callable[[str | None, str, Any, Any], str | None] | None = None) -> str:
    """A run's page; ``cell(table, column, value, row)`` draws a result cell (a plugin's
    tilekit_web_render_cell, HTML) or returns None for the escaped value."""
    rid = esc(info["id"])
    total = max(1, int(info["chunks_total"] or 0))
    pct = 100.0 * int(info["chunks_done"] or 0) / total
    body = (f'<h1>Run {rid}: {esc(info["kind"])}</h1>'
            f'<div id="run" data-run="{rid}" data-status="{esc(info["status"])}">'
            f'<p>status <b id="status">{esc(info["status"])}</b>; chunks <span id="chunks">'
            f'{esc(info["chunks_done"])}/{esc(info["chunks_total"])}</span>; rows <span id="rows">{esc(info["rows"])}</span>;'
            f' <span id="seconds">{float(info["seconds"] or 0):.2f}</span> s</p>'
            f'<progress id="progress" max="100" value="{pct:.1f}"></progress></div>'
            f'<p>params <code>{esc(json.dumps(info["params"], ensure_ascii=False))}</code></p>')
    if info.get("summary"):
        body += f'<p>summary <code id="summary">{esc(json.dumps(info["summary"], ensure_ascii=False))}</code></p>'
    if info.get("error"):
        body += f'<p class="error">{esc(info["error"])}</p>'
    if writable and info["status"] not in ("done", "cancelled"):
        body += '<p><button id="cancel" type="button">cancel run</button></p>'
    cols = list(page["columns"])
    head = "".join(f"<th>{esc(c)}</th>" for c in cols)
    table = page.get("table")

    def td(r: Any, c: str) -> str:
        if not isinstance(r, dict):
            return "<td></td>"
        drawn = cell(table, c, r.get(c), r) if cell is not None else None
        return f"<td>{drawn if drawn is not None else esc(fmt_value(r.get(c)))}</td>"

    rows = "".join("<tr>" + "".join(td(r, c) for c in cols) + "</tr>" for r in page["rows"])
    where = f' from result table <code>{esc(page["table"])}</code>' if page.get("table") else ""
    body += f"<h2>Results{where}</h2>" + pager(f"/runs/{info['id']}", {}, page["total"], page["offset"], page["limit"])
    body += f'<table class="list" id="results"><tr>{head}</tr>{rows}</table>'
    return layout(f"run {info['id']}", body, scripts=["run.js"], writable=writable)


def api_page(extra: Sequence[tuple[str, str, str]] = ()) -> str:
    """The API's endpoints, the app's own and ``extra`` (method, path, what) from the plugins."""
    rows = [
        ("GET", "/api/families", "installed families with their tiling counts"),
        ("GET", "/api/query?family=&where=&text=&order=&limit=&offset=", "typed filters (repeat where), paged (limit ≤ 200)"),
        ("GET", "/api/tiling/NAME", "entry, spec, description, spec hash"),
        ("GET", "/api/tiling/NAME/spec?params=&edges=", "the (configured) tiling's JSON spec"),
        ("GET", "/api/render/NAME?params=&edges=&depth=&region=&colours=&size=&format=svg|png|json", "a bounded render"),
        ("POST", "/api/render", "the same as a JSON body {name, params, edges, ...}"),
        ("GET", "/api/runs", "every run"),
        ("GET", "/api/runs/ID", "one run with its counts"),
        ("GET", "/api/runs/ID/results?limit=&offset=", "a page of its results (its result table's rows)"),
        ("GET", "/api/runs/ID/events", "server-sent progress events until the run ends"),
        ("POST", "/api/runs/ID/cancel", "cancel (only with --writable)"),
        *extra,
    ]
    trs = "".join(f"<tr><td>{esc(m)}</td><td><code>{esc(p)}</code></td><td>{esc(d)}</td></tr>" for m, p, d in rows)
    return layout("API", '<h1>JSON API</h1><p>Errors are <code>{"error": "one line", "status": N}</code> '
                  "with 400 (bad filter or value), 403 (read-only), 404 (unknown name), 413 (over the tile "
                  f'or size limit). See docs/web.md.</p><table class="list">{trs}</table>')
