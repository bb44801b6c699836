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

    Called once when the plugin manager is built. Family names must be unique across
    all plugins; a clash is a :class:`tilekit.errors.PluginError`.
    """


@hookspec
def tilekit_catalogue_records():
    """Return an iterable of :class:`tilekit.plugins.CatalogueRecord` this plugin ships.

    Called when a catalogue is empty (first open) or re-seeded, to load the known tilings
    of the plugin's families. Records carry a JSON ``spec`` that the family's
    ``from_spec`` turns back into a :class:`tilekit.Tiling`.
    """


@hookspec
def tilekit_searches():
    """Return a list of :class:`tilekit.plugins.Search` (enumeration / search jobs).

    Each search names its parameters, splits a run into chunks and computes the results of
    one chunk; tilekit.search stores them, resumes interrupted runs and runs chunks in
    parallel.
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

    Called once while the command line is assembled; return value ignored.
    """


@hookspec
def tilekit_migration_locations():
    """Return a list of directories holding Alembic version scripts for a plugin's own tables.

    Each directory is added to Alembic's ``version_locations``; give its revisions their own
    ``branch_labels`` so they upgrade independently of the core tables.
    """
