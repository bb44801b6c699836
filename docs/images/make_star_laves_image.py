"""Regenerate docs/images/star-laves-escher.png: Escher-like tiles on the duals of two
non-Wythoffian uniform tilings of the hyperbolic plane, drawn by tilekit itself in the Poincaré
disc, each under the rotations of its group: [3^3.6^2] (3222: S edges and a J pair, four
colours), [3.6.3.6.6] (3322: two J pairs and an S edge, six colours) and [4^2.6^2] (3222: two S
edges and a J pair, two colours); tiles coloured by the least perfect colouring.

Run: python docs/images/make_star_laves_image.py
"""

from __future__ import annotations

# the panels side by side: the isohedral image's helper (this folder is the script's path)
from make_curved_isohedral_image import _strip

from tilekit.plugins.curved.starlaves import StarLavesTiling

RADIUS = 3.5


def main() -> None:
    _strip([
        StarLavesTiling("[3^3.6^2]", group="rotations", radius=RADIUS,
                        edges={"a": "0.2,0.12:0.35,0.1", "c": "0.3,0.14:0.6,-0.1:0.8,0.05"}),
        StarLavesTiling("[3.6.3.6.6]", group="rotations", radius=RADIUS,
                        edges={"b": "0.25,0.14:0.5,-0.1:0.75,0.06", "d": "0.3,-0.12:0.6,0.1"}),
        StarLavesTiling("[4^2.6^2]", group="rotations", radius=RADIUS, edges={"b": "0.3,-0.14:0.65,0.12"}),
    ], "star-laves-escher.png")


if __name__ == "__main__":
    main()
