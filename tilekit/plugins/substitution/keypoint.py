"""Keypoint substitutions: supertiles built from rigid copies placed by matching keypoints.

The Spectre's substitution (arXiv:2305.17743) is combinatorial, not a similarity: a
level-(n+1) supertile is a few level-n supertiles moved by rigid motions, chosen so that a
keypoint of each copy lands on a keypoint of the previous one. The motions therefore differ
from level to level (they are computed from that level's keypoints), but within a level they
are shared by all labels, so generation stays a batched product of (k, 3, 3) stacks: the
same array engine as for similarity systems, with per-level rule matrices.
"""

from __future__ import annotations

import math
from abc import abstractmethod
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
import shapely

from tilekit.errors import ParameterError, ParseError
from tilekit.geometry import Affine
from tilekit.limits import STREAM_CHUNK_TILES, check_chunk_tiles
from tilekit.plugins.substitution.expr import constants_with, evaluate
from tilekit.plugins.substitution.formats import read_system_data
from tilekit.plugins.substitution.levels import (
    Centres,
    Cull,
    Expand,
    expand_base,
    expand_by_label,
    meets_discs,
    placed_points,
    substitute_in_chunks,
    substitute_levels,
)
from tilekit.plugins.substitution.rules import MatrixFacts, Rule
from tilekit.tiling import Prototile

REFLECT_Y = np.diag([-1.0, 1.0, 1.0])

#: The tiles of a level-0 supertile stream: (prototile, transform, colour) arrays.
Tiles = tuple[np.ndarray, np.ndarray, np.ndarray]


@dataclass
class Generation:
    """How one monotile system substitutes a seed: the level-``depth`` seed (labels, maps),
    the per-level expansion and cull, where a placed level-n supertile is (its bounding
    disc's centre), and ``finish``, which places the tiles of level-0 supertiles."""

    label: np.ndarray
    maps: np.ndarray
    expand: Expand
    cull: Cull | None
    centres: Centres
    finish: Callable[[np.ndarray, np.ndarray], Tiles]


class MonotileSystem(MatrixFacts):
    """What the monotile systems (spectre, hat) share: one tile shape, carried by supertiles
    whose geometry is recomputed per level, with ``base[label]`` the tiles of a level-0 label."""

    tile: Prototile
    labels: Sequence[str]
    base: Sequence[np.ndarray]
    name: str
    #: per level, the bounding discs :meth:`bounds` computed (a field of each system)
    _bounds: list[tuple[np.ndarray, np.ndarray]]
    #: ``generate`` without a region refuses a supertile of more tiles than this (ParameterError)
    max_tiles: ClassVar[float] = math.inf

    @property
    def n(self) -> int:
        return len(self.labels)

    @property
    def tiles(self) -> list[Prototile]:
        return [self.tile]

    @property
    def prototiles(self) -> list[Prototile]:
        return [self.tile]

    @property
    def output_prototiles(self) -> list[Prototile]:
        return [self.tile]

    @property
    def scale(self) -> float:
        """Linear growth per level: the square root of the Perron-Frobenius eigenvalue."""
        return math.sqrt(self.perron_frobenius()[0])

    def tiles_per_label(self) -> np.ndarray:
        return np.array([len(b) for b in self.base], dtype=np.int64)

    def leaf_tiles(self) -> np.ndarray:
        return self.tiles_per_label().astype(float)

    def tile_counts(self, generations: int, start: int | None = None) -> list[int]:
        """Number of actual tiles in a level-n supertile, n = 0..generations."""
        per_label = self.tiles_per_label()
        return [int(np.dot(c, per_label)) for c in self.counts(generations, start)]

    def rep_tile(self) -> None:
        return None

    @abstractmethod
    def generation(self, depth: int, seed_transform: np.ndarray | None, seed_label: int | None,
                   box: tuple[float, float, float, float] | None) -> Generation:
        """How this system substitutes a level-``depth`` seed (see :class:`Generation`)."""

    @abstractmethod
    def rules_at(self, n: int) -> list[Rule]:
        """Per label, the children (label indices) and rigid maps building level n from n-1."""

    def placed_base(self) -> Sequence[np.ndarray]:
        """Per label, the Cartesian placements (m, 3, 3) of a level-0 supertile's tiles."""
        return self.base

    def bounds(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """Per label, a centre and radius bounding its level-n supertile's tiles (in its own
        frame): the tiles' points at level 0, then each level's children's discs, kept."""
        kept = self._bounds
        while len(kept) <= n:
            centres, radii = [], []
            if not kept:
                for maps in self.placed_base():
                    pts = Affine.apply(maps, self.tile.outline).reshape(-1, 2)
                    c = pts.mean(axis=0)
                    centres.append(c)
                    radii.append(float(np.linalg.norm(pts - c, axis=1).max()))
            else:
                pc, pr = kept[-1]
                for rule in self.rules_at(len(kept)):
                    img = placed_points(rule.children, rule.matrices, pc)
                    c = img.mean(axis=0)
                    centres.append(c)
                    radii.append(float((np.linalg.norm(img - c, axis=1) + pr[rule.children]).max()))
            kept.append((np.array(centres), np.array(radii)))
        return kept[n]

    def rigid_generation(self, seed: np.ndarray, seed_label: int | None, box: tuple[float, float, float, float] | None,
                         colours: Sequence[np.ndarray]) -> Generation:
        """The :class:`Generation` of a system whose rules are Cartesian rigid maps
        (``rules_at``): the seed placed by ``seed`` (3, 3), each level one batched expansion,
        culled by :meth:`bounds`, tiles placed by ``base`` and coloured ``colours[label]``."""
        label = np.array([self.seed if seed_label is None else seed_label], dtype=np.int64)

        def expand(label: np.ndarray, maps: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
            rules = self.rules_at(n)
            return expand_by_label(label, maps, [r.children for r in rules], [r.matrices for r in rules])

        def cull(label: np.ndarray, maps: np.ndarray, n: int) -> np.ndarray:
            return meets_discs(label, maps, self.bounds(n), box)

        def centres(label: np.ndarray, maps: np.ndarray, n: int) -> np.ndarray:
            return placed_points(label, maps, self.bounds(n)[0])

        def finish(label: np.ndarray, maps: np.ndarray) -> Tiles:
            transform, colour = expand_base(label, maps, self.base, colours)
            return np.zeros(len(transform), dtype=np.int64), transform.astype(float, copy=False), colour

        return Generation(label, np.asarray(seed, dtype=float).reshape(1, 3, 3), expand,
                          cull if box is not None else None, centres, finish)

    def generate(
        self,
        depth: int,
        seed_transform: np.ndarray | None = None,
        seed_label: int | None = None,
        box: tuple[float, float, float, float] | None = None,
    ) -> Tiles:
        """Tiles of a level-``depth`` supertile: (prototile, transform, colour) arrays; with a
        ``box``, supertiles whose bounding discs miss it are dropped level by level."""
        self.refuse_whole(depth, seed_label, box)
        g = self.generation(depth, seed_transform, seed_label, box)
        return g.finish(*substitute_levels(g.label, g.maps, depth, g.expand, g.cull))

    def refuse_whole(self, depth: int, seed_label: int | None, box: Any) -> None:
        """ParameterError when a whole (``box`` None) level-``depth`` supertile has more than
        ``max_tiles`` tiles (``generate_chunks`` streams them)."""
        if box is None and math.isfinite(self.max_tiles):
            count = self.tile_counts(depth, self.seed if seed_label is None else int(seed_label))[-1]
            if count > self.max_tiles:
                raise ParameterError(f"{self.name} depth {depth} would make {count} {self.tile.name}s; the limit "
                                     f"is {self.max_tiles} (give a smaller depth or a region)")

    def generate_grouped(
        self,
        depth: int,
        level: int,
        seed_transform: np.ndarray | None = None,
        seed_label: int | None = None,
        box: tuple[float, float, float, float] | None = None,
    ) -> tuple[Tiles, np.ndarray, np.ndarray]:
        """:meth:`generate`'s tiles, in the same order, and for each tile the index of the
        level-``level`` supertile it lies in (levels above ``depth``: the seed) and that
        supertile's label index. The level-``level`` supertiles are substituted like the
        others, each tile's supertile index repeated for its children, so the cost is
        :meth:`generate`'s plus an integer array."""
        self.refuse_whole(depth, seed_label, box)
        g = self.generation(depth, seed_transform, seed_label, box)
        top = max(0, min(int(level), depth))
        label, maps = substitute_levels(g.label, g.maps, depth, g.expand, g.cull, stop=top)
        group = np.arange(len(label))
        group_label = label.copy()
        kids = np.array([len(c) for c in self.child_labels()], dtype=np.int64)
        for n in range(top, 0, -1):
            group = np.repeat(group, kids[label])
            label, maps = g.expand(label, maps, n)
            if g.cull is not None:
                keep = g.cull(label, maps, n - 1)
                label, maps, group = label[keep], maps[keep], group[keep]
        group = np.repeat(group, self.tiles_per_label()[label])
        return g.finish(label, maps), group, group_label

    def generate_chunks(
        self,
        depth: int,
        seed_transform: np.ndarray | None = None,
        seed_label: int | None = None,
        box: tuple[float, float, float, float] | None = None,
        chunk_tiles: int = STREAM_CHUNK_TILES,
    ) -> Iterator[Tiles]:
        """:meth:`generate` in chunks of at most ``chunk_tiles`` tiles (more only when one
        level-0 supertile has more), whose union is ``generate``'s tiles; never the whole
        supertile at once (:func:`levels.substitute_in_chunks`)."""
        check_chunk_tiles(chunk_tiles)
        g = self.generation(depth, seed_transform, seed_label, box)
        for label, maps in substitute_in_chunks(g.label, g.maps, depth, g.expand, g.cull, self.descendants,
                                                g.centres, chunk_tiles):
            yield g.finish(label, maps)


@dataclass
class KeypointSystem(MonotileSystem):
    """A keypoint substitution (see the module docstring and catalogue/substitution/spectre.toml)."""

    name: str
    title: str
    labels: list[str]
    tile: Prototile
    quad: np.ndarray  # (4, 2) level-0 keypoints
    base: list[np.ndarray]  # per label: (m, 3, 3) level-0 tile placements
    steps: list[tuple[float, int, int]]
    reflect: bool
    next_quad: list[tuple[int, int]]
    rules: list[np.ndarray]  # per label: slot -> child label index, -1 for an empty slot
    seed: int = 0
    facts: dict[str, Any] = field(default_factory=dict)
    source: str = "<data>"
    data: dict[str, Any] = field(default_factory=dict)
    kind: str = "keypoint"
    _levels: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    _bounds: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)

    def child_labels(self) -> list[np.ndarray]:
        return [slots[slots >= 0] for slots in self.rules]

    # ------------------------------------------------------------------ levels
    def level(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """The slot transforms (8, 3, 3) that build level-n supertiles from level n-1 ones,
        and the level-n quad (4, 2); n >= 1."""
        if n < 1:
            raise ValueError("levels start at 1")
        while len(self._levels) < n:
            quad = self.quad if not self._levels else self._levels[-1][1]
            self._levels.append(self._place(quad))
        return self._levels[n - 1]

    def _place(self, quad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        transforms = [np.eye(3)]
        total = 0.0
        rot = np.eye(3)
        for angle, frm, to in self.steps:
            total += angle
            if angle:
                rot = Affine.rotation(math.radians(total))
            prev = Affine.apply(transforms[-1], quad[frm])
            here = Affine.apply(rot, quad[to])
            transforms.append(Affine.translation(*(prev - here)) @ rot)
        ts = np.array(transforms)
        if self.reflect:
            ts = REFLECT_Y[None] @ ts
        new_quad = np.array([Affine.apply(ts[slot], quad[k]) for slot, k in self.next_quad])
        return ts, new_quad

    def rules_at(self, n: int) -> list[Rule]:
        """Per label, the children (label indices) and rigid maps building level n from n-1."""
        ts, _ = self.level(n)
        out = []
        for slots in self.rules:
            used = np.flatnonzero(slots >= 0)
            out.append(Rule(slots[used], ts[used]))
        return out

    # ------------------------------------------------------------------ generation
    def generation(self, depth: int, seed_transform: np.ndarray | None, seed_label: int | None,
                   box: tuple[float, float, float, float] | None) -> Generation:
        """Colour 1 marks the Mystic's turned spectre, 0 every other one. Odd depths get one
        extra reflection so that every spectre is unreflected."""
        t0 = np.eye(3) if seed_transform is None else np.asarray(seed_transform, dtype=float)
        if depth % 2 == 1 and self.reflect:
            t0 = t0 @ REFLECT_Y
        colours = [(np.arange(len(p)) > 0).astype(np.int64) for p in self.base]
        return self.rigid_generation(t0, seed_label, box, colours)


# ---------------------------------------------------------------------- loading


def keypoint_system_from_data(data: Mapping[str, Any], source: str = "<data>") -> KeypointSystem:
    """Build and check a keypoint system from parsed TOML (errors name the file and part):
    the shape of every field is checked by the keypoint schema (:mod:`.formats`), then labels
    are resolved and the supertiles checked for overlaps."""
    where = f"substitution system {source}"
    raw = data
    _, data = read_system_data(data, source, "keypoint")

    def fail(msg: str) -> ParseError:
        return ParseError(f"{where}: {msg}")

    try:
        env = constants_with(data["constants"])
    except ParseError as exc:
        raise fail(str(exc)) from None

    def num(v: Any, ctx: str) -> float:
        try:
            return evaluate(v, env)
        except ParseError as exc:
            raise fail(f"{ctx}: {exc}") from None

    labels = data["labels"]
    index = {nm: i for i, nm in enumerate(labels)}
    tile_data = data["tile"]
    outline = np.array([[num(c, "tile outline") for c in p] for p in tile_data["outline"]])
    try:
        tile = Prototile(outline, name=tile_data["name"])
    except Exception as exc:  # GeometryError
        raise fail(f"[tile]: {exc}") from None
    quad_idx = tile_data["quad"]
    if max(quad_idx) >= len(outline):
        raise fail(f"[tile] quad must be 4 vertex indices in 0..{len(outline) - 1}")
    base = [_base_maps(data["base"].get(nm, [{"rotate": 0, "translate": [0, 0]}]), nm, num) for nm in labels]
    placement = data["placement"]
    steps = []
    for k, st in enumerate(placement["steps"]):
        if not all(_index_in(i, 4) for i in st[1:]):
            raise fail(f"[placement] step #{k + 1} must be [angle, from keypoint 0..3, to keypoint 0..3]")
        steps.append((num(st[0], f"step #{k + 1}"), int(st[1]), int(st[2])))
    slots = len(steps) + 1
    next_quad = placement["next_quad"]
    if not all(a < slots and b < 4 for a, b in next_quad):
        raise fail(f"[placement] next_quad must be four [slot 0..{slots - 1}, keypoint 0..3] pairs")
    rules = [_slots(data["rules"].get(nm), nm, slots, index, fail) for nm in labels]
    seed = index.get(str(data.get("seed", labels[0])))
    if seed is None:
        raise fail(f"seed {data.get('seed')!r} is not a label")
    system = KeypointSystem(
        name=str(data.get("name", source)),
        title=str(data.get("title", data.get("name", source))),
        labels=list(labels),
        tile=tile,
        quad=outline[quad_idx],
        base=base,
        steps=steps,
        reflect=placement["reflect"],
        next_quad=[(int(a), int(b)) for a, b in next_quad],
        rules=rules,
        seed=seed,
        facts=dict(data.get("properties", {})),
        source=source,
        data=dict(raw),
    )
    check_keypoint_system(system)
    return system


def _base_maps(entries: list[Mapping[str, Any]], nm: str, num: Any) -> np.ndarray:
    """A label's level-0 tiles: rotation (degrees) about the origin, then translation."""
    mats = []
    for e in entries:
        ang = math.radians(num(e["rotate"], f"[base] {nm} rotate"))
        tx, ty = (num(v, f"[base] {nm} translate") for v in e["translate"])
        mats.append(Affine.translation(tx, ty) @ Affine.rotation(ang))
    return np.array(mats)


def _slots(row: Any, nm: str, slots: int, index: Mapping[str, int], fail: Any) -> np.ndarray:
    """A rule's row of slot labels as label indices (-1: an empty slot)."""
    if row is None or len(row) != slots:
        raise fail(f"rule for {nm!r} must list {slots} slots")
    kids = []
    for s in row:
        if s != "" and s not in index:
            raise fail(f"rule for {nm!r}: unknown label {s!r}; known: {', '.join(index)}")
        kids.append(index[s] if s else -1)
    return np.array(kids, dtype=np.int64)


def _index_in(value: Any, n: int) -> bool:
    """Whether ``value`` is an int (not a bool) in 0..n-1."""
    return isinstance(value, int) and not isinstance(value, bool) and 0 <= value < n


def check_keypoint_system(system: KeypointSystem, levels: int = 2) -> None:
    """Every label's supertile, for the first ``levels`` levels, is a set of non-overlapping
    tiles (the placement data is wrong otherwise)."""
    tile = system.tile.outline
    for n in range(0, levels + 1):
        for j, nm in enumerate(system.labels):
            _, tr, _ = system.generate(n, seed_label=j)
            polys = shapely.polygons(Affine.apply(tr, tile))
            total = float(shapely.area(polys).sum())
            grid = 1e-9
            union = shapely.union_all(polys, grid_size=grid).area
            if total - union > 1e-6 * float(shapely.area(polys[0])):
                raise ParseError(
                    f"substitution system {system.source}: level-{n} supertile {nm!r} has overlapping tiles"
                )
