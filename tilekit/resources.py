"""Where the shipped data lives at run time: catalogue/ and migrations/ inside the wheel."""

from __future__ import annotations

from importlib import resources
from pathlib import Path


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
