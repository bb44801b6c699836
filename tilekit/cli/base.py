"""The command line's frame: the plugin manager it uses (tests replace ``plugin_manager``), the
per-invocation State (the catalogue, opened on first use), the ``tilekit`` group with its
plugin commands and close-name suggestions, one-line errors and exit codes, ``main``."""

from __future__ import annotations

import io
import os
import sys
from collections.abc import Sequence
from typing import Any

import click
import pluggy

from tilekit.errors import NotFoundError, TilekitError


def plugin_manager() -> pluggy.PluginManager:
    """The plugin manager the command line uses (tests replace this function)."""
    from tilekit.plugins import get_plugin_manager

    return get_plugin_manager()


def _one_line(message: str) -> str:
    return "; ".join(line.strip() for line in str(message).splitlines() if line.strip())


def _fail(message: str, code: int = 2) -> None:
    click.echo(f"error: {_one_line(message)}", err=True)
    sys.exit(code)


class _Stopped(Exception):
    """A run stopped by Ctrl-C (exit 130) or SIGTERM (exit 143), with the line to print."""

    def __init__(self, message: str, code: int) -> None:
        super().__init__(message)
        self.message = message
        self.code = code


# --------------------------------------------------------------------------- state


class State:
    """Per-invocation state: the catalogue URL and the catalogue, opened on first use."""

    def __init__(self, url: str | None) -> None:
        self.url = url
        self._catalogue: Any = None

    @property
    def pm(self) -> pluggy.PluginManager:
        return plugin_manager()

    def catalogue(self, *, seed: bool = True) -> Any:
        if self._catalogue is None:
            from tilekit.catalogue import open_catalogue

            self._catalogue = open_catalogue(self.url, seed=seed, pm=self.pm)
        return self._catalogue

    def reader(self, family: str | None = None) -> Any:
        """Something to read tilings with: the catalogue, or, when it is a current SQLite
        file and ``family`` is not in a result table, a reader that needs no SQLAlchemy
        (``tilekit.catalogue.reading.open_reader``: a warm ``list`` in half the CPU)."""
        if self._catalogue is None and os.environ.get("TILEKIT_READ_PATH", "fast") != "full":
            from tilekit.catalogue.reading import open_reader

            reader = open_reader(self.url, self.pm, family)
            if reader is not None:
                self._catalogue = reader
                return reader
        return self.catalogue()

    def close(self) -> None:
        if self._catalogue is not None:
            self._catalogue.close()
            self._catalogue = None


pass_state = click.make_pass_decorator(State)


# --------------------------------------------------------------------------- groups


class SuggestingGroup(click.Group):
    """A group whose unknown subcommands are a NotFoundError suggesting the closest names."""

    what = "command"

    def resolve_command(self, ctx: click.Context, args: list[str]) -> Any:
        name = args[0] if args else ""
        if name and not name.startswith("-") and self.get_command(ctx, name) is None:
            raise NotFoundError(self.what, name, self.list_commands(ctx))
        return super().resolve_command(ctx, args)


class TilekitGroup(SuggestingGroup):
    """The top-level group: adds plugin commands, suggests close names, prints one-line errors."""

    _plugin_cache: dict[int, tuple[pluggy.PluginManager, dict[str, click.Command]]] = {}

    def plugin_commands(self) -> dict[str, click.Command]:
        """Commands the plugins add through ``tilekit_cli_commands(cli)`` (per plugin manager)."""
        pm = plugin_manager()
        cached = self._plugin_cache.get(id(pm))
        if cached is None or cached[0] is not pm:
            holder = click.Group(name=self.name)
            pm.hook.tilekit_cli_commands(cli=holder)
            cached = (pm, dict(holder.commands))
            self._plugin_cache[id(pm)] = cached
        return cached[1]

    def list_commands(self, ctx: click.Context) -> list[str]:
        names = set(self.commands)
        names.update(self.plugin_commands())
        return sorted(names)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name in self.commands:
            return self.commands[cmd_name]
        return self.plugin_commands().get(cmd_name)

    def main(self, args: Sequence[str] | None = None, prog_name: str | None = None,
             complete_var: str | None = None, standalone_mode: bool = True, **extra: Any) -> Any:
        from tilekit.signals import Terminated, sigterm_raises

        try:
            with sigterm_raises():
                rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        except Terminated:
            _fail("terminated", 143)
        except KeyboardInterrupt:
            _fail("interrupted", 130)
        except _Stopped as exc:
            _fail(exc.message, exc.code)
        except TilekitError as exc:
            _fail(str(exc))
        except click.exceptions.Abort as exc:  # click's wrapping of KeyboardInterrupt
            cause = exc.__cause__ or exc.__context__
            if isinstance(cause, Terminated):
                _fail("terminated", 143)
            _fail("interrupted", 130)
        except click.exceptions.NoArgsIsHelpError as exc:
            click.echo(exc.ctx.get_help())
            rv = 0
        except click.ClickException as exc:
            _fail(exc.format_message())
        except BrokenPipeError:  # `tilekit list | head`: the reader left; stop quietly
            try:
                devnull = os.open(os.devnull, os.O_WRONLY)
                os.dup2(devnull, sys.stdout.fileno())
            except (OSError, ValueError, io.UnsupportedOperation):
                pass
            sys.exit(1)
        except OSError as exc:
            _fail(f"{exc.strerror or exc}" + (f": {exc.filename}" if exc.filename else ""))
        if not standalone_mode:
            return rv
        sys.exit(rv if isinstance(rv, int) else 0)


@click.group(cls=TilekitGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.option(
    "--catalogue",
    "catalogue_url",
    envvar="TILEKIT_CATALOGUE",
    metavar="URL",
    help="Catalogue database: a SQLAlchemy URL or a SQLite file path "
    "(default: a SQLite file in the user data directory; env TILEKIT_CATALOGUE).",
)
@click.version_option(package_name="tilekit")
@click.pass_context
def cli(ctx: click.Context, catalogue_url: str | None) -> None:
    """tilekit: computational tiling theory after Kaplan's Introductory Tiling Theory.

    \b
    Examples:
      tilekit list --family archimedean
      tilekit show cairo
      tilekit render penrose-p3 --depth 6 -o p3.svg
    """
    state = State(catalogue_url)
    ctx.obj = state
    ctx.call_on_close(state.close)


def main(argv: Sequence[str] | None = None) -> None:
    """Console-script entry point."""
    cli.main(args=list(argv) if argv is not None else None, prog_name="tilekit")


# --------------------------------------------------------------------------- output helpers


FORMAT = click.Choice(["table", "json", "csv"])
