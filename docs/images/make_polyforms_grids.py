"""Regenerate docs/images/polyforms-grids.png: one 6-cell polyform on each grid but the square.

For each grid the free 6-form with the most symmetries (ties: the most cell shapes) is drawn
cell by cell with its exact coordinates (tilekit.plugins.polyomino.polyform), cells coloured
by shape; panels in the order of tilekit.lattice.GRIDS, three to a row.

Run: python docs/images/make_polyforms_grids.py
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from PIL import Image

from tilekit.lattice import GRIDS, SQUARE, encode, enumerate_free
from tilekit.plugins.polyomino.polyform import from_spec
from tilekit.render import write_image

OUT = Path(__file__).with_name("polyforms-grids.png")


def pick(grid, n: int = 6) -> str:
    best = None
    for r in range(len(grid.roots)):
        polys, _, masks, _ = enumerate_free(grid, n, root=r, with_symmetry=True)
        for p, m in zip(polys, masks.tolist()):
            if len(p) == n:
                score = (bin(m).count("1"), len({grid.shapes[t] for t in grid.cell_type(p)}))
                if best is None or score > best[0]:
                    best = (score, p)
    return encode(grid, best[1])


def main() -> None:
    panels = []
    with tempfile.TemporaryDirectory() as tmp:
        for grid in GRIDS.values():
            if grid is SQUARE:
                continue
            path = Path(tmp) / f"{grid.name}.png"
            write_image(from_spec({"code": pick(grid)}).patch(None), path, width=200)
            panels.append(Image.open(path).convert("RGB"))
    w, h = max(p.width for p in panels), max(p.height for p in panels)
    sheet = Image.new("RGB", (3 * w, ((len(panels) + 2) // 3) * h), "white")
    for k, p in enumerate(panels):
        sheet.paste(p, ((k % 3) * w, (k // 3) * h))
    sheet.save(OUT, optimize=True)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
