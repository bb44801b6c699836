"""``tilekit render``: a tiling (from the catalogue or a data file) drawn or exported, bounded
and streamed (docs/exports.md); tests replace ``on_terminal`` and ``PROGRESS_TILES``."""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Callable

import click

from tilekit import limits
from tilekit.cli.base import (
    State,
    cli,
    pass_state,
)
from tilekit.cli_types import OUTPUT, POSITIVE, BoundedInt, FiniteFloat
from tilekit.progress import terminal_bar
from tilekit.text import configure_options

# --------------------------------------------------------------------------- render


#: Renders estimated above this many tiles say what they are doing on a terminal.
PROGRESS_TILES = 50_000


def on_terminal() -> bool:
    """Whether progress lines go to a terminal (tests replace this function)."""
    return sys.stderr.isatty()


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
    from tilekit import api

    written = api.render(state.catalogue, out, name, system=system, family=family, pm=state.pm,
                         options=configure_options(params, edges, settings, which, depth), geometry=geometry,
                         region=region, max_tiles=max_tiles, palette=colours, stroke=stroke,
                         stroke_width=stroke_width, width=width, height=height, dpi=dpi, labels=labels,
                         vectors=vectors, layers=layers, mm_per_unit=mm_per_unit, progress=TerminalProgress(out))
    streamed = f", streamed in chunks of at most {written.chunk:,}" if written.chunk else ""
    click.echo(f"wrote {written.path} ({written.tiles} tiles{streamed})")


class TerminalProgress:
    """Progress of a large render on a terminal: a line before making and drawing a patch over
    PROGRESS_TILES tiles, a bar while streaming (nothing when stderr is not a terminal)."""

    def __init__(self, out: str) -> None:
        self.out = out

    def making(self, estimate: float) -> None:
        if estimate > PROGRESS_TILES and on_terminal():
            click.echo(f"making about {int(estimate):,} tiles ...", err=True)

    def drawing(self, tiles: int) -> None:
        if tiles > PROGRESS_TILES and on_terminal():
            click.echo(f"drawing {tiles:,} tiles to {self.out} ...", err=True)

    def streaming(self, estimate: float) -> contextlib.AbstractContextManager[Callable[[int], None]]:
        return terminal_bar(f"streaming {os.path.basename(self.out)}", estimate, "{task.completed:,} tiles",
                            shown=estimate > PROGRESS_TILES and on_terminal())
