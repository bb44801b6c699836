"""The quasivertex parameterization of Penrose's kite and dart (P2, book §6.3), derived from
the substitution family's own P2 patches because the book's Figure 6.12 (its formulas) is not
in the extracted text; only its consequences are: the edge labels ``abcdaefghd`` (kite) and
``ghefgcdabf`` (dart) and the interlocking pairs (a,d), (b,h), (c,e), (f,g), "four
non-congruent edge shapes between them".

Derivation (:func:`tilekit.plugins.substitution.p2_derivation.derive`, re-run by the tests):

1. The straight P2 patch gives the interlocking edge classes of the kite and dart
   (:func:`~.shapes.edge_classes`): class 0 holds the four long edges, class 1 the four short
   ones, each edge traversed with (+1) or against (-1) its class's direction.
2. Tiling vertices are moved off the corners the way P3's r1, theta1, r2, theta2 move them
   (Figure 6.13): every edge of a class is a polyline ``P, P + d*ks, Q - d*ke, Q`` from its
   class start P to its class end Q (d the unit direction, complex numbers), so each class
   has two unknown *spokes* ks, ke (a point at distance |ks| from a corner, at angle arg ks
   from the edge). A shared edge is drawn by both its tiles from the same class polyline, so
   any spokes give interlocking tiles; what makes a spoke point a *tiling vertex* is a
   degeneracy (the book: "partially overlapping tile edges"): a tile corner is *cut* when the
   spoke ending its incoming edge and the spoke starting its outgoing edge coincide, so the
   corner drops out of the tile and its neighbours meet along the spoke. Each cut is one
   complex linear equation on the spokes.
3. For every choice of cut corners (none, one or two per tile) the equations' null space is
   computed (SVD), a generic member of it is drawn, and a patch of the deformed tiles is
   built and checked: ``Patch.validate`` (no gap, no overlap), every piece (the segment
   between two consecutive quasivertices) shared with exactly one reversed piece of a
   neighbour (no quasivertex of one tile lies inside a piece of another), and a union-find
   with parity over the pieces of the patch groups them into interlocking classes - which
   piece is which is read off the adjacencies, not assumed. The result is compared with the
   book's labels up to renaming the four pairs and choosing each tile's first edge.

Exactly two cut choices reproduce the book, mirror images of one another: the kite cut at its
side corner 1 and the dart at its side corner 3 (the one used here), or the kite at 3 and the
dart at 1. Both leave a four-dimensional null space with

    ks(short) = rot(36 deg) * ke(long),     ke(short) = rot(72 deg) * ks(long),

so two free complex numbers: ``ks(long) = r1 * exp(i theta1)`` and ``ke(long) = r2 * exp(i
theta2)`` - the four parameters r1, theta1, r2, theta2 of P3, here measured from the long
edge's direction at its class start (the kite's side corner 1, the dart's apex) and from the
reversed direction at its class end (the kite's apex, the dart's side corners): theta = 0
puts the spoke on the edge itself. In the system's frames (kite corners K0 = 0 (apex),
K1 = phi e^(-i pi/10), K2 = phi e^(i pi/10), K3 = phi e^(3i pi/10); dart corners D0 = 0
(reflex), D1 = e^(-3i pi/10), D2 = e^(3i pi/10) (apex), D3 = -e^(-i pi/10)), with
u(a, b) the unit vector from a to b, w1 = r1 e^(i theta1), w2 = r2 e^(i theta2),
rho = e^(i pi/5):

    kite: K0, K0 + u(K0,K1) w2, K1 + u(K1,K0) w1 [= K1 + u(K1,K2) rho^2 w1, the cut],
          K2 + u(K2,K1) rho w2, K2, K2 + u(K2,K3) rho w2, K3 + u(K3,K2) rho^2 w1,
          K3, K3 + u(K3,K0) w1, K0 + u(K0,K3) w2
    dart: D0, D0 + u(D0,D1) rho^2 w1, D1 + u(D1,D0) rho w2, D1, D1 + u(D1,D2) w2,
          D2 + u(D2,D1) w1, D2, D2 + u(D2,D3) w1, D3 + u(D3,D2) w2
          [= D3 + u(D3,D0) rho w2, the cut], D0 + u(D0,D3) rho^2 w1

(the point rotations follow from the spokes' definition, each spoke turned into its edge's
frame). Starting the kite at K0 and the dart at D2 the pieces carry the book's labels
``abcdaefghd`` and ``ghefgcdabf``. r1 = r2 = 0 gives the straight kite and dart back.
"""

from __future__ import annotations

import cmath
import math

import numpy as np

#: The system whose tiles these formulas deform.
SYSTEM = "penrose-p2"
#: Per tile (system order kite, dart), per edge i (corner i to corner i+1): (edge class,
#: +1 along the class direction / -1 against it); class 0 = long edges, 1 = short edges.
EDGES = {"kite": ((0, -1), (1, -1), (1, 1), (0, 1)), "dart": ((1, -1), (0, -1), (0, 1), (1, 1))}
#: The corner each tile loses (its two spokes coincide there).
CUT = {"kite": 1, "dart": 3}
#: The short class's spokes as turns (degrees) of the long class's: ks(short) = turn * ke(long),
#: ke(short) = turn * ks(long).
SHORT_FROM_LONG = (36.0, 72.0)
#: The book's labels (§6.3) and the index of the piece of our outline each starts at.
BOOK_LABELS = {"kite": "abcdaefghd", "dart": "ghefgcdabf"}
BOOK_START = {"kite": 0, "dart": 6}
#: Our outlines' labels, piece i from point i to point i + 1.
LABELS = {name: BOOK_LABELS[name][-BOOK_START[name]:] + BOOK_LABELS[name][: -BOOK_START[name]] if BOOK_START[name]
          else BOOK_LABELS[name] for name in BOOK_LABELS}
PARTNER = {"a": "d", "d": "a", "b": "h", "h": "b", "c": "e", "e": "c", "f": "g", "g": "f"}
PRIMARY = ("a", "b", "c", "f")

PHI = (1 + math.sqrt(5)) / 2
CORNERS = {
    "kite": (0j, PHI * cmath.exp(-1j * math.pi / 10), PHI * cmath.exp(1j * math.pi / 10),
             PHI * cmath.exp(3j * math.pi / 10)),
    "dart": (0j, cmath.exp(-3j * math.pi / 10), cmath.exp(3j * math.pi / 10), -cmath.exp(-1j * math.pi / 10)),
}


def spokes(r1: float, t1: float, r2: float, t2: float) -> tuple[complex, complex, complex, complex]:
    """(ks, ke) of the long class then of the short class (theta in radians)."""
    w1, w2 = r1 * cmath.exp(1j * t1), r2 * cmath.exp(1j * t2)
    a, b = (cmath.exp(1j * math.radians(d)) for d in SHORT_FROM_LONG)
    return w1, w2, a * w2, b * w1


def _outline(corners: tuple[complex, ...], edges: tuple[tuple[int, int], ...], cut: set[int],
             ks_ke: tuple[complex, ...]) -> np.ndarray:
    """The tile's quasivertices (complex): per edge its corner and its two spoke points, a cut
    corner and its outgoing edge's first spoke point (equal to the last one) left out."""
    k = len(corners)
    out = []
    for i in range(k):
        cls, sign = edges[i]
        a, b = corners[i], corners[(i + 1) % k]
        p, q = (a, b) if sign > 0 else (b, a)
        d = (q - p) / abs(q - p)
        at_p, at_q = p + d * ks_ke[2 * cls], q - d * ks_ke[2 * cls + 1]
        first, second = (at_p, at_q) if sign > 0 else (at_q, at_p)
        if i not in cut:
            out += [a, first]
        out.append(second)
    return np.array(out)


def outlines(r1: float, t1: float, r2: float, t2: float) -> dict[str, tuple[np.ndarray, str]]:
    """{"kite"|"dart": ((10, 2) quasivertices in the system's frame, their labels)}, theta in radians."""
    s = spokes(r1, t1, r2, t2)
    out = {}
    for name in ("kite", "dart"):
        z = _outline(CORNERS[name], EDGES[name], {CUT[name]}, s)
        out[name] = (np.column_stack([z.real, z.imag]), LABELS[name])
    return out


# --------------------------------------------------------------------------- derivation
