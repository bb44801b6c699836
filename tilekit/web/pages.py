"""HTML pages as plain Python string templates; every value goes through :func:`esc`.

No template engine: each page is a function returning text, and the only markup not built
here is the SVG that :func:`tilekit.render.patch_to_svg` writes (numbers and escaped
colours). Scripts come from /static only (the Content-Security-Policy forbids inline ones);
data for them travels in escaped ``data-`` attributes.
"""

from __future__ import annotations

import html
import json
import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import Any
from urllib.parse import quote, urlencode

import numpy as np

from tilekit.render import PALETTE


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
    """A value as a page shows it: booleans as true/false, floats to 6 significant digits,
    lists and objects as JSON, a missing value as a dash (never "None")."""
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, list | dict):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def facet_text(value: Any) -> str:
    """A facet value as a filter writes it (``true``, ``6``, ``p6m``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
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
    """Properties as a table: values rounded; a long value (a witness, a matrix) folded."""
    rows = []
    for k, v in props.items():
        text = fmt_value(v)
        cell = (f"<details><summary>{esc(text[:80])}… ({len(text):,} characters)</summary>"
                f"<code>{esc(text)}</code></details>" if len(text) > 160 else esc(text))
        rows.append(f"<tr><th>{esc(k)}</th><td>{cell}</td></tr>")
    return f'<table class="props" id="properties">{"".join(rows)}</table>'


_FILL = re.compile(r'<path[^>]*?fill="(#[0-9a-fA-F]{3,8}|[a-z]+)"')


def legend(svg: str, describe: str | None) -> str:
    """What the picture's colours are: a swatch per fill in the drawing, named by its place in
    the default palette (the tiling's colour index: its colouring, aspect or class, as its
    description says)."""
    fills: list[str] = []
    for fill in _FILL.findall(svg):
        if fill not in fills and fill != "none":
            fills.append(fill)
    if not fills:
        return ""
    index = {c.lower(): i for i, c in enumerate(PALETTE)}
    items = "".join(
        f'<span><svg class="swatch" width="14" height="14" data-fill="{esc(f)}"><rect width="14" height="14" '
        f'fill="{esc(f)}" stroke="#444"/></svg>'
        f'{"colour " + str(index[f.lower()]) if f.lower() in index else esc(f)}</span>' for f in fills)
    why = f" — {esc(describe.splitlines()[0][:200])}" if describe else ""
    return (f'<div class="legend" id="legend"><b>legend</b> {items}<span class="why">tiles are filled by their '
            f'colour index in the tiling\'s colouring{why}</span></div>')


def prototile_svgs(prototiles: Sequence[Any], size: int = 90) -> str:
    """Each prototile's outline as a small SVG (its shape; a polyform's cells' outline)."""
    out = []
    drawn: set[bytes] = set()
    for i, proto in enumerate(prototiles):
        try:
            pts = np.asarray(proto.outline, dtype=float)
        except (AttributeError, TypeError, ValueError):
            continue
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 3 or not np.isfinite(pts).all():
            continue
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        shape = np.round(pts - lo, 6).tobytes()
        if shape in drawn:  # one picture per distinct outline (14 Wang tiles are one square)
            continue
        drawn.add(shape)
        span = float(max(hi - lo)) or 1.0
        pad = 0.06 * span
        d = "M" + " L".join(f"{x:.5g},{-y:.5g}" for x, y in pts) + " Z"
        out.append(f'<svg class="prototile" width="{size}" height="{size}" viewBox="{lo[0] - pad:.5g} '
                   f'{-hi[1] - pad:.5g} {span + 2 * pad:.5g} {span + 2 * pad:.5g}"><title>prototile {i}</title>'
                   f'<path d="{d}" fill="#f4c27a" stroke="#222" stroke-width="{span / 60:.4g}"/></svg>')
    return f'<div class="prototiles" id="prototiles">{"".join(out)}</div>' if out else ""


def _region_text(box: Sequence[float]) -> str:
    return ",".join(f"{v:.4g}" for v in box)


def tiling_page(entry: Any, svg: str | None, describe: str | None, problem: str | None,
                links: Sequence[tuple[str, str]] = (), *, chosen: Mapping[str, str] | None = None,
                region: Sequence[float] | None = None, view_problem: str | None = None,
                prototiles: Sequence[Any] = ()) -> str:
    """A tiling's page; ``links`` are the (href, label) pairs plugins offer for it (an editor);
    ``chosen`` the region and depth asked for (the form's values), ``region`` the tiling's
    default region's bounds, ``view_problem`` why the chosen view was refused."""
    chosen = dict(chosen or {})
    n = esc(name_path(entry.name))
    head = f"<h1>{esc(entry.name)}</h1>"
    if entry.title:
        head += f'<p class="subtitle">{esc(entry.title)}</p>'
    verdict = entry.properties.get("verdict")
    if verdict:
        head += f'<p class="verdict" id="verdict">{esc(verdict)}</p>'
    meta = (f'<p>family <a href="/family/{esc(name_path(entry.family))}">{esc(entry.family)}</a>'
            + (f"; aliases {esc(', '.join(entry.aliases))}" if entry.aliases else "")
            + f' · <a id="as-json" href="/tiling/{n}?_format=json">JSON</a></p>')
    opts = {k: chosen[k] for k in ("region", "depth") if k in chosen}
    downloads = (f'<p class="downloads">download <a id="dl-svg" href="{esc(url(f"/api/render/{n}", **opts, download=1))}">SVG</a> '
                 f'<a id="dl-png" href="{esc(url(f"/api/render/{n}", **opts, format="png", download=1))}">PNG</a> '
                 f'<a id="dl-json" href="{esc(url(f"/api/tiling/{n}/spec", download=1))}">JSON spec</a>')
    for i, (href, label) in enumerate(links):
        downloads += f' · <a id="{"edit" if i == 0 else f"edit-{i}"}" href="{esc(href)}">{esc(label)}</a>'
    downloads += "</p>"
    control = ""
    if svg and region is not None:
        x0, y0, x1, y1 = (float(v) for v in region)
        cx, cy, w, h = (x0 + x1) / 2, (y0 + y1) / 2, x1 - x0, y1 - y0
        zoom = " ".join(
            f'<a class="zoom" href="/tiling/{n}?{esc(urlencode({"region": _region_text((cx - f * w / 2, cy - f * h / 2, cx + f * w / 2, cy + f * h / 2))}))}">{label}</a>'
            for f, label in ((0.5, "closer"), (2.0, "wider")))
        control = (f'<form class="view-control" id="view-control" method="get" action="/tiling/{n}">'
                   f'<label>region x0,y0,x1,y1 <input name="region" size="22" value="{esc(chosen.get("region", ""))}" '
                   f'placeholder="{esc(_region_text(region))}"></label>'
                   f'<label>depth <input name="depth" size="3" inputmode="numeric" value="{esc(chosen.get("depth", ""))}" '
                   'placeholder="auto"></label><button type="submit">draw</button>'
                   f'<span class="zooms">{zoom} · <a href="/tiling/{n}">default</a></span></form>')
        if view_problem:
            control += f'<p class="error" id="view-error">{esc(view_problem)} (the default view is shown)</p>'
    figure = (f'<figure class="large" id="figure">{svg}</figure>{legend(svg, describe)}' if svg
              else f'<p class="error" id="no-geometry">no geometry: {esc(problem)}</p>')
    text = f'<h2>Template / system</h2><pre id="describe">{esc(describe)}</pre>' if describe else ""
    shapes = prototile_svgs(prototiles)
    shapes = f"<h2>Prototiles</h2>{shapes}" if shapes else ""
    spec = f'<h2>Spec</h2><pre id="spec">{esc(json.dumps(entry.spec, indent=1, default=str))}</pre>'
    return layout(entry.name, head + meta + downloads + control + '<div class="two"><div>' + figure + shapes
                  + f'</div><div><h2>Properties</h2>{property_table(entry.properties)}{text}{spec}</div></div>')


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
        f'<td>{esc(r["status"])}</td><td class="num">{fmt_number(r["chunks_done"])}/{fmt_number(r["chunks_total"])}</td>'
        f'<td class="num">{fmt_number(r["rows"])}</td><td class="num">{duration(r["seconds"])}</td></tr>' for r in runs)
    return layout("runs", '<h1>Search runs</h1><p class="views"><a href="/runs?_format=json">JSON</a> · '
                  '<a href="/runs?_format=csv">CSV</a></p><table class="list" id="runs"><tr><th>id</th><th>kind</th>'
                  f"<th>status</th><th>chunks</th><th>rows</th><th>time</th></tr>{rows}</table>")


def duration(seconds: Any) -> str:
    """Seconds for people: 0.42 s, 12 s, 3 min 05 s, 2 h 10 min."""
    if seconds is None:
        return "—"
    t = float(seconds)
    if t < 10:
        return f"{t:.2g} s" if t < 1 else f"{t:.1f} s"
    if t < 60:
        return f"{t:.0f} s"
    if t < 3600:
        return f"{int(t // 60)} min {int(t % 60):02d} s"
    return f"{int(t // 3600)} h {int(t % 3600 // 60):02d} min"


_SERIES = re.compile(r"^([A-Za-z_]+?)_(\d+)$")  # free_7, not hc_7_1
_CHART_COLOURS = ("#2f6f9f", "#d1495b", "#66a182", "#edae49", "#8d6cab", "#555555")


def split_summary(summary: Mapping[str, Any]) -> tuple[dict[str, Any], dict[str, dict[int, float]]]:
    """A run summary's plain values and its per-n series (``free_7``, ``tiles_7`` ... become
    series ``free`` and ``tiles`` over n = 7 ...)."""
    plain: dict[str, Any] = {}
    series: dict[str, dict[int, float]] = {}
    for key, value in summary.items():
        m = _SERIES.match(str(key))
        if m and isinstance(value, int | float) and not isinstance(value, bool):
            series.setdefault(m.group(1), {})[int(m.group(2))] = value
        else:
            plain[key] = value
    for label in [k for k, v in series.items() if len(v) < 2]:  # one point is a value, not a series
        (n, v), = series.pop(label).items()
        plain[f"{label}_{n}"] = v
    return plain, series


def series_chart(series: Mapping[str, Mapping[int, float]], width: int = 420, height: int = 180) -> str:
    """Counts per n as a small SVG line chart (log scale when they span more than 50x)."""
    import math

    lines = {k: v for k, v in series.items() if any(x > 0 for x in v.values())}
    if not lines:
        return ""
    ns = sorted({n for v in lines.values() for n in v})
    values = [x for v in lines.values() for x in v.values() if x > 0]
    lo, hi = min(values), max(values)
    log = hi / lo > 50
    f = (lambda x: math.log10(x)) if log else (lambda x: x)
    y0, y1 = (f(lo), f(hi)) if log else (0.0, hi)
    y1 = y1 if y1 > y0 else y0 + 1
    left, right, top, bottom = 44, 10, 10, 24
    def px(n: int) -> float:
        return left + (width - left - right) * (ns.index(n) / max(1, len(ns) - 1))
    def py(x: float) -> float:
        return top + (height - top - bottom) * (1 - (f(x) - y0) / (y1 - y0))
    parts = [f'<svg class="chart" id="chart" width="{width}" height="{height}" viewBox="0 0 {width} {height}" '
             'role="img"><title>counts per n</title>']
    for n in ns:
        parts.append(f'<text x="{px(n):.1f}" y="{height - 8}" font-size="10" text-anchor="middle">{n}</text>')
    for x in ((lo, hi) if log else (0, hi)):
        if x > 0 or not log:
            parts.append(f'<text x="{left - 4}" y="{py(x) + 3 if x else height - bottom:.1f}" font-size="10" '
                         f'text-anchor="end">{esc(fmt_number(x))}</text>')
    for i, (label, pts) in enumerate(sorted(lines.items())):
        colour = _CHART_COLOURS[i % len(_CHART_COLOURS)]
        xy = " ".join(f"{px(n):.1f},{py(x):.1f}" for n, x in sorted(pts.items()) if x > 0 or not log)
        parts.append(f'<polyline fill="none" stroke="{colour}" stroke-width="1.6" points="{xy}"><title>{esc(label)}</title></polyline>')
        parts.append(f'<text x="{left + 6}" y="{top + 10 + 12 * i}" font-size="10" fill="{colour}">{esc(label)}</text>')
    parts.append(f'<text x="{left - 4}" y="{height - 8}" font-size="10" text-anchor="end">n</text></svg>')
    return "".join(parts)


def summary_block(summary: Mapping[str, Any]) -> str:
    """A run's summary: its values as a table, its per-n counts as a table and a chart."""
    plain, series = split_summary(summary)
    out = ""
    if plain:
        rows = "".join(f"<tr><th>{esc(k)}</th><td>{esc(short(v if not isinstance(v, float) else float(f'{v:.4g}')))}</td></tr>"
                       for k, v in plain.items())
        out += f'<table class="props" id="summary">{rows}</table>'
    if series:
        labels = sorted(series)
        ns = sorted({n for v in series.values() for n in v})
        head = "<th>n</th>" + "".join(f"<th>{esc(k)}</th>" for k in labels)
        body = "".join(
            f"<tr><th>{n}</th>" + "".join(
                f"<td>{esc(fmt_number(series[k][n])) if n in series[k] else ''}</td>" for k in labels) + "</tr>"
            for n in ns)
        chart = series_chart({k: v for k, v in series.items() if k not in ("seconds", "time")})
        out += (f'<div class="two"><table class="list summary" id="per-n"><tr>{head}</tr>{body}</table>'
                f"<div>{chart}</div></div>")
    return out


def run_page(info: Mapping[str, Any], page: Mapping[str, Any], writable: bool,
             cell: Callable[[str | None, str, Any, Any], str | None] | None = None,
             link: Callable[[Mapping[str, Any]], str | None] | None = None) -> str:
    """A run's page; ``cell(table, column, value, row)`` draws a result cell (a plugin's
    tilekit_web_render_cell, HTML) or returns None for the shortened escaped value;
    ``link(row)`` is the catalogue name a row's page has (or None)."""
    rid = esc(info["id"])
    total = max(1, int(info["chunks_total"] or 0))
    done = int(info["chunks_done"] or 0)
    pct = 100.0 * done / total
    seconds = float(info["seconds"] or 0)
    rows_n = int(info["rows"] or 0)
    rate = f"{fmt_number(rows_n / seconds)} rows/s, {fmt_number(done / seconds)} chunks/s" if seconds > 0 else "—"
    running = info["status"] not in ("done", "cancelled", "failed", "interrupted")
    eta = (duration((total - done) * seconds / done) if running and done and seconds > 0
           else "—")
    body = (f'<h1>Run {rid}: {esc(info["kind"])}</h1>'
            f'<div id="run" data-run="{rid}" data-status="{esc(info["status"])}">'
            f'<p>status <b id="status">{esc(info["status"])}</b>; chunks <span id="chunks">'
            f'{done:,}/{int(info["chunks_total"] or 0):,}</span>; rows <span id="rows">{rows_n:,}</span>;'
            f' time <span id="seconds">{duration(seconds)}</span>; rate <span id="rate">{rate}</span>;'
            f' left <span id="eta">{eta}</span></p>'
            f'<progress id="progress" max="100" value="{pct:.1f}"></progress> <span id="percent">{pct:.0f}%</span></div>')
    params = info.get("params") or {}
    if params:
        body += ('<p class="params" id="params">parameters ' + ", ".join(
            f"<code>{esc(k)}={esc(fmt_value(v))}</code>" for k, v in params.items()) + "</p>")
    if info.get("summary"):
        body += "<h2>Summary</h2>" + summary_block(info["summary"])
    if info.get("error"):
        body += f'<p class="error">{esc(info["error"])}</p>'
    if writable and info["status"] not in ("done", "cancelled"):
        body += '<p><button id="cancel" type="button">cancel run</button></p>'
    cols = list(page["columns"])
    table = page.get("table")
    names = [link(r) if link is not None and isinstance(r, dict) else None for r in page["rows"]]
    pictures = any(names)
    head = ("<th></th>" if pictures else "") + "".join(f"<th>{esc(c)}</th>" for c in cols)

    def td(r: Any, c: str, name: str | None) -> str:
        if not isinstance(r, dict):
            return "<td></td>"
        drawn = cell(table, c, r.get(c), r) if cell is not None else None
        if drawn is not None:
            return f"<td>{drawn}</td>"
        value = r.get(c)
        text = short(value, 40)
        full = fmt_value(value)
        tip = f' title="{esc(full[:400])}"' if len(full) > 40 else ""
        if name is not None and value == name:
            return f'<td><a href="/tiling/{esc(name_path(name))}">{esc(text)}</a></td>'
        return f"<td{tip}>{esc(text)}</td>"

    rows = []
    for r, name in zip(page["rows"], names):
        thumb = ""
        if pictures:
            thumb = (f'<td><a href="/tiling/{esc(name_path(name))}"><img class="mini" loading="lazy" alt="" width="48" '
                     f'height="48" src="/thumb/{esc(name_path(name))}.svg"></a></td>' if name else "<td></td>")
        rows.append("<tr>" + thumb + "".join(td(r, c, name) for c in cols) + "</tr>")
    where = f' from result table <code>{esc(page["table"])}</code>' if page.get("table") else ""
    body += (f'<h2>Results{where}</h2><p class="views"><a id="as-json" href="/api/runs/{rid}/results?'
             f'limit={int(page["limit"])}&amp;offset={int(page["offset"])}">JSON</a> · '
             f'<a id="as-csv" href="/runs/{rid}?_format=csv&amp;limit={int(page["limit"])}&amp;offset={int(page["offset"])}">CSV</a></p>')
    body += pager(f"/runs/{info['id']}", {}, page["total"], page["offset"], page["limit"])
    body += f'<div class="wide"><table class="list" id="results"><tr>{head}</tr>{"".join(rows)}</table></div>'
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
