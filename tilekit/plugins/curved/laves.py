"""LavesTiling: the dual of a uniform tiling of the sphere or the hyperbolic plane (§4.4 Laves
tilings carried to curved space): the Catalan solids as tilings of the sphere, and their
hyperbolic kin ([4.6.14], [3.3.3.3.3.3.3] = {7,3} ...), named ``[3.4.3.4]`` or ``V3.4.3.4``
after the vertex configuration of the uniform tiling they are dual to.

Everything comes from Wythoff's construction (wythoff.py) on the same triangle group: the tile
is the polygon round the generator G (a vertex of the uniform tiling) whose corners are the
centres of the faces at G (orbifold._star), and the group's elements place it, one tile per
image of G (the construction's cells times the cell corner's dihedral group, images of G told
apart on the construction's grid). The tile is isohedral by construction: one prototile, one
orbit; its incidence symbol (§5.3.1) comes from the group too: edges related by an element
fixing G share a label (one that reverses an edge leaves it undirected), and each label is
matched to the edge of the neighbouring tile that the element carrying G to its neighbour
across the edge brings onto it. ``group='rotations'`` takes the rotation subgroup only (tiles
without mirror symmetry, as Escher-like tiles want: their edges may be chiral), which is
isohedral unless the generator's stabiliser is trivial (the omnitruncations' duals: the
rotations split the tiles into two mirror-image orbits — the snub's dual is the chiral one).
The symbol is the one under the tiling's whole group, which is the construction's except where
Wythoff's construction gives the tiling only on a subgroup (the antiprisms, | 2 2 n on 22n,
whose whole group is 2*n; | 2 2 3, the octahedron, has *432): the elements fixing G then come
from the uniform tiling's vertex stabiliser (:func:`.orbifold.vertex_stabiliser`), so the
trapezohedra's kites keep their mirror. :func:`symbol_from_group` reads the symbol from any
such group, and the vertex-star tilings' duals (starlaves.py) use it too.

Escher-like tiles (§7.3): ``edges`` shapes the tile's edges as the curved isohedral tiles' option
does (a fundamental shape per label of the incidence symbol, EdgeShape text on the unit segment:
a J edge any curve, an S edge's half completed by the half-turn about its midpoint, I edges
straight; labels not named take the default shapes, damped until the tile is simple). The curves
go onto the tile through each edge's chart and onto the neighbours as the symbol's hops carry
them (:mod:`.shaped`, shared with isohedral.py), so every edge coincides with its partner.
Under a kaleidoscope's group *pqr every edge is an I edge (it lies on a mirror), so shapes need
``group=rotations`` (or a snub's dual), whose tiles are chiral: no hop or tile symmetry
reverses orientation; a trapezohedron under 2*n shapes its two S edges. Under the whole group or
its rotations the Laves tiles have no U edges (a U edge needs a mirror of the tile through an
edge's midpoint).

Isohedral types (issue 35, item 3; Grünbaum and Shephard's spherical isohedral tilings): on the
sphere a Laves topology is isohedral under every subgroup H of its whole group that is
transitive on its faces, and each H gives a type of its own, its incidence symbol read from H's
elements alone and its edges free as H allows. :func:`face_transitive_subgroups` finds them
(:mod:`.subgroups`: every subgroup of the finite group from its Cayley table, one per conjugacy
class, named by orbifold symbol), :func:`isohedral_types` lists the types, and ``group=<orbifold>``
(e.g. the cube ``| 2 2 3`` under ``332``: a square with a half-turn only, J edges; under ``3*2`` the
square's mirrors through its edge midpoints make U edges) places the tile by H: one element of H
per tile, the symbol and the shaped edges under H, so shaped edges still meet their partners.
The hyperbolic Laves tilings' groups are infinite: only ``full`` and ``rotations`` there.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property, lru_cache
from typing import Any

import numpy as np

from tilekit.edgeshapes import EdgeShape
from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.incidence import LABELS, IncidenceSymbol, edge_curves
from tilekit.plugins.curved import delaney, model, notation, subgroups, wythoff
from tilekit.plugins.curved.isohedral import colouring, hop_words, hops, patch_colours
from tilekit.plugins.curved.orbifold import (
    _first_of_each,
    _local_elements,
    _star,
    _unique,
    construction_stabiliser,
    same_point,
    vertex_stabiliser,
)
from tilekit.plugins.curved.patch import ModelPatch, ModelPrototile
from tilekit.plugins.curved.shaped import (
    edge_frames,
    edges_text,
    first_simple,
    parse_edges,
    shaped_outline,
)
from tilekit.plugins.curved.tiling import DEFAULT_SAMPLES, clipped
from tilekit.plugins.curved.uniform import DEFAULT_FACES, MAX_RADIUS, UniformTiling

#: Peak bytes per tile while a patch is made: the construction's cells (their breadth-first
#: candidates) per tile are more than a uniform tiling's per face, up to a cell per tile when G is
#: the cell's corner; measured with tracemalloc at 340-3900 for [4.6.14], [7^3], [5^4] and [3^7]
#: patches of 2·10^3 to 3·10^4 tiles (tests/plugins/test_curved_laves.py keeps it a bound).
LAVES_BYTES_PER_TILE = 5000

#: The groups a Laves tiling may be taken under by name: the construction's (``full``) or its
#: rotations; on the sphere also any face-transitive subgroup by its orbifold symbol
#: (:func:`face_transitive_subgroups`).
GROUPS = ("full", "rotations")
#: The characters of an orbifold symbol as a group option spells it (``×`` is read as ``x``).
_ORBIFOLD_CHARS = set("0123456789,*xo#")

_OPTIONS = ("configuration", "symbol", "group", "edges", "radius", "samples", "plane", "geometry")
#: ``laves: true`` tells a Laves spec from a uniform tiling's in the curved family.
_SPEC_KEYS = set(_OPTIONS) | {"laves", "name", "title"}


def _configuration(text: Any) -> str:
    """A configuration option with or without the Laves brackets or V (``[3.4.3.4]`` = ``3.4.3.4``)."""
    if not isinstance(text, str):
        raise ParameterError(f"configuration must be a vertex configuration like 3.4.3.4, got {str(text)[:40]}")
    cfg = notation.laves_configuration(text)
    return text if cfg is None else notation.dotted(cfg)


def _check_group(group: Any) -> str:
    """full, rotations, or an orbifold symbol (checked against the topology once it is known)."""
    if isinstance(group, str):
        text = group.strip().replace("×", "x")
        if text in GROUPS or (text and len(text) <= 20 and set(text) <= _ORBIFOLD_CHARS):
            return text
    raise ParameterError(f"group must be one of full, rotations or (on the sphere) the orbifold symbol of a "
                         f"face-transitive subgroup such as 332, got {str(group)[:40]}")


class LavesTiling(UniformTiling):
    """The dual of the uniform tiling with a given vertex configuration on the sphere or the
    hyperbolic plane: one prototile, placed by the triangle group (see the module). Named,
    configured and specified as the uniform tiling is (UniformTiling), with ``group`` besides."""

    OPTIONS = _OPTIONS
    bytes_per_tile = LAVES_BYTES_PER_TILE
    DEFINING = ("configuration", "symbol", "group")
    #: Set by __init__: the fundamental shape per label when ``edges`` was given, else None
    #: (the straight geodesic tile).
    edge_shapes: dict[str, EdgeShape] | None
    SPEC_KEYS = tuple(sorted(_SPEC_KEYS))
    SPEC_WHAT = "curved Laves"

    def __init__(self, configuration: str | None = None, *, symbol: str | None = None, group: str = "full",
                 edges: Mapping[str, EdgeShape | str] | str | None = None, radius: float | None = None,
                 samples: int = DEFAULT_SAMPLES, plane: str = "poincare", geometry: str | None = None,
                 name: str = "", title: str = "") -> None:
        self.group = _check_group(group)
        super().__init__(None if configuration is None else _configuration(configuration), symbol=symbol,
                         radius=radius, samples=samples, plane=plane, geometry=geometry, name=name, title=title)
        #: (|H|, 3, 3) the subgroup H named by an orbifold ``group``, else None (full, rotations)
        self.subgroup: np.ndarray | None = None
        if self.group not in GROUPS:
            if self.hyperbolic:
                raise ParameterError(f"[{self.configuration}] tiles the hyperbolic plane, whose group is infinite: "
                                     f"group must be full or rotations there, got {self.group}")
            subs = face_transitive_subgroups(self.symbol)
            if self.group not in subs:
                raise ParameterError(f"[{self.configuration}]: {self.group} is not a subgroup of "
                                     f"{self.symmetry.notation} transitive on its {self.faces} faces; valid groups: "
                                     f"{', '.join(subs)} (or full, rotations)")
            self.subgroup = subs[self.group]
        if self.group == "rotations" and self.symbol.form == "omni":
            raise ParameterError(f"[{self.configuration}] under the rotation group {self.symbol.group.lstrip('*')} has "
                                 "two tile orbits (the tile and its mirror image), so it is not isohedral; "
                                 "group=rotations applies to the duals of vertex, edge and snub forms (the chiral "
                                 "dual of an omnitruncation is the snub's, e.g. [3.3.3.3.4])")
        self.given_edges = parse_edges(edges) if edges is not None else None
        self.edge_shapes = None
        if self.given_edges is not None:
            # the default shapes bend less where the most tiles meet at a corner (angle 2π/q at
            # the sharpest), halved until the tile is simple; shapes given are never changed
            what = f"[{self.configuration}] under group {self.group} (incidence symbol {self.incidence_symbol})"
            self.edge_shapes, self._shaped = first_simple(
                self.tile_symbol, self.given_edges, what, min(1.0, 4.0 / max(self.valences)), self._shaped_tile,
                self.label_order)

    def euclidean_message(self) -> str:
        dotted = wythoff.uniform_configuration(self.symbol)
        return (f"[{dotted}] tiles the Euclidean plane: see the laves family (tilekit render '[{dotted}]'); the "
                "curved family draws the sphere and the hyperbolic plane")

    def default_name(self) -> str:
        base = f"[{notation.exponent(self.symbol.configuration or ())}]"
        return base if self.group == "full" else f"{base}-{self.group}"

    @property
    def rotations_only(self) -> bool:
        """Whether the group the tiles are taken under has rotations only: ``group=rotations``,
        or a full group without mirrors (a snub's, pqr), or a subgroup of proper motions."""
        if self.subgroup is not None:
            return bool((np.linalg.det(self.subgroup) > 0).all())
        return self.group == "rotations" or not self.symmetry.group.mirrors

    @property
    def construction_rotations(self) -> bool:
        """Whether the tiles are placed by the construction's rotations only (a snub's group,
        or ``group=rotations``): the construction's group is vertex-transitive either way."""
        return self.group == "rotations" or self.symbol.form == "snub"

    @cached_property
    def _local(self) -> tuple[np.ndarray, np.ndarray]:
        """(corners (k, 3): the centres of the faces at G, counter-clockwise round G starting
        with the first face of the star; L·L: the group's elements near G, proper ones first
        under group='rotations' only proper ones). Where the tiling's group is larger than the
        construction's (an antiprism's dual: 2*n against 22n), L·L times the tiling's
        stabiliser of G (:func:`.orbifold.vertex_stabiliser`), so the symbol is the one under
        the tiling's whole group. Under a subgroup H (an orbifold ``group``): H's elements, all of them."""
        c = self.construction
        local = _local_elements(c)
        frames, _sides = _star(c, local)
        centres = frames[:, :, 2]
        g = c.generator
        frame = c.space.frame(g, centres[0])
        inv = np.linalg.inv(frame)
        at_pole = centres @ inv.T
        angle = np.mod(np.arctan2(at_pole[:, 1], at_pole[:, 0]), 2 * np.pi)
        order = np.argsort(angle, kind="stable")
        corners = centres[order]
        if self.subgroup is not None:
            sub = self.subgroup
            return corners, sub[np.argsort(np.linalg.det(sub) < 0, kind="stable")]
        pair = np.matmul(local[:, None], local[None]).reshape(-1, 3, 3)
        if self.symmetry.index > 1:
            stab = vertex_stabiliser(c)
            pair = _unique(np.matmul(pair[:, None], stab[None]).reshape(-1, 3, 3))
        det = np.linalg.det(pair)
        pair = pair[np.argsort(det < 0, kind="stable")]  # proper elements first
        if self.rotations_only:
            pair = pair[np.linalg.det(pair) > 0]
        return corners, pair

    @cached_property
    def frame(self) -> np.ndarray:
        """The proper motion taking the pole to G and the x axis towards the first corner: the
        central tile's transform."""
        corners, _ = self._local
        return self.construction.space.frame(self.construction.generator, corners[0])

    @cached_property
    def corners(self) -> np.ndarray:
        """(k, 3): the prototile's corners, counter-clockwise round the pole (the tile at G
        carried back by :attr:`frame`)."""
        corners, _ = self._local
        out = corners @ np.linalg.inv(self.frame).T
        k = len(out)
        if k != len(self.symbol.configuration or ()):
            raise GeometryError(f"[{self.configuration}]: found {k} faces round the generator, not "
                                f"{len(self.symbol.configuration or ())}")
        return out

    @cached_property
    def valences(self) -> tuple[int, ...]:
        """Tiles meeting at each corner of the prototile, in order: the sides of the uniform
        tiling's face whose centre the corner is (the dual of the dual's vertex configuration)."""
        c = self.construction
        g = c.generator
        corners, _ = self._local
        sizes = {round(f.circumradius, 9): f.sides for f in c.face_types}
        out = []
        for pt in corners:
            d = float(c.space.distance(pt, g))
            near = min(sizes, key=lambda r: abs(r - d))
            out.append(sizes[near])
        return tuple(out)

    @cached_property
    def circumradius(self) -> float:
        """The largest distance from the tile's centre G to a corner."""
        return float(self.construction.space.distance(self.corners, self.construction.space.point(0.0, 0.0)).max())

    @cached_property
    def edge_lengths(self) -> np.ndarray:
        sp = self.construction.space
        return sp.distance(self.corners, np.roll(self.corners, -1, axis=0))

    # -- the incidence symbol (§5.3.1) ---------------------------------------------------
    @cached_property
    def stabiliser(self) -> np.ndarray:
        """(s, 3, 3): the group's elements fixing G (the tile's symmetries in the group)."""
        _, pair = self._local
        g = self.construction.generator
        fix = same_point(pair @ g, g)
        return _unique(pair[fix])

    @cached_property
    def incidence_symbol(self) -> IncidenceSymbol:
        """The tile's incidence symbol under the group (canonical form)."""
        return self.tile_symbol.canonical()

    @cached_property
    def tile_symbol(self) -> IncidenceSymbol:
        """The incidence symbol read from the tile's edge 0 (corner 0 to corner 1) counter-
        clockwise, edge i the tile's edge i, with the labels of the canonical form
        (:attr:`incidence_symbol`): the labels ``edges`` names."""
        corners, pair = self._local
        sp = self.construction.space
        g = self.construction.generator

        def hop(a: np.ndarray, b: np.ndarray) -> np.ndarray | None:
            found = pair[same_point(pair @ g, _reflect_across(sp, g, a, b))]
            return found[0] if len(found) else None

        return symbol_from_group(corners, self.stabiliser, hop, f"[{self.configuration}]")

    # -- shaped edges (Escher-like tiles) -------------------------------------------------
    @cached_property
    def frames(self) -> np.ndarray:
        """(k, 3, 3): each edge's frame at its midpoint, the x axis along the edge
        (:func:`.shaped.edge_frames`)."""
        return edge_frames(self.construction.space.sign, self.corners)

    def edge_curves(self) -> list[np.ndarray]:
        """Each edge's curve on the unit segment, (0,0) to (1,0), in the tile's counter-clockwise
        direction (:func:`tilekit.incidence.edge_curves` on :attr:`tile_symbol`); straight
        without ``edges``."""
        if self.edge_shapes is None:
            return [np.array([[0.0, 0.0], [1.0, 0.0]])] * len(self.corners)
        return edge_curves(self.tile_symbol, self.edge_shapes, self.label_order)

    @property
    def label_order(self) -> list[str]:
        """The labels in the canonical symbol's order: of two adjacent labels, the first owns
        the pair's shape, as in :attr:`incidence_symbol`."""
        return self.incidence_symbol.labels

    def _shaped_tile(self, shapes: Mapping[str, EdgeShape]) -> ModelPrototile:
        sp = self.construction.space
        geom = model.Geometry(sp.sign)
        curves = edge_curves(self.tile_symbol, shapes, self.label_order)
        pts, triangles = shaped_outline(geom, self.frames, self.edge_lengths, curves, self.samples,
                                        f"[{self.configuration}]", lambda i: self.tile_symbol.edges[i][0])
        return ModelPrototile.on_model(pts, sign=sp.sign, name=f"[{self.configuration}] tile", plane=self.plane,
                                       corners=tuple(range(len(pts))), triangles=triangles)

    @cached_property
    def motions(self) -> np.ndarray:
        """(k, 3, 3): the hops across the tile's edges in its own frame (:func:`.isohedral.hops`
        on :attr:`tile_symbol`): the neighbour across edge i is the tile moved by ``motions[i]``."""
        return hops(self.frames, self.tile_symbol)

    @cached_property
    def perfect_colouring(self) -> tuple[tuple[int, int], tuple[int, ...]]:
        """((a, b), φ per edge's hop): the least perfect colouring of the tiles (a homomorphism of
        the group onto Z_b or Z_a × Z_b, zero on the tile's symmetries; :func:`.isohedral.colouring`,
        with the relations read round the tile's corners), as the curved isohedral tiles take."""
        geom = model.Geometry(self.construction.space.sign)
        bound = 2 * self.circumradius + 1e-9 if self.hyperbolic else math.inf
        relations = hop_words(self.tile_symbol, self.motions, geom, bound, self.construction.edge_length)[2]
        return colouring(self.tile_symbol, relations)

    def _colours(self, mats: np.ndarray) -> np.ndarray:
        """The perfect colouring's colour of each tile (transforms ``mats``), by
        :func:`.isohedral.patch_colours` in the central tile's frame."""
        local = np.linalg.inv(self.frame) @ mats                    # the tiles in the central tile's frame
        return patch_colours(self.tile_symbol, self.motions, model.Geometry(self.construction.space.sign), local,
                             self.construction.edge_length, f"[{self.configuration}]", self.perfect_colouring)[1]

    # -- the Tiling interface ------------------------------------------------------------
    @cached_property
    def _proto(self) -> ModelPrototile:
        if self.edge_shapes is not None:
            return self._shaped
        sp = self.construction.space
        geom = model.Geometry(sp.sign)
        v = self.corners
        parts = []
        for i in range(len(v)):
            pair = np.array([v[i], v[(i + 1) % len(v)]])
            parts.append(model.sample_edges(geom, pair, float(self.edge_lengths[i]), self.samples)[: self.samples])
        pts = np.concatenate(parts)
        return ModelPrototile.on_model(pts, sign=sp.sign, name=f"[{self.configuration}] tile", plane=self.plane,
                                       corners=tuple(range(0, len(pts), self.samples)))

    @property
    def prototiles(self) -> list[ModelPrototile]:
        return [self._proto]

    def tiles_per_area(self) -> float:
        """Tiles (vertices of the uniform tiling) per unit area: one per generator's orbit point,
        so per triangle of *pqr one over the generator's stabiliser (the snub's group has two
        triangles per element)."""
        stab = construction_stabiliser(self.symbol) * (2 if self.symbol.form == "snub" else 1)
        return 1.0 / (stab * wythoff.triangle_area(self.symbol.orders))

    def _radius(self) -> float:
        return self.radius if self.radius is not None else default_radius(self.tiles_per_area(), self.circumradius,
                                                                          DEFAULT_FACES, MAX_RADIUS)

    def estimate_tiles(self, region: Any = None) -> float:
        """The sphere's face count; hyperbolic: tiles per area times the disc's area, the disc
        grown by twice the tile's circumradius."""
        if not self.hyperbolic:
            return float(self.faces)
        r = self._radius() + 2 * self.circumradius
        return 1.0 + self.tiles_per_area() * 2 * math.pi * (math.cosh(r) - 1)

    def group_elements(self) -> np.ndarray:
        """(n, 3, 3): one element of the group per tile (per image of G; proper ones where the
        group has one), every tile of the sphere, or those whose centre lies within the radius
        plus the circumradius (the disc of the radius is covered)."""
        c = self.construction
        self._check_size(self.estimate_tiles())
        if self.subgroup is not None:  # H's elements, one per image of G (transitive: every tile)
            _, sub = self._local
            return sub[_first_of_each(sub @ c.generator)]
        reach = None
        if self.hyperbolic:
            reach = self._radius() + self.circumradius
        g = c.generator
        pole = c.corners[0]
        cells = c.cells(None if reach is None else reach + float(c.space.distance(g, pole)) + c.cell_radius)
        stab = c.stabiliser
        n = c.orders[c.cell_corner]
        if self.construction_rotations:
            stab = stab[:n]
        # one element of the cell corner's group per image of G (G at the cell corner: just one),
        # proper ones first, so a cell brings each of its vertices once
        stab = stab[np.argsort(np.linalg.det(stab) < 0, kind="stable")]
        stab = stab[_first_of_each(stab @ g)]
        elems = np.matmul(cells[:, None], stab[None]).reshape(-1, 3, 3)
        elems = elems[np.argsort(np.linalg.det(elems) < 0, kind="stable")]  # proper ones first
        pts = elems @ g
        if reach is not None:
            near = c.space.distance(pts, pole) <= reach + 1e-12
            elems, pts = elems[near], pts[near]
        keep = wythoff.dedup(c._key_points(pts), c.edge_length)
        return elems[keep]

    def group_matrices(self) -> np.ndarray:
        """(|Γ|, 3, 3): every element of the group the tiles are taken under (the tiling's whole
        group, or its rotations), on the sphere, as O(3) matrices: the element placing each tile
        times the tile's stabiliser (a coset each). The trapezohedra's 2*n holds the 22n that
        Wythoff's construction gives and as many elements again: n mirrors and n rotary reflections."""
        if self.hyperbolic:
            raise ParameterError(f"[{self.configuration}] tiles the hyperbolic plane: its group is infinite")
        if self.subgroup is not None:
            return self.subgroup
        return _unique(np.matmul(self.group_elements()[:, None], self.stabiliser[None]).reshape(-1, 3, 3))

    def patch(self, region: Any = None) -> ModelPatch:
        """Every tile (sphere) or every tile whose centre (a vertex of the uniform tiling) lies
        within the radius plus the tile's circumradius, less those whose outline misses
        ``region``; colour: the tile's handedness (0 placed by a rotation, 1 by a reflection:
        the two halves of an omnitruncation's dual, all 0 where the tile has a mirror); with
        shaped edges the least perfect colouring (:attr:`perfect_colouring`), as the curved
        isohedral tiles are coloured."""
        elems = self.group_elements()
        mats = elems @ self.frame
        if self.edge_shapes is not None:
            colour = self._colours(mats)
        else:
            colour = (np.linalg.det(mats) < 0).astype(np.int64)
        patch = ModelPatch([self._proto], np.zeros(len(mats), dtype=np.int64), mats, colour=colour)
        return clipped(patch, region)

    # -- records and options -------------------------------------------------------------
    @property
    def faces(self) -> int:
        """Tiles on the sphere: the group's order over G's stabiliser (the uniform tiling's
        vertices)."""
        if self.hyperbolic:
            raise ParameterError(f"[{self.configuration}] tiles the hyperbolic plane: it has infinitely many tiles")
        order = self.symbol.group_order() // (2 if self.symbol.form == "snub" else 1)  # a snub's: the rotations
        return order // construction_stabiliser(self.symbol)

    def face_counts(self) -> dict[int, int]:
        """Tiles per number of sides on the sphere: all the tile's."""
        return {len(self.symbol.configuration or ()): self.faces}

    def group_notation(self) -> str:
        """The group the tiles and their incidence symbol are taken under, in orbifold notation:
        the tiling's symmetry group (``group=full``: *pqr, 2*n for an antiprism's dual) or its
        rotation subgroup (pqr, 22n), or the subgroup an orbifold ``group`` names."""
        if self.subgroup is not None:
            return self.group
        full = self.symmetry.group
        return (full.rotations() if self.group == "rotations" else full).notation

    @cached_property
    def delaney_symbol(self) -> delaney.Delaney:
        """The Delaney symbol of :attr:`tile_symbol` on the tile's topology (corner valences
        :attr:`valences`; :func:`.delaney.check_on`): it closes round every vertex, so the symbol
        tiles, and its orbifold (:meth:`symbol_orbifold`) is read from the combinatorics alone."""
        return delaney.check_on(self.tile_symbol, len(self.corners), self.valences)

    def symbol_orbifold(self) -> str:
        """The orbifold of the symbol's group read off its Delaney symbol (an independent
        reading of :meth:`group_notation`, which comes from the geometry)."""
        return delaney.orbifold_symbol(self.delaney_symbol, self.valences)

    def properties(self) -> dict[str, Any]:
        cfg = self.symbol.configuration or ()
        sym = self.incidence_symbol
        props: dict[str, Any] = {
            "periodic": self.hyperbolic,
            "k_hedral": 1,
            "k_isohedral": 1,
            "edge_to_edge": True,
            "laves": True,
            "geometry": self.kind,
            "topology": f"[{notation.exponent(cfg)}]",
            "dual": notation.exponent(cfg),
            "dual_configuration": self.configuration,
            "wythoff_symbol": str(self.symbol),
            "group": self.group,
            # Wythoff's construction's group (as the uniform records store it); the tiles and their
            # symbol are taken under symbol_group: the tiling's whole group or its rotations
            "construction_group": self.symbol.group,
            "symbol_group": self.group_notation(),
            "sides": [len(cfg)],
            "valences": ".".join(map(str, self.valences)),
            # the symbol under the construction's group (as the isohedral families store it: the
            # canonical form under both keys, so an incidence_symbol filter finds it)
            "incidence_symbol": str(sym),
            "canonical_symbol": str(sym),
            "edge_kinds": sym.edge_kinds(),
            "tile_symmetry": len(self.stabiliser),
            # the tiling's full group: the uniform tiling's (orbifold.py), which is the construction's
            # except for the antiprisms' duals (2*n, made on 22n; [3.3.3.3] is the cube, *432)
            "symmetry_group": self.symmetry.notation,
            "orbifold": self.symmetry.notation,
        }
        if not self.hyperbolic:
            props["faces"] = self.faces
            props["vertices"] = sum(self.symbol.face_counts().values())
        return props

    def describe(self) -> str:
        where = "the sphere" if not self.hyperbolic else "the hyperbolic plane (Poincaré disc)"
        count = f", {self.faces} faces" if not self.hyperbolic else ""
        return (f"[{self.configuration}]: the Laves tiling of {where} dual to the uniform tiling {self.configuration} "
                f"({self.symbol}){count}; one {len(self.corners)}-gon tile, group {self.group_notation()}, "
                f"incidence symbol {self.incidence_symbol} ({self.incidence_symbol.edge_kinds()} edges)")

    def options_help(self) -> str:
        own = super().options_help().splitlines()[2:]  # radius, geometry, drawing: the uniform tiling's
        return "\n".join([
            "--set configuration=C       the dual's vertex configuration, e.g. 3.4.3.4 (or [3.4.3.4], V3.4.3.4)",
            "--set symbol=S              instead: the dual's Wythoff symbol, e.g. '2 3 | 7'",
            "--set group=G               full (default: the tiling's group), rotations (chiral tiles), or on the "
            "sphere a face-transitive subgroup's orbifold symbol, e.g. 332 (tilekit laves-types NAME lists them)",
            "--set edges=JSON            edge shapes by label of the incidence symbol, e.g. "
            "'{\"a\": \"0.2,0.1:0.4,0.1\"}' (EdgeShape text; {} the default shapes)",
            *own,
        ])

    def carried(self, options: Mapping[str, Any]) -> dict[str, Any]:
        """group, and the edge shapes unless the tile changes (its labels name other edges)."""
        kept = None if set(self.DEFINING) & set(options) else self.spec_edges()
        return {"group": options.get("group", self.group), "edges": options.get("edges", kept)}

    def spec_edges(self) -> dict[str, str] | None:
        """The shapes as EdgeShape text per label (None: the straight tile)."""
        return edges_text(self.edge_shapes)

    def defining_spec(self) -> dict[str, Any]:
        out: dict[str, Any] = {"laves": True, **super().defining_spec()}
        if self.group != "full":
            out["group"] = self.group
        if self.edge_shapes is not None:
            out["edges"] = self.spec_edges()
        return out

    @classmethod
    def spec_options(cls, spec: Mapping[str, Any]) -> dict[str, Any]:
        if spec.get("laves", True) is not True:
            raise ParseError(f"curved Laves spec: laves must be true, got {str(spec.get('laves'))[:20]}")
        return {"group": spec.get("group", "full"), "edges": spec.get("edges")}


def default_radius(tiles_per_area: float, circumradius: float, tiles: int, max_radius: float) -> float:
    """The radius of a hyperbolic Laves patch of about ``tiles`` tiles: the disc holding that
    many, less the tile's circumradius (tiles reaching into the disc are drawn too), within 0..max_radius."""
    r = math.acosh(1 + tiles / (2 * math.pi * tiles_per_area))
    return float(min(max_radius, max(0.0, r - circumradius)))


def symbol_from_group(corners: np.ndarray, stabiliser: np.ndarray,
                      hop: Callable[[np.ndarray, np.ndarray], np.ndarray | None], what: str) -> IncidenceSymbol:
    """The incidence symbol (§5.3.1) of a tile with these corners (k, 3), counter-clockwise, in
    an isohedral tiling whose group's elements fixing the tile are ``stabiliser`` and where
    ``hop(a, b)`` is an element carrying the tile onto its neighbour across the edge from corner
    a to corner b (None: none found), read from edge 0 (corner 0 to 1), edge i the tile's edge i,
    labels in canonical order: edges related by the stabiliser share a label (one reversed onto
    itself is undirected), and each label meets the edge the hop carries onto it. Shared by
    the Laves tilings of Wythoff's construction and of the vertex-star tilings (starlaves.py)."""
    k = len(corners)

    # the tile's symmetries as edge maps: edge i (corner i to i + 1) goes to edge j forwards
    # (+1: start to start) or backwards (−1)
    def edge_map(m: np.ndarray, i: int, target: np.ndarray) -> tuple[int, int]:
        a, b = index_in(target, m @ corners[i]), index_in(target, m @ corners[(i + 1) % k])
        if a < 0 or b < 0:
            return -1, 0
        if b == (a + 1) % k:
            return a, 1
        if a == (b + 1) % k:
            return b, -1
        return -1, 0

    def index_in(target: np.ndarray, pt: np.ndarray) -> int:
        hit = np.flatnonzero(same_point(target, pt))
        return int(hit[0]) if len(hit) else -1

    labels: list[int | None] = [None] * k
    signs = [0] * k
    next_label = 0
    for i in range(k):
        if labels[i] is not None:
            continue
        lab = next_label
        next_label += 1
        undirected = False
        images: dict[int, int] = {}
        for s in stabiliser:
            j, sense = edge_map(s, i, corners)
            if j < 0:
                raise GeometryError(f"{what}: a symmetry of the tile does not map its edges")
            if j == i and sense < 0:
                undirected = True
            images.setdefault(j, sense)
        for j, sense in images.items():
            labels[j] = lab
            signs[j] = 0 if undirected else sense
    # adjacency: the element carrying the tile to its neighbour across edge i carries some edge
    # j of the tile onto edge i
    first = {}
    for i in range(k):
        first.setdefault(labels[i], i)
    adjacency: dict[int, tuple[int, int]] = {}
    for lab, i in first.items():
        a, b = corners[i], corners[(i + 1) % k]
        h = hop(a, b)
        if h is None:
            raise GeometryError(f"{what}: no element of the group carries the tile across its edge {i + 1}")
        found = None
        for j in range(k):
            aj, bj = h @ corners[j], h @ corners[(j + 1) % k]
            if same_point(aj[None], b)[0] and same_point(bj[None], a)[0]:
                found = (j, -1)  # the neighbour's edge j runs from b to a: against edge i
            elif same_point(aj[None], a)[0] and same_point(bj[None], b)[0]:
                found = (j, 1)
            if found:
                break
        if found is None:
            raise GeometryError(f"{what}: the neighbour across edge {i + 1} does not share it")
        j, along = found
        other = labels[j]
        if signs[i] == 0:
            adjacency[lab] = (other, 0)  # type: ignore[assignment]
        else:
            # the neighbour's arrow on the shared edge, as a sign along edge i; + when the two
            # arrows point in opposite directions (§5.2)
            theirs = signs[j] * along
            adjacency[lab] = (other, 1 if theirs != signs[i] else -1)  # type: ignore[assignment]
    edges = tuple((LABELS[lab], sg) for lab, sg in zip(labels, signs))  # type: ignore[index]
    adj = tuple((LABELS[adjacency[lab][0]], adjacency[lab][1]) for lab in sorted(adjacency))
    sym = IncidenceSymbol(edges, adj)
    sym.check()
    return sym.canonical_labelling()


def _reflect_across(sp: wythoff.Space, g: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """G's neighbour across the dual edge ab: G's mirror image in the geodesic through a and b
    (the uniform tiling's edge from G crosses the dual edge at right angles, and both its ends
    are one edge length from the crossing point)."""
    f, w = sp.mirror(a, b, g)
    return (np.eye(3) - 2.0 * np.outer(w, f)) @ g


# -- isohedral types under the subgroups (issue 35, item 3) -----------------------------------

@dataclass(frozen=True)
class IsohedralType:
    """One isohedral type of a spherical Laves topology: the face-transitive subgroup H it is
    taken under (``group``, its orbifold symbol; ``order`` |H|), the tile's incidence symbol under
    H (canonical), the tile's symmetries in H (``tile_symmetry``: |H| / faces), its edge kinds,
    and the other groups whose type has the same incidence symbol (``same_symbol``: a symbol
    alone does not tell them apart, so they are listed, not merged)."""

    group: str
    order: int
    incidence_symbol: str
    tile_symmetry: int
    edge_kinds: str
    same_symbol: tuple[str, ...]


@lru_cache(maxsize=64)
def _subgroups_of(symbol_text: str) -> tuple[tuple[str, np.ndarray], ...]:
    full = LavesTiling(symbol=symbol_text)
    mats = full.group_matrices()
    table = subgroups.cayley_table(mats)
    inv = subgroups.inverses(table)
    g = full.construction.generator
    fixing = np.flatnonzero(same_point(mats @ g, g))
    classes: dict[bytes, np.ndarray] = {}
    for sub in subgroups.subgroups(table):
        if len(sub) != full.faces * len(np.intersect1d(sub, fixing)):
            continue  # not transitive on the faces: |H| / |H ∩ Stab(G)| is the orbit of G's tile
        classes.setdefault(subgroups.conjugacy_key(table, inv, sub), sub)
    named: dict[str, list[np.ndarray]] = {}
    for sub in classes.values():
        m = mats[sub]
        m.setflags(write=False)  # shared by every tiling under that group (the cache's copy)
        named.setdefault(subgroups.orbifold_name(m), []).append(m)
    out = []
    for name, subs in sorted(named.items(), key=lambda kv: (-len(kv[1][0]), kv[0])):
        # two classes with one orbifold (not met on the Laves topologies, checked by the tests): numbered
        out += [(name if len(subs) == 1 else f"{name}#{k + 1}", m) for k, m in enumerate(subs)]
    return tuple(out)


def face_transitive_subgroups(symbol: wythoff.Symbol) -> dict[str, np.ndarray]:
    """The subgroups H of a spherical Laves tiling's whole group (the one ``group=full`` takes,
    as O(3) matrices in the construction's frame) that act transitively on its faces, one per
    conjugacy class in that group, by orbifold symbol (:func:`.subgroups.orbifold_name`),
    largest first (then by name): each is a tiling's isohedral group, the tile's stabiliser in it
    of order |H| / faces. The cube ``| 2 2 3``: *432, *332, 3*2, 432, 2*3, 332, 223, 3x."""
    if sum(Fraction(1, n) for n in symbol.orders) <= 1:
        raise ParameterError(f"{symbol} does not tile the sphere: its group is infinite, so it has no finite list "
                             "of subgroups")
    return dict(_subgroups_of(str(symbol)))


def isohedral_types(tiling: LavesTiling) -> list[IsohedralType]:
    """The isohedral types of a spherical Laves tiling's topology, one per face-transitive
    subgroup up to conjugacy (:func:`face_transitive_subgroups`), largest group first."""
    if tiling.hyperbolic:
        raise ParameterError(f"[{tiling.configuration}] tiles the hyperbolic plane: its isohedral types are not listed "
                             "(its group is infinite); group=full and group=rotations apply there")
    rows = []
    for name in face_transitive_subgroups(tiling.symbol):
        t = LavesTiling(symbol=str(tiling.symbol), group=name)
        sym = t.incidence_symbol
        rows.append((name, len(t.subgroup), str(sym), len(t.stabiliser), sym.edge_kinds()))
    return [IsohedralType(name, order, sym, stab, kinds,
                          tuple(other for other, _, s, _, _ in rows if s == sym and other != name))
            for name, order, sym, stab, kinds in rows]
