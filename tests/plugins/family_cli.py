"""A command line restricted to one plugin, on a fresh SQLite catalogue (shared by the family
tests that drive ``tilekit`` through click's runner)."""

from __future__ import annotations

from collections.abc import Callable

from click.testing import CliRunner, Result

from tilekit.plugins import make_plugin_manager


def family_cli(tmp_path, monkeypatch, plugin: str) -> Callable[..., Result]:
    """``run(*args)``: ``tilekit --catalogue <fresh> *args`` with only ``plugin`` loaded,
    in ``tmp_path``."""
    import tilekit.cli

    monkeypatch.setenv("TILEKIT_PLUGINS", plugin)
    pm = make_plugin_manager()
    monkeypatch.setattr(tilekit.cli.base, "plugin_manager", lambda: pm)
    url = f"sqlite:///{tmp_path / 'cat.sqlite'}"
    monkeypatch.chdir(tmp_path)

    def run(*args: str) -> Result:
        return CliRunner().invoke(tilekit.cli.cli, ["--catalogue", url, *args], catch_exceptions=False)

    return run
