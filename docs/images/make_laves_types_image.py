"""Regenerate docs/images/laves-types.png: Laves topologies of the sphere under small
face-transitive subgroups (``group=<orbifold>``), drawn by tilekit itself: the cube's square
under 332 (a half-turn only: J edges), under 3*2 (the square's mirrors through its edge
midpoints: U edges, each edge its own mirror image), and the rhombic dodecahedron's rhombus under
332 (no tile symmetry, four J edges), each coloured by its least perfect colouring.

Run: python docs/images/make_laves_types_image.py
"""

from __future__ import annotations

import sys
from pathlib import Path

from tilekit.plugins.curved.laves import LavesTiling

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from make_curved_image import side_by_side  # noqa: E402  (the panels' layout, one copy)

J = "0.3,0.15:0.6,-0.1"


def main() -> None:
    side_by_side([LavesTiling(symbol="| 2 2 3", group="332", edges={"a": J}, samples=24),
                  LavesTiling(symbol="| 2 2 3", group="3*2", edges={"a": "0.25,-0.12:0.4,0.1"}, samples=24),
                  LavesTiling("3.4.3.4", group="332", edges={"a": J, "c": "0.4,0.1"}, samples=24)],
                 HERE / "laves-types.png", stroke_width_px=0.8)


if __name__ == "__main__":
    main()
