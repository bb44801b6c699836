"""Regenerate docs/images/curved-stereographic.png: tilings of the sphere in stereographic
projection (``--set plane=stereographic``), drawn by tilekit itself: the icosahedron from the
centre of a face, the truncated icosahedron (5.6.6) from the centre of a pentagon, and a
curved-isohedral tile on the dodecahedron's pentagon (J edges) from the centre of a tile.
Every edge is the SVG arc through its projected ends and midpoint; the pole's tile is the
outside.

Run: python docs/images/make_curved_stereographic_image.py
"""

from __future__ import annotations

import sys
from pathlib import Path

from tilekit.plugins.curved import regular, uniform_tiling
from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from make_curved_image import side_by_side  # noqa: E402  (the panels' layout, one copy)


def main() -> None:
    side_by_side([regular(3, 5, plane="stereographic"), uniform_tiling("5.6.6", plane="stereographic"),
                  CurvedIsohedralTiling(5, 3, pairing="a a b b c", edges={"a": "0.3,0.12:0.6,-0.1", "c": "0.3,0.1"},
                                        plane="stereographic")],
                 HERE / "curved-stereographic.png", stroke_width_px=0.8)


if __name__ == "__main__":
    main()
