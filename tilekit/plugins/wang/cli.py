"""``tilekit wang ...``: thin commands over the Wang library (render with triangles, solve).

``tilekit wang render SET -o FILE`` draws a fill with the four-triangle picture (or a
texture file, exercise 6.8); ``tilekit wang solve SET --rows R --cols C`` answers the
rectangle/torus question with a chosen solver. SET is a shipped set name or a .wang file.
"""

from __future__ import annotations

from pathlib import Path

import click

from tilekit.errors import ParseError
from tilekit.plugins.wang.render import write_wang_image
from tilekit.plugins.wang.solve import METHODS, solve
from tilekit.plugins.wang.tileset import WangTileSet, get_tileset, load_tileset
from tilekit.plugins.wang.tiling import WangTiling


def _tileset(name: str) -> WangTileSet:
    if name.endswith(".wang") or Path(name).is_file():
        return load_tileset(name)
    return get_tileset(name)


def _fixed(items: tuple[str, ...]) -> dict[tuple[int, int], str | int]:
    out: dict[tuple[int, int], str | int] = {}
    for item in items:
        pos, sep, tile = item.partition("=")
        try:
            i, j = (int(v) for v in pos.split(","))
        except ValueError:
            raise ParseError(f"--fix {item!r} is not ROW,COL=TILE (e.g. 0,3=a or 0,3=5)") from None
        if not sep or not tile:
            raise ParseError(f"--fix {item!r} is not ROW,COL=TILE (e.g. 0,3=a or 0,3=5)")
        out[(i, j)] = int(tile) if tile.isdigit() else tile
    return out


@click.group(name="wang")
def wang_group() -> None:
    """Wang tiles: render fills with coloured triangles or textures, solve rectangles and tori."""


@wang_group.command(name="render")
@click.argument("set_name", metavar="SET")
@click.option("-o", "--output", "out", required=True, type=click.Path(dir_okay=False), help="Output .svg or .png.")
@click.option("--rows", type=click.IntRange(min=1), default=12, show_default=True)
@click.option("--cols", type=click.IntRange(min=1), default=16, show_default=True)
@click.option("--seed", type=int, default=0, show_default=True)
@click.option("--method", type=click.Choice(["auto", "random-access", "scanline", "periodic", "solver"]), default="auto",
              show_default=True, help="How to fill the grid.")
@click.option("--texture", type=click.Path(exists=True, dir_okay=False), help="TOML file of SVG motifs per edge colour.")
@click.option("--size", type=click.IntRange(min=16), default=800, show_default=True, help="Image size in pixels.")
def render_command(set_name: str, out: str, rows: int, cols: int, seed: int, method: str, texture: str | None,
                   size: int) -> None:
    """Fill a ROWS x COLS grid with SET and draw it."""
    ts = _tileset(set_name)
    grid = WangTiling(ts, seed=seed, method=method).grid(0, 0, rows, cols)
    path = write_wang_image(grid, ts, out, texture=texture, size=size)
    click.echo(f"wrote {path} ({rows * cols} tiles of {ts.name})")


@wang_group.command(name="solve")
@click.argument("set_name", metavar="SET")
@click.option("--rows", type=click.IntRange(min=1), required=True)
@click.option("--cols", type=click.IntRange(min=1), required=True)
@click.option("--torus", is_flag=True, help="Ask for a torus (a periodic unit) instead of a rectangle.")
@click.option("--method", type=click.Choice(METHODS), default="sat", show_default=True)
@click.option("--fix", "fixes", multiple=True, metavar="ROW,COL=TILE", help="Fix a tile (index or name); repeatable.")
@click.option("--time-limit", type=float, help="Seconds before giving up.")
@click.option("-o", "--output", "out", type=click.Path(dir_okay=False), help="Also draw the tiling found (.svg/.png).")
def solve_command(set_name: str, rows: int, cols: int, torus: bool, method: str, fixes: tuple[str, ...],
                  time_limit: float | None, out: str | None) -> None:
    """Does SET tile a ROWS x COLS rectangle (or torus) with the fixed tiles?"""
    ts = _tileset(set_name)
    result = solve(ts, rows, cols, torus=torus, fixed=_fixed(fixes), method=method, time_limit=time_limit)
    click.echo(f"{ts.name}: {result.describe()}")
    if result.tiles:
        names = ts.tile_names
        for row in result.grid.tolist():
            click.echo(" ".join(names[t] for t in row))
        if out:
            click.echo(f"wrote {write_wang_image(result.grid, ts, out)}")
