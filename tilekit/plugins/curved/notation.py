"""Vertex configurations p1.p2...pk for the curved family: the core's regular-polygon
vertex-type notation (tilekit.regular.notation) under the names the family uses, so that the
family imports it in this one place.
"""

from __future__ import annotations

from tilekit.regular.notation import angle_excess, canonical, geometry_of
from tilekit.regular.notation import format_sequence as exponent
from tilekit.regular.notation import parse_sequence as parse

__all__ = ["angle_excess", "canonical", "dotted", "exponent", "geometry_of", "parse"]


def dotted(seq: tuple[int, ...]) -> str:
    """``(3, 4, 4, 4)`` -> ``3.4.4.4``."""
    return ".".join(map(str, seq))
