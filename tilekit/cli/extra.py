"""Commands about the catalogue's vocabulary and single shapes: ``tilekit keys [FAMILY]`` (every
queryable key with its type, families and an example) and ``tilekit prototile NAME`` (one
prototile of any tiling as SVG, DXF or GeoJSON). The package's __init__ registers them on the
``tilekit`` group."""

from __future__ import annotations

import json
from typing import Any

import click

from tilekit.cli_types import OUTPUT, BoundedInt
from tilekit.text import configure_options, text_table


@click.command(name="keys")
@click.argument("family", required=False)
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table", show_default=True)
@click.pass_obj
def keys_command(state: Any, family: str | None, fmt: str) -> None:
    """List every key `tilekit list --where` takes: its type, the families whose tilings have it,
    how many tilings do, an example filter and its older names (aliases). The shared vocabulary
    (sides, aperiodic, periodic, wallpaper_group ...) comes first; docs/catalogue.md explains it.

    \b
    Examples:
      tilekit keys
      tilekit keys isohedral
      tilekit keys --format json
    """
    from tilekit import api

    infos = api.keys(state.reader(family), family)
    if fmt == "json":
        click.echo(json.dumps([i.to_dict() for i in infos], indent=2, ensure_ascii=False))
        return
    if not infos:
        click.echo("no keys: the catalogue has no tilings" + (f" of family {family!r}" if family else ""), err=True)
        return
    rows = [[i.key, i.type, ", ".join(i.families), str(i.tilings), i.example, ", ".join(i.aliases)] for i in infos]
    click.echo(text_table(["key", "type", "families", "tilings", "example", "aliases"], rows, {2: 48}))


@click.command(name="prototile")
@click.argument("name")
@click.option("--index", type=BoundedInt(0, 10_000), default=0, show_default=True,
              help="Which prototile (0-based; the message names how many there are).")
@click.option("-o", "--output", "out", required=True, type=OUTPUT,
              help="Output file: .svg or .png (the shape drawn), .geojson or .json (its polygon), .dxf or "
                   ".cut.svg (its outline as a cut path); see docs/exports.md.")
@click.option("--param", "params", multiple=True, metavar="X[,X...]", help="Tiling parameters, as for render.")
@click.option("--edge", "edges", multiple=True, metavar="SPEC", help="Edge shape 'name=x,y:x,y:...', as for render.")
@click.option("--set", "settings", multiple=True, metavar="KEY=VALUE", help="A family-specific option, as for render.")
@click.option("--tiling", "which", metavar="WHICH", help="Which of the tile's tilings, as for render.")
@click.option("--mm-per-unit", type=click.FloatRange(1e-6, 1e6), default=10.0, show_default=True,
              help=".dxf / .cut.svg: millimetres per tiling unit.")
@click.pass_obj
def prototile_command(state: Any, name: str, index: int, out: str, params: tuple[str, ...], edges: tuple[str, ...],
                      settings: tuple[str, ...], which: str | None, mm_per_unit: float) -> None:
    """Export one prototile of any tiling (an isohedral tile with its edge shapes, a Laves
    tile, a polyomino, the hat ...) as a picture, GeoJSON or a cut file, at the origin in the
    tiling's units.

    \b
    Examples:
      tilekit prototile IH16 --edge 'a=0,0:0.3,0.2:1,0' -o ih16-tile.svg
      tilekit prototile cairo -o cairo-tile.dxf
      tilekit prototile penrose-p3 --index 1 -o thin.geojson
    """
    from tilekit import api

    tile = api.write_prototile(state.catalogue, name, out, index, configure_options(params, edges, settings, which),
                               mm_per_unit=mm_per_unit)
    click.echo(f"wrote {tile.path} (prototile {tile.index} of {tile.of}{': ' + tile.name if tile.name else ''}; "
               f"{tile.sides} sides, area {tile.area:.6g})")


def register(group: click.Group) -> None:
    """Add this module's commands to the ``tilekit`` group."""
    group.add_command(keys_command)
    group.add_command(prototile_command)
