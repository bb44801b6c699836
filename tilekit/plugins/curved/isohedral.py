"""Isohedral tiles on the sphere and the hyperbolic plane (issue 35; §3.6.2, §7.3): the regular
p-gon of the tiling {p, q} with its edges matched up by motions, each edge shaped by the J/U/S/I
rule the group allows (the planar isohedral family's edge vocabulary, :mod:`tilekit.edgeshapes`,
and incidence symbols, :mod:`tilekit.incidence`).

A type is an incidence symbol (§5.2) on the p-gon, or, for tiles without symmetry hopped by
half-turns only, a *pairing*: a letter per edge, once for an **S** edge (paired with itself by
the half-turn about its midpoint), twice for a **J** pair (the symbol with each edge its own
label, a pair's labels adjacent with +). The hop across edge i is ``H_i = F_i · O · F_j⁻¹``
(F_k the frame at edge k's midpoint along the edge, j the first edge with the adjacent label,
O the half-turn for a direct hop or the mirror in the edge's line for an opposite one: with
F's a reflection or a glide), and the tile symmetries the symbol's labels and arrows keep are
the polygon's rotations and mirrors. Whether they tile {p, q} — each tile once, the group acting
transitively with the tile's stabiliser exactly those symmetries — is Poincaré's condition in
Dress's form, checked on the symbol's Delaney symbol (:mod:`.delaney`), which also gives the
group's orbifold. The tile may be deformed freely: an edge's curve lives on the unit segment
(0,0)–(1,0) and is carried onto the surface through the edge's chart
``F_k · exp((x − ½)L, yL)`` (the exponential map at the pole, L the edge length), which
commutes with the half-turn and the two mirrors of the edge, so a curve put on one edge arrives
on its partner as the unit-segment image the symbol names (:func:`tilekit.incidence.edge_curves`).
Neighbouring tiles share their edges point for point, and the tile is the geodesic polygon
through those points (straight in the Klein model), so the deformed tiles tile exactly as the
polygons do; a tile whose boundary crosses itself is refused (default shapes are damped first).
The outline code (frames, charts, the crossing check) is :mod:`.shaped`, and the hops, words and
colourings here colour the shaped Laves tiles too (laves.py).

Colours: a homomorphism φ: Γ → Z_k (or Z_a × Z_b), zero on the tile symmetries, one value per
pair of adjacent labels (:func:`colour_classes`), constrained by the relations found round the
tile's vertices (:meth:`CurvedIsohedralTiling.relations`), colours the tile γ(P) by φ(γ); its
classes are the cosets of the kernel, a normal subgroup of index k, so the colouring is perfect,
and with φ ≠ 0 on every hop no two neighbours share a colour. The smallest such k (at least 2)
is used, or the one asked for; none is a one-line error.

Covered: every isohedral type of {p, q}'s regular polygon (J, U, S and I edges; hops by
half-turns, mirrors and glides; tiles with any subgroup of the polygon's symmetries) on the
sphere and in the hyperbolic plane; :func:`tilekit.plugins.curved.delaney.enumerate_types`
lists them, and the family's records are those of the {p, q} in catalogue/curved/isohedral.toml.
"""

from __future__ import annotations

import itertools
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.edgeshapes import ROT, EdgeShape
from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.files import read_text
from tilekit.incidence import LABELS, IncidenceSymbol, edge_curves, shape_classes, symbol_table
from tilekit.plugins.curved import delaney, model, wythoff
from tilekit.plugins.curved.patch import ModelPatch, ModelPrototile
from tilekit.plugins.curved.shaped import edge_frames, first_simple, parse_edges, shaped_outline
from tilekit.plugins.curved.tiling import (
    DRAWING_HELP,
    MAX_RADIUS,
    CurvedTiling,
    _number,
    check_plane,
    clipped,
    spec_table,
)

FAMILY = "curved-isohedral"
#: Chart points per segment of an edge's curve (the curve is subdivided on the unit segment
#: before it is carried onto the surface, so it bends smoothly there).
DEFAULT_SAMPLES = 3
MAX_SAMPLES = 16
#: Hyperbolic radius when none is given (the tiles whose centres lie within it).
DEFAULT_RADIUS = 3.0
#: Most assignments of colours to the pairing motions tried for one quotient group (a
#: polygon with many J pairs is coloured by the smaller quotients only).
MAX_ASSIGNMENTS = 200_000
#: Largest k of a colouring searched for (and accepted).
MAX_COLOURS = 8
#: Largest spec file read (a spec is a few hundred bytes; edge shapes are bounded anyway).
MAX_SPEC_BYTES = 1 << 16
#: Peak bytes per tile while a patch is made: the Patch's columns and the breadth-first
#: layers' candidates (p per tile); bounded generously.
BYTES_PER_TILE = 4000

_OPTIONS = ("p", "q", "pairing", "symbol", "edges", "radius", "samples", "colours", "plane", "geometry")
_SPEC_KEYS = set(_OPTIONS) - {"geometry"} | {"name", "title"}
_ROT3 = np.diag([-1.0, -1.0, 1.0])
_ROFL3 = np.diag([1.0, -1.0, 1.0])   # the mirror in the edge's line (the unit segment's ROFL)
_FLIP3 = np.diag([-1.0, 1.0, 1.0])   # the mirror in its perpendicular bisector (FLIP)


# --------------------------------------------------------------------------- the pairing


@dataclass(frozen=True)
class Pairing:
    """Letters naming the p edges: ``labels[i]``; ``partner[i]`` the edge paired with edge i
    (itself for an S edge)."""

    labels: tuple[str, ...]
    partner: tuple[int, ...]

    @classmethod
    def parse(cls, text: Any, p: int) -> Pairing:
        """``'a b c a b c d'`` (letters a-z, spaces or commas between): one letter per edge."""
        if not isinstance(text, str):
            raise ParseError(f"pairing must be text like 'a b a b', got {type(text).__name__}")
        tokens = [t for t in text.replace(",", " ").split() if t]
        if len(tokens) != p or any(len(t) != 1 or not t.isalpha() or not t.islower() for t in tokens):
            raise ParseError(f"pairing {text[:60]!r}: give {p} letters a-z, one per edge of the {p}-gon "
                             "(a letter once: an S edge; twice: a J pair), e.g. " + " ".join("abcdefghijkl"[:p]))
        where: dict[str, list[int]] = {}
        for i, t in enumerate(tokens):
            where.setdefault(t, []).append(i)
        partner = list(range(p))
        for t, idx in where.items():
            if len(idx) > 2:
                raise ParseError(f"pairing {text[:60]!r}: letter {t!r} names {len(idx)} edges; a letter names one "
                                 "edge (S) or two (a J pair)")
            if len(idx) == 2:
                partner[idx[0]], partner[idx[1]] = idx[1], idx[0]
        return cls(tuple(tokens), tuple(partner))

    def __str__(self) -> str:
        return " ".join(self.labels)

    def cycles(self) -> list[list[int]]:
        """The vertex cycles: corner c (vertex c of the polygon, where edge c starts) is glued to
        corner partner(c) + 1."""
        p = len(self.labels)
        seen: set[int] = set()
        out = []
        for c in range(p):
            if c in seen:
                continue
            cyc = []
            while c not in seen:
                seen.add(c)
                cyc.append(c)
                c = (self.partner[c] + 1) % p
            out.append(cyc)
        return out


def check_pairing(pairing: Pairing, p: int, q: int) -> None:
    """Poincaré's condition: every vertex cycle's length divides q (one-line ParameterError)."""
    for cyc in pairing.cycles():
        if q % len(cyc):
            raise ParameterError(
                f"pairing '{pairing}' glues corners {', '.join(str(c + 1) for c in cyc)} of the {p}-gon into one "
                f"vertex, {len(cyc)} corners of angle 2π/{q}: it tiles {{{p},{q}}} only when each vertex cycle's "
                f"length divides q ({q}); {_pairing_hint(p, q)}")


def _pairing_hint(p: int, q: int) -> str:
    ex = example_pairing(p, q)
    return f"e.g. '{ex}'" if ex else f"no pairing of the {p}-gon found for {{{p},{q}}} (p up to 10 searched)"


def pairing_symbol(pairing: Pairing) -> IncidenceSymbol:
    """The incidence symbol of a pairing: every edge its own label, directed; a J pair's two
    labels adjacent with + (a direct hop, the half-turn seen from the edge), an S edge's label
    adjacent to itself with +. The owner edge of each pair keeps the pairing's letter, the
    other edge takes an unused label (a-z, then A-Z: :data:`tilekit.incidence.LABELS`); a
    pairing of more edges than there are labels is a one-line ParameterError."""
    p = len(pairing.labels)
    if p > len(LABELS):
        raise ParameterError(f"pairing '{pairing}': its incidence symbol needs a label per edge, {p}, over the "
                             f"{len(LABELS)} labels a-z, A-Z; pairings are taken on polygons of up to {len(LABELS)} "
                             "edges")
    spare = iter(c for c in LABELS if c not in pairing.labels)
    names = [""] * p
    for i in range(p):
        if pairing.partner[i] >= i:
            names[i] = pairing.labels[i]
    for i in range(p):
        if not names[i]:
            names[i] = next(spare)
    edges = tuple((n, 1) for n in names)
    adjacency = tuple((names[pairing.partner[i]], 1) for i in range(p))
    return IncidenceSymbol(edges, adjacency)


def orbifold(pairing: Pairing | IncidenceSymbol, q: int) -> str:
    """The group's orbifold symbol (Conway), read off the Delaney symbol (:mod:`.delaney`)."""
    sym = pairing_symbol(pairing) if isinstance(pairing, Pairing) else pairing
    return delaney.orbifold_symbol(delaney.check_on(sym, len(sym.edges), q), q)


def example_pairing(p: int, q: int) -> str | None:
    """A pairing of the p-gon that tiles {p, q}: the first found (J pairs of neighbouring
    edges first), or None (p up to 10 searched: 9,496 pairings)."""
    if p > 10:
        return None
    letters = "abcdefghijkl"

    def matchings(free: list[int]) -> Any:
        if not free:
            yield {}
            return
        i, rest = free[0], free[1:]
        for j in rest:
            for m in matchings([k for k in rest if k != j]):
                yield {i: j, j: i, **m}
        for m in matchings(rest):
            yield {i: i, **m}

    for m in matchings(list(range(p))):
        labels, name = [""] * p, 0
        for i in range(p):
            if not labels[i]:
                labels[i] = labels[m[i]] = letters[name]
                name += 1
        pairing = Pairing(tuple(labels), tuple(m[i] for i in range(p)))
        if all(q % len(c) == 0 for c in pairing.cycles()):
            return str(pairing)
    return None


# --------------------------------------------------------------------------- colourings


#: The finite abelian groups a colouring maps onto, smallest first: Z_b (a = 1) or Z_a × Z_b.
QUOTIENTS = ((1, 2), (1, 3), (1, 4), (2, 2), (1, 5), (1, 6), (1, 7), (1, 8), (2, 4))


def colour_classes(symbol: IncidenceSymbol) -> tuple[list[int], list[int], list[bool]]:
    """(class of each edge's hop, its sign ±1, per class whether it is an involution's class):
    hops of one label agree up to tile symmetries, a label's neighbour's hop is its inverse up
    to them, and a label adjacent to itself has a hop whose square is a tile symmetry."""
    adj = symbol.adjacent_map()
    cls: dict[str, tuple[int, int]] = {}
    order2: list[bool] = []
    for lab in symbol.labels:
        if lab in cls:
            continue
        other = adj[lab][0]
        cls[lab] = (len(order2), 1)
        if other != lab:
            cls[other] = (len(order2), -1)
        order2.append(other == lab)
    return ([cls[lab][0] for lab, _ in symbol.edges], [cls[lab][1] for lab, _ in symbol.edges], order2)


def colouring(symbol: IncidenceSymbol, relations: np.ndarray, k: int | None = None
              ) -> tuple[tuple[int, int], tuple[int, ...]]:
    """((a, b), φ per edge's hop as a colour index x·b + y of Z_a × Z_b): a homomorphism of the
    group onto a finite abelian group A (Z_b or Z_a × Z_b, k = |A|), zero on the tile symmetries
    (so a tile has one colour), given by one value per colour class (:func:`colour_classes`)
    that satisfies ``relations`` (rows: the classes' signed counts along two words of hops that
    reach one tile; see :meth:`CurvedIsohedralTiling.relations`); nonzero on every hop when one
    is (neighbours then differ), else any onto A; the smallest A first, or the first with k
    elements when k is asked for; a quotient whose assignments number over MAX_ASSIGNMENTS is
    skipped. None: one colour (k = 1, the trivial colouring, perfect too)."""
    p = len(symbol.edges)
    edge_class, edge_sign, order2 = colour_classes(symbol)
    n = len(order2)
    quotients = [ab for ab in QUOTIENTS if k is None or ab[0] * ab[1] == k]
    if k is not None and not quotients:
        raise ParameterError(f"colours must be one of {', '.join(str(a * b) for a, b in QUOTIENTS[:8])} (the "
                             f"abelian groups searched), got {k}")
    rel = np.asarray(relations, dtype=np.int64).reshape(-1, n)
    for nonzero in (True, False):
        for a, b in quotients:
            elems = [(x, y) for x in range(a) for y in range(b)]
            allowed = elems[1:] if nonzero else elems
            half = [e for e in allowed if not (2 * e[0]) % a and not (2 * e[1]) % b]  # 2φ = 0
            choices = [half if order2[c] else allowed for c in range(n)]
            total = math.prod(len(c) for c in choices)
            if not total or total > MAX_ASSIGNMENTS:
                continue  # budget: this quotient is not searched (the docstring says so)
            cand = np.array(list(itertools.product(*choices)), dtype=np.int64).reshape(total, n, 2)
            ok = ((cand[:, :, 0] @ rel.T) % a == 0).all(axis=1) & ((cand[:, :, 1] @ rel.T) % b == 0).all(axis=1)
            for row in cand[ok]:
                reach = {(0, 0)}
                for _ in range(a * b):
                    reach |= {((r[0] + g[0]) % a, (r[1] + g[1]) % b) for r in reach for g in row.tolist()}
                if len(reach) == a * b:
                    phi = [(int(edge_sign[i] * row[edge_class[i], 0]) % a, int(edge_sign[i] * row[edge_class[i], 1]) % b)
                           for i in range(p)]
                    return (a, b), tuple(x * b + y for x, y in phi)
    if k is not None:
        raise ParameterError(f"incidence symbol {symbol} has no perfect colouring with {k} colours (no "
                             "homomorphism of its group onto an abelian group of that order)")
    return (1, 1), (0,) * p


def add_colours(c: np.ndarray, phi: np.ndarray, quotient: tuple[int, int]) -> np.ndarray:
    """Colour indices (of Z_a × Z_b, index x·b + y) plus φ, elementwise."""
    a, b = quotient
    x = (c // b + phi // b) % a
    y = (c % b + phi % b) % b
    return x * b + y


# --------------------------------------------------------------------------- the tiling


def hops(frames: np.ndarray, symbol: IncidenceSymbol) -> np.ndarray:
    """(p, 3, 3): the hop H_i = F_i O F_j⁻¹ carries the tile onto its neighbour across edge i,
    presenting its edge j there (F the edges' frames, :func:`.shaped.edge_frames`; j and O from
    the symbol: O the half-turn for a direct hop, the mirror in the edge's line for an opposite
    one)."""
    inv = np.linalg.inv(frames)
    table = symbol_table(symbol)
    out = []
    for i in range(len(frames)):
        o = _ROT3 if (table.orientation[i] == ROT).all() else _ROFL3
        out.append(frames[i] @ o @ inv[int(table.partner[i])])
    return np.array(out)


def hop_words(symbol: IncidenceSymbol, motions: np.ndarray, g: model.Geometry, bound: float, sep: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(tiles (n, 3, 3), their words (n, classes), relations (r, classes)): breadth first over
    the hops ``motions`` from the tile (centred at the pole) to every tile whose centre is within
    ``bound`` (the sphere: all), each tile with the signed counts of its word's colour classes
    (:func:`colour_classes`); where two words reach one tile (centres welded at ``sep``, the
    least distance between two tiles' centres), their difference is a relation row."""
    edge_class, edge_sign, order2 = colour_classes(symbol)
    n, p = len(order2), len(symbol.edges)
    step = np.zeros((p, n), dtype=np.int64)
    step[np.arange(p), edge_class] = edge_sign
    mats, words = np.eye(3)[None], np.zeros((1, n), dtype=np.int64)
    layer, layer_w = mats, words
    rows = []
    while len(layer):
        cand = np.matmul(layer[:, None], motions[None]).reshape(-1, 3, 3)
        cw = (layer_w[:, None, :] + step[None]).reshape(-1, n)
        if math.isfinite(bound):
            inside = g.acos(cand[:, 2, 2]) <= bound
            cand, cw = cand[inside], cw[inside]
        allm, allw = np.concatenate([mats, cand]), np.concatenate([words, cw])
        key = allm[:, :, 2] if g.sign > 0 else allm[:, :2, 2]
        rep = wythoff.weld(key, sep)
        dup = np.flatnonzero(rep != np.arange(len(allm)))
        rows.append(allw[dup] - allw[rep[dup]])
        new = np.flatnonzero(rep == np.arange(len(allm)))
        new = new[new >= len(mats)]
        layer, layer_w = allm[new], allw[new]
        mats, words = np.concatenate([mats, layer]), np.concatenate([words, layer_w])
    out = np.concatenate(rows) if rows else np.zeros((0, n), dtype=np.int64)
    return mats, words, np.unique(out, axis=0)


def word_colours(symbol: IncidenceSymbol, words: np.ndarray, quotient: tuple[int, int], phi: tuple[int, ...]
                 ) -> np.ndarray:
    """Colour indices (of Z_a × Z_b, index x·b + y) of tiles reached by words of colour classes
    (:func:`hop_words`): each class's value read back from φ on its edges, summed along the word."""
    a, b = quotient
    edge_class, edge_sign, order2 = colour_classes(symbol)
    value = np.zeros((len(order2), 2), dtype=np.int64)
    for i, c in enumerate(edge_class):
        value[c] = ((edge_sign[i] * (phi[i] // b)) % a, (edge_sign[i] * (phi[i] % b)) % b)
    x = (words @ value[:, 0]) % a
    y = (words @ value[:, 1]) % b
    return x * b + y


def patch_colours(symbol: IncidenceSymbol, motions: np.ndarray, g: model.Geometry, local: np.ndarray, sep: float,
                  what: str, perfect: tuple[tuple[int, int], tuple[int, ...]] | None = None
                  ) -> tuple[tuple[int, int], np.ndarray]:
    """((a, b), colour per tile): the least perfect colouring (:func:`colouring`; ``perfect``
    when the caller has it already) of the tiles ``local`` (n, 3, 3), given in the frame of the
    tile at the pole, each matched by its centre (welded at ``sep``) to the tile that the hops
    ``motions`` reach breadth first (:func:`hop_words`), whose word gives its colour
    (:func:`word_colours`). Shared by the Laves tiles and the vertex-star duals."""
    bound = math.inf
    if g.sign < 0:
        bound = float(g.acos(local[:, 2, 2]).max()) + 1e-9 if len(local) else 0.0
    reached, words, relations = hop_words(symbol, motions, g, bound, sep)
    key = np.concatenate([reached, local])[:, :, 2]
    rep = wythoff.weld(key if g.sign > 0 else key[:, :2], sep)[len(reached):]
    if (rep >= len(reached)).any():
        raise GeometryError(f"{what}: a tile of the patch is not reached by the hops across its edges")
    quotient, phi = perfect if perfect is not None else colouring(symbol, relations)
    return quotient, word_colours(symbol, words, quotient, phi)[rep]


class CurvedIsohedralTiling(CurvedTiling):
    """Copies of one deformable tile filling the sphere or the hyperbolic plane (see the module).

    ``CurvedIsohedralTiling(7, 3, pairing='a b c a b c d', edges={'a': EdgeShape(...)})``.
    """

    streams = False
    bytes_per_tile = BYTES_PER_TILE
    family = FAMILY
    OPTIONS = _OPTIONS

    def __init__(self, p: int | None = None, q: int = 4, *, pairing: str | None = None, symbol: str | None = None,
                 edges: Mapping[str, EdgeShape | str] | None = None, radius: float | None = None,
                 samples: int = DEFAULT_SAMPLES, colours: int | None = None, plane: str = "poincare",
                 geometry: str | None = None, name: str = "", title: str = "") -> None:
        if pairing is not None and symbol is not None:
            raise ParameterError("give a pairing ('a b a b') or an incidence symbol ('[a+b+; b+a+]'), not both")
        parsed = IncidenceSymbol.parse(symbol, len(LABELS)) if symbol is not None else None
        if p is None:
            p = len(parsed.edges) if parsed is not None else 6
        self.p, self.q = model.check_pq(p, q)
        self.kind = model.kind_of(self.p, self.q)
        want = wythoff.check_geometry(geometry)
        if want is not None and want != self.kind:
            raise ParameterError(f"{{{self.p},{self.q}}} is {self.kind}, not {want}: (p-2)(q-2) < 4 is the sphere, "
                                 "> 4 the hyperbolic plane")
        if parsed is None:
            if pairing is None:
                pairing = example_pairing(self.p, self.q)
                if pairing is None:
                    raise ParameterError(f"{{{self.p},{self.q}}}: no side pairing of the {self.p}-gon found; give one "
                                         "(--set pairing='a b ...') or an incidence symbol (--set symbol='[aaa; a]')")
            self.pairing: Pairing | None = Pairing.parse(pairing, self.p)
            check_pairing(self.pairing, self.p, self.q)
            self.symbol = pairing_symbol(self.pairing)
        else:
            self.pairing = None
            self.symbol = parsed
        self.delaney = delaney.check_on(self.symbol, self.p, self.q)
        self.plane = check_plane(plane, self.kind == model.SPHERE)
        self.samples = int(_number("samples", samples, 1, MAX_SAMPLES, True))
        if radius is not None and self.kind == model.SPHERE:
            raise ParameterError("radius applies to hyperbolic tilings; a tiling of the sphere is drawn whole")
        self.radius = None if radius is None else float(_number("radius", radius, 0, MAX_RADIUS, False))
        self.polygon = model.RegularPolygon(self.p, self.q)
        self.quotient, self.phi = colouring(self.symbol, self.relations(),
                                            None if colours is None else
                                            int(_number("colours", colours, 1, MAX_COLOURS, True)))
        self.colour_count = self.quotient[0] * self.quotient[1]
        self.asked_colours = colours is not None
        self.name = name or f"{FAMILY}-{self.p}-{self.q}"
        self.title = title
        # the default shapes bend less where the corners are sharp (angle 2π/q), halved until
        # the tile is simple (an edge shape given is never changed: a crossing is its error)
        self.edge_shapes, self._proto = first_simple(
            self.symbol, edges or {}, f"{{{self.p},{self.q}}} with {self._what()}", min(1.0, 4.0 / self.q),
            self._prototile)

    # -- shapes ------------------------------------------------------------------------
    def _label(self, i: int) -> str:
        return self.pairing.labels[i] if self.pairing is not None else self.symbol.edges[i][0]

    def _what(self) -> str:
        return f"pairing '{self.pairing}'" if self.pairing is not None else f"incidence symbol {self.symbol}"

    def edge_curves(self) -> list[np.ndarray]:
        """Each edge's curve on the unit segment, (0,0) to (1,0), in the tile's counter-clockwise
        direction: levels 1 and 2 of the edge model (:func:`tilekit.incidence.edge_curves`: J
        whole, S and U completed by the half-turn or the mirror, I straight, a label's neighbour
        the hop's image)."""
        return edge_curves(self.symbol, self.edge_shapes)

    @cached_property
    def frames(self) -> np.ndarray:
        """(p, 3, 3): each edge's frame at its midpoint, the x axis along the edge
        (:func:`.shaped.edge_frames`)."""
        return edge_frames(self.polygon.geometry.sign, self.polygon.vertices())

    @cached_property
    def motions(self) -> np.ndarray:
        """(p, 3, 3): the hop H_i = F_i O F_j⁻¹ carries the tile onto its neighbour across edge
        i, presenting its edge j there (O the half-turn for a direct hop, the mirror in the
        edge's line for an opposite one)."""
        return hops(self.frames, self.symbol)

    @cached_property
    def tile_symmetries(self) -> np.ndarray:
        """(s, 3, 3): the motions of the tile onto itself that keep labels and arrows."""
        f = self.frames
        inv0 = np.linalg.inv(f[0])
        return np.array([f[shift] @ (_FLIP3 if reflect else np.eye(3)) @ inv0
                         for shift, reflect in self.symbol.tile_symmetries()])

    def relations(self) -> np.ndarray:
        """Relations among the colour classes' values (:func:`hop_words`, with the tiles within
        two circumradii: the tiles round the tile's vertices, whose cycles give the group's
        relations with the classes' own)."""
        bound = math.inf if not self.hyperbolic else 2 * self.polygon.circumradius + 1e-9
        return hop_words(self.symbol, self.motions, self.polygon.geometry, bound, 2 * self.polygon.inradius)[2]

    def _prototile(self, shapes: Mapping[str, EdgeShape]) -> ModelPrototile:
        g = self.polygon.geometry
        lengths = [self.polygon.edge_length] * self.p
        pts, triangles = shaped_outline(g, self.frames, lengths, edge_curves(self.symbol, shapes), self.samples,
                                        f"{{{self.p},{self.q}}}", self._label)
        return ModelPrototile.on_model(pts, sign=g.sign, name=f"{{{self.p},{self.q}}} tile", plane=self.plane,
                                       corners=tuple(range(len(pts))), triangles=triangles)

    # -- the Tiling interface ------------------------------------------------------------
    @property
    def prototiles(self) -> list[ModelPrototile]:
        return [self._proto]

    def _radius(self) -> float:
        return DEFAULT_RADIUS if self.radius is None else self.radius

    def estimate_tiles(self, region: Any = None) -> float:
        """The sphere's face count; hyperbolic: the disc's area (grown by a circumradius) over a
        tile's."""
        if not self.hyperbolic:
            return 4 * math.pi / self.polygon.area
        r = self._radius() + self.polygon.circumradius
        return 1.0 + 2 * math.pi * (math.cosh(r) - 1) / self.polygon.area

    def group_elements(self) -> tuple[np.ndarray, np.ndarray]:
        """(Γ's elements, one per tile: (n, 3, 3); their colours φ (n,)), breadth first across
        edges; hyperbolic: the tiles whose centre lies within the radius. The colours are
        checked to agree wherever two paths reach one tile."""
        est = self.estimate_tiles()
        self.refuse_oversize(f"tiles of {{{self.p},{self.q}}}", est,
                             "ask for a smaller radius (--set radius=R)" if self.hyperbolic else "")
        g = self.polygon.geometry
        sep = 2 * self.polygon.inradius
        bound = math.inf if not self.hyperbolic else self._radius() + 2 * self.polygon.circumradius
        motions, phi = self.motions, np.array(self.phi)
        layers, colours = [np.eye(3)[None]], [np.zeros(1, dtype=np.int64)]
        prev, prev_c = [np.zeros((0, 3, 3)), layers[0]], [np.zeros(0, dtype=np.int64), colours[0]]

        def key(m: np.ndarray) -> np.ndarray:
            c = m[:, :, 2]
            return c if g.sign > 0 else c[:, :2]

        while True:
            cand = np.matmul(layers[-1][:, None], motions[None]).reshape(-1, 3, 3)
            cc = add_colours(colours[-1][:, None], phi[None, :], self.quotient).reshape(-1)
            if math.isfinite(bound):
                inside = g.acos(cand[:, 2, 2]) <= bound
                cand, cc = cand[inside], cc[inside]
            known = np.concatenate(prev)
            known_c = np.concatenate(prev_c)
            allm = np.concatenate([known, cand])
            allc = np.concatenate([known_c, cc])
            rep = wythoff.weld(key(allm), sep)
            if (allc != allc[rep]).any():
                raise GeometryError(f"{self._what()}: the colouring disagrees where two paths meet "
                                    "(not a homomorphism)")
            first = len(known)
            new = np.flatnonzero(rep == np.arange(len(allm)))
            new = new[new >= first]
            if not len(new):
                break
            layers.append(allm[new])
            colours.append(allc[new])
            prev, prev_c = [prev[-1], layers[-1]], [prev_c[-1], colours[-1]]
        mats, cols = np.concatenate(layers), np.concatenate(colours)
        if self.hyperbolic:
            keep = g.acos(mats[:, 2, 2]) <= self._radius() + 1e-12
            mats, cols = mats[keep], cols[keep]
        return mats, cols

    def symmetries(self, reach: float) -> np.ndarray:
        """(n, 3, 3) proper motions of the group that keep the colouring (φ = 0) and move the
        pole at most ``reach`` (hyperbolic; the identity first): the viewer folds them into
        its view, which leaves the coloured picture unchanged."""
        mats, cols = self.configure(radius=reach).group_elements()
        keep = mats[cols == 0]
        both = np.matmul(keep[:, None], self.tile_symmetries[None]).reshape(-1, 3, 3)
        both = both[(np.linalg.det(both) > 0) & (both[:, 2, 2] <= math.cosh(reach) * (1 + 1e-12))]
        return both

    def patch(self, region: Any = None) -> ModelPatch:
        """Every tile (sphere) or every tile whose centre lies within the radius, coloured by
        the perfect colouring (see the module), less those whose outline misses ``region``."""
        mats, cols = self.group_elements()
        patch = ModelPatch([self._proto], np.zeros(len(mats), dtype=np.int64), mats, colour=cols)
        return clipped(patch, region)

    # -- records, options, specs ----------------------------------------------------------
    def properties(self) -> dict[str, Any]:
        props = type_properties(self.symbol, self.p, self.q, self.delaney)
        props.update(colours=self.colour_count,
                     colour_group=(f"Z{self.quotient[1]}" if self.quotient[0] == 1
                                   else f"Z{self.quotient[0]} x Z{self.quotient[1]}"))
        if self.pairing is not None:
            props["pairing"] = str(self.pairing)
        return props

    def describe(self) -> str:
        where = "the sphere" if not self.hyperbolic else "the hyperbolic plane"
        return (f"isohedral tiles of {where} on {{{self.p},{self.q}}}: edges {self.symbol.edge_kinds()}, "
                f"{self._what()}, group {delaney.orbifold_symbol(self.delaney, self.q)}, a perfect "
                f"{self.colour_count}-colouring")

    def options_help(self) -> str:
        return "\n".join([
            "--set p=P --set q=Q         the regular tiling {P,Q} whose polygon is deformed",
            "--set pairing='a b a b ...' one letter per edge: once an S edge, twice a J pair",
            "--set symbol='[aaa; a]'     an incidence symbol (§5.2) instead: tile symmetry, U/I/glide edges",
            "--set edges=JSON            edge shapes by letter, e.g. '{\"a\": \"0.2,0.1:0.4,0.1\"}' (EdgeShape text)",
            f"--set radius=R              hyperbolic: the tiles whose centre is within R (default {DEFAULT_RADIUS:g})",
            f"--set samples=N             chart points per segment of an edge curve (1..{MAX_SAMPLES}, default "
            f"{DEFAULT_SAMPLES})",
            f"--set colours=K             the perfect colouring's colour count (2..{MAX_COLOURS}; default the least)",
            *DRAWING_HELP[1:],
        ])

    def configure(self, **options: Any) -> CurvedIsohedralTiling:
        self.check_options(options)
        spec = self.spec()
        if "edges" in options:
            options["edges"] = parse_edges(options["edges"])
        if {"p", "q"} & set(options):
            if "pairing" not in options and "symbol" not in options:
                spec.pop("pairing", None)
                spec.pop("symbol", None)
                spec.pop("edges", None)
            p, q = model.check_pq(options.get("p", self.p), options.get("q", self.q))
            if model.kind_of(p, q) == model.SPHERE:  # a sphere is drawn whole, in its own view
                for key in ("radius", "plane"):
                    if key not in options:
                        spec.pop(key, None)
        if "symbol" in options:
            spec.pop("pairing", None)
            if "edges" not in options:
                spec.pop("edges", None)
            if "p" not in options:
                spec.pop("p", None)
        if "pairing" in options:
            spec.pop("symbol", None)
            if "edges" not in options:
                spec.pop("edges", None)
        spec.update(options)
        return CurvedIsohedralTiling.from_spec(spec)

    def spec(self) -> dict[str, Any]:
        out: dict[str, Any] = {"p": self.p, "q": self.q}
        if self.pairing is not None:
            out["pairing"] = str(self.pairing)
        else:
            out["symbol"] = str(self.symbol)
        out["edges"] = {k: v.to_text() for k, v in sorted(self.edge_shapes.items())}
        if self.radius is not None:
            out["radius"] = self.radius
        if self.samples != DEFAULT_SAMPLES:
            out["samples"] = self.samples
        if self.asked_colours:
            out["colours"] = self.colour_count
        if self.plane != "poincare":
            out["plane"] = self.plane
        if self.name != f"{FAMILY}-{self.p}-{self.q}":
            out["name"] = self.name
        if self.title:
            out["title"] = self.title
        return out

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> CurvedIsohedralTiling:
        spec_table(spec, sorted(_SPEC_KEYS | {"geometry"}), FAMILY)  # geometry: a check, as in configure
        return cls(spec.get("p"), spec.get("q", 4), pairing=spec.get("pairing"), symbol=spec.get("symbol"),
                   edges=spec.get("edges"),
                   radius=spec.get("radius"), samples=spec.get("samples", DEFAULT_SAMPLES),
                   colours=spec.get("colours"), plane=spec.get("plane", "poincare"), geometry=spec.get("geometry"),
                   name=str(spec.get("name", "")), title=str(spec.get("title", "")))


def type_properties(symbol: IncidenceSymbol, p: int, q: int, d: delaney.Delaney | None = None,
                    canonical: bool = False) -> dict[str, Any]:
    """What a type's record says without drawing it (cheap: no geometry): the space, {p,q},
    the incidence symbol and its canonical form, the edge kinds (J/U/S/I, per edge and
    counted), ``edge_shapes`` (the free fundamental shapes: the type's parameters, the
    polygon itself being rigid), the tile's own symmetries and the group's orbifold.
    ``canonical``: the symbol is in canonical form already (as the enumeration yields it)."""
    d = d if d is not None else delaney.check_on(symbol, p, q)
    group = delaney.orbifold_symbol(d, q)
    kinds = symbol.edge_kinds()
    hyperbolic = model.kind_of(p, q) == model.HYPERBOLIC
    return {
        "periodic": hyperbolic,
        "k_isohedral": 1,
        "k_hedral": 1,
        "geometry": model.kind_of(p, q),
        "p": p,
        "q": q,
        "schlafli": f"{{{p},{q}}}",
        "incidence_symbol": str(symbol),
        "canonical_symbol": str(symbol if canonical else symbol.canonical()),
        "edge_kinds": kinds,
        "j_edges": kinds.count("J"),
        "u_edges": kinds.count("U"),
        "s_edges": kinds.count("S"),
        "i_edges": kinds.count("I"),
        "edge_shapes": len(shape_classes(symbol)),
        "tile_symmetry": len(symbol.tile_symmetries()),
        "symmetry_group": group,
        "orbifold": group,
        "sides": [p],
    }


def write_spec(tiling: CurvedIsohedralTiling, path: str | Path) -> None:
    """The tiling's spec as a JSON file that :func:`from_file` reopens to the same tiling."""
    Path(path).write_text(json.dumps(tiling.spec(), indent=2, sort_keys=True) + "\n")


def from_file(path: str) -> CurvedIsohedralTiling:
    """A tiling from a spec file (JSON, as :func:`write_spec` writes it; read bounded)."""
    text = read_text(path, f"{FAMILY} spec", MAX_SPEC_BYTES)
    try:
        spec = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ParseError(f"{FAMILY} spec {Path(path).name}: not JSON ({exc.msg} at line {exc.lineno})") from None
    return CurvedIsohedralTiling.from_spec(spec)
