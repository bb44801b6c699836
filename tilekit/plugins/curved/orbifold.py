"""The full symmetry group of a uniform tiling of the sphere or the hyperbolic plane, in
Conway's orbifold notation, computed from Wythoff's construction (not read off the symbol:
3 3 | 2 on the group *332 is the cuboctahedron, whose group is *432; | 2 3 3 is the
icosahedron, *532; | 2 2 n is the n-gonal antiprism, 2*n).

The construction's group G (*pqr, or its rotations pqr for a snub) acts transitively on the
vertices, so the full group is G·S, with S the stabiliser of the generator vertex v0. S is
found among the isometries fixing v0 that permute its edges (a rotation or a reflection
taking the first edge to each edge): a candidate is kept when it maps the second corona of v0 (the faces at v0
and at its neighbours) onto itself, sizes kept. Everything is local: the elements used are
L·L, with L the dihedral groups of the triangle's three corners (the faces at v0 are elements
of L times the face types, their vertices elements of L·L times v0), so the cost does not
grow with the size of the faces.

A rotation of a tiling by regular polygons fixes a vertex, a face's centre or an edge's
midpoint, and a mirror passes through a face's centre; G is vertex-transitive, so every such
point is equivalent to v0, to the centre of a face at v0 or to the midpoint of an edge at
v0. The orbifold's features are read from those points' stabilisers in G·S, one per orbit:
a dihedral stabiliser of order 2n (n >= 2) is a mirror corner n, a cyclic one of order n >= 2
a cone point n; mirrors exist when some stabiliser holds a reflection. The rotation subgroup
of a group containing a triangle group is a triangle group (Singerman), so these features
make the whole symbol (no handles or crosscaps). Digits are written largest first
(``*532``, ``*732`` for the {7,3} tilings' group, which is also written *237), except the
dihedral groups of the sphere, written as Conway does: ``*22n``, ``22n``, ``2*n``.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from tilekit.errors import GeometryError
from tilekit.plugins.curved import model, wythoff
from tilekit.symmetry.names import orbifold_symbol

#: Two model points closer than this (in the geometry's distance) are one point.
_TOL = 1e-6


@dataclass(frozen=True)
class OrbifoldGroup:
    """A symmetry group as its orbifold features: ``cones`` (cone point orders), ``corners``
    (mirror corner orders), ``mirrors`` (whether it has reflections)."""

    cones: tuple[int, ...]
    corners: tuple[int, ...]
    mirrors: bool

    @property
    def notation(self) -> str:
        cones = sorted(self.cones, reverse=True)
        corners = sorted(self.corners, reverse=True)
        # the sphere's dihedral groups as Conway writes them: *22n, 22n
        if not self.mirrors and len(cones) == 3 and cones[1:] == [2, 2]:
            cones = [2, 2, cones[0]]
        if self.mirrors and not cones and len(corners) == 3 and corners[1:] == [2, 2]:
            corners = [2, 2, corners[0]]
        return orbifold_symbol(cones, [corners] if self.mirrors else [])  # *10,3,2: commas past 9

    @property
    def euler_characteristic(self) -> Fraction:
        """Conway's orbifold Euler characteristic (2 − Σ(n−1)/n over cones − 1 for the
        mirror boundary − Σ(n−1)/2n over corners): 2/|G| for a group of the sphere,
        −area/2π for one of the hyperbolic plane."""
        chi = Fraction(2) - sum((Fraction(n - 1, n) for n in self.cones), Fraction(0))
        if self.mirrors:
            chi -= 1 + sum((Fraction(n - 1, 2 * n) for n in self.corners), Fraction(0))
        return chi

    def rotations(self) -> OrbifoldGroup:
        """The rotation subgroup (index 2 when there are mirrors): the orientable double cover
        of a disc with cone points and one mirror boundary, each cone point twice and each
        corner once as a cone point (*pqr: pqr, 2*n: 22n). The groups here contain a triangle
        group, so they have no handles, cross-caps or second boundary (see the module)."""
        if not self.mirrors:
            return self
        return OrbifoldGroup(self.cones * 2 + self.corners, (), False)

    def order(self) -> int:
        """The group's order (a group of the sphere: 2/χ)."""
        chi = self.euler_characteristic
        if chi <= 0:
            raise GeometryError(f"{self.notation} is not a group of the sphere: it is infinite")
        return int(2 / chi)


@dataclass(frozen=True)
class UniformSymmetry:
    """What :func:`uniform_symmetry` found: the group, the vertex stabiliser's order, and
    the index of the construction's group in it."""

    group: OrbifoldGroup
    vertex_stabiliser: int
    index: int

    @property
    def notation(self) -> str:
        return self.group.notation


def _inverse(m: np.ndarray) -> np.ndarray:
    return np.linalg.inv(m)


def same_point(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Whether model points a and b (broadcast) are one point: their coordinates agree to
    _TOL of their size (arccosh of a near −1 inner product loses half the digits)."""
    scale = np.maximum(1.0, np.maximum(np.abs(a).max(axis=-1), np.abs(b).max(axis=-1)))
    return np.abs(a - b).max(axis=-1) < _TOL * scale


def _distinct(m: np.ndarray) -> int:
    """How many distinct matrices (k, 3, 3) there are."""
    if not len(m):
        return 0
    scale = max(1.0, float(np.abs(m).max()))
    return len(np.unique(np.round(m.reshape(len(m), -1) / (scale * _TOL)), axis=0))


def _local_elements(c: wythoff.Construction) -> np.ndarray:
    """L: the construction group's elements fixing a corner of the triangle (the dihedral
    group of each corner; its rotations for a snub). The generator's stabiliser lies in L,
    and a face at the generator is an element of L times a face type in fundamental position."""
    out = []
    for i, n in enumerate(c.orders):
        rots = [np.linalg.matrix_power(c.rotations[i], k) for k in range(n)]
        out += rots
        if c.symbol.form != "snub":
            out += [r @ c.reflections[(i + 1) % 3] for r in rots]
    return _unique(np.array(out))


def _unique(m: np.ndarray) -> np.ndarray:
    scale = max(1.0, float(np.abs(m).max()))
    _, keep = np.unique(np.round(m.reshape(len(m), -1) / (scale * _TOL)), axis=0, return_index=True)
    return m[np.sort(keep)]


def _first_of_each(points: np.ndarray) -> np.ndarray:
    """Indices of the first of each group of equal points (n, 3)."""
    same = same_point(points[:, None, :], points[None, :, :])
    return np.flatnonzero(~np.triu(same, 1).any(axis=0))


def _star(c: wythoff.Construction, local: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The faces at the generator: (frames (k, 3, 3) taking the pole's regular polygon onto
    them, sides (k,))."""
    sp, v0 = c.space, c.generator
    frames, sides = [], []
    for f in c.face_types:
        cand = local @ f.frame
        at = np.flatnonzero(np.abs(sp.distance(cand[:, :, 2], v0) - f.circumradius) < 1e-7 * max(1.0, f.circumradius))
        at = at[_first_of_each(cand[at, :, 2])]
        frames.append(cand[at])
        sides += [f.sides] * len(at)
    return np.concatenate(frames), np.array(sides)


def star_symmetries(sequence: tuple[int, ...]) -> int:
    """How many isometries fixing a vertex map its star onto itself: the rotations and
    reflections of the cyclic sequence of its faces' sizes that keep it (the faces are regular
    with one edge length, so the sizes fix the star)."""
    k = len(sequence)
    turns = [sequence[i:] + sequence[:i] for i in range(k)]
    back = tuple(reversed(sequence))
    return sum(t == sequence for t in turns) + sum(t == back for t in turns)


def construction_stabiliser(symbol: wythoff.Symbol) -> int:
    """The order of the generator's stabiliser in the construction's group: the dihedral
    group of its corner (p | q r: 2p), the mirror it lies on (p q | r: 2), none (omni, snub)."""
    return {"vertex": 2 * symbol.orders[0], "edge": 2, "omni": 1, "snub": 1}[symbol.form]


def _construction_group(symbol: wythoff.Symbol, orders: tuple[int, int, int]) -> OrbifoldGroup:
    ones = tuple(n for n in orders if n >= 2)
    return OrbifoldGroup((), ones, True) if symbol.form != "snub" else OrbifoldGroup(ones, (), False)


def symbol_symmetry(symbol: wythoff.Symbol) -> UniformSymmetry | None:
    """The group when the symbol alone decides it (the vertex star has no symmetry beyond the
    generator's stabiliser in the construction's group, so neither has the full group's
    vertex stabiliser): the construction's group; None when the construction must be asked."""
    own = construction_stabiliser(symbol)
    if star_symmetries(symbol.sequence) == own:
        return UniformSymmetry(_construction_group(symbol, symbol.orders), own, 1)
    return None


@dataclass(frozen=True)
class _VertexSearch:
    """What the stabiliser search of :func:`uniform_symmetry` finds near the generator v0:
    ``local`` (L), ``pair`` (L·L moving v0 at most two face circumradii), the faces at v0
    (``frames``), its neighbours ``nbrs``, and ``stab`` (the full group's elements fixing v0)."""

    local: np.ndarray
    pair: np.ndarray
    frames: np.ndarray
    nbrs: np.ndarray
    stab: np.ndarray


def _vertex_search(c: wythoff.Construction) -> _VertexSearch:
    """The isometries fixing v0 that keep the second corona (see the module), checked against
    the construction's own stabiliser of v0."""
    own = construction_stabiliser(c.symbol)
    sp, v0 = c.space, c.generator
    e = c.edge_length
    local = _local_elements(c)
    frames, sides = _star(c, local)
    circ = {f.sides: f.circumradius for f in c.face_types}
    # the vertices of the faces at v0, each with an element of L·L carrying v0 onto it
    pair = np.matmul(local[:, None], local[None]).reshape(-1, 3, 3)
    pair = _unique(pair)
    reach_v = max(2 * r for r in circ.values()) + 1e-6
    pair = pair[sp.distance(pair @ v0, v0) <= reach_v]
    images = pair @ v0
    at_e = np.flatnonzero(np.abs(sp.distance(images, v0) - e) < 1e-7 * max(1.0, e))
    nbr_idx = at_e[_first_of_each(images[at_e])].tolist()
    nbrs = images[nbr_idx]
    if len(nbrs) < 3:
        raise GeometryError(f"{c.symbol}: found {len(nbrs)} edges at the generator, not a vertex of a tiling")
    # the second corona: the faces at v0 and at each neighbour (an element of G carries the star)
    centres = np.concatenate([frames[:, :, 2]] + [(pair[k] @ frames[:, :, 2].T).T for k in nbr_idx])
    all_sides = np.concatenate([sides] * (1 + len(nbr_idx)))
    # one copy of each (a point split by rounding stays twice: harmless for the test below)
    scale = max(1.0, float(np.abs(centres).max()))
    _, keep = np.unique(np.round(centres / (scale * _TOL)), axis=0, return_index=True)
    centres, all_sides = centres[keep], all_sides[keep]
    # candidate symmetries fixing v0: the first edge to each edge, turned or reflected
    f0_inv = np.linalg.inv(sp.frame(v0, nbrs[0]))
    flip = np.diag([1.0, -1.0, 1.0])
    # distinct face centres are two inradii apart (the hyperboloid's (x, y) are at least as
    # far apart as the points): clustered on a grid (wythoff.weld), an image must fall on a
    # centre of its own size
    g = model.Geometry(sp.sign)
    inr = min(float(g.acos(float(g.cos(f.circumradius)) / float(g.cos(e / 2)))) for f in c.face_types)
    n = len(centres)
    stab = []
    for nb in nbrs:
        fj = sp.frame(v0, nb)
        for s in (fj @ f0_inv, fj @ flip @ f0_inv):
            img = centres @ s.T
            both = np.concatenate([centres, img])
            rep = wythoff.weld(both if sp.sign > 0 else both[:, :2], 2 * inr)[n:]
            if (rep < n).all() and (all_sides[np.minimum(rep, n - 1)] == all_sides).all():
                stab.append(s)
    stab_m = np.array(stab)
    g_stab = _distinct(local[same_point(local @ v0, v0)])
    if len(stab_m) % g_stab:
        raise GeometryError(f"{c.symbol}: the vertex stabiliser ({len(stab_m)}) is not a multiple of the "
                            f"construction's ({g_stab})")
    if g_stab != own:
        raise GeometryError(f"{c.symbol}: the generator's stabiliser has {g_stab} elements, not {own}")
    return _VertexSearch(local, pair, frames, nbrs, stab_m)


def vertex_stabiliser(construction: wythoff.Construction) -> np.ndarray:
    """(s, 3, 3): the tiling's symmetries fixing the generator vertex v0, as O(3) or O(2,1)
    matrices: the construction's own (L's elements fixing v0) when the symbol decides the
    group (:func:`symbol_symmetry`), else the search's (an antiprism's: the mirror through v0
    that 2*n adds to 22n)."""
    c = construction
    if symbol_symmetry(c.symbol) is not None:
        local = _local_elements(c)
        return _unique(local[same_point(local @ c.generator, c.generator)])
    return _vertex_search(c).stab


def uniform_symmetry(construction: wythoff.Construction) -> UniformSymmetry:
    """The full symmetry group of the construction's tiling (see the module). When the vertex
    star has no more symmetry than the generator's stabiliser in the construction's group,
    the full group's vertex stabiliser can be no larger, so the group is the construction's
    (most tilings: nothing else is computed)."""
    c = construction
    quick = symbol_symmetry(c.symbol)
    if quick is not None:
        return quick
    sp, v0 = c.space, c.generator
    found = _vertex_search(c)
    pair, frames, nbrs, stab_m = found.pair, found.frames, found.nbrs, found.stab
    g_stab = construction_stabiliser(c.symbol)
    if len(stab_m) == g_stab:  # no symmetry beyond the construction's group: *pqr or pqr
        return UniformSymmetry(_construction_group(c.symbol, c.orders), len(stab_m), 1)
    # feature points: v0, the centres of its faces, the midpoints of its edges; the elements
    # of the full group that can map one to another or fix one: L·L times the stabiliser
    points = np.array([v0] + list(frames[:, :, 2]) + [sp.normalise(v0 + n) for n in nbrs])
    full = np.matmul(pair[:, None], stab_m[None]).reshape(-1, 3, 3)
    det = np.linalg.det(full)
    orbit_of = np.full(len(points), -1)
    cones, corners, mirrors = [], [], False
    for i in range(len(points)):
        if orbit_of[i] >= 0:
            continue
        img = full @ points[i]
        orbit_of[(same_point(img[:, None, :], points[None, :, :]).any(axis=0)) & (orbit_of < 0)] = i
        fix = same_point(img, points[i])
        rot = _distinct(full[fix & (det > 0)])
        refl = bool((fix & (det < 0)).any())
        mirrors |= refl
        if rot >= 2:
            (corners if refl else cones).append(rot)
    group = OrbifoldGroup(tuple(cones), tuple(corners), mirrors)
    return UniformSymmetry(group, len(stab_m), len(stab_m) // g_stab)


def construction_euler_characteristic(symbol: wythoff.Symbol) -> Fraction:
    """χ of the construction's group: *pqr has (1/p + 1/q + 1/r − 1)/2, pqr twice that."""
    p, q, r = symbol.orders
    chi = Fraction(1, p) + Fraction(1, q) + Fraction(1, r) - 1
    return chi if symbol.form == "snub" else chi / 2


def check_index(sym: UniformSymmetry, symbol: wythoff.Symbol) -> bool:
    """Whether χ(construction's group) = index · χ(full group): the index found from the
    vertex stabilisers agrees with the orbifolds' areas (Riemann–Hurwitz)."""
    return construction_euler_characteristic(symbol) == sym.index * sym.group.euler_characteristic

