"""``tilekit sample``: tile-based importance sampling (tilekit.sampling, docs/sampling.md)."""

from __future__ import annotations

import click

from tilekit.cli import base  # base.plugin_manager: tests replace it there
from tilekit.cli.base import (
    cli,
)
from tilekit.cli_types import OUTPUT, BoundedInt
from tilekit.errors import ParameterError

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
    result = sampling.sample(density, count, method=method, seed=seed, relax=relax, pm=base.plugin_manager(),
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
