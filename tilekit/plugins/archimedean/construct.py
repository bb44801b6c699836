"""Build Archimedean tilings from their vertex types, and Laves tilings as their duals.

Construction (no coordinates typed in): the shared builder grows a patch of unit-edge
regular polygons under the rule "every vertex has this type" to a radius; the translations
that map the patch's core onto the patch are read off (the differences of equal, equally
turned tiles that carry every tile near the centre onto a tile); the two shortest
independent ones form a reduced lattice basis; the tiles whose centres fall in one
fundamental parallelogram are the translational unit. The result is checked before it is
returned: the periodic patch it generates is valid and every interior vertex has the type.
If the patch was too small to show two translations, the radius grows.

Laves tilings (§4.2): one tile per vertex of the Archimedean tiling, the polygon through the
centres of the tiles round that vertex, in order; all such tiles are congruent, and each is
placed by the rigid motion taking the first onto it.
"""

from __future__ import annotations

import json
import math
from functools import cache
from typing import Any

import numpy as np

from tilekit.builder import TWO_PI, BuildResult, PatchBuilder, VertexView
from tilekit.colouring import Colouring
from tilekit.errors import GeometryError, ParseError
from tilekit.geometry import Affine, snap_noise
from tilekit.limits import DEFAULT_SOLVER_SECONDS
from tilekit.polygon import vertex_stars
from tilekit.regular.notation import (
    VertexType,
    arrangements,
    canonical,
    parse_vertex_type,
)
from tilekit.regular.tiles import (
    format_vector,
    polygon_angle,
    regular_prototiles,
    size_colour,
    unit_text,
)
from tilekit.resources import catalogue_dir
from tilekit.symmetry import canonical_basis, symmetries
from tilekit.tiling import Patch, PeriodicTiling, Prototile


class VertexTypeRule:
    """The builder rule "every vertex has one of these types".

    A closed vertex must read, counter-clockwise, as an arrangement of an allowed type. An
    open vertex's fans (runs of abutting corners) with the angular gaps between them must
    fit some arrangement: each fan a run of the cycle, each gap exactly filled by the
    polygons between."""

    def __init__(self, types: list[VertexType], sides: list[int]) -> None:
        self.types = list(types)
        self.sides = list(sides)  # prototile index -> number of sides
        self._closed = {a for t in self.types for a in arrangements(t.polygons)}
        self._cycles = sorted(self._closed)

    def describe(self) -> str:
        return "every vertex of type " + " or ".join(str(t) for t in self.types)

    def closed(self, view: VertexView) -> bool:
        seq = tuple(self.sides[c.prototile] for c in view.fans[0])
        return seq in self._closed

    def open(self, view: VertexView) -> bool:
        fans = [tuple(self.sides[c.prototile] for c in fan) for fan in view.fans]
        gaps = list(view.gaps)
        return any(self._fits(cyc, fans, gaps) for cyc in self._cycles)

    @staticmethod
    def _fits(cyc: tuple[int, ...], fans: list[tuple[int, ...]], gaps: list[float]) -> bool:
        k = len(cyc)
        if sum(len(f) for f in fans) > k:
            return False
        for start in range(k):
            pos = start
            ok = True
            used = 0
            for fan, gap in zip(fans, gaps):
                for p in fan:
                    if cyc[pos % k] != p:
                        ok = False
                        break
                    pos += 1
                    used += 1
                if not ok:
                    break
                # fill the gap with the next polygons of the cycle
                acc = 0.0
                while acc < gap - 1e-5 and used < k:
                    acc += polygon_angle(cyc[pos % k])
                    pos += 1
                    used += 1
                if abs(acc - gap) > 1e-5:
                    ok = False
                    break
            if ok and used == k:
                return True
        return False


def seed_radius(vt: VertexType) -> float:
    """Circumradius of the seed polygon that :func:`grow` starts from (the largest one)."""
    return 0.5 / math.sin(math.pi / max(vt.polygons))


def grow(vertex_type: VertexType | str, radius: float, *, max_nodes: int = 200_000,
         max_seconds: float | None = DEFAULT_SOLVER_SECONDS, seed_size: int | None = None) -> BuildResult:
    """Grow a patch round a seed polygon in which every closed vertex has ``vertex_type``."""
    vt = parse_vertex_type(vertex_type) if isinstance(vertex_type, str) else vertex_type
    sizes = vt.sizes
    protos = regular_prototiles(sizes)
    rule = VertexTypeRule([vt], list(sizes))
    seed = sizes.index(seed_size) if seed_size is not None else len(sizes) - 1
    builder = PatchBuilder(protos, rule=rule, order="nearest")
    # centre the seed polygon on the origin
    c = protos[seed].outline.mean(axis=0)
    return builder.build(radius=radius, seed=seed, seed_transform=Affine.translation(-c[0], -c[1]),
                         max_nodes=max_nodes, max_seconds=max_seconds)


def _tile_keys(patch: Patch, sides: list[int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centres, sides and orientation class (rotation angle modulo the polygon's symmetry)."""
    centres = patch.centres()
    n = np.array([sides[p] for p in patch.prototile])
    theta = np.arctan2(patch.transform[:, 1, 0], patch.transform[:, 0, 0])
    orient = np.mod(theta, TWO_PI / n) / (TWO_PI / n)
    orient = np.where(orient > 1 - 1e-6, 0.0, orient)
    return centres, n, orient


def find_lattice(patch: Patch, sides: list[int], radius: float) -> tuple[np.ndarray, np.ndarray] | None:
    """Two independent translations mapping the patch's core onto the patch, or None.

    A translation t qualifies when every tile whose centre lies within ``radius - |t| - d``
    of the origin (d: the largest tile diameter) has a tile of the same size and orientation
    at its centre + t, and that core reaches at least |t| (so a whole period was seen)."""
    centres, n, orient = _tile_keys(patch, sides)
    q = 1e-5
    keys = {
        (int(k), round(float(o) * 1e4), round(float(x) / q), round(float(y) / q))
        for k, o, (x, y) in zip(n, orient, centres)
    }

    def has(k, o, x, y) -> bool:
        ko = round(float(o) * 1e4)
        kx, ky = round(float(x) / q), round(float(y) / q)
        return any((int(k), ko2, kx + dx, ky + dy) in keys
                   for ko2 in (ko - 1, ko, ko + 1) for dx in (-1, 0, 1) for dy in (-1, 0, 1))

    diam = max(1.0 / math.sin(math.pi / p) for p in set(sides))
    dist = np.hypot(centres[:, 0], centres[:, 1])
    seed = int(np.argmin(dist))
    same = np.flatnonzero((n == n[seed]) & (np.abs(orient - orient[seed]) < 1e-4))
    cands = centres[same] - centres[seed]
    lengths = np.hypot(cands[:, 0], cands[:, 1])
    order = np.lexsort((np.round(np.mod(np.arctan2(cands[:, 1], cands[:, 0]), TWO_PI), 6), np.round(lengths, 6)))
    good: list[np.ndarray] = []
    for i in order:
        t, length = cands[i], lengths[i]
        if length < 1e-6:
            continue
        core_r = radius - length - diam
        if core_r < length:
            break
        core = dist <= core_r
        if all(has(k, o, x + t[0], y + t[1]) for k, o, (x, y) in zip(n[core], orient[core], centres[core])):
            if not good:
                good.append(t)
            elif abs(good[0][0] * t[1] - good[0][1] * t[0]) > 1e-6:
                good.append(t)
                return canonical_basis(good[0], good[1])
    return None


def unit_from_patch(patch: Patch, v1: np.ndarray, v2: np.ndarray) -> np.ndarray:
    """Indices of the tiles whose centres lie in the fundamental parallelogram at the origin
    (shifted by a small generic offset so no centre sits on its boundary)."""
    centres = patch.centres()
    basis = np.column_stack([v1, v2])
    ab = (centres - np.array([0.0123, 0.0171])) @ np.linalg.inv(basis).T + np.array([0.5, 0.5])
    return np.flatnonzero(np.all((ab >= 0) & (ab < 1), axis=1))


def _vertex_sequences(patch: Patch, sides: list[int], region_radius: float) -> dict[tuple[int, ...], int]:
    """Canonical polygon sequence (CCW) round every vertex within ``region_radius`` whose
    surrounding angle is complete, counted; used to check a construction."""

    polys = patch.polygons()
    stars = vertex_stars(polys)
    corners: list[list[tuple[float, int, float]]] = []
    for v in range(len(stars)):
        lst = []
        for c in stars.members(v):
            t, i = int(stars.tile[c]), int(stars.index[c])
            pts = polys[t]
            x, y = pts[i]
            if math.hypot(x, y) > region_radius:
                continue
            d = pts[(i + 1) % len(pts)] - pts[i]
            p = sides[int(patch.prototile[t])]
            lst.append((math.atan2(d[1], d[0]), p, polygon_angle(p)))
        if lst:
            corners.append(lst)
    out: dict[tuple[int, ...], int] = {}
    for lst in corners:
        total = sum(c[2] for c in lst)
        if abs(total - TWO_PI) > 1e-6:
            continue
        seq = canonical(tuple(c[1] for c in sorted(lst)))
        out[seq] = out.get(seq, 0) + 1
    return out


def vertex_types_in(patch: Patch, sides: list[int], radius: float) -> dict[str, int]:
    """Vertex types (exponent form) of the surrounded vertices within ``radius`` of the origin."""
    return {str(VertexType(s)): n for s, n in _vertex_sequences(patch, sides, radius).items()}


@cache
def _construct(polygons: tuple[int, ...]) -> tuple[list[int], np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
    vt = VertexType(polygons)
    sizes = vt.sizes
    radius = 6.0
    last = None
    while radius <= 40.0:
        res = grow(vt, radius)
        last = res
        if not res.ok:
            raise GeometryError(
                f"vertex type {vt} does not extend to a tiling: {res.stats.reason}"
            )
        patch = res.patch
        assert patch is not None
        lattice = find_lattice(patch, list(sizes), radius)
        if lattice is not None:
            v1, v2 = lattice
            idx = unit_from_patch(patch, v1, v2)
            unit = patch.subset(idx)
            area = sum(abs(patch.prototiles[int(p)].area) for p in unit.prototile)
            if abs(area - abs(v1[0] * v2[1] - v1[1] * v2[0])) < 1e-6:
                info = {"radius": radius, "nodes": res.stats.nodes, "backtracks": res.stats.backtracks,
                        "seconds": res.stats.seconds}
                return list(unit.prototile), snap_noise(unit.transform), snap_noise(v1), snap_noise(v2), info
        radius *= 1.5
    raise GeometryError(
        f"vertex type {vt}: no translational unit found up to radius 40 ({last.stats.reason if last else ''})"
    )


def hand_of(sizes: tuple[int, ...], prototile: np.ndarray, transforms: np.ndarray, v1: np.ndarray) -> str:
    """'l' or 'r' for a tiling with hexagons whose lattice is turned against them (3^4.6):
    'l' when the shortest translation lies counter-clockwise of the nearest hexagon apothem
    (by an angle in (0, π/6)), 'r' when clockwise; '' for a tiling without that twist."""
    if 6 not in sizes:
        return ""
    i = int(np.flatnonzero(np.array([sizes[int(p)] for p in prototile]) == 6)[0])
    theta = math.atan2(transforms[i][1, 0], transforms[i][0, 0])
    # the first edge of regular_polygon(6) runs along +x, so its apothem points at -π/2
    apothem = theta - math.pi / 2
    phi = (math.atan2(v1[1], v1[0]) - apothem) % (math.pi / 3)
    if phi < 1e-6 or phi > math.pi / 3 - 1e-6 or abs(phi - math.pi / 6) < 1e-6:
        return ""
    return "l" if phi < math.pi / 6 else "r"


def _mirror(transforms: np.ndarray, v1: np.ndarray, v2: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The mirror image (in the x-axis) of a unit of regular polygons, as direct placements:
    a regular polygon is symmetric in the perpendicular bisector of its first edge (x = 1/2),
    so m @ T @ that reflection maps the prototile onto the mirrored tile."""
    m = Affine.scaling(1.0, -1.0)
    bisector = Affine.reflection(math.pi / 2, (0.5, 0.0))
    w1, w2 = canonical_basis(m[:2, :2] @ v1, m[:2, :2] @ v2)
    return snap_noise(m @ transforms @ bisector), snap_noise(w1), snap_noise(w2)


def _unit(vt: VertexType, hand: str, rebuild: bool = False) -> tuple[list[int], np.ndarray, np.ndarray, np.ndarray]:
    """The translational unit of (vt) in the requested hand, from the shipped data or built."""
    cached = None if rebuild else cached_data().get("archimedean", {}).get(str(vt))
    if cached is not None:
        protos = [vt.sizes.index(int(p)) for p, _ in cached["unit"]]
        transforms = np.array([np.vstack([np.reshape(t, (2, 3)), [0.0, 0.0, 1.0]]) for _, t in cached["unit"]])
        v1, v2 = np.array(cached["v1"], float), np.array(cached["v2"], float)
    else:
        protos, transforms, v1, v2, _ = _construct(vt.polygons)
    built = hand_of(vt.sizes, np.asarray(protos), transforms, v1)
    if hand and built and hand != built:
        transforms, v1, v2 = _mirror(transforms, v1, v2)
    return list(protos), transforms, v1, v2


def archimedean_tiling(vertex_type: VertexType | str, hand: str = "", *, rebuild: bool = False) -> ArchimedeanTiling:
    """The Archimedean tiling ``(vertex_type)`` as a PeriodicTiling, coloured by polygon size.

    The chiral 3^4.6 comes in two hands, ``hand='l'`` (default) or ``'r'`` (see
    :func:`hand_of`); other types take no hand. The unit comes from the shipped data
    (catalogue/archimedean/tilings.json, written by ``python -m
    tilekit.plugins.archimedean.generate``) unless ``rebuild`` asks for a fresh construction.
    """
    vt = parse_vertex_type(vertex_type) if isinstance(vertex_type, str) else vertex_type
    if vt.geometry != "euclidean":
        raise ParseError(
            f"vertex type {vt} is {vt.geometry} (angle sum {'<' if vt.excess < 0 else '>'} 2π), not a plane tiling"
        )
    hand = _check_hand(vt, hand)
    protos_idx, transforms, v1, v2 = _unit(vt, hand, rebuild)
    sizes = vt.sizes
    protos = regular_prototiles(sizes)
    colours = [size_colour(sizes[p]) for p in protos_idx]
    colouring = Colouring.by_aspect(colours)
    return ArchimedeanTiling(protos, protos_idx, transforms, v1, v2, colouring, vertex_type=vt, hand=hand,
                             name=archimedean_name(vt, hand))


def is_chiral(vt: VertexType) -> bool:
    """Whether (vt) has two mirror-image forms; decided from the built tiling (its unit is
    turned against its hexagons), not from a list."""
    if vt.geometry != "euclidean":
        return False
    protos, transforms, v1, _ = _unit(vt, "")
    return hand_of(vt.sizes, np.asarray(protos), transforms, v1) != ""


def _check_hand(vt: VertexType, hand: str) -> str:
    hand = (hand or "").lower()
    if hand not in ("", "l", "r"):
        raise ParseError(f"hand {hand!r} is not 'l' or 'r'")
    if is_chiral(vt):
        return hand or "l"
    if hand:
        raise ParseError(f"({vt}) is not chiral, so it takes no hand (got {hand!r})")
    return ""


_CACHE: dict[str, Any] | None = None


def cached_data() -> dict[str, Any]:
    """The shipped construction results (empty when the data file is absent)."""
    global _CACHE
    if _CACHE is None:
        path = catalogue_dir() / "archimedean" / "tilings.json"
        _CACHE = json.loads(path.read_text()) if path.exists() else {}
    return _CACHE


def archimedean_name(vt: VertexType, hand: str = "") -> str:
    """Catalogue name: the vertex type, with the hand for the chiral one (``3^4.6l``)."""
    return f"{vt}" + (hand if hand else "")


class ArchimedeanTiling(PeriodicTiling):
    """A PeriodicTiling that remembers its vertex type (and hand, for 3^4.6)."""

    def __init__(self, *args: Any, vertex_type: VertexType, hand: str = "", name: str = "", **kw: Any) -> None:
        super().__init__(*args, family="archimedean", name=name, **kw)
        self.vertex_type = vertex_type
        self.hand = hand

    def spec(self) -> dict[str, Any]:
        return {"kind": "archimedean", "vertex_type": str(self.vertex_type), "hand": self.hand}

    def describe(self) -> str:
        return (
            f"Every vertex: {self.vertex_type.dotted} (polygons met in order round it).\n"
            f"{unit_text(self, self.vertex_type.sizes)}\n"
            f"Dual: the Laves tiling [{self.vertex_type}]{self.hand}."
        )

    def properties(self) -> dict[str, Any]:
        props = super().properties()
        props.update(archimedean_properties(self))
        return props


class LavesTiling(PeriodicTiling):
    """The dual of an Archimedean tiling: monohedral, isohedral, named ``[vertex type]``."""

    def __init__(self, *args: Any, vertex_type: VertexType, hand: str = "", name: str = "", **kw: Any) -> None:
        super().__init__(*args, family="laves", name=name, **kw)
        self.vertex_type = vertex_type
        self.hand = hand

    def spec(self) -> dict[str, Any]:
        return {"kind": "laves", "vertex_type": str(self.vertex_type), "hand": self.hand}

    def describe(self) -> str:
        corners = ", ".join(f"{p}" for p in self.vertex_type.polygons)
        return (
            f"Topological type [{self.vertex_type}]: each tile has {len(self.vertex_type.polygons)} corners, "
            f"where {corners} tiles meet.\n"
            f"Prototile corners: {', '.join(format_vector(p) for p in self.prototiles[0].outline)}.\n"
            f"{len(self.unit_prototile)} tiles per translational unit; dual of ({self.vertex_type}){self.hand}."
        )

    def properties(self) -> dict[str, Any]:
        props = super().properties()
        props.update(laves_properties(self))
        return props


def _match_polygon(base: np.ndarray, poly: np.ndarray, tol: float = 1e-6) -> np.ndarray | None:
    """A rigid motion (direct first, then with reflection) mapping outline ``base`` onto
    ``poly`` as point sequences (cyclic shift allowed), or None."""
    k = len(base)
    if len(poly) != k:
        return None
    for mirror in (False, True):
        src = base if not mirror else (base * np.array([1.0, -1.0]))[::-1]
        pre = np.eye(3) if not mirror else Affine.scaling(1.0, -1.0)
        for s in range(k):
            tgt = np.roll(poly, -s, axis=0)
            m = Affine.segment_map(tgt[0], tgt[1], src[0], src[1])
            if Affine.similarity_scale(m) is None or abs(Affine.similarity_scale(m) - 1) > 1e-6:
                continue
            if np.allclose(Affine.apply(m, src), tgt, atol=tol):
                return m @ pre
    return None


@cache
def _laves(
    polygons: tuple[int, ...], hand: str, rebuild: bool = False
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    key = str(VertexType(polygons)) + hand
    cached = None if rebuild else cached_data().get("laves", {}).get(key)
    if cached is not None:
        transforms = np.array([np.vstack([np.reshape(t, (2, 3)), [0.0, 0.0, 1.0]]) for t in cached["unit"]])
        return (np.array(cached["outline"], float), transforms, np.array(cached["v1"], float),
                np.array(cached["v2"], float))
    arch = archimedean_tiling(VertexType(polygons), hand, rebuild=rebuild)
    v1, v2 = arch.v1, arch.v2
    span = 2.5 * max(np.hypot(*v1), np.hypot(*v2)) + 3
    patch = arch.patch((-span, -span, span, span))
    centres = patch.centres()
    polys = patch.polygons()
    stars = vertex_stars(polys)
    basis = np.column_stack([v1, v2])
    inv = np.linalg.inv(basis)
    offset = np.array([0.0123, 0.0171])
    tiles = []
    for v in sorted(range(len(stars)), key=lambda v: stars.keys[v]):
        p = stars.points[v]
        lst = []
        for c in stars.members(v):
            t = int(stars.tile[c])
            x, y = polys[t][int(stars.index[c])]  # the corner's own coordinates decide ±π ties
            lst.append((math.atan2(centres[t][1] - y, centres[t][0] - x), t))
        ab = (p - offset) @ inv.T + 0.5
        if not np.all((ab >= 0) & (ab < 1)):
            continue
        angle_sum = sum(polygon_angle(len(polys[t])) for _, t in lst)
        if abs(angle_sum - TWO_PI) > 1e-6:
            raise GeometryError(f"({arch.vertex_type}): vertex near the unit is not surrounded; enlarge the patch")
        ring = np.array([centres[t] for _, t in sorted(lst)])
        tiles.append((p, ring))
    if len(tiles) == 0:
        raise GeometryError(f"({arch.vertex_type}): no vertex in the fundamental parallelogram")
    p0, ring0 = tiles[0]
    outline = ring0 - p0  # prototile: the dual tile of the first vertex, that vertex at the origin
    transforms = []
    for _p, ring in tiles:
        m = _match_polygon(outline, ring)
        if m is None:
            raise GeometryError(f"[{arch.vertex_type}]: dual tiles are not congruent")
        transforms.append(m)
    return snap_noise(outline), snap_noise(np.array(transforms)), v1, v2


def laves_tiling(vertex_type: VertexType | str, hand: str = "", *, rebuild: bool = False) -> LavesTiling:
    """The Laves tiling ``[vertex_type]``: the geometric dual of the Archimedean tiling
    (``hand`` as for :func:`archimedean_tiling`)."""
    vt = parse_vertex_type(vertex_type) if isinstance(vertex_type, str) else vertex_type
    if vt.geometry != "euclidean":
        raise ParseError(f"vertex type {vt} is {vt.geometry}, so it has no plane Laves tiling")
    hand = _check_hand(vt, hand)
    outline, transforms, v1, v2 = _laves(vt.polygons, hand, rebuild)
    proto = Prototile(outline, name=f"[{vt}]")
    m = len(transforms)
    # colour by aspect class: tiles whose placements differ by a translation share a colour
    classes: list[np.ndarray] = []
    colours = []
    for tr in transforms:
        lin = tr[:2, :2]
        for i, c in enumerate(classes):
            if np.allclose(c, lin, atol=1e-6):
                colours.append(i)
                break
        else:
            classes.append(lin)
            colours.append(len(classes) - 1)
    return LavesTiling([proto], [0] * m, transforms, v1, v2, Colouring.by_aspect(colours),
                       vertex_type=vt, hand=hand, name=f"[{vt}]" + hand)


def laves_prototile(vertex_type: VertexType | str) -> Prototile:
    """The prototile of the Laves tiling [vertex_type] (a default shape for its topological type)."""
    return laves_tiling(vertex_type).prototiles[0]


def archimedean_properties(t: ArchimedeanTiling) -> dict[str, Any]:
    vt = t.vertex_type
    return {
        "vertex_type": str(vt),
        "species": vt.species_name,
        "sides": sorted(set(vt.sizes)),
        "chiral": bool(t.hand),
        "chirality": t.hand or "achiral",
        "dual": f"[{vt}]" + t.hand,
        "edge_to_edge": True,
        "k_hedral": len(vt.sizes),
    }


def laves_properties(t: LavesTiling) -> dict[str, Any]:
    vt = t.vertex_type
    return {
        "vertex_type": str(vt),
        "topology": f"[{vt}]",
        "species": vt.species_name,
        "chiral": bool(t.hand),
        "chirality": t.hand or "achiral",
        "dual": f"{vt}" + t.hand,
        "edge_to_edge": True,
        "k_hedral": 1,
        "sides": [len(vt.polygons)],
    }


def orbit_count(points: np.ndarray, tiling: PeriodicTiling) -> int:
    """How many orbits the symmetry group of ``tiling`` has on ``points`` (one per point of a
    translational unit, given modulo the lattice v1, v2): 1 means transitive."""

    group = symmetries(tiling)
    basis = np.column_stack([tiling.v1, tiling.v2])
    inv = np.linalg.inv(basis)
    frac = np.mod(points @ inv.T, 1.0)
    parent = list(range(len(points)))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    ops = [op.matrix for op in group.operations] + [Affine.translation(*w) for w in group.lattice]
    for m in ops:
        img = np.mod(Affine.apply(m, points) @ inv.T, 1.0)
        d = np.abs(img[:, None, :] - frac[None, :, :])
        d = np.minimum(d, 1.0 - d).max(axis=-1)
        j = np.argmin(d, axis=1)
        if np.any(d[np.arange(len(points)), j] > 1e-6):
            raise GeometryError("a symmetry does not map the unit's points onto themselves")
        for i, jj in enumerate(j):
            a, b = find(i), find(int(jj))
            if a != b:
                parent[max(a, b)] = min(a, b)
    return len({find(i) for i in range(len(points))})


def unit_vertices(tiling: PeriodicTiling) -> np.ndarray:
    """One point per vertex of the tiling modulo its lattice (tile corners, deduplicated)."""
    basis = np.column_stack([tiling.v1, tiling.v2])
    inv = np.linalg.inv(basis)
    pts = np.concatenate(tiling.unit().polygons())
    frac = np.mod(pts @ inv.T + 1e-9, 1.0)
    keep: list[int] = []
    for i, f in enumerate(frac):
        if not any(np.all(np.minimum(np.abs(frac[k] - f), 1 - np.abs(frac[k] - f)) < 1e-6) for k in keep):
            keep.append(i)
    return pts[keep]


def transitivity(tiling: PeriodicTiling) -> dict[str, int]:
    """Orbits of the symmetry group on tiles (k-isohedral) and on vertices (k-isogonal)."""
    return {
        "k_isohedral": orbit_count(tiling.unit().centres(), tiling),
        "k_isogonal": orbit_count(unit_vertices(tiling), tiling),
    }
