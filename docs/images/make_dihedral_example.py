"""Regenerate docs/images/escherize-pair.png: dihedral Escherization of a bird and a fish.

The goals are tests/data/escher/bird.json and fish.json. The types (default IH1, IH2, IH3,
IH41) are fitted by ``tilekit.plugins.isohedral.dihedral.escherize_dihedral`` (the library call
behind ``tilekit escherize GOAL_A GOAL_B``); the left panel is the best split tile with each
goal aligned onto its piece (dashed), the right panel its dihedral tiling.

Run: python docs/images/make_dihedral_example.py [--types IH1,IH2,IH3,IH41]
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import cairosvg
import numpy as np

from tilekit.plugins.isohedral.dihedral import escherize_dihedral, pieces_svg
from tilekit.plugins.isohedral.escher import parse_types, read_goal

HERE = Path(__file__).resolve().parent
DATA = HERE.parent.parent / "tests" / "data" / "escher"
PANEL = 360


def inner(svg: str, x: int) -> str:
    """An SVG document as a nested <svg> panel at (x, 0), PANEL x PANEL pixels."""
    svg = re.sub(r"<\?xml[^>]*\?>", "", svg).strip()
    svg = re.sub(r'\swidth="[^"]*"', "", svg, count=1)
    svg = re.sub(r'\sheight="[^"]*"', "", svg, count=1)
    return svg.replace("<svg", f'<svg x="{x}" y="0" width="{PANEL}" height="{PANEL}"', 1)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--types", default="IH1,IH2,IH3,IH41")
    args = ap.parse_args()
    goals = [read_goal(DATA / "bird.json"), read_goal(DATA / "fish.json")]
    results, _ = escherize_dihedral(*goals, parse_types(args.types))
    best = results[0]
    tiling = best.tiling()
    outline = np.asarray(tiling.base.prototile.outline)
    centre = outline.mean(axis=0)
    half = 2.2 * float(np.ptp(outline, axis=0).max())
    patch = tiling.patch((centre[0] - half, centre[1] - half, centre[0] + half, centre[1] + half))
    right = tiling.render_svg(patch)
    svg = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{2 * PANEL}" height="{PANEL}">'
           f'<rect width="{2 * PANEL}" height="{PANEL}" fill="white"/>'
           + inner(pieces_svg(best, goals), 0) + inner(right, PANEL) + "</svg>")
    out = HERE / "escherize-pair.png"
    cairosvg.svg2png(bytestring=svg.encode(), write_to=str(out))
    print(f"wrote {out}: {best.name} d = {best.distance:.4f} (bird {best.distances[0]:.4f}, "
          f"fish {best.distances[1]:.4f})")


if __name__ == "__main__":
    main()
