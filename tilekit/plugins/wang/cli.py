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
from tilekit.progress import terminal_bar

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
    """Wang tiles: render fills with coloured triangles or textures, solve rectangles and tori,
    make textures from an example image (§7.5).

    \b
    Examples:
      tilekit wang render stochastic-2colour -o wang.svg
      tilekit wang solve jeandel-rao --rows 10 --cols 10
      tilekit wang texture pebbles.png --tile 64 -o tiles.png
      tilekit wang synth tiles.png --width 4096 --height 4096 -o texture.png
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
              help="CPU seconds the exact (SAT) solver may take when the set has no direct fill "
                   "(then a one-line error).")
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
              help="CPU seconds the solver (sat, builder or backtrack) may take before it gives up with a "
                   "one-line error.")
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


# ---------------------------------------------------------------------- textures (§7.5)

#: Spelled here so that ``tilekit --help`` does not import the texture modules (a test keeps
#: the copies equal): synth.METHODS, synth.MAX_SIDE, exemplars.KINDS, texture.MIN_TILE/MAX_TILE.
SYNTH_METHODS = ("auto", "random-access", "scanline")
MAX_TEXTURE_SIDE = 1 << 16
EXAMPLE_KINDS = ("noise", "pebbles", "bricks")
MIN_TEXTURE_TILE, MAX_TEXTURE_TILE = 8, 1024
#: Largest |--x0|, |--y0| (synth.MAX_ORIGIN).
MAX_TEXTURE_ORIGIN = 1 << 48


def _on_terminal() -> bool:
    import sys

    return sys.stderr.isatty()


@wang_group.command(name="example")
@click.argument("kind", type=click.Choice(EXAMPLE_KINDS))
@click.option("-o", "--output", "out", required=True, type=click.Path(dir_okay=False), help="Output .png.")
@click.option("--size", type=BoundedInt(32, 4096), default=256, show_default=True, help="Side in pixels.")
@click.option("--seed", type=BoundedInt(0), default=0, show_default=True)
def example_command(kind: str, out: str, size: int, seed: int) -> None:
    """Make an example image for `wang texture`: fractal noise, pebbles or bricks.

    The examples are generated by tilekit's own code from the seed (nothing is downloaded).

    \b
    Examples:
      tilekit wang example pebbles -o pebbles.png
      tilekit wang example noise --size 512 --seed 3 -o noise.png
    """
    # measured start-up cost: NumPy and the PNG writer load only when the command runs
    from tilekit.plugins.wang.exemplars import example
    from tilekit.pngstream import write_png  # start-up cost: as above

    if not out.lower().endswith(".png"):
        raise ParseError(f"output {out!r} must end in .png")
    write_png(out, example(kind, size, seed))
    click.echo(f"wrote {out} ({kind}, {size} x {size}, seed {seed})")


@wang_group.command(name="texture")
@click.argument("example_path", metavar="EXAMPLE", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "out", required=True, type=click.Path(dir_okay=False), help="Output atlas .png.")
@click.option("--set", "set_name", default="stochastic-2colour", show_default=True,
              help="Tile set: a shipped name or a .wang file (edge or corner tiles).")
@click.option("--tile", type=BoundedInt(MIN_TEXTURE_TILE, MAX_TEXTURE_TILE), default=128, show_default=True,
              help="Tile side in pixels (even).")
@click.option("--band", type=BoundedInt(0, MAX_TEXTURE_TILE // 2),
              help="How far (pixels) a cut may stray from the straight seam [default: tile / 4]; 0: straight seams.")
@click.option("--tries", type=BoundedInt(1, 1000), default=8, show_default=True,
              help="Random draws of the patch positions; the draw with the least cut error is kept.")
@click.option("--seed", type=BoundedInt(0), default=0, show_default=True)
def texture_command(example_path: str, out: str, set_name: str, tile: int, band: int | None, tries: int,
                    seed: int) -> None:
    """Make a textured Wang tile set from an EXAMPLE image and write it as an atlas PNG.

    Each edge colour (corner colour, for corner tiles) is a patch of the example; each tile
    joins its four patches along minimum-error cuts (Cohen et al. 2003; Efros and Freeman
    2001). The atlas carries the set, so `wang synth` needs nothing else. Needs Pillow
    (pip install 'tilekit[texture]').

    \b
    Examples:
      tilekit wang texture pebbles.png --set stochastic-2colour --tile 64 -o tiles.png
      tilekit wang texture noise.png --set corner-2colour --tile 128 --band 16 -o corner-tiles.png
    """
    # measured start-up cost: NumPy and Pillow load only when the command runs
    from tilekit.plugins.wang.texture import check_tile_size, make_texture_tiles, read_image

    if not out.lower().endswith(".png"):
        raise ParseError(f"output {out!r} must end in .png (the atlas is a PNG)")
    ts = _tileset(set_name)
    if tile % 2:
        raise ParseError(f"--tile {tile} must be even (a tile is cut into halves)")
    check_tile_size(tile, ts)
    if band is not None and band > tile // 2:
        raise ParseError(f"--band {band} must be at most half the tile ({tile // 2})")
    example, _ = read_image(example_path)
    tex = make_texture_tiles(example, ts, tile=tile, band=band, seed=seed, tries=tries, name=Path(example_path).name)
    tex.save(out)
    meta = tex.meta
    gain = meta["cut_error"] / meta["straight_error"] if meta["straight_error"] else 1.0
    click.echo(f"wrote {out}: {len(ts)} tiles of {tile} x {tile} px ({ts.name}, {ts.kind} tiles, "
               f"{len(meta['sources'])} patches of {meta['window']} px from {meta['example']})")
    click.echo(f"cut error {meta['cut_error']:.4g} = {gain:.3f} x the straight seams' {meta['straight_error']:.4g} "
               f"(band {meta['band']} px, best of {tries} draws)")


@wang_group.command(name="synth")
@click.argument("tiles_path", metavar="TILES", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "out", required=True, type=click.Path(dir_okay=False), help="Output .png.")
@click.option("--width", type=BoundedInt(1, MAX_TEXTURE_SIDE), required=True, help="Pixels (1..65536).")
@click.option("--height", type=BoundedInt(1, MAX_TEXTURE_SIDE), required=True, help="Pixels (1..65536).")
@click.option("--method", type=click.Choice(SYNTH_METHODS), default="auto", show_default=True,
              help="Fill: random access (hash of the lattice points) or the scanline fill; auto picks the one "
                   "the set allows.")
@click.option("--seed", type=BoundedInt(0), default=0, show_default=True)
@click.option("--x0", type=BoundedInt(-MAX_TEXTURE_ORIGIN, MAX_TEXTURE_ORIGIN), default=0, show_default=True,
              help="Left column of the window in the unbounded texture (random access only).")
@click.option("--y0", type=BoundedInt(-MAX_TEXTURE_ORIGIN, MAX_TEXTURE_ORIGIN), default=0, show_default=True,
              help="Top row of the window (random access only).")
@click.option("--compress", type=BoundedInt(0, 9), default=6, show_default=True, help="zlib level.")
@click.option("--threads", type=BoundedInt(0, 64), default=1, show_default=True,
              help="Compression threads (0: one per core).")
@click.option("--stats", is_flag=True, help="Print the seam error of the whole texture and its repetition.")
def synth_command(tiles_path: str, out: str, width: int, height: int, method: str, seed: int, x0: int, y0: int,
                  compress: int, threads: int, stats: bool) -> None:
    """Assemble a texture of WIDTH x HEIGHT pixels from the tile atlas TILES, streamed to a PNG.

    The PNG is written row block by row block, so memory does not grow with the size (up to
    65536 x 65536, the bound on the work); its size is estimated from its first rows and
    refused when it exceeds the free disk space.

    \b
    Examples:
      tilekit wang synth tiles.png --width 2048 --height 1024 -o texture.png
      tilekit wang synth corner-tiles.png --width 512 --height 512 --x0 100000 --y0 -7 -o window.png
    """
    # measured start-up cost: NumPy and Pillow load only when the command runs
    from tilekit.plugins.wang.synth import synthesize

    if not out.lower().endswith(".png"):
        raise ParseError(f"output {out!r} must end in .png")
    with terminal_bar(f"writing {Path(out).name}", height, "{task.completed}/{task.total} rows",
                      shown=width * height >= 1 << 26 and _on_terminal()) as progress:
        done = synthesize(tiles_path, out, width, height, method=method, seed=seed, x0=x0, y0=y0, level=compress,
                          threads=threads, progress=progress, stats=stats)
    click.echo(f"wrote {out} ({width} x {height}, {done['method']} fill of {done['tileset']}, "
               f"{done['bytes']:,} bytes; estimated {done['estimate']:,})")
    if stats:
        s, rep = done["seams"], done["repetition"]
        click.echo(f"seam error: {s['edge']:.4g} across tile edges, {s['inside']:.4g} inside tiles "
                   f"(ratio {s['ratio']:.3f})")
        click.echo(f"repetition: autocorrelation peak {rep['peak']:.3f} at lag {rep['lag']} "
                   f"(a {rep['side']} px crop; a periodic tiling of one tile scores 1)")


@wang_group.command(name="scatter")
@click.option("-o", "--output", "out", required=True, type=click.Path(dir_okay=False),
              help="Output .svg or .png (primitives), or .csv / .npy (points).")
@click.option("--width", type=BoundedInt(1, MAX_TEXTURE_SIDE), default=800, show_default=True)
@click.option("--height", type=BoundedInt(1, MAX_TEXTURE_SIDE), default=600, show_default=True)
@click.option("--tile", type=BoundedInt(2, 1 << 20), default=128, show_default=True, help="Tile side in pixels.")
@click.option("--per-tile", type=BoundedInt(1, 64), default=16, show_default=True, help="Points per tile (about).")
@click.option("--motifs", type=click.Path(dir_okay=False),
              help="TOML file of SVG primitives ([motifs] NAME = '<svg .../>'); default: dots.")
@click.option("--seed", type=BoundedInt(0), default=0, show_default=True)
@click.option("--x0", type=BoundedInt(-MAX_TEXTURE_ORIGIN, MAX_TEXTURE_ORIGIN), default=0, show_default=True)
@click.option("--y0", type=BoundedInt(-MAX_TEXTURE_ORIGIN, MAX_TEXTURE_ORIGIN), default=0, show_default=True)
def scatter_command(out: str, width: int, height: int, tile: int, per_tile: int, motifs: str | None, seed: int,
                    x0: int, y0: int) -> None:
    """Strew points (Poisson-disk-like) or SVG primitives over a window of the plane.

    Points come from corner Wang tiles looked up by a hash (random access), so any window is
    the same as inside a larger one; each primitive's choice, turn and size are hashed too.

    \b
    Examples:
      tilekit wang scatter --motifs catalogue/wang/textures/scatter-garden.toml -o garden.svg
      tilekit wang scatter --width 4096 --height 4096 --per-tile 32 -o points.npy
    """
    # measured start-up cost: NumPy and the sampler's tiles load only when the command runs
    from tilekit.plugins.wang.scatter import load_motifs, scatter_points, scatter_svg
    from tilekit.render import write_svg  # start-up cost: as above
    from tilekit.sampling import write_points

    suffix = Path(out).suffix.lower()
    if suffix not in (".svg", ".png", ".csv", ".npy"):
        raise ParseError(f"output {out!r} must end in .svg, .png, .csv or .npy")
    shapes = load_motifs(motifs) if motifs else None
    points, ids = scatter_points(x0, y0, width, height, tile=tile, per_tile=per_tile, seed=seed)
    if suffix in (".csv", ".npy"):
        write_points(points, out)
    else:
        spacing = tile / per_tile ** 0.5
        write_svg(scatter_svg(points, ids, width, height, spacing, shapes, x0, y0), out)
    click.echo(f"wrote {out} ({len(points):,} points, about {per_tile} per {tile} px tile)")
