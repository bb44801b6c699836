"""The hat's continuum Tile(a, b) (Smith, Myers, Kaplan, Goodman-Strauss, arXiv:2303.10798).

The hat's 14 edges (its edge of length 2 counted as two) are of two classes: 8 of length 1
along the triangular lattice's directions (0, 60, ..., 300 degrees) and 6 of length sqrt3
along the directions between them. Tile(a, b) keeps every edge's direction and gives the
first class length a, the second length b: the hat is Tile(1, sqrt3), the turtle
Tile(sqrt3, 1), the chevron Tile(0, 1), the comet Tile(1, 0), and the equilateral Tile(1, 1)
is the Spectre's polygon (arXiv:2305.17743).

A hat tiling deforms edge by edge into a tiling by Tile(a, b), with the same tiles meeting
along the same edges. The edge vectors of each class add up to zero round every hat, so
adding them up separately along tile edges does not depend on the path: every vertex of a
hat tiling has a *lift* (u, v), two triangular-lattice vectors whose sum is its position,
u the sum of the class-1 steps and v of the class-2 steps from a fixed vertex; the
Tile(a, b) tiling puts that vertex at ``a * u + (b / sqrt3) * v``. A symmetry of the lattice
turns u and v alike, so a placement lifts to a pair of lattice maps (M, u) and (M, v) with
the same linear part, and lifted placements compose member by member: the hat's hierarchy,
lifted once, is for every (a, b) a hierarchy of rigid maps with translations
``a u + (b / sqrt3) v``, and a Tile(a, b) patch is the hat's batched products with other
numbers in them. Nothing is computed per tile.

The lifts come from the data, level by level (:class:`HatLifts`): the hats of a metatile
are lifted through the vertices they share; at level n the children of the four new
supertiles (level-(n-1) supertiles of the assembled cluster) are lifted one from another
across the outline edges they share: the hats of both supertiles near the middle of that
edge are generated (culled to a small box), their shared vertices matched, and the one
translation that makes the lifts agree is taken. Every match is checked: all shared
vertices must give the same translation, and every pair of touching children must agree,
or the data is rejected.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.geometry import Affine
from tilekit.plugins.substitution.expr import evaluate
from tilekit.plugins.substitution.hat import (
    LATTICE,
    TO_LATTICE,
    HatSystem,
    hat_colours,
    to_cartesian,
)
from tilekit.plugins.substitution.keypoint import Generation, MonotileSystem
from tilekit.plugins.substitution.levels import (
    expand_by_label,
    meets_discs,
    placed_points,
)
from tilekit.plugins.substitution.rules import Rule
from tilekit.tiling import Prototile

SQRT3 = math.sqrt(3.0)
#: Half-sizes (lattice units; a hat is about 5 across) of the boxes tried round a contact.
CONTACT_BOXES = (6.0, 12.0, 24.0)
#: Largest a or b accepted (the hat is Tile(1, sqrt3)).
MAX_EDGE = 1000.0
#: Outline points closer than this (relative to the tile's size) are one point (a = 0 or b = 0).
COLLAPSE_TOL = 1e-12


def edge_classes(vectors: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(class 1, class 2) masks of integer lattice vectors (..., 2): class 1 along the
    lattice directions [1, 0], [0, 1], [-1, 1] (and their negatives), class 2 along the
    directions between them, [1, 1], [-1, 2], [-2, 1] (and their negatives)."""
    m, n = vectors[..., 0], vectors[..., 1]
    nonzero = (m != 0) | (n != 0)
    one = nonzero & ((m == 0) | (n == 0) | (m == -n))
    two = nonzero & ((m == n) | (m == -2 * n) | (n == -2 * m))
    return one, two


def vertex_lifts(outline: np.ndarray, what: str = "the hat") -> tuple[np.ndarray, np.ndarray]:
    """Lifts (u, v) of an outline's integer lattice vertices (k, 2): the sums of its class-1
    and class-2 edge vectors from vertex 0. ParseError when an edge is in neither class or a
    class does not close up round the outline (the outline is then no member of the hat's
    continuum)."""
    pts = np.asarray(outline, dtype=np.int64)
    steps = np.roll(pts, -1, axis=0) - pts
    one, two = edge_classes(steps)
    if not np.all(one | two):
        bad = int(np.flatnonzero(~(one | two))[0])
        raise ParseError(f"{what}: edge {bad} {steps[bad].tolist()} is along neither edge class of the hat's lattice")
    u_steps, v_steps = steps * one[:, None], steps * two[:, None]
    if u_steps.sum(axis=0).any() or v_steps.sum(axis=0).any():
        raise ParseError(f"{what}: the edges of one class do not add up to zero round the outline")
    zero = np.zeros((1, 2), dtype=np.int64)
    return np.concatenate([zero, np.cumsum(u_steps, axis=0)[:-1]]), np.concatenate([zero, np.cumsum(v_steps, axis=0)[:-1]])


def deform(a: float, b: float, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Cartesian points ``a * u + (b / sqrt3) * v`` of lifts (u, v), each (..., 2) in
    lattice coordinates."""
    return (a * np.asarray(u, dtype=float) + (b / SQRT3) * np.asarray(v, dtype=float)) @ LATTICE.T


def _with_translation(maps: np.ndarray, t: np.ndarray) -> np.ndarray:
    out = np.array(maps, dtype=np.int64, copy=True)
    out[..., :2, 2] = t
    return out


def _keys(points: np.ndarray) -> np.ndarray:
    """One int64 per integer lattice point (k, 2) (coordinates within +-2^30)."""
    p = np.asarray(points, dtype=np.int64) + (1 << 30)
    return p[:, 0] * (1 << 31) + p[:, 1]


@dataclass
class HatLifts:
    """The lifted hat hierarchy (see the module docstring): lifts of the hat's vertices, of
    the metatiles' hats and of every level's supertile placements, solved lazily per level
    and kept. ``system`` is a :class:`tilekit.plugins.substitution.hat.HatSystem`."""

    system: HatSystem
    tile_u: np.ndarray = field(init=False)
    tile_v: np.ndarray = field(init=False)
    base_u: list[np.ndarray] = field(init=False)
    base_v: list[np.ndarray] = field(init=False)
    #: deformed systems by (a, b), see :func:`continuum_system`
    systems: dict[tuple[float, float], ContinuumSystem] = field(default_factory=dict)
    _rules: list[tuple[list[np.ndarray], list[np.ndarray]]] = field(default_factory=list)

    def __post_init__(self) -> None:
        outline = np.rint(Affine.apply(TO_LATTICE, self.system.tile.outline)).astype(np.int64)
        self.outline = outline
        self.tile_u, self.tile_v = vertex_lifts(outline, f"substitution system {self.system.source}: [tile]")
        self.base_u, self.base_v = [], []
        for j, maps in enumerate(self.system.base):
            u, v = self._lift_pieces(maps, f"[metatiles.{self.system.labels[j]}]")
            self.base_u.append(u)
            self.base_v.append(v)

    # ------------------------------------------------------------------ vertices and matches
    def vertices(self, U: np.ndarray, V: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Lattice positions and u-lifts (m * k, 2) of the vertices of hats lifted by (U, V)."""
        lin = U[:, :2, :2]
        pu = np.einsum("mij,kj->mki", lin, self.tile_u) + U[:, None, :2, 2]
        pv = np.einsum("mij,kj->mki", lin, self.tile_v) + V[:, None, :2, 2]
        return (pu + pv).reshape(-1, 2), pu.reshape(-1, 2)

    @staticmethod
    def offsets(pos_a: np.ndarray, u_a: np.ndarray, pos_b: np.ndarray, u_b: np.ndarray) -> np.ndarray:
        """The distinct u-translations (k, 2) that make the lifts of B's vertices equal A's at
        every position the two sets share (none: they share no vertex)."""
        ka, kb = _keys(pos_a), _keys(pos_b)
        order = np.argsort(ka, kind="stable")
        ks = ka[order]
        at = np.minimum(np.searchsorted(ks, kb), max(len(ks) - 1, 0))
        hit = ks[at] == kb if len(ks) else np.zeros(len(kb), dtype=bool)
        if not hit.any():
            return np.zeros((0, 2), dtype=np.int64)
        return np.unique(u_a[order[at[hit]]] - u_b[hit], axis=0)

    def _lift_pieces(self, maps: np.ndarray, what: str) -> tuple[np.ndarray, np.ndarray]:
        """Lifts of a metatile's hats (lattice maps (m, 3, 3)): the first by its translation
        as class-1 steps, each other one through the vertices it shares with those lifted."""
        maps = np.asarray(maps, dtype=np.int64)
        U = maps.copy()
        V = _with_translation(maps, 0)
        done = [0]
        todo = list(range(1, len(maps)))
        while todo:
            pos_a, u_a = self.vertices(U[done], V[done])
            for h in todo:
                pos_b, u_b = self.vertices(_with_translation(maps[[h]], 0), V[[h]])
                # hat h at u-translation 0 and v-translation 0: its vertices sit at
                # (position - t); the offsets below are then its whole u-translation
                cand = self.offsets(pos_a, u_a, pos_b + maps[h, :2, 2], u_b)
                if len(cand) > 1:
                    raise ParseError(f"substitution system {self.system.source}: {what} hat #{h + 1} meets "
                                     "the others at vertices that do not fit edge by edge")
                if len(cand):
                    U[h, :2, 2] = cand[0]
                    V[h, :2, 2] = maps[h, :2, 2] - cand[0]
                    done.append(h)
                    todo.remove(h)
                    break
            else:
                raise ParseError(f"substitution system {self.system.source}: {what} hats do not form one patch")
        return U, V

    # ------------------------------------------------------------------ levels
    def rules(self, n: int) -> tuple[list[np.ndarray], list[np.ndarray]]:
        """Per label, the lifted placements (U, V), each (m, 3, 3) integer, of its level-(n-1)
        children in its level-n frame (n >= 1); same children and order as ``rules_at(n)``."""
        if n < 1:
            raise ValueError("levels start at 1")
        while len(self._rules) < n:
            self._rules.append(self._solve_level(len(self._rules) + 1))
        return self._rules[n - 1]

    def generate(self, label: np.ndarray, U: np.ndarray, V: np.ndarray, depth: int,
                 box: tuple[float, float, float, float]) -> tuple[np.ndarray, np.ndarray]:
        """Lifted hats (U, V) of level-``depth`` supertiles ``label`` lifted by (U, V), culled
        to ``box`` (Cartesian) level by level with the hat's bounding discs."""
        s = self.system

        def cull(label: np.ndarray, U: np.ndarray, V: np.ndarray, n: int) -> np.ndarray:
            return meets_discs(label, to_cartesian(_with_translation(U, U[:, :2, 2] + V[:, :2, 2])), s.bounds(n), box)

        for n in range(depth, 0, -1):
            keep = cull(label, U, V, n)
            label, U, V = self._descend(label[keep], U[keep], V[keep], n)
        keep = cull(label, U, V, 0)
        label, U, V = label[keep], U[keep], V[keep]
        slots = [np.arange(len(b)) for b in s.base]
        _, U = expand_by_label(label, U, slots, self.base_u)
        _, V = expand_by_label(label, V, slots, self.base_v)
        return U, V

    def _descend(self, label: np.ndarray, U: np.ndarray, V: np.ndarray,
                 n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Level-n lifted supertiles (label, U, V) -> their level-(n-1) children."""
        rules_u, rules_v = self.rules(n)
        kids = [r.children for r in self.system.rules_at(n)]
        new_label, U = expand_by_label(label, U, kids, rules_u)
        _, V = expand_by_label(label, V, kids, rules_v)
        return new_label, U, V

    def _discs(self, label: np.ndarray, U: np.ndarray, V: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        """Centres (k, 2) and radii (k,) of the bounding discs of placed level-n supertiles."""
        centres, radii = self.system.bounds(n)
        maps = to_cartesian(_with_translation(U, U[:, :2, 2] + V[:, :2, 2]))
        return placed_points(label, maps, centres), radii[label]

    def _offset(self, n: int, j: int, k: int, U: np.ndarray, V: np.ndarray) -> np.ndarray | None:
        """The u-translation of cluster tile k (level n - 1) that makes the lifts of its hats
        agree with those of the lifted cluster tile j where their hats share vertices; None
        when they share none.

        Both supertiles are substituted down together, keeping at each level only the parts
        near the place where they come closest: the pair of parts (one of each) whose
        bounding discs overlap most, and every part whose disc meets the disc holding both.
        So the work per level is bounded, whatever the level."""
        s = self.system
        labels, lattice = s.cluster_at(n)
        a = (labels[[j]], U[[j]], V[[j]])
        b = (labels[[k]], _with_translation(lattice[[k]], 0), lattice[[k]])
        for level in range(n - 1, -1, -1):
            ca, ra = self._discs(*a, level)
            cb, rb = self._discs(*b, level)
            gap = np.linalg.norm(ca[:, None, :] - cb[None, :, :], axis=2) - ra[:, None] - rb[None, :]
            ia, ib = np.unravel_index(int(np.argmin(gap)), gap.shape)
            if gap[ia, ib] > 0:
                return None  # the two do not come near each other
            focus = (ca[ia] + cb[ib]) / 2
            reach = ra[ia] + rb[ib]
            near_a = np.linalg.norm(ca - focus, axis=1) <= ra + reach
            near_b = np.linalg.norm(cb - focus, axis=1) <= rb + reach
            a = tuple(x[near_a] for x in a)
            b = tuple(x[near_b] for x in b)
            if level:
                a, b = self._descend(*a, level), self._descend(*b, level)
        slots = [np.arange(len(m)) for m in s.base]
        hats = []
        for lab, u, v in (a, b):
            hats.append((expand_by_label(lab, u, slots, self.base_u)[1], expand_by_label(lab, v, slots, self.base_v)[1]))
        cand = self.offsets(*self.vertices(*hats[0]), *self.vertices(*hats[1]))
        if len(cand) > 1:
            raise ParseError(f"substitution system {s.source}: level {n}: cluster tiles {j} and {k} meet at "
                             "vertices that do not fit edge by edge")
        return cand[0] if len(cand) else None

    def _solve_level(self, n: int) -> tuple[list[np.ndarray], list[np.ndarray]]:
        """Lift the children of the level-n supertiles (see the module docstring): from the
        first child on, each one from a lifted child it touches (pairs whose bounding discs
        overlap most tried first); then every other touching pair must agree."""
        s = self.system
        labels, lattice = s.cluster_at(n)
        members = np.unique(np.concatenate(s.cluster_children))
        centres, radii = self._discs(labels[members], lattice[members], _with_translation(lattice[members], 0), n - 1)
        gap = np.linalg.norm(centres[:, None, :] - centres[None, :, :], axis=2) - radii[:, None] - radii[None, :]
        i, j = np.nonzero(np.triu(gap <= 0, 1))
        order = np.argsort(gap[i, j], kind="stable")
        pairs = [(int(members[x]), int(members[y])) for x, y in zip(i[order], j[order])]
        U = lattice.copy()
        V = _with_translation(lattice, 0)
        root = int(members[0])  # a gauge: the root's translation as class-1 steps
        done = {root}
        tried: set[tuple[int, int]] = set()
        progress = True
        while progress and len(done) < len(members):
            progress = False
            for p, q in pairs:
                if (p in done) == (q in done):
                    continue
                src, dst = (p, q) if p in done else (q, p)
                tried.add((p, q))
                off = self._offset(n, src, dst, U, V)
                if off is None:
                    continue
                U[dst, :2, 2] = off
                V[dst, :2, 2] = lattice[dst, :2, 2] - off
                done.add(dst)
                progress = True
                break
        if len(done) < len(members):
            missing = sorted(set(members.tolist()) - done)
            raise ParseError(f"substitution system {s.source}: level {n}: cluster tiles {missing} share no "
                             "vertices with the other children")
        for p, q in pairs:
            if (p, q) in tried:
                continue
            off = self._offset(n, p, q, U, V)
            if off is not None and np.any(off != U[q, :2, 2]):
                raise ParseError(f"substitution system {s.source}: level {n}: cluster tiles {p} and {q} "
                                 "do not fit edge by edge")
        if np.any((V[members, 0, 2] - V[members, 1, 2]) % 3):
            raise ParseError(f"substitution system {s.source}: level {n}: a lifted placement is off the lattice")
        return [U[c] for c in s.cluster_children], [V[c] for c in s.cluster_children]


# ---------------------------------------------------------------------- the deformed system


def check_edges(a: Any, b: Any) -> tuple[float, float]:
    """(a, b) as floats, or ParameterError: finite, in 0..MAX_EDGE, not both 0."""
    out = []
    for name, value in (("a", a), ("b", b)):
        try:
            x = float(value)
        except (TypeError, ValueError):
            raise ParameterError(f"Tile(a, b): {name}={value!r} is not a number; a and b are edge lengths "
                                 f"in 0..{MAX_EDGE:g}") from None
        if not (math.isfinite(x) and 0.0 <= x <= MAX_EDGE):
            raise ParameterError(f"Tile(a, b): {name}={value!r} is out of range; a and b are edge lengths in "
                                 f"0..{MAX_EDGE:g}")
        out.append(x)
    if out[0] == 0 and out[1] == 0:
        raise ParameterError("Tile(0, 0) is a point; give a > 0 or b > 0 (the hat is Tile(1, sqrt3))")
    return out[0], out[1]


def deformed_outline(lifts: HatLifts, a: float, b: float) -> np.ndarray:
    """Tile(a, b)'s outline: the hat's vertices at ``a u + (b / sqrt3) v``, points that
    coincide (edges of length 0 when a or b is 0) merged."""
    pts = deform(a, b, lifts.tile_u, lifts.tile_v)
    size = float(np.ptp(pts, axis=0).max())
    keep = np.linalg.norm(pts - np.roll(pts, 1, axis=0), axis=1) > COLLAPSE_TOL * size
    return pts[keep]


def tile_name(a: float, b: float) -> str:
    return f"Tile({_number(a)}, {_number(b)})"


def _number(x: float) -> str:
    if abs(x - SQRT3) < 1e-12:
        return "sqrt3"
    return f"{x:.12g}"


@dataclass
class ContinuumSystem(MonotileSystem):
    """The hat's metatile hierarchy with Tile(a, b) in place of the hat: the same labels,
    children and counts; placements rigid, their translations ``a u + (b / sqrt3) v`` from
    the lifted hierarchy (:class:`HatLifts`)."""

    hat: HatSystem
    lifts: HatLifts
    a: float
    b: float
    name: str = "hat"
    kind: str = "keypoint"
    reflect: bool = False
    _rules: list[list[Rule]] = field(default_factory=list)
    _bounds: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)

    def __post_init__(self) -> None:
        outline = deformed_outline(self.lifts, self.a, self.b)
        try:
            self.tile = Prototile(outline, name=tile_name(self.a, self.b))
        except GeometryError as exc:
            raise ParameterError(f"{tile_name(self.a, self.b)} is not a simple polygon ({exc})") from None
        self.base = [self._placements(u, v) for u, v in zip(self.lifts.base_u, self.lifts.base_v)]

    # the hat's combinatorics
    @property
    def labels(self) -> list[str]:
        return self.hat.labels

    @property
    def seed(self) -> int:  # type: ignore[override]
        return self.hat.seed

    @property
    def title(self) -> str:
        return f"{tile_name(self.a, self.b)} of the hat's continuum, on the hat's metatiles H, T, P, F"

    @property
    def source(self) -> str:
        return self.hat.source

    @property
    def max_tiles(self) -> float:  # type: ignore[override]
        return self.hat.max_tiles

    @property
    def facts(self) -> dict[str, Any]:
        return self.hat.facts

    def child_labels(self) -> list[np.ndarray]:
        return self.hat.child_labels()

    @property
    def rules(self) -> list[np.ndarray]:
        """Per label, the labels of its children (for ``describe``)."""
        return self.hat.rules

    def _placements(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Cartesian rigid maps (m, 3, 3) of lifted placements (U, V)."""
        out = to_cartesian(_with_translation(u, 0))
        out[:, :2, 2] = deform(self.a, self.b, u[:, :2, 2], v[:, :2, 2])
        return out

    def rules_at(self, n: int) -> list[Rule]:
        """Per label, the children and rigid maps building level n from level n - 1."""
        if n < 1:
            raise ValueError("levels start at 1")
        while len(self._rules) < n:
            k = len(self._rules) + 1
            rules_u, rules_v = self.lifts.rules(k)
            kids = [r.children for r in self.hat.rules_at(k)]
            self._rules.append([Rule(c, self._placements(u, v)) for c, u, v in zip(kids, rules_u, rules_v)])
        return self._rules[n - 1]

    def generation(self, depth: int, seed_transform: np.ndarray | None, seed_label: int | None,
                   box: tuple[float, float, float, float] | None) -> Generation:
        """Colours as the hat's: 0 unreflected tile of an H, 1 its reflected tile, 2 T, 3 P, 4 F."""
        t0 = np.eye(3) if seed_transform is None else np.asarray(seed_transform, dtype=float)
        return self.rigid_generation(t0, seed_label, box, hat_colours(self.hat.base))


def lifts_of(hat: HatSystem) -> HatLifts:
    """The hat system's lifted hierarchy (built once, kept on the system)."""
    if hat.lifted is None:
        hat.lifted = HatLifts(hat)
    return hat.lifted


#: Deformed systems kept per hat system and (a, b) (each holds its rules and bounds per level).
_SYSTEMS_KEPT = 8


def continuum_system(hat: HatSystem, a: float, b: float) -> ContinuumSystem:
    """The hat's hierarchy with Tile(a, b) (kept: the last few asked for are reused)."""
    lifts = lifts_of(hat)
    kept = lifts.systems
    key = (float(a), float(b))
    if key not in kept:
        if len(kept) >= _SYSTEMS_KEPT:
            kept.pop(next(iter(kept)))
        kept[key] = ContinuumSystem(hat, lifts, *key)
    return kept[key]


@dataclass(frozen=True)
class Member:
    """A named member of the continuum (``[continuum.members.NAME]``)."""

    name: str
    a: float
    b: float
    title: str
    aperiodic: bool | None
    aliases: tuple[str, ...]


def members(hat: HatSystem) -> dict[str, Member]:
    """The named members of the hat file's ``[continuum.members]`` table, by name; a bad
    entry is one ParseError naming the file and the member."""
    out = {}
    for name, entry in hat.continuum.get("members", {}).items():
        where = f"substitution system {hat.source}: [continuum.members.{name}]"
        try:
            a, b = check_edges(evaluate(entry["a"]), evaluate(entry["b"]))
        except (ParseError, ParameterError) as exc:
            raise ParseError(f"{where}: {exc}") from None
        out[name] = Member(name, a, b, str(entry.get("title", tile_name(a, b))), entry.get("aperiodic"),
                           tuple(str(x) for x in entry.get("aliases", [])))
    return out
