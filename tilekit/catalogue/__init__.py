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

from tilekit.lazy import lazy_exports

# Lazy (PEP 562): the read path without SQLAlchemy (tilekit.catalogue.reading) is a module of
# this package, and importing the package must not import SQLAlchemy for it.
_EXPORTS = {
    **dict.fromkeys(["Entry"], "tilekit.catalogue.entry"),
    **dict.fromkeys(["BUSY_TIMEOUT_MS", "Catalogue", "open_catalogue"], "tilekit.catalogue.core"),
    **dict.fromkeys(["SEED_KEY", "open_reader", "shipped_fingerprint"], "tilekit.catalogue.reading"),
    **dict.fromkeys(["FILTER_FORMS", "NUMBER_RTOL", "Filter", "auto_type", "parse_filter"],
                    "tilekit.catalogue.filters"),
    **dict.fromkeys(["FORMATS", "entries_text", "write_entries"], "tilekit.catalogue.output"),
    **dict.fromkeys(["RunInfo", "lease_seconds", "run_json"], "tilekit.catalogue.runs"),
    **dict.fromkeys(["ENV_VAR", "default_path", "resolve_url"], "tilekit.catalogue.urls"),
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

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
    "open_reader",
    "entries_text",
    "lease_seconds",
    "open_catalogue",
    "parse_filter",
    "resolve_url",
    "run_json",
    "shipped_fingerprint",
    "write_entries",
]
