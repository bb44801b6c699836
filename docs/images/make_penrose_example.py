"""Regenerate docs/images/escherize-penrose.png: the Penrose P3 rhombs fitted to the fish.

The goal is tests/data/escher/fish.json; ``escherize_penrose`` (the library call behind
``tilekit escherize-penrose``) fits the quasivertex parameters and the edge shapes a, b, c, f
with both rhombs compared with the fish. Left: the thick and thin rhombs with the goal aligned
onto each (dashed); right: a patch of the deformed tiling.

Run: python docs/images/make_penrose_example.py [--starts N]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import cairosvg
import shapely
from make_escher_example import PANEL, inner  # the panel layout of the other Escherization pictures

from tilekit.escher import read_goal
from tilekit.plugins.substitution import penrose_escher as pe

HERE = Path(__file__).resolve().parent
DATA = HERE.parent.parent / "tests" / "data" / "escher"


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser()
    ap.add_argument("--starts", type=int, default=4)
    return ap


def main() -> None:
    args = build_parser().parse_args()
    goal = read_goal(DATA / "fish.json")
    result = pe.escherize_penrose(goal, settings=pe.PenroseSettings(starts=args.starts))
    tiling = result.tiling()
    patch = tiling.patch(shapely.box(-3.5, -3.5, 3.5, 3.5))
    panels = inner(pe.tiles_svg(result, [goal]), 0) + inner(tiling.render_svg(patch), PANEL)
    svg = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{2 * PANEL}" height="{PANEL}">'
           f'<rect width="100%" height="100%" fill="white"/>{panels}</svg>')
    cairosvg.svg2png(bytestring=svg.encode(), write_to=str(HERE / "escherize-penrose.png"))
    print(f"d = {result.distance:.4f} (thick {result.distances[0]:.4f}, thin {result.distances[1]:.4f}); "
          + ", ".join(f"{k}={v:.4g}" for k, v in result.params.items()))


if __name__ == "__main__":
    main()
