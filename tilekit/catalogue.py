"""The catalogue database: open (migrating and seeding), query by typed filters, record runs.

``open_catalogue()`` opens the SQLite file under the user data directory, or any SQLAlchemy
URL given as an argument or in ``TILEKIT_CATALOGUE``; it runs the Alembic migrations to head
and seeds the tilings the plugins ship when the catalogue is empty, and again (merging, never
dropping search results) whenever the plugins or their shipped data change. Queries are built from
parsed filters (:func:`parse_filter`) with SQLAlchemy expressions only: a user's text never
reaches the database as SQL. See docs/catalogue.md.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import math
import numbers
import os
import re
import sys
import threading
import types
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path
from typing import IO, Any

import pluggy
import sqlalchemy as sa
from sqlalchemy import event
from sqlalchemy.engine import Connection, Engine, make_url
from sqlalchemy.exc import ArgumentError, SQLAlchemyError

from tilekit.errors import (
    CatalogueError,
    NotFoundError,
    ParameterError,
    ParseError,
    PluginError,
    TilekitError,
)
from tilekit.models import (
    RUN_STATUSES,
    SHARED_COLUMNS,
    TEXT_COLUMNS,
    AliasRow,
    MetaRow,
    PropertyRow,
    RunChunkRow,
    RunResultRow,
    RunRow,
    TilingRow,
    utcnow,
)
from tilekit.plugins import (
    CatalogueRecord,
    ChunkResult,
    catalogue_records,
    families,
    get_plugin_manager,
    migration_locations,
)
from tilekit.resources import catalogue_dir, migrations_dir

__all__ = [
    "Catalogue",
    "ENV_VAR",
    "Entry",
    "Filter",
    "RunInfo",
    "default_path",
    "open_catalogue",
    "parse_filter",
    "resolve_url",
]

#: Environment variable naming the catalogue URL (or a file path).
ENV_VAR = "TILEKIT_CATALOGUE"

#: SQLite waits this long (ms) for a lock held by another writer before giving up.
BUSY_TIMEOUT_MS = 30_000

#: ``KEY=N`` on a numeric property matches values within this relative tolerance, so a
#: float written with 10 significant digits finds the stored double.
NUMBER_RTOL = 1e-9

#: Alembic keeps its migration context in module globals: one migration at a time per process.
_MIGRATION_LOCK = threading.RLock()

#: Batch size for ``IN (...)`` lists and bulk inserts.
_BATCH = 500

_TILINGS = TilingRow.__table__
_ALIASES = AliasRow.__table__
_PROPS = PropertyRow.__table__
_META = MetaRow.__table__
#: catalogue_meta key holding the fingerprint of the records the plugins shipped at last seeding
SEED_KEY = "seed_fingerprint"


def shipped_fingerprint(pm: pluggy.PluginManager) -> str:
    """A hash of what determines the shipped records: tilekit's version, the registered
    plugins' names and source files, and the shipped catalogue/ data.

    Computing it reads about a megabyte of files (milliseconds); building the records
    themselves takes a second, so it is done only when the fingerprint changes.
    """
    from tilekit import __version__

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
_RUNS = RunRow.__table__
_CHUNKS = RunChunkRow.__table__
_RESULTS = RunResultRow.__table__

#: Keys an Entry row uses itself; a property may not take these names.
_RESERVED_KEYS = frozenset({"name", "family", "title", "spec", "aliases", "id"})
_KEY_RE = re.compile(r"^[a-z][a-z0-9_]*$")


# --------------------------------------------------------------------------- URLs


def default_path() -> Path:
    """The default catalogue file: ``<user data dir>/tilekit/catalogue.sqlite``."""
    import platformdirs

    return Path(platformdirs.user_data_dir("tilekit")) / "catalogue.sqlite"


def resolve_url(url: str | os.PathLike[str] | None = None) -> str:
    """The catalogue URL to use: ``url``, else ``$TILEKIT_CATALOGUE``, else the default file.

    A value without ``://`` is a file path and becomes a ``sqlite:///`` URL.
    """
    raw = os.fspath(url) if url is not None else None
    if not raw:
        raw = os.environ.get(ENV_VAR, "").strip() or None
    if not raw:
        return "sqlite:///" + str(default_path())
    if "://" not in raw:
        return "sqlite:///" + str(Path(raw).expanduser().resolve())
    return raw


def _display(url: sa.URL) -> str:
    return url.render_as_string(hide_password=True)


def _sqlite_file(url: sa.URL) -> Path | None:
    if url.get_backend_name() != "sqlite":
        return None
    db = url.database
    if not db or db == ":memory:" or db.startswith("file:"):
        return None
    return Path(db)


_SQLITE_MAGIC = b"SQLite format 3\x00"


def _check_sqlite_file(path: Path, *, create_parent: bool) -> None:
    """Refuse a path that is not (and cannot become) a SQLite database, touching nothing."""
    if path.is_dir():
        raise CatalogueError(f"catalogue path {path} is a directory; give a file path")
    if path.exists():
        try:
            with path.open("rb") as fh:
                head = fh.read(len(_SQLITE_MAGIC))
        except OSError as exc:
            raise CatalogueError(f"cannot read catalogue file {path}: {exc.strerror}") from None
        if head and head != _SQLITE_MAGIC:
            raise CatalogueError(
                f"{path} is not a SQLite database (left untouched); point --catalogue / "
                f"{ENV_VAR} at a new or existing catalogue file"
            )
        return
    if not path.parent.exists():
        if create_parent:
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise CatalogueError(f"cannot create directory {path.parent}: {exc.strerror}") from None
        else:
            raise CatalogueError(f"cannot create catalogue {path}: directory {path.parent} does not exist")


def _one_line(exc: BaseException) -> str:
    orig = getattr(exc, "orig", None) or exc
    text = " ".join(str(orig).split())
    return text or type(orig).__name__


# --------------------------------------------------------------------------- filters

_FILTER_RE = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_\-]*)\s*(!=|>=|<=|=|>|<|~)(.*)$", re.S)
_INT_RE = re.compile(r"^[+-]?\d+$")
_FLOAT_RE = re.compile(r"^[+-]?(\d+\.\d*|\.\d+|\d+)([eE][+-]?\d+)?$")

FILTER_FORMS = "KEY=VALUE, KEY!=VALUE, KEY>=N, KEY<=N, KEY>N, KEY<N or KEY~TEXT"


def auto_type(text: str) -> bool | int | float | str:
    """``true``/``false`` -> bool, integers -> int, decimals -> float, anything else -> str."""
    low = text.strip().lower()
    if low in ("true", "false"):
        return low == "true"
    stripped = text.strip()
    if _INT_RE.match(stripped) and len(stripped) <= 18:
        return int(stripped)
    if _INT_RE.match(stripped) or _FLOAT_RE.match(stripped):
        value = float(stripped)  # a huge integer compares as a float
        if not math.isfinite(value):
            raise ParseError(f"number {stripped[:24]}{'...' if len(stripped) > 24 else ''} is out of range")
        return value
    return text


@dataclass(frozen=True)
class Filter:
    """A parsed filter: property ``key``, operator, auto-typed ``value`` and the ``raw`` text."""

    key: str
    op: str
    value: bool | int | float | str
    raw: str

    def __str__(self) -> str:
        return f"{self.key}{self.op}{self.raw}"


def parse_filter(expr: str | Filter) -> Filter:
    """Parse ``KEY=VALUE``, ``KEY!=V``, ``KEY>=N``, ``KEY<=N``, ``KEY>N``, ``KEY<N``, ``KEY~TEXT``.

    Values are auto-typed (``true``/``false`` -> bool, numbers -> number, else text); a value
    in matching quotes is always text (``name="6"``). ``~`` is a case-insensitive substring
    match. Keys are snake_case; dashes are read as underscores (``k-hedral``).
    """
    if isinstance(expr, Filter):
        return expr
    m = _FILTER_RE.match(str(expr))
    if not m:
        raise ParseError(f"filter {expr!r} is not of the form {FILTER_FORMS}")
    key = m.group(1).replace("-", "_").lower()
    op = m.group(2)
    raw = m.group(3).strip()
    quoted = len(raw) >= 2 and raw[0] == raw[-1] and raw[0] in "'\""
    if quoted:
        raw = raw[1:-1]
        value: bool | int | float | str = raw
    elif op == "~":
        value = raw
    else:
        value = auto_type(raw)
    if op in (">", "<", ">=", "<=") and (isinstance(value, bool) or not isinstance(value, int | float)):
        raise ParseError(f"filter {expr!r}: {op} needs a number, got {raw!r}")
    return Filter(key, op, value, raw)


# --------------------------------------------------------------------------- entries


@dataclass
class Entry:
    """One catalogue tiling as a query returns it (properties with their lists restored)."""

    name: str
    family: str
    title: str
    spec: dict[str, Any]
    properties: dict[str, Any] = field(default_factory=dict)
    aliases: list[str] = field(default_factory=list)
    id: int | None = None

    def flat(self) -> dict[str, Any]:
        """``{"name", "family", "title", **properties}`` (the shape ``tilekit list`` prints)."""
        return {"name": self.name, "family": self.family, "title": self.title, **self.properties}

    def full(self) -> dict[str, Any]:
        """Everything, spec included (the shape ``export`` writes)."""
        return {
            "name": self.name,
            "family": self.family,
            "title": self.title,
            "aliases": list(self.aliases),
            "properties": dict(self.properties),
            "spec": self.spec,
        }


@dataclass
class RunInfo:
    """A search run as ``tilekit runs`` shows it."""

    id: int
    kind: str
    params: dict[str, Any]
    status: str
    chunks_total: int
    chunks_done: int
    created_at: datetime | None
    started_at: datetime | None
    finished_at: datetime | None
    seconds: float
    summary: dict[str, Any] | None
    error: str | None

    @property
    def progress(self) -> str:
        return f"{self.chunks_done}/{self.chunks_total}"


def _scalar_row(key: str, value: Any, owner: str) -> dict[str, Any]:
    kind = type(value)  # fast path for the plain types; ABC checks below for numpy and co.
    if kind is str:
        return {"kind": "str", "value_text": value, "value_num": None, "value_bool": None}
    if kind is int:
        return {"kind": "int", "value_text": None, "value_num": float(value), "value_bool": None}
    if kind is bool:
        return {"kind": "bool", "value_text": None, "value_num": None, "value_bool": value}
    row: dict[str, Any] = {"value_text": None, "value_num": None, "value_bool": None}
    if value is None:
        row["kind"] = "null"
    elif isinstance(value, bool):
        row["kind"], row["value_bool"] = "bool", value
    elif isinstance(value, numbers.Integral):
        row["kind"], row["value_num"] = "int", float(int(value))
    elif isinstance(value, numbers.Real):
        v = float(value)
        if not math.isfinite(v):
            raise CatalogueError(f"record {owner!r}: property {key!r} is {v}, not a finite number")
        row["kind"], row["value_num"] = "float", v
    elif isinstance(value, str):
        row["kind"], row["value_text"] = "str", value
    else:
        raise CatalogueError(
            f"record {owner!r}: property {key!r} has a {type(value).__name__}; "
            "properties are str, int, float, bool, null or lists of them"
        )
    return row


def _json_row(owner: str, key: str, value: Any) -> dict[str, Any]:
    """A nested value (list of lists, object) kept whole as JSON text: shown, ~-searchable."""
    _json_ok(f"record {owner!r}", f"property {key!r}", value)
    return {"key": key, "position": None, "kind": "json", "value_text": json.dumps(value),
            "value_num": None, "value_bool": None}


def _property_rows(owner: str, properties: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Typed rows for every property; a list becomes one row per element (``position``)."""
    rows: list[dict[str, Any]] = []
    for key, value in properties.items():
        if not isinstance(key, str) or not _KEY_RE.match(key):
            raise CatalogueError(f"record {owner!r}: property key {key!r} is not snake_case")
        if key in _RESERVED_KEYS:
            raise CatalogueError(
                f"record {owner!r}: property key {key!r} is reserved ({', '.join(sorted(_RESERVED_KEYS))})"
            )
        if isinstance(value, list | tuple):
            if not value:
                rows.append({"key": key, "position": None, "kind": "empty",
                             "value_text": None, "value_num": None, "value_bool": None})
            elif any(isinstance(item, list | tuple | dict) for item in value):
                rows.append(_json_row(owner, key, value))
            else:
                for i, item in enumerate(value):
                    rows.append({"key": key, "position": i, **_scalar_row(key, item, owner)})
        elif isinstance(value, dict):
            rows.append(_json_row(owner, key, value))
        else:
            rows.append({"key": key, "position": None, **_scalar_row(key, value, owner)})
    return rows


def _restore_value(kind: str, text: str | None, num: float | None, flag: bool | None) -> Any:
    if kind == "str":
        return text
    if kind == "int":
        return int(num) if num is not None else None
    if kind == "float":
        return num
    if kind == "bool":
        return bool(flag) if flag is not None else None
    if kind == "json":
        return json.loads(text) if text is not None else None
    return None


def _shared_values(owner: str, properties: Mapping[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, typ in SHARED_COLUMNS.items():
        value = properties.get(key)
        if key == "symmetry_group" and value is None:
            # families report the wallpaper group as "wallpaper_group" (tilekit.symmetry)
            value = properties.get("wallpaper_group")
        if value is None:
            out[key] = None
        elif typ is bool:
            if not isinstance(value, bool):
                raise CatalogueError(f"record {owner!r}: property {key!r} must be true or false, got {value!r}")
            out[key] = value
        elif typ is int:
            if isinstance(value, bool) or not isinstance(value, numbers.Integral):
                raise CatalogueError(f"record {owner!r}: property {key!r} must be an integer, got {value!r}")
            out[key] = int(value)
        else:
            if not isinstance(value, str):
                raise CatalogueError(f"record {owner!r}: property {key!r} must be text, got {value!r}")
            out[key] = value
    return out


def _json_ok(owner: str, what: str, value: Any) -> None:
    try:
        json.dumps(value, allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise CatalogueError(f"{owner}: {what} is not plain JSON ({exc})") from None


def _batches(items: Sequence[Any], size: int = _BATCH) -> Iterator[Sequence[Any]]:
    for start in range(0, len(items), size):
        yield items[start : start + size]


# --------------------------------------------------------------------------- catalogue


class Catalogue:
    """An open catalogue database. Build one with :func:`open_catalogue`."""

    def __init__(self, engine: Engine, pm: pluggy.PluginManager | None = None) -> None:
        self.engine = engine
        self._pm = pm

    # ----------------------------------------------------------------- basics

    @property
    def pm(self) -> pluggy.PluginManager:
        return self._pm or get_plugin_manager()

    @property
    def url(self) -> str:
        """The database URL, password hidden."""
        return _display(self.engine.url)

    @property
    def path(self) -> Path | None:
        """The SQLite file, or None for other databases."""
        return _sqlite_file(self.engine.url)

    def close(self) -> None:
        self.engine.dispose()

    def __enter__(self) -> Catalogue:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"<Catalogue {self.url}>"

    @contextmanager
    def _errors(self, action: str) -> Iterator[None]:
        try:
            yield
        except SQLAlchemyError as exc:
            raise CatalogueError(f"catalogue {self.url}: {action} failed: {_one_line(exc)}") from None

    def _lock_for_writing(self, conn: Connection) -> None:
        """On SQLite, take the write lock now (BEGIN IMMEDIATE), so a check-then-write
        sequence (am I migrated? is it empty? does this name exist?) is atomic; other
        writers wait for it through the busy timeout. pysqlite would otherwise run DDL and
        the leading SELECTs outside any transaction."""
        if conn.dialect.name == "sqlite":
            conn.exec_driver_sql("BEGIN IMMEDIATE")

    # ----------------------------------------------------------------- migrations

    def _alembic_config(self) -> Any:
        from alembic.config import Config

        cfg = Config()
        cfg.set_main_option("script_location", str(migrations_dir()).replace("%", "%%"))
        locations = [str(migrations_dir() / "versions"), *migration_locations(self.pm)]
        cfg.set_main_option("path_separator", "os")
        cfg.set_main_option("version_path_separator", "os")
        cfg.set_main_option("version_locations", os.pathsep.join(locations).replace("%", "%%"))
        cfg.set_main_option("sqlalchemy.url", self.engine.url.render_as_string(hide_password=False).replace("%", "%%"))
        return cfg

    def revisions(self) -> tuple[set[str], set[str]]:
        """(the revisions the database is at, the head revisions of the migration scripts)."""
        from alembic.runtime.migration import MigrationContext
        from alembic.script import ScriptDirectory

        script = ScriptDirectory.from_config(self._alembic_config())
        with self._errors("reading the migration state"), self.engine.connect() as conn:
            current = set(MigrationContext.configure(conn).get_current_heads())
        return current, set(script.get_heads())

    def upgrade(self, revision: str = "heads") -> set[str]:
        """Run the Alembic migrations (core and plugins) up to ``revision``; return the new state."""
        from alembic import command
        from alembic.runtime.migration import MigrationContext
        from alembic.script import ScriptDirectory
        from alembic.script.revision import RevisionError
        from alembic.util import CommandError

        cfg = self._alembic_config()
        script = ScriptDirectory.from_config(cfg)
        with _MIGRATION_LOCK, self._errors("migrating"), self.engine.begin() as conn:
            self._lock_for_writing(conn)
            current = set(MigrationContext.configure(conn).get_current_heads())
            for rev in current:
                try:
                    known = script.get_revision(rev)
                except (CommandError, RevisionError):
                    known = None
                if known is None:
                    raise CatalogueError(
                        f"catalogue {self.url} is at migration {rev!r}, which this tilekit does not "
                        "know (made by a newer version or a missing plugin?); left untouched"
                    )
            if revision == "heads" and current == set(script.get_heads()):
                return current
            cfg.attributes["connection"] = conn
            try:
                command.upgrade(cfg, revision)
            except (CommandError, RevisionError) as exc:
                raise CatalogueError(f"catalogue {self.url}: migration to {revision!r} failed: {exc}") from None
            return set(MigrationContext.configure(conn).get_current_heads())

    def downgrade(self, revision: str) -> None:
        """Run migrations down to ``revision`` (``"base"`` drops every tilekit table)."""
        from alembic import command
        from alembic.script.revision import RevisionError
        from alembic.util import CommandError

        cfg = self._alembic_config()
        with _MIGRATION_LOCK, self._errors("migrating"), self.engine.begin() as conn:
            self._lock_for_writing(conn)
            cfg.attributes["connection"] = conn
            try:
                command.downgrade(cfg, revision)
            except (CommandError, RevisionError) as exc:
                raise CatalogueError(f"catalogue {self.url}: downgrade to {revision!r} failed: {exc}") from None

    # ----------------------------------------------------------------- writing tilings

    def count(self, family: str | None = None) -> int:
        """Number of tilings (of one family)."""
        stmt = sa.select(sa.func.count()).select_from(_TILINGS)
        if family is not None:
            stmt = stmt.where(_TILINGS.c.family == family)
        with self._errors("counting"), self.engine.connect() as conn:
            return int(conn.execute(stmt).scalar_one())

    def seed(self, replace: bool = False) -> tuple[int, int]:
        """Load the records every plugin ships; return (added, replaced).

        Records whose name is already in the catalogue are left alone unless ``replace``;
        tilings not shipped by any plugin (e.g. search results) are never removed.
        """
        records = catalogue_records(self.pm)
        return self.upsert(records, replace=replace)

    def seed_if_empty(self) -> tuple[int, int]:
        """Seed only if the catalogue has no tilings, checked and written in one transaction."""
        records = catalogue_records(self.pm)
        with self._errors("seeding"), self.engine.begin() as conn:
            self._lock_for_writing(conn)
            if conn.execute(sa.select(sa.func.count()).select_from(_TILINGS)).scalar_one():
                return 0, 0
            return _upsert(conn, list(records), replace=False)

    def refresh_shipped(self) -> tuple[int, int] | None:
        """Bring the shipped records up to date when the plugins or their data changed.

        Compares :func:`shipped_fingerprint` with the one stored at the last seeding; when
        they differ, inserts new shipped records and updates existing ones (spec, title,
        aliases, shipped properties), keeping properties that searches added and every
        tiling no plugin ships. Returns (added, updated), or None when nothing changed.
        """
        fingerprint = shipped_fingerprint(self.pm)
        with self._errors("reading the catalogue's metadata"), self.engine.connect() as conn:
            stored = conn.execute(sa.select(_META.c.value).where(_META.c.key == SEED_KEY)).scalar()
        if stored == fingerprint:
            return None
        records = list(catalogue_records(self.pm))
        with self._errors("seeding"), self.engine.begin() as conn:
            self._lock_for_writing(conn)
            stored = conn.execute(sa.select(_META.c.value).where(_META.c.key == SEED_KEY)).scalar()
            if stored == fingerprint:  # another process refreshed it meanwhile
                return None
            names = [r.name for r in records]
            rows = []
            for batch in _batches(names):
                rows += conn.execute(
                    sa.select(_TILINGS.c.id, _TILINGS.c.name, _TILINGS.c.family, _TILINGS.c.title, _TILINGS.c.spec)
                    .where(_TILINGS.c.name.in_(batch))
                ).all()
            existing = {e.name: e for e in self._entries(conn, rows)}
            merged = []
            for rec in records:
                old = existing.get(rec.name)
                if old is not None:
                    rec = CatalogueRecord(
                        family=rec.family,
                        name=rec.name,
                        spec=rec.spec,
                        title=rec.title,
                        properties={**old.properties, **rec.properties},
                        aliases=list(rec.aliases),
                    )
                merged.append(rec)
            result = _upsert(conn, merged, replace=True)
            conn.execute(sa.delete(_META).where(_META.c.key == SEED_KEY))
            conn.execute(sa.insert(_META).values(key=SEED_KEY, value=fingerprint))
            return result

    def upsert(self, records: Iterable[CatalogueRecord], *, replace: bool = True) -> tuple[int, int]:
        """Insert records by name (replacing existing ones if ``replace``); return (added, replaced)."""
        records = list(records)
        with self._errors("writing tilings"), self.engine.begin() as conn:
            self._lock_for_writing(conn)
            return _upsert(conn, records, replace=replace)

    def delete(self, name: str) -> None:
        """Remove a tiling (by name or alias) with its properties and aliases."""
        entry = self.get(name)
        with self._errors("deleting"), self.engine.begin() as conn:
            conn.execute(sa.delete(_PROPS).where(_PROPS.c.tiling_id == entry.id))
            conn.execute(sa.delete(_ALIASES).where(_ALIASES.c.tiling_id == entry.id))
            conn.execute(sa.delete(_TILINGS).where(_TILINGS.c.id == entry.id))

    # ----------------------------------------------------------------- reading tilings

    def property_keys(self) -> list[str]:
        """Every property key present in the catalogue, sorted."""
        with self._errors("reading property keys"), self.engine.connect() as conn:
            keys = conn.execute(sa.select(_PROPS.c.key).distinct()).scalars().all()
        return sorted(keys)

    def query(
        self,
        family: str | None = None,
        where: Iterable[str | Filter] = (),
        text: str | None = None,
        order_by: str = "name",
        limit: int | None = None,
        offset: int = 0,
    ) -> list[Entry]:
        """Tilings matching every filter, ordered and paged.

        ``family`` restricts to one family; ``where`` holds filter expressions (see
        :func:`parse_filter`): ``=`` on numbers allows a relative tolerance of 1e-9; on a
        list property ``=`` means "some element equals", ``!=``
        means "has the property and no element equals", ranges mean "some element is in
        range". ``text`` is a case-insensitive substring of the name, title, an alias or a
        text property. ``order_by`` is a column or property key, ``-key`` for descending.
        """
        stmt = self._select(family, where, text)
        stmt = stmt.order_by(*self._ordering(order_by))
        if limit is not None:
            if limit < 0:
                raise ParameterError(f"limit must be >= 0, got {limit}")
            stmt = stmt.limit(limit)
        if offset:
            if offset < 0:
                raise ParameterError(f"offset must be >= 0, got {offset}")
            stmt = stmt.offset(offset)
        with self._errors("querying"), self.engine.connect() as conn:
            rows = conn.execute(stmt).all()
            return self._entries(conn, rows)

    def count_matching(
        self, family: str | None = None, where: Iterable[str | Filter] = (), text: str | None = None
    ) -> int:
        """How many tilings :meth:`query` would return without a limit."""
        sub = self._select(family, where, text).subquery()
        with self._errors("counting"), self.engine.connect() as conn:
            return int(conn.execute(sa.select(sa.func.count()).select_from(sub)).scalar_one())

    def _select(self, family: str | None, where: Iterable[str | Filter], text: str | None) -> sa.Select:
        t = _TILINGS
        stmt = sa.select(t.c.id, t.c.name, t.c.family, t.c.title, t.c.spec)
        if family is not None:
            stmt = stmt.where(t.c.family == family)
        filters = [parse_filter(w) for w in where]
        unknown = [
            f.key for f in filters if f.key not in TEXT_COLUMNS and f.key not in SHARED_COLUMNS
        ]
        if unknown:
            known = set(self.property_keys())
            for key in unknown:
                if key not in known:
                    raise NotFoundError("property", key, [*TEXT_COLUMNS, *SHARED_COLUMNS, *sorted(known)])
        for f in filters:
            stmt = stmt.where(_condition(f))
        if text:
            needle = text.lower()
            p, a = _PROPS, _ALIASES
            stmt = stmt.where(
                sa.or_(
                    sa.func.lower(t.c.name).contains(needle, autoescape=True),
                    sa.func.lower(t.c.title).contains(needle, autoescape=True),
                    t.c.id.in_(
                        sa.select(a.c.tiling_id).where(
                            sa.func.lower(a.c.alias).contains(needle, autoescape=True)
                        )
                    ),
                    t.c.id.in_(
                        sa.select(p.c.tiling_id).where(
                            sa.func.lower(p.c.value_text).contains(needle, autoescape=True)
                        )
                    ),
                )
            )
        return stmt

    def _ordering(self, order_by: str) -> list[Any]:
        key = (order_by or "name").strip()
        descending = key.startswith("-")
        key = key.lstrip("-+").replace("-", "_").lower()
        t, p = _TILINGS, _PROPS
        columns = {*TEXT_COLUMNS, *SHARED_COLUMNS, "id", "created_at", "updated_at"}
        if key in columns:
            exprs = [t.c[key]]
        else:
            known = self.property_keys()
            if key not in known:
                raise NotFoundError("order key", key, [*sorted(columns), *known])
            num = (
                sa.select(sa.func.min(p.c.value_num))
                .where(p.c.tiling_id == t.c.id, p.c.key == key)
                .scalar_subquery()
            )
            txt = (
                sa.select(sa.func.min(p.c.value_text))
                .where(p.c.tiling_id == t.c.id, p.c.key == key)
                .scalar_subquery()
            )
            exprs = [num, txt]
        ordered = [(e.desc() if descending else e.asc()).nulls_last() for e in exprs]
        return [*ordered, t.c.name.asc(), t.c.id.asc()]

    def _entries(self, conn: Connection, rows: Sequence[Any]) -> list[Entry]:
        entries = {
            r.id: Entry(name=r.name, family=r.family, title=r.title or "", spec=r.spec, id=r.id)
            for r in rows
        }
        ids = list(entries)
        lists: dict[tuple[int, str], list[Any]] = {}
        for batch in _batches(ids):
            prop_rows = conn.execute(
                sa.select(
                    _PROPS.c.tiling_id, _PROPS.c.key, _PROPS.c.position, _PROPS.c.kind,
                    _PROPS.c.value_text, _PROPS.c.value_num, _PROPS.c.value_bool,
                )
                .where(_PROPS.c.tiling_id.in_(batch))
                .order_by(_PROPS.c.tiling_id, _PROPS.c.id)
            ).all()
            for tid, key, position, kind, text, num, flag in prop_rows:
                props = entries[tid].properties
                if kind == "empty":
                    props[key] = []
                elif position is None:
                    props[key] = _restore_value(kind, text, num, flag)
                else:
                    bucket = lists.setdefault((tid, key), [])
                    bucket.append((position, _restore_value(kind, text, num, flag)))
                    props.setdefault(key, [])
            alias_rows = conn.execute(
                sa.select(_ALIASES.c.tiling_id, _ALIASES.c.alias)
                .where(_ALIASES.c.tiling_id.in_(batch))
                .order_by(_ALIASES.c.id)
            ).all()
            for tid, alias in alias_rows:
                entries[tid].aliases.append(alias)
        for (tid, key), items in lists.items():
            entries[tid].properties[key] = [v for _, v in sorted(items, key=lambda pv: pv[0])]
        return [entries[r.id] for r in rows]

    def names(self) -> list[str]:
        """Every tiling name and alias (for suggestions)."""
        with self._errors("reading names"), self.engine.connect() as conn:
            names = conn.execute(sa.select(_TILINGS.c.name)).scalars().all()
            aliases = conn.execute(sa.select(_ALIASES.c.alias)).scalars().all()
        return [*names, *aliases]

    def get(self, name: str) -> Entry:
        """The tiling called ``name`` or having it as an alias (exact, then case-insensitive).

        Raises NotFoundError suggesting the closest names.
        """
        t, a = _TILINGS, _ALIASES
        cols = (t.c.id, t.c.name, t.c.family, t.c.title, t.c.spec)
        attempts = [
            sa.select(*cols).where(t.c.name == name),
            sa.select(*cols).join(a, a.c.tiling_id == t.c.id).where(a.c.alias == name),
            sa.select(*cols).where(sa.func.lower(t.c.name) == name.lower()),
            sa.select(*cols).join(a, a.c.tiling_id == t.c.id).where(sa.func.lower(a.c.alias) == name.lower()),
        ]
        with self._errors("looking up a tiling"), self.engine.connect() as conn:
            for stmt in attempts:
                rows = conn.execute(stmt.order_by(t.c.id)).all()
                if len(rows) >= 1:
                    return self._entries(conn, rows[:1])[0]
        raise NotFoundError("tiling", name, self.names())

    def tiling(self, name: str) -> Any:
        """The :class:`tilekit.Tiling` called ``name``, rebuilt by its family's ``from_spec``."""
        entry = self.get(name)
        fams = families(self.pm)
        if entry.family not in fams:
            raise NotFoundError("family", entry.family, fams)
        try:
            return fams[entry.family].from_spec(entry.spec)
        except TilekitError:
            raise
        except Exception as exc:
            raise PluginError(
                f"family {entry.family!r} could not rebuild {entry.name!r} from its spec: "
                f"{type(exc).__name__}: {_one_line(exc)}"
            ) from exc

    # ----------------------------------------------------------------- export

    def export(
        self,
        path_or_stream: str | os.PathLike[str] | IO[str],
        format: str = "json",
        **query: Any,
    ) -> int:
        """Write every tiling (or those matching ``query`` keywords) as JSON or CSV.

        JSON is an array of ``{name, family, title, aliases, properties, spec}``; CSV has
        one column per property (lists and the spec as JSON text). Returns the row count.
        """
        if format not in ("json", "csv"):
            raise ParameterError(f"export format {format!r} is not one of: json, csv")
        entries = self.query(**query)
        if isinstance(path_or_stream, str | os.PathLike):
            try:
                with open(path_or_stream, "w", encoding="utf-8", newline="") as fh:
                    write_entries(entries, fh, format, full=True)
            except OSError as exc:
                raise CatalogueError(f"cannot write {os.fspath(path_or_stream)}: {exc.strerror}") from None
        else:
            write_entries(entries, path_or_stream, format, full=True)
        return len(entries)

    # ----------------------------------------------------------------- runs

    def create_run(self, kind: str, params: Mapping[str, Any], chunks: Sequence[Mapping[str, Any]]) -> int:
        """Store a new queued run with its chunks (all pending); return its id."""
        _json_ok(f"search {kind!r}", "the parameters", dict(params))
        for i, chunk in enumerate(chunks):
            _json_ok(f"search {kind!r}", f"chunk {i}", dict(chunk))
        with self._errors("creating a run"), self.engine.begin() as conn:
            run_id = conn.execute(
                sa.insert(_RUNS)
                .values(kind=kind, params=dict(params), status="queued", chunks_total=len(chunks),
                        chunks_done=0, seconds=0.0)
                .returning(_RUNS.c.id)
            ).scalar_one()
            for batch in _batches([
                {"run_id": run_id, "index": i, "spec": dict(c), "status": "pending"}
                for i, c in enumerate(chunks)
            ]):
                conn.execute(sa.insert(_CHUNKS), list(batch))
        return int(run_id)

    def start_run(self, run_id: int) -> None:
        """Mark a run running (keeping its first start time)."""
        with self._errors("starting a run"), self.engine.begin() as conn:
            conn.execute(
                sa.update(_RUNS)
                .where(_RUNS.c.id == run_id)
                .values(status="running", error=None,
                        started_at=sa.func.coalesce(_RUNS.c.started_at, utcnow()))
            )

    def pending_chunks(self, run_id: int) -> list[tuple[int, dict[str, Any]]]:
        """(index, chunk) of every chunk of the run not yet done, in index order."""
        with self._errors("reading chunks"), self.engine.connect() as conn:
            rows = conn.execute(
                sa.select(_CHUNKS.c.index, _CHUNKS.c.spec)
                .where(_CHUNKS.c.run_id == run_id, _CHUNKS.c.status != "done")
                .order_by(_CHUNKS.c.index)
            ).all()
        return [(int(i), spec) for i, spec in rows]

    def record_chunk(
        self, run_id: int, index: int, result: ChunkResult, seconds: float | None = None
    ) -> bool:
        """Store a chunk's results and records and mark it done, in ONE transaction.

        Returns False (writing nothing) if the chunk was already done, so a chunk computed
        twice (a resumed run, two workers) is never stored twice.
        """
        if not isinstance(result, ChunkResult):
            raise CatalogueError(
                f"run {run_id} chunk {index}: expected a ChunkResult, got {type(result).__name__}"
            )
        for item in result.results:
            if not isinstance(item, dict):
                raise CatalogueError(
                    f"run {run_id} chunk {index}: a result is a {type(item).__name__}, not a JSON object"
                )
            _json_ok(f"run {run_id} chunk {index}", "a result", item)
        with self._errors(f"recording run {run_id} chunk {index}"), self.engine.begin() as conn:
            self._lock_for_writing(conn)
            marked = conn.execute(
                sa.update(_CHUNKS)
                .where(_CHUNKS.c.run_id == run_id, _CHUNKS.c.index == index, _CHUNKS.c.status != "done")
                .values(status="done", seconds=seconds, finished_at=utcnow())
            ).rowcount
            if marked != 1:
                exists = conn.execute(
                    sa.select(_CHUNKS.c.id).where(_CHUNKS.c.run_id == run_id, _CHUNKS.c.index == index)
                ).first()
                if exists is None:
                    raise CatalogueError(f"run {run_id} has no chunk {index}")
                return False
            if result.results:
                for batch in _batches(
                    [{"run_id": run_id, "chunk_index": index, "data": item} for item in result.results]
                ):
                    conn.execute(sa.insert(_RESULTS), list(batch))
            if result.records:
                _upsert(conn, list(result.records), replace=True)
            conn.execute(
                sa.update(_RUNS).where(_RUNS.c.id == run_id).values(chunks_done=_RUNS.c.chunks_done + 1)
            )
        return True

    def finish_run(
        self,
        run_id: int,
        status: str,
        *,
        summary: Mapping[str, Any] | None = None,
        error: str | None = None,
        seconds: float = 0.0,
    ) -> None:
        """Set a run's final (or interrupted) status, add ``seconds`` of work, store summary/error."""
        if status not in RUN_STATUSES:
            raise ParameterError(f"run status {status!r} is not one of: {', '.join(RUN_STATUSES)}")
        values: dict[str, Any] = {
            "status": status,
            "seconds": _RUNS.c.seconds + float(seconds),
            "error": error,
        }
        if status in ("done", "failed", "interrupted"):
            values["finished_at"] = utcnow()
        if summary is not None:
            _json_ok(f"run {run_id}", "the summary", dict(summary))
            values["summary"] = dict(summary)
        with self._errors("finishing a run"), self.engine.begin() as conn:
            conn.execute(sa.update(_RUNS).where(_RUNS.c.id == run_id).values(**values))

    def runs(self, kind: str | None = None) -> list[RunInfo]:
        """Every run (of one search kind), oldest first."""
        stmt = sa.select(_RUNS).order_by(_RUNS.c.id)
        if kind is not None:
            stmt = stmt.where(_RUNS.c.kind == kind)
        with self._errors("reading runs"), self.engine.connect() as conn:
            return [_run_info(r) for r in conn.execute(stmt).all()]

    def run(self, run_id: int) -> RunInfo:
        """One run, or NotFoundError naming the existing run ids."""
        with self._errors("reading a run"), self.engine.connect() as conn:
            row = conn.execute(sa.select(_RUNS).where(_RUNS.c.id == int(run_id))).first()
            if row is None:
                ids = conn.execute(sa.select(_RUNS.c.id).order_by(_RUNS.c.id)).scalars().all()
                raise NotFoundError("run", str(run_id), [str(i) for i in ids])
        return _run_info(row)

    def run_chunks(self, run_id: int) -> list[dict[str, Any]]:
        """Every chunk of a run: index, status, seconds, spec."""
        with self._errors("reading chunks"), self.engine.connect() as conn:
            rows = conn.execute(
                sa.select(_CHUNKS.c.index, _CHUNKS.c.status, _CHUNKS.c.seconds, _CHUNKS.c.spec)
                .where(_CHUNKS.c.run_id == run_id)
                .order_by(_CHUNKS.c.index)
            ).all()
        return [{"index": i, "status": s, "seconds": sec, "spec": spec} for i, s, sec, spec in rows]

    def results(self, run_id: int) -> list[dict[str, Any]]:
        """Every result of a run, in chunk order."""
        with self._errors("reading results"), self.engine.connect() as conn:
            return list(
                conn.execute(
                    sa.select(_RESULTS.c.data)
                    .where(_RESULTS.c.run_id == run_id)
                    .order_by(_RESULTS.c.chunk_index, _RESULTS.c.id)
                ).scalars()
            )


def _run_info(row: Any) -> RunInfo:
    return RunInfo(
        id=row.id,
        kind=row.kind,
        params=row.params or {},
        status=row.status,
        chunks_total=row.chunks_total,
        chunks_done=row.chunks_done,
        created_at=row.created_at,
        started_at=row.started_at,
        finished_at=row.finished_at,
        seconds=float(row.seconds or 0.0),
        summary=row.summary,
        error=row.error,
    )


# --------------------------------------------------------------------------- filters -> SQL


def _type_error(f: Filter, wanted: str) -> ParameterError:
    return ParameterError(f"filter {f}: {f.key} {wanted}, got {f.raw!r}")


def _compare(column: Any, op: str, value: Any) -> Any:
    if op == "=":
        return column == value
    if op == "!=":
        return column != value
    if op == ">":
        return column > value
    if op == "<":
        return column < value
    if op == ">=":
        return column >= value
    return column <= value


def _condition(f: Filter) -> Any:
    """The SQLAlchemy condition of one filter (values are always bound parameters)."""
    t, p = _TILINGS, _PROPS
    if f.key in TEXT_COLUMNS or SHARED_COLUMNS.get(f.key) is str:
        column = t.c[f.key]
        if f.op == "~":
            return sa.func.lower(column).contains(f.raw.lower(), autoescape=True)
        if f.op in ("=", "!="):
            names = _group_names(f.key, f.raw)
            if len(names) > 1:  # p6m or *632
                return column.in_(names) if f.op == "=" else sa.and_(column.is_not(None), column.not_in(names))
            return _compare(column, f.op, f.raw)
        raise _type_error(f, f"is text and takes =, != or ~ (not {f.op})")
    if f.key in SHARED_COLUMNS:
        column = t.c[f.key]
        if SHARED_COLUMNS[f.key] is bool:
            if f.op not in ("=", "!=") or not isinstance(f.value, bool):
                raise _type_error(f, "takes =true, =false or !=")
            return _compare(column, f.op, f.value)
        if f.op == "~" or isinstance(f.value, bool) or not isinstance(f.value, int | float):
            raise _type_error(f, "is a number")
        return _compare(column, f.op, f.value)

    # Uncorrelated "id IN (SELECT tiling_id ...)" subqueries: each is evaluated once through
    # the (key, value) indexes, instead of once per tiling.
    def having(*conditions: Any) -> Any:
        return t.c.id.in_(sa.select(p.c.tiling_id).where(p.c.key == f.key, *conditions))

    if f.op == "~":
        return having(sa.func.lower(p.c.value_text).contains(f.raw.lower(), autoescape=True))
    if f.op in ("=", "!="):
        # each alternative is its own indexed subquery (an OR inside one would defeat the index)
        if isinstance(f.value, bool):
            alternatives = [p.c.value_bool == f.value, p.c.value_text == f.raw]
        elif isinstance(f.value, int | float):
            v = float(f.value)
            eps = NUMBER_RTOL * max(1.0, abs(v))
            alternatives = [p.c.value_num.between(v - eps, v + eps), p.c.value_text == f.raw]
        else:
            alternatives = [p.c.value_text == name for name in _group_names(f.key, f.raw)]
        equal = sa.or_(*(having(c) for c in alternatives))
        if f.op == "=":
            return equal
        return sa.and_(having(), ~equal)
    return having(_compare(p.c.value_num, f.op, float(f.value)))


def _group_names(key: str, value: str) -> list[str]:
    """A wallpaper group matches by its IUC name (p6m) and its orbifold symbol (*632) alike."""
    if key not in ("symmetry_group", "wallpaper_group", "orbifold"):
        return [value]
    from tilekit.symmetry import IUC, ORBIFOLD

    return sorted({value, ORBIFOLD.get(value, value), IUC.get(value, value)})


# --------------------------------------------------------------------------- upsert


def _upsert(conn: Connection, records: list[CatalogueRecord], *, replace: bool) -> tuple[int, int]:
    """Insert or (if ``replace``) replace records by name inside the caller's transaction."""
    prepared: dict[str, tuple[dict[str, Any], list[dict[str, Any]], list[str]]] = {}
    for rec in records:
        if not isinstance(rec, CatalogueRecord):
            raise CatalogueError(f"expected a CatalogueRecord, got {type(rec).__name__}")
        if not isinstance(rec.name, str) or not rec.name.strip():
            raise CatalogueError(f"a record of family {rec.family!r} has an empty name")
        if not isinstance(rec.family, str) or not rec.family:
            raise CatalogueError(f"record {rec.name!r} has no family")
        if rec.name in prepared:
            raise CatalogueError(f"two records are named {rec.name!r}")
        if not isinstance(rec.spec, dict):
            raise CatalogueError(f"record {rec.name!r}: spec is a {type(rec.spec).__name__}, not a JSON object")
        _json_ok(f"record {rec.name!r}", "spec", rec.spec)
        props = dict(rec.properties or {})
        row = {
            "family": rec.family,
            "name": rec.name,
            "title": rec.title or "",
            "spec": rec.spec,
            **_shared_values(rec.name, props),
        }
        aliases = [a for a in dict.fromkeys(rec.aliases or ()) if a and a != rec.name]
        prepared[rec.name] = (row, _property_rows(rec.name, props), aliases)
    if not prepared:
        return 0, 0

    t, a, p = _TILINGS, _ALIASES, _PROPS
    names = list(prepared)
    existing: dict[str, int] = {}
    for batch in _batches(names):
        for tid, name in conn.execute(sa.select(t.c.id, t.c.name).where(t.c.name.in_(batch))):
            existing[name] = tid
    to_replace = [n for n in names if n in existing] if replace else []
    to_insert = [n for n in names if n not in existing]

    ids: dict[str, int] = {}
    if to_replace:
        replace_ids = [existing[n] for n in to_replace]
        for batch in _batches(replace_ids):
            conn.execute(sa.delete(p).where(p.c.tiling_id.in_(batch)))
            conn.execute(sa.delete(a).where(a.c.tiling_id.in_(batch)))
        now = utcnow()
        for name in to_replace:
            row = dict(prepared[name][0])
            row.pop("name")
            conn.execute(sa.update(t).where(t.c.id == existing[name]).values(**row, updated_at=now))
            ids[name] = existing[name]
    if to_insert:
        for batch in _batches(to_insert):
            result = conn.execute(
                sa.insert(t).returning(t.c.id, t.c.name), [prepared[n][0] for n in batch]
            )
            for tid, name in result:
                ids[name] = tid

    # aliases: refuse one that already names or aliases a different tiling
    wanted_aliases = {alias: name for name in ids for alias in prepared[name][2]}
    if wanted_aliases:
        alias_list = list(wanted_aliases)
        own_ids = set(ids.values())
        for batch in _batches(alias_list):
            for alias, tid in conn.execute(sa.select(a.c.alias, a.c.tiling_id).where(a.c.alias.in_(batch))):
                if tid not in own_ids:
                    raise CatalogueError(
                        f"alias {alias!r} of {wanted_aliases[alias]!r} already belongs to another tiling"
                    )
            for (name,) in conn.execute(sa.select(t.c.name).where(t.c.name.in_(batch))):
                if name != wanted_aliases[name]:
                    raise CatalogueError(
                        f"alias {name!r} of {wanted_aliases[name]!r} is the name of another tiling"
                    )
        seen: dict[str, str] = {}
        for name in ids:
            for alias in prepared[name][2]:
                if alias in seen and seen[alias] != name:
                    raise CatalogueError(f"alias {alias!r} is claimed by both {seen[alias]!r} and {name!r}")
                seen[alias] = name
        alias_rows = [{"alias": alias, "tiling_id": ids[name]} for alias, name in seen.items()]
        for batch in _batches(alias_rows):
            conn.execute(sa.insert(a), list(batch))

    prop_rows = [{"tiling_id": ids[name], **row} for name in ids for row in prepared[name][1]]
    for batch in _batches(prop_rows, 5000):
        conn.execute(sa.insert(p), list(batch))
    return len(to_insert), len(to_replace)


# --------------------------------------------------------------------------- output helpers


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, list | dict):
        return json.dumps(value, ensure_ascii=False)
    return str(value)


def write_entries(entries: Sequence[Entry], stream: IO[str], format: str = "json", *, full: bool = False) -> None:
    """Write entries as a JSON array or CSV (``full`` adds aliases and spec)."""
    if format == "json":
        data = [e.full() if full else e.flat() for e in entries]
        json.dump(data, stream, indent=2, ensure_ascii=False)
        stream.write("\n")
        return
    if format != "csv":
        raise ParameterError(f"format {format!r} is not one of: json, csv")
    keys: dict[str, None] = {}
    for e in entries:
        keys.update(dict.fromkeys(e.properties))
    header = ["name", "family", "title", *( ["aliases"] if full else []), *keys, *( ["spec"] if full else [])]
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow(header)
    for e in entries:
        row = [e.name, e.family, e.title]
        if full:
            row.append("; ".join(e.aliases))
        row.extend(_cell(e.properties.get(k)) for k in keys)
        if full:
            row.append(json.dumps(e.spec, ensure_ascii=False))
        writer.writerow(row)


def entries_text(entries: Sequence[Entry], format: str = "json", *, full: bool = False) -> str:
    buf = io.StringIO()
    write_entries(entries, buf, format, full=full)
    return buf.getvalue()


# --------------------------------------------------------------------------- opening


def _sqlite_pragmas(dbapi_connection: Any, _record: Any) -> None:
    cursor = dbapi_connection.cursor()
    try:
        cursor.execute(f"PRAGMA busy_timeout = {BUSY_TIMEOUT_MS}")
        cursor.execute("PRAGMA foreign_keys = ON")
        cursor.execute("PRAGMA journal_mode = WAL")
    finally:
        cursor.close()


def open_catalogue(
    url: str | os.PathLike[str] | None = None,
    *,
    seed: bool = True,
    pm: pluggy.PluginManager | None = None,
    migrate: bool = True,
    engine_factory: Callable[..., Engine] | None = None,
) -> Catalogue:
    """Open the catalogue at ``url`` (or ``$TILEKIT_CATALOGUE``, or the default SQLite file).

    Runs the migrations (core and plugins) to head, and, if ``seed`` and the catalogue has no
    tilings, loads the records the plugins ship. ``pm`` is the plugin manager to use
    (default: the process-wide one). Raises CatalogueError (one line) if the database cannot
    be opened; an existing file that is not a database is never modified.
    """
    resolved = resolve_url(url)
    try:
        sa_url = make_url(resolved)
    except ArgumentError:
        raise CatalogueError(
            f"catalogue URL {resolved!r} is not a database URL (e.g. sqlite:///path/catalogue.sqlite, "
            "postgresql+psycopg://user@host/db) or a file path"
        ) from None
    path = _sqlite_file(sa_url)
    if path is not None:
        explicit = url is not None or bool(os.environ.get(ENV_VAR, "").strip())
        _check_sqlite_file(path, create_parent=not explicit)
    try:
        engine = (engine_factory or sa.create_engine)(sa_url)
    except (ArgumentError, ImportError, SQLAlchemyError) as exc:
        raise CatalogueError(f"cannot open catalogue {_display(sa_url)}: {_one_line(exc)}") from None
    if sa_url.get_backend_name() == "sqlite":
        event.listen(engine, "connect", _sqlite_pragmas)
    catalogue = Catalogue(engine, pm)
    try:
        with engine.connect() as conn:
            conn.execute(sa.text("SELECT 1"))
        if migrate:
            try:
                catalogue.upgrade()
            except CatalogueError:
                # on a server, another process may have migrated the same new catalogue at
                # the same moment (SQLite serialises this through BEGIN IMMEDIATE)
                current, heads = catalogue.revisions()
                if current != heads:
                    raise
        if seed and migrate:
            catalogue.refresh_shipped()
    except SQLAlchemyError as exc:
        engine.dispose()
        raise CatalogueError(f"cannot open catalogue {_display(sa_url)}: {_one_line(exc)}") from None
    except BaseException:
        engine.dispose()
        raise
    return catalogue
