"""The ``tilekit`` command line: a thin click layer over the library (see docs/cli.md).

Every command is a few lines over a public call: ``tilekit.plugins.families``,
``Catalogue.query`` / ``get`` / ``tiling`` / ``export`` / ``seed``, ``tilekit.search.run_search``
and ``tilekit.render.write_image``. Errors print one line ``error: ...`` on stderr and exit 2.

The package, by command group: base (the frame: State, the group, errors, ``main``), listing
(families, plugins, list, show), render, runs (search, runs), catalogue, sample, serve, extra
(keys, prototile). Each module adds its commands to the one ``cli`` group when imported.
"""

from tilekit.cli import catalogue, extra, listing, render, runs, sample, serve  # noqa: F401  (their commands)
from tilekit.cli.base import State, cli, main, pass_state, plugin_manager

extra.register(cli)

__all__ = ["State", "cli", "main", "pass_state", "plugin_manager"]
