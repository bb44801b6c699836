"""The isohedral engine: hops, aspect transforms, translation vectors and prototiles (§5.4).

For each tiling edge, the *hop* across it (§5.4.2) is the rigid motion carrying the tile onto
its neighbour: it maps the adjacent edge named by the incidence symbol onto the edge, as a
direct motion (translation, or half-turn about the edge centre, or a rotation about a vertex)
when the arrows say so, otherwise as an opposite motion (reflection in the edge, or a glide
reflection). Appendix A's rules compose hops into aspect transforms; translation vectors come
from the centroid rule. Every type then becomes a :class:`tilekit.PeriodicTiling`.
"""

from __future__ import annotations

import functools
import json
import math
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import shapely

from tilekit.colouring import Colouring
from tilekit.edgeshapes import (
    FLIP,
    IDENTITY,
    EdgeShape,
    apply_unit,
    parse_edge_option,
)
from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.geometry import Affine, snap_noise
from tilekit.incidence import IncidenceSymbol, shape_classes, symbol_table
from tilekit.incidence import label_curves as _label_curves
from tilekit.incidence import unit_orientation as _unit_orientation
from tilekit.plugins.isohedral.properties import type_properties
from tilekit.plugins.isohedral.templates import (
    Parameterization,
    Template,
    get_template,
    load_parameterizations,
    topology_valences,
)
from tilekit.polygon import signed_area
from tilekit.schema import Field, check, shown
from tilekit.symmetry import SymmetryGroup, absolute_tolerance, group_from_maps
from tilekit.symmetry import is_perfect_colouring as shared_is_perfect_colouring
from tilekit.tiling import Patch, PeriodicTiling, Prototile

FAMILY = "isohedral"


# --------------------------------------------------------------------------- geometry helpers


def edge_frames(verts: np.ndarray) -> np.ndarray:
    """(n, 3, 3): the direct similarity taking (0,0)-(1,0) onto edge i (P_i -> P_i+1)."""
    p = np.asarray(verts, dtype=float)
    q = np.roll(p, -1, axis=0)
    d = q - p
    out = np.zeros((len(p), 3, 3))
    out[:, 0, 0] = d[:, 0]
    out[:, 0, 1] = -d[:, 1]
    out[:, 1, 0] = d[:, 1]
    out[:, 1, 1] = d[:, 0]
    out[:, :2, 2] = p
    out[:, 2, 2] = 1.0
    return out


def laves_polygon(topology: str) -> np.ndarray:
    """The Laves tile of a topological type, counter-clockwise (§4.2, §5.2).

    Its vertices are the centres of the regular polygons around a vertex of the dual
    Archimedean tiling (unit edges), so the valence of Laves vertex j is the j-th polygon's.
    """
    pts = []
    ang = 0.0
    for p in topology_valences(topology):
        interior = math.pi * (p - 2) / p
        radius = 1.0 / (2.0 * math.sin(math.pi / p))
        mid = ang + interior / 2
        pts.append((radius * math.cos(mid), radius * math.sin(mid)))
        ang += interior
    if abs(ang - 2 * math.pi) > 1e-9:
        raise ParameterError(f"topology {topology!r}: the polygons' angles do not fill a vertex")
    return np.array(pts)


# --------------------------------------------------------------------------- the engine


@dataclass(frozen=True)
class UnitProgram:
    """Appendix A's rules of one type compiled to indices: rule r multiplies the transform of
    ``base[r]`` (an earlier result) by the hops ``hops[r]`` (0-based edges); results are the
    aspects in the template's order, then v1 and v2. Compiled once per type."""

    base: tuple[int, ...]
    hops: tuple[np.ndarray, ...]
    slot: tuple[int, ...]  # where rule r's result goes
    aspects: int


@functools.cache
def unit_program(template: Template) -> UnitProgram:
    """The compiled :class:`UnitProgram` of ``template`` (cached per type)."""
    names = list(template.aspects) + ["v1", "v2"]
    slot_of = {nm: i for i, nm in enumerate(names)}
    return UnitProgram(
        base=tuple(slot_of[rule.base] for rule in template.rules),
        hops=tuple(np.array(rule.hops, dtype=np.int64) - 1 for rule in template.rules),
        slot=tuple(slot_of[rule.target] for rule in template.rules),
        aspects=len(template.aspects),
    )


class HopEngine:
    """Hops and symmetry data of one incidence symbol at one set of tiling vertices.

    Edge i (label x, sign s) is adjacent to label y with sign t. The neighbour across edge i
    presents its edge j, the *first* edge labelled y (Appendix A's rules assume this choice:
    when the tile has symmetries, another choice changes the hop by a tile symmetry and the
    rules then walk across different edges). With T_k the similarity taking the unit segment
    onto edge k, the hop is ``H_i = T_i O T_j^-1`` where O is the half-turn about (1/2, 0)
    for a direct hop (t = s * s_j) and the mirror in the x axis otherwise (always for
    undirected edges, whose neighbour is a mirror image).
    """

    def __init__(self, symbol: IncidenceSymbol, verts: np.ndarray) -> None:
        self.symbol = symbol
        self.verts = np.asarray(verts, dtype=float)
        table = symbol_table(symbol)
        self.partner: list[int] = table.partner.tolist()
        self.orientation: list[np.ndarray] = list(table.orientation)  # O in H_i = T_i O S_j
        self.frames = edge_frames(self.verts)
        self.inverse_frames = Affine.inverse(self.frames)
        self.hops = self.frames @ table.orientation @ self.inverse_frames[table.partner]

    def unit_orientation(self, i: int) -> np.ndarray:
        """O_i: how edge i's curve sits relative to its label's curve (FLIP for reversed arrows)."""
        return _unit_orientation(self.symbol, i)

    def tile_symmetries(self) -> np.ndarray:
        """(s, 3, 3): the isometries of the tiling polygon that preserve labels and arrows."""
        out = []
        for shift, reflect in self.symbol.tile_symmetries():
            m = self.frames[shift] @ (FLIP if reflect else IDENTITY) @ self.inverse_frames[0]
            out.append(m)
        return np.stack(out)

    def label_curves(self, shapes: Mapping[str, EdgeShape]) -> dict[str, np.ndarray]:
        """Level 1 and 2 of the edge model: the curve of every label, from (0,0) to (1,0)."""
        return _label_curves(self.symbol, shapes)

    def outline(self, shapes: Mapping[str, EdgeShape]) -> tuple[np.ndarray, tuple[int, ...], list[np.ndarray]]:
        """Level 3: the prototile outline, the indices of the tiling vertices in it, and edge curves."""
        curves = self.label_curves(shapes)
        parts = []
        corners = []
        edge_paths = []
        count = 0
        for i, (label, _) in enumerate(self.symbol.edges):
            local = apply_unit(self.unit_orientation(i), curves[label])
            pts = local @ self.frames[i][:2, :2].T + self.frames[i][:2, 2]
            edge_paths.append(pts)
            corners.append(count)
            parts.append(pts[:-1])
            count += len(pts) - 1
        return np.vstack(parts), tuple(corners), edge_paths


def compute_unit(template: Template, verts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, HopEngine]:
    """Aspect transforms (m, 3, 3) and translation vectors v1, v2 from the template's rules."""
    engine = HopEngine(template.symbol, verts)
    program = unit_program(template)
    results = np.zeros((program.aspects + 2, 3, 3))
    results[0] = np.eye(3)
    for base, hops, slot in zip(program.base, program.hops, program.slot):
        m = results[base]
        for h in hops:
            m = m @ engine.hops[h]
        results[slot] = m
    aspects = results[: program.aspects]
    centre = verts.mean(axis=0)
    v1, v2 = (Affine.apply(m, verts).mean(axis=0) - centre for m in results[program.aspects:])
    return snap_noise(aspects, 1e-10), snap_noise(v1, 1e-10), snap_noise(v2, 1e-10), engine


def tile_outlines(patch: Patch, prototile: int = 0) -> np.ndarray:
    """(n, k, 2) outlines of the patch's tiles of one prototile (one batched transform)."""
    idx = np.flatnonzero(patch.prototile == prototile)
    return Affine.apply(patch.transform[idx], patch.prototiles[prototile].outline)


# --------------------------------------------------------------------------- the tiling


#: Largest |parameter| accepted (the tiling vertex parameters are O(1) shape values).
MAX_PARAM = 1e6


def _param_values(name: str, params: Any) -> tuple[float, ...]:
    """Tiling vertex parameters as floats, or a ParameterError naming the first that is not
    a number (a string, a list, None, an integer too large for a float)."""
    if isinstance(params, str | bytes) or not isinstance(params, Sequence | np.ndarray):
        raise ParameterError(f"{name}: params {shown(params)} must be a list of numbers")
    out = []
    for p in params:
        if isinstance(p, bool) or not isinstance(p, numbers.Real):
            raise ParameterError(f"{name}: parameter {shown(p)} is not a number")
        try:
            out.append(float(p))
        except OverflowError:
            raise ParameterError(f"{name}: parameter {shown(p)} is too large (within ±{MAX_PARAM:g})") from None
    return tuple(out)


class IsohedralTiling(PeriodicTiling):
    """A tiling of one of the 93 isohedral types with given parameters, edge shapes and colouring.

    ``IsohedralTiling("IH16", params=[0.3], edges={"b": EdgeShape(...)})``. Unmarked types
    are built from their Appendix A template; the 12 marked types are drawn as the Laves tile
    of their topology with a marking.
    """

    def __init__(
        self,
        ih: str | int,
        params: Sequence[float] | None = None,
        edges: Mapping[str, EdgeShape] | None = None,
        colouring: Colouring | str | None = None,
        check: bool | None = None,
    ) -> None:
        self.template = get_template(ih)
        t = self.template
        if t.marked:
            raise ParameterError(
                f"{t.name} can only be realised with marked tiles; build it with marked_tiling('{t.name}')"
            )
        self.parameterization: Parameterization = load_parameterizations()[t.parameterization or ""]
        tv = self.parameterization
        if params is None:
            params = tv.default
        params = _param_values(t.name, params)
        if len(params) != tv.parameters:
            raise ParameterError(
                f"{t.name} takes {tv.parameters} parameter(s) ({t.parameterization}), got {len(params)}"
                + (f"; default {list(tv.default)}" if tv.parameters else "")
            )
        if not all(math.isfinite(p) for p in params):
            raise ParameterError(f"{t.name}: parameters {list(params)} must be finite numbers")
        if any(abs(p) > MAX_PARAM for p in params):
            raise ParameterError(
                f"{t.name}: parameters {list(params)} must lie within ±{MAX_PARAM:g} (tiling vertex "
                "parameters are of the tile's own size; larger ones only overflow)"
            )
        self.params = params
        self.edge_shapes: dict[str, EdgeShape] = {}
        classes = shape_classes(t.symbol)
        adj = t.symbol.adjacent_map()
        for label, shape in (edges or {}).items():
            if label not in t.symbol.labels:
                raise ParameterError(
                    f"{t.name} has no edge label {label!r}; its labels are {', '.join(t.symbol.labels)}"
                )
            if t.symbol.label_kind(label) == "I":
                raise ParameterError(f"{t.name}: edges labelled {label!r} are I edges and must stay straight")
            rep = label if label in classes else adj[label][0]
            if rep != label:
                # the shape was given for the partner label: carry it over to the class's own label
                shape = _transfer_shape(t.symbol, label, rep, shape, tv, params)
            self.edge_shapes[rep] = shape
        verts = self.tiling_vertices()
        self._check_polygon(verts)
        aspects, v1, v2, engine = compute_unit(t, verts)
        self.engine = engine
        outline, corners, paths = engine.outline(self.edge_shapes)
        self.edge_paths = paths
        self._check_outline(paths)
        proto = Prototile(outline, name=t.name, corners=corners, edge_labels=_symbol_labels(t.symbol, outline, corners))
        if isinstance(colouring, str):
            colouring = Colouring.parse(colouring)
        if colouring is not None and not isinstance(colouring, Colouring):
            raise ParameterError(f"{t.name}: colouring {colouring!r} is not text like '(1 2)(2 1)(2 1)'")
        col = colouring or t.colouring
        super().__init__(
            [proto],
            np.zeros(len(aspects), dtype=np.int64),
            aspects,
            v1,
            v2,
            col,
            np.arange(len(aspects)),
            family=FAMILY,
            name=t.name,
        )
        if check is None:
            check = bool(self.edge_shapes) or self.params != tuple(tv.default)
        if check:
            self.check_overlaps()

    # geometry ----------------------------------------------------------------------
    def tiling_vertices(self) -> np.ndarray:
        """The tiling polygon's vertices, numbered as the incidence symbol's edges (§5.4.1)."""
        verts = self.parameterization.evaluate(self.params)
        return np.roll(verts, -self.template.edge_offset, axis=0)

    @property
    def symbol(self) -> IncidenceSymbol:
        return self.template.symbol

    @property
    def prototile(self) -> Prototile:
        return self.prototiles[0]

    def _param_names(self, edge: int) -> str:
        """The parameters on which tiling edge ``edge``'s two vertices depend."""
        tv = self.parameterization
        k = tv.vertices
        off = self.template.edge_offset
        rows = []
        for v in (edge, edge + 1):
            idx = (v + off) % k
            rows += [tv.coefficients[2 * idx, :-1], tv.coefficients[2 * idx + 1, :-1]]
        used = [f"v{p}={self.params[p]:g}" for p in range(tv.parameters) if any(abs(r[p]) > 0 for r in rows)]
        return ", ".join(used) if used else "no parameter"

    def _check_polygon(self, verts: np.ndarray) -> None:
        t = self.template
        n = len(verts)
        scale = max(float(np.ptp(verts, axis=0).max()), 1e-12)
        lengths = np.linalg.norm(np.roll(verts, -1, axis=0) - verts, axis=1)
        for i in range(n):
            if lengths[i] < 1e-7 * scale:
                raise ParameterError(
                    f"{t.name}: parameters {list(self.params)} make tiling edge {i + 1} degenerate "
                    f"(zero length; it depends on {self._param_names(i)}) - the tiling would change type (§5.4.5)"
                )
        poly = shapely.Polygon(verts)
        if signed_area(verts) <= 0 or not poly.is_valid:
            raise ParameterError(
                f"{t.name}: parameters {list(self.params)} make the tiling polygon self-intersecting or "
                f"inside out; try values near the default {list(self.parameterization.default)}"
            )

    def _check_outline(self, paths: list[np.ndarray]) -> None:
        t = self.template
        lines = [shapely.LineString(p) for p in paths]
        n = len(lines)
        for i, line in enumerate(lines):
            if not line.is_simple:
                raise ParameterError(
                    f"{t.name}: the shape of edge {i + 1} (label {t.symbol.edges[i][0]!r}) crosses itself"
                )
        for i in range(n):
            for j in range(i + 1, n):
                inter = lines[i].intersection(lines[j])
                if inter.is_empty:
                    continue
                allowed = []
                if j == i + 1:
                    allowed.append(shapely.Point(paths[i][-1]))
                if i == 0 and j == n - 1:
                    allowed.append(shapely.Point(paths[0][0]))
                rest = inter
                for pt in allowed:
                    rest = rest.difference(pt.buffer(1e-9))
                if not rest.is_empty:
                    raise ParameterError(
                        f"{t.name}: edge {i + 1} (label {t.symbol.edges[i][0]!r}) and edge {j + 1} "
                        f"(label {t.symbol.edges[j][0]!r}) cross - the tile would be self-intersecting; "
                        "use a smaller edge shape"
                    )

    def check_overlaps(self) -> None:
        """GeometryError if tiles of the unit and its 8 neighbour units overlap (§5.4.5)."""
        unit = self.unit()
        ring = [
            unit.transformed(Affine.translation(*(a * self.v1 + b * self.v2)))
            for a in (-1, 0, 1)
            for b in (-1, 0, 1)
        ]
        report = Patch.concat(ring).validate()
        if report.overlaps:
            inter = max(area for _, _, area in report.overlaps)
            raise GeometryError(
                f"{self.name}: with parameters {list(self.params)} and edge shapes "
                f"{ {k: v.to_text() for k, v in self.edge_shapes.items()} } neighbouring tiles overlap "
                f"(area {inter:.3g}); use smaller edge shapes or parameters nearer the default"
            )

    # Tiling API ----------------------------------------------------------------------
    def patch(self, region: Any) -> Patch:
        """Tiles covering ``region`` by §3.4 replication (PeriodicTiling), transforms snapped.

        Transforms are rounded to 1e-12 so that tiles sharing an edge share its coordinates
        bit for bit; GEOS overlays of nearly-but-not-exactly coincident edges are not robust.
        """
        out = super().patch(region)
        out.transform = snap_noise(out.transform, 0.0, decimals=12)
        out._geoms = None
        return out

    def describe(self) -> str:
        t = self.template
        lines = [t.text(), ""]
        lines.append(f"edge kinds {t.symbol.edge_kinds()}   canonical symbol {t.symbol.canonical()}")
        if self.parameterization.parameters:
            lines.append(
                "parameters " + ", ".join(f"v{i}={p:g}" for i, p in enumerate(self.params))
                + f" (default {', '.join(f'{p:g}' for p in self.parameterization.default)})"
            )
        classes = shape_classes(t.symbol)
        if classes:
            lines.append(
                "edge shapes (--edge LABEL=x,y:...:1,0): "
                + ", ".join(f"{c} ({t.symbol.label_kind(c)})" for c in classes)
            )
        return "\n".join(lines)

    def options_help(self) -> str:
        return "\n".join([
            "--param X[,X...]       the type's tiling vertex parameters (tilekit show IHn lists them)",
            "--edge b=x,y:x,y:...   an edge shape for a label (end points (0,0), (1,0) optional)",
            "--set colouring=(c..)(p..)(q..)   a colouring of §5.4.3",
            "--set split=S,T[;x,y:...:1,0]     split every tile in two by a path from boundary position S to T",
            "--set split_colour=piece|tile|class   colour a split tiling by piece (default), base tile or class",
            "                       (edge index + fraction; the path in the frame of the chord S -> T)",
        ])

    def configure(self, **options: Any) -> PeriodicTiling:
        """A new tiling with ``params`` (floats), ``edges`` ('b=x,y:...'), ``colours``/``colouring``;
        with ``split`` ('S,T;PATH', :mod:`.split`) the dihedral tiling of the new tile split in two."""
        if "split_colour" in options and "split" not in options:
            raise ParameterError(f"{self.name}: split_colour applies to a split tiling; give split=S,T too")
        if "split" in options:
            # start-up cost: the split tiling is loaded only when a split is asked for
            from tilekit.plugins.isohedral.split import with_split

            split = options.pop("split")
            colour = options.pop("split_colour", None)
            return with_split(self.configure(**options), split, colour)
        params = self.params
        edges = dict(self.edge_shapes)
        colouring: Colouring | None = self.colouring
        for key, value in options.items():
            if key == "params":
                if value is None:
                    continue
                if isinstance(value, str):  # --set params=0.1,0.2
                    value = [v for v in value.split(",") if v.strip()]
                try:
                    params = tuple(float(v) for v in value)
                except (TypeError, ValueError, OverflowError):
                    raise ParameterError(f"{self.name}: params {shown(value)} are not numbers") from None
            elif key == "edges":
                for item in [value] if isinstance(value, str) else value or ():
                    if isinstance(item, str):
                        label, shape = parse_edge_option(item)
                    elif isinstance(item, tuple) and len(item) == 2 and isinstance(item[1], EdgeShape):
                        label, shape = item
                    else:
                        raise ParameterError(f"{self.name}: edge {item!r} is not 'LABEL=x,y:x,y:...'")
                    edges[label] = shape
            elif key in ("colours", "colouring"):
                if not isinstance(value, str | Colouring):
                    raise ParameterError(f"{self.name}: colouring {value!r} is not text like '(1 2)(2 1)(2 1)'")
                colouring = Colouring.parse(value) if isinstance(value, str) else value
            else:
                raise ParameterError(
                    f"{self.name} does not take option {key!r}; valid: params, edges, colouring, split, split_colour"
                )
        return IsohedralTiling(self.template.ih, params, edges, colouring)

    def spec(self) -> dict[str, Any]:
        out: dict[str, Any] = {"ih": self.template.ih, "params": list(self.params)}
        if self.edge_shapes:
            out["edges"] = {k: v.to_text() for k, v in self.edge_shapes.items()}
        if self.colouring != self.template.colouring:
            out["colouring"] = str(self.colouring)
        return out

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> IsohedralTiling:  # type: ignore[override]
        """An unmarked type from its spec (:func:`tilekit.plugins.isohedral.spec.tiling_from_spec`
        also builds the marked ones)."""
        ih = _spec_ih(spec)
        if get_template(ih).marked:
            raise ParameterError(f"IH{ih} is a marked type; build it with tilekit.plugins.isohedral.spec.tiling_from_spec")
        return unmarked_from_spec(spec)

    def properties(self) -> dict[str, Any]:
        """The type's catalogue properties; colour facts follow this tiling's own colouring."""
        props = dict(type_properties(self.template.ih))
        if self.colouring != self.template.colouring:
            props["colours"] = self.colouring.colours
            props["perfect_colouring"] = is_perfect_colouring(self)
        return props


def _transfer_shape(
    symbol: IncidenceSymbol, label: str, rep: str, shape: EdgeShape, tv: Parameterization, params: tuple
) -> EdgeShape:
    """A shape given for ``label`` expressed as the fundamental shape of its partner ``rep``.

    The partner's curve is O_j O O_i applied to the class curve (see HopEngine.label_curves);
    these unit maps are involutions, so the inverse applies them in the opposite order. For U
    labels the map is the mirror in the edge line, which acts on the free half alike.
    """
    engine = HopEngine(symbol, tv.evaluate(params)[: len(symbol)])
    i = next(k for k, (lab, _) in enumerate(symbol.edges) if lab == rep)
    j = engine.partner[i]
    c = apply_unit(engine.unit_orientation(j), np.asarray(shape.points))
    c = apply_unit(engine.orientation[i], c)
    c = apply_unit(engine.unit_orientation(i), c)
    return EdgeShape(c, shape.smooth)


#: An isohedral spec, as the catalogue stores it and spec files and the web API give it
#: (``null`` for an optional field means its default).
SPEC = Field("table", fields={
    "ih": Field("ref", required=True, missing="'ih' is missing; give a type 1..93 or a name like 'IH16'"),
    "params": Field("list", items=Field("number"), length=(0, 16)),
    "edges": Field("table", values=Field("str")),
    "colouring": Field("str"),
    "split": Field("table", values=Field("any"),  # its fields are checked by split.checked_split
                   error='split {value!r} is not an object like {{"ends": [0.5, 3.5], "path": "0,0:0.5,0.1:1,0"}}'),
})


def checked_spec(spec: Any) -> dict[str, Any]:
    """``spec`` checked against :data:`SPEC` (types, finite numbers), or one ParseError."""
    if not isinstance(spec, Mapping):
        raise ParseError(f'an isohedral spec is a JSON object like {{"ih": 16, "params": [0.3]}}, not {shown(spec)}')
    return check(SPEC, {k: v for k, v in spec.items() if v is not None}, "isohedral spec")


def _spec_ih(spec: Mapping[str, Any]) -> Any:
    return checked_spec(spec)["ih"]


def unmarked_from_spec(spec: Mapping[str, Any]) -> IsohedralTiling:
    """An unmarked isohedral tiling from ``{"ih": 16, "params": [...], "edges": {...}}``."""
    spec = checked_spec(spec)
    t = get_template(spec["ih"])
    edges = {k: EdgeShape.parse(v) for k, v in spec.get("edges", {}).items()}
    return IsohedralTiling(t.ih, spec.get("params"), edges, spec.get("colouring"))


def _symbol_labels(symbol: Any, outline: Any, corners: Any) -> tuple[str, ...] | None:
    """Per outline segment, the incidence-symbol label of the tiling edge it belongs to
    (``a+``, ``b-``, ``c``), for ``tilekit render --labels``; None if the outline is not
    counter-clockwise with one corner per symbol edge."""
    pts = np.asarray(outline, dtype=float)
    if corners is None or len(corners) != len(symbol.edges) or signed_area(pts) <= 0:
        return None
    text = [lab + {1: "+", -1: "-", 0: ""}[sg] for lab, sg in symbol.edges]
    out = []
    for i in range(len(pts)):
        e = max(k for k, c in enumerate(corners) if c <= i) if i >= corners[0] else len(corners) - 1
        out.append(text[e])
    return tuple(out)


# --------------------------------------------------------------------------- the type's group


def symmetry_cosets(tiling: IsohedralTiling) -> np.ndarray:
    """(m*s, 3, 3): aspect transforms composed with the tile's own symmetries (mod lattice)."""
    syms = tiling.engine.tile_symmetries()
    return np.einsum("aij,sjk->asik", tiling.unit_transform, syms).reshape(-1, 3, 3)


#: Groups by geometry (the spec without its colouring): recolouring a tiling, as the
#: exercises on perfect colourings do thousands of times, keeps its group.
_GROUPS: dict[str, SymmetryGroup] = {}


def symmetry_group(tiling: IsohedralTiling) -> SymmetryGroup:
    """The type's symmetry group without a search: the lattice v1, v2 and the cosets
    {aspect transform o tile symmetry} that the template and the incidence symbol give."""
    key = json.dumps({k: v for k, v in tiling.spec().items() if k != "colouring"}, sort_keys=True)
    group = _GROUPS.get(key)
    if group is None:
        basis = np.array([tiling.v1, tiling.v2], dtype=float)
        group = group_from_maps(symmetry_cosets(tiling), basis, absolute_tolerance(tiling))
        if len(_GROUPS) > 4096:
            _GROUPS.clear()
        _GROUPS[key] = group
    return group


def is_perfect_colouring(tiling: IsohedralTiling, radius: int = 3) -> bool:
    """True when every symmetry of the tiling permutes the colours (§3.6.1, §5.4.3).

    The core's :func:`tilekit.symmetry.is_perfect_colouring` with the type's group as input
    (its generators are tested on a cell of the coloured tiling that every symmetry maps onto
    itself). ``radius`` is accepted for compatibility and no longer needed: the core's cell is
    exact, not a window of ``radius`` units.
    """
    del radius
    return shared_is_perfect_colouring(tiling, group=symmetry_group(tiling))
