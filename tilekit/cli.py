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

from tilekit import limits
from tilekit.cli_types import COUNT, INT64_MAX, OUTPUT, POSITIVE, RUN_ID, BoundedInt, FiniteFloat
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
    """List the tiling families the installed plugins provide.

    \b
    Examples:
      tilekit families
      tilekit families --format json
    """
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
@click.option("--family", help="Only tilings of this family (a family with a result table lists its rows).")
@click.option("--where", "where", multiple=True, metavar="EXPR",
              help="Filter KEY=V, KEY!=V, KEY>=N, KEY<=N, KEY>N, KEY<N or KEY~TEXT (repeatable; all must hold).")
@click.option("--text", help="Case-insensitive text in the name, title, an alias or a text property.")
@click.option("--order", "order_by", default="name", show_default=True,
              help="Sort key: name, family, title, a shared column or any property; -KEY descends.")
@click.option("--limit", type=COUNT, help="At most N tilings.")
@click.option("--offset", type=COUNT, default=0, help="Skip the first N tilings.")
@click.option("--count", "count_only", is_flag=True, help="Print only how many match.")
@click.option("--format", "fmt", type=click.Choice(["table", "json", "csv", "jsonl"]), default="table",
              show_default=True)
@pass_state
def list_(state: State, family: str | None, where: tuple[str, ...], text: str | None, order_by: str,
          limit: int | None, offset: int, count_only: bool, fmt: str) -> None:
    """List catalogue tilings matching the filters (Catalogue.iter_query), streamed; a family
    with a result table lists its rows.

    \b
    Examples:
      tilekit list --family archimedean
      tilekit list --where polygons=6 --where symmetry_group=p6m
      tilekit list --text penrose --limit 5 --format json
      tilekit list --family vertex-species --where status=impossible --count
    """
    from tilekit.catalogue.output import write_entries

    cat = state.reader(family)
    cat.check_family(family)
    if count_only:
        click.echo(cat.count_matching(family=family, where=list(where), text=text))
        return
    entries = cat.iter_query(family=family, where=list(where), text=text, order_by=order_by,
                             limit=limit, offset=offset)
    if fmt in ("json", "csv", "jsonl"):
        keys = cat._export_keys(family) if fmt == "csv" and cat.family_table(family) is not None else None
        write_entries(entries, sys.stdout, fmt, keys=keys)
        return
    shown = 0
    batch: list[Any] = []
    for entry in entries:
        batch.append([entry.name, entry.family, entry.title])
        if len(batch) == 1000:
            click.echo(_table(["name", "family", "title"], batch, {2: 60}))
            shown += len(batch)
            batch = []
    if batch or not shown:
        if not batch:
            click.echo("no tilings match", err=True)
            return
        click.echo(_table(["name", "family", "title"], batch, {2: 60}))


@cli.command()
@click.argument("name")
@pass_state
def show(state: State, name: str) -> None:
    """Show a tiling: every catalogue property, then its family's description.

    \b
    Examples:
      tilekit show IH16
      tilekit show cairo
      tilekit show penrose-p3
    """
    from tilekit.plugins import families as all_families

    cat = state.catalogue()
    fams = all_families(state.pm)
    if name in fams and not cat.query(where=[f"name={name}"]):
        _show_family(cat, fams[name])
        return
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
    if entry.family not in all_families(state.pm) and cat.family_table(entry.family) is None:
        click.echo(f"(family {entry.family!r} is not installed: no geometry)", err=True)
        return
    try:
        tiling = cat.tiling(entry)
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


def _show_family(cat: Any, fam: Any) -> None:
    """``tilekit show FAMILY``: its summary, description, size and the options its tilings take."""
    click.echo(f"family: {fam.name}")
    click.echo(f"summary: {fam.summary}")
    if getattr(fam, "description", ""):
        click.echo(f"description: {fam.description}")
    click.echo(f"tilings: {cat.count(fam.name)} (tilekit list --family {fam.name})")
    sample = cat.query(family=fam.name, limit=1)
    if sample:
        try:
            text = cat.tiling(sample[0].name).options_help()
        except TilekitError:
            text = ""
        if text:
            click.echo(f"options of tilekit render (e.g. {sample[0].name}):")
            for line in text.splitlines():
                click.echo(f"  {line}")


# --------------------------------------------------------------------------- render


#: Largest |value| of a tiling parameter (--param): shapes are unit-sized, so beyond this a
#: value is a typo and would only overflow the geometry.
MAX_PARAM = 1e6


def _floats(text: str, what: str, bound: float = limits.MAX_COORDINATE) -> list[float]:
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
        if abs(value) > bound:
            raise ParseError(f"{what} {text!r}: {part!r} is outside ±{bound:g}")
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


#: Renders estimated above this many tiles say what they are doing on a terminal.
PROGRESS_TILES = 50_000


def on_terminal() -> bool:
    """Whether progress lines go to a terminal (tests replace this function)."""
    return sys.stderr.isatty()


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
@click.option("-o", "--output", "out", required=True, type=OUTPUT,
              help="Output file: .svg or .png (a picture), .geojson, .json or .csv (tiles and neighbours), "
                   ".cut.svg or .dxf (edges for cutters, shared edges once); see docs/exports.md.")
@click.option("--param", "params", multiple=True, metavar="X[,X...]", help="Tiling parameters (repeatable, or comma-separated).")
@click.option("--edge", "edges", multiple=True, metavar="SPEC", help="Edge shape 'name=x,y:x,y:...' (repeatable).")
@click.option("--depth", type=BoundedInt(0, limits.MAX_DEPTH), help="Substitution depth.")
@click.option("--set", "settings", multiple=True, metavar="KEY=VALUE", help="A family-specific option (repeatable).")
@click.option("--geometry", type=click.Choice(["sphere", "plane", "hyperbolic"]), help="Curved tilings: the surface a vertex configuration closes on, checked (same as --set geometry=G).")
@click.option("--tiling", "which", metavar="WHICH", help="Which of the tile's tilings (e.g. an IH type or a 1-based index; same as --set tiling=WHICH).")
@click.option("--region", metavar="x0,y0,x1,y1", help="The region to cover (default: the tiling's own).")
@click.option("--colours", "--colors", "colours", metavar="c1,c2,...", help="Fill colours, CSS names or #rrggbb.")
@click.option("--labels", is_flag=True, help="Draw edge labels.")
@click.option("--vectors", is_flag=True, help="Draw the translation vectors (periodic tilings).")
@click.option("--system", type=click.Path(exists=True, dir_okay=False), help="Build the tiling from this data file instead of the catalogue.")
@click.option("--family", help="Family that reads --system (default: the family that claims the file by its suffix).")
@click.option("--max-tiles", type=POSITIVE, default=limits.MAX_TILES, show_default=True,
              help="Refuse (before drawing) a patch estimated at more than N tiles.")
@click.option("--width", type=BoundedInt(16, 20_000), help="Image width in pixels (default: longer side 800).")
@click.option("--height", type=BoundedInt(16, 20_000), help="Image height in pixels (instead of --width).")
@click.option("--dpi", type=FiniteFloat(2400, min=10), default=96.0, show_default=True,
              help="PNG resolution: pixels are scaled by DPI/96.")
@click.option("--stroke", default="#222", show_default=True, metavar="COLOUR", help="Outline colour (CSS name or #rrggbb).")
@click.option("--stroke-width", type=FiniteFloat(1e3, min=0.0), help="Outline width in pixels (default: 1.2 for tiles 14 px across or more, thinner for smaller tiles, none under 2.5 px).")
@click.option("--layers", type=click.Choice(["one", "colour"]), default=None,
              help=".cut.svg / .dxf: one layer of every edge (default), or a layer per colour.")
@click.option("--mm-per-unit", type=FiniteFloat(1e6, min=1e-6), default=None,
              help=".cut.svg / .dxf: millimetres per tiling unit (default 10).")
@pass_state
def render(state: State, name: str | None, out: str, params: tuple[str, ...], edges: tuple[str, ...],
           depth: int | None, settings: tuple[str, ...], which: str | None, region: str | None, colours: str | None,
           labels: bool, vectors: bool, system: str | None, family: str | None, max_tiles: int,
           width: int | None, height: int | None, dpi: float, stroke: str, stroke_width: float | None,
           layers: str | None, mm_per_unit: float | None, geometry: str | None) -> None:
    """Render a catalogue tiling (or a --system file) to SVG or PNG, or export it (.geojson,
    .json, .cut.svg, .dxf; the output suffix chooses).

    \b
    Examples:
      tilekit render 3.4.6.4 -o rhombitrihexagonal.svg --vectors
      tilekit render penrose-p3 --depth 5 -o p3.geojson
      tilekit render 3.4.6.4 -o coasters.cut.svg --layers colour --mm-per-unit 20
      tilekit render penrose-p3 --depth 6 -o p3.png
      tilekit render IH41 --param 0.1,0.2 --region -5,-5,5,5 -o ih41.svg
      tilekit render pentomino-F --tiling 0 -o f.svg
    """
    from tilekit.export import (
        STREAM_FORMATS,
        check_disk_space,
        check_export_size,
        export_fits_in_memory,
        outline_vertices,
        output_format,
        write_patch,
    )
    from tilekit.geometry import as_region
    from tilekit.plugins import family_for_file, get_family
    from tilekit.render import parse_palette, write_svg

    fmt = output_format(out)  # an unknown suffix fails before any work, naming the valid ones
    picture = fmt in (".svg", ".png")
    cut = fmt in (".cut.svg", ".dxf")
    for given, flag, ok in ((layers, "--layers", cut), (mm_per_unit, "--mm-per-unit", cut),
                            (width, "--width", picture), (height, "--height", picture),
                            (stroke_width, "--stroke-width", picture), (labels or None, "--labels", picture),
                            (vectors or None, "--vectors", picture)):
        if given is not None and not ok:
            kinds = ".cut.svg and .dxf" if flag in ("--layers", "--mm-per-unit") else ".svg and .png"
            raise ParameterError(f"{flag} applies to {kinds} output, not {fmt}")
    if system is not None:
        if name is not None:
            raise ParameterError(f"give either a tiling NAME ({name!r}) or --system FILE, not both")
        # a plugin claims the file by its suffix (tilekit_claim_file): the core names no family
        claimed = family or family_for_file(system, state.pm)
        if claimed is None:
            from tilekit.plugins import families as all_families

            readers = sorted(n for n, f in all_families(state.pm).items() if f.from_file is not None)
            raise ParameterError(
                f"no installed family claims the file {os.path.basename(system)!r}; name one with --family "
                f"(families that read files: {', '.join(readers) or 'none'})"
            )
        fam = get_family(claimed, state.pm)
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
        options["params"] = [v for p in params for v in _floats(p, "--param", MAX_PARAM)]
    if edges:
        options["edges"] = list(edges)
    if depth is not None:
        options["depth"] = depth
    options.update(parse_settings(settings), **({"geometry": geometry} if geometry else {}))
    if which is not None:
        options["tiling"] = which
    if options:
        tiling = tiling.configure(**options)

    palette = parse_palette(colours)  # a bad colour fails before any work
    parse_palette(stroke)
    if width is not None and height is not None:
        raise ParameterError("give --width or --height, not both (the other follows the region's shape)")
    box = parse_region(region) if region is not None else None
    # estimate first: nothing is allocated for a patch over the limit
    estimate = tiling.estimate_tiles(as_region(box) if box is not None else None)
    check_export_size(estimate, fmt, max_tiles, memory=False)
    area = as_region(box) if box is not None else tiling.default_region()
    vertices = outline_vertices(tiling.prototiles)
    if not export_fits_in_memory(estimate, fmt, vertices, tiling.bytes_per_tile):
        if not (tiling.streams and fmt in STREAM_FORMATS and not labels):
            # the one-line refusal: this cannot stream
            check_export_size(estimate, fmt, max_tiles, vertices=vertices, making=tiling.bytes_per_tile)
        check_disk_space(out, estimate, fmt, tiling.prototiles)
        _render_stream(tiling, area, out, fmt, estimate, palette, stroke, stroke_width, width, height, vectors,
                       vertices)
        return
    check_disk_space(out, estimate, fmt, tiling.prototiles)
    if estimate > PROGRESS_TILES and on_terminal():
        click.echo(f"making about {int(estimate):,} tiles ...", err=True)
    patch = tiling.patch(area)
    if not picture:
        classes = _tile_classes(tiling, patch) if fmt in (".geojson", ".json") else None
        names = tiling.tile_labels(patch, area) if fmt in (".json", ".csv") else None
        # --stroke's default is the picture's outline colour; cut lines are red unless it is given
        write_patch(patch, out, classes=classes, layers=layers or "one", mm_per_unit=mm_per_unit or 10.0,
                    palette=palette, stroke=stroke if stroke != "#222" else None, labels=names)
        click.echo(f"wrote {out} ({len(patch)} tiles)")
        return
    if len(patch) > PROGRESS_TILES and on_terminal():
        click.echo(f"drawing {len(patch):,} tiles to {out} ...", err=True)
    drawn: dict[str, Any] = {"palette": palette, "labels": labels, "region": area, "stroke": stroke,
                             "width": width, "height": height, "dpi": dpi}
    if stroke_width is not None:
        drawn["stroke_width_px"] = stroke_width
    if vectors:
        drawn["vectors"] = _vectors(tiling, area.bounds)
    if labels and not any(p.edge_labels is not None for p in patch.prototiles):
        raise ParameterError(
            f"--labels: the tiles of {tiling.name or 'this tiling'} carry no edge labels "
            "to draw (isohedral types and Wang sets do)"
        )
    dpi_ = drawn.pop("dpi")
    path = write_svg(tiling.render_svg(patch, **drawn), out, dpi_)
    click.echo(f"wrote {path} ({len(patch)} tiles)")


def _render_stream(tiling: Any, area: Any, out: str, fmt: str, estimate: float, palette: Any, stroke: str,
                   stroke_width: float | None, width: int | None, height: int | None, vectors: bool,
                   vertices: int = 4) -> None:
    """Write a patch larger than memory chunk by chunk (``Tiling.iter_patches``, chunks as
    large as half the memory the export may take allows): GeoJSON features or SVG paths,
    a progress bar on a terminal."""
    from tilekit.export import stream_chunk_tiles, write_patches

    chunk = stream_chunk_tiles(fmt, vertices)
    options: dict[str, Any] = {}
    if fmt == ".svg":
        options = {"palette": palette, "stroke": stroke, "region": area, "width": width, "height": height}
        if stroke_width is not None:
            options["stroke_width_px"] = stroke_width
        if vectors:
            options["vectors"] = _vectors(tiling, area.bounds)
    patches = tiling.iter_patches(area, chunk_tiles=chunk)
    bar = None
    if estimate > PROGRESS_TILES and on_terminal():
        from rich.console import Console
        from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

        bar = Progress(TextColumn("[bold]{task.description}"), BarColumn(), TextColumn("{task.completed:,} tiles"),
                       TimeElapsedColumn(), console=Console(stderr=True))
        task = bar.add_task(f"streaming {os.path.basename(out)}", total=estimate)
        bar.start()

        def shown(patches: Any) -> Any:
            for p in patches:
                bar.update(task, advance=len(p))
                yield p

        patches = shown(patches)
    try:
        count = write_patches(patches, out, **options)
    finally:
        if bar is not None:
            bar.stop()
    click.echo(f"wrote {out} ({count} tiles, streamed in chunks of at most {chunk:,})")


def _tile_classes(tiling: Any, patch: Any) -> Any:
    """Each tile's transitivity class for a periodic tiling whose aspects tell it, else None."""
    from tilekit.symmetry.orbits import patch_tile_classes
    from tilekit.tiling import PeriodicTiling

    if not isinstance(tiling, PeriodicTiling):
        return None
    try:
        return patch_tile_classes(tiling, patch)
    except TilekitError:  # a unit the symmetry search cannot analyse: the classes are unknown
        return None


# --------------------------------------------------------------------------- search / runs


_PARAM_TYPES: dict[type, click.ParamType] = {int: BoundedInt(-INT64_MAX, INT64_MAX),
                                             float: FiniteFloat(1e300), str: click.STRING}


def _search_command(search: Any) -> click.Command:
    """A click command for one Search: an option per SearchParam plus executor options."""

    def callback(**kwargs: Any) -> None:
        ctx = click.get_current_context()
        state = ctx.find_object(State)
        executor = kwargs.pop("executor")
        workers = kwargs.pop("workers")
        resume = kwargs.pop("resume")
        scheduler = kwargs.pop("scheduler")
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
        _run_search_cli(state, search.name, params, executor, workers, resume, scheduler)

    from tilekit.search import describe_params

    options: list[click.Parameter] = []
    for p, line in zip(search.params, describe_params(search)):
        flag = "--" + p.name.replace("_", "-")
        help_text = line.split(": ", 1)[-1] + (" [required]" if p.required else "")
        if p.choices is not None:
            help_text += f" (one of {', '.join(map(str, p.choices))})"
        elif p.min is not None or p.max is not None:
            help_text += f" (range {p.min if p.min is not None else '-inf'}..{p.max if p.max is not None else 'inf'})"
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
        click.Option(["--workers"], type=BoundedInt(1, 4096), help="Parallel workers (process/dask)."),
        click.Option(["--scheduler"], metavar="ADDRESS",
                     help="A running dask scheduler (default: $TILEKIT_DASK_SCHEDULER, else a local cluster)."),
        click.Option(["--resume"], type=RUN_ID, metavar="RUN_ID",
                     help="Continue an interrupted or failed run, or join one that is running."),
    ]
    return click.Command(search.name, callback=callback, params=options,
                         help=f"{search.summary} (family {search.family}).\n\n\b\nExamples:\n"
                              f"  tilekit search {search.name}\n  tilekit search {search.name} --executor process --workers 2\n"
                              f"  tilekit search {search.name} --resume RUN_ID",
                         short_help=search.summary)


class _Reporter:
    """Progress of a run: a rich bar on a terminal, a plain line every few seconds otherwise."""

    def __init__(self, cat: Any, name: str) -> None:
        self.cat = cat
        self.name = name
        self.run_id: int | None = None
        self.tty = sys.stderr.isatty()
        self.bar: Any = None
        self.task: Any = None
        self.last_line = 0.0
        self.started = 0.0
        self.first_done: int | None = None
        self.rows = 0
        self.rows_at = -1e9

    def __call__(self, done: int, total: int) -> None:
        import time

        now = time.monotonic()
        if self.first_done is None:
            self.first_done, self.started = done, now
        if self.run_id is not None and (now - self.rows_at >= 1.0 or done == total):
            self.rows_at = now
            self.rows = self.cat.run(self.run_id).rows
        rows = self.rows
        if self.tty:
            if self.bar is None:
                from rich.progress import (
                    BarColumn,
                    MofNCompleteColumn,
                    Progress,
                    TextColumn,
                    TimeElapsedColumn,
                    TimeRemainingColumn,
                )

                self.bar = Progress(TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn(),
                                    TextColumn("chunks, {task.fields[rows]} rows"), TimeElapsedColumn(),
                                    TimeRemainingColumn(), transient=False,
                                    console=__import__("rich.console").console.Console(stderr=True))
                self.bar.start()
                self.task = self.bar.add_task(f"run {self.run_id}: {self.name}", total=total, completed=done,
                                              rows=rows or 0)
            self.bar.update(self.task, completed=done, total=total, rows=rows or 0)
            return
        if now - self.last_line < 5.0 and done != total:
            return
        self.last_line = now
        rate = (done - (self.first_done or 0)) / max(now - self.started, 1e-9)
        left = f", about {(total - done) / rate:.0f} s left" if rate > 0 and done < total else ""
        click.echo(f"run {self.run_id}: {done}/{total} chunks, {rows or 0} rows, "
                   f"{rate:.2f} chunks/s{left}", err=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
            self.bar = None


def _run_search_cli(state: State, name: str, params: dict[str, Any] | None, executor: str,
                    workers: int | None, resume: int | None, scheduler: str | None = None) -> None:
    from tilekit.search import run_search
    from tilekit.signals import Terminated

    cat = state.catalogue()
    reporter = _Reporter(cat, name)

    def announce(run_id: int) -> None:
        reporter.run_id = run_id

    try:
        run_id = run_search(cat, name, params, executor=executor, workers=workers, resume_run=resume,
                            progress=reporter, pm=state.pm, on_run=announce, scheduler=scheduler)
    except KeyboardInterrupt as exc:
        reporter.close()
        code = 143 if isinstance(exc, Terminated) else 130
        what = "terminated" if code == 143 else "interrupted"
        if reporter.run_id is None:
            raise _Stopped(f"{what} before the run was created", code) from None
        info = cat.run(reporter.run_id)
        raise _Stopped(f"run {info.id} {what} after {info.progress} chunks (kept); continue it with: "
                       f"tilekit search {name} --resume {info.id}", code) from None
    finally:
        reporter.close()
    _print_run(cat.run(run_id))


def _print_run(info: Any) -> None:
    click.echo(f"run {info.id}: {info.kind} {info.status} ({info.progress} chunks, {info.rows} rows, "
               f"{info.seconds:.2f} s wall, {info.worker_seconds:.2f} s worker time)")
    for key, value in (info.summary or {}).items():
        click.echo(f"  {key}: {_format_value(value)}")


@cli.group(cls=SearchGroup)
def search() -> None:
    """Run a search a family provides (tilekit search KIND --help for its options).

    \b
    Examples:
      tilekit search
      tilekit search vertex-species --executor process --workers 2
      tilekit search vertex-species --resume 3
    """


_RUN_ACTIONS = ("show", "cancel", "delete")


@cli.command(context_settings={"ignore_unknown_options": False})
@click.argument("words", nargs=-1, metavar="[show|cancel|delete] [RUN_ID]")
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table", show_default=True)
@pass_state
def runs(state: State, words: tuple[str, ...], fmt: str) -> None:
    """Search runs: status, progress, wall and worker time, summary.

    tilekit runs lists every run; tilekit runs RUN_ID (or runs show RUN_ID) shows one;
    tilekit runs cancel RUN_ID stops a run for good (its workers stop after their current
    chunk; recorded chunks are kept); tilekit runs delete RUN_ID removes a run with its
    chunks and results.

    \b
    Examples:
      tilekit runs
      tilekit runs show 3 --format json
      tilekit runs cancel 3
    """
    from tilekit.catalogue import run_json

    action, run_id = _run_words(words)
    cat = state.catalogue()
    if action == "cancel":
        info = cat.cancel_run(run_id)
        click.echo(f"run {info.id} cancelled ({info.progress} chunks recorded)")
        return
    if action == "delete":
        rows = cat.delete_run(run_id)
        click.echo(f"run {run_id} deleted ({rows} result rows)")
        return
    infos = [cat.run(run_id)] if run_id is not None else cat.runs()
    if fmt == "json":
        data = []
        for info in infos:
            item = run_json(info)
            if run_id is not None:
                item["results"] = cat.results(info.id)
                item["counts"] = cat.run_counts(info.id)
            data.append(item)
        click.echo(json.dumps(data, indent=2, ensure_ascii=False, default=str))
        return
    if run_id is None:
        if not infos:
            click.echo("no runs yet", err=True)
            return
        rows = [[str(i.id), i.kind, i.status, i.progress, f"{i.seconds:.2f}", str(i.rows),
                 json.dumps(i.summary, ensure_ascii=False) if i.summary else (i.error or "")] for i in infos]
        click.echo(_table(["id", "kind", "status", "progress", "seconds", "rows", "summary"], rows, {6: 70}))
        return
    info = infos[0]
    _print_run(info)
    click.echo(f"  params: {json.dumps(info.params, ensure_ascii=False)}")
    for k in ("created_at", "started_at", "finished_at"):
        value = getattr(info, k)
        if value is not None:
            click.echo(f"  {k}: {value.isoformat(sep=' ', timespec='seconds')}")
    if info.workers_alive or info.chunks_leased:
        click.echo(f"  workers alive: {info.workers_alive}, chunks leased: {info.chunks_leased}")
    if info.error:
        click.echo(f"  error: {info.error}")
    chunks = cat.run_chunks(info.id)
    pending = [str(c["index"]) for c in chunks if c["status"] != "done"]
    if pending:
        shown = ", ".join(pending[:40]) + (f", ... ({len(pending)} in all)" if len(pending) > 40 else "")
        click.echo(f"  pending chunks: {shown}")
    if info.chunks_done and info.seconds > 0:
        click.echo(f"  rate: {info.chunks_done / info.seconds:.2f} chunks/s, {info.rows / info.seconds:,.0f} rows/s (wall)")
    if info.chunks_done and info.status in ("running", "interrupted") and info.worker_seconds > 0:
        per_chunk = info.worker_seconds / info.chunks_done
        left = per_chunk * (info.chunks_total - info.chunks_done)
        click.echo(f"  worker time per chunk: {per_chunk:.3f} s; left: about {left:.0f} worker-seconds"
                   + (f" (about {left / info.workers_alive:.0f} s with {info.workers_alive} workers)"
                      if info.workers_alive else ""))
    click.echo(f"  results: {sum(1 for _ in cat.iter_results(info.id))}")


def _run_words(words: tuple[str, ...]) -> tuple[str, int | None]:
    """``()``, ``(N,)``, ``(ACTION, N)`` -> (action, run id); one-line errors otherwise."""
    def number(text: str) -> int:
        if not (text.isascii() and text.isdigit()) or len(text) > 18:
            raise ParameterError(f"run id {text!r} is not a run number (see tilekit runs)")
        return int(text)

    if not words:
        return "list", None
    if len(words) == 1:
        if words[0] in _RUN_ACTIONS:
            raise ParameterError(f"tilekit runs {words[0]} needs a RUN_ID")
        return "show", number(words[0])
    if len(words) == 2 and words[0] in _RUN_ACTIONS:
        return words[0], number(words[1])
    close = NotFoundError("runs action", words[0], _RUN_ACTIONS)
    raise ParameterError(f"{close}; usage: tilekit runs [show|cancel|delete] RUN_ID")


# --------------------------------------------------------------------------- catalogue


@cli.group(name="catalogue", cls=SuggestingGroup)
def catalogue_group() -> None:
    """The catalogue database: where it is, migrate, export, seed.

    \b
    Examples:
      tilekit catalogue path
      tilekit catalogue export --format csv -o all.csv
    """


@catalogue_group.command(name="path")
@pass_state
def catalogue_path(state: State) -> None:
    """Print the catalogue's file (SQLite) or URL (password hidden), without opening it.

    \b
    Example:
      tilekit --catalogue shared.sqlite catalogue path
    """
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
    """Run the Alembic migrations (core and plugins) to head.

    \b
    Example:
      tilekit catalogue upgrade
    """
    cat = state.catalogue(seed=False)
    current, heads = cat.revisions()
    click.echo(f"catalogue {cat.url} at revision {', '.join(sorted(current)) or 'base'} (heads: {', '.join(sorted(heads))})")


@catalogue_group.command(name="export")
@click.option("--format", "fmt", type=click.Choice(["json", "jsonl", "csv"]), default="json", show_default=True,
              help="A JSON array, JSON Lines (one object a line) or CSV; all streamed.")
@click.option("-o", "--output", "out", type=OUTPUT, help="Output file (default: stdout).")
@click.option("--family", help="Only tilings of this family.")
@click.option("--where", "where", multiple=True, metavar="EXPR", help="Filter, as for tilekit list.")
@pass_state
def catalogue_export(state: State, fmt: str, out: str | None, family: str | None, where: tuple[str, ...]) -> None:
    """Export tilings (name, family, title, aliases, properties, spec) as JSON, JSON Lines or
    CSV, streamed in constant memory (a family with a result table exports its rows).

    \b
    Examples:
      tilekit catalogue export -o all.json
      tilekit catalogue export --format csv --family archimedean -o arch.csv
      tilekit catalogue export --family vertex-species --format jsonl -o species.jsonl
    """
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
    """Load the tilings the installed plugins ship (new names; all with --replace).

    \b
    Examples:
      tilekit catalogue seed
      tilekit catalogue seed --replace
    """
    cat = state.catalogue(seed=False)
    added, replaced = cat.seed(replace=replace)
    click.echo(f"added {added}, replaced {replaced} tilings ({cat.count()} in the catalogue)")


# --------------------------------------------------------------------------- sample (issue 17)
# A self-contained block: tile-based importance sampling of tilekit.sampling (docs/sampling.md).

#: tilekit.sampling.MAX_SAMPLES, spelled here so that `tilekit --help` does not import NumPy
#: (a test keeps the copies equal).
_MAX_SAMPLES = 20_000_000

@cli.command()
@click.option("--density", "density_spec", required=True, metavar="IMAGE.png|NAME|EXPR",
              help="A PNG (brighter = more samples), a named density (uniform, ramp, radial, step, rings) "
              "or an expression in x, y over the unit square, e.g. 'x*y' or 'exp(-9*((x-.5)**2+(y-.5)**2))'.")
@click.option("--method", default="penrose", show_default=True, help="Sampler: penrose, polyomino or wang (plugins may add more).")
@click.option("-n", "count", type=BoundedInt(1, _MAX_SAMPLES), required=True, help=f"Number of samples (1..{_MAX_SAMPLES:,}).")
@click.option("-o", "--output", "out", type=OUTPUT, required=True,
              help="Points as .csv (x,y) or .npy, or a stipple picture as .svg / .png.")
@click.option("--svg", "svg_out", type=OUTPUT, help="Also draw the stipple picture as SVG.")
@click.option("--png", "png_out", type=OUTPUT, help="Also draw the stipple picture as PNG.")
@click.option("--seed", type=BoundedInt(0, 2**32 - 1), default=0, show_default=True, help="Placement of the tiling.")
@click.option("--relax", type=BoundedInt(0, 50), default=0, show_default=True, help="Lloyd iterations after sampling.")
@click.option("--no-correction", is_flag=True, help="Leave out the sampler's correction step (penrose's table).")
@click.option("--invert", is_flag=True, help="Darker = more samples (classic stippling of a photograph).")
@click.option("--size", type=BoundedInt(16, 10_000), default=800, show_default=True, help="Picture size in pixels.")
@click.option("--stats", is_flag=True, help="Also print nearest-neighbour spacing and the chi-square of the counts.")
def sample(density_spec: str, method: str, count: int, out: str, svg_out: str | None, png_out: str | None,
           seed: int, relax: int, no_correction: bool, invert: bool, size: int, stats: bool) -> None:
    """Sample N points following a density by selective tile subdivision (book §7.4).

    \b
    Examples:
      tilekit sample --density ramp --method penrose -n 20000 -o points.csv
      tilekit sample --density photo.png --invert --method wang -n 50000 -o stipple.png
      tilekit sample --density 'x*y' --method polyomino -n 1000000 -o points.npy
    """
    from pathlib import Path

    from tilekit import sampling
    from tilekit.density import density_from

    outputs = [p for p in (out, svg_out, png_out) if p]
    for p in outputs:
        if Path(p).suffix.lower() not in (".csv", ".npy", ".svg", ".png"):
            raise ParameterError(f"output {Path(p).name!r}: give .csv or .npy for points, .svg or .png for a picture")
    density = density_from(density_spec, invert=invert)
    result = sampling.sample(density, count, method=method, seed=seed, relax=relax, pm=plugin_manager(),
                             correct=not no_correction)
    for p in outputs:
        if Path(p).suffix.lower() in (".csv", ".npy"):
            sampling.write_points(result.points, p)
        else:
            sampling.write_picture(result.points, p, size=size, dark=not invert)
    click.echo(f"wrote {', '.join(outputs)}: {result.count} points ({method}, {count} asked, "
               f"{100 * (result.count - count) / count:+.2f}%, relax {relax})")
    if stats:
        lo, mean = sampling.normalised_spacing(result.points) if result.count > 1 else (float("nan"),) * 2
        fit = sampling.density_fidelity(result.points, density)
        click.echo(f"nearest neighbour / sqrt(1/N): min {lo:.3f}, mean {mean:.3f}; counts on 8 x 8 cells: "
                   f"chi2 {fit['chi2']:.1f} on {fit['dof']} dof, max relative error {fit['max_relative_error']:.3f}")


# --------------------------------------------------------------------------- serve (issue 16)
# A self-contained block: the web catalogue and editor of tilekit.web (docs/web.md).


@cli.command()
@click.option("--host", default="127.0.0.1", show_default=True, help="Interface to bind (loopback unless told otherwise).")
@click.option("--port", default=8000, show_default=True, type=click.IntRange(min=0, max=65535), help="TCP port.")
@click.option("--writable", is_flag=True, help="Allow the write endpoints (cancel a run); read-only otherwise.")
@click.option("--max-tiles", default=20_000, show_default=True, type=click.IntRange(min=1), help="Tiles one render request may draw.")
@pass_state
def serve(state: State, host: str, port: int, writable: bool, max_tiles: int) -> None:
    """Serve the web catalogue, tiling pages and the isohedral editor (needs the web extra).

    Example: tilekit serve --port 8000, then open http://127.0.0.1:8000/
    """
    from tilekit.errors import optional

    for module in ("starlette", "uvicorn"):  # the web extra, checked before anything starts
        optional(module, "web", "tilekit serve")
    import uvicorn

    from tilekit.web import create_app
    state.catalogue()  # open (and migrate) before binding: a bad catalogue is one line, exit 2
    sock = _listening_socket(host, port)  # a bad --host or a taken port: one line, exit 2
    app = create_app(state.url, writable=writable, max_tiles=max_tiles, catalogue=state.catalogue())
    bound = sock.getsockname()[1]
    shown = f"[{host}]" if ":" in host else host
    click.echo(f"serving {state.catalogue().url} on http://{shown}:{bound}/ ({'writable' if writable else 'read-only'})", err=True)
    uvicorn.Server(uvicorn.Config(app, log_level="warning")).run(sockets=[sock])


def _listening_socket(host: str, port: int) -> Any:
    """A TCP socket bound to ``host``:``port`` and listening, or a ParameterError naming
    the host or port and why (not an address, not this machine's, in use): uvicorn would
    otherwise log its own line and exit 3, or raise UnicodeError on a non-ASCII name."""
    import ipaddress
    import re
    import socket

    what = f"--host {host[:60]!r}"
    try:
        ipaddress.ip_address(host)
    except ValueError:
        if re.fullmatch(r"[0-9.]+", host):
            raise ParameterError(f"{what} is not an IPv4 address (four numbers 0..255, e.g. 127.0.0.1)") from None
        try:
            host.encode("idna")
        except UnicodeError:
            raise ParameterError(f"{what} is not a valid host name; give an IP address such as 127.0.0.1 "
                                 "or a name of letters, digits, '-' and '.'") from None
    try:
        family, kind, proto, _, address = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM,
                                                             flags=socket.AI_PASSIVE)[0]
    except (OSError, UnicodeError, ValueError) as exc:
        raise ParameterError(f"{what} cannot be resolved to an address of this machine "
                             f"({getattr(exc, 'strerror', None) or exc})") from None
    sock = socket.socket(family, kind, proto)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(address)
        sock.listen(2048)
    except OSError as exc:
        sock.close()
        raise ParameterError(f"cannot serve on {host}:{port}: {exc.strerror or exc}") from None
    return sock


# commands kept in their own module (keys, prototile), registered here
from tilekit import cli_extra  # noqa: E402  (it reads this module's helpers when it runs)

cli_extra.register(cli)


if __name__ == "__main__":  # pragma: no cover
    main()
