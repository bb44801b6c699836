"""``tilekit escherize-penrose GOAL [GOAL_B] -o DIR``: Penrose rhombs deformed to resemble a
goal (§7.3 with §6.3's quasivertices), a thin command over
:func:`tilekit.plugins.substitution.penrose_escher.escherize_penrose`.

Only click and import-free limits are loaded at the top, so that ``tilekit --help``, which
adds this command, does not import NumPy or scipy.
"""

from __future__ import annotations

import click

from tilekit.cli_types import BoundedInt
from tilekit.errors import TilekitError, optional
from tilekit.limits import DEFAULT_SAMPLES, MAX_SAMPLES, MIN_SAMPLES
from tilekit.plugins.substitution import penrose_limits as lim


@click.command(name="escherize-penrose")
@click.argument("goals", nargs=-1, required=True, metavar="GOAL.svg|GOAL.json [GOAL_B]")
@click.option("-o", "--output", "out", required=True, type=click.Path(file_okay=False),
              help="Directory for penrose.json, tiles.svg and patch.svg.")
@click.option("--tiling", "which", default="p3", show_default=True, metavar="p3|p2",
              help="The Penrose tiling whose quasivertex parameters are fitted: p3 (thick and thin rhombs, "
                   "Figure 6.13) or p2 (kite and dart, derived from P2 patches).")
@click.option("--samples", type=BoundedInt(MIN_SAMPLES, MAX_SAMPLES), default=DEFAULT_SAMPLES, show_default=True,
              help="Points each outline is resampled to by arc length.")
@click.option("--starts", type=BoundedInt(1, lim.MAX_STARTS), default=lim.DEFAULT_STARTS, show_default=True,
              help=f"Starts of the parameter search, each at most {lim.START_EVALUATIONS} evaluations.")
@click.option("--edge-points", type=BoundedInt(1, lim.MAX_EDGE_POINTS), default=lim.DEFAULT_EDGE_POINTS,
              show_default=True, help="Interior control points of each of the edge shapes a, b, c, f.")
@click.option("--reflection/--no-reflection", default=True, show_default=True,
              help="Also match the mirror image of a goal.")
@click.option("--seed", type=BoundedInt(0, 2**32 - 1), default=0, show_default=True,
              help="Seed of the random starts.")
def escherize_penrose_command(goals: tuple[str, ...], out: str, which: str, samples: int, starts: int,
                              edge_points: int, reflection: bool, seed: int) -> None:
    """Deform the Penrose P3 rhombs (or, with --tiling p2, the kite and dart) to resemble GOAL
    (Penrose Escherization, §7.3 and §6.3).

    The quasivertex parameters r1, theta1, r2, theta2 (Figure 6.13 for P3, derived for P2) and
    the interlocking edge shapes a, b, c, f (Figure 6.14; their partners get the complements)
    are fitted with the Escherization metric. With one goal both tiles are compared with it;
    with two, the thick rhomb (the kite) with GOAL and the thin one (the dart) with GOAL_B. The
    score is the larger of the two
    distances (0 = similar). The result is checked as a Penrose tiling (a validated patch, the
    matching rules on every shared edge) and written to -o DIR.

    Budget: --starts Nelder-Mead runs of at most 200 evaluations each (every evaluation
    projects the edge shapes in 6 linear steps), then at most 4 rounds of a least-squares
    polish of at most 60 evaluations each; about 5-15 s of CPU.

    \b
    Examples:
      tilekit escherize-penrose fish.json -o penrose-fish/
      tilekit escherize-penrose fish.json bird.json --starts 2 -o penrose-pair/
      tilekit escherize-penrose --tiling p2 kite-goal.json dart-goal.json -o p2/
    """
    if len(goals) > 2:
        raise TilekitError(f"escherize-penrose takes one goal or two (thick or kite, thin or dart), got {len(goals)}: "
                           + " ".join(goals[:4]))
    for module in ("scipy.optimize", "threadpoolctl"):
        optional(module, "escher", "tilekit escherize-penrose")
    # measured start-up cost: the fit loads NumPy, shapely, scipy and the systems (~1 s), so it
    # is imported when the command runs, not when `tilekit --help` lists it
    from tilekit.escher import read_goal
    from tilekit.plugins.substitution import penrose_escher as pe

    pe.check_tiling(which)
    targets = [read_goal(g) for g in goals]
    settings = pe.PenroseSettings(samples=samples, starts=starts, edge_points=edge_points, reflection=reflection,
                                  seed=seed)
    result = pe.escherize_penrose(*targets, tiling=which, settings=settings)
    written = pe.write_outputs(result, targets, out)
    what = " and ".join(f"{len(t)}-gon" for t in targets)
    click.echo(f"{what} goal{'s' if len(targets) > 1 else ''}, {result.system}, {settings.starts} starts, "
               f"{result.evaluations} evaluations")
    note = "" if result.shrink == 1.0 else f"  (edge shapes shrunk to {result.shrink:g} to tile; fit {result.fitted_distance:.4f})"
    first, second = pe.GOAL_TILES[result.system]
    click.echo(f"distance {result.distance:.5f}  {first} {result.distances[0]:.5f}  {second} {result.distances[1]:.5f}{note}")
    click.echo("quasivertex " + ", ".join(f"{k}={v:.4g}" for k, v in result.params.items()))
    click.echo(f"wrote {len(written)} files to {out}")
    click.echo("render: tilekit render " + " ".join(result.render_options()) + " -o penrose.svg")
