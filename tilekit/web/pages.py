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
        return f"{value:.6g}"
    return str(value)


def fmt_number(value: Any) -> str:
    """A count or measure for people: thousands separated, floats to 4 significant digits."""
    if isinstance(value, bool) or value is None:
        return fmt_value(value) if value is not None else ""
    if isinstance(value, int):
        return f"{value:,}"
    if isinstance(value, float):
        return f"{value:,.4g}" if abs(value) < 1e15 else f"{value:.4g}"
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


def page_numbers(page: int, pages: int, around: int = 2) -> list[int | None]:
    """The page numbers a pager shows: first, last and ``around`` either side of ``page``,
    None where numbers are left out (1-based)."""
    keep = {1, pages, *range(max(1, page - around), min(pages, page + around) + 1)}
    out: list[int | None] = []
    for n in sorted(keep):
        if out and out[-1] is not None and n > out[-1] + 1:
            out.append(None)
        out.append(n)
    return out


def pager(path: str, query: Mapping[str, Any], total: int, offset: int, limit: int) -> str:
    """The count, "previous"/"next" and numbered pages (links keep ``query``)."""
    parts = [f'<span class="count" id="count">{total:,} match{"" if total == 1 else "es"}'
             + (f"; {offset + 1:,}–{min(total, offset + limit):,} shown" if total and limit and offset < total else "")
             + "</span>"]
    if limit <= 0:
        return f'<p class="pager">{parts[0]}</p>'
    if offset > 0:
        parts.append(f'<a rel="prev" href="{esc(url(path, **query, offset=max(0, offset - limit) or None))}">previous</a>')
    if offset + limit < total:
        parts.append(f'<a rel="next" href="{esc(url(path, **query, offset=offset + limit))}">next</a>')
    pages = (total + limit - 1) // limit
    if pages > 1:
        page = offset // limit + 1
        nums = []
        for n in page_numbers(page, pages):
            if n is None:
                nums.append('<span class="gap">…</span>')
            elif n == page:
                nums.append(f'<b aria-current="page">{n:,}</b>')
            else:
                nums.append(f'<a href="{esc(url(path, **query, offset=(n - 1) * limit or None))}">{n:,}</a>')
        parts.append(f'<span class="pages" id="pages">page {page:,} of {pages:,}: {" ".join(nums)}</span>')
    return f'<p class="pager">{" ".join(parts)}</p>'


def _with(query: Mapping[str, Any], **changes: Any) -> dict[str, Any]:
    out = {k: v for k, v in query.items() if k not in ("offset", "_format")}
    out.update(changes)
    return out


def facets_block(path: str, query: Mapping[str, Any], listing: Any, family_links: bool) -> str:
    """The facet counts beside a listing: each value a link adding its filter (or, chosen, a
    link removing it); the family facet links to the family's own listing."""
    from tilekit.web.browse import facet_text

    where = list(listing.where)
    blocks = []
    for facet in listing.facets:
        items = []
        for value, count in facet.values:
            text = facet_text(value)
            if facet.key == "family":
                if not family_links:
                    continue
                href = url(path, **_with(query, family=text))
                chosen = listing.family == text
            else:
                expr = f"{facet.key}={text}"
                chosen = expr in where
                rest = [w for w in where if w != expr] if chosen else [*where, expr]
                href = url(path, **_with(query, where=rest))
            cls = ' class="chosen"' if chosen else ""
            mark = " ✕" if chosen and facet.key != "family" else ""
            items.append(f'<li{cls}><a href="{esc(href)}" data-facet="{esc(facet.key)}" data-value="{esc(text)}">'
                         f'{esc(text)}{mark}</a> <span class="n">{count:,}</span></li>')
        if facet.more:
            items.append(f'<li class="more">{facet.more:,} in other values</li>')
        if items:
            title = f' title="{esc(facet.meaning)}"' if facet.meaning else ""
            blocks.append(f'<section class="facet" id="facet-{esc(facet.key)}"><h3{title}>{esc(facet.key)}</h3>'
                          f'<ul>{"".join(items)}</ul></section>')
    return f'<aside class="facets" id="facets"><h2>Facets</h2>{"".join(blocks)}</aside>' if blocks else ""


def sort_links(path: str, query: Mapping[str, Any], order: str, keys: Sequence[str]) -> str:
    """Links ordering the listing by each key (the chosen one again reverses it)."""
    links = []
    for key in keys:
        now = order.lstrip("-") == key
        target = ("-" + key) if now and not order.startswith("-") else key
        arrow = (" ▼" if order.startswith("-") else " ▲") if now else ""
        links.append(f'<a href="{esc(url(path, **_with(query, order=None if target == "name" else target)))}"'
                     f'{" class=chosen" if now else ""}>{esc(key)}{arrow}</a>')
    return f'<p class="sort" id="sort">sort by {" ".join(links)}</p>'


def entry_table(entries: Sequence[Any], columns: Sequence[str], path: str, query: Mapping[str, Any],
                order: str) -> str:
    """A listing as a table: thumbnail, name, family, title and property columns; the column
    heads order the listing."""
    def head(key: str) -> str:
        now = order.lstrip("-") == key
        target = ("-" + key) if now and not order.startswith("-") else key
        arrow = (" ▼" if order.startswith("-") else " ▲") if now else ""
        return f'<th><a href="{esc(url(path, **_with(query, order=target)))}">{esc(key)}{arrow}</a></th>'

    rows = []
    for e in entries:
        n = esc(name_path(e.name))
        cells = "".join(f"<td>{esc(short(e.properties.get(c)))}</td>" for c in columns)
        rows.append(f'<tr data-name="{esc(e.name)}"><td><a href="/tiling/{n}"><img class="mini" loading="lazy" '
                    f'alt="" width="48" height="48" src="/thumb/{n}.svg"></a></td>'
                    f'<td><a href="/tiling/{n}">{esc(e.name)}</a></td><td>{esc(e.family)}</td>'
                    f'<td class="title">{esc(e.title)}</td>{cells}</tr>')
    heads = "<th></th>" + head("name") + head("family") + "<th>title</th>" + "".join(head(c) for c in columns)
    return (f'<table class="list entries" id="table"><tr>{heads}</tr>{"".join(rows)}</table>' if rows
            else '<p id="none">no tilings match</p>')


def short(value: Any, most: int = 60) -> str:
    """A value for a table cell: rounded, and cut with an ellipsis past ``most`` characters."""
    if value is None:
        return ""
    text = fmt_value(value)
    return text if len(text) <= most else text[: most - 1] + "…"


def listing_block(path: str, query: Mapping[str, Any], listing: Any, view: str, family_links: bool = True) -> str:
    """A listing: facets beside it, active filters, sorting, the view and format switches,
    numbered pages and the entries as thumbnails or a table."""
    where = list(listing.where)
    chips = "".join(
        f'<a class="chip" href="{esc(url(path, **_with(query, where=[x for x in where if x != w])))}">'
        f'{esc(w)} ✕</a>' for w in where)
    if listing.family and family_links:
        chips = (f'<a class="chip" href="{esc(url(path, **_with(query, family=None)))}">family={esc(listing.family)} ✕</a>'
                 + chips)
    active = f'<p class="active" id="active">filters {chips}</p>' if chips else ""
    keys = ["name"] + ([] if listing.family else ["family"]) + [f.key for f in listing.facets if f.key != "family"][:8]
    other = "grid" if view == "table" else "table"
    switches = (f'<p class="views">view <a id="view-{other}" href="{esc(url(path, **_with(query, view=None if other == "grid" else other)))}">'
                f'{other}</a> · <a id="as-json" href="{esc(url(path, **_with(query, _format="json"), offset=listing.offset or None))}">JSON</a>'
                f' · <a id="as-csv" href="{esc(url(path, **_with(query, _format="csv"), offset=listing.offset or None))}">CSV</a></p>')
    keep = _with(query)
    body = (active + sort_links(path, query, listing.order, keys) + switches
            + pager(path, keep, listing.total, listing.offset, listing.limit))
    if view == "table":
        body += entry_table(listing.entries, listing.columns(), path, keep, listing.order)
    else:
        body += grid(listing.entries)
    if listing.total > listing.limit:
        body += pager(path, keep, listing.total, listing.offset, listing.limit).replace('id="count"', "").replace(
            'id="pages"', "")
    return f'<div class="browse">{facets_block(path, query, listing, family_links)}<div class="results">{body}</div></div>'


def search_page(q: Mapping[str, Any], families: Sequence[str], listing: Any, error: str | None,
                view: str = "grid", query: Mapping[str, Any] | None = None, keys: Sequence[Any] = ()) -> str:
    """The search form over the all-families listing; ``keys`` are the vocabulary's
    (key, type, families, example, meaning) rows offered as filter suggestions."""
    wheres = list(q.get("where") or []) + [""] * max(0, 3 - len(q.get("where") or []))
    tf = [("", "any"), ("true", "true"), ("false", "false")]
    where_inputs = "".join(
        f'<input name="where" value="{esc(w)}" placeholder="KEY=VALUE, KEY~TEXT, KEY>=N" size="26" list="keys">'
        for w in wheres
    )
    datalist = "".join(f'<option value="{esc(k[3])}">{esc(k[0])}: {esc(k[1])}</option>' for k in keys)
    key_rows = "".join(
        f'<tr><td><code>{esc(k[0])}</code></td><td>{esc(k[1])}</td><td>{esc(", ".join(k[2]))}</td>'
        f'<td><a href="{esc(url("/", where=[k[3]]))}"><code>{esc(k[3])}</code></a></td><td>{esc(k[4])}</td></tr>'
        for k in keys)
    vocabulary = (f'<details class="keys" id="keys"><summary>filter keys ({len(keys)})</summary>'
                  '<table class="list"><tr><th>key</th><th>type</th><th>families</th><th>example</th>'
                  f'<th>meaning</th></tr>{key_rows}</table></details><datalist id="keys">{datalist}</datalist>'
                  if keys else "")
    form = f"""<form class="search" method="get" action="/" id="search">
<label>family <select name="family">{options([("", "all")] + [(f, f) for f in families], q.get("family"))}</select></label>
<label>text <input name="text" value="{esc(q.get("text"))}" placeholder="name, title, alias"></label>
<label>periodic <select name="periodic">{options(tf, q.get("periodic"))}</select></label>
<label>edge-to-edge <select name="edge_to_edge">{options(tf, q.get("edge_to_edge"))}</select></label>
<label>range <input name="range_key" value="{esc(q.get("range_key"))}" placeholder="property, e.g. k_hedral" size="14">
from <input name="range_min" value="{esc(q.get("range_min"))}" size="5"> to
<input name="range_max" value="{esc(q.get("range_max"))}" size="5"></label>
<fieldset><legend>filters (all must hold)</legend>{where_inputs}</fieldset>
<label>order <input name="order" value="{esc(q.get("order") or "name")}" size="10"></label>
<button type="submit">search</button></form>{vocabulary}"""
    body = "<h1>Search the catalogue</h1>" + form
    if error:
        body += f'<p class="error" id="error">{esc(error)}</p>'
    if listing is not None:
        body += listing_block("/", query or {}, listing, view)
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
                    f'<td class="num">{c:,}</td></tr>' for n, s, c in rows)
    total = sum(c for _, _, c in rows)
    return layout("families", f'<h1>Families</h1><p class="views"><a href="/families.json">JSON</a> · '
                  f'<a href="/families.csv">CSV</a></p><table class="list" id="families"><tr><th>family</th>'
                  f'<th>summary</th><th>entries</th></tr>{items}<tr class="total"><td>all</td><td></td>'
                  f'<td class="num"><a href="/" id="all-count">{total:,}</a></td></tr></table>')


def family_page(name: str, summary: str, description: str, listing: Any, view: str = "grid",
                query: Mapping[str, Any] | None = None) -> str:
    body = f"<h1>Family {esc(name)}</h1><p>{esc(summary)}</p>"
    if description:
        body += f'<pre class="describe">{esc(description)}</pre>'
    body += listing_block(f"/family/{name_path(name)}", query or {}, listing, view, family_links=False)
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
