"""Regenerate docs/images/uniform.png: three uniform tilings by Wythoff's construction, drawn
by tilekit itself: the truncated {7,3} (3.14.14, 2 3 | 7) in the Poincaré disc, the snub cube
(3.3.3.3.4, | 2 3 4) on the sphere, and the snub {4,5} (3.3.4.3.5, | 2 4 5) in the upper
half-plane.

Run: python docs/images/make_uniform_image.py
"""

from __future__ import annotations

import re
from pathlib import Path

import cairosvg

from tilekit.plugins.curved import uniform_tiling

HERE = Path(__file__).resolve().parent
PANEL = 360


def main() -> None:
    panels = [uniform_tiling("3.14.14", radius=4.0), uniform_tiling("3.3.3.3.4", samples=24),
              uniform_tiling("3.3.4.3.5", radius=3.5, plane="halfplane")]
    parts = []
    x = 0
    for t in panels:
        patch = t.patch(t.default_region())
        svg = t.render_svg(patch, height=PANEL, stroke_width_px=0.6)
        width = int(re.search(r'width="(\d+)"', svg).group(1))
        parts.append(re.sub(r"^<svg ", f'<svg x="{x}" y="0" ', svg, count=1))
        x += width
    doc = f'<svg xmlns="http://www.w3.org/2000/svg" width="{x}" height="{PANEL}">' + "".join(parts) + "</svg>"
    cairosvg.svg2png(bytestring=doc.encode(), write_to=str(HERE / "uniform.png"))


if __name__ == "__main__":
    main()
