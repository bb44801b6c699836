"""SubstitutionTiling: a Tiling whose patches come from a substitution system (§6.1, §7.4).

``patch(region)`` picks the depth that covers the region: the seed prototile, scaled by
s**d about its largest inscribed disc, must hold the region's circumscribed disc; for an
exact system (a composition) its d-th substitution then covers the region, and only tiles
whose inflated bounds meet the region are expanded. ``configure(depth=N)`` fixes the depth
instead (the seed scaled by s**N at the origin) and ``patch`` returns the tiles meeting the
region.
"""

from __future__ import annotations

import math
import numbers
import weakref
from collections.abc import Iterator, Mapping, Sequence
from functools import partial
from typing import Any

import numpy as np
import shapely
from shapely.geometry.base import BaseGeometry
from shapely.geometry.polygon import orient

from tilekit import export
from tilekit.errors import GeometryError, NotFoundError, ParameterError, ParseError
from tilekit.geometry import Affine, as_region
from tilekit.limits import (  # MAX_DEPTH: the depth range; the tile estimate is the real bound
    GENERATION_BYTES_PER_TILE,
    MAX_DEPTH,
    MAX_TILES,
    STREAM_CHUNK_TILES,
    check_chunk_tiles,
    refuse_over_memory,
)
from tilekit.plugins.substitution import continuum, engine, shapes
from tilekit.plugins.substitution import quasivertex as qv
from tilekit.plugins.substitution.builtin import builtin_systems
from tilekit.plugins.substitution.expr import evaluate
from tilekit.plugins.substitution.hat import HatSystem
from tilekit.plugins.substitution.shapes import (
    canonical_transforms,
    edge_classes,
    halves_mirror,
    parse_edge_shape,
)
from tilekit.plugins.substitution.system import SubstitutionSystem, load_data
from tilekit.polygon import corner_count, edge_to_edge, inscribed_disc
from tilekit.render import patch_to_svg
from tilekit.schema import Field, check, shown
from tilekit.tiling import Patch, Prototile, Tiling, region_tile_estimate


class SubstitutionTiling(Tiling):
    """A substitution tiling: a validated system, an optional fixed depth, and options."""

    family = "substitution"

    def __init__(
        self,
        system: SubstitutionSystem,
        depth: int | None = None,
        seed: str | None = None,
        spec_source: Mapping[str, Any] | None = None,
        params: Sequence[float] | None = None,
        edges: Sequence[str] | None = None,
        quasivertex: Mapping[str, float] | None = None,
    ) -> None:
        self.system = system
        self.name = system.name
        self.depth = depth
        if depth is not None and not 0 <= depth <= MAX_DEPTH:
            raise ParameterError(f"depth {depth} is out of range 0..{MAX_DEPTH}")
        names = [p.name for p in system.prototiles]
        if seed is not None and seed not in names:
            raise ParameterError(f"seed {seed!r} is not a prototile of {system.name}; valid: {', '.join(names)}")
        self.seed = seed
        self._spec_source = dict(spec_source) if spec_source is not None else {"system": system.name}
        self.params = [float(v) for v in params] if params is not None else None
        if self.params is not None and not all(math.isfinite(v) and abs(v) <= 1.0 for v in self.params):
            raise ParameterError(
                f"params {self.params} are tooth heights of unit edges and must be finite numbers in -1..1"
            )
        self.edges = list(edges) if edges is not None else None
        self.quasivertex = dict(quasivertex) if quasivertex is not None else None
        self._shaped: list[Prototile] | None = None
        self._cluster: tuple[np.ndarray, np.ndarray] | None = None
        self._classes: Any = None
        self._mirrors: Any = None
        if self.quasivertex is not None:
            if self.params is not None:
                raise ParameterError(
                    "params (tooth heights) and quasivertex parameters r1, theta1, r2, theta2 "
                    "cannot be combined; give edge shapes for the labels a..h with edges instead"
                )
            self._shaped = self._quasivertex_tiles()
        elif self.params is not None or self.edges is not None:
            self._shaped = self._shape_tiles()

    def _quasivertex_tiles(self) -> list[Prototile]:
        """The rhombs deformed by Figure 6.13's quasivertices, with Figure 6.14's edge shapes."""
        params = qv.QuasivertexParams.from_options(self.quasivertex or {})
        self.quasivertex = params.as_dict()
        shapes = {}
        for text in self.edges or []:
            name, pts = parse_edge_shape(text)
            if name in shapes:
                raise ParameterError(f"edge shape {name!r} is given twice")
            shapes[name] = pts
        tiles = qv.deformed_tiles(self.system.tiles, self.name, params, shapes)
        self._mirrors = tuple(halves_mirror(self.system))
        return tiles

    def _shape_tiles(self) -> list[Prototile]:
        """Shaped whole tiles from params (tooth heights) and/or named edge shapes (§6.3)."""
        if self.system.output_prototiles is None:
            raise ParameterError(
                f"{self.name} has no assembled whole tiles; edge shapes apply to penrose-p2, "
                "penrose-p3 and other systems with an [assemble] table"
            )
        try:
            classes = _edge_classes(self.system)
        except GeometryError as exc:
            raise ParameterError(f"{self.name}: edges cannot carry interlocking shapes ({exc})") from None
        letters = "abcdefghijklmnopqrstuvwxyz"[: classes.count]
        heights = list(self.params or [])
        if len(heights) > classes.count:
            raise ParameterError(
                f"{self.name} has {classes.count} free edge shape(s) ({', '.join(letters)}); "
                f"{len(heights)} params given"
            )
        defaults = [0.1, -0.08, 0.06, -0.05]
        heights += [defaults[i % 4] for i in range(len(heights), classes.count)]
        shape_list = [shapes.default_shape(h) for h in heights]
        for text in self.edges or []:
            name, pts = shapes.parse_edge_shape(text)
            if name not in letters:
                raise ParameterError(
                    f"edge shape {name!r} is not one of {self.name}'s edge classes {', '.join(letters)}"
                )
            shape_list[letters.index(name)] = pts
        self._classes = classes
        self._mirrors = classes.mirror
        return shapes.shaped_tiles(self.system.tiles, classes, shape_list)

    # ------------------------------------------------------------------ Tiling API
    @property
    def prototiles(self) -> list[Prototile]:
        return self._shaped if self._shaped is not None else self.system.tiles

    def _seed_index(self) -> int:
        if self.seed is not None:
            return [p.name for p in self.system.prototiles].index(self.seed)
        return self.system.seed

    def seed_placement(self, region: BaseGeometry, depth: int | None = None) -> tuple[int, np.ndarray, int]:
        """(seed prototile, seed transform, depth) whose substitution covers ``region``: the
        prototile with the largest inscribed disc, scaled by s**d about that disc's centre
        placed on the region's centre, d the least depth whose disc holds the region (or the
        given ``depth``, when it is enough)."""
        x0, y0, x1, y1 = region.bounds
        centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
        need = math.hypot(x1 - x0, y1 - y0) / 2
        # the seed with the largest inscribed disc relative to its tiles needs the fewest levels
        best: tuple[float, int, np.ndarray] | None = None
        candidates = [self._seed_index()] if self.seed is not None else range(self.system.n)
        for i in candidates:
            c, r = inscribed_disc(self.system.prototiles[i].outline)
            if best is None or r > best[0]:
                best = (r, i, c)
        assert best is not None
        r, i, c = best
        d = max(0, math.ceil(math.log(max(need, 1e-12) / r) / math.log(self.system.scale) - 1e-12))
        if depth is not None:
            if d > depth:
                raise ParameterError(
                    f"depth {depth} covers at most a disc of radius {r * self.system.scale**depth:.4g} "
                    f"(or the depth-{depth} patch, box {_rounded(self.default_region().bounds)}); region "
                    f"{_rounded(region.bounds)} needs depth {d}: give --depth {d} or more, or leave out --depth"
                )
            d = depth
        if d > MAX_DEPTH:
            raise ParameterError(f"region {region.bounds} needs depth {d}; the limit is {MAX_DEPTH}")
        lam = self.system.scale**d
        t = Affine.translation(*centre) @ Affine.scaling(lam) @ Affine.translation(-c[0], -c[1])
        return i, t, d

    # ------------------------------------------------------------------ the depth-N patch
    def seed_cluster(self) -> tuple[np.ndarray, np.ndarray]:
        """The depth-0 patch as rule prototiles and transforms: ``depth=N`` substitutes each
        of them N times (scaled by s**N about the origin).

        For a system of whole tiles it is the seed tile. For a system assembled from halves
        (exercise 6.10) it is *whole* tiles, never a lone half: the seed's whole tile, and,
        when that tile has a vertex with equal edges and angle 360/n degrees, n copies of it
        turned about that vertex (the sun or star of Penrose's P2 and P3, the eight-rhomb star
        of Ammann-Beenker). With ``seed=NAME`` it is that one prototile.
        """
        if self._cluster is not None:
            return self._cluster
        s = self.system
        seed = self._seed_index()
        one = (np.array([seed], dtype=np.int64), np.eye(3)[None])
        if s.output_prototiles is None or self.seed is not None:
            self._cluster = one
            return one
        halves = _whole_tile_halves(s, seed)
        whole = shapely.union_all([shapely.Polygon(Affine.apply(h, s.prototiles[seed].outline)) for h in halves],
                                  grid_size=1e-9)
        maps = list(halves)
        if isinstance(whole, shapely.Polygon):
            whole = orient(whole.simplify(0), 1.0)  # counter-clockwise, no collinear points
            turn = _star_vertex(np.asarray(whole.exterior.coords)[:-1])
            if turn is not None:
                v, n = turn
                rots = [Affine.translation(*v) @ Affine.rotation(2 * math.pi * k / n) @ Affine.translation(-v[0], -v[1])
                        for k in range(n)]
                # the star's centre at the origin, so that depth N scales it about its centre
                centre = Affine.translation(-v[0], -v[1])
                maps = [centre @ r @ h for r in rots for h in halves]
        self._cluster = (np.full(len(maps), seed, dtype=np.int64), np.array(maps))
        return self._cluster

    def _cluster_polygon(self, depth: int) -> BaseGeometry:
        proto, maps = self.seed_cluster()
        lam = Affine.scaling(self.system.scale**depth)
        return shapely.union_all(
            [shapely.Polygon(Affine.apply(lam @ m, self.system.prototiles[p].outline)) for p, m in zip(proto, maps)],
            grid_size=1e-9,
        )

    def _plan(self, reg: BaseGeometry | None) -> tuple[np.ndarray, np.ndarray, int, Any]:
        """What to substitute for ``raw(reg)``: the seeds' prototiles and maps (k,) and
        (k, 3, 3), the depth, and the box whose tiles are kept (None: every tile)."""
        if reg is None and self.depth is None:
            raise ParameterError("a region or a fixed depth is needed")
        box = tuple(reg.bounds) if reg is not None else None
        if box is not None and self.system.pairing_edge is not None:
            # a half whose partner lies outside the generated set is dropped: add a margin
            margin = 2 * max(float(np.ptp(p.outline, axis=0).max()) for p in self.system.tiles)
            box = (box[0] - margin, box[1] - margin, box[2] + margin, box[3] + margin)
        if self.depth is None:
            assert reg is not None and box is not None
            seed, t, d = self.seed_placement(shapely.box(*box))
            members = [(seed, t)]
        else:
            d = int(self.depth)
            lam = Affine.scaling(self.system.scale**d)
            members = [(int(p), lam @ m) for p, m in zip(*self.seed_cluster())]
            if reg is not None and not self._cluster_polygon(d).buffer(1e-9).contains(reg):
                # a depth with a region covers the region: move the seed onto it
                seed, t, d = self.seed_placement(shapely.box(*box) if box else reg, depth=d)
                members = [(seed, t)]
        protos = np.array([p for p, _ in members], dtype=np.int64)
        return protos, np.array([t for _, t in members]), d, box

    def raw(self, region: Any = None) -> tuple[np.ndarray, np.ndarray]:
        """The (prototile, transform) arrays before clipping (whole tiles after assembly)."""
        protos, maps, d, box = self._plan(as_region(region) if region is not None else None)
        self._refuse_unaffordable(protos, d, box)
        out = [engine.generate(self.system, d, t, int(p), box=box) for p, t in zip(protos, maps)]
        return engine.assemble(self.system, np.concatenate([o[0] for o in out]), np.concatenate([o[1] for o in out]))

    def _refuse_unaffordable(self, protos: np.ndarray, depth: int, box: Any) -> None:
        """LimitError before generating when the rule tiles would not fit in memory: the
        seeds' counts after ``depth`` substitutions (exact), or, with a box, at most what
        fits in it, at GENERATION_BYTES_PER_TILE each (:meth:`iter_patches` streams instead)."""
        count = float(sum(sum(self.system.counts(depth, int(p))[-1]) for p in protos))
        if box is not None:
            count = min(count, region_tile_estimate(shapely.box(*box), self.system.prototiles))
        refuse_over_memory("tiles", count, GENERATION_BYTES_PER_TILE, hint="ask for a smaller depth or region")

    def _generation_region(self, reg: BaseGeometry | None) -> BaseGeometry | None:
        """The region to generate for ``reg``: shaped tiles reach beyond their straight tiles,
        so a wider box."""
        if self._shaped is None or reg is None:
            return reg
        margin = self._shape_margin()
        x0, y0, x1, y1 = reg.bounds
        return shapely.box(x0 - margin, y0 - margin, x1 + margin, y1 + margin)

    def _as_patch(self, proto: np.ndarray, transform: np.ndarray) -> Patch:
        """A Patch of the (whole) tiles, shaped and coloured."""
        if self._shaped is not None:
            transform = canonical_transforms(proto, transform, self._mirrors)
        return Patch(self.prototiles, proto, transform, colour=_colours(proto, transform, self._turns()))

    def _turns(self) -> np.ndarray | bool | None:
        """What _colours colours by: False (the prototile) for systems of several
        prototiles, the orientation classes of a one-prototile system otherwise."""
        if len(self.prototiles) > 1:
            return False
        return orientation_turns(self.system)

    def patch(self, region: Any = None) -> Patch:
        """Tiles meeting ``region`` (every tile of the fixed-depth patch when region is None)."""
        reg = as_region(region) if region is not None else None
        if reg is not None and self.depth is not None and self._is_frame(reg):
            # the default region of a fixed depth frames the whole depth-N patch: draw all of it
            return self.patch(None).clip(reg)
        patch = self._as_patch(*self.raw(self._generation_region(reg)))
        if reg is not None:
            patch = patch.clip(reg)
        return patch

    @property
    def streams(self) -> bool:  # type: ignore[override]
        """Every system but an overlapping one (whose duplicates span whole levels) streams."""
        return self.system.kind != "overlapping"

    def iter_patches(self, region: Any = None, chunk_tiles: int = STREAM_CHUNK_TILES) -> Iterator[Patch]:
        """``patch(region)`` as a stream of patches of about ``chunk_tiles`` whole tiles each,
        never the whole patch at once (the memory refusal of :meth:`patch` does not apply).

        The seeds are substituted in chunks (:func:`engine.generate_chunks`, neighbouring
        supertiles in nearby chunks), the halves of whole tiles are paired across chunks
        (:func:`engine.assemble_chunks`) and every chunk is shaped, coloured and clipped as
        :meth:`patch` does: the union of the patches is ``patch(region)``, tile for tile.
        Empty chunks are not yielded. ``region=None``: the fixed depth's whole patch.
        """
        self._check_stream(region, chunk_tiles)
        reg = as_region(region) if region is not None else None
        if reg is not None and self.depth is not None and self._is_frame(reg):
            reg_clip, reg = reg, None  # the frame of the whole depth-N patch: all of it, clipped
        else:
            reg_clip = reg
        protos, maps, d, box = self._plan(self._generation_region(reg))
        chunks = engine.generate_chunks(self.system, d, maps, protos, box=box, chunk_tiles=chunk_tiles)
        for proto, transform in engine.assemble_chunks(self.system, chunks):
            patch = self._as_patch(proto, transform)
            if reg_clip is not None:
                patch = patch.clip(reg_clip)
            if len(patch):
                yield patch

    def _check_stream(self, region: Any, chunk_tiles: int) -> None:
        """ParameterError for a chunk size that is not a positive whole number; LimitError
        before streaming when what a stream holds at once would not fit in memory: a chunk (at
        most the patch) and the supertiles the chunks are cut from, about (patch tiles) x
        (growth per level) / ``chunk_tiles`` of them, at GENERATION_BYTES_PER_TILE each."""
        chunk_tiles = check_chunk_tiles(chunk_tiles)
        total = self.estimate_tiles(region)
        held = min(total, chunk_tiles) + total * self.system.perron_frobenius()[0] / chunk_tiles
        refuse_over_memory("tiles held at once by the stream", held, GENERATION_BYTES_PER_TILE,
                           hint=f"give a chunk size nearer {STREAM_CHUNK_TILES:,} tiles")

    def _is_frame(self, reg: BaseGeometry) -> bool:
        """Whether ``reg`` is (or holds) the box of the whole depth-N patch, default_region()."""
        x0, y0, x1, y1 = self.default_region().bounds
        tol = 1e-6 * max(x1 - x0, y1 - y0)
        r0, s0, r1, s1 = reg.bounds
        return abs(r0 - x0) <= tol and abs(s0 - y0) <= tol and abs(r1 - x1) <= tol and abs(s1 - y1) <= tol

    def _shape_margin(self) -> float:
        """How far any shaped tile reaches outside its straight tile (Hausdorff bound)."""
        assert self._shaped is not None
        return max(
            float(shapely.hausdorff_distance(shapely.Polygon(a.outline), shapely.Polygon(b.outline)))
            for a, b in zip(self._shaped, self.system.tiles)
        )

    def default_region(self) -> BaseGeometry:
        """A window of about 12 tiles across, or, with a fixed depth, the whole inflated seed."""
        if self.depth is not None:
            # whole tiles assembled from boundary halves reach up to one tile beyond the seed
            reach = 0.0
            if self.system.output_prototiles is not None:
                reach = max(float(np.ptp(p.outline, axis=0).max()) for p in self.prototiles)
            x0, y0, x1, y1 = self._cluster_polygon(self.depth).bounds
            return shapely.box(x0 - reach, y0 - reach, x1 + reach, y1 + reach)
        size = math.sqrt(max(abs(p.area) for p in self.system.tiles))
        return shapely.box(-6 * size, -6 * size, 6 * size, 6 * size)

    def estimate_tiles(self, region: Any = None) -> float:
        """Tiles of ``patch(region)``: with a fixed depth, at most the seed's count after
        ``depth`` substitutions (the substitution matrix's M^d e, exact), and at most what fits
        in the region at the prototiles' areas."""
        reg = as_region(region) if region is not None else None
        if self.depth is not None:
            full = float(self._full_count(self.depth))
            return full if reg is None else min(full, region_tile_estimate(reg, self.system.prototiles))
        return region_tile_estimate(reg if reg is not None else self.default_region(), self.system.prototiles)

    def _full_count(self, depth: int) -> int:
        """Rule tiles after ``depth`` substitutions of the seed cluster (M^d applied to it)."""
        proto, _ = self.seed_cluster()
        return sum(int(sum(self.system.counts(depth, int(p))[-1])) for p in proto)

    def options_help(self) -> str:
        return "\n".join([
            "--depth N              substitutions of the seed cluster (0..60)",
            "--set seed=NAME        substitute this rule prototile instead of the seed cluster",
            "--param H[,H...]       tooth heights of the free edge shapes a, b, ... (assembled systems)",
            "--edge a=x,y:x,y       an edge shape from (0,0) to (1,0) (assembled systems)",
            "--set r1=R --set theta1=DEG --set r2=R --set theta2=DEG   quasivertex deformation (P2, P3)",
        ])

    def configure(self, **options: Any) -> SubstitutionTiling:
        """Options: ``depth`` (int, fixed substitution depth), ``seed`` (prototile name),
        ``params`` (tooth heights of the free edge shapes a, b, ... of assembled systems) and
        ``edges`` ('a=x,y:x,y' edge shapes from (0,0) to (1,0), interior points only)."""
        depth = options.pop("depth", self.depth)
        seed = options.pop("seed", self.seed)
        params = options.pop("params", self.params)
        edges = options.pop("edges", self.edges)
        qv_given = {k: options.pop(k) for k in ("r1", "theta1", "r2", "theta2") if k in options}
        quasivertex = {**(self.quasivertex or {}), **qv_given} if (qv_given or self.quasivertex) else None
        if options:
            raise ParameterError(
                f"{self.name} does not take option(s) {', '.join(sorted(options))}; "
                "valid: depth, seed, params, edges, r1, theta1, r2, theta2"
            )
        depth = _depth(depth)
        if params is not None:
            try:
                params = [float(v) for v in params]
            except (TypeError, ValueError, OverflowError):
                raise ParameterError(f"params {shown(params)} are not numbers") from None
        if isinstance(edges, str):
            edges = [edges]
        return SubstitutionTiling(self.system, depth, seed, self._spec_source, params, edges, quasivertex)

    def spec(self) -> dict[str, Any]:
        out = dict(self._spec_source)
        if self.depth is not None:
            out["depth"] = self.depth
        if self.seed is not None:
            out["seed"] = self.seed
        if self.params is not None:
            out["params"] = self.params
        if self.edges is not None:
            out["edges"] = self.edges
        if self.quasivertex is not None:
            out.update(self.quasivertex)
        return out

    # ------------------------------------------------------------------ facts
    def properties(self) -> dict[str, Any]:
        return {**system_properties(self.system), "edge_to_edge": self.edge_to_edge()}

    def edge_to_edge(self) -> bool:
        """Whether the tiles meet edge to edge (§4.1: shape vertices and tiling vertices
        coincide), read from a patch of the default region: P2, P3 and Ammann-Beenker do; the
        chair, the pinwheel, the hat and the spectre (a 14-gon with one straight angle, so a
        13-sided polygon whose long side neighbours meet at its midpoint) do not."""
        patch = self.patch(self.default_region())
        return edge_to_edge(pts for _, _, pts in patch.groups())

    def describe(self) -> str:
        s = self.system
        lines = [f"{s.title}: {s.n} rule prototile(s), expansion constant {s.scale:.9g}, kind {s.kind}"]
        m = s.substitution_matrix()
        lines.append("substitution matrix (column j = children of prototile j): " + str(m.tolist()))
        for j, rule in enumerate(s.rules):
            kids = ", ".join(s.prototiles[k].name for k in rule.children)
            lines.append(f"  {s.prototiles[j].name} -> {kids}")
        return "\n".join(lines)


def system_properties(system: SubstitutionSystem, generations: int = 6) -> dict[str, Any]:
    """The catalogue facts of a system: expansion constant, matrix, eigen-data, counts ..."""
    eig, freq = system.perron_frobenius()
    counts = system.counts(generations)
    tile_counts = getattr(system, "tile_counts", None)
    if tile_counts is None and system.output_prototiles is not None:
        tile_counts = partial(patch_counts, system)
    props: dict[str, Any] = {
        "expansion_constant": round(system.scale, 12),
        "substitution_matrix": [[int(v) for v in row] for row in system.substitution_matrix()],
        "perron_frobenius_eigenvalue": round(eig, 12),
        "tile_frequencies": [round(float(f), 12) for f in freq],
        "rule_prototiles": [p.name for p in system.prototiles],
        "tiles_per_generation": tile_counts(generations) if tile_counts else [int(sum(c)) for c in counts],
        "kind": system.kind,
        "k_hedral": len({_shape_key(p) for p in system.tiles}),
        "sides": sorted({corner_count(p.outline, p.corners) for p in system.tiles}),
    }
    rep = system.rep_tile()
    if rep is not None:
        props["rep_tile"] = rep
    aperiodic = system.facts.get("aperiodic")
    if aperiodic is not None:
        props["aperiodic"] = bool(aperiodic)
    if system.facts.get("nonperiodic", aperiodic):
        props["periodic"] = False
    for key, value in system.facts.items():
        if key not in props and key != "aliases" and isinstance(value, str | int | float | bool | list):
            props[key] = value
    return props


#: Most rule tiles ``patch_counts`` generates for one depth (its list stops before).
COUNT_BUDGET = 50_000


def patch_counts(system: SubstitutionSystem, generations: int) -> list[int]:
    """Tiles of the depth-n patch (``render NAME --depth n``), n = 0..generations, counted on
    the generated patches; for systems assembled from halves this is the meaning of
    ``tiles_per_generation`` (whole tiles, each once). Stops early at COUNT_BUDGET rule tiles."""
    base = SubstitutionTiling(system)
    out = []
    for n in range(generations + 1):
        t = base.configure(depth=n)
        if t._full_count(n) > COUNT_BUDGET:
            break
        out.append(len(t.patch()))
    return out


class KeypointTiling(SubstitutionTiling):
    """A tiling from a keypoint substitution (the Spectre): supertiles grow by rigid placement.

    ``patch(region)`` centres a level-d supertile on the region, with d the first level whose
    bounding disc is twice the region's, and goes one level further while the tiles do not
    cover the region (the supertiles are not convex, so their inner radius is measured, not
    assumed).

    Options beyond ``depth`` and ``seed``: ``overlay`` (supertile levels whose outlines
    :meth:`render_svg` draws over the tiles) and, for a system whose tiles are never
    reflected (``chiral`` in its facts: the Spectre), ``curved`` (every edge an S-shaped
    curve, the Spectre's curved edges: :func:`shapes.spectre_edge`).
    """

    system: Any

    def __init__(self, system: Any, depth: int | None = None, seed: str | None = None,
                 spec_source: Mapping[str, Any] | None = None, overlay: Any = None, curved: Any = None) -> None:
        self.system = system
        self.name = system.name
        if depth is not None and not 0 <= depth <= MAX_DEPTH // 4:
            raise ParameterError(f"depth {depth} is out of range 0..{MAX_DEPTH // 4}")
        self.depth = depth
        if seed is not None and seed not in system.labels:
            raise ParameterError(
                f"seed {seed!r} is not a supertile label of {system.name}; valid: {', '.join(system.labels)}"
            )
        self.seed = seed
        self._spec_source = dict(spec_source) if spec_source is not None else {"system": system.name}
        self.params = None
        self.edges = None
        self._shaped = None
        self.quasivertex = None
        self._mirrors = None
        self.overlay = overlay_levels(overlay)
        self.curved = curve_amplitude(curved)
        if self.curved is not None:
            if not system.facts.get("chiral"):
                raise ParameterError(
                    f"curved edges fit only tilings without reflected tiles (the spectre); {system.name}'s "
                    "tiles come in both hands"
                )
            self._shaped = shapes.curved_tiles(system.tiles, shapes.spectre_edge(self.curved))

    def _seed_index(self) -> int:
        return self.system.labels.index(self.seed) if self.seed is not None else self.system.seed

    def patch(self, region: Any = None) -> Patch:
        return self._generated(region)[0]

    def _generated(self, region: Any = None, level: int | None = None) -> tuple[Patch, np.ndarray | None, np.ndarray | None]:
        """``patch(region)``, and with a ``level``, for each of its tiles the index of the
        level-``level`` supertile it lies in and that supertile's label index (the same
        generation, :meth:`MonotileSystem.generate_grouped`)."""
        reg = as_region(region) if region is not None else None
        s = self.system
        label = self._seed_index()
        margin = self._shape_margin() if self._shaped is not None else 0.0

        def make(depth: int, t0: np.ndarray | None, box: Any) -> tuple[Patch, np.ndarray | None, np.ndarray | None]:
            if box is not None and margin:
                box = (box[0] - margin, box[1] - margin, box[2] + margin, box[3] + margin)
            if level is None:
                (proto, transform, colour), group, names = s.generate(depth, t0, label, box=box), None, None
            else:
                (proto, transform, colour), group, names = s.generate_grouped(depth, level, t0, label, box=box)
            patch = Patch(self.prototiles, proto, transform, colour=colour)
            if reg is None:
                return patch, group, names
            keep = patch.clip_index(reg)
            return patch.subset(keep), None if group is None else group[keep], names

        count = float(self._full_count(self.depth if self.depth is not None else 0))
        if self.depth is not None:
            box = tuple(reg.bounds) if reg is not None else None
            if box is not None:
                count = min(count, region_tile_estimate(reg, s.tiles))
            if box is not None or count <= getattr(s, "max_tiles", math.inf):
                # (over its own whole-supertile limit, the system's generate refuses by count)
                refuse_over_memory("tiles", count, GENERATION_BYTES_PER_TILE, hint="ask for a smaller depth or region")
            return make(self.depth, None, box)
        if reg is None:
            raise ParameterError("a region or a fixed depth is needed")
        refuse_over_memory("tiles", region_tile_estimate(reg, s.tiles), GENERATION_BYTES_PER_TILE,
                           hint="ask for a smaller region")
        for depth, t0 in self._candidates(reg):
            out = make(depth, t0, tuple(reg.bounds))
            if len(out[0]) and _covers(out[0], reg):
                return out
        raise ParameterError(f"could not cover region {reg.bounds} by depth {depth}")

    def _candidates(self, reg: BaseGeometry) -> Iterator[tuple[int, np.ndarray]]:
        """(depth, seed map) of the supertiles tried for ``reg``: centred on it, from the
        first level whose bounding disc is twice the region's, four levels."""
        s = self.system
        label = self._seed_index()
        x0, y0, x1, y1 = reg.bounds
        centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
        need = math.hypot(x1 - x0, y1 - y0) / 2
        d = 0
        while s.bounds(d)[1][label] < 2 * need:
            d += 1
        for depth in range(d, d + 4):
            c = s.bounds(depth)[0][label]
            if depth % 2 == 1 and s.reflect:
                c = np.array([-c[0], c[1]])
            yield depth, Affine.translation(*(centre - c))

    @property
    def streams(self) -> bool:  # type: ignore[override]
        """Streams, unless an overlay is asked for (supertile outlines need the whole patch)."""
        return not self.overlay

    def iter_patches(self, region: Any = None, chunk_tiles: int = STREAM_CHUNK_TILES) -> Iterator[Patch]:
        """``patch(region)`` as a stream of patches of at most about ``chunk_tiles`` tiles
        (the system's ``generate_chunks``), clipped as :meth:`patch` clips; the union is
        ``patch(region)``. Without a fixed depth the supertile must cover the region: each
        candidate is first streamed once to sum the area it covers (tiles do not overlap, so
        the chunks' covered areas add up), unless the region's estimate fits in one chunk,
        when :meth:`patch` is used as it is."""
        self._check_stream(region, chunk_tiles)
        reg = as_region(region) if region is not None else None
        s = self.system
        label = self._seed_index()
        box = tuple(reg.bounds) if reg is not None else None
        margin = self._shape_margin() if self._shaped is not None else 0.0
        if box is not None and margin:
            box = (box[0] - margin, box[1] - margin, box[2] + margin, box[3] + margin)

        def chunks(depth: int, t0: np.ndarray | None) -> Iterator[Patch]:
            for proto, transform, colour in s.generate_chunks(depth, t0, label, box=box, chunk_tiles=chunk_tiles):
                patch = Patch(self.prototiles, proto, transform, colour=colour)
                patch = patch.clip(reg) if reg is not None else patch
                if len(patch):
                    yield patch

        if self.depth is not None:
            yield from chunks(self.depth, None)
            return
        if reg is None:
            raise ParameterError("a region or a fixed depth is needed")
        if region_tile_estimate(reg, s.tiles) <= chunk_tiles:
            yield self.patch(reg)
            return
        for depth, t0 in self._candidates(reg):
            covered = sum(p.covered_area(reg) for p in chunks(depth, t0))
            if covered and _covered(covered, reg):
                yield from chunks(depth, t0)
                return
        raise ParameterError(f"could not cover region {reg.bounds} by depth {depth}")

    def raw(self, region: Any = None) -> tuple[np.ndarray, np.ndarray]:
        p = self.patch(region)
        return p.prototile, p.transform

    def _full_count(self, depth: int) -> int:
        return int(self.system.tile_counts(depth, self._seed_index())[-1])

    def default_region(self) -> BaseGeometry:
        """About 12 tiles across, or, with a fixed depth, the level-d supertile's bounding box
        (its tiles are generated only when there are few enough to be drawn)."""
        if self.depth is not None:
            if self._full_count(self.depth) > MAX_TILES:  # the bounding disc's box, no tiles made
                centres, radii = self.system.bounds(self.depth)
                label = self._seed_index()
                c, r = np.array(centres[label], dtype=float), float(radii[label])
                if self.depth % 2 == 1 and getattr(self.system, "reflect", False):
                    c = np.array([-c[0], c[1]])
                return shapely.box(c[0] - r, c[1] - r, c[0] + r, c[1] + r)
            _, tr, _ = self.system.generate(self.depth, seed_label=self._seed_index())
            pts = Affine.apply(tr, self.system.tile.outline).reshape(-1, 2)
            x0, y0 = pts.min(axis=0)
            x1, y1 = pts.max(axis=0)
            return shapely.box(x0, y0, x1, y1)
        size = math.sqrt(abs(self.system.tile.area))
        return shapely.box(-6 * size, -6 * size, 6 * size, 6 * size)

    def options_help(self) -> str:
        lines = [
            f"--depth N              level of the supertile (0..{MAX_DEPTH // 4})",
            "--set seed=LABEL       the supertile label to start from",
            f"--set overlay=L[,L..]  draw the outlines of the level-L supertiles over the tiles (0..{MAX_DEPTH // 4})",
        ]
        if self.system.facts.get("chiral"):
            lines.append(f"--set curved=H         S-shaped edges (the Spectre's), height H in (0, {MAX_CURVE}]; 1 or true: "
                         f"{DEFAULT_CURVE}")
        return "\n".join(lines)

    def _options(self, options: dict[str, Any]) -> dict[str, Any]:
        """Pop the options every keypoint tiling takes (depth, seed, overlay, curved) into
        constructor keywords, current values for those not given."""
        depth = options.pop("depth", self.depth)
        return {"depth": _depth(depth), "seed": options.pop("seed", self.seed),
                "overlay": options.pop("overlay", self.overlay), "curved": options.pop("curved", self.curved)}

    def configure(self, **options: Any) -> KeypointTiling:
        kept = self._options(options)
        if options:
            valid = "depth, seed, overlay" + (", curved" if self.system.facts.get("chiral") else "")
            raise ParameterError(f"{self.name} does not take option(s) {', '.join(sorted(options))}; valid: {valid}")
        return KeypointTiling(self.system, spec_source=self._spec_source, **kept)

    def spec(self) -> dict[str, Any]:
        out = super().spec()
        if self.overlay:
            out["overlay"] = list(self.overlay)
        if self.curved is not None:
            out["curved"] = self.curved
        return out

    def describe(self) -> str:
        s = self.system
        lines = [f"{s.title}: keypoint substitution on {s.n} supertile labels, growth {s.perron_frobenius()[0]:.9g} per level"]
        for j, slots in enumerate(s.rules):
            kids = ", ".join(s.labels[k] if k >= 0 else "-" for k in slots)
            lines.append(f"  {s.labels[j]} -> {kids}")
        lines.append("options of tilekit render:")
        lines += ["  " + line for line in self.options_help().splitlines()]
        return "\n".join(lines)

    def supertiles(self, patch: Patch, region: Any = None, level: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """For each tile of ``patch`` (made by ``self.patch(region)``), the index of the
        level-``level`` supertile it lies in and that supertile's label index; -1 for a tile
        the same generation does not make (a patch from elsewhere). The generation is made
        again with the supertiles followed, and its tiles matched to the patch's by their
        placements."""
        full, group, names = self._generated(region, level)
        assert group is not None and names is not None
        at = match_placements(patch.transform, full.transform)
        found = at >= 0
        out_group = np.where(found, group[np.maximum(at, 0)], -1)
        out_label = np.where(found, names[np.maximum(out_group, 0)], -1)
        return out_group, out_label

    def tile_labels(self, patch: Patch, region: Any = None) -> np.ndarray | None:
        """Each tile's level-0 supertile label (the hat's metatile H, T, P, F; the spectre's
        Gamma .. Psi), "" for a tile this tiling's generation does not make."""
        _, label = self.supertiles(patch, region, 0)
        names = np.array(list(self.system.labels) + [""], dtype=object)
        return names[label]

    def render_svg(self, patch: Patch, **options: Any) -> str:
        """The picture, with the outlines of the supertiles of each ``overlay`` level drawn
        over the tiles (lines between tiles of different supertiles, found on the tiles'
        shared edges: :func:`tilekit.export.group_boundaries`), thicker for higher levels."""
        if not self.overlay or not len(patch):
            return patch_to_svg(patch, **options)
        region = options.get("region")
        edges = export.tile_edges(patch)
        lines = []
        for i, level in enumerate(self.overlay):
            group, _ = self.supertiles(patch, region, level)
            missing = group < 0
            group = np.where(missing, -1 - np.arange(len(group)), group)  # unknown tiles: their own
            segments = export.group_boundaries(patch, group, outer=region is None, edges=edges)
            lines.append((segments, OVERLAY_COLOURS[i % len(OVERLAY_COLOURS)], 2.0 + 1.5 * i))
        return patch_to_svg(patch, overlay=lines, **options)


#: Strokes of the overlay levels, lowest level first.
OVERLAY_COLOURS = ("#b40000", "#1f3fbf", "#0a7a2a", "#7a2a9a")
#: Height of the default S-curve of ``curved`` (a fraction of the edge), and the largest allowed.
DEFAULT_CURVE = 0.1
MAX_CURVE = 0.2


def overlay_levels(value: Any) -> tuple[int, ...]:
    """``overlay`` as a sorted tuple of supertile levels ('1', '0,2', 2, [0, 2]; None or ''
    for none); ParameterError naming the valid range."""
    if value is None or value == "" or value == ():
        return ()
    items = value.split(",") if isinstance(value, str) else (list(value) if isinstance(value, list | tuple) else [value])
    out = set()
    for item in items:
        try:
            level = int(str(item).strip())
        except ValueError:
            level = -1
        if not 0 <= level <= MAX_DEPTH // 4 or isinstance(item, bool):
            raise ParameterError(f"overlay {value!r}: give supertile levels 0..{MAX_DEPTH // 4}, "
                                 "e.g. overlay=1 or overlay=0,2")
        out.add(level)
    return tuple(sorted(out))


def curve_amplitude(value: Any) -> float | None:
    """``curved`` as the S-curve's height, a fraction of the edge: true/1/yes/on the
    default, false/0/no/off/None none, else a number in (0, MAX_CURVE]."""
    if value is None or value is False:
        return None
    text = str(value).strip().lower()
    if value is True or text in ("true", "yes", "on", "1"):
        return DEFAULT_CURVE
    if text in ("false", "no", "off", "0", ""):
        return None
    try:
        h = float(text)
    except ValueError:
        h = math.nan
    if not (math.isfinite(h) and 0 < h <= MAX_CURVE):
        raise ParameterError(f"curved={value!r}: give true (height {DEFAULT_CURVE}) or the S-curve's height as a "
                             f"fraction of the edge in (0, {MAX_CURVE}]")
    return h


def match_placements(transforms: np.ndarray, among: np.ndarray) -> np.ndarray:
    """For each placement (n, 3, 3), the index of the equal one in ``among`` (m, 3, 3), or -1;
    equal up to float noise (1e-9 relative to the largest translation), by sorted keys."""
    a = np.asarray(transforms, dtype=float).reshape(-1, 9)[:, [0, 1, 2, 3, 4, 5]]
    b = np.asarray(among, dtype=float).reshape(-1, 9)[:, [0, 1, 2, 3, 4, 5]]
    if not len(a) or not len(b):
        return np.full(len(a), -1, dtype=np.int64)
    scale = max(1.0, float(np.abs(b[:, [2, 5]]).max()))
    tol = 1e-9 * scale
    ka = np.round(a / tol).astype(np.int64)
    kb = np.round(b / tol).astype(np.int64)
    rows = np.ascontiguousarray(kb).view([("", np.int64)] * 6).reshape(-1)
    order = np.argsort(rows, kind="stable")
    keys = np.ascontiguousarray(ka).view([("", np.int64)] * 6).reshape(-1)
    at = np.minimum(np.searchsorted(rows[order], keys), len(b) - 1)
    return np.where(rows[order][at] == keys, order[at], -1)


class HatTiling(KeypointTiling):
    """The hat's tilings and their deformations, the continuum Tile(a, b) (arXiv:2303.10798;
    :mod:`.continuum`): ``a`` and ``b`` (numbers or expressions such as ``sqrt3``) or
    ``shape`` (a named member of the hat file's ``[continuum.members]``: hat, turtle,
    chevron, comet). Tile(a, a) is handled as the paper does: it is the Spectre's polygon,
    whose tilings without reflected tiles come from the spectre system, so ``a == b == 1``
    (or ``shape=spectre``) gives that system's tiling."""

    def __init__(self, hat: Any, depth: int | None = None, seed: str | None = None,
                 spec_source: Mapping[str, Any] | None = None, overlay: Any = None, curved: Any = None,
                 a: float | None = None, b: float | None = None, shape: str | None = None) -> None:
        self.hat = hat
        self.a, self.b, self.shape = a, b, shape
        system = hat if a is None or b is None else continuum.continuum_system(hat, a, b)
        super().__init__(system, depth, seed, spec_source, overlay, curved)
        if shape is not None:
            self.name = shape
        elif a is not None and b is not None:
            self.name = continuum.tile_name(a, b)

    def options_help(self) -> str:
        names = ", ".join([*continuum.members(self.hat), str(self.hat.continuum.get("equilateral", ""))])
        return "\n".join([
            super().options_help(),
            f"--set a=A --set b=B     Tile(a, b): edges along the lattice directions a, between them b (0..{continuum.MAX_EDGE:g};"
            " expressions such as sqrt3; the hat is a=1, b=sqrt3)",
            f"--set shape=NAME       a named member: {names}",
        ])

    def configure(self, **options: Any) -> KeypointTiling:
        a, b, shape = options.pop("a", None), options.pop("b", None), options.pop("shape", None)
        kept = self._options(options)
        if options:
            raise ParameterError(f"{self.name} does not take option(s) {', '.join(sorted(options))}; "
                                 "valid: depth, seed, overlay, a, b, shape")
        if shape is not None and (a is not None or b is not None):
            raise ParameterError(f"give shape={shape} or a and b, not both")
        if shape is not None:
            return self._member(str(shape).strip(), kept)
        if a is not None or b is not None:
            if a is None or b is None:
                raise ParameterError("Tile(a, b) needs both a and b (the hat is a=1, b=sqrt3)")
            return self._member_ab(*continuum.check_edges(_edge_value(a, "a"), _edge_value(b, "b")), None, kept)
        return HatTiling(self.hat, spec_source=self._spec_source, a=self.a, b=self.b, shape=self.shape, **kept)

    def _member(self, name: str, kept: dict[str, Any]) -> KeypointTiling:
        members = continuum.members(self.hat)
        if name == self.hat.continuum.get("equilateral"):
            return self._member_ab(1.0, 1.0, name, kept)
        if name not in members:
            valid = ", ".join([*members, str(self.hat.continuum.get("equilateral", ""))])
            raise ParameterError(f"shape {name!r} is not a named member of the hat's continuum; valid: {valid}")
        m = members[name]
        return self._member_ab(m.a, m.b, name, kept)

    def _member_ab(self, a: float, b: float, name: str | None, kept: dict[str, Any]) -> KeypointTiling:
        """The tiling of Tile(a, b) (a checked pair), named ``name`` when it is a member."""
        if math.isclose(a, b, rel_tol=1e-12):
            equilateral = self.hat.continuum.get("equilateral")
            if equilateral is None:
                raise ParameterError("Tile(a, a) has no tilings here: the hat file names no equilateral system")
            if not math.isclose(a, 1.0, rel_tol=1e-12):
                raise ParameterError(f"Tile({a:g}, {b:g}) is the Spectre's polygon, offered as the {equilateral} "
                                     f"tiling at edge length 1: give a=1 b=1 or shape={equilateral}")
            return KeypointTiling(builtin_systems()[equilateral], spec_source={"system": equilateral}, **kept)
        hat = continuum.members(self.hat).get("hat")
        if hat is not None and math.isclose(a, hat.a, rel_tol=1e-12) and math.isclose(b, hat.b, rel_tol=1e-12):
            # the hat itself: its own exact lattice generation
            return HatTiling(self.hat, spec_source=self._spec_source, shape=None if name in (None, "hat") else name,
                             **kept)
        return HatTiling(self.hat, spec_source=self._spec_source, a=a, b=b, shape=name, **kept)

    def spec(self) -> dict[str, Any]:
        out = super().spec()
        if self.shape is not None:
            out["shape"] = self.shape
        elif self.a is not None and self.b is not None:
            out["a"], out["b"] = self.a, self.b
        return out

    def properties(self) -> dict[str, Any]:
        props = {**system_properties(self.system), "edge_to_edge": self.edge_to_edge()}
        if self.a is None or self.b is None:
            return props
        props.update({"tile": self.system.tile.name, "edge_a": self.a, "edge_b": self.b,
                      "tile_area": round(abs(self.system.tile.area), 12)})
        member = continuum.members(self.hat).get(self.shape or "")
        if member is not None and member.aperiodic is not None:
            props["aperiodic"] = member.aperiodic
        elif self.a == 0 or self.b == 0:
            props["aperiodic"] = False  # the ends of the continuum tile periodically too
        return props

    def describe(self) -> str:
        text = super().describe()
        if self.a is None or self.b is None:
            return text
        return (f"{self.system.tile.name}: the hat's edges along the lattice directions of length {self.a:.9g}, "
                f"the others {self.b:.9g}; area {abs(self.system.tile.area):.9g}; the hat's tilings deformed edge "
                "by edge\n" + text)


def _edge_value(value: Any, name: str) -> float:
    """An edge length from a number or a safe expression (``sqrt3``, ``1/2``)."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    try:
        return evaluate(str(value))
    except ParseError as exc:
        raise ParameterError(f"Tile(a, b): {name}={value!r} is not a number or an expression ({exc})") from None


def continuum_records(hat: Any) -> list[tuple[str, dict[str, Any], str, dict[str, Any], list[str]]]:
    """(name, spec, title, properties, aliases) of the hat continuum's named members other
    than the hat itself (its record is the system's), for the catalogue."""
    out = []
    for name, member in continuum.members(hat).items():
        if name == "hat":
            continue
        t = HatTiling(hat).configure(shape=name)
        out.append((name, t.spec(), member.title, t.properties(), list(member.aliases)))
    return out


#: Orientation classes a one-prototile system is coloured by (turns are binned when more).
ORIENTATION_COLOURS = 8


def _turn_keys(linear: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(turn key, reflected?) of linear parts (..., 2, 2): the angle of the first column in
    units of 1e-4 rad, taken modulo a full turn (so that -0 and 2 pi agree)."""
    angle = np.mod(np.arctan2(linear[..., 1, 0], linear[..., 0, 0]), 2 * np.pi)
    full = round(2 * np.pi * 1e4)
    key = np.mod(np.round(angle * 1e4).astype(np.int64), full)
    det = linear[..., 0, 0] * linear[..., 1, 1] - linear[..., 0, 1] * linear[..., 1, 0]
    return key, det < 0


#: id(system) -> (a weak reference to the system, its turns): a dead system's id may be reused
_TURNS_CACHE: dict[int, tuple[Any, np.ndarray | None]] = {}


def orientation_turns(system: Any) -> np.ndarray | None:
    """The sorted turn keys (see _turn_keys) of the tiles a one-prototile system makes from
    an unturned seed: the closure of its children's orientations; None when there are more
    than ORIENTATION_COLOURS (the pinwheel's are dense). A property of the system, so every
    patch and every chunk of a stream colours a tile alike."""
    key = id(system)
    cached = _TURNS_CACHE.get(key)
    if cached is not None and cached[0]() is system:
        return cached[1]
    units = np.concatenate([np.asarray(r.matrices, dtype=float)[:, :2, :2] for r in system.rules]) * system.scale
    seen: dict[tuple[int, bool], np.ndarray] = {(0, False): np.eye(2)}
    frontier = [np.eye(2)]
    turns: np.ndarray | None = None
    while frontier:
        found = np.einsum("aij,bjk->abik", np.array(frontier), units).reshape(-1, 2, 2)
        keys, flips = _turn_keys(found)
        frontier = []
        for k, f, m in zip(keys.tolist(), flips.tolist(), found):
            if (k, f) not in seen:
                seen[(k, f)] = m
                frontier.append(m)
        if len({k for k, _ in seen}) > ORIENTATION_COLOURS:
            break
    else:
        turns = np.array(sorted({k for k, _ in seen}), dtype=np.int64)
    _TURNS_CACHE[key] = (weakref.ref(system), turns)
    return turns


def _colours(proto: np.ndarray, transform: np.ndarray, turns: np.ndarray | None | bool = False) -> np.ndarray:
    """Colour by prototile (``turns`` False); a system of one prototile (chair, sphinx,
    pinwheel) by the tile's orientation instead: its turn among the system's ``turns``
    (orientation_turns; None: 4 bins of 90 degrees, as for the pinwheel) and, doubling
    them, its handedness. A tile's colour depends on it alone, never on the rest of the patch."""
    if turns is False or not len(proto):
        return proto
    key, flip = _turn_keys(transform[:, :2, :2])
    if turns is not None:
        index = np.searchsorted(turns, key)
        index = np.minimum(index, len(turns) - 1)
        if np.array_equal(turns[index], key):
            return index.astype(np.int64) + len(turns) * flip
    # dense orientations (or a turn the closure missed): 4 bins
    angle = np.mod(np.arctan2(transform[:, 1, 0], transform[:, 0, 0]), 2 * np.pi)
    index = (angle // (np.pi / 2)).astype(np.int64) % 4
    return index + 4 * flip


def _rounded(bounds: Sequence[float]) -> tuple[float, ...]:
    return tuple(round(float(v), 3) for v in bounds)


def _whole_tile_halves(system: SubstitutionSystem, seed: int) -> list[np.ndarray]:
    """Placements (in the seed half's frame) of the halves making up the seed's whole tile,
    the seed half itself first."""
    outline = system.prototiles[seed].outline
    if system.pairing_edge is not None:
        a, b = (outline[i] for i in system.pairing_edge)
        if "mirror" in system.pairing:  # the partner is the half reflected across the edge
            ang = math.atan2(b[1] - a[1], b[0] - a[0])
            other = (Affine.translation(*a) @ Affine.rotation(ang) @ np.diag([1.0, -1.0, 1.0])
                     @ Affine.rotation(-ang) @ Affine.translation(-a[0], -a[1]))
        else:  # "turn": the half turned about the edge's midpoint
            mid = (a + b) / 2
            other = Affine.translation(*mid) @ Affine.rotation(math.pi) @ Affine.translation(-mid[0], -mid[1])
        return [np.eye(3), other]
    assert system.assemble_tile is not None and system.assemble_matrix is not None
    # The partner is the half the substitution itself puts beside a seed half (a symmetry of
    # the whole tile's outline may map the half onto the partner's place with the wrong
    # orientation, e.g. the thick rhomb's half-turn): find two seed halves of one whole tile
    # in a generated patch and take their relative placement.
    t = int(system.assemble_tile[seed])
    whole = system.output_prototiles[t].outline if system.output_prototiles else outline
    for depth in range(1, 7):
        proto, transform = engine.generate(system, depth, np.eye(3), seed)
        idx = np.flatnonzero((proto == seed) & (system.assemble_tile[proto] == t))
        if len(idx) < 2:
            continue
        wholes = np.matmul(transform[idx], system.assemble_matrix[seed])
        centres = Affine.apply(wholes, whole).mean(axis=1)  # (k, 2)
        keys = np.round(centres / (1e-6 * system.scale**-depth)).astype(np.int64)
        _, first, counts = np.unique(keys, axis=0, return_index=True, return_counts=True)
        for f, c in zip(first, counts):
            if c < 2:
                continue
            i = idx[f]
            same = np.flatnonzero(np.all(keys == keys[f], axis=1))
            j = idx[same[same != f][0]]
            return [np.eye(3), np.linalg.inv(transform[i]) @ transform[j]]
    return [np.eye(3)]  # the seed's whole tile is the seed itself


def _star_vertex(outline: np.ndarray) -> tuple[np.ndarray, int] | None:
    """A vertex of the (counter-clockwise) outline with equal edges and angle 360/n degrees,
    n >= 3, the one with the largest n: (vertex, n), or None."""
    k = len(outline)
    best: tuple[np.ndarray, int] | None = None
    for i in range(k):
        p, prev, nxt = outline[i], outline[i - 1], outline[(i + 1) % k]
        u, w = nxt - p, prev - p
        lu, lw = float(np.hypot(*u)), float(np.hypot(*w))
        if lu < 1e-9 or abs(lu - lw) > 1e-7 * max(lu, lw):
            continue
        angle = math.atan2(u[0] * w[1] - u[1] * w[0], float(u @ w)) % (2 * math.pi)
        n = round(2 * math.pi / angle) if angle > 1e-9 else 0
        if n >= 3 and abs(n * angle - 2 * math.pi) < 1e-7 and (best is None or n > best[1]):
            best = (p.copy(), n)
    return best


def _covers(patch: Patch, region: BaseGeometry) -> bool:
    """Whether the (non-overlapping) tiles cover the region, up to 1e-7 of its area."""
    return _covered(patch.covered_area(region), region)


def _covered(area: float, region: BaseGeometry) -> bool:
    """Whether tiles covering ``area`` of the region (without overlaps) cover all of it."""
    return bool(region.area - area <= 1e-7 * region.area)


def _shape_key(p: Prototile) -> tuple[int, ...]:
    """Congruence-class key of an outline: sorted edge lengths and squared-area (for k_hedral)."""
    pts = p.outline
    edges = np.linalg.norm(np.roll(pts, -1, axis=0) - pts, axis=1)
    return (len(pts), round(abs(p.area) * 1e6), *sorted(np.round(edges * 1e6).astype(int).tolist()))


_NUMBER = Field("number")

#: A substitution spec as the catalogue stores it (the options are those of ``configure``).
SPEC = Field("table", fields={
    "system": Field("str"),
    "system_data": Field("table"),
    "source": Field("str"),
    "depth": Field("int", range=(0, MAX_DEPTH)),
    "seed": Field("str"),
    "params": Field("list", items=_NUMBER, length=(0, 64)),
    "edges": Field("list", items=Field("str"), length=(0, 64)),
    **{k: _NUMBER for k in ("r1", "theta1", "r2", "theta2")},
})


def tiling_from_spec(spec: Mapping[str, Any], systems: Mapping[str, SubstitutionSystem]) -> SubstitutionTiling:
    """Rebuild a tiling from ``{"system": name}`` or ``{"system_data": {...}}`` plus options
    (checked against :data:`SPEC`: types, ranges, finite numbers)."""
    if not isinstance(spec, Mapping):
        raise ParseError(f'a substitution spec is a JSON object like {{"system": "penrose-p3"}}, not {shown(spec)}')
    spec = check(SPEC, {k: v for k, v in spec.items() if v is not None}, "substitution spec")
    if "system_data" in spec:
        system = load_data(spec["system_data"], source=str(spec.get("source", "<spec>")))
    elif "system" in spec:
        name = spec["system"]
        if name not in systems:
            raise NotFoundError("substitution system", str(name), systems)
        system = systems[name]
    else:
        raise ParseError("substitution spec needs 'system' (a built-in name) or 'system_data'")
    source = {k: spec[k] for k in ("system", "system_data", "source") if k in spec}
    tiling = make_tiling(system, spec_source=source)
    options = {k: spec[k] for k in ("depth", "seed", "params", "edges", "r1", "theta1", "r2", "theta2", "a", "b",
                                    "shape", "overlay", "curved") if k in spec}
    return tiling.configure(**options) if options else tiling


def _depth(depth: Any) -> int | None:
    """A depth option (an int, or text of one) as an int, or a ParameterError: never
    truncated (2.5), never an OverflowError (inf)."""
    if depth is None:
        return None
    if isinstance(depth, str):
        text = depth.strip()
        if not (text.isascii() and text.isdigit() and len(text) <= 3):
            raise ParameterError(f"depth {shown(depth)} is not an integer 0..{MAX_DEPTH}")
        return int(text)
    if isinstance(depth, bool) or not isinstance(depth, numbers.Integral):
        raise ParameterError(f"depth {shown(depth)} is not an integer 0..{MAX_DEPTH}")
    return int(depth)


_EDGE_CLASS_CACHE: dict[int, Any] = {}


def _edge_classes(system: SubstitutionSystem) -> Any:
    key = id(system)
    if key not in _EDGE_CLASS_CACHE:
        _EDGE_CLASS_CACHE[key] = edge_classes(system)
    return _EDGE_CLASS_CACHE[key]


def make_tiling(system: Any, spec_source: Mapping[str, Any] | None = None) -> SubstitutionTiling:
    """The tiling class that fits the system (similarity rules or keypoint placement)."""
    if isinstance(system, HatSystem):
        return HatTiling(system, spec_source=spec_source)
    if getattr(system, "kind", "") == "keypoint":
        return KeypointTiling(system, spec_source=spec_source)
    return SubstitutionTiling(system, spec_source=spec_source)
