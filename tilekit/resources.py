"""Where the shipped data lives at run time (catalogue/ and migrations/ inside the wheel), and
reading its TOML files with one-line errors."""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from tilekit.errors import ParseError


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
    """Parse a TOML data file; a ParseError names ``what`` and the file (and, from tomllib,
    the line) when it cannot be read or is not TOML."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise ParseError(f"{what} {str(p)!r} cannot be read: {exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        raise ParseError(f"{what} {p.name}: not UTF-8 text (byte {exc.start}); save it as UTF-8") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParseError(f"{what} {p.name}: not valid TOML ({exc})") from None
