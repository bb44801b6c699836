"""``tilekit render``: a tiling (from the catalogue or a data file) drawn or exported, bounded
and streamed (docs/exports.md); tests replace ``on_terminal`` and ``PROGRESS_TILES``."""

from __future__ import annotations

import os
import sys
from typing import Any

import click

from tilekit import limits
from tilekit.cli.base import (
    State,
    cli,
    pass_state,
)
from tilekit.cli_types import OUTPUT, POSITIVE, BoundedInt, FiniteFloat, geometry_option
from tilekit.errors import ParameterError, TilekitError
from tilekit.text import configure_options, parse_region

# --------------------------------------------------------------------------- render


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

    options = configure_options(params, edges, settings, which, depth)
    options.update(geometry_option(tiling, geometry))
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
