"""Vertex-type notation (§4.1): parse, print, canonical form, species, angle sums, enumeration,
the 21 Euclidean vertex types.

A vertex type p1.p2...pk lists the regular polygons met in a loop round a vertex. Types are
equal under cyclic shift and reversal; the canonical form is the lexicographically least
such sequence, printed with exponents for runs (``3.3.3.3.6`` is ``3^4.6``). A species
(exercise 4.10) disregards order. Parenthesised ``(3^4.6)`` names the Archimedean tiling and
bracketed ``[3^4.6]`` the Laves tiling; both parse to the same type.
"""

from __future__ import annotations

import itertools
import re
from dataclasses import dataclass
from fractions import Fraction

from tilekit.errors import ParseError

_SUPERSCRIPT = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹", "0123456789")
_PART = re.compile(r"^(\d+)(?:\^(\d+))?$")
_SUP_PART = re.compile(r"^(\d+?)([⁰¹²³⁴⁵⁶⁷⁸⁹]+)$")

#: The largest polygon accepted in a vertex type (a typo guard; 3.7.42 is the largest
#: Euclidean one).
MAX_SIDES = 1000


def canonical(seq: tuple[int, ...] | list[int]) -> tuple[int, ...]:
    """The least sequence among the cyclic shifts and reversals of ``seq``."""
    s = tuple(seq)
    if not s:
        return s
    forms = []
    for base in (s, s[::-1]):
        for i in range(len(base)):
            forms.append(base[i:] + base[:i])
    return min(forms)


def arrangements(seq: tuple[int, ...]) -> list[tuple[int, ...]]:
    """Every distinct cyclic shift and reversal of ``seq`` (the ways to read it round a vertex)."""
    s = tuple(seq)
    out: list[tuple[int, ...]] = []
    for base in (s, s[::-1]):
        for i in range(len(base)):
            form = base[i:] + base[:i]
            if form not in out:
                out.append(form)
    return out


def format_sequence(seq: tuple[int, ...]) -> str:
    """``(3, 3, 3, 3, 6)`` -> ``3^4.6`` (runs as exponents, in the given order)."""
    parts = []
    for p, run in itertools.groupby(seq):
        n = len(list(run))
        parts.append(f"{p}^{n}" if n > 1 else str(p))
    return ".".join(parts)


def angle_excess(seq: tuple[int, ...]) -> Fraction:
    """Sum of the interior angles of the polygons, in units of π, minus 2 (exact).

    Zero: the vertex is flat (Euclidean); negative: spherical; positive: hyperbolic."""
    return sum((Fraction(p - 2, p) for p in seq), Fraction(0)) - 2


def geometry_of(seq: tuple[int, ...]) -> str:
    e = angle_excess(seq)
    return "euclidean" if e == 0 else ("spherical" if e < 0 else "hyperbolic")


@dataclass(frozen=True)
class VertexType:
    """A vertex type in canonical order; ``str`` gives the exponent form (``3^4.6``)."""

    polygons: tuple[int, ...]

    @classmethod
    def of(cls, seq: tuple[int, ...] | list[int]) -> VertexType:
        seq = tuple(int(p) for p in seq)
        if len(seq) < 3:
            raise ParseError(f"vertex type {format_sequence(seq)!r} has {len(seq)} polygons; at least 3 meet at a vertex")
        bad = [p for p in seq if p < 3 or p > MAX_SIDES]
        if bad:
            raise ParseError(
                f"vertex type {format_sequence(seq)!r}: polygon size(s) {bad} out of range 3..{MAX_SIDES}"
            )
        return cls(canonical(seq))

    @classmethod
    def parse(cls, text: str) -> VertexType:
        return cls.of(parse_sequence(text))

    def __str__(self) -> str:
        return format_sequence(self.polygons)

    @property
    def dotted(self) -> str:
        """The plain dotted form, ``3.3.3.3.6``."""
        return ".".join(str(p) for p in self.polygons)

    @property
    def archimedean_name(self) -> str:
        return f"({self})"

    @property
    def laves_name(self) -> str:
        return f"[{self}]"

    @property
    def species(self) -> tuple[int, ...]:
        """The multiset of polygons (exercise 4.10), sorted."""
        return tuple(sorted(self.polygons))

    @property
    def species_name(self) -> str:
        """The species as the sorted sequence in exponent form: ``3^3.4^2`` names the species
        of both 3^3.4^2 and 3^2.4.3.4."""
        return format_sequence(self.species)

    @property
    def excess(self) -> Fraction:
        return angle_excess(self.polygons)

    @property
    def geometry(self) -> str:
        return geometry_of(self.polygons)

    @property
    def sizes(self) -> tuple[int, ...]:
        """The distinct polygon sizes, ascending."""
        return tuple(sorted(set(self.polygons)))

    def aliases(self) -> list[str]:
        """Other usual spellings: dotted, parenthesised, bracketed."""
        s = str(self)
        out = [self.dotted, f"({s})", f"({self.dotted})"]
        return [a for a in dict.fromkeys(out) if a != s]


def parse_sequence(text: str) -> tuple[int, ...]:
    """Parse ``3.3.3.3.6``, ``3^4.6``, ``(3^4.6)``, ``[3^4.6]``, ``3⁴.6`` into a sequence (as written)."""
    if not isinstance(text, str):
        raise ParseError(f"vertex type {text!r} is not text like '3^4.6'")
    if len(text) > 200:
        raise ParseError(f"vertex type {text[:30]!r}... is {len(text)} characters; a vertex has at most 6 polygons")
    raw = text.strip().replace(" ", "")
    body = raw
    if len(body) >= 2 and ((body[0], body[-1]) in (("(", ")"), ("[", "]"))):
        body = body[1:-1]
    if not body:
        raise ParseError(f"vertex type {text!r} is empty; write e.g. '3^4.6' or '3.3.3.3.6'")
    seq: list[int] = []
    for part in body.replace(",", ".").split("."):
        m = _PART.match(part)
        if m is None:
            sm = _SUP_PART.match(part)
            if sm is not None:
                m_base, m_exp = sm.group(1), sm.group(2).translate(_SUPERSCRIPT)
            else:
                raise ParseError(
                    f"vertex type {text!r}: cannot read {part!r}; write polygon sizes joined by '.', "
                    "with '^n' for repeats, e.g. '3^4.6' or '3.12^2'"
                )
        else:
            m_base, m_exp = m.group(1), m.group(2)
        if len(m_base) > 4 or (m_exp and len(m_exp) > 4):
            raise ParseError(f"vertex type {text!r}: {part!r} is out of range (polygon sizes 3..{MAX_SIDES})")
        p = int(m_base)
        n = int(m_exp) if m_exp else 1
        if n < 1:
            raise ParseError(f"vertex type {text!r}: exponent in {part!r} must be at least 1")
        if n > 12:
            raise ParseError(f"vertex type {text!r}: exponent in {part!r} is too large (at most 12)")
        seq.extend([p] * n)
    bad = [p for p in seq if p < 3 or p > MAX_SIDES]
    if bad:
        raise ParseError(f"vertex type {text!r}: polygon size(s) {bad} out of range 3..{MAX_SIDES}")
    if len(seq) < 3:
        raise ParseError(f"vertex type {text!r} has {len(seq)} polygon(s); at least 3 meet at a vertex")
    return tuple(seq)


def parse_vertex_type(text: str) -> VertexType:
    """The canonical :class:`VertexType` of ``text`` (a ParseError names what is wrong)."""
    return VertexType.parse(text)


def types_of_species(species: tuple[int, ...]) -> list[VertexType]:
    """The distinct vertex types (cyclic orders up to rotation and reversal) of a species."""
    seen: set[tuple[int, ...]] = set()
    out: list[VertexType] = []
    first, rest = species[0], species[1:]
    for perm in sorted(set(itertools.permutations(rest))):
        c = canonical((first, *perm))
        if c not in seen:
            seen.add(c)
            out.append(VertexType(c))
    return sorted(out, key=lambda t: t.polygons)


def euclidean_species(min_k: int = 3, max_k: int = 6) -> list[tuple[int, ...]]:
    """All multisets {p1 <= ... <= pk} (3 <= pi) whose angles sum to exactly 2π.

    Exhaustive: with the sizes sorted, the remaining budget bounds each next size, so the
    recursion is finite (1/p_i summed must equal (k - 2) / 2)."""
    out: list[tuple[int, ...]] = []

    def rec(prefix: list[int], remaining: Fraction, slots: int) -> None:
        # remaining = required sum of 1/p over the remaining slots
        if slots == 0:
            if remaining == 0:
                out.append(tuple(prefix))
            return
        lo = prefix[-1] if prefix else 3
        # need slots * 1/p >= remaining with p >= lo  =>  p <= slots / remaining
        if remaining <= 0:
            return
        hi = int(slots / remaining)
        for p in range(lo, hi + 1):
            r = remaining - Fraction(1, p)
            if r < 0:
                continue
            if slots == 1:
                if r == 0:
                    out.append(tuple(prefix + [p]))
                continue
            # the largest sum the rest can reach with sizes >= p is (slots - 1) / p
            if r > Fraction(slots - 1, p):
                continue
            rec(prefix + [p], r, slots - 1)

    for k in range(min_k, max_k + 1):
        rec([], Fraction(k - 2, 2), k)
    return sorted(out, key=lambda s: (len(s), s))


def bounded_species(max_sides: int, min_k: int = 3, max_k: int = 6) -> list[tuple[int, ...]]:
    """All multisets with 3 <= pi <= max_sides and min_k <= k <= max_k (any angle sum)."""
    out: list[tuple[int, ...]] = []
    for k in range(min_k, max_k + 1):
        out.extend(itertools.combinations_with_replacement(range(3, max_sides + 1), k))
    return out


def euclidean_vertex_types() -> tuple[VertexType, ...]:
    """The 21 vertex types whose angles sum to 2π (§4.1, exercise 4.8): the types of the 17
    Euclidean species, in species order."""
    return tuple(t for s in euclidean_species() for t in types_of_species(s))
