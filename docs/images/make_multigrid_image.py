"""Regenerate docs/images/multigrid.png: the multigrid tilings of orders 5, 8 and 12, the
last one drawn around (10^6, 10^6), side by side, drawn by tilekit itself.

Run: python docs/images/make_multigrid_image.py
"""

from __future__ import annotations

import re
from pathlib import Path

import cairosvg

from tilekit.plugins.quasiperiodic import tiling
from tilekit.render import patch_to_svg

HERE = Path(__file__).resolve().parent
PANEL = 360


def main() -> None:
    panels = [(5, (0.0, 0.0)), (8, (0.0, 0.0)), (12, (1e6, 1e6))]
    parts = []
    for i, (n, (x, y)) in enumerate(panels):
        region = (x - 9, y - 9, x + 9, y + 9)
        svg = patch_to_svg(tiling(n).patch(region), region=region, size=PANEL)
        parts.append(re.sub(r"^<svg ", f'<svg x="{i * PANEL}" y="0" ', svg, count=1))
    doc = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{len(panels) * PANEL}" height="{PANEL}">'
           + "".join(parts) + "</svg>")
    cairosvg.svg2png(bytestring=doc.encode(), write_to=str(HERE / "multigrid.png"))


if __name__ == "__main__":
    main()
