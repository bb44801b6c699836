"""The catalogue database's tables as SQLAlchemy Core ``Table`` objects (see docs/catalogue.md).

``tilings`` holds one row per known tiling with the properties every family shares as
indexed columns; ``tiling_properties`` holds every property of a record as typed key/value
rows (one row per list element), so plugins add properties without a migration;
``runs`` / ``run_chunks`` / ``run_workers`` / ``run_results`` record search runs, their unit
of resume, their workers and their results. The Alembic migrations in migrations/versions/
create exactly these tables (a test compares them).

Core tables and no ORM: the catalogue builds every statement itself, and importing
``sqlalchemy.orm`` would cost every CLI call a fifth of a second for nothing.
"""

from __future__ import annotations

from datetime import UTC, datetime

from sqlalchemy import (
    JSON,
    Boolean,
    Column,
    DateTime,
    Float,
    ForeignKey,
    Index,
    Integer,
    MetaData,
    String,
    Table,
    Text,
    UniqueConstraint,
)
from sqlalchemy.types import TypeDecorator

from tilekit.catalogue.entry import SHARED_COLUMNS, TEXT_COLUMNS  # noqa: F401 - re-exported


class JSONType(TypeDecorator):
    """JSON everywhere, JSONB on PostgreSQL. A decorator rather than ``with_variant(JSONB())``
    so that the PostgreSQL dialect's module (21 ms of every command's start-up) is imported
    only when a PostgreSQL connection compiles the type."""

    impl = JSON
    cache_ok = True

    def load_dialect_impl(self, dialect):  # noqa: ANN001, ANN201 - SQLAlchemy's signature
        if dialect.name == "postgresql":
            # measured start-up cost: the dialect module, needed only on PostgreSQL
            from sqlalchemy.dialects.postgresql import JSONB

            return dialect.type_descriptor(JSONB())
        return dialect.type_descriptor(JSON())


def is_json(type_: object) -> bool:
    """Whether a column type holds JSON (a plain JSON or a :class:`JSONType`)."""
    return isinstance(type_, JSON) or isinstance(getattr(type_, "impl", None), JSON)

#: A run is queued, then running (while some worker's lease is alive), then done, failed (a
#: chunk raised), interrupted (stopped, or every worker died) or cancelled (by the user).
RUN_STATUSES: tuple[str, ...] = ("queued", "running", "done", "failed", "interrupted", "cancelled")
#: A chunk is pending, leased by one worker (until its lease expires), then done.
CHUNK_STATUSES: tuple[str, ...] = ("pending", "leased", "done")


def utcnow() -> datetime:
    """The current time, timezone-aware UTC (stored as UTC)."""
    return datetime.now(UTC)


#: Deterministic constraint and index names, so migrations can name what they create.
NAMING_CONVENTION = {
    "ix": "ix_%(column_0_label)s",
    "uq": "uq_%(table_name)s_%(column_0_N_name)s",
    "fk": "fk_%(table_name)s_%(column_0_name)s_%(referred_table_name)s",
    "pk": "pk_%(table_name)s",
}


#: The metadata of the core tables (Alembic's target, and what the test compares).
METADATA = MetaData(naming_convention=NAMING_CONVENTION)


def _id() -> Column:
    return Column("id", Integer, primary_key=True)


def _stamp(name: str, nullable: bool = True, **kw) -> Column:
    return Column(name, DateTime(timezone=True), nullable=nullable, **kw)


#: One known tiling: family, unique name, JSON spec and the shared indexed properties.
TILINGS = Table(
    "tilings", METADATA,
    _id(),
    Column("family", String(64), nullable=False, index=True),
    Column("name", String(200), nullable=False, unique=True),
    Column("title", String(400), nullable=False, default=""),
    Column("spec", JSONType, nullable=False),
    Column("periodic", Boolean, index=True),
    Column("k_hedral", Integer, index=True),
    Column("k_isohedral", Integer, index=True),
    Column("edge_to_edge", Boolean, index=True),
    Column("symmetry_group", String(16), index=True),
    _stamp("created_at", False, default=utcnow),
    _stamp("updated_at", False, default=utcnow, onupdate=utcnow),
)

#: Another spelling of a tiling's name (``4.4.4.4`` for ``4^4``).
ALIASES = Table(
    "tiling_aliases", METADATA,
    _id(),
    Column("alias", String(200), nullable=False, unique=True),
    Column("tiling_id", Integer, ForeignKey("tilings.id", ondelete="CASCADE"), nullable=False, index=True),
)

#: One typed property value of a tiling; a list property has one row per element.
#: ``kind`` is how the value is restored: ``str``, ``int``, ``float``, ``bool``, ``null``,
#: ``empty`` (an empty list) or ``json`` (a nested list or object kept whole as JSON text,
#: in ``value_text``). ``position`` is the element's index for list properties and NULL for
#: scalars. Numbers are in ``value_num``, booleans in ``value_bool``, text in ``value_text``.
PROPS = Table(
    "tiling_properties", METADATA,
    _id(),
    Column("tiling_id", Integer, ForeignKey("tilings.id", ondelete="CASCADE"), nullable=False, index=True),
    Column("key", String(64), nullable=False),
    Column("position", Integer),
    Column("kind", String(8), nullable=False),
    Column("value_text", Text),
    Column("value_num", Float),
    Column("value_bool", Boolean),
    # covering indexes: a filter's "tiling_id IN (SELECT ...)" never touches the table
    Index("ix_tiling_properties_key_text", "key", "value_text", "tiling_id"),
    Index("ix_tiling_properties_key_num", "key", "value_num", "tiling_id"),
)

#: A search run: which search, its validated parameters, status, progress and timing.
RUNS = Table(
    "runs", METADATA,
    _id(),
    Column("kind", String(100), nullable=False, index=True),
    Column("params", JSONType, nullable=False),
    Column("status", String(16), nullable=False, default="queued", index=True),
    Column("chunks_total", Integer, nullable=False, default=0),
    Column("chunks_done", Integer, nullable=False, default=0),
    _stamp("created_at", False, default=utcnow),
    _stamp("started_at"),
    _stamp("finished_at"),
    Column("seconds", Float, nullable=False, default=0.0),
    Column("summary", JSONType),
    Column("error", Text),
)

#: One chunk of a run: the unit of parallel work, of leases and of resume. A worker claims
#: a pending chunk (or one whose lease expired) by setting ``lease_owner`` and
#: ``lease_expires`` (seconds since the epoch); its heartbeat pushes the expiry on while it
#: computes; recording the chunk sets it done. ``seconds`` is the worker time it took,
#: ``rows`` how many result rows it wrote, ``counts`` the tallies it reported.
CHUNKS = Table(
    "run_chunks", METADATA,
    _id(),
    Column("run_id", Integer, ForeignKey("runs.id", ondelete="CASCADE"), nullable=False, index=True),
    Column("index", Integer, nullable=False),
    Column("spec", JSONType, nullable=False),
    Column("status", String(16), nullable=False, default="pending"),
    Column("seconds", Float),
    _stamp("finished_at"),
    Column("lease_owner", String(200)),
    Column("lease_expires", Float),
    Column("attempts", Integer, nullable=False, default=0),
    Column("rows", Integer),
    Column("counts", JSONType),
    UniqueConstraint("run_id", "index"),
    Index("ix_run_chunks_run_status", "run_id", "status", "index"),
)

#: One worker of a run (a process running the claim-compute-record loop). ``owner`` is
#: ``host/pid/token``; ``heartbeat`` (epoch seconds) is refreshed while it lives; ``stop``
#: asks it to stop after its current chunk; ``finished`` is set when it ends. A run is
#: running exactly while one of its workers has a fresh heartbeat.
WORKERS = Table(
    "run_workers", METADATA,
    _id(),
    Column("run_id", Integer, ForeignKey("runs.id", ondelete="CASCADE"), nullable=False, index=True),
    Column("owner", String(200), nullable=False, unique=True),
    Column("session", String(200), nullable=False, index=True),
    Column("host", String(200), nullable=False),
    Column("pid", Integer, nullable=False),
    Column("started", Float, nullable=False),
    Column("heartbeat", Float, nullable=False),
    Column("finished", Float),
    Column("stop", Boolean, nullable=False, default=False),
    Column("chunks_done", Integer, nullable=False, default=0),
)

#: One JSON result a chunk yielded.
RESULTS = Table(
    "run_results", METADATA,
    _id(),
    Column("run_id", Integer, ForeignKey("runs.id", ondelete="CASCADE"), nullable=False),
    Column("chunk_index", Integer, nullable=False),
    Column("data", JSONType, nullable=False),
    Index("ix_run_results_run_chunk", "run_id", "chunk_index"),
)

#: Key/value facts about the catalogue itself (e.g. the fingerprint of the shipped data).
META = Table(
    "catalogue_meta", METADATA,
    Column("key", String(100), primary_key=True),
    Column("value", String(400), nullable=False),
)
