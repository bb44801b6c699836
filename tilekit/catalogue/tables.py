"""The core tables as SQLAlchemy Core handles (the catalogue's modules build statements on these)."""

from __future__ import annotations

from tilekit.models import (
    AliasRow,
    MetaRow,
    PropertyRow,
    RunChunkRow,
    RunResultRow,
    RunRow,
    RunWorkerRow,
    TilingRow,
)

TILINGS = TilingRow.__table__
ALIASES = AliasRow.__table__
PROPS = PropertyRow.__table__
META = MetaRow.__table__
RUNS = RunRow.__table__
CHUNKS = RunChunkRow.__table__
RESULTS = RunResultRow.__table__
WORKERS = RunWorkerRow.__table__

#: Batch size for ``IN (...)`` lists and bulk inserts.
BATCH = 500
