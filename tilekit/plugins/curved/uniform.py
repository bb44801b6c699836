"""UniformTiling: a uniform tiling of the sphere or the hyperbolic plane by Wythoff's
construction (wythoff.py), named by its vertex configuration or its Wythoff symbol, as a
:class:`tilekit.Tiling` whose patches are :class:`ModelPatch` es with one prototile per face
size; and the plane's Wythoffian tilings as :class:`tilekit.PeriodicTiling` s
(:func:`euclidean_tiling`), which the tests hold to the archimedean family's.

The vertex configuration decides the geometry (its Euclidean angles sum to less than, exactly
or more than a full turn); ``geometry`` is a check on it. A spherical tiling is all its faces;
a hyperbolic patch is every face whose centre lies within ``radius`` plus the face's
circumradius of the disc's centre, so it covers the disc of that radius (default: the
radius of about DEFAULT_FACES faces). Faces are coloured by their kind.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cached_property
from typing import Any

import numpy as np

from tilekit.errors import ParameterError
from tilekit.plugins.curved import model, notation, wythoff
from tilekit.plugins.curved.orbifold import UniformSymmetry, symbol_symmetry, uniform_symmetry
from tilekit.plugins.curved.patch import ModelPatch, ModelPrototile
from tilekit.plugins.curved.tiling import (
    DEFAULT_SAMPLES,
    DRAWING_HELP,
    CurvedTiling,
    _number,
    clipped,
    drawing_options,
    drawing_spec,
    spec_table,
)
from tilekit.plugins.curved.wythoff import GEOMETRIES, check_geometry  # noqa: F401 - the spellings, re-exported
from tilekit.tiling import PeriodicTiling, Prototile

#: Faces of a hyperbolic patch when no radius is given (the radius is chosen to give about this many).
DEFAULT_FACES = 800
#: Largest radius: past it the face estimate is far over any limit, and the construction's
#: coordinates (about e^R) leave too few digits to tell faces apart.
MAX_RADIUS = 12.0
#: Peak bytes per face while a patch is made: the Patch's columns, the cells and the
#: candidate centres of the faces round the other corners; measured with tracemalloc at
#: 380-1500 for 3.3.3.3.7, 4.6.14, 3.14.14 and 5.8.8 patches of 2·10^3 to 3·10^4 faces
#: (tests/plugins/test_uniform.py keeps it a bound).
UNIFORM_BYTES_PER_TILE = 2000

_OPTIONS = ("configuration", "symbol", "radius", "samples", "plane", "geometry")
_SPEC_KEYS = set(_OPTIONS) | {"name", "title"}


def resolve(configuration: str | None = None, symbol: str | None = None,
            geometry: str | None = None) -> wythoff.Symbol:
    """The Wythoff symbol for a vertex configuration or a symbol's text, checked against the
    geometry hint (one-line errors: a configuration no symbol gives, a geometry it does not
    close on, orders out of range)."""
    if (configuration is None) == (symbol is None):
        raise ParameterError("give a vertex configuration (e.g. 3.4.4.4) or a Wythoff symbol (e.g. '2 3 | 7'), "
                             "one of the two")
    want = check_geometry(geometry)
    if symbol is not None:
        sym = wythoff.Symbol.parse(str(symbol))
        if sym.configuration is None:
            raise ParameterError(f"Wythoff symbol {sym} makes fewer than three faces at a vertex (a degenerate "
                                 "tiling): no uniform tiling by polygons")
        kind = sym.geometry
        what = f"Wythoff symbol {sym}"
    else:
        cfg = notation.parse(str(configuration))
        kind = notation.geometry_of(cfg)
        what = notation.dotted(cfg)
        sym = None  # type: ignore[assignment]
    if want is not None and kind != want:
        raise ParameterError(f"{what} is {kind}, not {want}: its angles close on one surface only "
                             f"(below a full turn: sphere, exactly: plane, above: hyperbolic)")
    if sym is None:
        sym = wythoff.symbol_for(cfg)
    return sym


def _outline(space: wythoff.Space, sides: int, rho: float, per_edge: int) -> np.ndarray:
    """(sides * per_edge, 3): the regular polygon at the pole, its edges sampled on the geodesics."""
    v = wythoff.regular_polygon(space, sides, rho)
    return model.sample_edges(model.Geometry(space.sign), v, float(space.distance(v[0], v[1])), per_edge)


_POLYGON_NAMES = {3: "triangle", 4: "square", 5: "pentagon", 6: "hexagon", 7: "heptagon", 8: "octagon",
                  9: "nonagon", 10: "decagon", 12: "dodecagon"}


def _polygon(n: int) -> str:
    return _POLYGON_NAMES.get(n, f"{n}-gon")


class UniformTiling(CurvedTiling):
    """A uniform tiling of the sphere or the hyperbolic plane by Wythoff's construction (the
    base of its dual, laves.LavesTiling, which shares the naming, options and specs)."""

    streams = False
    bytes_per_tile = UNIFORM_BYTES_PER_TILE
    OPTIONS = _OPTIONS
    #: Options that name another tiling: configure() keeps the name and title without them.
    DEFINING: tuple[str, ...] = ("configuration", "symbol")
    #: The spec's keys, and what its one-line errors call it.
    SPEC_KEYS: tuple[str, ...] = tuple(sorted(_SPEC_KEYS))
    SPEC_WHAT = "curved"

    def __init__(self, configuration: str | None = None, *, symbol: str | None = None, radius: float | None = None,
                 samples: int = DEFAULT_SAMPLES, plane: str = "poincare", geometry: str | None = None,
                 name: str = "", title: str = "") -> None:
        self.symbol = resolve(configuration, symbol, geometry)
        self.given = "symbol" if symbol is not None else "configuration"
        self.geometry_hint = check_geometry(geometry)
        kind = self.symbol.geometry
        if kind == wythoff.EUCLIDEAN:
            raise ParameterError(self.euclidean_message())
        self.kind = kind
        self.family = "curved"
        self.plane, self.samples = drawing_options(plane, samples, kind == wythoff.SPHERE)
        if radius is not None and kind == wythoff.SPHERE:
            raise ParameterError("radius applies to hyperbolic tilings; a tiling of the sphere is drawn whole")
        self.radius = None if radius is None else float(_number("radius", radius, 0, MAX_RADIUS, False))
        self.configuration = wythoff.uniform_configuration(self.symbol)
        self.name = name or self.default_name()
        self.title = title

    def euclidean_message(self) -> str:
        return (f"{wythoff.uniform_configuration(self.symbol)} tiles the Euclidean plane: see the archimedean family "
                "(tilekit render 3.4.6.4); the curved family draws the sphere and the hyperbolic plane")

    def default_name(self) -> str:
        return notation.exponent(self.symbol.configuration or ())

    @cached_property
    def construction(self) -> wythoff.Construction:
        """The construction (made on first use: a record needs only the symbol)."""
        return wythoff.Construction(self.symbol)

    @cached_property
    def symmetry(self) -> UniformSymmetry:
        """The tiling's full symmetry group (orbifold notation in ``.notation``)."""
        return symbol_symmetry(self.symbol) or uniform_symmetry(self.construction)

    @cached_property
    def _protos(self) -> list[ModelPrototile]:
        sp = self.construction.space
        return [ModelPrototile.on_model(pts, sign=sp.sign, name=_polygon(face.sides), plane=self.plane,
                                        corners=tuple(range(0, len(pts), self.samples)))
                for face in self.construction.face_types
                for pts in [_outline(sp, face.sides, face.circumradius, self.samples)]]

    # -- the Tiling interface ------------------------------------------------------
    @property
    def prototiles(self) -> list[ModelPrototile]:
        return list(self._protos)

    def _radius(self) -> float:
        if self.radius is not None:
            return self.radius
        # the disc whose area holds about DEFAULT_FACES faces
        r = math.acosh(1 + DEFAULT_FACES / (2 * math.pi * self.construction.faces_per_area()))
        return float(min(MAX_RADIUS, max(0.0, r - max(f.circumradius for f in self.construction.face_types))))

    def estimate_tiles(self, region: Any = None) -> float:
        """The sphere's face count (the group's order over each face's stabiliser); in the
        hyperbolic plane, faces per area (per triangle of the group) times the disc's area,
        the disc grown by twice the largest face's circumradius."""
        if not self.hyperbolic:
            return float(sum(self.face_counts().values()))
        c = self.construction
        r = self._radius() + 2 * max(f.circumradius for f in c.face_types)
        return 1.0 + c.faces_per_area() * 2 * math.pi * (math.cosh(r) - 1)

    def _check_size(self, estimate: float) -> None:
        what = f"faces of {self.configuration}"
        hint = "ask for a smaller radius (--set radius=R)" if self.hyperbolic else ""
        self.refuse_oversize(what, estimate, hint)

    def patch(self, region: Any = None) -> ModelPatch:
        """Every face (sphere) or every face whose centre is within the radius plus its
        circumradius (hyperbolic: the disc of the radius is covered), less those whose projected outline misses ``region``; colour: the face's kind."""
        self._check_size(self.estimate_tiles(region))
        mats, kinds = self.construction.faces(self._radius() if self.hyperbolic else None)
        patch = ModelPatch(self._protos, kinds, mats, colour=kinds.copy())
        return clipped(patch, region)

    # -- records and options -------------------------------------------------------------
    def face_counts(self) -> dict[int, int]:
        """Faces per polygon size (the sphere)."""
        return self.symbol.face_counts()

    def properties(self) -> dict[str, Any]:
        cfg = self.symbol.configuration or ()
        props: dict[str, Any] = {
            "periodic": self.hyperbolic,  # hyperbolic: a cocompact group; the sphere's is finite
            "k_hedral": len(set(cfg)),
            "k_isogonal": 1,
            "edge_to_edge": True,
            "uniform": True,
            "geometry": self.kind,
            "vertex_configuration": self.configuration,
            "wythoff_symbol": str(self.symbol),
            "construction_group": self.symbol.group,
            # the full group, computed from the construction (orbifold.py): larger than the
            # construction's when the tiling has more symmetry (3 3 | 2 is the cuboctahedron, *432)
            "symmetry_group": self.symmetry.notation,
            "orbifold": self.symmetry.notation,
            "sides": sorted(set(cfg)),
            "valence": len(cfg),
        }
        if not self.hyperbolic:
            counts = self.face_counts()
            faces = sum(counts.values())
            corners = sum(n * k for n, k in counts.items())
            props["faces"] = faces
            props["vertices"] = corners // len(cfg)
            props["edges"] = corners // 2
            props["face_counts"] = " + ".join(f"{counts[n]} {_polygon(n)}s" for n in sorted(counts))
        return props

    def describe(self) -> str:
        where = "the sphere" if not self.hyperbolic else "the hyperbolic plane (Poincaré disc)"
        faces = ""
        if not self.hyperbolic:
            faces = f": {self.properties()['face_counts']}"
        return (f"{self.configuration}: the uniform tiling of {where} by Wythoff's construction "
                f"{self.symbol} on the triangle group {self.symbol.group}{faces}")

    def options_help(self) -> str:
        return "\n".join([
            "--set configuration=C       the vertex configuration, e.g. 3.4.4.4 or 3.14^2",
            "--set symbol=S              instead: the Wythoff symbol, e.g. '2 3 | 7', '| 2 4 5'",
            f"--set radius=R              hyperbolic: the faces covering the disc of radius R (0..{MAX_RADIUS:g}; "
            f"default: about {DEFAULT_FACES} faces)",
            "--set geometry=G            sphere, plane or hyperbolic: a check on the configuration's geometry",
            *DRAWING_HELP,
        ])

    def configure(self, **options: Any) -> UniformTiling:
        self.check_options(options)
        if "configuration" in options and "symbol" in options:
            raise ParameterError("give configuration or symbol, not both")
        if "configuration" in options:
            named = {"configuration": options["configuration"]}
        elif "symbol" in options:
            named = {"symbol": options["symbol"]}
        else:
            named = {self.given: self.configuration if self.given == "configuration" else str(self.symbol)}
        same = not (set(self.DEFINING) & set(options))
        return type(self)(**named, **self.carried(options), radius=options.get("radius", self.radius),
                          samples=options.get("samples", self.samples), plane=options.get("plane", self.plane),
                          geometry=options.get("geometry", self.geometry_hint),
                          name=self.name if same else "", title=self.title if same else "")

    def carried(self, options: Mapping[str, Any]) -> dict[str, Any]:
        """A subclass's own options for configure(): ``options``' value, else the tiling's."""
        return {}

    def defining_spec(self) -> dict[str, Any]:
        """The spec's keys that say which tiling this is (drawing_spec adds the rest)."""
        return ({"configuration": self.configuration} if self.given == "configuration"
                else {"symbol": str(self.symbol)})

    def spec(self) -> dict[str, Any]:
        return drawing_spec(self.defining_spec(), self, self.default_name())

    @classmethod
    def spec_options(cls, spec: Mapping[str, Any]) -> dict[str, Any]:
        """A subclass's own keyword arguments from its spec (checked)."""
        return {}

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> UniformTiling:
        spec_table(spec, cls.SPEC_KEYS, cls.SPEC_WHAT)
        return cls(spec.get("configuration"), symbol=spec.get("symbol"), radius=spec.get("radius"),
                   samples=spec.get("samples", DEFAULT_SAMPLES), plane=spec.get("plane", "poincare"),
                   geometry=spec.get("geometry"), name=str(spec.get("name", "")), title=str(spec.get("title", "")),
                   **cls.spec_options(spec))


def euclidean_tiling(configuration: str | None = None, *, symbol: str | None = None) -> PeriodicTiling:
    """The plane's uniform tiling by Wythoff's construction as a periodic tiling: the
    group's two shortest independent translations, and the faces whose centres lie in one
    translational unit (half-open in lattice coordinates)."""
    sym = resolve(configuration, symbol, "plane")
    con = wythoff.Construction(sym)
    v1, v2 = con.translations()
    reach = 3.0 * float(np.hypot(*v1) + np.hypot(*v2)) + con.face_reach
    mats, kinds = con.faces(reach)
    basis = np.column_stack([v1, v2])
    frac = np.linalg.solve(basis, mats[:, :2, 2].T).T
    cell = np.floor(frac + 1e-9)
    unit = (cell == 0).all(axis=1)
    protos = [Prototile(wythoff.regular_polygon(con.space, f.sides, f.circumradius)[:, :2], name=_polygon(f.sides))
              for f in con.face_types]
    return PeriodicTiling(protos, kinds[unit], mats[unit], v1, v2, family="wythoff",
                          name=wythoff.uniform_configuration(sym))
