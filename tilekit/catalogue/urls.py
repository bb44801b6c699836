"""Where a catalogue lives: URL resolution, the default file, and the checks made on a SQLite
file before anything touches it (not a database, a directory, a foreign database)."""

from __future__ import annotations

import os
import sqlite3
from pathlib import Path
from typing import TYPE_CHECKING

from tilekit.errors import CatalogueError

if TYPE_CHECKING:  # the read path without SQLAlchemy (catalogue.reading) resolves URLs here
    import sqlalchemy as sa

#: Environment variable naming the catalogue URL (or a file path).
ENV_VAR = "TILEKIT_CATALOGUE"

_SQLITE_MAGIC = b"SQLite format 3\x00"

#: Tables whose presence marks a SQLite file as a tilekit catalogue (or an empty file).
_OWN_TABLES = frozenset({"alembic_version", "tilings"})


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


def check_sqlite_file(path: Path, *, create_parent: bool) -> bool:
    """Refuse a path that is not (and cannot become) a tilekit SQLite catalogue, touching
    nothing. Returns True when the file exists but cannot be written (read-only file or
    file system): the catalogue is then opened read-only."""
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
        if head:
            _refuse_foreign(path)
        return not os.access(path, os.W_OK) or not os.access(path.parent, os.W_OK)
    if not path.parent.exists():
        if create_parent:
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise CatalogueError(f"cannot create directory {path.parent}: {exc.strerror}") from None
        else:
            raise CatalogueError(f"cannot create catalogue {path}: directory {path.parent} does not exist")
    return False


def _refuse_foreign(path: Path) -> None:
    """A SQLite file with tables but none of tilekit's is someone else's database: refuse it
    before tilekit adds its tables or switches the journal mode (read through a read-only,
    immutable URI connection, so not even a lock is taken)."""
    try:
        conn = sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro&immutable=1", uri=True)
        try:
            names = {row[0] for row in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")}
        finally:
            conn.close()
    except sqlite3.Error as exc:
        raise CatalogueError(f"cannot read catalogue file {path}: {exc}") from None
    if names and not names & _OWN_TABLES:
        shown = ", ".join(sorted(names)[:5]) + (", ..." if len(names) > 5 else "")
        raise CatalogueError(
            f"{path} is a SQLite database that tilekit did not create (tables: {shown}); left "
            f"untouched: point --catalogue / {ENV_VAR} at a new file or an existing catalogue"
        )


def one_line(exc: BaseException) -> str:
    """An exception (or the DB-API error behind a SQLAlchemy one) as one line."""
    orig = getattr(exc, "orig", None) or exc
    text = " ".join(str(orig).split())
    return text or type(orig).__name__
