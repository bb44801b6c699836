"""RegularTiling: the regular tiling {p, q} of the sphere (the five Platonic solids) or of the
hyperbolic plane, as a :class:`tilekit.Tiling` whose patches are :class:`ModelPatch` es.

A hyperbolic patch is the first ``depth`` layers (tiles reached by ``depth`` steps across
edges, OEIS's layer sequences) or every tile whose centre lies within hyperbolic distance
``radius`` of the origin, streamed layer by layer; the drawing plane is the Poincaré disc,
and ``render_svg`` draws every edge as the true circular arc. A spherical tiling is all its
faces, drawn in orthographic projection with the far side faint.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Mapping
from functools import lru_cache
from typing import Any

import numpy as np
import shapely
from shapely.geometry.base import BaseGeometry

from tilekit.errors import ParameterError, ParseError
from tilekit.geometry import as_region
from tilekit.limits import (
    MAX_TILES,
    STREAM_CHUNK_TILES,
    check_chunk_tiles,
    refuse_over,
    refuse_over_memory,
)
from tilekit.plugins.curved import layers, model
from tilekit.plugins.curved.patch import ModelPatch, ModelPrototile
from tilekit.plugins.curved.render import curved_svg, stereographic_paths
from tilekit.tiling import Patch, Tiling

#: Layers of a hyperbolic patch when neither depth nor radius is given.
DEFAULT_DEPTH = 4
#: Largest depth accepted (the tile estimate refuses far earlier for any {p, q}).
MAX_DEPTH = 60
#: Largest radius: past it a tile's Poincaré coordinates are within 1e-11 of the unit circle,
#: where float64 no longer tells tiles apart.
MAX_RADIUS = 25.0
#: Points per edge of the projected outlines (exports, clipping); the SVG draws true arcs.
DEFAULT_SAMPLES = 8
MAX_SAMPLES = 64
#: Peak bytes per tile while a patch is made: the Patch's 96 (the 72-byte matrix, prototile,
#: colour, aspect) plus the last boundary; measured with tracemalloc at 96-137 for {7,3},
#: {5,4}, {3,7} patches of 0.4-0.9 M tiles (tests/plugins/test_curved.py keeps it a bound).
CURVED_BYTES_PER_TILE = 200

_OPTIONS = ("p", "q", "depth", "radius", "samples", "plane")
#: The hyperbolic drawing planes (``--set plane=...``).
PLANES = ("poincare", "klein", "halfplane")
#: ``options_help``'s lines for samples and plane (the uniform and vertex-star tilings).
DRAWING_HELP = (
    f"--set samples=N             points per edge of exported outlines (1..{MAX_SAMPLES}, default "
    f"{DEFAULT_SAMPLES}); SVG draws true arcs",
    "--set plane=P               the hyperbolic drawing plane: poincare (default), klein or halfplane; the "
    "sphere's view: orthographic (default), stereographic or stereographic:K (from tile K's centre)",
)

_PALETTE = ("#f4d35e", "#ee964b", "#f95738", "#0d3b66", "#5aa9e6", "#7fc8f8", "#c1e1c1", "#a3c4bc")


def _number(name: str, value: Any, lo: float, hi: float, integer: bool) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ParameterError(f"{name} must be a number {lo:g}..{hi:g}, got {type(value).__name__}")
    try:
        f = float(value)
    except (ValueError, OverflowError):
        raise ParameterError(f"{name} must be a number {lo:g}..{hi:g}, got {str(value)[:40]!r}") from None
    if not math.isfinite(f) or not lo <= f <= hi or (integer and f != int(f)):
        kind = "an integer" if integer else "a number"
        raise ParameterError(f"{name} must be {kind} {lo:g}..{hi:g}, got {str(value)[:40]}")
    return int(f) if integer else f


#: The sphere's views (``--set plane=...``): orthographic (the default, stored as the default
#: plane's name) or stereographic from the centre of tile K (``stereographic:K``, default 0).
SPHERE_PLANES = ("orthographic", "stereographic")
_SPHERE_HELP = "orthographic (default), stereographic or stereographic:K (from the centre of tile K)"


def check_plane(plane: Any, spherical: bool) -> str:
    """The drawing plane checked: a hyperbolic tiling's of :data:`PLANES`; a sphere's of
    :data:`SPHERE_PLANES`, 'orthographic' stored as 'poincare' (the default, so specs omit it)
    and 'stereographic:K' as 'stereographic' when K is 0 (:func:`stereographic_pole` reads K);
    one-line ParameterErrors."""
    text = plane.strip() if isinstance(plane, str) else None
    head = None if text is None else text.split(":", 1)[0].strip()
    if head not in PLANES + SPHERE_PLANES or (":" in (text or "") and head != "stereographic"):
        raise ParameterError(f"plane must be one of {', '.join(PLANES)} (hyperbolic) or {_SPHERE_HELP} (sphere), "
                             f"got {str(plane)[:40]}")
    if spherical:
        if head in PLANES and head != "poincare":
            raise ParameterError(f"plane applies to hyperbolic tilings ({', '.join(PLANES)}); a sphere is drawn "
                                 f"{_SPHERE_HELP}, got {text}")
        if head != "stereographic":
            return "poincare"
        k = stereographic_pole(text)
        return "stereographic" if k == 0 else f"stereographic:{k}"
    if head in SPHERE_PLANES:
        raise ParameterError(f"plane {head} applies to tilings of the sphere; a hyperbolic tiling is drawn in "
                             f"{', '.join(PLANES)}")
    return head


def stereographic_pole(plane: str) -> int:
    """K of a sphere's plane 'stereographic:K' (0 for 'stereographic'): the tile whose centre is
    the projection's pole; a one-line ParameterError for anything but an integer 0..MAX_TILES."""
    _, sep, k = plane.partition(":")
    if not k.strip():
        if sep:
            raise ParameterError(f"plane stereographic:K needs a tile number K (0, 1, ...), got {plane[:40]}")
        return 0
    return int(_number("the stereographic pole's tile K", k.strip(), 0, MAX_TILES, True))


def drawing_options(plane: Any, samples: Any, spherical: bool) -> tuple[str, int]:
    """``plane`` and ``samples`` checked (the regular and the uniform tilings take both): a
    drawing plane (:func:`check_plane`) and 1..MAX_SAMPLES points per edge; one-line
    ParameterErrors."""
    return check_plane(plane, spherical), int(_number("samples", samples, 1, MAX_SAMPLES, True))


def drawing_spec(out: dict[str, Any], tiling: Any, default_name: str) -> dict[str, Any]:
    """``out`` with what a curved tiling's spec adds past its defining keys: radius, samples and
    plane when not the defaults, name when not ``default_name``, title when given."""
    if getattr(tiling, "radius", None) is not None:
        out["radius"] = tiling.radius
    if tiling.samples != DEFAULT_SAMPLES:
        out["samples"] = tiling.samples
    if tiling.plane != "poincare":
        out["plane"] = tiling.plane
    if tiling.name != default_name:
        out["name"] = tiling.name
    if tiling.title:
        out["title"] = tiling.title
    return out


@lru_cache(maxsize=256)
def _exact_counts(p: int, q: int, depth: int) -> tuple[int, ...]:
    """Layer counts 0..depth, stopping after the first layer over 10^4 tiles (cheap: the NumPy
    automaton over at most a few 10^4 boundary vertices)."""
    return tuple(layers.layer_counts(p, q, depth, stop_over=10_000))


def _layer_estimate(p: int, q: int, depth: int) -> float:
    counts = _exact_counts(p, q, depth)
    total = float(sum(counts[: depth + 1]))
    if len(counts) <= depth:
        ratio = max(b / max(a, 1) for a, b in zip(counts[-5:-1], counts[-4:]))
        last = float(counts[-1])
        for _ in range(depth + 1 - len(counts)):
            last *= ratio
            total += last
    return total


class CurvedTiling(Tiling):
    """What every tiling of the curved family shares: its geometry (``kind``), its hyperbolic
    drawing plane, the curved SVG (true arcs), the clip of a model patch to a region of the
    drawing plane, the size check before a patch is made, and the check of configure's
    option names against the subclass's ``OPTIONS``."""

    kind: str
    plane: str = "poincare"
    OPTIONS: tuple[str, ...] = ()

    @property
    def hyperbolic(self) -> bool:
        return self.kind == model.HYPERBOLIC

    @property
    def pole(self) -> int | None:
        """The tile K from whose centre a sphere's stereographic view projects (the SVG draws
        that view when this is not None), None in the other views."""
        if self.hyperbolic or not self.plane.startswith("stereographic"):
            return None
        return stereographic_pole(self.plane)

    def default_region(self) -> BaseGeometry:
        if self.pole is not None:
            # the stereographic picture's square: the pole tile's boundary holds every other tile
            e = stereographic_paths(self.patch(), self.pole)[1]
            return shapely.box(-e, -e, e, e)
        return shapely.box(*model.PLANE_VIEWS.get(self.plane, (-1.0, -1.0, 1.0, 1.0)))

    def render_svg(self, patch: Patch, **options: Any) -> str:
        return curved_svg(self, patch, **options)

    def check_options(self, options: Mapping[str, Any]) -> None:
        """One-line ParameterError for an option name not in ``OPTIONS``."""
        unknown = set(options) - set(self.OPTIONS)
        if unknown:
            raise ParameterError(f"{self.name} does not take option(s) {', '.join(sorted(unknown))}; "
                                 f"valid: {', '.join(self.OPTIONS)}")

    def refuse_oversize(self, what: str, estimate: float, hint: str) -> None:
        """Refuse a patch of ``estimate`` tiles past the tile limit or the memory bound."""
        refuse_over(what, estimate, MAX_TILES, "--max-tiles", hint)
        refuse_over_memory(what, estimate, self.bytes_per_tile, hint)


def spec_table(spec: Any, keys: Iterable[str], what: str) -> Mapping[str, Any]:
    """``spec`` checked as a table whose keys are among ``keys`` (listed in that order in the
    error); one-line ParseErrors naming ``what`` ("curved", "curved vertex-star" ...)."""
    if not isinstance(spec, Mapping):
        raise ParseError(f"{what} spec must be a table, got {type(spec).__name__}")
    keys = tuple(keys)
    unknown = set(spec) - set(keys)
    if unknown:
        raise ParseError(f"{what} spec has unknown key(s) {', '.join(sorted(map(str, unknown)))}; "
                         f"valid: {', '.join(keys)}")
    return spec


def clip_region(region: Any) -> BaseGeometry | None:
    """``region`` as a shape when it cuts the drawing plane's unit box, else None (no clip)."""
    reg = None if region is None else as_region(region)
    return None if reg is None or reg.covers(shapely.box(-1, -1, 1, 1)) else reg


def clipped(patch: ModelPatch, region: Any) -> ModelPatch:
    """``patch`` less the tiles whose projected outline misses ``region`` (see :func:`clip_region`);
    a sphere's patch in the stereographic view whole (the region frames its picture only: the
    outlines are the orthographic view's)."""
    first = patch.prototiles[0] if len(patch.prototiles) else None
    if getattr(first, "sign", -1) > 0 and getattr(first, "plane", "").startswith("stereographic"):
        return patch
    reg = clip_region(region)
    return patch.subset(patch.clip_index(reg)) if reg is not None and len(patch) else patch


class RegularTiling(CurvedTiling):
    """The regular tiling {p, q}: p-gons, q at each vertex, on the sphere or the hyperbolic plane."""

    streams = True
    bytes_per_tile = CURVED_BYTES_PER_TILE
    OPTIONS = _OPTIONS

    def __init__(self, p: int = 7, q: int = 3, *, depth: int | None = None, radius: float | None = None,
                 samples: int = DEFAULT_SAMPLES, plane: str = "poincare", name: str = "", title: str = "",
                 want: str | None = None) -> None:
        self.plane, self.samples = drawing_options(plane, samples, model.kind_of(*model.check_pq(p, q)) == model.SPHERE)
        self.p, self.q = model.check_pq(p, q, want)
        self.kind = model.kind_of(self.p, self.q)
        self.family = self.kind
        if depth is not None and radius is not None:
            raise ParameterError("give depth or radius, not both")
        self.depth = None if depth is None else int(_number("depth", depth, 0, MAX_DEPTH, True))
        self.radius = None if radius is None else float(_number("radius", radius, 0, MAX_RADIUS, False))
        self.polygon = model.RegularPolygon(self.p, self.q)
        self.name = name or f"{self.kind}-{self.p}-{self.q}"
        self.title = title
        sign = 1 if self.kind == model.SPHERE else -1
        pts = self.polygon.outline(self.samples)
        # the outline the core sees is the central tile in the drawing plane; the model
        # points are what the transforms act on
        self._proto = ModelPrototile.on_model(pts, sign=sign, name=f"{{{self.p},{self.q}}}", plane=plane,
                                              corners=tuple(range(0, len(pts), self.samples)))

    # -- the Tiling interface ------------------------------------------------------
    @property
    def prototiles(self) -> list[ModelPrototile]:
        return [self._proto]

    def _depth(self) -> int:
        return DEFAULT_DEPTH if self.depth is None else self.depth

    def layer_counts(self, depth: int | None = None) -> list[int]:
        """Tiles per layer 0..depth (the boundary automaton alone; the sphere's breadth-first layers)."""
        if not self.hyperbolic:
            return [len(x) for x in layers.spherical_layers(self.p, self.q)]
        return layers.layer_counts(self.p, self.q, self._depth() if depth is None else depth)

    def estimate_tiles(self, region: Any = None) -> float:
        """Tiles of the patch before any is made: the sphere's face count; for layers, the exact
        counts while a layer has at most 10^4 tiles, then the largest of the last four growth
        ratios (the ratios settle towards their limit from above or oscillate about it); for a
        radius, the disc's area over a tile's, the disc grown by a tile's circumradius."""
        if not self.hyperbolic:
            return float(4 * math.pi / self.polygon.area)
        if self.radius is not None:
            r = self.radius + self.polygon.circumradius
            return 1.0 + 2 * math.pi * (math.cosh(r) - 1) / self.polygon.area
        return _layer_estimate(self.p, self.q, self._depth())

    def _check_size(self, estimate: float) -> None:
        what = f"tiles of {{{self.p},{self.q}}}"
        hint = ("ask for fewer layers (--depth) or a smaller radius (--set radius=R)" if self.hyperbolic else "")
        self.refuse_oversize(what, estimate, hint)

    def layers(self) -> Iterator[tuple[int, np.ndarray]]:
        """(layer number, transforms) for the patch's layers; with a radius, each layer
        filtered to the centres within it, and the walk stopped once a whole layer lies
        farther than radius + circumradius (a tile within the radius is reached through
        tiles each meeting the disc, so through no such layer)."""
        if not self.hyperbolic:
            yield from enumerate(layers.spherical_layers(self.p, self.q))
            return
        if self.radius is None:
            yield from enumerate(layers.hyperbolic_layers(self.p, self.q, self._depth()))
            return
        far = math.cosh(self.radius + self.polygon.circumradius) * (1 + 1e-9)
        near = math.cosh(self.radius)
        for k, t in enumerate(layers.hyperbolic_layers(self.p, self.q, None)):
            ch = t[:, 2, 2]  # cosh of the centre's distance from the origin
            yield k, t[ch <= near]
            if ch.min() > far:
                return

    def iter_patches(self, region: Any = None, chunk_tiles: int = STREAM_CHUNK_TILES) -> Iterator[Patch]:
        """The patch layer by layer, each split into chunks of at most ``chunk_tiles`` tiles;
        tiles whose projected outline misses ``region`` (a box or shape in the drawing plane;
        None: the whole disc or sphere) are left out. Colour: the layer number."""
        check_chunk_tiles(chunk_tiles)
        self._check_size(self.estimate_tiles(region))
        # a sphere's stereographic view is drawn whole (clipped: the region frames the picture)
        reg = None if self.pole is not None else clip_region(region)
        for k, t in self.layers():
            for lo in range(0, len(t), chunk_tiles):
                part = t[lo:lo + chunk_tiles]
                patch = ModelPatch([self._proto], np.zeros(len(part), dtype=np.int64), part,
                                   colour=np.full(len(part), k, dtype=np.int64))
                if reg is not None and len(patch):
                    patch = patch.subset(patch.clip_index(reg))
                if len(patch):
                    yield patch

    def patch(self, region: Any = None) -> ModelPatch:
        """The tiles of :meth:`iter_patches` as one patch; layers of the whole disc are written
        in place into one array (no concatenation)."""
        if self.hyperbolic and self.radius is None and clip_region(region) is None:
            estimate = self.estimate_tiles(region)
            self._check_size(estimate)
            t, sizes = layers.hyperbolic_transforms(self.p, self.q, self._depth(), capacity=int(estimate) + 1)
            colour = np.repeat(np.arange(len(sizes), dtype=np.int64), sizes)
            return ModelPatch([self._proto], np.zeros(len(t), dtype=np.int64), t, colour=colour)
        parts = list(self.iter_patches(region, chunk_tiles=STREAM_CHUNK_TILES))
        if not parts:
            return ModelPatch([self._proto], np.zeros(0, dtype=np.int64), np.zeros((0, 3, 3)))
        return parts[0] if len(parts) == 1 else ModelPatch.concat(parts)  # type: ignore[return-value]

    # -- records and options -------------------------------------------------------------
    def vertex_configuration(self) -> str:
        return ".".join([str(self.p)] * self.q)

    def orbifold(self) -> str:
        """The full symmetry group, the triangle group (p, q, 2), in orbifold notation."""
        a, b = sorted((self.p, self.q), reverse=True)
        return f"*{a}{b}2"

    def properties(self) -> dict[str, Any]:
        props: dict[str, Any] = {
            "periodic": self.hyperbolic,  # hyperbolic: a cocompact symmetry group; the sphere's is finite
            "k_hedral": 1,
            "k_isohedral": 1,
            "k_isogonal": 1,
            "edge_to_edge": True,
            "geometry": self.kind,
            "schlafli": f"{{{self.p},{self.q}}}",
            "sides": [self.p],  # regular p-gons (the shared vocabulary, docs/catalogue.md)
            "p": self.p,
            "q": self.q,
            "vertex_configuration": self.vertex_configuration(),
            "symmetry_group": self.orbifold(),
            "orbifold": self.orbifold(),
            "tile_area": round(self.polygon.area, 12),
            "edge_length": round(self.polygon.edge_length, 12),
        }
        if self.hyperbolic:
            props["layer_counts"] = layers.layer_counts(self.p, self.q, 8)
        else:
            faces = len(np.concatenate(layers.spherical_layers(self.p, self.q)))
            props["faces"] = faces
            props["edges"] = faces * self.p // 2
            props["vertices"] = faces * self.p // self.q
        return props

    def describe(self) -> str:
        if self.hyperbolic:
            counts = ", ".join(map(str, layers.layer_counts(self.p, self.q, 6)))
            return (f"{{{self.p},{self.q}}}: regular {self.p}-gons, {self.q} at each vertex, in the hyperbolic "
                    f"plane (Poincaré disc); tiles per layer {counts}, ...")
        return (f"{{{self.p},{self.q}}}: regular {self.p}-gons, {self.q} at each vertex, on the sphere "
                f"({len(np.concatenate(layers.spherical_layers(self.p, self.q)))} faces)")

    def options_help(self) -> str:
        return "\n".join([
            f"--depth N / --set depth=N   layers of edge-neighbours around the centre tile (default {DEFAULT_DEPTH}, "
            f"at most {MAX_DEPTH}; the tile estimate refuses first)",
            f"--set radius=R              instead: every tile whose centre is within hyperbolic distance R "
            f"(0..{MAX_RADIUS:g})",
            f"--set p=P --set q=Q         the Schläfli symbol {{P,Q}} (3..{model.MAX_PQ}; the family's geometry)",
            f"--set samples=N             points per edge of exported outlines (1..{MAX_SAMPLES}, default "
            f"{DEFAULT_SAMPLES}); SVG draws true arcs",
            "--set plane=P                the hyperbolic drawing plane: poincare (default; edges are arcs), "
            "klein (edges are chords) or halfplane (the upper half-plane; edges are half-circles); the sphere: "
            "orthographic (default) or stereographic[:K] (from the centre of tile K, default 0; edges are arcs)",
            "--region x0,y0,x1,y1        the part of the disc (or the sphere's picture) to keep",
        ])

    def configure(self, **options: Any) -> RegularTiling:
        if "geometry" in options:  # the --geometry check (wythoff.check_geometry's spellings)
            # start-up cost: the construction module, only when a geometry is given
            from tilekit.plugins.curved.wythoff import check_geometry

            want = check_geometry(options.pop("geometry"))
            if want != self.kind:
                raise ParameterError(f"{self.name} ({self.vertex_configuration()}) is {self.kind}, not {want}: "
                                     "a vertex configuration closes on one surface only")
            if not options:
                return self
        self.check_options(options)
        p = options.get("p", self.p)
        q = options.get("q", self.q)
        depth = options.get("depth", self.depth if "radius" not in options else None)
        radius = options.get("radius", self.radius if "depth" not in options else None)
        if not self.hyperbolic and ("depth" in options or "radius" in options):
            raise ParameterError(f"{self.name} is a tiling of the sphere, drawn whole: depth and radius "
                                 "apply to hyperbolic tilings")
        same = (model.check_pq(p, q) == (self.p, self.q))
        return RegularTiling(p, q, depth=depth, radius=radius, samples=options.get("samples", self.samples),
                             plane=options.get("plane", self.plane),
                             name=self.name if same else "", title=self.title if same else "", want=self.kind)

    def spec(self) -> dict[str, Any]:
        out: dict[str, Any] = {"p": self.p, "q": self.q}
        if self.depth is not None:
            out["depth"] = self.depth
        return drawing_spec(out, self, f"{self.kind}-{self.p}-{self.q}")

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any], want: str | None = None) -> RegularTiling:
        spec_table(spec, ("p", "q", "depth", "radius", "samples", "plane", "name", "title"), want or "curved")
        if "p" not in spec or "q" not in spec:
            raise ParseError(f"{want or 'curved'} spec needs p and q (the Schläfli symbol {{p,q}})")
        return cls(spec["p"], spec["q"], depth=spec.get("depth"), radius=spec.get("radius"),
                   samples=spec.get("samples", DEFAULT_SAMPLES), plane=spec.get("plane", "poincare"),
                   name=str(spec.get("name", "")),
                   title=str(spec.get("title", "")), want=want)
