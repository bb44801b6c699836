"""The ``tilekit`` command line: a thin click layer over the library (see docs/cli.md).

Every command is a few lines over a public call: ``tilekit.plugins.families``,
``Catalogue.query`` / ``get`` / ``tiling`` / ``export`` / ``seed``, ``tilekit.search.run_search``
and ``tilekit.render.write_image``. Errors print one line ``error: ...`` on stderr and exit 2.
"""

from __future__ import annotations

import io
import json
import math
import os
import sys
from collections.abc import Sequence
from typing import Any

import click
import pluggy

from tilekit.errors import NotFoundError, ParameterError, ParseError, TilekitError

__all__ = ["cli", "main", "plugin_manager"]


def plugin_manager() -> pluggy.PluginManager:
    """The plugin manager the command line uses (tests replace this function)."""
    from tilekit.plugins import get_plugin_manager

    return get_plugin_manager()


def _one_line(message: str) -> str:
    return "; ".join(line.strip() for line in str(message).splitlines() if line.strip())


def _fail(message: str, code: int = 2) -> None:
    click.echo(f"error: {_one_line(message)}", err=True)
    sys.exit(code)


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
        try:
            rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        except TilekitError as exc:
            _fail(str(exc))
        except click.exceptions.Abort:
            _fail("aborted", 1)
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


class SearchGroup(SuggestingGroup):
    """``tilekit search KIND``: one subcommand per registered search, built from its SearchParams."""

    what = "search"

    def list_commands(self, ctx: click.Context) -> list[str]:
        from tilekit.plugins import searches

        return sorted(searches(plugin_manager()))

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        from tilekit.plugins import searches

        search = searches(plugin_manager()).get(cmd_name)
        return None if search is None else _search_command(search)


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
    """tilekit: computational tiling theory after Kaplan's Introductory Tiling Theory."""
    state = State(catalogue_url)
    ctx.obj = state
    ctx.call_on_close(state.close)


def main(argv: Sequence[str] | None = None) -> None:
    """Console-script entry point."""
    cli.main(args=list(argv) if argv is not None else None, prog_name="tilekit")


# --------------------------------------------------------------------------- output helpers


def _format_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, list) and any(isinstance(v, list | dict) for v in value):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list):
        return ", ".join(_format_value(v) for v in value) if value else "[]"
    if isinstance(value, dict):
        return json.dumps(value, ensure_ascii=False)
    return str(value)


def _table(headers: Sequence[str], rows: Sequence[Sequence[Any]], widths: dict[int, int] | None = None) -> str:
    """A plain fixed-width table (column i clipped to ``widths[i]`` characters)."""
    widths = widths or {}
    cells = [[_format_value(c) if not isinstance(c, str) else c for c in row] for row in rows]
    for row in cells:
        for i, limit in widths.items():
            if len(row[i]) > limit:
                row[i] = row[i][: limit - 1] + "…"
    sizes = [len(h) for h in headers]
    for row in cells:
        sizes = [max(s, len(c)) for s, c in zip(sizes, row)]
    lines = ["  ".join(h.upper().ljust(s) for h, s in zip(headers, sizes)).rstrip()]
    for row in cells:
        lines.append("  ".join(c.ljust(s) for c, s in zip(row, sizes)).rstrip())
    return "\n".join(lines)


FORMAT = click.Choice(["table", "json", "csv"])


# --------------------------------------------------------------------------- families


@cli.command()
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table", show_default=True)
@pass_state
def families(state: State, fmt: str) -> None:
    """List the tiling families the installed plugins provide."""
    from tilekit.plugins import families as all_families

    fams = all_families(state.pm)
    if fmt == "json":
        data = [{"name": f.name, "summary": f.summary, "reads_files": f.from_file is not None}
                for f in fams.values()]
        click.echo(json.dumps(data, indent=2, ensure_ascii=False))
        return
    if not fams:
        click.echo("no families are installed", err=True)
        return
    click.echo(_table(["family", "summary"], [[f.name, f.summary] for f in sorted(fams.values(), key=lambda f: f.name)]))


@cli.command()
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table", show_default=True)
@pass_state
def plugins(state: State, fmt: str) -> None:
    """List the loaded plugins, where each came from, and the hooks it implements."""
    from tilekit.plugins import plugin_info

    infos = plugin_info(state.pm)
    if fmt == "json":
        click.echo(json.dumps([i.to_dict() for i in infos], indent=2, ensure_ascii=False))
        return
    rows = [[i.name, i.distribution or "built in", ", ".join(h.removeprefix("tilekit_") for h in i.hooks), i.source]
            for i in infos]
    click.echo(_table(["plugin", "from", "hooks", "source"], rows))


# --------------------------------------------------------------------------- list / show


@cli.command(name="list")
@click.option("--family", help="Only tilings of this family.")
@click.option("--where", "where", multiple=True, metavar="EXPR",
              help="Filter KEY=V, KEY!=V, KEY>=N, KEY<=N, KEY>N, KEY<N or KEY~TEXT (repeatable; all must hold).")
@click.option("--text", help="Case-insensitive text in the name, title, an alias or a text property.")
@click.option("--order", "order_by", default="name", show_default=True,
              help="Sort key: name, family, title, a shared column or any property; -KEY descends.")
@click.option("--limit", type=click.IntRange(min=0), help="At most N tilings.")
@click.option("--offset", type=click.IntRange(min=0), default=0, help="Skip the first N tilings.")
@click.option("--format", "fmt", type=FORMAT, default="table", show_default=True)
@pass_state
def list_(state: State, family: str | None, where: tuple[str, ...], text: str | None, order_by: str,
          limit: int | None, offset: int, fmt: str) -> None:
    """List catalogue tilings matching the filters (Catalogue.query)."""
    from tilekit.catalogue import entries_text
    from tilekit.plugins import families as all_families

    cat = state.catalogue()
    if family is not None:
        fams = set(all_families(state.pm))
        if family not in fams and cat.count(family) == 0:
            raise NotFoundError("family", family, fams)
    entries = cat.query(family=family, where=list(where), text=text, order_by=order_by, limit=limit, offset=offset)
    if fmt in ("json", "csv"):
        click.echo(entries_text(entries, fmt), nl=False)
        return
    if not entries:
        click.echo("no tilings match", err=True)
        return
    click.echo(_table(["name", "family", "title"], [[e.name, e.family, e.title] for e in entries], {2: 60}))


@cli.command()
@click.argument("name")
@pass_state
def show(state: State, name: str) -> None:
    """Show a tiling: every catalogue property, then its family's description."""
    from tilekit.plugins import families as all_families

    cat = state.catalogue()
    entry = cat.get(name)
    click.echo(f"name: {entry.name}")
    click.echo(f"family: {entry.family}")
    if entry.title:
        click.echo(f"title: {entry.title}")
    if entry.aliases:
        click.echo(f"aliases: {', '.join(entry.aliases)}")
    click.echo("properties:")
    width = max((len(k) for k in entry.properties), default=0)
    for key, value in entry.properties.items():
        click.echo(f"  {key.ljust(width)}  {_format_value(value)}")
    if entry.family not in all_families(state.pm):
        click.echo(f"(family {entry.family!r} is not installed: no geometry)", err=True)
        return
    try:
        tiling = cat.tiling(entry.name)
    except TilekitError as exc:  # a record without geometry, e.g. a vertex type that cannot tile
        click.echo(f"(no geometry: {exc})")
        return
    if "wallpaper_group" not in entry.properties and "symmetry_group" not in entry.properties:
        from tilekit.tiling import PeriodicTiling

        if isinstance(tiling, PeriodicTiling):
            from tilekit.symmetry import wallpaper_group

            group = wallpaper_group(tiling)
            click.echo(f"  {'wallpaper_group'.ljust(width)}  {group.iuc} ({group.orbifold}; computed)")
    text = tiling.describe()
    if text:
        click.echo("")
        click.echo(text.rstrip("\n"))


# --------------------------------------------------------------------------- render


def _floats(text: str, what: str) -> list[float]:
    out: list[float] = []
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        try:
            value = float(part)
        except ValueError:
            raise ParseError(f"{what} {text!r}: {part!r} is not a number") from None
        if not math.isfinite(value):
            raise ParseError(f"{what} {text!r}: {part!r} is not a finite number")
        out.append(value)
    return out


def parse_region(text: str) -> tuple[float, float, float, float]:
    """``x0,y0,x1,y1`` -> a box with x0 < x1 and y0 < y1."""
    values = _floats(text, "--region")
    if len(values) != 4:
        raise ParseError(f"--region {text!r} needs four numbers x0,y0,x1,y1")
    x0, y0, x1, y1 = values
    if not (x0 < x1 and y0 < y1):
        raise ParseError(f"--region {text!r} needs x0 < x1 and y0 < y1")
    return x0, y0, x1, y1


def parse_settings(items: Sequence[str]) -> dict[str, str]:
    """``KEY=VALUE`` strings -> a dict (values stay text; the family parses them)."""
    out: dict[str, str] = {}
    for item in items:
        key, sep, value = item.partition("=")
        key = key.strip()
        if not sep or not key:
            raise ParseError(f"--set {item!r} is not KEY=VALUE")
        out[key] = value.strip()
    return out


def _vectors(tiling: Any, region: tuple[float, float, float, float]) -> tuple[Any, Any, Any]:
    import numpy as np

    v1, v2 = getattr(tiling, "v1", None), getattr(tiling, "v2", None)
    if v1 is None or v2 is None:
        raise ParameterError(f"--vectors needs a periodic tiling; {tiling.name or 'this tiling'} has no translation vectors")
    basis = np.column_stack([v1, v2])
    centre = np.array([(region[0] + region[2]) / 2, (region[1] + region[3]) / 2])
    origin = basis @ np.round(np.linalg.solve(basis, centre))
    return origin, np.asarray(v1, dtype=float), np.asarray(v2, dtype=float)


@cli.command()
@click.argument("name", required=False)
@click.option("-o", "--output", "out", required=True, type=click.Path(dir_okay=False), help="Output .svg or .png file.")
@click.option("--param", "params", multiple=True, metavar="X[,X...]", help="Tiling parameters (repeatable, or comma-separated).")
@click.option("--edge", "edges", multiple=True, metavar="SPEC", help="Edge shape 'name=x,y:x,y:...' (repeatable).")
@click.option("--depth", type=click.IntRange(min=0), help="Substitution depth.")
@click.option("--set", "settings", multiple=True, metavar="KEY=VALUE", help="A family-specific option (repeatable).")
@click.option("--region", metavar="x0,y0,x1,y1", help="The region to cover (default: the tiling's own).")
@click.option("--colours", "--colors", "colours", metavar="c1,c2,...", help="Fill colours, CSS names or #rrggbb.")
@click.option("--labels", is_flag=True, help="Draw edge labels.")
@click.option("--vectors", is_flag=True, help="Draw the translation vectors (periodic tilings).")
@click.option("--system", type=click.Path(exists=True, dir_okay=False), help="Build the tiling from this data file instead of the catalogue.")
@click.option("--family", help="Family that reads --system (default: the family that claims the file's suffix).")
@pass_state
def render(state: State, name: str | None, out: str, params: tuple[str, ...], edges: tuple[str, ...],
           depth: int | None, settings: tuple[str, ...], region: str | None, colours: str | None,
           labels: bool, vectors: bool, system: str | None, family: str | None) -> None:
    """Render a catalogue tiling (or a --system file) to SVG or PNG."""
    from tilekit.geometry import as_region
    from tilekit.plugins import family_for_file, get_family
    from tilekit.render import parse_palette, write_image

    if system is not None:
        if name is not None:
            raise ParameterError(f"give either a tiling NAME ({name!r}) or --system FILE, not both")
        # a plugin claims the file by its suffix (tilekit_claim_file); the last fallback keeps
        # the old default until tests/test_cli.py stops asserting it
        fam = get_family(family or family_for_file(system, state.pm) or "substitution", state.pm)
        if fam.from_file is None:
            raise ParameterError(f"family {fam.name!r} cannot read data files; --system needs a family that can")
        tiling = fam.from_file(system)
    else:
        if name is None:
            raise ParameterError("render needs a tiling NAME (see tilekit list) or --system FILE")
        if family is not None:
            raise ParameterError("--family only goes with --system FILE")
        tiling = state.catalogue().tiling(name)

    options: dict[str, Any] = {}
    if params:
        options["params"] = [v for p in params for v in _floats(p, "--param")]
    if edges:
        options["edges"] = list(edges)
    if depth is not None:
        options["depth"] = depth
    options.update(parse_settings(settings))
    if options:
        tiling = tiling.configure(**options)

    box = parse_region(region) if region is not None else None
    area = as_region(box) if box is not None else tiling.default_region()
    patch = tiling.patch(area)
    drawn = {"palette": parse_palette(colours), "labels": labels, "region": area}
    if vectors:
        drawn["vectors"] = _vectors(tiling, area.bounds)
    path = write_image(patch, out, **drawn)
    click.echo(f"wrote {path} ({len(patch)} tiles)")


# --------------------------------------------------------------------------- search / runs


_PARAM_TYPES: dict[type, click.ParamType] = {int: click.INT, float: click.FLOAT, str: click.STRING}


def _search_command(search: Any) -> click.Command:
    """A click command for one Search: an option per SearchParam plus executor options."""

    def callback(**kwargs: Any) -> None:
        ctx = click.get_current_context()
        state = ctx.find_object(State)
        executor = kwargs.pop("executor")
        workers = kwargs.pop("workers")
        resume = kwargs.pop("resume")
        given = {
            p.name: kwargs[p.name]
            for p in search.params
            if ctx.get_parameter_source(p.name) not in (click.core.ParameterSource.DEFAULT, None)
        }
        if resume is not None and given:
            raise ParameterError(
                f"--resume {resume} continues the run with its stored parameters; drop "
                + ", ".join("--" + k.replace("_", "-") for k in given)
            )
        params = None if resume is not None else {k: v for k, v in kwargs.items() if v is not None}
        _run_search_cli(state, search.name, params, executor, workers, resume)

    options: list[click.Parameter] = []
    for p in search.params:
        flag = "--" + p.name.replace("_", "-")
        help_text = p.help + (" [required]" if p.required else "")
        if p.type is bool:
            options.append(click.Option([f"{flag}/--no-{flag[2:]}", p.name], default=p.default,
                                        help=help_text, show_default=p.default is not None))
        else:
            options.append(click.Option([flag, p.name], type=_PARAM_TYPES.get(p.type, click.STRING),
                                        default=p.default, help=help_text,
                                        show_default=p.default is not None))
    options += [
        click.Option(["--executor"], type=click.Choice(["local", "process", "dask"]), default="local",
                     show_default=True, help="Where chunks run: this process, a process pool, or dask."),
        click.Option(["--workers"], type=click.IntRange(min=1), help="Parallel workers (process/dask)."),
        click.Option(["--resume"], type=int, metavar="RUN_ID", help="Continue an interrupted or failed run."),
    ]
    return click.Command(search.name, callback=callback, params=options,
                         help=f"{search.summary} (family {search.family}).", short_help=search.summary)


def _run_search_cli(state: State, name: str, params: dict[str, Any] | None, executor: str,
                    workers: int | None, resume: int | None) -> None:
    from tilekit.search import run_search

    cat = state.catalogue()
    bar: Any = None
    show_bar = sys.stderr.isatty()

    def progress(done: int, total: int) -> None:
        nonlocal bar
        if not show_bar:
            return
        if bar is None:
            bar = click.progressbar(length=total, label=f"{name}", file=sys.stderr)
            bar.__enter__()
        bar.update(done - bar.pos)

    started: list[int] = []

    def close_bar() -> None:
        nonlocal bar
        if bar is not None:
            bar.__exit__(None, None, None)
            bar = None

    try:
        run_id = run_search(cat, name, params, executor=executor, workers=workers, resume_run=resume,
                            progress=progress, pm=state.pm, on_run=started.append)
    except KeyboardInterrupt:
        close_bar()
        if not started:
            _fail("interrupted before the run was created", 130)
        info = cat.run(started[0])
        _fail(f"run {info.id} interrupted after {info.progress} chunks; continue it with: "
              f"tilekit search {name} --resume {info.id}", 130)
    finally:
        close_bar()
    _print_run(cat.run(run_id))


def _print_run(info: Any) -> None:
    click.echo(f"run {info.id}: {info.kind} {info.status} ({info.progress} chunks, {info.seconds:.2f} s)")
    for key, value in (info.summary or {}).items():
        click.echo(f"  {key}: {_format_value(value)}")


@cli.group(cls=SearchGroup)
def search() -> None:
    """Run a search a family provides (tilekit search KIND --help for its options)."""


@cli.command()
@click.argument("run_id", required=False, type=int)
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table", show_default=True)
@pass_state
def runs(state: State, run_id: int | None, fmt: str) -> None:
    """Search runs: status, progress, seconds, summary (one run in detail with RUN_ID)."""
    cat = state.catalogue()
    infos = [cat.run(run_id)] if run_id is not None else cat.runs()
    if fmt == "json":
        data = []
        for info in infos:
            item = {k: getattr(info, k) for k in ("id", "kind", "params", "status", "chunks_total",
                                                   "chunks_done", "seconds", "summary", "error")}
            for k in ("created_at", "started_at", "finished_at"):
                value = getattr(info, k)
                item[k] = value.isoformat() if value is not None else None
            if run_id is not None:
                item["results"] = cat.results(info.id)
            data.append(item)
        click.echo(json.dumps(data, indent=2, ensure_ascii=False, default=str))
        return
    if run_id is None:
        if not infos:
            click.echo("no runs yet", err=True)
            return
        rows = [[str(i.id), i.kind, i.status, i.progress, f"{i.seconds:.2f}",
                 json.dumps(i.summary, ensure_ascii=False) if i.summary else (i.error or "")] for i in infos]
        click.echo(_table(["id", "kind", "status", "progress", "seconds", "summary"], rows, {5: 70}))
        return
    info = infos[0]
    _print_run(info)
    click.echo(f"  params: {json.dumps(info.params, ensure_ascii=False)}")
    for k in ("created_at", "started_at", "finished_at"):
        value = getattr(info, k)
        if value is not None:
            click.echo(f"  {k}: {value.isoformat(sep=' ', timespec='seconds')}")
    if info.error:
        click.echo(f"  error: {info.error}")
    chunks = cat.run_chunks(info.id)
    pending = [str(c["index"]) for c in chunks if c["status"] != "done"]
    if pending:
        click.echo(f"  pending chunks: {', '.join(pending)}")
    click.echo(f"  results: {len(cat.results(info.id))}")


# --------------------------------------------------------------------------- catalogue


@cli.group(name="catalogue", cls=SuggestingGroup)
def catalogue_group() -> None:
    """The catalogue database: where it is, migrate, export, seed."""


@catalogue_group.command(name="path")
@pass_state
def catalogue_path(state: State) -> None:
    """Print the catalogue's file (SQLite) or URL (password hidden), without opening it."""
    from sqlalchemy.engine import make_url

    from tilekit.catalogue import resolve_url

    url = make_url(resolve_url(state.url))
    if url.get_backend_name() == "sqlite" and url.database and url.database != ":memory:":
        click.echo(url.database)
    else:
        click.echo(url.render_as_string(hide_password=True))


@catalogue_group.command(name="upgrade")
@pass_state
def catalogue_upgrade(state: State) -> None:
    """Run the Alembic migrations (core and plugins) to head."""
    cat = state.catalogue(seed=False)
    current, heads = cat.revisions()
    click.echo(f"catalogue {cat.url} at revision {', '.join(sorted(current)) or 'base'} (heads: {', '.join(sorted(heads))})")


@catalogue_group.command(name="export")
@click.option("--format", "fmt", type=click.Choice(["json", "csv"]), default="json", show_default=True)
@click.option("-o", "--output", "out", type=click.Path(dir_okay=False), help="Output file (default: stdout).")
@click.option("--family", help="Only tilings of this family.")
@click.option("--where", "where", multiple=True, metavar="EXPR", help="Filter, as for tilekit list.")
@pass_state
def catalogue_export(state: State, fmt: str, out: str | None, family: str | None, where: tuple[str, ...]) -> None:
    """Export tilings (name, family, title, aliases, properties, spec) as JSON or CSV."""
    cat = state.catalogue()
    if out is None:
        cat.export(sys.stdout, fmt, family=family, where=list(where))
        return
    count = cat.export(out, fmt, family=family, where=list(where))
    click.echo(f"wrote {count} tilings to {out}", err=True)


@catalogue_group.command(name="seed")
@click.option("--replace", is_flag=True, help="Overwrite tilings the plugins ship (keeps others).")
@pass_state
def catalogue_seed(state: State, replace: bool) -> None:
    """Load the tilings the installed plugins ship (new names; all with --replace)."""
    cat = state.catalogue(seed=False)
    added, replaced = cat.seed(replace=replace)
    click.echo(f"added {added}, replaced {replaced} tilings ({cat.count()} in the catalogue)")


if __name__ == "__main__":  # pragma: no cover
    main()
