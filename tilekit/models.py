"""SQLAlchemy 2.0 declarative models of the catalogue database (see docs/catalogue.md).

``tilings`` holds one row per known tiling with the properties every family shares as
indexed columns; ``tiling_properties`` holds every property of a record as typed key/value
rows (one row per list element), so plugins add properties without a migration;
``runs`` / ``run_chunks`` / ``run_results`` record search runs, their unit of resume and
their results. The Alembic migrations in migrations/versions/ create exactly these tables.
"""

from __future__ import annotations

from datetime import UTC, datetime
from typing import Any

from sqlalchemy import (
    JSON,
    Boolean,
    DateTime,
    Float,
    ForeignKey,
    Index,
    Integer,
    MetaData,
    String,
    Text,
    UniqueConstraint,
)
from sqlalchemy.dialects.postgresql import JSONB
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column, relationship

#: JSON everywhere, JSONB on PostgreSQL.
JSONType = JSON().with_variant(JSONB(), "postgresql")

#: The properties mirrored in indexed columns of ``tilings`` and their Python types.
SHARED_COLUMNS: dict[str, type] = {
    "periodic": bool,
    "k_hedral": int,
    "k_isohedral": int,
    "edge_to_edge": bool,
    "symmetry_group": str,
}

#: Columns of ``tilings`` a filter or ``order_by`` may name directly (besides SHARED_COLUMNS).
TEXT_COLUMNS: tuple[str, ...] = ("name", "family", "title")

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


class Base(DeclarativeBase):
    """Declarative base of the core tables."""

    metadata = MetaData(naming_convention=NAMING_CONVENTION)


class TilingRow(Base):
    """One known tiling: family, unique name, JSON spec and the shared indexed properties."""

    __tablename__ = "tilings"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    family: Mapped[str] = mapped_column(String(64), index=True)
    name: Mapped[str] = mapped_column(String(200), unique=True)
    title: Mapped[str] = mapped_column(String(400), default="")
    spec: Mapped[dict[str, Any]] = mapped_column(JSONType)
    periodic: Mapped[bool | None] = mapped_column(Boolean, index=True)
    k_hedral: Mapped[int | None] = mapped_column(Integer, index=True)
    k_isohedral: Mapped[int | None] = mapped_column(Integer, index=True)
    edge_to_edge: Mapped[bool | None] = mapped_column(Boolean, index=True)
    symmetry_group: Mapped[str | None] = mapped_column(String(16), index=True)
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True), default=utcnow)
    updated_at: Mapped[datetime] = mapped_column(
        DateTime(timezone=True), default=utcnow, onupdate=utcnow
    )

    aliases: Mapped[list[AliasRow]] = relationship(
        back_populates="tiling", cascade="all, delete-orphan", passive_deletes=True
    )
    properties: Mapped[list[PropertyRow]] = relationship(
        back_populates="tiling", cascade="all, delete-orphan", passive_deletes=True
    )


class AliasRow(Base):
    """Another spelling of a tiling's name (``4.4.4.4`` for ``4^4``)."""

    __tablename__ = "tiling_aliases"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    alias: Mapped[str] = mapped_column(String(200), unique=True)
    tiling_id: Mapped[int] = mapped_column(
        ForeignKey("tilings.id", ondelete="CASCADE"), index=True
    )

    tiling: Mapped[TilingRow] = relationship(back_populates="aliases")


class PropertyRow(Base):
    """One typed property value of a tiling; a list property has one row per element.

    ``kind`` is how the value is restored: ``str``, ``int``, ``float``, ``bool``, ``null``,
    ``empty`` (an empty list) or ``json`` (a nested list or object kept whole as JSON text,
    in ``value_text``). ``position`` is the element's index for list properties
    and NULL for scalars. Numbers are in ``value_num``, booleans in ``value_bool``, text in
    ``value_text``.
    """

    __tablename__ = "tiling_properties"
    __table_args__ = (
        # covering indexes: a filter's "tiling_id IN (SELECT ...)" never touches the table
        Index("ix_tiling_properties_key_text", "key", "value_text", "tiling_id"),
        Index("ix_tiling_properties_key_num", "key", "value_num", "tiling_id"),
    )

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    tiling_id: Mapped[int] = mapped_column(
        ForeignKey("tilings.id", ondelete="CASCADE"), index=True
    )
    key: Mapped[str] = mapped_column(String(64))
    position: Mapped[int | None] = mapped_column(Integer)
    kind: Mapped[str] = mapped_column(String(8))
    value_text: Mapped[str | None] = mapped_column(Text)
    value_num: Mapped[float | None] = mapped_column(Float)
    value_bool: Mapped[bool | None] = mapped_column(Boolean)

    tiling: Mapped[TilingRow] = relationship(back_populates="properties")


class RunRow(Base):
    """A search run: which search, its validated parameters, status, progress and timing."""

    __tablename__ = "runs"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    kind: Mapped[str] = mapped_column(String(100), index=True)
    params: Mapped[dict[str, Any]] = mapped_column(JSONType)
    status: Mapped[str] = mapped_column(String(16), default="queued", index=True)
    chunks_total: Mapped[int] = mapped_column(Integer, default=0)
    chunks_done: Mapped[int] = mapped_column(Integer, default=0)
    created_at: Mapped[datetime] = mapped_column(DateTime(timezone=True), default=utcnow)
    started_at: Mapped[datetime | None] = mapped_column(DateTime(timezone=True))
    finished_at: Mapped[datetime | None] = mapped_column(DateTime(timezone=True))
    seconds: Mapped[float] = mapped_column(Float, default=0.0)
    summary: Mapped[dict[str, Any] | None] = mapped_column(JSONType)
    error: Mapped[str | None] = mapped_column(Text)


class RunChunkRow(Base):
    """One chunk of a run: the unit of parallel work, of leases and of resume.

    A worker claims a pending chunk (or one whose lease expired) by setting ``lease_owner``
    and ``lease_expires`` (seconds since the epoch); its heartbeat pushes the expiry on while
    it computes; recording the chunk sets it done. ``seconds`` is the worker time it took,
    ``rows`` how many result rows it wrote, ``counts`` the tallies it reported.
    """

    __tablename__ = "run_chunks"
    __table_args__ = (
        UniqueConstraint("run_id", "index"),
        Index("ix_run_chunks_run_status", "run_id", "status", "index"),
    )

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    run_id: Mapped[int] = mapped_column(ForeignKey("runs.id", ondelete="CASCADE"), index=True)
    index: Mapped[int] = mapped_column(Integer)
    spec: Mapped[dict[str, Any]] = mapped_column(JSONType)
    status: Mapped[str] = mapped_column(String(16), default="pending")
    seconds: Mapped[float | None] = mapped_column(Float)
    finished_at: Mapped[datetime | None] = mapped_column(DateTime(timezone=True))
    lease_owner: Mapped[str | None] = mapped_column(String(200))
    lease_expires: Mapped[float | None] = mapped_column(Float)
    attempts: Mapped[int] = mapped_column(Integer, default=0)
    rows: Mapped[int | None] = mapped_column(Integer)
    counts: Mapped[dict[str, Any] | None] = mapped_column(JSONType)


class RunWorkerRow(Base):
    """One worker of a run (a process running the claim-compute-record loop).

    ``owner`` is ``host/pid/token``; ``heartbeat`` (epoch seconds) is refreshed while it
    lives; ``stop`` asks it to stop after its current chunk; ``finished`` is set when it ends.
    A run is running exactly while one of its workers has a fresh heartbeat.
    """

    __tablename__ = "run_workers"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    run_id: Mapped[int] = mapped_column(ForeignKey("runs.id", ondelete="CASCADE"), index=True)
    owner: Mapped[str] = mapped_column(String(200), unique=True)
    session: Mapped[str] = mapped_column(String(200), index=True)
    host: Mapped[str] = mapped_column(String(200))
    pid: Mapped[int] = mapped_column(Integer)
    started: Mapped[float] = mapped_column(Float)
    heartbeat: Mapped[float] = mapped_column(Float)
    finished: Mapped[float | None] = mapped_column(Float)
    stop: Mapped[bool] = mapped_column(Boolean, default=False)
    chunks_done: Mapped[int] = mapped_column(Integer, default=0)


class RunResultRow(Base):
    """One JSON result a chunk yielded."""

    __tablename__ = "run_results"
    __table_args__ = (Index("ix_run_results_run_chunk", "run_id", "chunk_index"),)

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    run_id: Mapped[int] = mapped_column(ForeignKey("runs.id", ondelete="CASCADE"))
    chunk_index: Mapped[int] = mapped_column(Integer)
    data: Mapped[dict[str, Any]] = mapped_column(JSONType)


class MetaRow(Base):
    """Key/value facts about the catalogue itself (e.g. the fingerprint of the shipped data)."""

    __tablename__ = "catalogue_meta"

    key: Mapped[str] = mapped_column(String(100), primary_key=True)
    value: Mapped[str] = mapped_column(String(400))
