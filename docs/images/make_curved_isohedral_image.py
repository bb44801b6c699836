"""Regenerate docs/images/curved-isohedral.png: three Escher-like isohedral tilings drawn by
tilekit itself: {6,4}'s hexagon with J and S edges in the Poincaré disc (group 4422, two
colours), {5,4}'s pentagon (group 4222, two colours), and the dodecahedron's pentagon deformed on
the sphere (group 332, three colours); and docs/images/curved-isohedral-symmetric.png: types whose
tiles have their own symmetry or mirror edges — {4,5} with U edges and a half-turn (5*2), {6,4}
with U edges and a three-fold turn (4*3), {5,4} with a mirror edge and J pairs hopped by turns (42*),
and the cube's square with J edges and a half-turn (332).

Run: python docs/images/make_curved_isohedral_image.py
"""

from __future__ import annotations

import re
from pathlib import Path

import cairosvg

from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling

HERE = Path(__file__).resolve().parent
PANEL = 360


def main() -> None:
    panels = [
        CurvedIsohedralTiling(6, 4, radius=5.0, edges={"a": "0.3,0.15:0.6,-0.12:0.8,0.05",
                                                       "b": "0.3,-0.12:0.7,0.15", "c": "0.25,0.12:0.4,0.1",
                                                       "d": "0.25,-0.12:0.4,-0.08"}),
        CurvedIsohedralTiling(5, 4, radius=5.0,
                              edges={"a": "0.25,0.15:0.5,0.2:0.75,-0.1", "b": "0.3,-0.15:0.7,0.12",
                                     "c": "0.2,0.12:0.4,0.1"}),
        CurvedIsohedralTiling(5, 3, edges={"a": "0.3,0.15:0.7,-0.1", "b": "0.3,-0.15:0.6,0.15",
                                           "c": "0.2,0.15:0.35,0.1"}),
    ]
    _strip(panels, "curved-isohedral.png")
    _strip([
        CurvedIsohedralTiling(4, 5, symbol="[abab; ba]", radius=5.0, edges={"a": "0.22,0.16:0.38,-0.08"}),
        CurvedIsohedralTiling(6, 4, symbol="[ababab; ba]", radius=5.0, edges={"a": "0.2,-0.12:0.36,0.1"}),
        CurvedIsohedralTiling(5, 4, symbol="[a+b+c+d+e+; a-e+d+c+b+]", radius=5.0,
                              edges={"b": "0.3,0.14:0.6,-0.1:0.8,0.05", "c": "0.3,-0.12:0.65,0.12"}),
        CurvedIsohedralTiling(4, 3, symbol="[a+b+a+b+; b+a+]", edges={"a": "0.3,0.15:0.65,-0.12"}),
    ], "curved-isohedral-symmetric.png")


def _strip(panels: list[CurvedIsohedralTiling], name: str) -> None:
    parts = []
    x = 0
    for t in panels:
        patch = t.patch()
        svg = t.render_svg(patch, height=PANEL, stroke_width_px=0.6)
        width = int(re.search(r'width="(\d+)"', svg).group(1))
        parts.append(re.sub(r"^<svg ", f'<svg x="{x}" y="0" ', svg, count=1))
        x += width
    doc = f'<svg xmlns="http://www.w3.org/2000/svg" width="{x}" height="{PANEL}">' + "".join(parts) + "</svg>"
    cairosvg.svg2png(bytestring=doc.encode(), write_to=str(HERE / name))


if __name__ == "__main__":
    main()
