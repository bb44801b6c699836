"""Regenerate docs/images/curved.png: {7,3} and {5,4} in the Poincaré disc (true arcs) and
the icosahedron {3,5} on the sphere, side by side, drawn by tilekit itself.

Run: python docs/images/make_curved_image.py
"""

from __future__ import annotations

import re
from pathlib import Path

import cairosvg

from tilekit.plugins.curved import regular

HERE = Path(__file__).resolve().parent
PANEL = 360


def side_by_side(panels: list, out: Path, stroke_width_px: float = 0.6) -> None:
    """The tilings' whole patches as square SVG panels in a row, rasterized to ``out``."""
    parts = []
    for i, t in enumerate(panels):
        svg = t.render_svg(t.patch(), size=PANEL, stroke_width_px=stroke_width_px)
        parts.append(re.sub(r"^<svg ", f'<svg x="{i * PANEL}" y="0" ', svg, count=1))
    doc = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{len(panels) * PANEL}" height="{PANEL}">'
           + "".join(parts) + "</svg>")
    cairosvg.svg2png(bytestring=doc.encode(), write_to=str(out))


def main() -> None:
    side_by_side([regular(7, 3, depth=7), regular(5, 4, depth=6), regular(3, 5, samples=24)], HERE / "curved.png")


if __name__ == "__main__":
    main()
