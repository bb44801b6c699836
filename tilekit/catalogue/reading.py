"""Reading tilings, with or without SQLAlchemy.

:class:`TilingReader` holds the catalogue's read queries over the ``tilings`` tables (filters,
text search, ordering, paging, counts, the entries with their properties and aliases) as SQL
text with named parameters, run by whatever connection a subclass provides: the
:class:`~tilekit.catalogue.Catalogue` runs them through SQLAlchemy (SQLite and PostgreSQL),
:class:`SqliteReader` through the standard library's ``sqlite3``. One copy of each query.

:func:`open_reader` is the fast way in for a command that only reads: importing SQLAlchemy
costs about 0.2 s of CPU on the development machine, most of a warm ``tilekit list``
(docs/benchmarks.md). It opens a SQLite catalogue with ``sqlite3`` when the catalogue is
known to be current: its migration scripts' key and its shipped records' fingerprint, both
stored in ``catalogue_meta`` when :func:`~tilekit.catalogue.open_catalogue` last brought it up
to date, equal those of the installed tilekit and plugins. Otherwise (a new, old or read-only
file, another database, a family whose rows live in a plugin's result table) it returns None
and the caller opens the catalogue the full way, which migrates and seeds.
"""

from __future__ import annotations

import hashlib
import json
import os
import sqlite3
import sys
import types
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import AbstractContextManager, contextmanager
from pathlib import Path
from typing import Any

import pluggy

from tilekit import __version__
from tilekit.catalogue.entry import SHARED_COLUMNS, TEXT_COLUMNS, Entry, restore_value
from tilekit.catalogue.filters import (
    Filter,
    Params,
    condition,
    like_contains,
    natural_key,
    parse_filter,
    parse_order,
    quote,
)
from tilekit.catalogue.urls import resolve_url
from tilekit.catalogue.vocabulary import (
    KEY_ALIASES,
    KeyInfo,
    canonical_key,
    key_infos,
    shared_filter,
)
from tilekit.errors import CatalogueError, NotFoundError, ParameterError
from tilekit.plugins import families, get_plugin_manager, migration_locations, normalise
from tilekit.resources import catalogue_dir, migrations_dir

#: A function running one SQL text with its named parameters, returning the rows as tuples.
Run = Callable[[str, Mapping[str, Any]], Sequence[Sequence[Any]]]

#: catalogue_meta key: the fingerprint of the records the plugins shipped at last seeding.
SEED_KEY = "seed_fingerprint"
#: catalogue_meta key: the hash of the migration scripts and the heads they were at, last upgrade.
SCRIPTS_KEY = "migration_scripts"
#: catalogue_meta key: ``fingerprint:["family", ...]``, the families whose rows are in a plugin's
#: result table (read only through SQLAlchemy), for the installation with that fingerprint.
RESULT_FAMILIES_KEY = "result_families"

#: Rows fetched per page of a streamed query, and ids per ``IN (...)`` list.
PAGE = 1000
BATCH = 500

#: Longest value catalogue_meta holds (``String(400)``).
META_VALUE_LENGTH = 400


# ---------------------------------------------------------------------- whether a catalogue is current


def shipped_fingerprint(pm: pluggy.PluginManager) -> str:
    """A hash of what determines the shipped records: tilekit's version, the registered
    plugins' names and source files, and the shipped catalogue/ data.

    Computing it reads about a megabyte of files (milliseconds); building the records
    themselves takes a second, so it is done only when the fingerprint changes.
    """
    digest = hashlib.sha256(__version__.encode())
    paths: set[Path] = set()
    for name, plugin in sorted(pm.list_name_plugin(), key=lambda item: str(item[0])):
        digest.update(str(name).encode())
        module = plugin if isinstance(plugin, types.ModuleType) else sys.modules.get(type(plugin).__module__)
        source = getattr(module, "__file__", None)
        if source:
            src = Path(source)
            paths |= set(src.parent.rglob("*.py")) if src.name == "__init__.py" else {src}
    data = catalogue_dir()
    if data.is_dir():
        paths |= {f for f in data.rglob("*") if f.is_file() and "__pycache__" not in f.parts}
    for path in sorted(paths):
        digest.update(path.name.encode())
        try:
            digest.update(path.read_bytes())
        except OSError:
            continue
    return digest.hexdigest()


def scripts_key(pm: pluggy.PluginManager) -> str:
    """A hash of every migration script (core and plugins): equal keys, equal heads."""
    locations = [migrations_dir() / "versions", *map(Path, migration_locations(pm))]
    digest = hashlib.sha256()
    for folder in locations:
        for path in sorted(folder.glob("*.py")):
            digest.update(path.name.encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()


def result_families_value(fingerprint: str, names: Iterable[str]) -> str | None:
    """The catalogue_meta value recording the result-table families of an installation, or
    None when it does not fit in the column (the fast read path is then never used)."""
    value = f"{fingerprint}:{json.dumps(sorted(set(names)))}"
    return value if len(value) <= META_VALUE_LENGTH else None


# ---------------------------------------------------------------------- the read queries


def _json(value: Any) -> Any:
    """A JSON column's value: text on SQLite, already decoded by PostgreSQL's driver."""
    return json.loads(value) if isinstance(value, str | bytes) else value


def load_entries(run: Run, rows: Sequence[Sequence[Any]]) -> list[Entry]:
    """Entries (properties and aliases restored, lists in order) for rows of
    ``(id, name, family, title, spec)``, in the rows' order."""
    entries = {
        r[0]: Entry(name=r[1], family=r[2], title=r[3] or "", spec=_json(r[4]), id=r[0]) for r in rows
    }
    ids = list(entries)
    lists: dict[tuple[int, str], list[tuple[int, Any]]] = {}
    for start in range(0, len(ids), BATCH):
        params = Params()
        listed = params.many(ids[start : start + BATCH])
        prop_rows = run(
            "SELECT tiling_id, key, position, kind, value_text, value_num, value_bool "
            f"FROM tiling_properties WHERE tiling_id IN {listed} ORDER BY tiling_id, id",
            params,
        )
        for tid, key, position, kind, text, num, flag in prop_rows:
            props = entries[tid].properties
            if kind == "empty":
                props[key] = []
            elif position is None:
                props[key] = restore_value(kind, text, num, flag)
            else:
                lists.setdefault((tid, key), []).append((position, restore_value(kind, text, num, flag)))
                props.setdefault(key, [])
        alias_rows = run(f"SELECT tiling_id, alias FROM tiling_aliases WHERE tiling_id IN {listed} ORDER BY id",
                         params)
        for tid, alias in alias_rows:
            entries[tid].aliases.append(alias)
    for (tid, key), items in lists.items():
        entries[tid].properties[key] = [v for _, v in sorted(items, key=lambda pv: pv[0])]
    return [entries[r[0]] for r in rows]


class TilingReader(ABC):
    """The read queries over the ``tilings`` tables. A subclass provides :meth:`_reading`
    (a connection's ``run`` function inside a context that turns driver errors into one-line
    CatalogueErrors) and ``pm``; :meth:`family_table` says which families a plugin's result
    table holds instead (this class does not read those)."""

    pm: pluggy.PluginManager

    @abstractmethod
    def _reading(self, action: str) -> AbstractContextManager[Run]:
        """A context holding a connection's ``run``; driver errors inside it become one-line
        CatalogueErrors naming ``action``."""

    def family_table(self, family: str | None) -> Any:
        """The result table that holds ``family``'s entries, if it has one."""
        return None

    def property_keys(self, family: str | None = None) -> list[str]:
        """Every property key present in the catalogue (of one family's tilings), sorted."""
        params = Params()
        sql = "SELECT DISTINCT tiling_properties.key FROM tiling_properties"
        if family is not None:
            sql += (" JOIN tilings ON tilings.id = tiling_properties.tiling_id"
                    f" WHERE tilings.family = {params.bind(family)}")
        with self._reading("reading property keys") as run:
            return sorted(row[0] for row in run(sql, params))

    def key_families(self) -> dict[str, set[str]]:
        """Every property key present in the catalogue, with the families whose tilings have it."""
        sql = ("SELECT DISTINCT tiling_properties.key, tilings.family FROM tiling_properties"
               " JOIN tilings ON tilings.id = tiling_properties.tiling_id")
        out: dict[str, set[str]] = {}
        with self._reading("reading property keys") as run:
            for key, family in run(sql, {}):
                out.setdefault(key, set()).add(family)
        return out

    def key_table(self, family: str | None = None) -> list[KeyInfo]:
        """What ``tilekit keys [FAMILY]`` prints: every queryable key of the tilings (of one
        family) with its type, the families that have it and an example value, shared keys
        first (see :mod:`tilekit.catalogue.vocabulary`)."""
        params = Params()
        source = " FROM tiling_properties JOIN tilings ON tilings.id = tiling_properties.tiling_id"
        if family is not None:
            source += f" WHERE tilings.family = {params.bind(family)}"
        with self._reading("reading property keys") as run:
            rows = run("SELECT tiling_properties.key, tiling_properties.kind, tilings.family,"
                       " max(tiling_properties.position), min(tiling_properties.value_text),"
                       " min(tiling_properties.value_num)" + source
                       + " GROUP BY tiling_properties.key, tiling_properties.kind, tilings.family", params)
            counts = run("SELECT tiling_properties.key, tilings.family, count(DISTINCT tilings.id)" + source
                         + " GROUP BY tiling_properties.key, tilings.family", params)
        return key_infos(rows, counts)

    def _normalised(self, f: Filter) -> Filter:
        """A text ``=``/``!=`` filter on a property, with its value as stored: a plugin's
        ``tilekit_normalise`` reads equivalent spellings (incidence symbols, vertex types,
        polyomino codes, D-symbols); other filters unchanged."""
        if f.op not in ("=", "!=") or not isinstance(f.value, str) or f.key in TEXT_COLUMNS:
            return f
        key, value = normalise(f.key, f.value, self.pm)
        return f if (key, value) == (f.key, f.value) else Filter(key, f.op, value, value)

    def _check_keys(self, family: str | None, keys: Sequence[str]) -> None:
        """A key no tiling has is a NotFoundError suggesting the closest keys; a key the
        catalogue has, but not in ``family`` (which has tilings), is a ParameterError naming
        the families that have it."""
        if not keys:
            return
        owners = self.key_families()
        for key in keys:
            found = owners.get(key)
            if not found:
                if key in SHARED_COLUMNS:
                    continue
                raise NotFoundError("property", key, [*TEXT_COLUMNS, *SHARED_COLUMNS, *sorted(owners),
                                                      *KEY_ALIASES])
            if family is not None and family not in found and self.count(family) > 0:
                raise ParameterError(
                    f"family {family!r} has no property {key!r}; {', '.join(sorted(found))} "
                    f"{'has' if len(found) == 1 else 'have'} it (tilekit keys {family} lists {family}'s keys)")

    def count(self, family: str | None = None) -> int:
        """Number of tilings (of one family)."""
        params = Params()
        sql = "SELECT count(*) FROM tilings"
        if family is not None:
            sql += f" WHERE family = {params.bind(family)}"
        with self._reading("counting") as run:
            return int(run(sql, params)[0][0])

    def check_family(self, family: str | None) -> None:
        """NotFoundError (with suggestions) for a family that is neither installed nor present."""
        if family is None:
            return
        fams = set(families(self.pm))
        if family not in fams and self.family_table(family) is None and self.count(family) == 0:
            raise NotFoundError("family", family, fams)

    def _where(self, params: Params, family: str | None, where: Iterable[str | Filter], text: str | None) -> str:
        """The WHERE clause (or "") selecting the tilings that match every filter."""
        conditions = []
        if family is not None:
            conditions.append(f"tilings.family = {params.bind(family)}")
        filters = [self._normalised(shared_filter(parse_filter(w))) for w in where]
        self._check_keys(family, [f.key for f in filters if f.key not in TEXT_COLUMNS])
        conditions += [condition(params, f) for f in filters]
        if text:
            alias = like_contains(params, "tiling_aliases.alias", text)
            prop = like_contains(params, "tiling_properties.value_text", text)
            conditions.append(
                f"({like_contains(params, 'tilings.name', text)} OR {like_contains(params, 'tilings.title', text)}"
                f" OR tilings.id IN (SELECT tiling_aliases.tiling_id FROM tiling_aliases WHERE {alias})"
                f" OR tilings.id IN (SELECT tiling_properties.tiling_id FROM tiling_properties WHERE {prop}))"
            )
        return " WHERE " + " AND ".join(conditions) if conditions else ""

    def _order(self, params: Params, order_by: str) -> str:
        """The ORDER BY clause: a column or a property (its least numeric, then least text
        value), ``-key`` descending, missing values last, then name and id."""
        key, descending = parse_order(order_by)
        key = canonical_key(key)
        columns = {*TEXT_COLUMNS, *SHARED_COLUMNS, "id", "created_at", "updated_at"}
        if key in columns:
            exprs = ["tilings." + quote(key)]
        else:
            known = self.property_keys()
            if key not in known:
                raise NotFoundError("order key", key, [*sorted(columns), *known])
            bound = params.bind(key)
            exprs = [
                f"(SELECT min(tiling_properties.{col}) FROM tiling_properties"
                f" WHERE tiling_properties.tiling_id = tilings.id AND tiling_properties.key = {bound})"
                for col in ("value_num", "value_text")
            ]
        direction = "DESC" if descending else "ASC"
        return " ORDER BY " + ", ".join(
            [*(f"{e} {direction} NULLS LAST" for e in exprs), "tilings.name ASC", "tilings.id ASC"]
        )

    def iter_tilings(
        self,
        family: str | None = None,
        where: Iterable[str | Filter] = (),
        text: str | None = None,
        order_by: str = "name",
        limit: int | None = None,
        offset: int = 0,
    ) -> Iterator[Entry]:
        """Tilings of the ``tilings`` table matching every filter, ordered and paged, streamed
        a page at a time (see :meth:`tilekit.catalogue.Catalogue.iter_query`)."""
        if limit is not None and limit < 0:
            raise ParameterError(f"limit must be >= 0, got {limit}")
        if offset < 0:
            raise ParameterError(f"offset must be >= 0, got {offset}")
        key, descending = parse_order(order_by)
        if key == "name":
            yield from self._iter_by_name(family, where, text, descending, limit, offset)
            return
        params = Params()
        select = ("SELECT tilings.id, tilings.name, tilings.family, tilings.title, tilings.spec FROM tilings"
                  + self._where(params, family, where, text) + self._order(params, order_by))
        remaining = limit
        position = offset
        while remaining is None or remaining > 0:
            size = PAGE if remaining is None else min(PAGE, remaining)
            paged = {**params, "page_size": size, "page_start": position}
            with self._reading("querying") as run:
                rows = run(select + " LIMIT :page_size OFFSET :page_start", paged)
                entries = load_entries(run, rows)
            yield from entries
            if len(rows) < size:
                return
            position += len(rows)
            if remaining is not None:
                remaining -= len(rows)

    def _iter_by_name(self, family: str | None, where: Iterable[str | Filter], text: str | None,
                      descending: bool, limit: int | None, offset: int) -> Iterator[Entry]:
        """The matching tilings in natural name order (IH2 before IH10; filters.natural_key),
        which SQL does not have: the ids and names of every match are sorted here (a few MB
        for a million tilings; plugins' large results live in result tables), then the entries
        are read a batch at a time."""
        params = Params()
        sql = "SELECT tilings.id, tilings.name FROM tilings" + self._where(params, family, where, text)
        with self._reading("querying") as run:
            rows = run(sql, params)
        ordered = sorted(rows, key=lambda r: (natural_key(r[1]), r[1], r[0]), reverse=descending)
        ordered = ordered[offset:] if limit is None else ordered[offset : offset + limit]
        for start in range(0, len(ordered), BATCH):
            ids = [r[0] for r in ordered[start : start + BATCH]]
            batch = Params()
            with self._reading("querying") as run:
                found = run("SELECT tilings.id, tilings.name, tilings.family, tilings.title, tilings.spec FROM tilings"
                            f" WHERE tilings.id IN {batch.many(ids)}", batch)
                by_id = {r[0]: r for r in found}
                entries = load_entries(run, [by_id[i] for i in ids if i in by_id])
            yield from entries

    def count_tilings(self, family: str | None = None, where: Iterable[str | Filter] = (),
                      text: str | None = None) -> int:
        """How many tilings :meth:`iter_tilings` would yield without a limit."""
        params = Params()
        sql = "SELECT count(*) FROM tilings" + self._where(params, family, where, text)
        with self._reading("counting") as run:
            return int(run(sql, params)[0][0])

    def facet_counts(self, keys: Sequence[str], family: str | None = None, where: Iterable[str | Filter] = (),
                     text: str | None = None, exclude: Sequence[str] = ()) -> dict[str, list[tuple[Any, int]]]:
        """How many matching tilings (of families not in ``exclude``) have each value of each
        of ``keys``: ``{key: [(value, tilings), ...]}``, most first. A list property counts a
        tiling once under each of its distinct elements (as ``KEY=VALUE`` matches it); the
        ``family`` key counts by family."""
        params = Params()
        clause = self._where(params, family, where, text)
        if exclude:
            clause += (" AND " if clause else " WHERE ") + f"tilings.family NOT IN {params.many(list(exclude))}"
        out: dict[str, list[tuple[Any, int]]] = {}
        with self._reading("counting facets") as run:
            if "family" in keys:
                rows = run(f"SELECT tilings.family, count(*) FROM tilings{clause} GROUP BY tilings.family", params)
                out["family"] = [(r[0], int(r[1])) for r in rows]
            props = [canonical_key(k) for k in keys if k not in TEXT_COLUMNS]
            if props:
                listed = params.many(props)
                rows = run("SELECT p.key, p.kind, p.value_text, p.value_num, p.value_bool, count(DISTINCT p.tiling_id)"
                           f" FROM tiling_properties p WHERE p.key IN {listed} AND p.kind NOT IN ('json', 'empty')"
                           f" AND p.tiling_id IN (SELECT tilings.id FROM tilings{clause})"
                           " GROUP BY p.key, p.kind, p.value_text, p.value_num, p.value_bool", params)
                for key, kind, vtext, num, flag, count in rows:
                    out.setdefault(key, []).append((restore_value(kind, vtext, num, flag), int(count)))
        for values in out.values():
            values.sort(key=lambda vc: (-vc[1], str(vc[0])))
        return out

    def key_spread(self, exclude: Sequence[str] = ()) -> dict[str, tuple[int, int]]:
        """``{key: (distinct scalar values, tilings having it)}`` over the tilings of families
        not in ``exclude``: what a listing can offer as facets (a key with a few values)."""
        params = Params()
        clause = f" AND t.family NOT IN {params.many(list(exclude))}" if exclude else ""
        sql = ("SELECT p.key, count(DISTINCT coalesce(p.value_text, CAST(p.value_num AS TEXT),"
               " CAST(p.value_bool AS TEXT))), count(DISTINCT p.tiling_id) FROM tiling_properties p"
               " JOIN tilings t ON t.id = p.tiling_id WHERE p.kind NOT IN ('json', 'empty')" + clause
               + " GROUP BY p.key")
        with self._reading("reading property keys") as run:
            return {r[0]: (int(r[1]), int(r[2])) for r in run(sql, params)}

    # the names a caller of either reader uses

    def query(self, family: str | None = None, where: Iterable[str | Filter] = (), text: str | None = None,
              order_by: str = "name", limit: int | None = None, offset: int = 0) -> list[Entry]:
        """Tilings matching every filter, ordered and paged, as a list (see :meth:`iter_query`)."""
        return list(self.iter_query(family, where, text, order_by, limit, offset))

    def iter_query(self, family: str | None = None, where: Iterable[str | Filter] = (), text: str | None = None,
                   order_by: str = "name", limit: int | None = None, offset: int = 0) -> Iterator[Entry]:
        """Tilings matching every filter, ordered and paged, streamed."""
        return self.iter_tilings(family, where, text, order_by, limit, offset)

    def count_matching(self, family: str | None = None, where: Iterable[str | Filter] = (),
                       text: str | None = None) -> int:
        """How many tilings :meth:`iter_query` would return without a limit."""
        return self.count_tilings(family, where, text)

    def _export_keys(self, family: str | None) -> list[str]:
        """The CSV columns of a listing: the property keys (of the family's tilings)."""
        return self.property_keys(family)


# ---------------------------------------------------------------------- the SQLite reader


class SqliteReader(TilingReader):
    """A current SQLite catalogue read through ``sqlite3`` (see :func:`open_reader`)."""

    def __init__(self, path: Path, connection: sqlite3.Connection, pm: pluggy.PluginManager,
                 result_families: frozenset[str]) -> None:
        self.path = path
        self.pm = pm
        self.result_families = result_families
        self._conn = connection

    @property
    def url(self) -> str:
        return f"sqlite:///{self.path}"

    def family_table(self, family: str | None) -> Any:
        if family in self.result_families:
            raise CatalogueError(f"family {family!r} is read from a result table: open the catalogue "
                                 "with open_catalogue to read it")
        return None

    @contextmanager
    def _reading(self, action: str) -> Iterator[Run]:
        def run(sql: str, params: Mapping[str, Any]) -> list[Any]:
            return self._conn.execute(sql, params).fetchall()

        try:
            yield run
        except sqlite3.Error as exc:
            raise CatalogueError(f"catalogue {self.url}: {action} failed: {' '.join(str(exc).split())}") from None

    def close(self) -> None:
        self._conn.close()


def sqlite_path(url: str) -> Path | None:
    """The file of a plain ``sqlite:///`` URL (no driver, query string or escapes), else None."""
    prefix = "sqlite:///"
    if not url.startswith(prefix):
        return None
    rest = url[len(prefix):]
    if not rest or rest == ":memory:" or rest.startswith("file:") or any(c in rest for c in "?%#"):
        return None
    return Path(rest)


def open_reader(url: str | os.PathLike[str] | None = None, pm: pluggy.PluginManager | None = None,
                family: str | None = None) -> SqliteReader | None:
    """A :class:`SqliteReader` of the catalogue at ``url`` (as :func:`resolve_url` resolves
    it) when it is a writable SQLite file that :func:`~tilekit.catalogue.open_catalogue`
    would open without migrating or seeding, and ``family`` (if given) is not read from a
    result table; None otherwise (then open it with ``open_catalogue``)."""
    path = sqlite_path(resolve_url(url))
    if path is None or not path.is_file() or not os.access(path, os.W_OK) or not os.access(path.parent, os.W_OK):
        return None
    pm = pm or get_plugin_manager()
    try:
        conn = sqlite3.connect(f"{path.resolve().as_uri()}?mode=rw", uri=True, check_same_thread=False)
    except sqlite3.Error:
        return None
    try:
        conn.execute("PRAGMA busy_timeout = 30000")
        meta = dict(conn.execute("SELECT key, value FROM catalogue_meta WHERE key IN (?, ?, ?)",
                                 (SEED_KEY, SCRIPTS_KEY, RESULT_FAMILIES_KEY)).fetchall())
        current = sorted(row[0] for row in conn.execute("SELECT version_num FROM alembic_version"))
    except sqlite3.Error:  # not a tilekit catalogue, or one from before catalogue_meta
        conn.close()
        return None
    fingerprint = shipped_fingerprint(pm)
    stored = meta.get(RESULT_FAMILIES_KEY, "")
    if (
        meta.get(SCRIPTS_KEY) != f"{scripts_key(pm)}:{','.join(current)}"
        or meta.get(SEED_KEY) != fingerprint
        or not stored.startswith(fingerprint + ":")
    ):
        conn.close()
        return None
    result_families = frozenset(json.loads(stored[len(fingerprint) + 1:]))
    if family is not None and family in result_families:
        conn.close()
        return None
    return SqliteReader(path, conn, pm, result_families)
