"""The :class:`Catalogue`: opening (checks, migrations, seeding), tilings by name, typed
queries (streamed), export; its run and result-table methods come from
:mod:`tilekit.catalogue.runs` and :mod:`tilekit.catalogue.results`."""

from __future__ import annotations

import json
import os
import threading
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any

import pluggy
import sqlalchemy as sa
from sqlalchemy import event
from sqlalchemy.engine import Connection, Engine, make_url
from sqlalchemy.exc import ArgumentError, SQLAlchemyError

from tilekit.catalogue.codec import batches, upsert
from tilekit.catalogue.entry import Entry
from tilekit.catalogue.filters import Filter
from tilekit.catalogue.output import FORMATS, write_entries
from tilekit.catalogue.reading import (
    RESULT_FAMILIES_KEY,
    SCRIPTS_KEY,
    SEED_KEY,
    Run,
    TilingReader,
    load_entries,
    result_families_value,
    scripts_key,
    shipped_fingerprint,
)
from tilekit.catalogue.results import ResultsMixin
from tilekit.catalogue.runs import RunsMixin
from tilekit.catalogue.tables import ALIASES, META, PROPS, TILINGS
from tilekit.catalogue.urls import (
    ENV_VAR,
    check_sqlite_file,
    display,
    one_line,
    resolve_url,
    sqlite_file,
)
from tilekit.errors import CatalogueError, NotFoundError, ParameterError, PluginError, TilekitError
from tilekit.plugins import (
    CatalogueRecord,
    catalogue_records,
    families,
    get_plugin_manager,
    migration_locations,
    normalise,
)
from tilekit.resources import migrations_dir
from tilekit.signals import checkpoint

#: SQLite waits this long (ms) for a lock held by another writer before giving up.
BUSY_TIMEOUT_MS = 30_000

#: One step of waiting for SQLite's write lock (ms); see _begin_immediate.
_STEP_MS = 50

#: Alembic keeps its migration context in module globals: one migration at a time per process.
_MIGRATION_LOCK = threading.RLock()

#: catalogue_meta key: the property keys each family shipped at the last seeding (JSON, in
#: rows ``shipped_property_keys.0``, ``.1``, ...: a value column holds 400 characters)
SHIPPED_KEYS_KEY = "shipped_property_keys"


def _read_long_meta(conn: Connection, key: str) -> str | None:
    """A catalogue_meta value that :func:`_write_long_meta` split over numbered rows."""
    rows = conn.execute(sa.select(META.c.key, META.c.value).where(META.c.key.startswith(key + "."))).all()
    parts = sorted((int(k.rsplit(".", 1)[1]), v) for k, v in rows if k.rsplit(".", 1)[1].isdigit())
    return "".join(v for _, v in parts) if parts else None


def _write_long_meta(conn: Connection, key: str, text: str) -> None:
    """Store ``text`` under ``key`` in rows ``key.0``, ``key.1``, ... of at most the value
    column's length each (PostgreSQL enforces it; SQLite would not)."""
    width = META.c.value.type.length
    conn.execute(sa.delete(META).where(META.c.key.startswith(key + ".")))
    conn.execute(sa.insert(META), [{"key": f"{key}.{i}", "value": text[j:j + width]}
                                   for i, j in enumerate(range(0, max(len(text), 1), width))])


#: Names offered as suggestions at most (a catalogue of a million results is not read for them).
_MAX_NAMES = 20_000


#: PostgreSQL advisory lock key that serialises migrations, seeding and tiling upserts.
_PG_LOCK = 0x7415_E417


#: Properties whose canonical value determines a tiling up to similarity: records sharing one
#: are one tiling seen by two families (an Archimedean tiling is also the 1-uniform tiling with
#: its D-symbol), so a name read as such a value finds the first, not an ambiguity.
_IDENTITY_KEYS = ("dsymbol",)


class Catalogue(RunsMixin, ResultsMixin, TilingReader):
    """An open catalogue database. Build one with :func:`open_catalogue`."""

    def __init__(self, engine: Engine, pm: pluggy.PluginManager | None = None, *,
                 read_only: bool = False) -> None:
        self.engine = engine
        self._pm = pm
        self._result_tables = None
        #: True when the file (or its folder) cannot be written: queries work, writes are
        #: refused with one line.
        self.read_only = read_only

    # ----------------------------------------------------------------- basics

    @property
    def pm(self) -> pluggy.PluginManager:
        return self._pm or get_plugin_manager()

    @property
    def url(self) -> str:
        """The database URL, password hidden."""
        return display(self.engine.url)

    @property
    def path(self) -> Path | None:
        """The SQLite file, or None for other databases."""
        return sqlite_file(self.engine.url)

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
            text = one_line(exc)
            if "readonly database" in text or "read-only" in text:
                raise CatalogueError(
                    f"catalogue {self.url} is read-only (the file or its folder cannot be written): "
                    f"{action} is not possible; queries, show and render still work"
                ) from None
            raise CatalogueError(f"catalogue {self.url}: {action} failed: {text}") from None

    @contextmanager
    def _reading(self, action: str) -> Iterator[Run]:
        """TilingReader's queries, run through SQLAlchemy on one connection."""
        with self._errors(action), self.engine.connect() as conn:
            yield _runner(conn)

    def _lock_for_writing(self, conn: Connection, records: bool = True) -> None:
        """Take the write lock a check-then-write sequence needs, so it is atomic.

        On SQLite, BEGIN IMMEDIATE (other writers wait through the busy timeout; pysqlite
        would otherwise run DDL and the leading SELECTs outside any transaction). On
        PostgreSQL, with ``records`` (migrations, seeding, tiling upserts by name), a
        transaction-level advisory lock, so concurrent first opens and writers of the same
        names queue instead of failing on a duplicate key; leases need only row locks.
        """
        if self.read_only:
            raise CatalogueError(
                f"catalogue {self.url} is read-only (the file or its folder cannot be written); "
                "queries, show and render work, writing does not"
            )
        if conn.dialect.name == "sqlite":
            _begin_immediate(conn)
        elif conn.dialect.name == "postgresql" and records:
            conn.execute(sa.text("SELECT pg_advisory_xact_lock(:key)"), {"key": _PG_LOCK})

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

    def _known_current(self) -> set[str] | None:
        """The database's revisions, when it is known to be at the heads of exactly these
        scripts (the key stored at the last upgrade matches): opening then needs neither
        Alembic nor the write lock. None when that cannot be told cheaply."""
        try:
            key = scripts_key(self.pm)
            with self.engine.connect() as conn:
                stored = conn.execute(sa.select(META.c.value).where(META.c.key == SCRIPTS_KEY)).scalar()
                current = set(conn.execute(sa.text("SELECT version_num FROM alembic_version")).scalars())
        except (SQLAlchemyError, OSError):
            return None
        if stored is None or stored != f"{key}:{','.join(sorted(current))}":
            return None
        return current

    def upgrade(self, revision: str = "heads") -> set[str]:
        """Run the Alembic migrations (core and plugins) up to ``revision``; return the new state.

        An open of a catalogue already at the heads of the installed scripts (recorded in
        ``catalogue_meta`` at the last upgrade) reads two rows and returns.
        """
        if revision == "heads":
            known = self._known_current()
            if known is not None:
                return known
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
            _refuse_unknown(script, current, self.url)
            if revision == "heads" and current == set(script.get_heads()):
                self._remember_scripts(conn, current)
                return current
            cfg.attributes["connection"] = conn
            try:
                command.upgrade(cfg, revision)
            except (CommandError, RevisionError) as exc:
                raise CatalogueError(f"catalogue {self.url}: migration to {revision!r} failed: {exc}") from None
            current = set(MigrationContext.configure(conn).get_current_heads())
            if revision == "heads":
                self._remember_scripts(conn, current)
            return current

    def _remember_scripts(self, conn: Connection, current: set[str]) -> None:
        if "catalogue_meta" not in sa.inspect(conn).get_table_names():
            return
        value = f"{scripts_key(self.pm)}:{','.join(sorted(current))}"
        conn.execute(sa.delete(META).where(META.c.key == SCRIPTS_KEY))
        conn.execute(sa.insert(META).values(key=SCRIPTS_KEY, value=value))

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
            if conn.execute(sa.select(sa.func.count()).select_from(TILINGS)).scalar_one():
                return 0, 0
            return upsert(conn, list(records), replace=False)

    def refresh_shipped(self) -> tuple[int, int] | None:
        """Bring the shipped records up to date when the plugins or their data changed.

        Compares :func:`shipped_fingerprint` with the one stored at the last seeding; when
        they differ, inserts new shipped records and updates existing ones (spec, title,
        aliases, shipped properties), dropping a property a plugin shipped before and no longer
        ships, keeping properties that searches added and every tiling no plugin ships. Returns (added, updated), or None when nothing changed.
        """
        fingerprint = shipped_fingerprint(self.pm)
        with self._errors("reading the catalogue's metadata"), self.engine.connect() as conn:
            stored = conn.execute(sa.select(META.c.value).where(META.c.key == SEED_KEY)).scalar()
            readable = conn.execute(sa.select(META.c.value).where(META.c.key == RESULT_FAMILIES_KEY)).scalar()
        if stored == fingerprint:
            if readable is None or not readable.startswith(fingerprint + ":"):
                with self._errors("seeding"), self.engine.begin() as conn:
                    self._lock_for_writing(conn)
                    self._remember_result_families(conn, fingerprint)
            return None
        records = list(catalogue_records(self.pm))
        with self._errors("seeding"), self.engine.begin() as conn:
            self._lock_for_writing(conn)
            stored = conn.execute(sa.select(META.c.value).where(META.c.key == SEED_KEY)).scalar()
            if stored == fingerprint:  # another process refreshed it meanwhile
                return None
            names = [r.name for r in records]
            rows = []
            for batch in batches(names):
                rows += conn.execute(
                    sa.select(TILINGS.c.id, TILINGS.c.name, TILINGS.c.family, TILINGS.c.title, TILINGS.c.spec)
                    .where(TILINGS.c.name.in_(batch))
                ).all()
            existing = {e.name: e for e in load_entries(_runner(conn), rows)}
            # the property keys each family shipped last time: one that a shipped record no
            # longer carries (renamed or dropped by the plugin) goes; any other key on the old
            # row was added by a search and stays (a catalogue from before this was recorded
            # keeps every old key once)
            was_shipped = json.loads(_read_long_meta(conn, SHIPPED_KEYS_KEY) or "{}")
            shipped: dict[str, set[str]] = {}
            merged = []
            for rec in records:
                shipped.setdefault(rec.family, set()).update(rec.properties)
                old = existing.get(rec.name)
                if old is not None:
                    stale = set(was_shipped.get(old.family, ())) - set(rec.properties)
                    kept = {k: v for k, v in old.properties.items() if k not in stale}
                    rec = CatalogueRecord(
                        family=rec.family,
                        name=rec.name,
                        spec=rec.spec,
                        title=rec.title,
                        properties={**kept, **rec.properties},
                        aliases=list(rec.aliases),
                    )
                merged.append(rec)
            result = upsert(conn, merged, replace=True)
            conn.execute(sa.delete(META).where(META.c.key == SEED_KEY))
            conn.execute(sa.insert(META).values(key=SEED_KEY, value=fingerprint))
            _write_long_meta(conn, SHIPPED_KEYS_KEY, json.dumps({f: sorted(k) for f, k in sorted(shipped.items())}))
            self._remember_result_families(conn, fingerprint)
            return result

    def _remember_result_families(self, conn: Connection, fingerprint: str) -> None:
        """Record which families a result table holds, for the installation with this
        fingerprint: :func:`tilekit.catalogue.reading.open_reader` reads the others without
        SQLAlchemy, and needs to know these without building the plugins' tables."""
        value = result_families_value(fingerprint, (name for rt in self.result_tables.values() if rt.family
                                                    for name in (rt.family, *rt.aliases)))
        conn.execute(sa.delete(META).where(META.c.key == RESULT_FAMILIES_KEY))
        if value is not None:
            conn.execute(sa.insert(META).values(key=RESULT_FAMILIES_KEY, value=value))

    def upsert(self, records: Iterable[CatalogueRecord], *, replace: bool = True) -> tuple[int, int]:
        """Insert records by name (replacing existing ones if ``replace``); return (added, replaced)."""
        records = list(records)
        with self._errors("writing tilings"), self.engine.begin() as conn:
            self._lock_for_writing(conn)
            return upsert(conn, records, replace=replace)

    def delete(self, name: str) -> None:
        """Remove a tiling (by name or alias) with its properties and aliases."""
        entry = self.get(name)
        with self._errors("deleting"), self.engine.begin() as conn:
            conn.execute(sa.delete(PROPS).where(PROPS.c.tiling_id == entry.id))
            conn.execute(sa.delete(ALIASES).where(ALIASES.c.tiling_id == entry.id))
            conn.execute(sa.delete(TILINGS).where(TILINGS.c.id == entry.id))

    # ----------------------------------------------------------------- reading tilings

    def iter_query(
        self,
        family: str | None = None,
        where: Iterable[str | Filter] = (),
        text: str | None = None,
        order_by: str = "name",
        limit: int | None = None,
        offset: int = 0,
    ) -> Iterator[Entry]:
        """Tilings matching every filter, ordered and paged, streamed.

        ``family`` restricts to one family; a family whose plugin declares a result table
        (:class:`tilekit.plugins.ResultTable`) is read from that table, its filters typed by
        the table's columns. ``where`` holds filter expressions (see :func:`parse_filter`):
        ``=`` on numbers allows a relative tolerance of 1e-9; on a list property ``=`` means
        "some element equals", ``!=`` means "has the property and no element equals", ranges
        mean "some element is in range". ``text`` is a case-insensitive substring of the
        name, title, an alias or a text property. ``order_by`` is a column or property key,
        ``-key`` for descending.
        """
        where = list(where)
        rt = self.family_table(family)
        if rt is not None:
            if limit is not None and limit < 0:
                raise ParameterError(f"limit must be >= 0, got {limit}")
            for row in self.iter_result_rows(rt, where, text, order_by, limit, offset):
                yield self._row_entry(rt, row)
            return
        yield from self.iter_tilings(family, where, text, order_by, limit, offset)

    def count_matching(
        self, family: str | None = None, where: Iterable[str | Filter] = (), text: str | None = None
    ) -> int:
        """How many tilings :meth:`query` would return without a limit."""
        rt = self.family_table(family)
        if rt is not None:
            return self.count_result_rows(rt, where, text)
        return self.count_tilings(family, where, text)

    def names(self) -> list[str]:
        """Every tiling name and alias (for suggestions)."""
        with self._errors("reading names"), self.engine.connect() as conn:
            names = conn.execute(sa.select(TILINGS.c.name).limit(_MAX_NAMES)).scalars().all()
            aliases = conn.execute(sa.select(ALIASES.c.alias).limit(_MAX_NAMES)).scalars().all()
        return [*names, *aliases]

    def get(self, name: str) -> Entry:
        """The tiling called ``name`` or having it as an alias (exact, then case-insensitive),
        or, failing those, the one a plugin reads ``name`` as (``tilekit_normalise``: an
        equivalent incidence symbol, vertex type, polyomino code or D-symbol).

        Raises NotFoundError suggesting the closest names.
        """
        found = self._get(name)
        if found is not None:
            return found
        key, value = normalise("name", name, self.pm)
        if (key, value) != ("name", name):
            if key == "name":
                found = self._get(value)
            else:
                matches = self.query(where=[Filter(key, "=", value, value)], limit=2)
                if len(matches) > 1 and key not in _IDENTITY_KEYS:
                    raise ParameterError(f"{name!r} names several tilings ({matches[0].name}, {matches[1].name} ...): "
                                         f"tilekit list --where '{key}={value}' lists them")
                found = matches[0] if matches else None
            if found is not None:
                return found
        for filters in self.pm.hook.tilekit_resolve_name(name=name):
            if filters:
                hits = self.query(where=list(filters), order_by="name", limit=1)
                if hits:
                    return hits[0]
                exc = NotFoundError("tiling", name)
                exc.args = (f"no tiling in the catalogue is the one {name!r} denotes ({', '.join(filters)}); "
                            "a search may add it (tilekit searches)",)
                raise exc
        raise NotFoundError("tiling", name, self.names())

    def _get(self, name: str) -> Entry | None:
        """The tiling called ``name`` or having it as an alias, or a result-table row, or None."""
        t, a = TILINGS, ALIASES
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
                    return load_entries(_runner(conn), rows[:1])[0]
        return self._result_lookup(name)

    def tiling(self, name: str) -> Any:
        """The :class:`tilekit.Tiling` called ``name``, rebuilt by its family's ``from_spec``."""
        entry = name if isinstance(name, Entry) else self.get(name)
        fams = families(self.pm)
        family = entry.family
        rt = self.family_table(family)
        if family not in fams and rt is not None and rt.tiling_family:
            family = rt.tiling_family
        if family not in fams:
            raise NotFoundError("family", family, fams)
        try:
            return fams[family].from_spec(entry.spec)
        except TilekitError:
            raise
        except Exception as exc:
            raise PluginError(
                f"family {entry.family!r} could not rebuild {entry.name!r} from its spec: "
                f"{type(exc).__name__}: {one_line(exc)}"
            ) from exc

    # ----------------------------------------------------------------- export

    def export(
        self,
        path_or_stream: str | os.PathLike[str] | IO[str],
        format: str = "json",
        **query: Any,
    ) -> int:
        """Write every tiling (or those matching ``query`` keywords of :meth:`iter_query`)
        as a JSON array, JSON Lines or CSV, streamed in constant memory; return the count.

        Each item is ``{name, family, title, aliases, properties, spec}``; CSV has one column
        per property (lists and the spec as JSON text).
        """
        if format not in FORMATS:
            raise ParameterError(f"export format {format!r} is not one of: {', '.join(FORMATS)}")
        family = query.get("family")
        self.check_family(family)
        rt = self.family_table(family)

        def write(stream: IO[str]) -> int:
            if rt is not None and set(query) <= {"family", "where", "text", "order_by"}:
                return self.export_rows(rt, stream, format, query.get("where", ()), query.get("text"),
                                        query.get("order_by"))
            keys = self._export_keys(family) if format == "csv" else None
            return write_entries(self.iter_query(**query), stream, format, full=True, keys=keys)

        if isinstance(path_or_stream, str | os.PathLike):
            try:
                with open(path_or_stream, "w", encoding="utf-8", newline="") as fh:
                    return write(fh)
            except OSError as exc:
                raise CatalogueError(f"cannot write {os.fspath(path_or_stream)}: {exc.strerror}") from None
        return write(path_or_stream)

    def _export_keys(self, family: str | None) -> list[str]:
        """The CSV columns of an export: a result table's columns, or the property keys."""
        rt = self.family_table(family)
        if rt is not None:
            return [c.name for c in rt.table.c if c.name not in ("name", "family", "title", "spec")]
        return self.property_keys(family)


def _runner(conn: Connection) -> Run:
    """TilingReader's ``run`` on a SQLAlchemy connection (``:name`` parameters, tuples back)."""

    def run(sql: str, params: Mapping[str, Any]) -> Sequence[Any]:
        return conn.execute(sa.text(sql), dict(params)).all()

    return run


def _retry_locked(action: Callable[[], None], errors: type[Exception] | tuple[type[Exception], ...],
                  pause: float = 0.0) -> None:
    """Run ``action`` again while it fails with "database is locked", up to the busy timeout,
    sleeping ``pause`` seconds between tries (short steps, so Ctrl-C and SIGTERM are answered
    at once even while a catalogue is busy)."""
    import time

    deadline = time.monotonic() + BUSY_TIMEOUT_MS / 1000.0
    while True:
        try:
            action()
            return
        except errors as exc:
            if "locked" not in str(exc) or time.monotonic() > deadline:
                raise
            if pause:
                time.sleep(pause)


def _begin_immediate(conn: Connection) -> None:
    """BEGIN IMMEDIATE, waiting for another writer in short steps (SQLite's own busy wait of
    _STEP_MS per try, not one long wait inside its C code); gives up after the busy timeout."""
    from sqlalchemy.exc import OperationalError

    conn.exec_driver_sql(f"PRAGMA busy_timeout = {_STEP_MS}")
    try:
        def begin() -> None:
            checkpoint()  # a deferred Ctrl-C acts here: no lock is held yet
            conn.exec_driver_sql("BEGIN IMMEDIATE")

        _retry_locked(begin, OperationalError)
    finally:
        conn.exec_driver_sql(f"PRAGMA busy_timeout = {BUSY_TIMEOUT_MS}")


def _refuse_unknown_revisions(path: Path, revisions: frozenset[str], stored: str | None,
                              pm: pluggy.PluginManager) -> None:
    """Before a SQLite file is opened for writing (a pragma is a write: ``journal_mode=WAL``
    changes header bytes 18-19), every Alembic revision it records must be one of the
    installed scripts; otherwise it was made by a newer tilekit, a missing plugin or someone
    else, and is left untouched. The ``catalogue_meta`` row of the last upgrade answers
    without Alembic when the scripts have not changed since."""
    if stored == f"{scripts_key(pm)}:{','.join(sorted(revisions))}":
        return
    from alembic.script import ScriptDirectory

    probe = Catalogue(sa.create_engine("sqlite://"), pm)  # only for its Alembic configuration
    try:
        script = ScriptDirectory.from_config(probe._alembic_config())
    finally:
        probe.close()
    _refuse_unknown(script, revisions, str(path))


def _refuse_unknown(script: Any, revisions: Iterable[str], where: str) -> None:
    """CatalogueError (one line) naming the first of ``revisions`` the Alembic ``script``
    directory does not know: the database is then left untouched."""
    from alembic.script.revision import RevisionError
    from alembic.util import CommandError

    for rev in sorted(revisions):
        try:
            known = script.get_revision(rev)
        except (CommandError, RevisionError):
            known = None
        if known is None:
            raise CatalogueError(
                f"catalogue {where} is at migration {rev[:40]!r}, which this tilekit does not know (made by "
                "a newer version, a missing plugin or another program?); left untouched"
            )


def _journal_wal(cursor: Any) -> None:
    """``PRAGMA journal_mode = WAL``, retried while another process holds the file: the
    change to WAL needs an exclusive lock, and SQLite may answer "database is locked" at once
    instead of calling the busy handler (seen when first opens of a new file race)."""
    import sqlite3

    _retry_locked(lambda: cursor.execute("PRAGMA journal_mode = WAL"), sqlite3.OperationalError, pause=0.02)


def _sqlite_pragmas(dbapi_connection: Any, _record: Any) -> None:
    cursor = dbapi_connection.cursor()
    try:
        cursor.execute(f"PRAGMA busy_timeout = {BUSY_TIMEOUT_MS}")
        cursor.execute("PRAGMA foreign_keys = ON")
        _journal_wal(cursor)
        # in WAL mode, NORMAL is durable across process crashes (SIGKILL loses nothing
        # committed); only a power cut may lose the last transactions. It saves an fsync per commit.
        cursor.execute("PRAGMA synchronous = NORMAL")
    finally:
        cursor.close()


def missing_driver(sa_url: sa.URL, exc: ImportError) -> str:
    """What to install when a URL's database driver is missing: PostgreSQL through the
    ``postgresql`` extra (psycopg 3, so a ``postgresql+psycopg://`` URL), others by name."""
    module = (getattr(exc, "name", None) or str(exc)).split(".")[0]
    if sa_url.get_backend_name() == "postgresql":
        if sa_url.get_driver_name() == "psycopg":
            return (f"the PostgreSQL driver {module} is not installed; install it with: "
                    "pip install 'tilekit[postgresql]'")
        return (f"the PostgreSQL driver {module} ({sa_url.get_driver_name()}) is not installed; install the "
                "postgresql extra (pip install 'tilekit[postgresql]') and write the URL as postgresql+psycopg://...")
    return f"the database driver {module} is not installed ({sa_url.get_backend_name()} URLs need it)"


def _read_only_engine(sa_url: sa.URL, path: Path) -> Engine:
    """A SQLite engine that only reads (immutable: no lock, no -wal or -shm file is made)."""
    import sqlite3

    uri = f"{path.resolve().as_uri()}?mode=ro&immutable=1"
    return sa.create_engine(sa_url, creator=lambda: sqlite3.connect(uri, uri=True, check_same_thread=False))


def open_catalogue(
    url: str | os.PathLike[str] | None = None,
    *,
    seed: bool = True,
    pm: pluggy.PluginManager | None = None,
    migrate: bool = True,
    engine_factory: Callable[..., Engine] | None = None,
) -> Catalogue:
    """Open the catalogue at ``url`` (or ``$TILEKIT_CATALOGUE``, or the default SQLite file).

    Runs the migrations (core and plugins) to head, and, if ``seed``, loads the records the
    plugins ship when they are new or changed. ``pm`` is the plugin manager to use (default:
    the process-wide one). Raises CatalogueError (one line) if the database cannot be opened;
    an existing file that is not a database, or a SQLite database tilekit did not create, is
    never modified. A catalogue file that cannot be written is opened read-only.
    """
    resolved = resolve_url(url)
    try:
        sa_url = make_url(resolved)
    except ArgumentError:
        raise CatalogueError(
            f"catalogue URL {resolved!r} is not a database URL (e.g. sqlite:///path/catalogue.sqlite, "
            "postgresql+psycopg://user@host/db) or a file path"
        ) from None
    path = sqlite_file(sa_url)
    read_only = False
    if path is not None:
        explicit = url is not None or bool(os.environ.get(ENV_VAR, "").strip())
        found = check_sqlite_file(path, create_parent=not explicit, meta_key=SCRIPTS_KEY)
        read_only = found.read_only
        if found.revisions is not None:
            _refuse_unknown_revisions(path, found.revisions, found.meta, pm or get_plugin_manager())
    try:
        if read_only and engine_factory is None:
            engine = _read_only_engine(sa_url, path)
        else:
            engine = (engine_factory or sa.create_engine)(sa_url)
    except ImportError as exc:
        raise CatalogueError(f"cannot open catalogue {display(sa_url)}: {missing_driver(sa_url, exc)}") from None
    except (ArgumentError, SQLAlchemyError) as exc:
        raise CatalogueError(f"cannot open catalogue {display(sa_url)}: {one_line(exc)}") from None
    if sa_url.get_backend_name() == "sqlite" and not read_only:
        event.listen(engine, "connect", _sqlite_pragmas)
    catalogue = Catalogue(engine, pm, read_only=read_only)
    try:
        with engine.connect() as conn:
            conn.execute(sa.text("SELECT 1"))
        if read_only:
            current, heads = catalogue.revisions()
            if current != heads:
                raise CatalogueError(
                    f"catalogue {catalogue.url} is read-only and at migration "
                    f"{', '.join(sorted(current)) or 'none'}, not {', '.join(sorted(heads))}; "
                    "open it once where it can be written to upgrade it"
                )
        elif migrate:
            try:
                catalogue.upgrade()
            except CatalogueError:
                # on a server, another process may have migrated the same new catalogue at
                # the same moment (SQLite serialises this through BEGIN IMMEDIATE)
                current, heads = catalogue.revisions()
                if current != heads:
                    raise
        if seed and migrate and not read_only:
            catalogue.refresh_shipped()
    except SQLAlchemyError as exc:
        engine.dispose()
        raise CatalogueError(f"cannot open catalogue {display(sa_url)}: {one_line(exc)}") from None
    except BaseException:
        engine.dispose()
        raise
    return catalogue
