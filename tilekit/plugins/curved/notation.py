"""Vertex configurations p1.p2...pk for the curved family: parse, canonical form, print.

The canonical form, the exponent form and the geometry a configuration closes on are the
core's (``tilekit.regular.notation``, shared with the archimedean and k-uniform families); this
module adds the reading the curved family needs (up to 60 polygons at a vertex, as hyperbolic
{3,q} tilings have) and the plain dotted form.
"""

from __future__ import annotations

import re

from tilekit.errors import ParseError
from tilekit.regular.notation import canonical, geometry_of
from tilekit.regular.notation import format_sequence as exponent

__all__ = ["canonical", "dotted", "exponent", "geometry_of", "parse"]

_PART = re.compile(r"^(\d+)(?:\^(\d+))?$")
_SUPERSCRIPT = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹", "0123456789")
_SUP_PART = re.compile(r"^(\d+?)([⁰¹²³⁴⁵⁶⁷⁸⁹]+)$")

#: Largest polygon and largest number of polygons at a vertex accepted (typo guards).
MAX_SIDES = 1000
MAX_VALENCE = 60


def dotted(seq: tuple[int, ...]) -> str:
    """``(3, 4, 4, 4)`` -> ``3.4.4.4``."""
    return ".".join(map(str, seq))


def parse(text: str) -> tuple[int, ...]:
    """``3.4.4.4``, ``3.4^3`` or ``3.4³`` as the sequence of polygons round a vertex (one-line
    ParseError naming the bad part)."""
    if not isinstance(text, str) or not text.strip():
        raise ParseError("a vertex configuration is polygon sizes joined by dots, e.g. 3.4.4.4 or 3.4^3")
    out: list[int] = []
    for part in text.strip().split("."):
        part = part.strip()
        m = _PART.match(part)
        if m is None:
            s = _SUP_PART.match(part)
            if s is not None:
                m = _PART.match(f"{s.group(1)}^{s.group(2).translate(_SUPERSCRIPT)}")
        if m is None:
            raise ParseError(f"vertex configuration {text[:60]!r}: {part[:20]!r} is not a polygon size "
                             "(an integer, optionally ^count), e.g. 3.4.4.4 or 3.4^3")
        n, run = int(m.group(1)), int(m.group(2) or 1)
        if not 3 <= n <= MAX_SIDES or not 1 <= run <= MAX_VALENCE:
            raise ParseError(f"vertex configuration {text[:60]!r}: polygons have 3..{MAX_SIDES} sides and "
                             f"a count is 1..{MAX_VALENCE}, got {part[:20]!r}")
        out.extend([n] * run)
    if not 3 <= len(out) <= MAX_VALENCE:
        raise ParseError(f"vertex configuration {text[:60]!r}: 3..{MAX_VALENCE} polygons meet at a vertex, "
                         f"got {len(out)}")
    return tuple(out)
