"""Where the shipped data lives at run time (catalogue/ and migrations/ inside the wheel), and
reading TOML data files with one-line errors (through the bounded reader, tilekit.files), and
the per-user cache folder."""

from __future__ import annotations

import os
import tempfile
from importlib import resources
from pathlib import Path
from typing import Any

from tilekit import files


def _locate(package: str, folder: str) -> Path:
    try:
        return Path(str(resources.files(package)))
    except ModuleNotFoundError:  # running from a source tree that was never installed
        return Path(__file__).resolve().parent.parent / folder


#: The environment variable naming tilekit's cache folder ("none" turns the caches off).
CACHE_ENV = "TILEKIT_CACHE_DIR"


def writable(path: Path) -> bool:
    """Whether ``path`` exists as a folder this process can write into (created if missing)."""
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError:
        return False
    return os.access(path, os.W_OK | os.X_OK)


def cache_folder(name: str) -> Path | None:
    """tilekit's per-user cache sub-folder ``name``, or None when off or nothing is writable."""
    chosen = os.environ.get(CACHE_ENV)
    if chosen is not None and chosen.strip().lower() in {"none", "off", "0", ""}:
        return None
    if chosen:
        candidates = [Path(chosen) / name]
    else:
        from platformdirs import user_cache_dir

        uid = os.getuid() if hasattr(os, "getuid") else "user"
        candidates = [Path(user_cache_dir("tilekit")) / name, Path(tempfile.gettempdir()) / f"tilekit-{uid}" / name]
    return next((path for path in candidates if writable(path)), None)


def catalogue_dir() -> Path:
    """The shipped catalogue data folder (templates, substitution systems, tile sets)."""
    return _locate("tilekit._catalogue", "catalogue")


def migrations_dir() -> Path:
    """The Alembic environment of the core tables."""
    return _locate("tilekit._migrations", "migrations")


def read_toml(path: str | Path, what: str) -> dict[str, Any]:
    """Parse a TOML data file (a shipped one or a user's): :func:`tilekit.files.read_toml`,
    so only a regular file of bounded size is read and its nesting is bounded; a ParseError
    names ``what`` and the file (and, from tomllib, the line) when it cannot be read or is
    not TOML."""
    return files.read_toml(path, what)
