"""Regenerate docs/images/stars.png: two uniform tilings of the hyperbolic plane that no
Wythoff symbol gives, found by the vertex-star pairing search and drawn by tilekit itself in
the Poincaré disc: 4.4.6.6 and 3.4.4.4.4 (records of catalogue/curved/stars.toml), faces
coloured by their number of sides.

Run: python docs/images/make_stars_image.py
"""

from __future__ import annotations

import re
from pathlib import Path

import cairosvg

from tilekit.plugins.curved import notation
from tilekit.plugins.curved.stars import StarTiling

HERE = Path(__file__).resolve().parent
PANEL = 360


def main() -> None:
    parts = []
    x = 0
    for cfg, pairing in _records(["4.4.6.6", "3.4.4.4.4"]):
        t = StarTiling(cfg, pairing=pairing, radius=3.5, samples=8)
        svg = t.render_svg(t.patch(t.default_region()), height=PANEL, stroke_width_px=0.6)
        width = int(re.search(r'width="(\d+)"', svg).group(1))
        parts.append(re.sub(r"^<svg ", f'<svg x="{x}" y="0" ', svg, count=1))
        x += width
    doc = f'<svg xmlns="http://www.w3.org/2000/svg" width="{x}" height="{PANEL}">' + "".join(parts) + "</svg>"
    cairosvg.svg2png(bytestring=doc.encode(), write_to=str(HERE / "stars.png"))


def _records(names: list[str]) -> list[tuple[str, str]]:
    """(configuration, shipped pairing) of each name."""
    from tilekit.plugins.curved import _star_configurations

    shipped = dict(_star_configurations())
    return [(name, shipped[notation.canonical(notation.parse(name))]) for name in names]


if __name__ == "__main__":
    main()
