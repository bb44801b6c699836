"""Uniform tilings of the hyperbolic plane that Wythoff's construction does not give, found
by developing one vertex star: the non-Wythoffian family 3.3.3.p.q (p, q even, the hyperbolic
analogues of the plane's 3^3.4^2; B. Datta and S. Gupta, "Semi-regular tilings of the
hyperbolic plane", Discrete Comput. Geom. 65 (2021), doi:10.1007/s00454-019-00156-0, on
vertex types admitting uniform tilings beyond Wythoff's).

The star S at the pole: edges of one length l (the root of sum of the faces' angles = 2π,
a regular n-gon with side l having angle 2 asin(cos(π/n) / cosh(l/2))), edge i at direction
θ_i, face i between edges i and i + 1. A vertex-transitive tiling with this star has, for
each edge i, a motion g_i taking the pole to the edge's far end w_i and some edge j of S onto
the edge back (w_i to the pole), its two faces onto the two faces along that edge: a proper
motion when the faces round edge j, in order, are those round edge i reversed; a
reflection when they are the same. The *pairing* names, for every edge i, that partner j and
the sign (``+`` proper, ``-`` reflecting); g_j is g_i's inverse, so the pairing is an
involution. The tiling is then every image h(S), h a word in the g_i: a breadth-first walk
over vertices (new ones told apart from known ones on a grid, wythoff.dedup), the faces
deduplicated by their centres. Not every pairing closes up: :func:`find` builds each
pairing's patch and keeps those that pass ``ModelPatch.validate`` (no overlap, the disc
covered) with every inner vertex's angles summing to 2π over the configuration's valence;
:func:`find` drops pairings that give the same faces round the pole.

Completeness, also when the star has symmetries. Let T be a vertex-transitive tiling with
this star at the pole, Γ its symmetry group, Stab ≤ Γ the motions fixing the pole (they map
S onto itself), M_i ⊂ Γ the motions taking the pole to w_i. Each g ∈ M_i maps S onto the
star at w_i, so some edge j of S onto edge i reversed, with the two faces along it, so g is
:meth:`Star.generator` (i, j, ±) for an allowed (j, ±): a motion is fixed by where it sends
one directed edge and whether it reverses orientation. When Stab is trivial, M_i is one
motion and its inverse is M_j's, so the pairing is forced. When Stab is not, M_i = g·Stab
holds |Stab| motions (one per edge of the orbit Stab·j it can come from): the motion is
defined up to Stab, and :meth:`Star.pairings` lists every allowed (j, ±) of every edge, so
every choice is among the candidates. An *involutive* choice always exists: for g ∈ M_i with
g⁻¹ ∈ M_j, g·s ∈ M_i has inverse s⁻¹g⁻¹ ∈ M_{s⁻¹(j)}, so between the Stab-orbits of i and
j every edge of one is matched with every edge of the other (choose any bijection), and
when the orbits coincide i is matched with itself (g·s with (g·s)⁻¹ ∈ M_i swaps the pole
and w_i, so is an involution, the generator (i, i, ±)). The chosen generators generate a
subgroup of Γ that reaches every vertex, so their development is T: the search misses no
vertex-transitive tiling, and a configuration all of whose pairings fail has none.

A pairing is kept only when it closes up round every face of S (:func:`closes`) and every
motion of its group fixing the pole maps S onto itself (:func:`consistent`: necessary, as a
symmetry fixing a vertex keeps its star; without it 3.4.3.4.4's one closing pairing puts two
different stars at one vertex), and its development then validates (:func:`check`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import shapely

from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.plugins.curved import model, notation, wythoff
from tilekit.plugins.curved.patch import ModelPatch, ModelPrototile, vertex_angle_sums
from tilekit.plugins.curved.tiling import (
    DEFAULT_SAMPLES,
    DRAWING_HELP,
    CurvedTiling,
    _number,
    clipped,
    drawing_options,
    drawing_spec,
    spec_table,
)
from tilekit.plugins.curved.uniform import _polygon

G = model.HYPERBOLIC_GEOMETRY
_FLIP = np.diag([1.0, -1.0, 1.0])
#: Largest valence whose pairings are searched (the involutions of d edges grow fast).
MAX_VALENCE = 8
#: Most pairings :func:`find` checks (each develops a patch: 2,768 took 6 s at valence 8;
#: 3^8's star allows far more). Past it the search is refused before it starts.
MAX_PAIRINGS = 4096


#: :func:`check`'s overlap and gap tolerance, relative to the median face's area (see there).
CHECK_AREA_TOL = 1e-4


def polygon_angle(n: int, edge: float) -> float:
    """The interior angle of the regular hyperbolic n-gon with side ``edge``."""
    return 2.0 * math.asin(min(1.0, math.cos(math.pi / n) / math.cosh(edge / 2)))


def edge_length(cfg: tuple[int, ...]) -> float:
    """The side l at which the regular faces of ``cfg`` close round a vertex (bisection: the
    angle sum falls from the Euclidean sum, above 2π, to 0 as l grows)."""
    if notation.geometry_of(cfg) != wythoff.HYPERBOLIC:
        raise ParameterError(f"{notation.dotted(cfg)} is {notation.geometry_of(cfg)}: the vertex-star construction "
                             "is for hyperbolic configurations (angles summing past a full turn)")
    cosines = [(cfg.count(n), math.cos(math.pi / n)) for n in set(cfg)]

    def total(edge: float) -> float:
        c = math.cosh(edge / 2)
        return sum(k * 2.0 * math.asin(min(1.0, cos / c)) for k, cos in cosines)

    lo, hi = 1e-9, 1.0
    while total(hi) > 2 * math.pi:
        hi *= 2
    for _ in range(200):  # until the interval stops shrinking (about 60 halvings)
        mid = (lo + hi) / 2
        if not lo < mid < hi:
            break
        lo, hi = (mid, hi) if total(mid) > 2 * math.pi else (lo, mid)
    return (lo + hi) / 2


Pairing = tuple[tuple[int, int], ...]


def parse_pairing(text: str, valence: int) -> Pairing:
    """``'0- 2+ 1+ 3- 4-'``: per edge its partner and sign (one-line ParseError)."""
    if not isinstance(text, str):
        raise ParseError(f"pairing must be text such as '0- 2+ 1+ 3- 4-', got {type(text).__name__}")
    out = []
    for tok in text.split():
        if len(tok) < 2 or tok[-1] not in "+-" or not tok[:-1].isdigit():
            raise ParseError(f"pairing {text[:60]!r}: each edge's entry is its partner edge and a sign, e.g. 2+ or 0-")
        out.append((int(tok[:-1]), 1 if tok[-1] == "+" else -1))
    if len(out) != valence:
        raise ParseError(f"pairing {text[:60]!r} has {len(out)} entries; the configuration has {valence} edges")
    for i, (j, s) in enumerate(out):
        if not 0 <= j < valence or out[j] != (i, s):
            raise ParseError(f"pairing {text[:60]!r}: edge {i} names {j}{'+' if s > 0 else '-'}, which must name "
                             f"{i} back with the same sign")
    return tuple(out)


def format_pairing(pairing: Pairing) -> str:
    return " ".join(f"{j}{'+' if s > 0 else '-'}" for j, s in pairing)


@dataclass(frozen=True)
class Star:
    """The vertex star of a configuration at the pole (see the module)."""

    cfg: tuple[int, ...]

    @cached_property
    def edge(self) -> float:
        return edge_length(self.cfg)

    @cached_property
    def angles(self) -> np.ndarray:
        return np.array([polygon_angle(n, self.edge) for n in self.cfg])

    @cached_property
    def directions(self) -> np.ndarray:
        """θ_i, edge i's direction (θ_0 = 0)."""
        return np.concatenate([[0.0], np.cumsum(self.angles)[:-1]])

    def flank(self, i: int) -> tuple[int, int]:
        """(face before, face after) edge i, counter-clockwise: sizes of faces i − 1 and i."""
        d = len(self.cfg)
        return self.cfg[(i - 1) % d], self.cfg[i]

    def circumradius(self, n: int) -> float:
        return float(G.acos(1.0 / (math.tan(math.pi / n) * math.tan(self.angles_of(n) / 2))))

    def angles_of(self, n: int) -> float:
        return polygon_angle(n, self.edge)

    def face_frames(self) -> np.ndarray:
        """(d, 3, 3): face i as the image of the regular n_i-gon at the pole (vertex k at
        angle 2πk/n), its vertex 0 at the pole and vertex 1 at edge i's far end."""
        out = []
        for i, n in enumerate(self.cfg):
            phi = self.directions[i] + self.angles[i] / 2
            # the half-turn about the face's centre puts vertex 0 on the side of the pole
            out.append(G.rotation(phi) @ G.translation(self.circumradius(n)) @ G.rotation(math.pi))
        return np.array(out)

    def edge_frame(self, i: int) -> np.ndarray:
        """The proper motion taking the pole to itself and direction 0 to edge i's."""
        return G.rotation(float(self.directions[i]))

    def back_frame(self, i: int) -> np.ndarray:
        """The proper motion taking the pole to w_i and direction 0 to the direction back along edge i."""
        return G.rotation(float(self.directions[i])) @ G.translation(self.edge) @ G.rotation(math.pi)

    def generator(self, i: int, j: int, sign: int) -> np.ndarray:
        """g_i for partner j: edge j of S onto edge i reversed (a reflection for sign −1)."""
        inner = _FLIP if sign < 0 else np.eye(3)
        return self.back_frame(i) @ inner @ self.edge_frame(j).T

    def allowed(self, i: int, j: int, sign: int) -> bool:
        """Whether edge j's faces can go onto edge i's reversed (sign +1) or kept (−1)."""
        a, b = self.flank(i)
        c, e = self.flank(j)
        return (c, e) == ((b, a) if sign > 0 else (a, b))

    def pairings(self) -> Iterator[Pairing]:
        """Every involutive pairing the faces allow."""
        d = len(self.cfg)
        if d > MAX_VALENCE:
            raise ParameterError(f"{notation.dotted(self.cfg)} has valence {d}; the pairing search takes up to "
                                 f"{MAX_VALENCE}")

        def rec(assigned: dict[int, tuple[int, int]]) -> Iterator[Pairing]:
            free = [i for i in range(d) if i not in assigned]
            if not free:
                yield tuple(assigned[i] for i in range(d))
                return
            i = free[0]
            for j in free:
                for s in (1, -1):
                    if self.allowed(i, j, s) and (i == j or self.allowed(j, i, s)):
                        nxt = dict(assigned)
                        nxt[i] = (j, s)
                        nxt[j] = (i, s)
                        yield from rec(nxt)

        yield from rec({})


def star_symmetries(star: Star) -> list[tuple[np.ndarray, tuple[int, ...]]]:
    """The motions fixing the pole that map the star S onto itself (faces onto faces of the
    same size), each with the permutation of the edges it makes: rotations taking edge i to
    i + r, reflections taking it to r − i."""
    cfg, d = star.cfg, len(star.cfg)
    out = []
    for r in range(d):
        if all(cfg[(i + r) % d] == cfg[i] for i in range(d)):
            out.append((star.edge_frame(r), tuple((i + r) % d for i in range(d))))
        # face i lies between edges i and i + 1; the reflection puts it between r − i − 1 and r − i
        if all(cfg[(r - i - 1) % d] == cfg[i] for i in range(d)):
            out.append((star.edge_frame(r) @ _FLIP, tuple((r - i) % d for i in range(d))))
    return out


def _symmetry_lookup(star: Star, pairing: Pairing) -> tuple[list[tuple[np.ndarray, tuple[int, ...]]], np.ndarray,
                                                             list[np.ndarray], list[np.ndarray], Callable[[np.ndarray], int]]:
    """(S's symmetries with their edge permutations, their matrices, the pairing's motions g_i,
    their inverses, which: a motion's index among S's symmetries or −1)."""
    sym = star_symmetries(star)
    mats = np.array([m for m, _ in sym])
    gens = [star.generator(i, j, s) for i, (j, s) in enumerate(pairing)]
    inv = [np.linalg.inv(g) for g in gens]

    def which(h: np.ndarray) -> int:
        hit = np.flatnonzero(np.abs(mats - h).max(axis=(1, 2)) < 1e-6)
        return int(hit[0]) if len(hit) else -1

    return sym, mats, gens, inv, which


def consistent(star: Star, pairing: Pairing, returns: list[np.ndarray]) -> bool:
    """Whether every motion of the pairing's group that fixes the pole maps S onto itself:
    the group H made from the face walks' ``returns`` (:func:`closes`) and, for each s in H
    and each edge i, g_{s(i)}^{-1} s g_i (which fixes the pole) must lie in S's symmetry
    group; else two different stars would be put at one vertex. Necessary for a tiling (a
    symmetry fixing a vertex keeps its star)."""
    sym, mats, gens, inv, which = _symmetry_lookup(star, pairing)
    found = {0}  # the identity (r = 0 is always a symmetry)
    todo = [0]

    def reach(hs: list[np.ndarray]) -> bool:
        """Mark each of ``hs`` found; False when one is not among the symmetries."""
        for h in hs:
            k = which(h)
            if k < 0:
                return False
            if k not in found:
                found.add(k)
                todo.append(k)
        return True

    if not reach(list(returns)):
        return False
    while todo:
        m, perm = sym[todo.pop()]
        new = [inv[perm[i]] @ m @ gens[i] for i in range(len(gens))]
        if not reach(new + [m @ sym[x][0] for x in list(found)]):
            return False
    return True


def closes(star: Star, pairing: Pairing) -> bool:
    """The local condition for a pairing to make a tiling: walking round each face of S by
    the generators (leaving each vertex along the face's next edge in that vertex's own
    star, whose orientation the walk tracks) returns to the pole after the face's n steps,
    by a motion that maps S onto itself (its faces' centres and sizes)."""
    gens = [star.generator(i, j, s) for i, (j, s) in enumerate(pairing)]
    frames = star.face_frames()
    centres = frames[:, :, 2]
    d = len(star.cfg)
    returns: list[np.ndarray] = []
    for i, n in enumerate(star.cfg):
        h, e = np.eye(3), i
        for step in range(n):
            j = pairing[e][0]
            h = h @ gens[e]
            back = step == n - 1
            if (abs(h[0, 2]) < 1e-7 and abs(h[1, 2]) < 1e-7 and abs(h[2, 2] - 1.0) < 1e-7) != back:
                return False
            e = (j - 1) % d if np.linalg.det(h) > 0 else (j + 1) % d
        moved = centres @ h.T
        match = np.abs(moved[:, None, :] - centres[None, :, :]).max(axis=2) < 1e-7
        if not (match.any(axis=1).all() and all(star.cfg[int(np.argmax(match[k]))] == star.cfg[k] for k in range(d))):
            return False
        returns.append(h)
    return consistent(star, pairing, returns)


def tiling_stabiliser(star: Star, pairing: Pairing) -> np.ndarray:
    """(s, 3, 3): the symmetries of the pairing's tiling that fix the pole, the whole group's
    (not only those of the group the pairing's motions generate): the largest set X of S's
    symmetries with g_{s(i)}⁻¹ s g_i in X for every s in X and edge i, found by striking out
    from all of S's symmetries until nothing changes. Each s in X carries the star at w_i,
    g_i(S), onto g_{s(i)}(S), the star there, with g_{s(i)}⁻¹ s g_i in X again at w_{s(i)}, so
    by induction out from the pole s keeps every star: it is a symmetry; and every symmetry
    fixing the pole lies in X (as in :func:`consistent`). The pairing must close
    (:func:`closes`)."""
    sym, mats, gens, inv, which = _symmetry_lookup(star, pairing)
    alive = set(range(len(sym)))
    changed = True
    while changed:
        changed = False
        for k in sorted(alive):
            m, perm = sym[k]
            if any(which(inv[perm[i]] @ m @ gens[i]) not in alive for i in range(len(gens))):
                alive.discard(k)
                changed = True
    return mats[sorted(alive)]


def develop(star: Star, pairing: Pairing, radius: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(vertex motions (m, 3, 3), face transforms (n, 3, 3), face sizes (n,)): every vertex
    within ``radius`` + one edge of the pole reached by words in the g_i through such
    vertices, and every face of their stars whose centre lies within ``radius`` plus its
    circumradius (so the disc of ``radius`` is covered when the pairing closes up)."""
    gens = np.array([star.generator(i, j, s) for i, (j, s) in enumerate(pairing)])
    sep = 0.5 * 2 * math.sinh(star.edge / 2)  # half the Euclidean gap between neighbours on the hyperboloid
    reach = math.cosh(radius + star.edge + max(star.circumradius(n) for n in set(star.cfg))) * (1 + 1e-9)
    layers = [np.eye(3)[None]]
    known = np.array([[0.0, 0.0, 1.0]])
    while True:
        cand = np.matmul(layers[-1][:, None], gens[None]).reshape(-1, 3, 3)
        cand = cand[cand[:, 2, 2] <= reach]
        if not len(cand):
            break
        pts = cand[:, :, 2]
        new = wythoff.dedup(np.concatenate([known, pts]), sep, first=len(known)) - len(known)
        if not len(new):
            break
        layers.append(cand[new])
        known = np.concatenate([known, pts[new]])
        if len(known) > 2_000_000:
            raise GeometryError("the vertex-star development did not close up (too many vertices)")
    verts = np.concatenate(layers)
    frames = star.face_frames()
    faces = np.matmul(verts[:, None], frames[None]).reshape(-1, 3, 3)
    sizes = np.tile(np.array(star.cfg), len(verts))
    circ = np.array([star.circumradius(n) for n in star.cfg])
    keep = faces[:, 2, 2] <= np.cosh(radius + np.tile(circ, len(verts))) * (1 + 1e-9)
    faces, sizes = faces[keep], sizes[keep]
    centres = faces[:, :, 2]
    first = wythoff.dedup(centres[:, :2], sep * 0.5)
    return verts, faces[first], sizes[first]


@dataclass
class Found:
    """One pairing that closes up: the tiling's faces round the pole, for telling tilings apart."""

    pairing: Pairing
    signature: bytes


def check(star: Star, pairing: Pairing, radius: float | None = None) -> bool:
    """Whether the pairing's development is a tiling on the disc of ``radius`` (default: one
    edge and the largest face's diameter, every face at the pole's neighbours): no overlap, the disc covered, every vertex inside it
    with angles summing to 2π over the valence."""

    if not closes(star, pairing):
        return False
    big = max(star.circumradius(n) for n in star.cfg)
    r = radius if radius is not None else 2 * big + 2 * star.edge
    try:
        patch = patch_of(star, pairing, r)
    except GeometryError:
        return False
    disc = math.tanh(r / 2)
    # the tolerance is relative to the median face's area in the Klein disc, where most faces
    # lie near the rim and are tiny: at the default 1e-6, float noise along a shared edge
    # (1.5e-14 for 4.6.5.6.6) counted as an overlap. A wrong star overlaps by a good part of a face.
    report = patch.validate(shapely.Point(0, 0).buffer(disc * 0.999, 64), tolerance=CHECK_AREA_TOL)
    if report.overlaps or not report.ok:
        return False
    sums, counts = vertex_angle_sums(patch)
    pts = _vertex_points(patch)
    inner = pts[:, 2] <= math.cosh(r - 2 * big) * (1 + 1e-9)
    return bool(np.allclose(sums[inner], 2 * math.pi, atol=1e-7) and (counts[inner] == len(star.cfg)).all())


def _vertex_points(patch: object, decimals: int = 9) -> np.ndarray:
    """The patch's vertices welded as vertex_angle_sums welds them, in its order."""
    keys = []
    for _, idx, proto in patch.parts():  # type: ignore[attr-defined]
        v = model.apply(patch.transform[idx], proto.points[list(proto.corners or range(len(proto.points)))])  # type: ignore[attr-defined]
        keys.append(np.round(v.reshape(-1, 3), decimals))
    return np.unique(np.concatenate(keys), axis=0)


def patch_of(star: Star, pairing: Pairing, radius: float, samples: int = 1, plane: str = "poincare"):  # noqa: ANN201
    """The development as a :class:`ModelPatch`, one prototile per face size (colour: its index)."""

    _, faces, sizes = develop(star, pairing, radius)
    protos = prototiles(star, samples, plane)
    kinds = np.searchsorted(sorted(set(star.cfg)), sizes)
    return ModelPatch(protos, kinds, faces, colour=kinds.copy())


def prototiles(star: Star, samples: int = 1, plane: str = "poincare") -> list:

    out = []
    for n in sorted(set(star.cfg)):
        v = G.point(star.circumradius(n), 2 * np.pi * np.arange(n) / n)
        pts = model.sample_edges(G, v, star.edge, samples)
        out.append(ModelPrototile.on_model(pts, sign=-1, name=_polygon(n), plane=plane,
                                           corners=tuple(range(0, len(pts), max(1, samples)))))
    return out


def signature(star: Star, pairing: Pairing, radius: float) -> bytes:
    """The face centres within ``radius`` of the pole, rounded and sorted: equal for two
    pairings exactly when they make the same faces there."""
    _, faces, sizes = develop(star, pairing, radius)
    c = faces[:, :, 2]
    c = c[c[:, 2] <= math.cosh(radius) * (1 - 1e-9)]
    key = np.round(c, 6) + 0.0
    key = key[np.lexsort(key.T[::-1])]
    return key.tobytes()


def find(cfg: tuple[int, ...]) -> list[Pairing]:
    """The pairings of ``cfg``'s star that close up into a tiling, one per distinct tiling
    (see the module), in the order :meth:`Star.pairings` lists them."""
    star = search_bounds(cfg)
    pairings = list(star.pairings())
    big = max(star.circumradius(n) for n in star.cfg)
    out: list[Found] = []
    for pairing in pairings:
        if not check(star, pairing):
            continue
        sig = signature(star, pairing, 2 * big + star.edge)  # every face at the pole's neighbours
        if all(f.signature != sig for f in out):
            out.append(Found(pairing, sig))
    return [f.pairing for f in out]


#: Largest polygon a searched configuration may have: the check's patch reaches twice the
#: largest face's circumradius, whose face count grows like e^(2 circumradius).
MAX_SIDES = 12


def search_bounds(cfg: tuple[int, ...]) -> Star:
    """The star of ``cfg`` after the search's limits are checked (valence, sides, pairings:
    counted before any patch is developed), one-line ParameterErrors naming the limit."""
    star = Star(notation.canonical(cfg))
    if max(cfg) > MAX_SIDES:
        raise ParameterError(f"{notation.dotted(star.cfg)} has a {max(cfg)}-gon; the pairing search takes polygons "
                             f"of up to {MAX_SIDES} sides (its check develops a patch round the largest face)")
    count = sum(1 for _ in itertools.islice(star.pairings(), MAX_PAIRINGS + 1))  # raises past MAX_VALENCE
    if count > MAX_PAIRINGS:
        raise ParameterError(f"{notation.dotted(star.cfg)}: its star's edges allow more than {MAX_PAIRINGS} pairings, "
                             "too many to search; give one (--set pairing='0- 1+ ...')")
    return star


def find_first(cfg: tuple[int, ...], radius: float | None = None) -> Pairing | None:
    """The first pairing (in :meth:`Star.pairings` order) that closes up (:func:`closes`, with
    the stabiliser condition) and whose development validates (:func:`check`), or None when
    none does: then ``cfg`` has no vertex-transitive tiling (every vertex-transitive tiling's
    motions give such a pairing; see :func:`find`)."""
    star = search_bounds(cfg)
    for pairing in star.pairings():
        if closes(star, pairing) and check(star, pairing, radius):
            return pairing
    return None


def species_tilings(max_sides: int, max_valence: int) -> Iterator[tuple[tuple[int, ...], Pairing | None]]:
    """(configuration, :func:`find_first`'s pairing or None) for every hyperbolic vertex type of
    the vertex-species search's range (:func:`notation.hyperbolic_types`) that no Wythoff
    symbol gives: what catalogue/curved/stars.toml's [[tiling]] list ships (each a few tenths
    of a second; a minute or two for sides and valence up to 6)."""
    for cfg in notation.hyperbolic_types(max_sides, max_valence):
        if not wythoff.symbols_for(cfg):
            yield cfg, find_first(cfg)


def family(max_sides: int) -> Iterator[tuple[int, ...]]:
    """The configurations 3.3.3.p.q, p ≤ q even, 4 ≤ p, q ≤ max_sides, less the plane's 3.3.3.4.4."""
    for p, q in itertools.combinations_with_replacement(range(4, max_sides + 1, 2), 2):
        if (p, q) != (4, 4):
            yield (3, 3, 3, p, q)


# --------------------------------------------------------------------------- the tiling


#: Faces of a patch when no radius is given.
DEFAULT_FACES = 800
MAX_RADIUS = 10.0
#: Peak bytes per face while a patch is made (the vertex motions, their faces before the
#: centres are deduplicated: about d faces per vertex at 72 bytes each, and the dedup grid).
STAR_BYTES_PER_TILE = 2000
_OPTIONS = ("configuration", "pairing", "radius", "samples", "plane")
_SPEC_KEYS = set(_OPTIONS) | {"name", "title"}


def configured(tiling: Any, options: dict[str, Any]) -> Any:
    """``tiling`` (a :class:`StarTiling` or its dual) with ``options``, of its own class: a new
    configuration drops the pairing, and an option of the class's ``DEFINING`` the name and
    title, which belong to the old one; the class's own options (its ``carried``) pass on."""
    tiling.check_options(options)
    same = "configuration" not in options
    pairing = options.get("pairing", format_pairing(tiling.pairing) if same else None)
    named = not (set(tiling.DEFINING) & set(options))
    return type(tiling)(options.get("configuration", tiling.configuration), pairing=pairing,
                        radius=options.get("radius", tiling.radius), samples=options.get("samples", tiling.samples),
                        plane=options.get("plane", tiling.plane), name=tiling.name if named else "",
                        title=tiling.title if named else "", **tiling.carried(options))


class StarTiling(CurvedTiling):
    """A uniform tiling of the hyperbolic plane developed from its vertex star by a pairing
    of the star's edges (see the module): ``configuration`` (e.g. 3.3.3.6.6), ``pairing``
    (default: the first that closes up, :func:`find_first`), ``radius`` (the disc covered)."""

    streams = False
    bytes_per_tile = STAR_BYTES_PER_TILE
    OPTIONS = _OPTIONS
    #: Options that name another tiling: configure() keeps the name and title without them.
    DEFINING: tuple[str, ...] = ("configuration",)

    def __init__(self, configuration: str, *, pairing: str | None = None, radius: float | None = None,
                 samples: int = DEFAULT_SAMPLES, plane: str = "poincare", name: str = "", title: str = "") -> None:
        cfg = notation.canonical(notation.parse(str(configuration)))
        self.star = Star(cfg)
        self.star.edge  # noqa: B018 - a configuration that is not hyperbolic is refused here
        self.plane, self.samples = drawing_options(plane, samples, False)
        self.radius = None if radius is None else float(_number("radius", radius, 0, MAX_RADIUS, False))
        if pairing is None:
            first = find_first(cfg)
            if first is None:
                raise ParameterError(f"{notation.dotted(cfg)}: no pairing of its star's edges closes up into a "
                                     "vertex-transitive tiling")
            self.pairing = first
        else:
            self.pairing = parse_pairing(pairing, len(cfg))
            if not closes(self.star, self.pairing):
                raise ParameterError(f"{notation.dotted(cfg)} with pairing {pairing}: the faces do not close up round "
                                     "a vertex (try tilekit.plugins.curved.stars.find)")
        self.family = "curved"
        self.kind = wythoff.HYPERBOLIC
        self.configuration = notation.dotted(cfg)
        self.name = name or notation.exponent(cfg)
        self.title = title

    @cached_property
    def _protos(self) -> list:
        return prototiles(self.star, self.samples, self.plane)

    @property
    def prototiles(self) -> list:
        return list(self._protos)

    def faces_per_area(self) -> float:
        """Faces per unit area: sum 1/n over the vertex's faces, over each face's area share."""
        area = {n: (n - 2) * math.pi - n * self.star.angles_of(n) for n in set(self.star.cfg)}
        return sum(1 / n for n in self.star.cfg) / sum(area[n] / n for n in self.star.cfg)

    def _big(self) -> float:
        return max(self.star.circumradius(n) for n in set(self.star.cfg))

    def _radius(self) -> float:
        if self.radius is not None:
            return self.radius
        r = math.acosh(1 + DEFAULT_FACES / (2 * math.pi * self.faces_per_area()))
        return float(min(MAX_RADIUS, max(0.0, r - self._big())))

    def estimate_tiles(self, region: Any = None) -> float:
        """Faces per area times the disc's area, the disc grown by twice the largest face's circumradius."""
        r = self._radius() + 2 * self._big()
        return 1.0 + self.faces_per_area() * 2 * math.pi * (math.cosh(r) - 1)

    def patch(self, region: Any = None) -> Any:
        """Every face whose centre is within the radius plus its circumradius (the disc of the
        radius covered), less those whose outline misses ``region``; colour: the face's size."""
        what = f"faces of {self.configuration}"
        estimate = self.estimate_tiles(region)
        self.refuse_oversize(what, estimate, "ask for a smaller radius (--set radius=R)")
        patch = patch_of(self.star, self.pairing, self._radius(), self.samples, self.plane)
        return clipped(patch, region)

    def symmetries(self, reach: float) -> np.ndarray:
        """The tiling's symmetries (words in the generators) moving the pole at most ``reach``."""
        verts, _, _ = develop(self.star, self.pairing, reach)
        return verts[verts[:, 2, 2] <= math.cosh(reach) * (1 + 1e-12)]

    def properties(self) -> dict[str, Any]:
        cfg = self.star.cfg
        return {"periodic": True, "k_hedral": len(set(cfg)), "k_isogonal": 1, "edge_to_edge": True,
                "uniform": True, "geometry": self.kind, "vertex_configuration": self.configuration,
                "construction": "vertex star", "pairing": format_pairing(self.pairing), "wythoffian": False,
                "sides": sorted(set(cfg)), "valence": len(cfg)}

    def describe(self) -> str:
        return (f"{self.configuration}: a uniform tiling of the hyperbolic plane that Wythoff's construction does not "
                f"give, developed from its vertex star (edge pairing {format_pairing(self.pairing)})")

    def options_help(self) -> str:
        return "\n".join([
            "--set configuration=C       the vertex configuration, e.g. 3.3.3.6.6",
            "--set pairing=P             each star edge's partner and sign, e.g. '0- 1+ 2+ 3- 4+' (default: the "
            f"first that closes up; the search takes valence <= {MAX_VALENCE}, polygons <= {MAX_SIDES} sides, <= "
            f"{MAX_PAIRINGS} pairings)",
            f"--set radius=R              the faces covering the disc of radius R (0..{MAX_RADIUS:g}; default: about "
            f"{DEFAULT_FACES} faces)",
            *DRAWING_HELP,
        ])

    def configure(self, **options: Any) -> StarTiling:
        return configured(self, options)

    def carried(self, options: Mapping[str, Any]) -> dict[str, Any]:
        """A subclass's own options for configure(): none here."""
        return {}

    def spec(self) -> dict[str, Any]:
        return drawing_spec({"configuration": self.configuration, "pairing": format_pairing(self.pairing)}, self,
                            notation.exponent(self.star.cfg))

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> StarTiling:
        spec_table(spec, sorted(_SPEC_KEYS), "curved vertex-star")
        if "configuration" not in spec:
            raise ParseError("curved vertex-star spec needs a configuration, e.g. 3.3.3.6.6")
        return cls(spec["configuration"], pairing=spec.get("pairing"), radius=spec.get("radius"),
                   samples=spec.get("samples", DEFAULT_SAMPLES), plane=spec.get("plane", "poincare"),
                   name=str(spec.get("name", "")), title=str(spec.get("title", "")))
