"""Regenerate docs/images/k-uniform-2.png (and -3): every k-uniform tiling, drawn by tilekit.

Each panel is the tiling found by the D-symbol search, tiles coloured by polygon size, with a
dot on every vertex coloured by its vertex orbit — the orbits computed by
``tilekit.symmetry.vertex_orbits`` from the tiling's symmetry group, not taken from the search.

Run: python docs/images/make_kuniform_sheet.py [K ...]   (default: 2)
"""

from __future__ import annotations

import html
import re
import sys
from pathlib import Path

import cairosvg
import numpy as np

from tilekit.plugins.kuniform.dsymbol import DSymbol
from tilekit.plugins.kuniform.search import chunks, records_for, tiling_of
from tilekit.regular.notation import VertexType
from tilekit.render import patch_to_svg
from tilekit.symmetry import vertex_orbits

HERE = Path(__file__).resolve().parent
PANEL = 240  # pixels per panel for k = 2; larger k get smaller panels (file size)
TITLE = 34
COLUMNS = 5
HALF = 5.0  # the panel shows [-HALF, HALF]^2
ORBIT_COLOURS = ("#111111", "#d62728", "#ffffff", "#9467bd", "#17becf", "#bcbd22")


def dots(tiling) -> str:
    points, orbit = vertex_orbits(tiling)
    lattice = np.array([[i, j] for i in range(-12, 13) for j in range(-12, 13)]) @ np.array([tiling.v1, tiling.v2])
    out = ['<g transform="scale(1,-1)" stroke="#000" stroke-width="0.03">']
    for p, o in zip(points, orbit):
        for q in p + lattice:
            if abs(q[0]) <= HALF and abs(q[1]) <= HALF:
                out.append(f'<circle cx="{q[0]:.4f}" cy="{q[1]:.4f}" r="0.13" fill="{ORBIT_COLOURS[int(o) % 6]}"/>')
    out.append("</g>")
    return "\n".join(out)


def panel(name: str, symbol: DSymbol, x: int, y: int) -> str:
    tiling = tiling_of(symbol, name)
    region = (-HALF, -HALF, HALF, HALF)
    svg = patch_to_svg(tiling.patch(region), region=region, size=PANEL)
    svg = svg[: svg.rindex("</svg>")] + dots(tiling) + "</svg>"
    svg = re.sub(r"^<svg ", f'<svg x="{x}" y="{y + TITLE}" ', svg, count=1)
    cut = name.index("]") + 1
    types, group = name[:cut], name[cut:].strip()  # "[types]", "group" or "group #i"
    size = 12 if PANEL >= 240 else 9
    label = (f'<text x="{x + PANEL / 2}" y="{y + 14}" text-anchor="middle" font-size="{size}" '
             f'font-family="sans-serif">{html.escape(types)}</text>'
             f'<text x="{x + PANEL / 2}" y="{y + 29}" text-anchor="middle" font-size="{size}" '
             f'font-family="sans-serif">{html.escape(group)}</text>')
    return label + svg


def sheet(k: int) -> str:
    records = []
    for chunk in chunks({"k": k}):
        records += records_for([VertexType.parse(t).polygons for t in chunk["types"]])
    records.sort(key=lambda r: r.name)
    rows = -(-len(records) // COLUMNS)
    width, height = COLUMNS * (PANEL + 10) + 10, rows * (PANEL + TITLE + 10) + 10
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}">',
           f'<rect width="{width}" height="{height}" fill="#fff"/>']
    for i, r in enumerate(records):
        x = 10 + (i % COLUMNS) * (PANEL + 10)
        y = 10 + (i // COLUMNS) * (PANEL + TITLE + 10)
        out.append(panel(r.name, DSymbol.decode(r.spec["dsymbol"]), x, y))
    out.append("</svg>")
    return "\n".join(out)


def main(argv: list[str]) -> None:
    global PANEL
    for k in [int(a) for a in argv] or [2]:
        PANEL = 240 if k <= 2 else 170
        target = HERE / f"k-uniform-{k}.png"
        cairosvg.svg2png(bytestring=sheet(k).encode(), write_to=str(target))
        print(f"wrote {target}")


if __name__ == "__main__":
    main(sys.argv[1:])
