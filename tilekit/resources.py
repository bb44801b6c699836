"""Where the shipped data lives at run time (catalogue/ and migrations/ inside the wheel), and
reading TOML data files with one-line errors (through the bounded reader, tilekit.files)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path
from typing import Any

from tilekit import files


def _locate(package: str, folder: str) -> Path:
    try:
        return Path(str(resources.files(package)))
    except ModuleNotFoundError:  # running from a source tree that was never installed
        return Path(__file__).resolve().parent.parent / folder


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
