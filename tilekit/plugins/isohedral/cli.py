"""``tilekit escherize GOAL -o DIR``: the isohedral tiles nearest a goal shape (§7.3), a thin
command over :func:`tilekit.plugins.isohedral.escher.escherize`.

Only click and the limits (a module without imports) are loaded at the top, so that
``tilekit --help``, which adds this command, does not import NumPy or scipy.
"""

from __future__ import annotations

from typing import Any

import click

from tilekit.cli_types import OUTPUT, BoundedInt
from tilekit.errors import TilekitError, optional
from tilekit.plugins.isohedral import escher_limits as lim


@click.command(name="escherize")
@click.argument("goals", nargs=-1, required=True, metavar="GOAL.svg|GOAL.json [GOAL_B]")
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
@click.option("--path-points", type=BoundedInt(1, lim.MAX_PATH_POINTS), default=lim.DEFAULT_PATH_POINTS,
              show_default=True, help="With two goals: interior points of the splitting path.")
@click.option("--heaven-hell", is_flag=True,
              help="With two goals: one tile resembling both, two-coloured so that neighbours differ "
                   "(Dress's Heaven and Hell patterns; the types whose tilings allow it).")
@click.option("--reflection/--no-reflection", default=True, show_default=True,
              help="Also match the mirror image of the goal (a type's tilings are closed under reflection).")
@click.option("--workers", type=BoundedInt(1, lim.MAX_WORKERS), default=1, show_default=True,
              help="Processes fitting types in parallel.")
@click.option("--seed", type=BoundedInt(0, 2**32 - 1), default=0, show_default=True,
              help="Seed of the random starts.")
def escherize_command(goals: tuple[str, ...], out: str, types: str | None, all_types: bool, top: int, samples: int,
                      starts: int, edge_points: int, path_points: int, heaven_hell: bool, reflection: bool,
                      workers: int, seed: int) -> None:
    """Find the isohedral tiles that best resemble GOAL (Kaplan and Salesin's Escherization).

    GOAL is an SVG file with one <path> (M/L/H/V/Z), <polygon> or <polyline>, or a JSON list
    of [x, y] points: a simple polygon. Every type's tiling vertex parameters and edge shapes
    are fitted; the best TOP are ranked by distance (0 = similar) and written to -o DIR.

    With two goals (dihedral Escherization, Kaplan and Salesin 2004) each type's tile is split
    in two by a path between two boundary points (its ends and --path-points interior points
    are fitted too) and ranked by the larger of the two pieces' distances from their goals,
    which are matched at their relative size (areas within 25x). A type's search is bounded
    by --starts Nelder-Mead runs of at most 40 (n + 1) evaluations each (n: the type's
    parameters, plus the two ends with two goals) and a 40-evaluation polish;
    with two goals every ordered pair of tile corners and edge midpoints (at most
    132) is screened first.

    \b
    Examples:
      tilekit escherize fish.svg --top 3 -o fish/
      tilekit escherize star.json --types IH1,IH4,IH28 --workers 2 -o star/
      tilekit escherize bird.json fish.json --types IH1,IH2 -o pair/
    """
    _check_goals(goals, heaven_hell)
    # measured start-up cost: the fit loads NumPy, shapely, scipy and the engine (~1 s), so
    # it is imported when the command runs, not when `tilekit --help` lists it
    from tilekit.plugins.isohedral import escher

    if types is not None and all_types:
        raise TilekitError("give --types or --all, not both")
    chosen = escher.parse_types(types) if types is not None else None
    if len(goals) == 2:
        _dihedral(goals, out, chosen, top, samples, starts, edge_points, path_points, heaven_hell, reflection,
                  workers, seed)
        return
    settings = escher.Settings(samples=samples, starts=starts, edge_points=edge_points,
                               reflection=reflection, seed=seed)
    _print_ranking(escher.fit_goal_file(goals[0], out, chosen, top=top, settings=settings, workers=workers), out)


def _check_goals(goals: tuple[str, ...], heaven_hell: bool) -> None:
    """One goal or two (two with --heaven-hell), and the fit's optional modules installed:
    checked before any work, each a line naming what is wrong (or the extra to install)."""
    if heaven_hell and len(goals) != 2:
        raise TilekitError("--heaven-hell needs two goals (GOAL_A GOAL_B): the one tile is matched to both")
    if len(goals) > 2:
        raise TilekitError(f"escherize takes one goal (monohedral) or two (dihedral), got {len(goals)}: "
                           + " ".join(goals[:4]))
    for module in ("scipy.optimize", "threadpoolctl"):
        optional(module, "escher", "tilekit escherize")


def _print_ranking(fit: Any, out: str) -> None:
    """The monohedral fit's ranking, the files written and how to reopen them."""
    best = fit.best
    click.echo(f"{fit.sides}-gon goal, {len(fit.types)} types, {fit.fitted} fitted"
               + (f", {len(fit.failed)} without a valid tiling" if fit.failed else ""))
    click.echo("rank  type   distance  note")
    for rank, r in enumerate(best, 1):
        note = "" if r.shrink == 1.0 else f"edge shapes shrunk to {r.shrink:g} to tile (fit {r.fitted_distance:.4f})"
        click.echo(f"{rank:>4}  {r.name:<5}  {r.distance:8.5f}  {note}".rstrip())
    click.echo(f"wrote {len(fit.written)} files to {out}")
    first = f"{out.rstrip('/')}/01-{best[0].name}.isohedral.json"
    click.echo(f"reopen: tilekit render --system {first} -o {best[0].name}.svg")
    click.echo("in the web editor (tilekit serve, then http://127.0.0.1:8000 and the path; also in ranking.json):")
    for rank, r in enumerate(best, 1):
        click.echo(f"{rank:>4}  {r.editor()}")


def _dihedral(goals: tuple[str, ...], out: str, chosen: list[int] | None, top: int, samples: int, starts: int,
              edge_points: int, path_points: int, heaven_hell: bool, reflection: bool, workers: int, seed: int) -> None:
    """``tilekit escherize GOAL_A GOAL_B``: the split tiles whose pieces resemble the goals
    (with ``--heaven-hell``: the two-coloured tiles that resemble both)."""
    # measured start-up cost: as the monohedral fit (NumPy, shapely, scipy, the engine, ~1 s)
    from tilekit.plugins.isohedral import dihedral, escher, heaven

    a = escher.read_goal(goals[0])
    b = escher.read_goal(goals[1])
    dihedral.check_goals(a, b)
    settings = dihedral.DihedralSettings(samples=samples, starts=starts, edge_points=edge_points,
                                         path_points=path_points, reflection=reflection, seed=seed)
    if heaven_hell:
        if chosen is not None:
            bad = [ih for ih in chosen if ih not in heaven.heaven_hell_types()]
            if bad:
                raise TilekitError(f"--heaven-hell: IH{bad[0]} has no two-colouring in which neighbouring tiles "
                                   "differ; valid types: " + ",".join(f"IH{t}" for t in heaven.heaven_hell_types()))
        results, failed = heaven.heaven_hell(a, b, chosen, settings=settings, workers=workers)
    else:
        results, failed = dihedral.escherize_dihedral(a, b, chosen, settings=settings, workers=workers)
    chosen = chosen or (heaven.heaven_hell_types() if heaven_hell else escher.unmarked_types())
    if not results:
        raise TilekitError(f"no type gave a valid tiling for {goals[0]} and {goals[1]}: "
                           + "; ".join(f"IH{ih}: {why}" for ih, why in failed[:3]))
    best = results[:top]
    written = dihedral.write_outputs(best, [a, b], out)
    click.echo(f"{len(a)}-gon and {len(b)}-gon goals, {len(chosen)} types, {len(results)} fitted"
               + (f", {len(failed)} without a valid tiling" if failed else ""))
    click.echo("rank  type   distance   goal A    goal B  note")
    for rank, r in enumerate(best, 1):
        note = "" if r.shrink == 1.0 else f"shapes shrunk to {r.shrink:g} to tile (fit {r.fitted_distance:.4f})"
        click.echo(f"{rank:>4}  {r.name:<5}  {r.distance:8.5f}  {r.distances[0]:8.5f}  {r.distances[1]:8.5f}  {note}".rstrip())
    click.echo(f"wrote {len(written)} files to {out}")
    kind = "hh" if heaven_hell else "split"
    first = f"{out.rstrip('/')}/01-{best[0].name}-{kind}.isohedral.json"
    click.echo(f"reopen: tilekit render --system {first} -o {best[0].name}-{kind}.svg")


@click.command(name="metamorphosis")
@click.argument("end", metavar="END.isohedral.json")
@click.option("--start", metavar="START.isohedral.json",
              help="The left keyframe (default: END's type and parameters with straight edges).")
@click.option("--columns", type=BoundedInt(2, 40), default=12, show_default=True,
              help="Strip width in tile-sized cells.")
@click.option("--rows", type=BoundedInt(1, 20), default=3, show_default=True, help="Strip height in tile-sized cells.")
@click.option("-o", "--output", "out", required=True, type=OUTPUT, help="The strip as .svg or .png.")
def metamorphosis_command(end: str, start: str | None, columns: int, rows: int, out: str) -> None:
    """Draw a strip whose tiles change from START's tile (left) to END's (right).

    END and START are isohedral spec files (what `tilekit escherize` writes, or the editor's
    export) of one type with the same parameters; edge shapes with the same numbers of points
    are interpolated edge by edge across the strip (parquet deformations, exercise 5.13;
    Escher's metamorphoses, §7.3). The strip is at most 40 x 20 tile-sized cells.

    \b
    Example:
      tilekit metamorphosis fish/01-IH3.isohedral.json --columns 10 -o morph.svg
    """
    import shapely  # start-up cost: loaded when the command runs, not by `tilekit --help`

    from tilekit.plugins.isohedral.engine import IsohedralTiling  # start-up cost: the engine
    from tilekit.plugins.isohedral.metamorphosis import metamorphosis  # start-up cost: the engine
    from tilekit.plugins.isohedral.spec import tiling_from_file  # start-up cost: the engine
    from tilekit.render import patch_to_svg, write_svg  # start-up cost: the renderer (shapely)

    last = tiling_from_file(end)
    if not isinstance(last, IsohedralTiling):
        raise TilekitError(f"{end}: a metamorphosis takes an unmarked isohedral tiling without a split")
    first = tiling_from_file(start) if start else IsohedralTiling(last.template.ih, list(last.params))
    if not isinstance(first, IsohedralTiling):
        raise TilekitError(f"{start}: a metamorphosis takes an unmarked isohedral tiling without a split")
    patch, box = metamorphosis(first, last, columns, rows)
    strip = patch.clip(shapely.box(*box))
    path = write_svg(patch_to_svg(strip), out)
    click.echo(f"wrote {path} ({len(strip)} tiles, {last.name}, {columns} x {rows})")
