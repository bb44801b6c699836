"""The catalogue as the web pages browse it: one listing over the ``tilings`` table and the
plugins' result tables, so every family counts what its page lists (``/families``,
``/family/X``, the all-families listing and a family's facet agree), with facet counts,
sorting and numbered pages, and the same listing as JSON or CSV.

A family whose plugin keeps its entries in a result table (the polyominoes classified by a
run) is listed from that table, as :meth:`tilekit.catalogue.Catalogue.query` does; the other
families from the ``tilings`` table. A filter applies to the families that have its key (a
result table's column, or a property one of the family's tilings has): ``heesch>=1`` with no
family lists the classified polyforms, ``sides=6`` the tilings. Without a family the listing
is grouped by family (families in name order, each in the chosen order).
"""

from __future__ import annotations

import csv
import io
import json
import threading
import time
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from tilekit.catalogue.entry import SHARED_COLUMNS, TEXT_COLUMNS
from tilekit.catalogue.filters import parse_filter, parse_order
from tilekit.catalogue.output import csv_cell
from tilekit.catalogue.vocabulary import KEY_ALIASES, SHARED_BY_NAME, SHARED_KEYS, canonical_key
from tilekit.errors import NotFoundError
from tilekit.plugins import families as installed_families
from tilekit.web.pages import facet_text

#: Facets offered beside a listing: keys with at least 2 and at most this many values.
MAX_FACET_VALUES = 24
#: Facet values shown per facet (the rest summed as "more").
SHOWN_VALUES = 12
#: Facets from the shared vocabulary, then from the families' own keys (most held first).
SHARED_FACETS = 8
OWN_FACETS = 14
#: Seconds a source's key spread (its facet candidates) is reused before it is read again.
SPREAD_SECONDS = 60.0

_ORDER_COLUMNS = frozenset({*TEXT_COLUMNS, *SHARED_COLUMNS, "id", "created_at", "updated_at"})


@dataclass(frozen=True)
class Source:
    """Where one family's entries are listed from: its result table, or the tilings table."""

    family: str
    table: Any = None  # a tilekit.plugins.ResultTable, or None for the tilings table
    keys: frozenset[str] = frozenset()

    def key(self, key: str) -> str:
        """A filter or order key as this source stores it (shared names for the tilings table)."""
        return key if self.table is not None else canonical_key(key)

    def has(self, key: str) -> bool:
        return self.key(key) in self.keys


@dataclass
class Facet:
    """One facet: a key, what it means (shared keys), and ``(value, count)`` pairs, most first."""

    key: str
    values: list[tuple[Any, int]]
    meaning: str = ""
    more: int = 0


@dataclass
class Listing:
    """One page of a listing, with the totals and facets of all its matches."""

    family: str | None
    where: list[str]
    text: str | None
    order: str
    offset: int
    limit: int
    total: int
    counts: dict[str, int]
    entries: list[Any] = field(default_factory=list)
    facets: list[Facet] = field(default_factory=list)

    def columns(self, most: int = 6) -> list[str]:
        """The property columns of a table view: facet keys the page's entries have."""
        have = {k for e in self.entries for k in e.properties}
        return [f.key for f in self.facets if f.key != "family" and f.key in have][:most]


class Browser:
    """Listings of one catalogue (its sources and their facet candidates cached briefly)."""

    def __init__(self, catalogue: Any) -> None:
        self.catalogue = catalogue
        self._lock = threading.Lock()
        self._spread: dict[str, tuple[float, dict[str, tuple[int, int]]]] = {}

    # sources -----------------------------------------------------------------------
    def sources(self) -> list[Source]:
        """Every installed family with entries or a result table, in name order."""
        cat = self.catalogue
        owners = cat.key_families()
        out = []
        for name in sorted(installed_families(cat.pm)):
            rt = cat.family_table(name)
            if rt is not None:
                out.append(Source(name, rt, frozenset(c.name for c in rt.table.c)))
            else:
                keys = {k for k, fams in owners.items() if name in fams} | set(SHARED_COLUMNS) | set(TEXT_COLUMNS)
                out.append(Source(name, None, frozenset(keys)))
        return out

    def family_name(self, family: str | None) -> str | None:
        """The family a ``family`` parameter names (a result table's alias reads as its family)."""
        if family in (None, ""):
            return None
        cat = self.catalogue
        cat.check_family(family)
        rt = cat.family_table(family)
        if rt is None or not rt.family or rt.scopes:  # a scoped name (polyform) reads its own rows
            return family
        return rt.family

    def counts(self) -> dict[str, int]:
        """Entries per family, as each family's page lists them."""
        every = self.sources()
        return self._count(every, [], None, every)

    def _count(self, sources: Sequence[Source], where: list[str], text: str | None,
               every: Sequence[Source]) -> dict[str, int]:
        cat = self.catalogue
        out: dict[str, int] = {}
        records = [s for s in sources if s.table is None]
        if records:
            excluded = [s.family for s in every if s.table is not None]
            if len(records) == 1:
                out[records[0].family] = cat.count_matching(records[0].family, where, text)
            else:
                found = dict(cat.facet_counts(["family"], None, where, text, exclude=excluded).get("family", []))
                for s in records:
                    out[s.family] = int(found.get(s.family, 0))
        for s in sources:
            if s.table is not None:
                out[s.family] = cat.count_matching(s.family, where, text)
        return {s.family: out.get(s.family, 0) for s in sources}

    # the listing -------------------------------------------------------------------
    def listing(self, family: str | None = None, where: Iterable[str] = (), text: str | None = None,
                order: str | None = None, offset: int = 0, limit: int = 48, facets: bool = True) -> Listing:
        """One page of the entries matching every filter (of ``family``, or of all families)."""
        where = [w.strip() for w in where if w and w.strip()]
        filters = [parse_filter(w) for w in where]  # a malformed filter is a ParseError here
        order = (order or "name").strip() or "name"
        okey, _ = parse_order(order)
        family = self.family_name(family)
        every = self.sources()
        chosen = [s for s in every if family is None or s.family == family]
        if family is not None and not chosen:  # a result table's scoped name (polyform: every grid)
            rt = self.catalogue.family_table(family)
            if rt is not None:
                chosen = [Source(family, rt, frozenset(c.name for c in rt.table.c))]
        for f in filters:
            if not any(s.has(f.key) for s in chosen):
                known = sorted({k for s in chosen for k in s.keys} - set(TEXT_COLUMNS) - set(SHARED_COLUMNS))
                raise NotFoundError("property", f.key, [*TEXT_COLUMNS, *SHARED_COLUMNS, *known, *KEY_ALIASES])
        if okey not in _ORDER_COLUMNS and not any(s.has(okey) for s in every):
            raise NotFoundError("order key", okey, sorted({*_ORDER_COLUMNS, *(k for s in every for k in s.keys)}))
        applicable = [s for s in chosen if all(s.has(f.key) for f in filters)]
        counts = self._count(applicable, where, text, every)
        total = sum(counts.values())
        entries: list[Any] = []
        skip, want = offset, limit
        for s in applicable:
            n = counts.get(s.family, 0)
            if want <= 0:
                break
            if skip >= n:
                skip -= n
                continue
            by = order if (okey in ("name",) or s.has(okey) or (s.table is None and okey in _ORDER_COLUMNS)) else "name"
            got = self.catalogue.query(family=s.family, where=where, text=text, order_by=by, limit=want, offset=skip)
            entries.extend(got)
            want -= len(got)
            skip = 0
        listing = Listing(family, where, text, order, offset, limit, total,
                          {k: v for k, v in counts.items() if v}, entries)
        if facets:
            listing.facets = self.facets(applicable, chosen, where, text, counts, family, every)
        return listing

    # facets ------------------------------------------------------------------------
    def spread(self, source: Source, every: Sequence[Source]) -> dict[str, tuple[int, int]]:
        """``{key: (distinct values, entries having it)}`` of one source (cached briefly)."""
        now = time.monotonic()
        with self._lock:
            hit = self._spread.get(source.family)
            if hit is not None and now - hit[0] < SPREAD_SECONDS:
                return hit[1]
        cat = self.catalogue
        if source.table is not None:
            found = cat.result_spread(source.table)
        else:
            others = [s.family for s in every if s.family != source.family]
            found = cat.key_spread(exclude=others)
        with self._lock:
            self._spread[source.family] = (now, found)
        return found

    def facets(self, applicable: Sequence[Source], chosen: Sequence[Source], where: list[str],
               text: str | None, counts: Mapping[str, int], family: str | None,
               every: Sequence[Source]) -> list[Facet]:
        """The facets of a listing: family (without one), then the shared vocabulary's keys, then
        the families' own keys with a few values, each with its counts among the matches."""
        spread: dict[str, list[int]] = {}
        for s in chosen:
            for key, (distinct, held) in self.spread(s, every).items():
                item = spread.setdefault(key, [0, 0])
                item[0] = max(item[0], distinct)
                item[1] += held
        size = sum(self._count(chosen, [], None, every).values())
        # a key with a few values; one value is a facet too when some entries lack the key
        good = {k for k, (d, held) in spread.items() if 1 <= d <= MAX_FACET_VALUES and (d >= 2 or held < size)}
        shared = [k.name for k in SHARED_KEYS if k.name in good][:SHARED_FACETS]
        own = sorted((k for k in good if k not in SHARED_BY_NAME and k not in ("name", "title", "code")),
                     key=lambda k: (-spread[k][1], k))[:OWN_FACETS]
        keys = shared + own
        merged: dict[str, dict[Any, int]] = {k: {} for k in keys}
        cat = self.catalogue
        records = [s for s in applicable if s.table is None]
        if records:
            excluded = [s.family for s in every if s.table is not None]
            wanted = [k for k in keys if any(s.has(k) for s in records)]
            if wanted:
                found = cat.facet_counts(wanted, family, where, text, exclude=excluded)
                for k, values in found.items():
                    for v, n in values:
                        merged[k][v] = merged[k].get(v, 0) + n
        for s in applicable:
            if s.table is None:
                continue
            cols = [k for k in keys if k in s.keys]
            if cols and counts.get(s.family):
                for k, values in cat.result_facet_counts(s.table, cols, where, text).items():
                    for v, n in values:
                        merged[k][v] = merged[k].get(v, 0) + n
        out = []
        if family is None:
            out.append(Facet("family", sorted(((f, n) for f, n in counts.items() if n), key=lambda fn: fn[0]),
                             "the tiling family"))
        for k in keys:
            values = sorted(merged[k].items(), key=lambda vc: (-vc[1], _sortable(vc[0])))
            if not values or any(len(facet_text(v)) > 40 for v, _ in values):  # a blob is no facet
                continue
            meaning = SHARED_BY_NAME[k].meaning if k in SHARED_BY_NAME else ""
            shown = sorted(values[:SHOWN_VALUES], key=lambda vc: _sortable(vc[0]))
            out.append(Facet(k, shown, meaning, sum(n for _, n in values[SHOWN_VALUES:])))
        return out


def _sortable(value: Any) -> tuple[int, float, str]:
    if isinstance(value, bool):
        return (0, float(value), "")
    if isinstance(value, int | float):
        return (1, float(value), "")
    return (2, 0.0, str(value))


# --------------------------------------------------------------------------- JSON and CSV


def plain(value: Any) -> Any:
    """A value as JSON holds it (dates and the like as text)."""
    return json.loads(json.dumps(value, default=str))


def listing_json(listing: Listing, item: Any) -> dict[str, Any]:
    """A listing as the ``.json`` / ``?_format=json`` view answers it; ``item(entry)`` is an
    entry's JSON (the API's entry_json)."""
    return {
        "family": listing.family, "where": listing.where, "text": listing.text, "order": listing.order,
        "total": listing.total, "offset": listing.offset, "limit": listing.limit, "counts": listing.counts,
        "facets": {f.key: [[plain(v), n] for v, n in f.values] for f in listing.facets},
        "items": [item(e) for e in listing.entries],
    }


def csv_text(rows: Iterable[Mapping[str, Any]], columns: Sequence[str]) -> str:
    """Rows as CSV with a header (lists and objects as JSON, booleans as true/false, None empty)."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow([csv_cell(row.get(c)) for c in columns])
    return out.getvalue()


def listing_csv(listing: Listing) -> str:
    """A listing's page as CSV: name, family, title and every property its entries have."""
    keys: list[str] = []
    for e in listing.entries:
        for k in e.properties:
            if k not in keys and k not in ("name", "family", "title"):
                keys.append(k)
    return csv_text((e.flat() for e in listing.entries), ["name", "family", "title", *keys])
