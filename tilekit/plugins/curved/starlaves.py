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
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cached_property
from typing import Any

import numpy as np

from tilekit.errors import ParseError
from tilekit.incidence import IncidenceSymbol
from tilekit.plugins.curved import delaney, model, notation, wythoff
from tilekit.plugins.curved.laves import default_radius, symbol_from_group
from tilekit.plugins.curved.orbifold import same_point
from tilekit.plugins.curved.patch import ModelPatch, ModelPrototile
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
_OPTIONS = ("configuration", "pairing", "radius", "samples", "plane")
_SPEC_KEYS = set(_OPTIONS) | {"laves", "name", "title"}


class StarLavesTiling(CurvedTiling):
    """The dual of :class:`.stars.StarTiling` (see the module): ``configuration`` the uniform
    tiling's (e.g. 3.3.3.6.6, or [3.3.3.6.6], V3.3.3.6.6), ``pairing`` its edge pairing
    (default: the first that closes up), ``radius`` the disc covered."""

    streams = False
    bytes_per_tile = STAR_BYTES_PER_TILE
    OPTIONS = _OPTIONS

    def __init__(self, configuration: str, *, pairing: str | None = None, radius: float | None = None,
                 samples: int = DEFAULT_SAMPLES, plane: str = "poincare", name: str = "", title: str = "") -> None:
        text = str(configuration)
        cfg = notation.laves_configuration(text)
        self.uniform = StarTiling(text if cfg is None else notation.dotted(cfg), pairing=pairing, radius=radius,
                                  samples=samples, plane=plane)
        self.star, self.pairing = self.uniform.star, self.uniform.pairing
        self.radius, self.samples, self.plane = self.uniform.radius, self.uniform.samples, self.uniform.plane
        self.family = "curved"
        self.kind = self.uniform.kind
        self.configuration = self.uniform.configuration
        self.name = name or f"[{notation.exponent(self.star.cfg)}]"
        self.title = title

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

    @cached_property
    def stabiliser(self) -> np.ndarray:
        """The tiling's symmetries fixing the pole (the tile's symmetries in the group)."""
        return tiling_stabiliser(self.star, self.pairing)

    @cached_property
    def tile_symbol(self) -> IncidenceSymbol:
        """The incidence symbol read from the tile's edge 0 (corner 0 to 1)."""
        gens = [self.star.generator(i, j, s) for i, (j, s) in enumerate(self.pairing)]
        d = len(gens)

        def hop(a: np.ndarray, _b: np.ndarray) -> np.ndarray:
            i = int(np.flatnonzero(same_point(self.corners, a))[0])
            return gens[(i + 1) % d]  # the tile's edge i crosses the star's edge i + 1

        return symbol_from_group(self.corners, self.stabiliser, hop, f"[{self.configuration}]")

    @cached_property
    def incidence_symbol(self) -> IncidenceSymbol:
        return self.tile_symbol.canonical()

    @cached_property
    def delaney_symbol(self) -> delaney.Delaney:
        """The symbol's Delaney symbol on the tile's topology (it closes round every vertex)."""
        return delaney.check_on(self.tile_symbol, len(self.corners), self.valences)

    def symbol_orbifold(self) -> str:
        return delaney.orbifold_symbol(self.delaney_symbol, self.valences)

    # -- the Tiling interface --------------------------------------------------------------
    @cached_property
    def _proto(self) -> ModelPrototile:
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
        the circumradius (the disc of the radius covered), less those missing ``region``;
        colour: 1 for a tile placed by a reflection."""
        self.refuse_oversize(f"tiles of [{self.configuration}]", self.estimate_tiles(region),
                             "ask for a smaller radius (--set radius=R)")
        reach = self._radius() + self.circumradius
        verts, _, _ = develop(self.star, self.pairing, reach)
        verts = verts[verts[:, 2, 2] <= math.cosh(reach) * (1 + 1e-9)]
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
        group = self.symbol_orbifold()
        return {
            "periodic": True, "k_hedral": 1, "k_isohedral": 1, "edge_to_edge": True, "laves": True,
            "geometry": self.kind, "topology": f"[{notation.exponent(cfg)}]", "dual": notation.exponent(cfg),
            "dual_configuration": self.configuration, "construction": "vertex star", "wythoffian": False,
            "pairing": format_pairing(self.pairing), "group": "full", "sides": [len(cfg)],
            "valences": ".".join(map(str, self.valences)), "incidence_symbol": str(sym),
            "canonical_symbol": str(sym), "edge_kinds": sym.edge_kinds(), "tile_symmetry": len(self.stabiliser),
            # read off the Delaney symbol; the uniform tiling's whole group, as the symbol is under it
            "symbol_group": group, "symmetry_group": group, "orbifold": group,
        }

    def describe(self) -> str:
        return (f"[{self.configuration}]: the Laves tiling of the hyperbolic plane dual to the non-Wythoffian uniform "
                f"tiling {self.configuration} (edge pairing {format_pairing(self.pairing)}); one "
                f"{len(self.corners)}-gon tile, group {self.symbol_orbifold()}, incidence symbol {self.incidence_symbol} "
                f"({self.incidence_symbol.edge_kinds()} edges)")

    def options_help(self) -> str:
        return "\n".join(["--set configuration=C       the dual's vertex configuration, e.g. 3.3.3.6.6 "
                          "(or [3.3.3.6.6], V3.3.3.6.6)",
                          *self.uniform.options_help().splitlines()[1:]])

    def configure(self, **options: Any) -> StarLavesTiling:
        return configured(self, options)

    def spec(self) -> dict[str, Any]:
        return drawing_spec({"laves": True, "configuration": self.configuration,
                             "pairing": format_pairing(self.pairing)}, self, f"[{notation.exponent(self.star.cfg)}]")

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> StarLavesTiling:
        spec_table(spec, sorted(_SPEC_KEYS), "curved vertex-star Laves")
        if spec.get("laves", True) is not True:
            raise ParseError(f"curved vertex-star Laves spec: laves must be true, got {str(spec.get('laves'))[:20]}")
        if "configuration" not in spec:
            raise ParseError("curved vertex-star Laves spec needs a configuration, e.g. 3.3.3.6.6")
        return cls(spec["configuration"], pairing=spec.get("pairing"), radius=spec.get("radius"),
                   samples=spec.get("samples", DEFAULT_SAMPLES), plane=spec.get("plane", "poincare"),
                   name=str(spec.get("name", "")), title=str(spec.get("title", "")))
