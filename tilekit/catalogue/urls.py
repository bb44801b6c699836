"""Where a catalogue lives: URL resolution, the default file, and the checks made on a SQLite
file before anything touches it (not a regular file, not a database, a directory, a foreign
database)."""

from __future__ import annotations

import os
import sqlite3
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from tilekit.errors import CatalogueError

if TYPE_CHECKING:  # the read path without SQLAlchemy (catalogue.reading) resolves URLs here
    import sqlalchemy as sa

#: Environment variable naming the catalogue URL (or a file path).
ENV_VAR = "TILEKIT_CATALOGUE"

_SQLITE_MAGIC = b"SQLite format 3\x00"



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


def display(url: sa.URL) -> str:
    """The URL as it may be printed (password hidden)."""
    return url.render_as_string(hide_password=True)


def sqlite_file(url: sa.URL) -> Path | None:
    """The file of a SQLite URL, or None (another database, or in memory)."""
    if url.get_backend_name() != "sqlite":
        return None
    db = url.database
    if not db or db == ":memory:" or db.startswith("file:"):
        return None
    return Path(db)


@dataclass(frozen=True)
class SqliteFile:
    """What :func:`check_sqlite_file` found: whether the file can be written, the Alembic
    revisions it records (None for a new or empty file) and the ``catalogue_meta`` value
    asked for (None when absent)."""

    read_only: bool = False
    revisions: frozenset[str] | None = None
    meta: str | None = None


def check_sqlite_file(path: Path, *, create_parent: bool, meta_key: str = "") -> SqliteFile:
    """Refuse a path that is not (and cannot become) a tilekit SQLite catalogue, touching
    nothing: not a regular file (a FIFO would block the open), not SQLite, or SQLite with
    tables but no ``alembic_version``. A file that cannot be written (read-only file or file
    system) is opened read-only. The revisions it records are checked against the installed
    scripts by the caller (:func:`tilekit.catalogue.core.open_catalogue`) before the file
    is opened for writing; ``meta_key`` names a ``catalogue_meta`` row read with them."""
    try:
        info = os.stat(path)
    except FileNotFoundError:
        info = None
    except (OSError, ValueError) as exc:
        raise CatalogueError(f"cannot read catalogue file {path}: {getattr(exc, 'strerror', None) or exc}") from None
    if info is not None:
        if stat.S_ISDIR(info.st_mode):
            raise CatalogueError(f"catalogue path {path} is a directory; give a file path")
        if not stat.S_ISREG(info.st_mode):
            kind = "a FIFO (named pipe)" if stat.S_ISFIFO(info.st_mode) else "not a regular file"
            raise CatalogueError(f"catalogue path {path} is {kind}; give a SQLite file (left untouched)")
        head = _head(path)
        if head and head[:16] != _SQLITE_MAGIC:
            raise CatalogueError(
                f"{path} is not a SQLite database (left untouched); point --catalogue / "
                f"{ENV_VAR} at a new or existing catalogue file"
            )
        revisions, meta = _refuse_foreign(path, head[18:20] == b"\x02\x02", meta_key) if head else (None, None)
        read_only = not os.access(path, os.W_OK) or not os.access(path.parent, os.W_OK)
        return SqliteFile(read_only, revisions, meta)
    if not path.parent.exists():
        if create_parent:
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise CatalogueError(f"cannot create directory {path.parent}: {exc.strerror}") from None
        else:
            raise CatalogueError(f"cannot create catalogue {path}: directory {path.parent} does not exist")
    return SqliteFile()


def _head(path: Path) -> bytes:
    """The first 100 bytes of a regular file (the SQLite header), read without blocking."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
        try:
            return os.read(fd, 100)
        finally:
            os.close(fd)
    except OSError as exc:
        raise CatalogueError(f"cannot read catalogue file {path}: {exc.strerror}") from None


def _refuse_foreign(path: Path, wal: bool, meta_key: str) -> tuple[frozenset[str] | None, str | None]:
    """A SQLite file with tables but no ``alembic_version`` (every tilekit catalogue has one,
    made in the transaction that made its tables) is someone else's database: refuse it
    before anything is written, not even a pragma. Returns the Alembic revisions it records
    (None when it has no tables yet) and the ``catalogue_meta`` value of ``meta_key``.

    Read through a read-only connection that writes nothing: ``immutable`` (no lock taken,
    no ``-wal`` or ``-shm`` file made) unless the file is in WAL mode (header bytes 18-19 =
    2) and has a ``-wal`` file beside it, whose committed pages an immutable reader would
    miss; a plain read-only connection then reads them through the files already there."""
    live_wal = wal and Path(f"{path}-wal").exists()
    query = "?mode=ro" if live_wal else "?mode=ro&immutable=1"
    try:
        conn = sqlite3.connect(f"{path.resolve().as_uri()}{query}", uri=True)
        try:
            names = {row[0] for row in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")}
            revisions = (frozenset(str(r[0]) for r in conn.execute("SELECT version_num FROM alembic_version"))
                         if "alembic_version" in names else None)
            meta = None
            if meta_key and "catalogue_meta" in names:
                row = conn.execute("SELECT value FROM catalogue_meta WHERE key = ?", (meta_key,)).fetchone()
                meta = None if row is None else str(row[0])
        finally:
            conn.close()
    except sqlite3.Error as exc:
        raise CatalogueError(f"cannot read catalogue file {path}: {exc}") from None
    if names and revisions is None:
        shown = ", ".join(sorted(names)[:5]) + (", ..." if len(names) > 5 else "")
        raise CatalogueError(
            f"{path} is a SQLite database that tilekit did not create (tables: {shown}); left "
            f"untouched: point --catalogue / {ENV_VAR} at a new file or an existing catalogue"
        )
    return revisions, meta


def one_line(exc: BaseException) -> str:
    """An exception (or the DB-API error behind a SQLAlchemy one) as one line."""
    orig = getattr(exc, "orig", None) or exc
    text = " ".join(str(orig).split())
    return text or type(orig).__name__
