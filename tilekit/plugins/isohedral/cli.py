"""``tilekit escherize GOAL -o DIR``: the isohedral tiles nearest a goal shape (§7.3), a thin
command over :func:`tilekit.plugins.isohedral.escher.escherize`.

Only click and the limits (a module without imports) are loaded at the top, so that
``tilekit --help``, which adds this command, does not import NumPy or scipy.
"""

from __future__ import annotations

import click

from tilekit.cli_types import BoundedInt
from tilekit.errors import TilekitError, optional
from tilekit.plugins.isohedral import escher_limits as lim


@click.command(name="escherize")
@click.argument("goal", metavar="GOAL.svg|GOAL.json")
@click.option("-o", "--output", "out", required=True, type=click.Path(file_okay=False),
              help="Directory for the specs, tile and tiling SVGs and ranking.json.")
@click.option("--types", metavar="IH1,IH4,...", help="The types to try (default: all 81 unmarked types).")
@click.option("--all", "all_types", is_flag=True, help="Try all 81 unmarked types (the default).")
@click.option("--top", type=BoundedInt(1, lim.MAX_TOP), default=lim.DEFAULT_TOP, show_default=True,
              help="How many of the best types to write.")
@click.option("--samples", type=BoundedInt(lim.MIN_SAMPLES, lim.MAX_SAMPLES), default=lim.DEFAULT_SAMPLES,
              show_default=True, help="Points each outline is resampled to by arc length.")
@click.option("--starts", type=BoundedInt(1, lim.MAX_STARTS), default=lim.DEFAULT_STARTS, show_default=True,
              help="Starts of the parameter search per type.")
@click.option("--edge-points", type=BoundedInt(1, lim.MAX_EDGE_POINTS), default=lim.DEFAULT_EDGE_POINTS,
              show_default=True, help="Interior control points of each fundamental edge shape.")
@click.option("--reflection/--no-reflection", default=True, show_default=True,
              help="Also match the mirror image of the goal (a type's tilings are closed under reflection).")
@click.option("--workers", type=BoundedInt(1, lim.MAX_WORKERS), default=1, show_default=True,
              help="Processes fitting types in parallel.")
@click.option("--seed", type=BoundedInt(0, 2**32 - 1), default=0, show_default=True,
              help="Seed of the random starts.")
def escherize_command(goal: str, out: str, types: str | None, all_types: bool, top: int, samples: int, starts: int,
                      edge_points: int, reflection: bool, workers: int, seed: int) -> None:
    """Find the isohedral tiles that best resemble GOAL (Kaplan and Salesin's Escherization).

    GOAL is an SVG file with one <path> (M/L/H/V/Z), <polygon> or <polyline>, or a JSON list
    of [x, y] points: a simple polygon. Every type's tiling vertex parameters and edge shapes
    are fitted; the best TOP are ranked by distance (0 = similar) and written to -o DIR.

    \b
    Examples:
      tilekit escherize fish.svg --top 3 -o fish/
      tilekit escherize star.json --types IH1,IH4,IH28 --workers 2 -o star/
    """
    # measured start-up cost: the fit loads NumPy, shapely, scipy and the engine (~1 s), so
    # it is imported when the command runs, not when `tilekit --help` lists it
    # every optional module the fit imports later, checked before any work: one line naming the extra
    for module in ("scipy.optimize", "threadpoolctl"):
        optional(module, "escher", "tilekit escherize")
    from tilekit.plugins.isohedral import escher

    if types is not None and all_types:
        raise TilekitError("give --types or --all, not both")
    chosen = escher.parse_types(types) if types is not None else escher.unmarked_types()
    target = escher.read_goal(goal)
    settings = escher.Settings(samples=samples, starts=starts, edge_points=edge_points,
                               reflection=reflection, seed=seed)
    results, failed = escher.escherize(target, chosen, settings=settings, workers=workers)
    if not results:
        raise TilekitError(f"no type gave a valid tiling for {goal}: "
                           + "; ".join(f"IH{ih}: {why}" for ih, why in failed[:3]))
    best = results[:top]
    written = escher.write_outputs(best, target, out)
    click.echo(f"{len(target)}-gon goal, {len(chosen)} types, {len(results)} fitted"
               + (f", {len(failed)} without a valid tiling" if failed else ""))
    click.echo("rank  type   distance  note")
    for rank, r in enumerate(best, 1):
        note = "" if r.shrink == 1.0 else f"edge shapes shrunk to {r.shrink:g} to tile (fit {r.fitted_distance:.4f})"
        click.echo(f"{rank:>4}  {r.name:<5}  {r.distance:8.5f}  {note}".rstrip())
    click.echo(f"wrote {len(written)} files to {out}")
    first = f"{out.rstrip('/')}/01-{best[0].name}.isohedral.json"
    click.echo(f"reopen: tilekit render --system {first} -o {best[0].name}.svg")
    click.echo("in the web editor (tilekit serve, then http://127.0.0.1:8000 and the path; also in ranking.json):")
    for rank, r in enumerate(best, 1):
        click.echo(f"{rank:>4}  {r.editor()}")
