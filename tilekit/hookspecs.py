"""The hook specifications every tilekit plugin (built-in family or pip package) implements.

A plugin is a module or object with functions decorated by ``tilekit.hookimpl`` whose names
match the specs below. Built-in families live in tilekit/plugins/ and are registered from
``DEFAULT_PLUGINS``; third-party ones are found through the ``tilekit`` entry-point group.
"""

from __future__ import annotations

import pluggy

hookspec = pluggy.HookspecMarker("tilekit")
hookimpl = pluggy.HookimplMarker("tilekit")


@hookspec
def tilekit_families():
    """Return a list of :class:`tilekit.plugins.Family` this plugin contributes.

    Called by :func:`tilekit.plugins.families` every time families are looked up (the CLI's
    ``families``, ``list``, ``show`` and ``render``; checking a catalogue's records), so it
    must be cheap and give the same answer each time. Family names must be unique across
    all plugins; a clash is a :class:`tilekit.errors.PluginError`.
    """


@hookspec
def tilekit_catalogue_records():
    """Return an iterable of :class:`tilekit.plugins.CatalogueRecord` this plugin ships.

    Called by :func:`tilekit.plugins.catalogue_records` when a catalogue is opened empty, is
    re-seeded (``tilekit catalogue seed``), or is opened after the fingerprint of the
    installed plugins and shipped data changed, to load the known tilings of the plugin's
    families. Records carry a JSON ``spec`` that the family's
    ``from_spec`` turns back into a :class:`tilekit.Tiling`.
    """


@hookspec
def tilekit_searches():
    """Return a list of :class:`tilekit.plugins.Search` (enumeration / search jobs).

    Called by :func:`tilekit.plugins.searches` whenever searches are looked up (``tilekit
    search``, ``tilekit runs``, resuming a run). Each search names its parameters, splits a
    run into chunks and computes the results of one chunk; tilekit.search stores them,
    resumes interrupted runs and runs chunks in parallel.
    """


@hookspec
def tilekit_samplers():
    """Return a list of :class:`tilekit.plugins.Sampler` (tile-based importance sampling, §7.4).

    Called by :func:`tilekit.plugins.samplers` whenever samplers are looked up (``tilekit
    sample``, :func:`tilekit.sampling.sample`); must be cheap (import the sampling code in the
    sampler's ``candidates`` function, not here).
    """


@hookspec
def tilekit_result_tables():
    """Return a list of :class:`tilekit.plugins.ResultTable` this plugin's searches write.

    Called when a catalogue is opened and when a chunk's rows are recorded. Each table must
    be created by the plugin's own Alembic branch (:func:`tilekit_migration_locations`).
    """


@hookspec
def tilekit_cli_commands(cli):
    """Add click commands or groups to the ``tilekit`` command group ``cli``.

    Called once per plugin manager, the first time the ``tilekit`` command lists or looks
    up a command (``tilekit --help`` included); return value ignored.
    """


@hookspec
def tilekit_migration_locations():
    """Return a list of directories holding Alembic version scripts for a plugin's own tables.

    Called by :func:`tilekit.plugins.migration_locations` each time a catalogue is opened
    (before its migrations run). Each directory is added to Alembic's ``version_locations``; give its revisions their own
    ``branch_labels`` so they upgrade independently of the core tables.
    """


@hookspec(firstresult=True)
def tilekit_claim_file(path):
    """Return the name of the family that reads the data file ``path`` (a ``str``), or None.

    Called by :func:`tilekit.plugins.family_for_file` when ``tilekit render --system FILE``
    is given no ``--family``; decide by the file's suffix (or a cheap look inside). The
    first non-None answer wins; plugins registered later are asked first (pluggy's order).
    """


@hookspec
def tilekit_extra_properties(record):
    """Return a dict of properties to add to ``record`` (a :class:`tilekit.plugins.CatalogueRecord`
    of any family, usually another plugin's), or None.

    Called by :func:`tilekit.plugins.catalogue_records` once per record, after every plugin's
    ``tilekit_catalogue_records`` has been collected (so whenever records are built: seeding,
    re-seeding, a changed fingerprint). A key the record already has is kept; among plugins, the first
    answer for a key wins. Values follow the rules of ``CatalogueRecord.properties``.
    """


@hookspec(firstresult=True)
def tilekit_normalise(key, value):
    """Return ``(key, value)``, the stored form of a text value someone typed, or None.

    Called by :func:`tilekit.plugins.normalise` for each ``KEY=VALUE`` / ``KEY!=VALUE`` filter
    with a text value (``key`` under its shared name, see tilekit.catalogue.vocabulary) and,
    with ``key="name"``, for a name :meth:`tilekit.catalogue.Catalogue.get` (``tilekit show``,
    ``render``) did not find as written. A plugin that reads the value returns what to look for
    instead: an equivalent incidence symbol as its ``canonical_symbol``, a vertex type in its
    canonical rotation (``4.3.4.6`` -> ``3.4.6.4``), a polyomino code in its canonical
    orientation, a D-symbol canonically numbered. Return None at once for keys the plugin does
    not know (import its parsers only then); raise a TilekitError only for a value that is its
    own and ambiguous. The first non-None answer wins.
    """


@hookspec
def tilekit_resolve_name(name):
    """Return ``--where`` filters (``KEY=VALUE`` strings) that find the tiling ``name`` denotes
    in a notation the plugin reads (e.g. a GomJau-Hogg string or a D-symbol), or None.

    Called by :meth:`tilekit.catalogue.Catalogue.get` (``tilekit show``, ``render``) only
    when no tiling, alias or result row is called ``name``; the first answer whose filters
    match a tiling wins. Raise a :class:`tilekit.errors.TilekitError` for text that is the
    plugin's notation but malformed, naming what is wrong.
    """


@hookspec
def tilekit_public_names():
    """Return a dict of names a family adds to the ``tilekit`` package, name -> object
    (``{"polyomino": polyomino}`` makes ``tilekit.polyomino(...)``), or None.

    Called by :func:`tilekit.plugins.public_name` when code asks ``tilekit`` for a name its
    own module does not define; two plugins offering one name are a PluginError. Offer cheap objects: import heavy modules inside the function you return.
    """


# --------------------------------------------------------------------------- the web app (tilekit serve)
# In the manner of Datasette's register_routes, menu_links, table_actions and render_cell: a
# family's editors and pages arrive with the plugin, and tilekit/web names no family. ``web`` is
# the app's state (tilekit.web.app.State): ``web.catalogue``, ``web.renderer`` (build and render
# a catalogue tiling within the app's tile limit), ``web.writable``, ``web.page(title, body,
# scripts=...)`` (a page in the site's layout) and ``web.render_options(request, own=())`` (the
# render API's query syntax, parsed; the keys in ``own`` are the view's own, left out). Import
# starlette and your page code inside the hook.


@hookspec
def tilekit_web_routes(web):
    """Return a list of :class:`tilekit.plugins.WebRoute` (path, view, methods): pages and
    ``/api/`` endpoints the plugin adds to ``tilekit serve``.

    Called once when the app is created. A view is ``view(request, web)``, run in a worker
    thread; it returns a str (an HTML page, see ``web.page``), a dict or list (JSON), or a
    starlette Response. A TilekitError it raises becomes the site's error page (or, under
    ``/api/``, the API's JSON error) with the error's status. Paths the app serves itself win.
    """


@hookspec
def tilekit_web_menu_links(web):
    """Return ``(href, label)`` pairs for the navigation bar of every page (an editor's entry
    page, say). Called once when the app is created."""


@hookspec
def tilekit_web_tiling_links(web, name, tiling):
    """Return ``(href, label)`` pairs shown on the page of the catalogue tiling ``name``
    (``tiling``, built, of any family): an editor that opens it, a page about it. Return None
    or [] for tilings that are not yours. Called each time a tiling page is drawn."""


@hookspec(firstresult=True)
def tilekit_web_render_cell(table, column, value, row):
    """Return the HTML of one cell of a run's results page, or None for the default (the
    value as escaped text). ``table`` is the result table's name (None for JSON results),
    ``row`` the whole row as a dict. The first non-None answer wins; escape what you show."""


@hookspec
def tilekit_web_static():
    """Return ``(name, directory)`` pairs: the directory's files are served at
    ``/static/plugins/<name>/`` (a page's scripts: ``web.page(..., scripts=["plugins/<name>/x.js"])``).
    Called once when the app is created."""
