"""Regenerate docs/images/escherize-fish.png: the best isohedral tile for a fish-like goal.

The goal is tests/data/escher/fish.json (a 100-point polygon). All 81 unmarked types are
fitted by ``tilekit.plugins.isohedral.escher.escherize`` (the library call behind
``tilekit escherize``); the panel on the left is the best tile with the goal, aligned by the
metric's similarity, dashed in red; the panel on the right is its tiling.

Run: python docs/images/make_escher_example.py [GOAL ...] [--out DIR] [--workers N]
GOAL is fish, bird (tests/data/escher/NAME.json), star, hexagon or a .json/.svg file.
"""

from __future__ import annotations

import argparse
import math
import re
from pathlib import Path

import cairosvg
import numpy as np

from tilekit.geometry import as_region
from tilekit.plugins.isohedral.escher import escherize, outline_svg, read_goal

HERE = Path(__file__).resolve().parent
DATA = HERE.parent.parent / "tests" / "data" / "escher"
PANEL = 360


def goal_points(name: str) -> np.ndarray:
    if name in ("fish", "bird"):
        return read_goal(DATA / f"{name}.json")
    if name == "star":
        t = np.linspace(0, 2 * math.pi, 100, endpoint=False)
        r = 1 + 0.35 * np.cos(5 * t)
        return np.column_stack([r * np.cos(t), r * np.sin(t)])
    if name == "hexagon":
        t = np.arange(6) * math.pi / 3 + 0.2
        return np.column_stack([np.cos(t), np.sin(t)])
    return read_goal(name)


def inner(svg: str, x: int) -> str:
    """An SVG document as a nested <svg> panel at (x, 0), PANEL x PANEL pixels."""
    svg = re.sub(r"<\?xml[^>]*\?>", "", svg).strip()
    svg = re.sub(r'\swidth="[^"]*"', "", svg, count=1)
    svg = re.sub(r'\sheight="[^"]*"', "", svg, count=1)
    return svg.replace("<svg", f'<svg x="{x}" y="0" width="{PANEL}" height="{PANEL}"', 1)


def panel_pair(name: str, workers: int) -> tuple[str, str]:
    goal = goal_points(name)
    results, _ = escherize(goal, workers=workers)
    best = results[0]
    tiling = best.tiling()
    outline = np.asarray(tiling.prototile.outline)
    centre = outline.mean(axis=0)
    half = 2.2 * float(np.ptp(outline, axis=0).max())  # about four tiles across
    box = (centre[0] - half, centre[1] - half, centre[0] + half, centre[1] + half)
    patch = tiling.patch(box)
    doc = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{2 * PANEL}" height="{PANEL}">'
           + inner(outline_svg(best, goal, PANEL), 0)
           + inner(tiling.render_svg(patch, region=as_region(box)), PANEL) + "</svg>")
    summary = ", ".join(f"{r.name} {r.distance:.4f}" for r in results[:5])
    return doc, summary


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("goals", nargs="*", default=["fish"])
    ap.add_argument("--out", default=str(HERE))
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    for name in args.goals:
        doc, summary = panel_pair(name, args.workers)
        stem = Path(name).stem
        path = Path(args.out) / f"escherize-{stem}.png"
        cairosvg.svg2png(bytestring=doc.encode(), write_to=str(path))
        print(f"wrote {path}: {summary}")


if __name__ == "__main__":
    main()
