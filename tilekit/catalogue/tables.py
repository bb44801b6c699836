"""The core tables as SQLAlchemy Core handles (the catalogue's modules build statements on these)."""

from __future__ import annotations

from tilekit.models import ALIASES, CHUNKS, META, PROPS, RESULTS, RUNS, TILINGS, WORKERS

__all__ = ["ALIASES", "BATCH", "CHUNKS", "META", "PROPS", "RESULTS", "RUNS", "TILINGS", "WORKERS"]

#: Batch size for ``IN (...)`` lists and bulk inserts.
BATCH = 500
