"""Vertex configurations p1.p2...pk for the curved family: parse, canonical form, print.

The regular-polygon vertex-type notation lives in the archimedean family today
(``tilekit.plugins.archimedean.notation``) and is moving to a core module; a family never
imports another family, so this module holds the little the curved family needs, and is the
one place to replace by an import from the core module once it exists.
"""

from __future__ import annotations

import itertools
import re
from fractions import Fraction

from tilekit.errors import ParseError

_PART = re.compile(r"^(\d+)(?:\^(\d+))?$")
_SUPERSCRIPT = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹", "0123456789")
_SUP_PART = re.compile(r"^(\d+?)([⁰¹²³⁴⁵⁶⁷⁸⁹]+)$")

#: Largest polygon and largest number of polygons at a vertex accepted (typo guards).
MAX_SIDES = 1000
MAX_VALENCE = 60


def canonical(seq: tuple[int, ...] | list[int]) -> tuple[int, ...]:
    """The least sequence among the cyclic shifts and reversals of ``seq``."""
    s = tuple(seq)
    if not s:
        return s
    return min(base[i:] + base[:i] for base in (s, s[::-1]) for i in range(len(base)))


def dotted(seq: tuple[int, ...]) -> str:
    """``(3, 4, 4, 4)`` -> ``3.4.4.4``."""
    return ".".join(map(str, seq))


def exponent(seq: tuple[int, ...]) -> str:
    """``(3, 4, 4, 4)`` -> ``3.4^3`` (runs as exponents, in the given order)."""
    parts = []
    for p, run in itertools.groupby(seq):
        n = len(list(run))
        parts.append(f"{p}^{n}" if n > 1 else str(p))
    return ".".join(parts)


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


def angle_excess(seq: tuple[int, ...]) -> Fraction:
    """The interior angles of Euclidean regular polygons summed, less a full turn, in turns:
    below 0 the configuration closes on the sphere, 0 in the plane, above 0 hyperbolic."""
    return sum((Fraction(n - 2, 2 * n) for n in seq), Fraction(0)) - 1


def geometry_of(seq: tuple[int, ...]) -> str:
    """'spherical', 'euclidean' or 'hyperbolic' (the sign of :func:`angle_excess`)."""
    e = angle_excess(seq)
    return "spherical" if e < 0 else "euclidean" if e == 0 else "hyperbolic"
