"""``tilekit wang ...``: thin commands over the Wang library (render with triangles, solve).

``tilekit wang render SET -o FILE`` draws a fill with the four-triangle picture (or a
texture file, exercise 6.8); ``tilekit wang solve SET --rows R --cols C`` answers the
rectangle/torus question with a chosen solver. SET is a shipped set name or a .wang file.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import click

from tilekit import limits
from tilekit.cli_types import OUTPUT, POSITIVE, BoundedInt, FiniteFloat
from tilekit.errors import ParseError

if TYPE_CHECKING:  # pragma: no cover
    from tilekit.plugins.wang.tileset import WangTileSet

#: The choices of ``--method``: the fill methods (tilekit.plugins.wang.tiling.FILL_METHODS) and
#: the solvers (tilekit.plugins.wang.solve.METHODS), spelled here so that ``tilekit --help``
#: does not import them (a test keeps the copies equal).
FILL_CHOICES = ("auto", "random-access", "scanline", "periodic", "solver")
SOLVE_CHOICES = ("sat", "builder", "backtrack")

#: Largest image side of ``wang render --size`` (pixels): limits.MAX_PNG_PIXELS is its square.
MAX_SIZE = 10_000


def _tileset(name: str) -> WangTileSet:
    # measured start-up cost: the tile-set module loads NumPy (~0.2 s); the commands' bodies
    # import the library, so `tilekit --help` (which adds this group) stays cheap
    from tilekit.plugins.wang.tileset import get_tileset, load_tileset

    if name.endswith(".wang") or Path(name).is_file():
        return load_tileset(name)
    return get_tileset(name)


def _fixed(items: tuple[str, ...]) -> dict[tuple[int, int], str | int]:
    out: dict[tuple[int, int], str | int] = {}
    for item in items:
        pos, sep, tile = item.partition("=")
        bad = ParseError(f"--fix {item[:60]!r} is not ROW,COL=TILE (e.g. 0,3=a or 0,3=5)")
        parts = pos.split(",")
        if len(parts) != 2 or not all(p.strip().isascii() and p.strip().isdigit() and len(p.strip()) < 10 for p in parts):
            raise bad
        i, j = (int(v) for v in parts)
        if not sep or not tile:
            raise bad
        small_int = tile.isascii() and tile.isdigit() and len(tile) < 10
        out[(i, j)] = int(tile) if small_int else tile
    return out


@click.group(name="wang")
def wang_group() -> None:
    """Wang tiles: render fills with coloured triangles or textures, solve rectangles and tori.

    \b
    Examples:
      tilekit wang render stochastic-2colour -o wang.svg
      tilekit wang solve jeandel-rao --rows 10 --cols 10
    """


@wang_group.command(name="render")
@click.argument("set_name", metavar="SET")
@click.option("-o", "--output", "out", required=True, type=OUTPUT, help="Output .svg or .png.")
@click.option("--rows", type=POSITIVE, default=12, show_default=True)
@click.option("--cols", type=POSITIVE, default=16, show_default=True)
@click.option("--seed", type=BoundedInt(0), default=0, show_default=True)
@click.option("--method", type=click.Choice(FILL_CHOICES), default="auto",
              show_default=True, help="How to fill the grid.")
@click.option("--texture", type=click.Path(exists=True, dir_okay=False), help="TOML file of SVG motifs per edge colour.")
@click.option("--size", type=BoundedInt(16, MAX_SIZE), default=800, show_default=True,
              help="Image size in pixels (the longer side).")
@click.option("--max-tiles", type=POSITIVE, default=limits.MAX_GRID_CELLS, show_default=True,
              help="Refuse grids of more than N cells.")
@click.option("--time-limit", type=FiniteFloat(limits.MAX_SOLVER_SECONDS, min=1e-3),
              default=limits.DEFAULT_SOLVER_SECONDS, show_default=True,
              help="Seconds the exact solver may take when the set has no direct fill (then a one-line error).")
def render_command(set_name: str, out: str, rows: int, cols: int, seed: int, method: str, texture: str | None,
                   size: int, max_tiles: int, time_limit: float) -> None:
    """Fill a ROWS x COLS grid with SET and draw it.

    \b
    Examples:
      tilekit wang render stochastic-2colour --rows 20 --cols 30 -o wang.svg
      tilekit wang render jeandel-rao --rows 8 --cols 8 --method solver -o jr.png
    """
    # measured start-up cost: the fills and the renderer load NumPy, shapely and the solvers
    from tilekit.plugins.wang.render import write_wang_image
    from tilekit.plugins.wang.tiling import WangTiling  # start-up cost: as above

    limits.refuse_over("grid cells", rows * cols, max_tiles, "--max-tiles")
    ts = _tileset(set_name)
    grid = WangTiling(ts, seed=seed, method=method, time_limit=time_limit).grid(0, 0, rows, cols)
    path = write_wang_image(grid, ts, out, texture=texture, size=size)
    click.echo(f"wrote {path} ({rows * cols} tiles of {ts.name})")


@wang_group.command(name="solve")
@click.argument("set_name", metavar="SET")
@click.option("--rows", type=POSITIVE, required=True)
@click.option("--cols", type=POSITIVE, required=True)
@click.option("--torus", is_flag=True, help="Ask for a torus (a periodic unit) instead of a rectangle.")
@click.option("--method", type=click.Choice(SOLVE_CHOICES), default="sat", show_default=True)
@click.option("--fix", "fixes", multiple=True, metavar="ROW,COL=TILE", help="Fix a tile (index or name); repeatable.")
@click.option("--time-limit", type=FiniteFloat(limits.MAX_SOLVER_SECONDS, min=1e-3),
              default=limits.DEFAULT_SOLVER_SECONDS, show_default=True,
              help="Seconds before the solver gives up with a one-line error.")
@click.option("-o", "--output", "out", type=OUTPUT, help="Also draw the tiling found (.svg/.png).")
@click.option("--max-tiles", type=POSITIVE, default=limits.MAX_SOLVE_CELLS, show_default=True,
              help="Refuse grids of more than N cells.")
@click.option("--max-variables", type=POSITIVE, default=limits.MAX_SAT_VARIABLES, show_default=True,
              help="Refuse SAT encodings of more than N variables (cells x tiles, edges x colours); "
                   "encodings that would not fit in memory are refused too.")
def solve_command(set_name: str, rows: int, cols: int, torus: bool, method: str, fixes: tuple[str, ...],
                  time_limit: float, out: str | None, max_tiles: int, max_variables: int) -> None:
    """Does SET tile a ROWS x COLS rectangle (or torus) with the fixed tiles?

    \b
    Examples:
      tilekit wang solve jeandel-rao --rows 10 --cols 10
      tilekit wang solve jeandel-rao --rows 6 --cols 6 --torus --method builder
      tilekit wang solve my.wang --rows 4 --cols 4 --fix 0,0=a -o found.svg
    """
    # measured start-up cost: the solvers load NumPy, the builder and python-sat (~0.5-1 s)
    from tilekit.plugins.wang.render import write_wang_image
    from tilekit.plugins.wang.solve import solve  # start-up cost: as above

    limits.refuse_over("grid cells", rows * cols, max_tiles, "--max-tiles")
    ts = _tileset(set_name)
    options = {"max_variables": max_variables} if method == "sat" else {}
    result = solve(ts, rows, cols, torus=torus, fixed=_fixed(fixes), method=method, time_limit=time_limit, **options)
    click.echo(f"{ts.name}: {result.describe()}")
    if result.tiles:
        names = ts.tile_names
        for row in result.grid.tolist():
            click.echo(" ".join(names[t] for t in row))
        if out:
            click.echo(f"wrote {write_wang_image(result.grid, ts, out)}")
