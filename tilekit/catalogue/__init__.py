"""The catalogue database: open (migrating and seeding), query by typed filters, record runs.

``open_catalogue()`` opens the SQLite file under the user data directory, or any SQLAlchemy
URL given as an argument or in ``TILEKIT_CATALOGUE``; it runs the Alembic migrations (core
and every plugin's branch) to head and seeds the tilings the plugins ship, again (merging,
never dropping search results) whenever the plugins or their shipped data change. Queries
are built from parsed filters (:func:`parse_filter`) with SQLAlchemy expressions only: a
user's text never reaches the database as SQL. See docs/catalogue.md.

One job per module: :mod:`~tilekit.catalogue.urls` (where a catalogue lives, file checks),
:mod:`~tilekit.catalogue.filters` (the filter grammar and its SQL),
:mod:`~tilekit.catalogue.codec` (entries, typed property rows, upsert by name),
:mod:`~tilekit.catalogue.output` (streamed JSON / JSON Lines / CSV),
:mod:`~tilekit.catalogue.runs` (runs, leased chunks, workers),
:mod:`~tilekit.catalogue.results` (plugin result tables), :mod:`~tilekit.catalogue.core`
(the Catalogue and opening).
"""

from tilekit.catalogue.codec import Entry
from tilekit.catalogue.core import (
    BUSY_TIMEOUT_MS,
    SEED_KEY,
    Catalogue,
    open_catalogue,
    shipped_fingerprint,
)
from tilekit.catalogue.filters import FILTER_FORMS, NUMBER_RTOL, Filter, auto_type, parse_filter
from tilekit.catalogue.output import FORMATS, entries_text, write_entries
from tilekit.catalogue.runs import RunInfo, lease_seconds, run_json
from tilekit.catalogue.urls import ENV_VAR, default_path, resolve_url

__all__ = [
    "BUSY_TIMEOUT_MS",
    "Catalogue",
    "ENV_VAR",
    "Entry",
    "FILTER_FORMS",
    "FORMATS",
    "Filter",
    "NUMBER_RTOL",
    "RunInfo",
    "SEED_KEY",
    "auto_type",
    "default_path",
    "entries_text",
    "lease_seconds",
    "open_catalogue",
    "parse_filter",
    "resolve_url",
    "run_json",
    "shipped_fingerprint",
    "write_entries",
]
