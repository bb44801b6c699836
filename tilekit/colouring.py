"""Colourings of periodic tilings in the notation (c1..cm)(p1..pk)(q1..qk) of §5.4.3.

Aspect i of the translational unit at a*v1 + b*v2 has colour rho2^b(rho1^a(c_i)), where
rho1(j) = p_j and rho2(j) = q_j. Powers of the permutations are read from precomputed
tables indexed by the exponent modulo the permutation's order, so colouring a million tiles
is two array look-ups, never an iteration proportional to |a| or |b| (exercise 5.11).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from tilekit.errors import ParseError
from tilekit.limits import MAX_COLOURS

_GROUP = re.compile(r"\(([^()]*)\)")


def permutation_order(perm: Sequence[int]) -> int:
    """The order of a permutation of 0..k-1 (lcm of its cycle lengths)."""
    seen = [False] * len(perm)
    order = 1
    for start in range(len(perm)):
        if seen[start]:
            continue
        length = 0
        j = start
        while not seen[j]:
            seen[j] = True
            j = perm[j]
            length += 1
        order = order * length // math.gcd(order, length)
    return order


def power_table(perm: Sequence[int]) -> np.ndarray:
    """Rows ``perm^0, perm^1, ..., perm^(order-1)`` as an (order, k) int array."""
    p = np.asarray(perm, dtype=np.int64)
    order = permutation_order(list(p))
    table = np.empty((order, len(p)), dtype=np.int64)
    table[0] = np.arange(len(p))
    for e in range(1, order):
        table[e] = p[table[e - 1]]
    return table


def _cycles(perm: Sequence[int]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per element: its cycle's start offset in ``flat``, the cycle length, its position in
    the cycle; and ``flat``, the cycles laid end to end."""
    k = len(perm)
    start = np.zeros(k, dtype=np.int64)
    length = np.zeros(k, dtype=np.int64)
    pos = np.zeros(k, dtype=np.int64)
    flat: list[int] = []
    seen = [False] * k
    for s0 in range(k):
        if seen[s0]:
            continue
        cyc = []
        j = s0
        while not seen[j]:
            seen[j] = True
            cyc.append(j)
            j = perm[j]
        for i, c in enumerate(cyc):
            start[c], length[c], pos[c] = len(flat), len(cyc), i
        flat.extend(cyc)
    return start, length, pos, np.asarray(flat, dtype=np.int64)


def apply_power(perm: Sequence[int], exponent: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``perm^exponent[i](x[i])`` elementwise, for any (negative or huge) integer exponents."""
    start, length, pos, flat = _cycles(perm)
    x = np.asarray(x, dtype=np.int64)
    return flat[start[x] + (pos[x] + exponent) % length[x]]


@dataclass(frozen=True)
class Colouring:
    """Aspect colours and the two translation permutations, all 0-based internally."""

    aspects: tuple[int, ...]
    p: tuple[int, ...]
    q: tuple[int, ...]

    def __post_init__(self) -> None:
        k = len(self.p)
        if len(self.q) != k:
            raise ParseError(
                f"colouring permutations have different lengths ({len(self.p)} and {len(self.q)})"
            )
        for name, perm in (("first", self.p), ("second", self.q)):
            if sorted(perm) != list(range(k)):
                raise ParseError(
                    f"colouring: the {name} permutation ({' '.join(str(i + 1) for i in perm)}) "
                    f"is not a permutation of 1..{k}"
                )
        if k > MAX_COLOURS:
            raise ParseError(f"colouring has {k} colours; the limit is {MAX_COLOURS}")
        bad = [c + 1 for c in self.aspects if not 0 <= c < k]
        if bad:
            raise ParseError(f"colouring: aspect colour(s) {bad} outside 1..{k}")

    @property
    def colours(self) -> int:
        """Number of colours k."""
        return len(self.p)

    @classmethod
    def single(cls, aspects: int) -> Colouring:
        """Every tile the same colour."""
        return cls(tuple([0] * aspects), (0,), (0,))

    @classmethod
    def by_aspect(cls, aspect_colours: Sequence[int]) -> Colouring:
        """Given colours per aspect (0-based), with identity permutations."""
        k = max(aspect_colours) + 1 if aspect_colours else 1
        ident = tuple(range(k))
        return cls(tuple(int(c) for c in aspect_colours), ident, ident)

    @classmethod
    def parse(cls, text: str) -> Colouring:
        """Parse '(1 2 3) (1 2 3) (1 2 3)' (spaces or commas between numbers).

        Colours may be numbered from 1 (as in Figures 5.12 and 5.13) or from 0 (as Appendix A
        prints them): a permutation of 0..k-1 contains 0 and one of 1..k never does, so the
        base is read off the permutations unambiguously.
        """
        groups = _GROUP.findall(text)
        rest = _GROUP.sub("", text).strip()
        if len(groups) != 3 or rest:
            raise ParseError(
                f"colouring {text!r} is not three parenthesised groups like '(1 2 1 2)(2 1)(2 1)'"
            )
        seqs = []
        for g in groups:
            items = [s for s in re.split(r"[\s,]+", g.strip()) if s]
            try:
                seqs.append([int(s) for s in items])
            except ValueError:
                raise ParseError(f"colouring {text!r}: ({g}) holds a non-integer") from None
            if not items:
                raise ParseError(f"colouring {text!r}: empty group ()")
        base = 0 if 0 in seqs[1] or 0 in seqs[2] else 1
        seqs = [[v - base for v in seq] for seq in seqs]
        return cls(tuple(seqs[0]), tuple(seqs[1]), tuple(seqs[2]))

    def __str__(self) -> str:
        def grp(seq: Sequence[int]) -> str:
            return "(" + " ".join(str(i + 1) for i in seq) + ")"

        return grp(self.aspects) + grp(self.p) + grp(self.q)

    def colour(self, aspect: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Colours (0-based) of aspects ``aspect`` in the units at lattice points (a, b).

        ``perm^e(c)`` is read off c's cycle: the element ``e mod len`` steps further along it,
        so the cost is O(k + tiles) whatever the permutation's order (which, for k colours in
        cycles of distinct prime lengths, is astronomically larger than k).
        """
        base = np.asarray(self.aspects, dtype=np.int64)[np.asarray(aspect, dtype=np.int64)]
        return apply_power(self.q, np.asarray(b, dtype=np.int64), apply_power(self.p, np.asarray(a, dtype=np.int64), base))
