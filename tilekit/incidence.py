"""Incidence symbols of isohedral tilings (§5.2): parse, print, edge kinds, canonical form, and
what they say about the edges independent of geometry: each edge's hop (the neighbour's edge
it meets and whether the meeting is direct, a half-turn, or opposite, a mirror) and the
edge curves on the unit segment (levels 1 and 2 of :mod:`tilekit.edgeshapes`). Shared by the
planar isohedral family and the curved family's isohedral tiles on {p, q}.

An incidence symbol such as ``[a+b+c+c-b-a-; a-c+b+]`` lists, counter-clockwise around the
tile, the label of every tiling edge with its direction (``+`` agrees with the traversal,
``-`` opposes it, no sign: undirected), then for each distinct label in order of first
appearance the label of the edge adjacent to it in the neighbouring tile (with ``+`` when the
direction is preserved across the edge and ``-`` when it is reversed). The book's
superscript form ``$[a^+b^+c^+c^-b^-a^-; a^-c^+b^+]$`` is accepted as well.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from itertools import permutations

import numpy as np

from tilekit.edgeshapes import FLIP, IDENTITY, ROFL, ROT, EdgeShape, apply_unit, complete
from tilekit.errors import ParseError

#: One labelled edge: (label, sign) with sign +1, -1 or 0 (undirected).
Edge = tuple[str, int]

#: Most tiling edges a symbol may list (isohedral tiles have 3 to 6; generous for variants),
#: and the longest text parsed (the book's superscript form takes about 8 characters an edge).
MAX_EDGES = 12
MAX_TEXT = 400
#: The labels, in the order symbols are relabelled with them: a-z, then A-Z for a tile of
#: more than 26 edges (the curved family's side pairings of p-gons), so every symbol of up to
#: 26 labels reads exactly as before. One character a label; upper and lower case differ.
LABELS = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"

_TOKEN = re.compile(r"([a-zA-Z])(\^?\{?([+-])\}?)?")
_RANK = {c: i for i, c in enumerate(LABELS)}  # a-z before A-Z when symbols are ordered
_SIGN = {"+": 1, "-": -1, None: 0}
_SIGN_TEXT = {1: "+", -1: "-", 0: ""}


def _normalise(text: str) -> str:
    s = text.strip().strip("$").strip()
    s = s.replace("\\cdot", " ").replace("^+", "+").replace("^-", "-")
    s = s.replace("^{+}", "+").replace("^{-}", "-")
    return s


def _parse_part(part: str, text: str, which: str) -> list[Edge]:
    compact = re.sub(r"\s+", "", part)
    out: list[Edge] = []
    pos = 0
    while pos < len(compact):
        m = _TOKEN.match(compact, pos)
        if not m:
            raise ParseError(
                f"incidence symbol {text!r}: unexpected {compact[pos:pos + 3]!r} in the {which} part "
                "(expected labels a-z or A-Z, each optionally followed by + or -)"
            )
        out.append((m.group(1), _SIGN[m.group(3)]))
        pos = m.end()
    if not out:
        raise ParseError(f"incidence symbol {text!r}: the {which} part is empty")
    return out


@dataclass(frozen=True)
class IncidenceSymbol:
    """The two halves of an incidence symbol: ``edges`` around the tile, ``adjacency`` per label."""

    edges: tuple[Edge, ...]
    adjacency: tuple[Edge, ...]

    # construction ------------------------------------------------------------------
    @classmethod
    def parse(cls, text: str, max_edges: int = MAX_EDGES) -> IncidenceSymbol:
        """Parse the ASCII form ``[a+b+a-; b-a+]`` or the book's ``$[a^+b^+ ...]$`` form, of at
        most ``max_edges`` tiling edges (up to ``len(LABELS)``)."""
        if not isinstance(text, str):
            raise ParseError(f"incidence symbol {text!r} is not text like '[a+b+a-; b-a+]'")
        if len(text) > MAX_TEXT:
            raise ParseError(
                f"incidence symbol {text[:30]!r}... is {len(text)} characters long; an isohedral tile "
                f"has at most {max_edges} tiling edges (§5.2)"
            )
        s = _normalise(text)
        m = re.fullmatch(r"\[([^;\]]*);([^;\]]*)\]", s)
        if not m:
            raise ParseError(
                f"incidence symbol {text!r} is not of the form '[a+b+c+c-b-a-; a-c+b+]' "
                "(edge labels, a semicolon, adjacent labels, in square brackets)"
            )
        edges = _parse_part(m.group(1), text, "first")
        if len(edges) > max_edges:
            raise ParseError(
                f"incidence symbol {text!r} has {len(edges)} edges; an isohedral tile has at most "
                f"{max_edges} tiling edges (§5.2)"
            )
        adjacency = _parse_part(m.group(2), text, "second")
        sym = cls(tuple(edges), tuple(adjacency))
        sym.check(text)
        return sym

    def check(self, text: str | None = None) -> None:
        """Raise ParseError unless the symbol is internally consistent."""
        what = f"incidence symbol {text or str(self)!r}"
        labels = self.labels
        if len(self.adjacency) != len(labels):
            raise ParseError(
                f"{what}: {len(labels)} distinct edge labels ({''.join(labels)}) need "
                f"{len(labels)} adjacency entries, got {len(self.adjacency)}"
            )
        signs: dict[str, set[int]] = {}
        for lab, sg in self.edges:
            signs.setdefault(lab, set()).add(sg)
        for lab, ss in signs.items():
            if 0 in ss and len(ss) > 1:
                raise ParseError(f"{what}: label {lab!r} is both directed and undirected")
        adj = self.adjacent_map()
        for lab, (other, sg) in adj.items():
            if other not in signs:
                raise ParseError(f"{what}: label {lab!r} is adjacent to {other!r}, which labels no edge")
            directed = 0 not in signs[lab]
            if directed != (sg != 0):
                raise ParseError(
                    f"{what}: adjacency of {lab!r} must carry a sign exactly when {lab!r} is directed"
                )
            if (0 not in signs[other]) != directed:
                raise ParseError(f"{what}: {lab!r} and its neighbour {other!r} differ in directedness")
            back, bsg = adj[other]
            if back != lab or bsg != sg:
                raise ParseError(
                    f"{what}: adjacency is not symmetric ({lab!r} -> {other!r}{_SIGN_TEXT[sg]} but "
                    f"{other!r} -> {back!r}{_SIGN_TEXT[bsg]})"
                )

    # views ---------------------------------------------------------------------------
    @property
    def labels(self) -> list[str]:
        """Distinct labels in order of first appearance."""
        seen: list[str] = []
        for lab, _ in self.edges:
            if lab not in seen:
                seen.append(lab)
        return seen

    def adjacent_map(self) -> dict[str, Edge]:
        return dict(zip(self.labels, self.adjacency))

    def __len__(self) -> int:
        return len(self.edges)

    def __str__(self) -> str:
        first = "".join(lab + _SIGN_TEXT[sg] for lab, sg in self.edges)
        second = "".join(lab + _SIGN_TEXT[sg] for lab, sg in self.adjacency)
        return f"[{first}; {second}]"

    def latex(self) -> str:
        """The book's form, e.g. ``$[a^+b^+c^+; a^-b^+c^-]$``."""

        def part(items: tuple[Edge, ...]) -> str:
            return "".join(lab + ("^" + _SIGN_TEXT[sg] if sg else "") for lab, sg in items)

        return f"$[{part(self.edges)}; {part(self.adjacency)}]$"

    # edge kinds (§5.3.1) ---------------------------------------------------------------
    def label_kind(self, label: str) -> str:
        """J, U, S or I for a label, by the rules of §5.3.1."""
        other, sg = self.adjacent_map()[label]
        directed = self._directed(label)
        if not directed:
            return "I" if other == label else "U"
        if other == label:
            return "S" if sg > 0 else "I"
        return "J"

    def _directed(self, label: str) -> bool:
        return any(sg != 0 for lab, sg in self.edges if lab == label)

    def edge_kinds(self) -> str:
        """One letter per edge, e.g. 'IJJJJI' for IH16."""
        return "".join(self.label_kind(lab) for lab, _ in self.edges)

    # canonical form ------------------------------------------------------------------
    def variants(self) -> list[IncidenceSymbol]:
        """Every symbol of the same tiling type: each starting edge, both directions, relabelled.

        Reversing the traversal direction reverses the edge order and flips every edge sign
        (adjacency signs record preservation across an edge and do not change). Labels are
        renamed a, b, c ... in order of first appearance with each label's first arrow
        counter-clockwise, which is the lexicographic minimum over relabellings (and arrow
        choices) for that starting edge and direction.
        """
        n = len(self.edges)
        out: list[IncidenceSymbol] = []
        for direction in (1, -1):
            seq = list(self.edges) if direction == 1 else [(lab, -sg) for lab, sg in reversed(self.edges)]
            for start in range(n):
                rot = seq[start:] + seq[:start]
                out.append(self._relabelled(rot))
        return out

    def _relabelled(self, seq: list[Edge]) -> IncidenceSymbol:
        """Rename labels a, b, ... in order of appearance and redraw arrows so that each
        label's first edge points counter-clockwise (Step 1 of §5.2's derivation)."""
        return self._renamed(seq, *self._relabelling(seq))

    @staticmethod
    def _relabelling(seq: list[Edge]) -> tuple[dict[str, str], set[str]]:
        """(new name per label, labels whose arrows are reversed) for :meth:`_relabelled`."""
        names: dict[str, str] = {}
        flipped: set[str] = set()
        for lab, sg in seq:
            if lab not in names:
                names[lab] = LABELS[len(names)]
                if sg < 0:
                    flipped.add(lab)
        return names, flipped

    def _renamed(self, seq: list[Edge], names: dict[str, str], flipped: set[str]) -> IncidenceSymbol:
        """The edges ``seq`` (this symbol's, in some order) renamed by ``names`` with the arrows
        of the labels in ``flipped`` reversed.

        Reversing the arrows of a label x negates its signs around the tile; the adjacency
        sign between x and a different label y flips too (arrows that opposed now agree),
        while a label adjacent to itself keeps its adjacency sign.
        """
        adj = self.adjacent_map()
        edges = tuple((names[lab], -sg if lab in flipped else sg) for lab, sg in seq)
        labels = []
        for lab, _ in seq:
            if lab not in labels:
                labels.append(lab)
        adjacency = []
        for lab in labels:
            other, t = adj[lab]
            if other != lab and ((lab in flipped) != (other in flipped)):
                t = -t
            adjacency.append((names[other], t))
        return IncidenceSymbol(edges, tuple(adjacency))

    def canonical_labelling(self) -> IncidenceSymbol:
        """This symbol in its own edge order (edge i stays edge i) with the labels and arrows of
        its canonical form (:meth:`canonical`), so that a label of the canonical symbol names the
        same edges here; read clockwise, the canonical form's arrows show as '-' here."""
        n = len(self.edges)
        best: tuple[IncidenceSymbol, dict[str, str], set[str]] | None = None
        for direction in (1, -1):
            seq = list(self.edges) if direction == 1 else [(lab, -sg) for lab, sg in reversed(self.edges)]
            for start in range(n):
                rot = seq[start:] + seq[:start]
                names, flipped = self._relabelling(rot)
                sym = self._renamed(rot, names, flipped)
                if best is None or sym.sort_key() < best[0].sort_key():
                    # read clockwise every sign is negated, and negated back when the arrows are
                    # read counter-clockwise again: the same labels' arrows are reversed
                    best = (sym, names, flipped)
        if best is None:
            return self
        _, names, flipped = best
        return self._renamed(list(self.edges), names, flipped)

    def sort_key(self) -> tuple:
        # order: letters, then '+' before '-' before no sign (as Grünbaum and Shephard list them)
        order = {1: 0, -1: 1, 0: 2}
        return (
            tuple((_RANK.get(lab, len(LABELS)), lab, order[sg]) for lab, sg in self.edges),
            tuple((_RANK.get(lab, len(LABELS)), lab, order[sg]) for lab, sg in self.adjacency),
        )

    def canonical(self) -> IncidenceSymbol:
        """The lexicographically first symbol over relabelling, starting edge and direction."""
        return min(self.variants(), key=IncidenceSymbol.sort_key)

    def relabel(self, mapping: dict[str, str]) -> IncidenceSymbol:
        """Rename labels (a bijection); used to test that renaming preserves the type."""
        if sorted(mapping) != sorted(self.labels) or len(set(mapping.values())) != len(mapping):
            raise ParseError(f"relabelling {mapping} is not a bijection on the labels {self.labels}")
        edges = tuple((mapping[lab], sg) for lab, sg in self.edges)
        adjacency = tuple((mapping[lab], sg) for lab, sg in self.adjacency)
        return IncidenceSymbol(edges, adjacency)

    def rotated(self, start: int, reverse: bool = False) -> IncidenceSymbol:
        """The same symbol read from edge ``start`` (0-based), optionally clockwise; labels kept."""
        seq = list(self.edges) if not reverse else [(lab, -sg) for lab, sg in reversed(self.edges)]
        seq = seq[start:] + seq[:start]
        adj = self.adjacent_map()
        labels: list[str] = []
        for lab, _ in seq:
            if lab not in labels:
                labels.append(lab)
        return IncidenceSymbol(tuple(seq), tuple(adj[lab] for lab in labels))

    # tile symmetries -------------------------------------------------------------------
    def tile_symmetries(self) -> list[tuple[int, bool]]:
        """Edge permutations of the tile that preserve labels and arrows.

        Each is (shift, reflect): edge i goes to edge (shift + i) mod n without reflection,
        or to edge (shift - i) mod n traversed backwards with reflection (signs flip). The
        identity (0, False) comes first.
        """
        n = len(self.edges)
        out: list[tuple[int, bool]] = []
        for reflect in (False, True):
            for shift in range(n):
                ok = True
                for i, (lab, sg) in enumerate(self.edges):
                    j = (shift - i) % n if reflect else (shift + i) % n
                    lab2, sg2 = self.edges[j]
                    if lab2 != lab or sg2 != (-sg if reflect else sg):
                        ok = False
                        break
                if ok:
                    out.append((shift, reflect))
        return out


def all_relabellings(symbol: IncidenceSymbol) -> list[IncidenceSymbol]:
    """Every renaming of the labels by letters a.. (small symbols only: at most 6 labels)."""
    labels = symbol.labels
    letters = list(LABELS[:len(labels)])
    return [symbol.relabel(dict(zip(labels, p))) for p in permutations(letters)]


# --------------------------------------------------------------------------- hops and edge curves


@dataclass(frozen=True)
class SymbolTable:
    """What the hops of an incidence symbol are, independent of the tiling vertices: per edge
    i, the edge j of the neighbour that meets it (``partner``) and the orientation O of
    ``H_i = T_i O T_j^-1`` (the half-turn ROT or the mirror ROFL). Compiled once per symbol."""

    partner: np.ndarray  # (n,) int
    orientation: np.ndarray  # (n, 3, 3)


@functools.cache
def symbol_table(symbol: IncidenceSymbol) -> SymbolTable:
    """The compiled :class:`SymbolTable` of ``symbol`` (cached: symbols are frozen)."""
    adj = symbol.adjacent_map()
    first = {}
    for j, (lab, _) in enumerate(symbol.edges):
        first.setdefault(lab, j)  # the first edge with the adjacent label (the rules assume this)
    partner, orientation = [], []
    for label, sign in symbol.edges:
        other, t = adj[label]
        j = first[other]
        direct = sign != 0 and t == sign * symbol.edges[j][1]  # undirected edges: a mirror image
        partner.append(j)
        orientation.append(ROT if direct else ROFL)
    return SymbolTable(np.array(partner, dtype=np.int64), np.array(orientation))


def shape_classes(symbol: IncidenceSymbol, order: Sequence[str] | None = None) -> list[str]:
    """Labels that own a fundamental shape: one per pair of adjacent labels, I edges excluded;
    of a pair, the first in ``order`` (default: the symbol's order of first appearance)."""
    out: list[str] = []
    adj = symbol.adjacent_map()
    for lab in (symbol.labels if order is None else order):
        if symbol.label_kind(lab) == "I":
            continue
        other = adj[lab][0]
        if other in out:
            continue
        out.append(lab)
    return out


def unit_orientation(symbol: IncidenceSymbol, i: int) -> np.ndarray:
    """O_i: how edge i's curve sits relative to its label's curve (FLIP for reversed arrows)."""
    return FLIP if symbol.edges[i][1] < 0 else IDENTITY


def label_curves(symbol: IncidenceSymbol, shapes: Mapping[str, EdgeShape],
                 order: Sequence[str] | None = None) -> dict[str, np.ndarray]:
    """Levels 1 and 2 of the edge model: the curve of every label on the unit segment, from
    (0,0) to (1,0); a label adjacent to another takes the image of that one's curve under the
    hop between them (so the two tiles share the edge point for point); ``order`` picks each
    pair's owner as :func:`shape_classes` does."""
    table = symbol_table(symbol)
    curves: dict[str, np.ndarray] = {
        lab: complete("I", None) for lab in symbol.labels if symbol.label_kind(lab) == "I"
    }
    for rep in shape_classes(symbol, order):
        kind = symbol.label_kind(rep)
        base = complete(kind, shapes.get(rep))
        curves[rep] = base
        other, _ = symbol.adjacent_map()[rep]
        if other != rep:
            i = next(k for k, (lab, _) in enumerate(symbol.edges) if lab == rep)
            j = int(table.partner[i])
            c = apply_unit(unit_orientation(symbol, i), base)
            c = apply_unit(table.orientation[i], c)
            c = apply_unit(unit_orientation(symbol, j), c)
            curves[other] = c
    return curves


def edge_curves(symbol: IncidenceSymbol, shapes: Mapping[str, EdgeShape],
                order: Sequence[str] | None = None) -> list[np.ndarray]:
    """Each edge's curve on the unit segment, in the tile's traversal direction (``order``: as
    for :func:`label_curves`)."""
    curves = label_curves(symbol, shapes, order)
    return [apply_unit(unit_orientation(symbol, i), curves[lab]) for i, (lab, _) in enumerate(symbol.edges)]
