"""The hat monotile (arXiv:2303.10798) through its four metatiles H, T, P, F.

The paper's substitution is combinatorial: a level-(n+1) supertile is a cluster of level-n
supertiles placed by rigid motions that glue edges of their outlines together, and the
level-(n+1) outlines are then recomputed from points of that cluster (§4 of the paper). The
outlines are not similar from level to level, so the placements are computed per level, but
within a level they are shared by all supertiles of a label: generation is the same batched
product of (k, 3, 3) stacks as the keypoint engine (``keypoint.py``), with per-level rules.

Level 0: H carries four hats (one reflected), T one, P two, F two. The data (lattice
coordinates of the hat and the metatiles, the cluster assembly and the supertile children)
is ``catalogue/substitution/hat/hat.toml``; this module turns it into a system with the
KeypointSystem interface, so ``HatTiling`` (a ``KeypointTiling``) serves its patches; the
continuum Tile(a, b) deforms this hierarchy (``continuum.py``).

Colours of generated hats: 0 unreflected hat of an H, 1 the reflected hat of an H, 2 the
hat of a T, 3 hats of a P, 4 hats of an F.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import shapely

from tilekit.errors import ParseError
from tilekit.geometry import Affine
from tilekit.plugins.substitution.formats import read_system_data
from tilekit.plugins.substitution.keypoint import Generation, MonotileSystem, Tiles
from tilekit.plugins.substitution.levels import (
    expand_base,
    expand_by_label,
    meets_discs,
    placed_points,
)
from tilekit.plugins.substitution.rules import Rule
from tilekit.plugins.substitution.system import guarded_loader
from tilekit.polygon import signed_area
from tilekit.resources import catalogue_dir, read_toml
from tilekit.tiling import Prototile

SQRT3 = math.sqrt(3.0)
#: The triangular-lattice basis: [a, b] is a*(1, 0) + b*(1/2, sqrt3/2).
LATTICE = np.array([[1.0, 0.5], [0.0, SQRT3 / 2]])
#: Area of one kite of the [3.4.6.4] Laves tiling at the hat's scale (sides 1, 1, sqrt3, sqrt3).
KITE_AREA = SQRT3
REFLECT_X = np.diag([1.0, -1.0, 1.0])
#: Homogeneous change of basis: lattice coordinates -> Cartesian, and back.
TO_CARTESIAN = np.block([[LATTICE, np.zeros((2, 1))], [np.zeros((1, 2)), np.ones((1, 1))]])
TO_LATTICE = np.linalg.inv(TO_CARTESIAN)
#: Most hats a whole (unclipped) supertile may have.
MAX_TILES = 5_000_000
#: Largest distance (in lattice units) a computed map may lie from an exact lattice map.
SNAP_TOL = 1e-6
#: Relative tolerance on edge lengths when gluing supertiles (they must be congruent edges).
GLUE_TOL = 1e-9


def lattice_points(pairs: Any) -> np.ndarray:
    """Lattice pairs (k, 2) -> Cartesian points (k, 2)."""
    return np.asarray(pairs, dtype=float) @ LATTICE.T


def to_lattice(matrices: np.ndarray) -> np.ndarray:
    """Cartesian isometries (..., 3, 3) that preserve the triangular lattice -> their exact
    integer matrices in lattice coordinates; ValueError when one is not such a map."""
    lat = TO_LATTICE @ np.asarray(matrices, dtype=float) @ TO_CARTESIAN
    exact = np.round(lat)
    err = float(np.abs(lat - exact).max()) if lat.size else 0.0
    if err > SNAP_TOL:
        raise ValueError(f"a placement is {err:.3g} away from a symmetry of the triangular lattice")
    return exact.astype(np.int64)


def to_cartesian(lattice_maps: np.ndarray) -> np.ndarray:
    """Integer lattice-coordinate maps (..., 3, 3) -> Cartesian affine matrices."""
    return TO_CARTESIAN @ np.asarray(lattice_maps, dtype=float) @ TO_LATTICE


def rigid_match(p1: np.ndarray, q1: np.ndarray, p2: np.ndarray, q2: np.ndarray) -> np.ndarray:
    """The direct isometry taking p1 to p2 and q1 to q2; ValueError when |p1q1| != |p2q2|."""
    a, b = q1 - p1, q2 - p2
    la, lb = float(np.hypot(*a)), float(np.hypot(*b))
    if abs(la - lb) > GLUE_TOL * max(la, lb, 1.0):
        raise ValueError(f"segments of lengths {la:.9g} and {lb:.9g} cannot be matched rigidly")
    ang = math.atan2(b[1], b[0]) - math.atan2(a[1], a[0])
    rot = Affine.rotation(ang)
    moved = Affine.apply(rot, p1)
    return Affine.translation(*(p2 - moved)) @ rot


def _rotate(point: np.ndarray, degrees: float, centre: np.ndarray) -> np.ndarray:
    return Affine.apply(Affine.rotation(math.radians(degrees), centre), point)


def _intersect(p1: np.ndarray, q1: np.ndarray, p2: np.ndarray, q2: np.ndarray) -> np.ndarray:
    """Intersection of the lines p1q1 and p2q2."""
    d1, d2 = q1 - p1, q2 - p2
    den = d1[0] * d2[1] - d1[1] * d2[0]
    t = ((p2[0] - p1[0]) * d2[1] - (p2[1] - p1[1]) * d2[0]) / den
    return p1 + t * d1


@dataclass
class HatSystem(MonotileSystem):
    """The hat's metatile substitution, with the interface of ``KeypointSystem``."""

    #: ``generate`` without a region refuses more hats than this (ParameterError)
    max_tiles: ClassVar[float] = MAX_TILES

    name: str
    title: str
    labels: list[str]
    tile: Prototile
    outlines0: list[np.ndarray]  # per label, level-0 outline (k, 2)
    base: list[np.ndarray]  # per label, (m, 3, 3) integer lattice maps of its hats
    attach: list[tuple[Any, ...]]
    cluster_children: list[np.ndarray]  # per label, cluster tile indices
    seed: int = 0
    facts: dict[str, Any] = field(default_factory=dict)
    source: str = "<data>"
    data: dict[str, Any] = field(default_factory=dict)
    kind: str = "keypoint"
    reflect: bool = False
    #: the file's checked ``[continuum]`` table (continuum.py reads it: members Tile(a, b))
    continuum: dict[str, Any] = field(default_factory=dict)
    #: the lifted hierarchy, built on first use by ``continuum.lifts_of``
    lifted: Any = field(default=None, repr=False, compare=False)
    _levels: list[tuple[list[Rule], list[np.ndarray], list[np.ndarray], np.ndarray, np.ndarray]] = field(
        default_factory=list)
    _bounds: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)

    @property
    def rules(self) -> list[np.ndarray]:
        """Per label, the labels of its children (for ``describe``)."""
        lab = self.cluster_labels()
        return [lab[c] for c in self.cluster_children]

    def child_labels(self) -> list[np.ndarray]:
        return self.rules

    def cluster_labels(self) -> np.ndarray:
        index = {nm: i for i, nm in enumerate(self.labels)}
        return np.array([index[a[-2] if len(a) > 1 else a[0]] for a in self.attach], dtype=np.int64)

    def hats_per_label(self) -> np.ndarray:
        return self.tiles_per_label()

    def reflected_per_label(self) -> np.ndarray:
        return np.array([int((np.linalg.det(b[:, :2, :2]) < 0).sum()) for b in self.base], dtype=np.int64)

    def reflected_fraction_limit(self) -> float:
        """Limit share of reflected hats: from the Perron-Frobenius frequencies of the labels."""
        _, freq = self.perron_frobenius()
        return float(freq @ self.reflected_per_label() / (freq @ self.hats_per_label()))

    # ------------------------------------------------------------------ levels
    def outlines(self, n: int) -> list[np.ndarray]:
        """Per label, the level-n supertile outline (in its own frame)."""
        if n == 0:
            return self.outlines0
        self._build(n)
        return self._levels[n - 1][1]

    def rules_at(self, n: int) -> list[Rule]:
        """Per label, the children (labels) and rigid maps building level n from level n-1."""
        if n < 1:
            raise ValueError("levels start at 1")
        self._build(n)
        return self._levels[n - 1][0]

    def lattice_rules_at(self, n: int) -> list[np.ndarray]:
        """Per label, the exact integer (m, 3, 3) lattice-coordinate maps of ``rules_at(n)``."""
        if n < 1:
            raise ValueError("levels start at 1")
        self._build(n)
        return self._levels[n - 1][2]

    def cluster_at(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """The whole cluster assembled for level n (n >= 1), in the level-n supertiles' frame:
        its level-(n-1) supertiles' labels (k,) and exact lattice maps (k, 3, 3), in the order
        of ``[cluster] attach`` (the children of each label are among them)."""
        if n < 1:
            raise ValueError("levels start at 1")
        self._build(n)
        return self._levels[n - 1][3], self._levels[n - 1][4]

    def _build(self, n: int) -> None:
        while len(self._levels) < n:
            prev = self.outlines(len(self._levels))
            self._levels.append(self._next_level(prev))

    def _next_level(self, shapes: list[np.ndarray]) -> tuple[list[Rule], list[np.ndarray], list[np.ndarray],
                                                             np.ndarray, np.ndarray]:
        index = {nm: i for i, nm in enumerate(self.labels)}
        labels: list[int] = []
        maps: list[np.ndarray] = []
        lattice: list[np.ndarray] = []

        def vertex(k: int, v: int) -> np.ndarray:
            pts = shapes[labels[k]]
            return Affine.apply(maps[k], pts[v % len(pts)])

        for entry in self.attach:
            if len(entry) == 1:
                labels.append(index[entry[0]])
                maps.append(np.eye(3))
                lattice.append(np.eye(3, dtype=np.int64))
                continue
            if len(entry) == 4:
                k, e, lab, f = entry
                p, q = vertex(k, e + 1), vertex(k, e)
            else:
                k, u, m, v, lab, f = entry
                p, q = vertex(m, v), vertex(k, u)
            j = index[lab]
            own = shapes[j]
            try:
                t = rigid_match(own[f % len(own)], own[(f + 1) % len(own)], p, q)
            except ValueError as exc:
                raise ParseError(f"substitution system {self.source}: cluster entry {list(entry)}: {exc}") from None
            try:
                # every hat of the tiling lies on the kite lattice, so each placement is a
                # lattice symmetry: keep it exact (this also stops float drift between levels)
                exact = to_lattice(t)
            except ValueError as exc:
                raise ParseError(f"substitution system {self.source}: cluster entry {list(entry)}: {exc}") from None
            labels.append(j)
            maps.append(to_cartesian(exact))
            lattice.append(exact)
        lab_arr = np.array(labels, dtype=np.int64)
        map_arr = np.array(maps)
        lat_arr = np.array(lattice)
        rules = [Rule(lab_arr[c], map_arr[c]) for c in self.cluster_children]
        return rules, _outlines(vertex), [lat_arr[c] for c in self.cluster_children], lab_arr, lat_arr

    def placed_base(self) -> list[np.ndarray]:
        """Per label, the Cartesian placements of its metatile's hats."""
        return [to_cartesian(b) for b in self.base]

    # ------------------------------------------------------------------ generation
    def lattice_supertiles(self, depth: int, level: int = 0, seed_label: int | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The level-``level`` supertiles of a level-``depth`` one at the origin: labels and
        exact integer lattice-coordinate maps (k, 3, 3)."""
        label = np.array([self.seed if seed_label is None else seed_label], dtype=np.int64)
        lattice = np.eye(3, dtype=np.int64)[None]
        for n in range(depth, level, -1):
            label, lattice = self._expand(label, lattice, n)
        return label, lattice

    def supertiles(
        self, depth: int, level: int = 0, seed_transform: np.ndarray | None = None, seed_label: int | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """The level-``level`` supertiles (labels, Cartesian transforms) of a level-``depth`` one."""
        label, lattice = self.lattice_supertiles(depth, level, seed_label)
        return label, _placed(seed_transform, lattice)

    def _expand(self, label: np.ndarray, lattice: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        children = [rule.children for rule in self.rules_at(n)]
        return expand_by_label(label, lattice, children, self.lattice_rules_at(n))

    def generation(self, depth: int, seed_transform: np.ndarray | None, seed_label: int | None,
                   box: tuple[float, float, float, float] | None) -> Generation:
        """Placements are composed exactly, as integer matrices in lattice coordinates, and
        converted to Cartesian (and moved by ``seed_transform``) once, at the end."""
        label = np.array([self.seed if seed_label is None else seed_label], dtype=np.int64)

        def cull(label: np.ndarray, lattice: np.ndarray, n: int) -> np.ndarray:
            return meets_discs(label, _placed(seed_transform, lattice), self.bounds(n), box)

        def centres(label: np.ndarray, lattice: np.ndarray, n: int) -> np.ndarray:
            return placed_points(label, _placed(seed_transform, lattice), self.bounds(n)[0])

        colours = hat_colours(self.base)

        def finish(label: np.ndarray, lattice: np.ndarray) -> Tiles:
            lattice, colour = expand_base(label, lattice, self.base, colours)
            if not len(lattice):
                return np.zeros(0, dtype=np.int64), np.zeros((0, 3, 3)), np.zeros(0, dtype=np.int64)
            transform = _placed(seed_transform, lattice)
            return np.zeros(len(transform), dtype=np.int64), transform, colour

        lattice = np.eye(3, dtype=np.int64)[None]
        return Generation(label, lattice, self._expand, cull if box is not None else None, centres, finish)


def hat_colours(base: list[np.ndarray]) -> list[np.ndarray]:
    """Per metatile label, its tiles' colours: 0 an unreflected tile of an H, 1 the reflected
    one, 2 T, 3 P, 4 F (label j > 0: 1 + j)."""
    out = []
    for j, placements in enumerate(base):
        colour = np.full(len(placements), 1 + j, dtype=np.int64)
        if j == 0:
            colour = (np.linalg.det(np.asarray(placements, dtype=float)[:, :2, :2]) < 0).astype(np.int64)
        out.append(colour)
    return out


def _placed(seed_transform: np.ndarray | None, lattice: np.ndarray) -> np.ndarray:
    """Cartesian transforms of lattice maps, after ``seed_transform`` (identity if None):
    ``seed @ TO_CARTESIAN @ lattice[i] @ TO_LATTICE``, in one compiled pass."""
    # start-up cost: numba loads only when tiles are generated
    from tilekit.plugins.substitution import kernels

    left = TO_CARTESIAN if seed_transform is None else np.asarray(seed_transform, dtype=float) @ TO_CARTESIAN
    return kernels.sandwich(left, lattice, TO_LATTICE)


def _outlines(vertex: Any) -> list[np.ndarray]:
    """The next-level outlines of H, T, P, F from points of the assembled cluster.

    ``vertex(k, v)`` is vertex v of cluster tile k. The construction follows the paper's
    supertile figure: the long H-P-F boundary runs through vertex 2 of tiles 8 and 21 (the
    second turned by -120 degrees about the first gives the boundary direction); it meets the
    line through vertex 2 of tiles 6 and 7 at the common corner of the H, P and F
    supertiles; the other corners are cluster vertices or translates of these by the
    supertile edge vectors (turned by multiples of 60 degrees).
    """
    a = vertex(8, 2)
    b = vertex(21, 2)
    b_turned = _rotate(b, -120, a)
    p72 = vertex(7, 2)
    p252 = vertex(25, 2)
    corner = _intersect(a, b_turned, vertex(6, 2), p72)
    w = vertex(6, 2) - corner
    w1 = _rotate(w, -60, np.zeros(2))
    w2 = _rotate(w1, -60, np.zeros(2))
    h = np.array([corner, a, a + w1, vertex(14, 2), vertex(14, 2) - w2, vertex(6, 2)])
    p = np.array([p72, p72 + (a - corner), a, corner])
    f = np.array([b, vertex(24, 2), vertex(25, 0), p252, p252 + (corner - a)])
    t_apex = h[2]
    t_base = h[1] + (h[4] - h[5])
    t = np.array([t_base, _rotate(t_apex, -60, t_base), t_apex])
    return [h, t, p, f]


# ---------------------------------------------------------------------- loading


def hat_data_path() -> Path:
    """The shipped hat data file."""
    return catalogue_dir() / "substitution" / "hat" / "hat.toml"


@guarded_loader
def hat_system_from_data(data: Mapping[str, Any], source: str = "<data>") -> HatSystem:
    """Build and check the hat system from parsed TOML (errors name the file and part): the
    shape of every field is checked by the hat schema (:mod:`.formats`), then the metatiles'
    hats are placed and the cluster's attachments resolved."""
    raw = data
    _, data = read_system_data(data, source, "hat-metatiles")

    def fail(msg: str) -> ParseError:
        return ParseError(f"substitution system {source}: {msg}")

    labels = data["labels"]
    outline = lattice_points(np.array(data["tile"]["outline"], dtype=float))
    # Prototile wants a CCW outline; placements below are computed on the raw vertex order.
    ccw = outline if signed_area(outline) > 0 else outline[::-1]
    try:
        tile = Prototile(ccw, name=data["tile"]["name"])
    except Exception as exc:  # GeometryError
        raise fail(f"[tile]: {exc}") from None
    outlines0, base = [], []
    for nm in labels:
        meta = data["metatiles"][nm]
        pts = lattice_points(np.array(meta["outline"], dtype=float))
        outlines0.append(pts)
        mats = [_hat_placement(h, outline, pts, f"[metatiles.{nm}] hat #{k + 1}", fail)
                for k, h in enumerate(meta["hats"])]
        try:
            base.append(to_lattice(np.array(mats)))
        except ValueError as exc:
            raise fail(f"[metatiles.{nm}] hats: {exc}") from None
    cluster = data["cluster"]
    attach = [_attachment(e, k, labels, fail) for k, e in enumerate(cluster["attach"])]
    children = []
    for nm in labels:
        c = cluster["children"][nm]
        if max(c) >= len(attach):
            raise fail(f"[cluster.children] {nm} must list cluster tile indices 0..{len(attach) - 1}")
        children.append(np.array(c, dtype=np.int64))
    system = HatSystem(
        name=data["name"],
        title=data["title"],
        labels=list(labels),
        tile=tile,
        outlines0=outlines0,
        base=base,
        attach=attach,
        cluster_children=children,
        seed=labels.index(data["seed"]),
        facts=dict(data.get("properties", {})),
        source=source,
        data=dict(raw),
        continuum=dict(data.get("continuum", {})),
    )
    _derived_facts(system)
    check_hat_system(system)
    return system


def _hat_placement(h: Mapping[str, Any], hat: np.ndarray, outline: np.ndarray, ctx: str, fail: Any) -> np.ndarray:
    """A metatile's hat: by ``match`` (two hat vertices onto two outline vertices) or by
    reflect (in the x axis), rotate (degrees) and translate (a lattice pair)."""
    if "match" in h:
        try:
            (i, p), (j, q) = h["match"]
            return rigid_match(hat[i], hat[j], outline[p], outline[q])
        except (ValueError, TypeError, IndexError) as exc:
            raise fail(f"{ctx}: match must be [[hat vertex, outline vertex], [.., ..]] of equal lengths ({exc})") from None
    tx, ty = lattice_points(np.array([h["translate"]], dtype=float))[0]
    t = Affine.translation(tx, ty) @ Affine.rotation(math.radians(float(h["rotate"])))
    return t @ REFLECT_X if h["reflect"] else t


def _attachment(e: Any, k: int, labels: list[str], fail: Any) -> tuple[Any, ...]:
    """Cluster entry k: ["X"] (the first), [k', e, "X", f] or [k', u, m, v, "X", f] with
    earlier tiles k', m."""
    ok = isinstance(e, list) and (
        (len(e) == 1 and k == 0)
        or (len(e) == 4 and isinstance(e[0], int) and 0 <= e[0] < k)
        or (len(e) == 6 and all(isinstance(x, int) and 0 <= x < k for x in (e[0], e[2])))
    )
    if not ok or e[-2 if len(e) > 1 else 0] not in labels:
        raise fail(f"[cluster] attach entry #{k}: {e!r} is not [\"X\"] (first), [k, e, \"X\", f] or "
                   "[k, u, m, v, \"X\", f] with earlier k, m")
    return tuple(e)


def _derived_facts(system: HatSystem) -> None:
    """The counts the catalogue shows, unless the file states them."""
    facts = system.facts
    facts.setdefault("reflected_hats_per_metatile", system.reflected_per_label().tolist())
    facts.setdefault("hats_per_metatile", system.hats_per_label().tolist())
    frac = system.reflected_fraction_limit()
    facts.setdefault("reflected_hat_fraction", round(frac, 12))
    facts.setdefault("unreflected_to_reflected_ratio", round((1 - frac) / frac, 12))
    facts.setdefault(
        "reflected_hats_per_generation", [int(c @ system.reflected_per_label()) for c in map(np.array, system.counts(6))]
    )


def check_hat_system(system: HatSystem, levels: int = 2) -> None:
    """Every label's supertile, for the first ``levels`` levels, is a set of non-overlapping
    hats (the data is wrong otherwise)."""
    tile = system.tile.outline
    for n in range(levels + 1):
        for j, nm in enumerate(system.labels):
            _, tr, _ = system.generate(n, seed_label=j)
            polys = shapely.polygons(Affine.apply(tr, tile))
            total = float(shapely.area(polys).sum())
            union = shapely.union_all(polys, grid_size=1e-9).area
            if total - union > 1e-6 * float(shapely.area(polys[0])):
                raise ParseError(f"substitution system {system.source}: level-{n} supertile {nm!r} has overlapping hats")


def load_hat(path: str | Path | None = None) -> HatSystem:
    """Read and check the hat data file (the shipped one by default)."""
    p = Path(path) if path is not None else hat_data_path()
    return hat_system_from_data(read_toml(p, "substitution system"), source=p.name)


def hat_systems() -> dict[str, HatSystem]:
    """The hat system by name, for ``builtin_systems``."""
    system = load_hat()
    return {system.name: system}


__all__ = [
    "HatSystem",
    "hat_system_from_data",
    "hat_systems",
    "lattice_points",
    "load_hat",
    "rigid_match",
    "to_cartesian",
    "to_lattice",
]
