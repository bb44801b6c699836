"""Vertex configurations p1.p2...pk for the curved family: the core's regular-polygon
vertex-type notation (tilekit.regular.notation) under the names the family uses, so that the
family imports it in this one place.
"""

from __future__ import annotations

from tilekit.errors import ParseError
from tilekit.regular.notation import (
    angle_excess,
    bounded_species,
    canonical,
    geometry_of,
    types_of_species,
)
from tilekit.regular.notation import format_sequence as exponent
from tilekit.regular.notation import parse_sequence as parse

__all__ = ["angle_excess", "canonical", "dotted", "exponent", "geometry_of", "hyperbolic_types", "laves_configuration",
           "parse"]


def hyperbolic_types(max_sides: int, max_valence: int) -> list[tuple[int, ...]]:
    """Every hyperbolic vertex type of 3..max_valence polygons of 3..max_sides sides, canonical,
    as the vertex-species search lists them (its chunks: species by valence, then their types)."""
    out = []
    for k in range(3, max_valence + 1):
        for species in bounded_species(max_sides, k, k):
            if geometry_of(species) == "hyperbolic":
                out += [canonical(tuple(vt.polygons)) for vt in types_of_species(species)]
    return out


def dotted(seq: tuple[int, ...]) -> str:
    """``(3, 4, 4, 4)`` -> ``3.4.4.4``."""
    return ".".join(map(str, seq))


def laves_configuration(name: str) -> tuple[int, ...] | None:
    """The canonical vertex configuration a Laves name ``[3.4.3.4]``, ``[3.4^3]`` or
    ``V3.4.3.4`` denotes, or None for text that is not one (standard library only: the name
    hooks call it)."""
    s = name.strip()
    if len(s) > 2 and s[0] == "[" and s[-1] == "]":
        inner = s[1:-1]
    elif len(s) > 1 and s[0] in "Vv" and s[1].isdigit():
        inner = s[1:]
    else:
        return None
    try:
        return canonical(parse(inner))
    except ParseError:
        return None
