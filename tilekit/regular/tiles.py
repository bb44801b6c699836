"""Regular polygons as prototiles of a tiling by regular polygons (chapter 4): unit-edge
prototiles named by their sides, a colour per number of sides shared by every such tiling,
the corner angle, and the one-line text of a translational unit."""

from __future__ import annotations

import math

import numpy as np

from tilekit.polygon import regular_polygon
from tilekit.tiling import PeriodicTiling, Prototile

__all__ = ["SIZE_COLOURS", "format_vector", "polygon_angle", "regular_prototiles", "size_colour", "unit_text"]

#: Colour of a polygon by its number of sides (the same colour in every tiling).
SIZE_COLOURS = (3, 4, 6, 8, 12)


def format_vector(v: np.ndarray) -> str:
    """``(0.5, 0.866025)``: a vector printed to 6 significant digits."""
    return "(" + ", ".join(f"{float(x):.6g}" for x in np.asarray(v).ravel()) + ")"


def polygon_angle(p: int) -> float:
    """The corner angle of a regular p-gon, π(p - 2)/p."""
    return math.pi * (p - 2) / p


def unit_text(tiling: PeriodicTiling, sizes: tuple[int, ...]) -> str:
    """``Translational unit: 2 3-gons, 1 6-gon; v1 = (...), v2 = (...).`` for a tiling of
    regular polygons whose prototile i has ``sizes[i]`` sides."""
    counts = np.bincount(tiling.unit_prototile, minlength=len(sizes))
    per_unit = ", ".join(f"{c} {n}-gon{'s' if c > 1 else ''}" for n, c in zip(sizes, counts.tolist()))
    return f"Translational unit: {per_unit}; v1 = {format_vector(tiling.v1)}, v2 = {format_vector(tiling.v2)}."


def size_colour(p: int) -> int:
    """The colour index of a p-gon (:data:`SIZE_COLOURS` order; other sizes after them)."""
    return SIZE_COLOURS.index(p) if p in SIZE_COLOURS else len(SIZE_COLOURS) + p


def regular_prototiles(sizes: tuple[int, ...]) -> list[Prototile]:
    """Unit-edge regular polygons, one per size, named by their number of sides."""
    return [Prototile(regular_polygon(p), name=f"{p}-gon") for p in sizes]
