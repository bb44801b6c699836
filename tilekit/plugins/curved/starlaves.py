"""StarLavesTiling: the dual of a non-Wythoffian uniform tiling of the hyperbolic plane
(stars.py), the Laves tiling ``[3^3.6^2]`` of the vertex-star tiling 3.3.3.6.6 as laves.py's
are of the Wythoffian ones: face-transitive, one tile round each vertex of the uniform tiling.

The tile is the polygon on the centres of the faces at the pole, counter-clockwise (face i of
the star lies between its edges i and i + 1, so the tile's edge i, from corner i to i + 1,
crosses the star's edge i + 1). The uniform tiling's vertex motions (the development's words
in the pairing's motions g_i, one per vertex: :func:`.stars.develop`) place it, one tile per
vertex; each maps the star at the pole onto the star at its vertex, so the tile onto the tile
there. The group is the uniform tiling's whole group: the pairing's motions and the
symmetries fixing the pole that keep the tiling (:func:`.stars.tiling_stabiliser`); the
incidence symbol comes from them as for laves.py (:func:`.laves.symbol_from_group`: the
neighbour across the tile's edge i is the tile moved by g_{i+1}), and the group's orbifold is
read off the symbol's Delaney symbol on the tile's topology (corner valences: the star's face
sizes), checked against the tile's area (Gauss–Bonnet: −2πχ = area / |tile symmetry|).

``group='rotations'`` takes the group's orientation-preserving elements only: the proper words
in the g_i and the proper symmetries fixing the pole. The motions carrying the pole to a vertex
are one word times the stabiliser, so the rotations still reach every vertex exactly when the
stabiliser holds a reflection (a word and that word times it differ in orientation) or every
g_i is proper (then so is every word); otherwise they split the tiles into two mirror-image
orbits and the group is refused (:attr:`StarLavesTiling.rotations_transitive`). Under the
rotations a tile is placed by a proper motion (an improper word times a reflection of the
stabiliser) and the symbol is read with the proper stabiliser and proper hops.

Escher-like tiles (§7.3): ``edges`` shapes the tile's edges as laves.py's option does, on the
same pieces of :mod:`.shaped` (``parse_edges``, ``first_simple``, ``edge_frames``,
``shaped_outline``) and the curved isohedral tiles' hops and perfect colouring: a fundamental
shape per label of the incidence symbol that owns one (J, S), I edges (on a mirror of the
group) straight, so under the whole group an edge on a mirror is refused in one line naming the
labels that take shapes, and under the rotations every edge is J or S.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cached_property
from typing import Any

import numpy as np

from tilekit.edgeshapes import EdgeShape
from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.incidence import IncidenceSymbol, edge_curves
from tilekit.plugins.curved import delaney, model, notation, wythoff
from tilekit.plugins.curved.isohedral import hops, patch_colours
from tilekit.plugins.curved.laves import GROUPS, default_radius, symbol_from_group
from tilekit.plugins.curved.orbifold import same_point
from tilekit.plugins.curved.patch import ModelPatch, ModelPrototile
from tilekit.plugins.curved.shaped import (
    edge_frames,
    edges_text,
    first_simple,
    parse_edges,
    shaped_outline,
)
from tilekit.plugins.curved.stars import (
    DEFAULT_FACES,
    MAX_RADIUS,
    STAR_BYTES_PER_TILE,
    StarTiling,
    configured,
    develop,
    format_pairing,
    tiling_stabiliser,
)
from tilekit.plugins.curved.tiling import (
    DEFAULT_SAMPLES,
    CurvedTiling,
    clipped,
    drawing_spec,
    spec_table,
)

G = model.HYPERBOLIC_GEOMETRY
_OPTIONS = ("configuration", "pairing", "group", "edges", "radius", "samples", "plane")
_SPEC_KEYS = set(_OPTIONS) | {"laves", "name", "title"}


class StarLavesTiling(CurvedTiling):
    """The dual of :class:`.stars.StarTiling` (see the module): ``configuration`` the uniform
    tiling's (e.g. 3.3.3.6.6, or [3.3.3.6.6], V3.3.3.6.6), ``pairing`` its edge pairing
    (default: the first that closes up), ``group`` full or rotations, ``edges`` the edge shapes
    by label of the incidence symbol (None: the straight tile), ``radius`` the disc covered."""

    streams = False
    bytes_per_tile = STAR_BYTES_PER_TILE
    OPTIONS = _OPTIONS
    #: Options that name another tiling: configure() keeps the name and title without them.
    DEFINING = ("configuration", "group")
    #: Set by __init__: the fundamental shape per label when ``edges`` was given, else None.
    edge_shapes: dict[str, EdgeShape] | None

    def __init__(self, configuration: str, *, pairing: str | None = None, group: str = "full",
                 edges: Mapping[str, EdgeShape | str] | str | None = None, radius: float | None = None,
                 samples: int = DEFAULT_SAMPLES, plane: str = "poincare", name: str = "", title: str = "") -> None:
        if not isinstance(group, str) or group.strip() not in GROUPS:
            # the hyperbolic groups' other face-transitive subgroups are infinitely many: only
            # the whole group and its rotations are taken here (laves.py takes orbifolds on the sphere)
            raise ParameterError(f"group must be one of {', '.join(GROUPS)} for a vertex-star dual, got {str(group)[:40]}")
        self.group = group.strip()
        text = str(configuration)
        cfg = notation.laves_configuration(text)
        self.uniform = StarTiling(text if cfg is None else notation.dotted(cfg), pairing=pairing, radius=radius,
                                  samples=samples, plane=plane)
        self.star, self.pairing = self.uniform.star, self.uniform.pairing
        self.radius, self.samples, self.plane = self.uniform.radius, self.uniform.samples, self.uniform.plane
        self.family = "curved"
        self.kind = self.uniform.kind
        self.configuration = self.uniform.configuration
        self.name = name or self.default_name()
        self.title = title
        if self.group == "rotations" and not self.rotations_transitive:
            raise ParameterError(
                f"[{self.configuration}] under the rotations of its group {self.full_orbifold()} has two tile orbits "
                "(the tile and its mirror image: no symmetry fixing a tile reverses orientation, and a reflection "
                f"carries it to a neighbour), so it is not isohedral; group must be {GROUPS[0]} here "
                "(group=rotations applies e.g. to [3^3.6^2], [4^2.6^2])")
        self.edge_shapes = None
        if edges is not None:
            # as laves.py's: the default shapes bend less where the most tiles meet at a corner,
            # halved until the tile is simple; shapes given are never changed
            what = f"[{self.configuration}] under group {self.group} (incidence symbol {self.incidence_symbol})"
            self.edge_shapes, self._shaped = first_simple(
                self.tile_symbol, parse_edges(edges), what, min(1.0, 4.0 / max(self.valences)), self._shaped_tile,
                self.label_order)

    def default_name(self) -> str:
        base = f"[{notation.exponent(self.star.cfg)}]"
        return base if self.group == "full" else f"{base}-rotations"

    # -- the tile --------------------------------------------------------------------------
    @cached_property
    def corners(self) -> np.ndarray:
        """(d, 3): the centres of the faces at the pole, counter-clockwise."""
        return self.star.face_frames()[:, :, 2]

    @property
    def valences(self) -> tuple[int, ...]:
        """Tiles meeting at each corner: the sides of the face whose centre it is."""
        return self.star.cfg

    @cached_property
    def circumradius(self) -> float:
        return max(self.star.circumradius(n) for n in set(self.star.cfg))

    @cached_property
    def edge_lengths(self) -> np.ndarray:
        return wythoff.Space(-1).distance(self.corners, np.roll(self.corners, -1, axis=0))

    def tile_area(self) -> float:
        """(d − 2)π less the corner angles, 2π/n at a corner of valence n (the n tiles round a
        regular n-gon's centre are congruent)."""
        return (len(self.valences) - 2) * math.pi - sum(2 * math.pi / n for n in self.valences)

    # -- the group ---------------------------------------------------------------------------
    @cached_property
    def generators(self) -> np.ndarray:
        """(d, 3, 3): the pairing's motions g_i (g_i carries the pole to the far end of the
        star's edge i)."""
        return np.array([self.star.generator(i, j, s) for i, (j, s) in enumerate(self.pairing)])

    @cached_property
    def full_stabiliser(self) -> np.ndarray:
        """The tiling's symmetries fixing the pole (:func:`.stars.tiling_stabiliser`)."""
        return tiling_stabiliser(self.star, self.pairing)

    @cached_property
    def rotations_transitive(self) -> bool:
        """Whether the rotation subgroup reaches every tile (see the module): the stabiliser
        holds a reflection, or every g_i is proper."""
        return bool((np.linalg.det(self.full_stabiliser) < 0).any() or (np.linalg.det(self.generators) > 0).all())

    def _placing(self, mats: np.ndarray, rotations: bool) -> np.ndarray:
        """``mats`` (n, 3, 3), motions each carrying the pole to a vertex, as elements of the
        group: under the rotations an improper one times a reflection of the stabiliser (the
        same vertex, by a proper motion)."""
        if not rotations:
            return mats
        flip = np.linalg.det(mats) < 0
        if not flip.any():
            return mats
        mirrors = self.full_stabiliser[np.linalg.det(self.full_stabiliser) < 0]
        if not len(mirrors):
            raise GeometryError(f"[{self.configuration}]: no rotation carries the tile onto every tile")
        out = mats.copy()
        out[flip] = mats[flip] @ mirrors[0]
        return out

    @cached_property
    def stabiliser(self) -> np.ndarray:
        """The group's symmetries fixing the pole (the tile's symmetries in the group): the
        tiling's, or its proper ones under ``group=rotations``."""
        stab = self.full_stabiliser
        return stab if self.group == "full" else stab[np.linalg.det(stab) > 0]

    def _read_symbol(self, rotations: bool) -> IncidenceSymbol:
        """The incidence symbol under the whole group or its rotations, read from the tile's
        edge 0 (corner 0 to 1) by :func:`.laves.symbol_from_group`."""
        stab = self.full_stabiliser
        if rotations:
            stab = stab[np.linalg.det(stab) > 0]
        d = len(self.generators)

        def hop(a: np.ndarray, _b: np.ndarray) -> np.ndarray:
            i = int(np.flatnonzero(same_point(self.corners, a))[0])
            # the tile's edge i crosses the star's edge i + 1
            return self._placing(self.generators[(i + 1) % d][None], rotations)[0]

        return symbol_from_group(self.corners, stab, hop, f"[{self.configuration}]")

    @cached_property
    def tile_symbol(self) -> IncidenceSymbol:
        """The incidence symbol under the group, read from the tile's edge 0 (corner 0 to 1),
        with the canonical form's labels (the labels ``edges`` names)."""
        return self._read_symbol(self.group == "rotations")

    @cached_property
    def incidence_symbol(self) -> IncidenceSymbol:
        return self.tile_symbol.canonical()

    @cached_property
    def delaney_symbol(self) -> delaney.Delaney:
        """The symbol's Delaney symbol on the tile's topology (it closes round every vertex)."""
        return delaney.check_on(self.tile_symbol, len(self.corners), self.valences)

    def symbol_orbifold(self) -> str:
        """The orbifold of the group the tiles are taken under, read off the Delaney symbol."""
        return delaney.orbifold_symbol(self.delaney_symbol, self.valences)

    def full_orbifold(self) -> str:
        """The orbifold of the tiling's whole group (the symbol's under ``group=full``)."""
        if self.group == "full":
            return self.symbol_orbifold()
        sym = self._read_symbol(False)
        return delaney.orbifold_symbol(delaney.check_on(sym, len(self.corners), self.valences), self.valences)

    # -- shaped edges (Escher-like tiles) -----------------------------------------------------
    @property
    def label_order(self) -> list[str]:
        """The labels in the canonical symbol's order (the first of two adjacent labels owns
        the pair's shape)."""
        return self.incidence_symbol.labels

    @cached_property
    def frames(self) -> np.ndarray:
        """(d, 3, 3): each edge's frame at its midpoint (:func:`.shaped.edge_frames`)."""
        return edge_frames(-1, self.corners)

    def edge_curves(self) -> list[np.ndarray]:
        """Each edge's curve on the unit segment, counter-clockwise round the tile
        (:func:`tilekit.incidence.edge_curves`); straight without ``edges``."""
        if self.edge_shapes is None:
            return [np.array([[0.0, 0.0], [1.0, 0.0]])] * len(self.corners)
        return edge_curves(self.tile_symbol, self.edge_shapes, self.label_order)

    def _shaped_tile(self, shapes: Mapping[str, EdgeShape]) -> ModelPrototile:
        curves = edge_curves(self.tile_symbol, shapes, self.label_order)
        pts, triangles = shaped_outline(G, self.frames, self.edge_lengths, curves, self.samples,
                                        f"[{self.configuration}]", lambda i: self.tile_symbol.edges[i][0])
        return ModelPrototile.on_model(pts, sign=-1, name=f"[{self.configuration}] tile", plane=self.plane,
                                       corners=tuple(range(len(pts))), triangles=triangles)

    @cached_property
    def motions(self) -> np.ndarray:
        """(d, 3, 3): the hops across the tile's edges (:func:`.isohedral.hops`): the neighbour
        across edge i is the tile moved by ``motions[i]``."""
        return hops(self.frames, self.tile_symbol)

    def perfect_colours(self, mats: np.ndarray) -> tuple[tuple[int, int], np.ndarray]:
        """((a, b), colour per tile placed by ``mats``): the least perfect colouring of the
        tiles (:func:`.isohedral.patch_colours`)."""
        return patch_colours(self.tile_symbol, self.motions, G, mats, self.star.edge, f"[{self.configuration}]")

    # -- the Tiling interface --------------------------------------------------------------
    @cached_property
    def _proto(self) -> ModelPrototile:
        if self.edge_shapes is not None:
            return self._shaped
        v = self.corners
        parts = [model.sample_edges(G, np.array([v[i], v[(i + 1) % len(v)]]), float(self.edge_lengths[i]),
                                    self.samples)[: self.samples] for i in range(len(v))]
        pts = np.concatenate(parts)
        return ModelPrototile.on_model(pts, sign=-1, name=f"[{self.configuration}] tile", plane=self.plane,
                                       corners=tuple(range(0, len(pts), self.samples)))

    @property
    def prototiles(self) -> list[ModelPrototile]:
        return [self._proto]

    def tiles_per_area(self) -> float:
        """One tile per vertex of the uniform tiling: one over the tile's area."""
        return 1.0 / self.tile_area()

    def _radius(self) -> float:
        return self.radius if self.radius is not None else default_radius(self.tiles_per_area(), self.circumradius,
                                                                          DEFAULT_FACES, MAX_RADIUS)

    def estimate_tiles(self, region: Any = None) -> float:
        """Tiles per area times the disc's area, the disc grown by twice the circumradius."""
        r = self._radius() + 2 * self.circumradius
        return 1.0 + self.tiles_per_area() * 2 * math.pi * (math.cosh(r) - 1)

    def patch(self, region: Any = None) -> ModelPatch:
        """Every tile whose centre (a vertex of the uniform tiling) lies within the radius plus
        the circumradius (the disc of the radius covered), less those missing ``region``, each
        placed by an element of the group (a proper one under ``group=rotations``); colour: 1
        for a tile placed by a reflection, with shaped edges the least perfect colouring."""
        self.refuse_oversize(f"tiles of [{self.configuration}]", self.estimate_tiles(region),
                             "ask for a smaller radius (--set radius=R)")
        reach = self._radius() + self.circumradius
        verts, _, _ = develop(self.star, self.pairing, reach)
        verts = self._placing(verts[verts[:, 2, 2] <= math.cosh(reach) * (1 + 1e-9)], self.group == "rotations")
        if self.edge_shapes is not None:
            colour = self.perfect_colours(verts)[1]
        else:
            colour = (np.linalg.det(verts) < 0).astype(np.int64)
        patch = ModelPatch([self._proto], np.zeros(len(verts), dtype=np.int64), verts, colour=colour)
        return clipped(patch, region)

    def symmetries(self, reach: float) -> np.ndarray:
        """The uniform tiling's symmetries moving the pole at most ``reach`` (the viewer's)."""
        return self.uniform.symmetries(reach)

    # -- records and options ---------------------------------------------------------------
    def properties(self) -> dict[str, Any]:
        cfg = self.star.cfg
        sym = self.incidence_symbol
        full = self.full_orbifold()
        return {
            "periodic": True, "k_hedral": 1, "k_isohedral": 1, "edge_to_edge": True, "laves": True,
            "geometry": self.kind, "topology": f"[{notation.exponent(cfg)}]", "dual": notation.exponent(cfg),
            "dual_configuration": self.configuration, "construction": "vertex star", "wythoffian": False,
            "pairing": format_pairing(self.pairing), "group": self.group, "sides": [len(cfg)],
            "valences": ".".join(map(str, self.valences)), "incidence_symbol": str(sym),
            "canonical_symbol": str(sym), "edge_kinds": sym.edge_kinds(), "tile_symmetry": len(self.stabiliser),
            # each read off a Delaney symbol: the group the tiles and their symbol are taken
            # under, and the uniform tiling's whole group
            "symbol_group": self.symbol_orbifold(), "symmetry_group": full, "orbifold": full,
        }

    def describe(self) -> str:
        return (f"[{self.configuration}]: the Laves tiling of the hyperbolic plane dual to the non-Wythoffian uniform "
                f"tiling {self.configuration} (edge pairing {format_pairing(self.pairing)}); one "
                f"{len(self.corners)}-gon tile, group {self.symbol_orbifold()}, incidence symbol {self.incidence_symbol} "
                f"({self.incidence_symbol.edge_kinds()} edges)")

    def options_help(self) -> str:
        return "\n".join(["--set configuration=C       the dual's vertex configuration, e.g. 3.3.3.6.6 "
                          "(or [3.3.3.6.6], V3.3.3.6.6)",
                          "--set group=G               full (default: the uniform tiling's group) or rotations "
                          "(its proper motions: chiral tiles; refused where they make two tile orbits)",
                          "--set edges=JSON            edge shapes by label of the incidence symbol (its J and S "
                          "labels), e.g. '{\"a\": \"0.2,0.1:0.4,0.1\"}' ({} the default shapes)",
                          *self.uniform.options_help().splitlines()[1:]])

    def configure(self, **options: Any) -> StarLavesTiling:
        return configured(self, options)

    def carried(self, options: Mapping[str, Any]) -> dict[str, Any]:
        """group, and the edge shapes unless the tile's symbol may change (a new configuration,
        pairing or group: its labels name other edges)."""
        same_symbol = not {"configuration", "pairing", "group"} & set(options)
        return {"group": options.get("group", self.group),
                "edges": options.get("edges", edges_text(self.edge_shapes) if same_symbol else None)}

    def spec_edges(self) -> dict[str, str] | None:
        """The shapes as EdgeShape text per label (None: the straight tile)."""
        return edges_text(self.edge_shapes)

    def defining_spec(self) -> dict[str, Any]:
        """The spec's keys that say which tiling this is (drawing_spec adds the rest): group
        when not full, edges when shaped."""
        extra = {"group": self.group} if self.group != "full" else {}
        if self.edge_shapes is not None:
            extra["edges"] = self.spec_edges()
        return {"laves": True, "configuration": self.configuration, "pairing": format_pairing(self.pairing), **extra}

    def spec(self) -> dict[str, Any]:
        return drawing_spec(self.defining_spec(), self, self.default_name())

    @classmethod
    def spec_options(cls, spec: Mapping[str, Any]) -> dict[str, Any]:
        """group and edges from a spec (checked by __init__)."""
        if spec.get("laves", True) is not True:
            raise ParseError(f"curved vertex-star Laves spec: laves must be true, got {str(spec.get('laves'))[:20]}")
        return {"group": spec.get("group", "full"), "edges": spec.get("edges")}

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> StarLavesTiling:
        spec_table(spec, sorted(_SPEC_KEYS), "curved vertex-star Laves")
        if "configuration" not in spec:
            raise ParseError("curved vertex-star Laves spec needs a configuration, e.g. 3.3.3.6.6")
        return cls(spec["configuration"], pairing=spec.get("pairing"), radius=spec.get("radius"),
                   samples=spec.get("samples", DEFAULT_SAMPLES), plane=spec.get("plane", "poincare"),
                   name=str(spec.get("name", "")), title=str(spec.get("title", "")), **cls.spec_options(spec))
