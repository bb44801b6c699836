"""Isohedral types on the regular tiling {p, q} as Delaney symbols (Dress; the combinatorial side
of the book's §4.3/§5.2 incidence symbols, carried to the sphere and the hyperbolic plane).

The p-gon P of {p, q} has 2p *chambers* (flags): chamber ``2i + e`` is the half of edge i at
its end e (e = 0 at vertex i, 1 at vertex i + 1). s0 swaps the two halves of an edge, s1 the two
chambers at a vertex of P, s2 the chamber with the one across the edge in the neighbouring tile.
An incidence symbol says which tile symmetries S (the label- and arrow-preserving permutations
of P's edges) the tiling has and, per edge i, which edge j of P the neighbour presents there
and whether the hop is direct (a half-turn seen from the edge: the halves swap) or opposite (a
mirror: the halves keep their ends). Its Delaney symbol is the set D of S's orbits on the
chambers with s0, s1, s2 acting on them.

**Admissibility** (Poincaré's theorem in Dress's form): s2 must be well defined on D, an
involution commuting with s0, and round every vertex r12 | q, where r12 is the least r with
(s1 s2)^r fixing the orbit; then the symbol is realised by a tiling of {p, q}'s space whose
group Γ (a subgroup of {p, q}'s group *2pq) acts on the tiles transitively with stabiliser S.
The same rule decides the planar family's types: an edge whose stabiliser in Γ holds the mirror
in its own line is straight (I), the mirror in its perpendicular bisector U, the half-turn
about its midpoint S, nothing J (:meth:`tilekit.incidence.IncidenceSymbol.label_kind`).

**Non-regular topologies.** Every function taking q also takes the valences of the tile's
corners instead (a tuple, corner k the start of edge k): m12 of a chamber is then its corner's
valence, as for a Laves tile ([3.3.3.n]'s kite has corners of valence n, 3, 3, 3); a single q is
{p, q}'s. The conditions and the orbifold below are unchanged, read with that m12.

**The orbifold** of Γ is read off D: an orbit of <s_i, s_j> with v = m_ij / r_ij > 1 (m01 = p,
m12 = q or the corner's valence, m02 = 2) is a corner v when some chamber of it is fixed by s_i or s_j (it lies on a
mirror), else a cone point v; mirror boundaries are the cycles of chamber sides fixed by an
s_i, walked round their corners; the underlying surface is orientable exactly when D is
two-coloured by its non-fixing s_i; handles (o) or cross-caps (x) make up Conway's
characteristic χ = Σ_D (1/p + 1/m12 − 1/2)/2 (|D|(1/p + 1/q − 1/2)/2 on {p, q}).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction
from itertools import product

from tilekit.edgeshapes import ROT
from tilekit.errors import ParameterError, ParseError
from tilekit.incidence import IncidenceSymbol, symbol_table
from tilekit.limits import refuse_over
from tilekit.symmetry.names import orbifold_symbol as orbifold_text

#: q of {p, q}, or the valences of the tile's corners in order (a non-regular topology).
Valence = int | tuple[int, ...]

#: The largest p whose types :func:`enumerate_types` lists: the edge-orbit pairings it tries
#: grow about fivefold with each edge (p = 10 takes seconds, p = 13 minutes), and its labels
#: run a..l.
MAX_TYPES_P = 10


@dataclass(frozen=True)
class Delaney:
    """D = S\\chambers: ``s[i][d]`` the image of orbit d under s_i; ``orbit_of`` chamber -> d."""

    p: int
    s: tuple[tuple[int, ...], tuple[int, ...], tuple[int, ...]]
    orbit_of: tuple[int, ...]

    def __len__(self) -> int:
        return len(self.s[0])

    def r(self, i: int, j: int, d: int) -> int:
        """Least r > 0 with (s_i s_j)^r d = d."""
        x, r = d, 0
        while True:
            x = self.s[i][self.s[j][x]]
            r += 1
            if x == d:
                return r

    def orbit(self, i: int, j: int, d: int) -> set[int]:
        seen, todo = {d}, [d]
        while todo:
            x = todo.pop()
            for y in (self.s[i][x], self.s[j][x]):
                if y not in seen:
                    seen.add(y)
                    todo.append(y)
        return seen


def _chamber_permutation(p: int, shift: int, reflect: bool) -> list[int]:
    """A symmetry of the p-gon (edge i to shift ± i) as a permutation of its chambers."""
    return [2 * ((shift - i) % p) + (1 - e) if reflect else 2 * ((shift + i) % p) + e
            for i in range(p) for e in (0, 1)]


def _tile_permutations(symbol: IncidenceSymbol) -> list[list[int]]:
    """The tile symmetries as permutations of P's chambers."""
    p = len(symbol.edges)
    return [_chamber_permutation(p, shift, reflect) for shift, reflect in symbol.tile_symmetries()]


def _orbits(perms: list[list[int]], n: int) -> tuple[list[int], int]:
    """(orbit of each of n chambers under the group of permutations ``perms``, orbit count)."""
    orbit_of = [-1] * n
    count = 0
    for c in range(n):
        if orbit_of[c] < 0:
            for perm in perms:
                orbit_of[perm[c]] = count
            count += 1
    return orbit_of, count


def _bad(symbol: IncidenceSymbol, why: str) -> ParameterError:
    return ParameterError(f"incidence symbol {symbol}: {why}")


def delaney(symbol: IncidenceSymbol) -> Delaney:
    """The Delaney symbol of an incidence symbol on its p-gon (see the module); a symbol whose
    hops are not consistent with its tile symmetries is a one-line ParameterError."""
    p = len(symbol.edges)
    perms = _tile_permutations(symbol)
    orbit_of, count = _orbits(perms, 2 * p)
    table = symbol_table(symbol)
    s0, s1, s2 = [-1] * count, [-1] * count, [-1] * count
    for i in range(p):
        j = int(table.partner[i])
        direct = bool((table.orientation[i] == ROT).all())
        for e in (0, 1):
            c = 2 * i + e
            d = orbit_of[c]
            images = (orbit_of[2 * i + 1 - e], orbit_of[2 * ((i + e) % p) + (1 - e) if e else 2 * ((i - 1) % p) + 1],
                      orbit_of[2 * j + (1 - e if direct else e)])
            for s, img, name in ((s0, images[0], "s0"), (s1, images[1], "s1"), (s2, images[2], "s2")):
                if s[d] >= 0 and s[d] != img:
                    raise _bad(symbol, f"the neighbours across edges of one tile-symmetry class disagree ({name})")
                s[d] = img
    for d in range(count):
        if s2[s2[d]] != d:
            raise _bad(symbol, "the adjacency is not an involution (an edge's neighbour does not meet it back)")
        if s0[s2[d]] != s2[s0[d]]:
            raise _bad(symbol, "the hop across an edge does not keep the edge's ends together")
    return Delaney(p, (tuple(s0), tuple(s1), tuple(s2)), tuple(orbit_of))


def _corner(d: Delaney, x: int) -> int:
    """The tile's corner at which the chambers of orbit x lie (chamber 2i + e: corner i + e)."""
    c = d.orbit_of.index(x)
    return (c // 2 + c % 2) % d.p


def _m12(d: Delaney, q: Valence, x: int) -> int:
    """m12 of orbit x: q on {p, q}, else the valence of the orbit's corner."""
    return q if isinstance(q, int) else q[_corner(d, x)]


def _where(p: int, q: Valence) -> str:
    return f"{{{p},{q}}}" if isinstance(q, int) else f"the {p}-gon with corner valences {'.'.join(map(str, q))}"


def check_on(symbol: IncidenceSymbol, p: int, q: Valence) -> Delaney:
    """The symbol's Delaney symbol when it tiles {p, q} (q an int) or the topology whose tile
    has corners of the valences q (a tuple of p; else a one-line ParameterError naming the
    vertex whose cycle does not close)."""
    if len(symbol.edges) != p:
        raise ParameterError(f"incidence symbol {symbol} has {len(symbol.edges)} edges; the tile of {_where(p, q)} "
                             f"is a {p}-gon")
    if not isinstance(q, int) and len(q) != p:
        raise ParameterError(f"incidence symbol {symbol}: {len(q)} corner valences given for a {p}-gon")
    d = delaney(symbol)
    for x in range(len(d)):
        r = d.r(1, 2, x)
        m = _m12(d, q, x)
        if m % r:
            vertex = _corner(d, x)
            name = f"q = {m}" if isinstance(q, int) else f"its valence {m}"
            raise ParameterError(f"incidence symbol {symbol} does not tile {_where(p, q)}: round vertex {vertex + 1} "
                                 f"of the tile the edges close after {r} corners, which does not divide {name}")
        # the orbit round a vertex of the tiling meets corners of one valence only
        if not isinstance(q, int) and any(q[_corner(d, y)] != m for y in d.orbit(1, 2, x)):
            raise ParameterError(f"incidence symbol {symbol} does not tile {_where(p, q)}: it glues corner "
                                 f"{_corner(d, x) + 1} to a corner of another valence")
    return d


def _pair_order(d: Delaney, q: Valence, i: int, j: int, x: int) -> int:
    """m_ij at orbit x: p for sides 0, 1 (at the tile's centre), q or the corner's valence for
    1, 2 (at a vertex), 2 for 0, 2."""
    pair = (min(i, j), max(i, j))
    return d.p if pair == (0, 1) else 2 if pair == (0, 2) else _m12(d, q, x)


def _boundaries(d: Delaney, q: Valence) -> list[list[int]]:
    """The mirror boundaries: each the cyclic list of corner orders met walking round it (the
    chamber sides fixed by an s_i, joined where two meet round a vertex of the chambers)."""
    s = d.s
    segs = [(x, i) for x in range(len(d)) for i in range(3) if s[i][x] == x]
    seen: set[tuple[int, int]] = set()
    out = []
    for start in segs:
        if start in seen:
            continue
        ring: list[int] = []
        cur, j = start, min(v for v in range(3) if v != start[1])
        while True:
            seen.add(cur)
            x, i = cur
            k = 3 - i - j  # the other side through vertex j of the chamber
            e, other = x, k
            while s[other][e] != e:
                e = s[other][e]
                other = i if other == k else k
            v = _pair_order(d, q, i, k, x) // d.r(i, k, x)
            if v > 1:
                ring.append(v)
            cur, j = (e, other), 3 - other - j
            if cur == start:
                break
        out.append(ring)
    return out


def orbifold_symbol(d: Delaney, q: Valence) -> str:
    """Conway's orbifold symbol of the group of the Delaney symbol (see the module): o's, cone
    orders largest first, each mirror boundary ``*`` with its corners, x's."""
    cones: list[int] = []
    done: set[tuple[int, int, int]] = set()
    for i, j in ((0, 1), (1, 2), (0, 2)):
        for x in range(len(d)):
            if (i, j, x) in done:
                continue
            orb = d.orbit(i, j, x)
            done |= {(i, j, y) for y in orb}
            v = _pair_order(d, q, i, j, x) // d.r(i, j, x)
            if v > 1 and not any(d.s[i][y] == y or d.s[j][y] == y for y in orb):
                cones.append(v)
    rings = []
    for seq in _boundaries(d, q):
        variants = [seq[k:] + seq[:k] for k in range(len(seq))] or [[]]
        variants += [list(reversed(v)) for v in variants]
        rings.append(max(variants))
    # orientability: two-colour D by the non-fixing s_i
    colour = {0: 0}
    todo, orientable = [0], True
    while todo:
        x = todo.pop()
        for i in range(3):
            y = d.s[i][x]
            if y == x:
                continue
            if y not in colour:
                colour[y] = 1 - colour[x]
                todo.append(y)
            elif colour[y] == colour[x]:
                orientable = False
    rest = 2 - euler_characteristic(d, q) - len(rings) - sum(Fraction(c - 1, c) for c in cones) \
        - sum(Fraction(v - 1, 2 * v) for ring in rings for v in ring)
    if rest.denominator != 1 or rest < 0 or (orientable and rest % 2):
        raise ParameterError(f"the orbifold of this Delaney symbol does not add up (χ left over {rest})")
    genus = int(rest)
    cones.sort(reverse=True)
    if len(cones) == 3 and cones[1:] == [2, 2] and not rings:
        cones = [2, 2, cones[0]]  # the sphere's dihedral groups as Conway writes them: 22n, *22n
    if len(rings) == 1 and not cones and len(rings[0]) == 3 and sorted(rings[0])[:2] == [2, 2]:
        rings = [[2, 2, max(rings[0])]]
    return orbifold_text(cones, rings, genus // 2 if orientable else 0, 0 if orientable else genus)


def euler_characteristic(d: Delaney, q: Valence) -> Fraction:
    """Conway's orbifold characteristic of the group: Σ_D (1/p + 1/m12 − 1/2)/2, |D|(1/p + 1/q −
    1/2)/2 on {p, q} (2/|Γ| on the sphere)."""
    return sum((Fraction(1, d.p) + Fraction(1, _m12(d, q, x)) - Fraction(1, 2) for x in range(len(d))),
               Fraction(0)) / 2


# --------------------------------------------------------------------------- enumeration


def _subgroups(p: int) -> list[list[tuple[int, bool]]]:
    """The subgroups of the p-gon's symmetries up to conjugacy, as (shift, reflect) lists:
    the rotations by multiples of p/k, and with them the mirrors through edge 0's start
    (and, for even p/k, through edge 0's midpoint)."""
    out = []
    for k in range(1, p + 1):
        if p % k:
            continue
        step = p // k
        rots = [(step * t % p, False) for t in range(k)]
        out.append(rots)
        axes = [0] if step % 2 else [0, 1]
        for a in axes:
            out.append(rots + [((a + step * t) % p, True) for t in range(k)])
    return out


def enumerate_types(p: int, q: int) -> Iterator[IncidenceSymbol]:
    """Every isohedral type on {p, q}'s p-gon, one canonical incidence symbol each: for each
    tile stabiliser S (up to conjugacy), every s2 on the S-orbits of chambers that commutes with
    s0 and closes round every vertex (r12 | q), written as an incidence symbol. p over
    MAX_TYPES_P is a LimitError, raised before any work."""
    refuse_over("polygon edges to enumerate isohedral types on", p, MAX_TYPES_P,
                hint=f"types are enumerated for p up to {MAX_TYPES_P}")
    return _enumerate_types(p, q)


def _enumerate_types(p: int, q: int) -> Iterator[IncidenceSymbol]:
    seen: set[str] = set()
    for sub in _subgroups(p):
        perms = [_chamber_permutation(p, shift, reflect) for shift, reflect in sub]
        # edge orbits under S (with whether an element reverses the edge onto itself)
        edge_orbit: dict[int, int] = {}
        reps: list[int] = []
        for i in range(p):
            if i not in edge_orbit:
                for perm in perms:
                    edge_orbit[perm[2 * i] // 2] = len(reps)
                reps.append(i)
        undirected = [any(perm[2 * r] == 2 * r + 1 for perm in perms) for r in reps]
        # D = S-orbits of chambers, with s1 (s0 is fixed by the pairing below); survivors of the
        # cheap vertex test are written as symbols and checked in full
        orbit_of, size = _orbits(perms, 2 * p)
        s1 = [0] * size
        for i in range(p):
            s1[orbit_of[2 * i + 1]] = orbit_of[2 * ((i + 1) % p)]
            s1[orbit_of[2 * ((i + 1) % p)]] = orbit_of[2 * i + 1]
        # per edge orbit: partner orbit and hop kind (direct / opposite); undirected edges: opposite only
        n = len(reps)
        for match in _matchings(list(range(n))):
            if any(undirected[a] != undirected[match[a]] for a in range(n)):
                continue
            owners = [a for a in range(n) if match[a] >= a]  # one hop kind per pair of edge orbits
            options = [[False] if undirected[a] else [True, False] for a in owners]
            for chosen in product(*options):
                kinds = [False] * n
                for a, k in zip(owners, chosen):
                    kinds[a] = kinds[match[a]] = k
                s2 = [0] * size
                for a in range(n):
                    r, r2 = reps[a], reps[match[a]]
                    for e in (0, 1):
                        s2[orbit_of[2 * r + e]] = orbit_of[2 * r2 + (1 - e if kinds[a] else e)]
                if not _closes(s1, s2, q):
                    continue
                sym = _symbol(p, reps, edge_orbit, perms, undirected, match, tuple(kinds))
                if sym is None:
                    continue
                canon = sym.canonical()
                key = str(canon)
                if key in seen:
                    continue
                seen.add(key)
                try:
                    check_on(canon, p, q)  # the full check, once per type
                except ParameterError:
                    continue
                yield canon


def _closes(s1: list[int], s2: list[int], q: int) -> bool:
    """s2 an involution and every (s1 s2)-cycle's length dividing q (the vertex test, cheaply)."""
    for x in range(len(s1)):
        if s2[s2[x]] != x:
            return False
        y, r = s1[s2[x]], 1
        while y != x:
            y, r = s1[s2[y]], r + 1
            if r > q:
                return False
        if q % r:
            return False
    return True


def _matchings(items: list[int]) -> Iterator[dict[int, int]]:
    if not items:
        yield {}
        return
    i, rest = items[0], items[1:]
    for m in _matchings(rest):
        yield {i: i, **m}
    for j in rest:
        for m in _matchings([k for k in rest if k != j]):
            yield {i: j, j: i, **m}


def _symbol(p: int, reps: list[int], edge_orbit: dict[int, int], perms: list[list[int]], undirected: list[bool],
            match: dict[int, int], direct: tuple[bool, ...]) -> IncidenceSymbol | None:
    """The incidence symbol of a stabiliser and an edge-orbit pairing, or None when the symbol's
    own tile symmetries are more than S (that type is met with its larger S)."""
    letters = "abcdefghijkl"
    edges = []
    for i in range(p):
        a = edge_orbit[i]
        if undirected[a]:
            edges.append((letters[a], 0))
            continue
        # the sign: whether an element of S carries the representative onto edge i forwards
        r = reps[a]
        fwd = any(perm[2 * r] == 2 * i for perm in perms)
        edges.append((letters[a], 1 if fwd else -1))
    adjacency = []
    for a in range(len(reps)):
        b = match[a]
        if undirected[a]:
            adjacency.append((letters[b], 0))
        else:
            # the first edge labelled b has the sign of reps[b] (+): direct iff t = s_a * s_b
            adjacency.append((letters[b], 1 if direct[a] else -1))
    sym = IncidenceSymbol(tuple(edges), tuple(adjacency))
    try:
        sym.check()
    except ParseError:  # an inconsistent symbol (check raises nothing else): not a type
        return None
    if len(sym.tile_symmetries()) != len(perms):
        return None
    return sym
