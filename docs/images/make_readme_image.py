"""Regenerate docs/images/readme.png: three families side by side, drawn by tilekit itself.

Run: python docs/images/make_readme_image.py
"""

from __future__ import annotations

import re
from pathlib import Path

import cairosvg

from tilekit.plugins import catalogue_records, get_family
from tilekit.render import patch_to_svg

HERE = Path(__file__).resolve().parent
PANEL = 420


def tiling(name: str):
    record = next(r for r in catalogue_records() if r.name == name)
    return get_family(record.family).from_spec(record.spec)


def panel(patch, region, x_offset: int) -> str:
    svg = patch_to_svg(patch, region=region, size=PANEL)
    inner = re.sub(r"^<svg ", f'<svg x="{x_offset}" y="0" ', svg, count=1)
    return inner


def main() -> None:
    ih = tiling("IH21").configure(
        edges=["a=0,0:0.3,0.15:0.6,-0.1:1,0", "b=0,0:0.3,-0.15:0.7,0.15:1,0", "d=0,0:0.35,0.2:1,0"]
    )
    penrose = tiling("penrose-p3").configure(r1=0.15, theta1=30, r2=0.25, theta2=-15)
    hat = tiling("hat")
    panels = [
        (ih, (-4, -4, 4, 4)),
        (penrose, (-6, -6, 6, 6)),
        (hat, (-12, -12, 12, 12)),
    ]
    gap = 16
    parts = []
    for i, (t, region) in enumerate(panels):
        parts.append(panel(t.patch(region), region, i * (PANEL + gap)))
    width = len(panels) * PANEL + (len(panels) - 1) * gap
    doc = (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{PANEL}">'
        + "".join(parts)
        + "</svg>"
    )
    cairosvg.svg2png(bytestring=doc.encode(), write_to=str(HERE / "readme.png"))


if __name__ == "__main__":
    main()
