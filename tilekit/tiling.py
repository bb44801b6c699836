"""The core vocabulary: Prototile, Patch (tiles as columns), the Tiling ABC, PeriodicTiling.

A Patch stores n placed tiles as arrays (prototile index, 3x3 transform, colour, aspect),
so a million tiles is a handful of arrays; geometry is produced per prototile in batches.
PeriodicTiling implements ``patch(region)`` once, by the lattice rasterization of §3.4 with
as many rings as the translational unit's extent requires (§3.5).
"""

from __future__ import annotations

import importlib
import json
import math
from abc import ABC, abstractmethod
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from types import ModuleType
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely
from shapely.geometry.base import BaseGeometry

from tilekit.colouring import Colouring
from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.geometry import AREA_TOL, EPS, POINT_TOL, Affine, as_region, snap_noise
from tilekit.limits import (
    GENERATION_BYTES_PER_TILE,
    PERIODIC_BYTES_PER_TILE,
    STREAM_CHUNK_TILES,
    check_chunk_tiles,
)
from tilekit.polygon import centroid, ear_clip, interior_angles, signed_area
from tilekit.render import patch_to_svg

if TYPE_CHECKING:  # annotations only; the export layer stands above this module
    from tilekit.export import Adjacency, TileTable

#: The export layer Patch's and Tiling's output methods (``plot``, ``adjacency``, ``to_geojson``,
#: Jupyter's pictures ...) call, named rather than imported, in the manner of pandas'
#: ``plotting.backend``: it is a layer above this module (it reads Patch), imported on the first
#: call (so ``import tilekit.tiling`` does not load it, and it may import this module freely).
EXPORT_BACKEND = "tilekit.export"


def _export() -> ModuleType:
    """The export layer (:data:`EXPORT_BACKEND`), imported on first use and then cached by Python."""
    return importlib.import_module(EXPORT_BACKEND)


#: Refuse to rasterize more lattice cells than this in one patch (a typo guard, not a limit
#: of the method: 20 million cells is already hundreds of millions of tiles).
MAX_LATTICE_CELLS = 20_000_000

#: Patches with at least this many tiles get their bounding boxes from one compiled pass
#: (tilekit.kernels): 5x less time than the NumPy expressions at 4.5 * 10^5 tiles.
_COMPILED_BOUNDS = 50_000

#: Tiles per block of ``PeriodicTiling.patch``'s box test and output writes (fits in the cache).
_PATCH_BLOCK = 1 << 14


# --------------------------------------------------------------------------- Prototile


@dataclass(frozen=True, eq=False)
class Prototile:
    """A tile shape: a counter-clockwise outline (k, 2), optional edge labels and marking.

    ``edge_labels[i]`` labels the edge from ``outline[i]`` to ``outline[i+1]`` (integer
    labels with the i / -i matching rule of exercise 6.2, or any hashable value a family's
    compatibility rule understands). ``marking`` is a tuple of polylines drawn on the tile
    (decorations that break its symmetry, e.g. for marked isohedral types or Penrose arcs).
    ``corners`` optionally names which outline points are tiling vertices (§5.1) when the
    outline carries shaped edges with many points.
    """

    outline: np.ndarray
    edge_labels: tuple[Any, ...] | None = None
    marking: tuple[np.ndarray, ...] = ()
    name: str = ""
    corners: tuple[int, ...] | None = None

    def __post_init__(self) -> None:
        pts = np.asarray(self.outline, dtype=float)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 3:
            raise GeometryError(
                f"prototile {self.name or '?'}: outline must be at least 3 (x, y) points, "
                f"got shape {pts.shape}"
            )
        if not np.all(np.isfinite(pts)):
            raise GeometryError(f"prototile {self.name or '?'}: outline has non-finite coordinates")
        if np.allclose(pts[0], pts[-1]) and len(pts) > 3:
            pts = pts[:-1]
        area = signed_area(pts)
        if abs(area) < EPS:
            raise GeometryError(f"prototile {self.name or '?'}: outline has zero area")
        if area < 0:
            if self.edge_labels is not None:
                raise GeometryError(
                    f"prototile {self.name or '?'}: outline is clockwise; give it "
                    "counter-clockwise so edge labels keep their meaning"
                )
            pts = pts[::-1].copy()
        pts.setflags(write=False)
        object.__setattr__(self, "outline", pts)
        if self.edge_labels is not None and len(self.edge_labels) != len(pts):
            raise GeometryError(
                f"prototile {self.name or '?'}: {len(self.edge_labels)} edge labels for "
                f"{len(pts)} edges"
            )
        marks = tuple(np.asarray(m, dtype=float).reshape(-1, 2) for m in self.marking)
        object.__setattr__(self, "marking", marks)
        if not shapely.Polygon(pts).is_valid:
            raise GeometryError(f"prototile {self.name or '?'}: outline is self-intersecting")

    @property
    def area(self) -> float:
        return signed_area(self.outline)

    @property
    def edges(self) -> int:
        return len(self.outline)

    def polygon(self) -> shapely.Polygon:
        return shapely.Polygon(self.outline)

    def _repr_svg_(self) -> str:
        """Jupyter draws the prototile alone (with its markings)."""
        return patch_to_svg(Patch([self], np.zeros(1, dtype=np.int64), np.eye(3)[None]), size=160)

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {"outline": np.round(self.outline, 12).tolist()}
        if self.edge_labels is not None:
            out["edge_labels"] = list(self.edge_labels)
        if self.marking:
            out["marking"] = [np.round(m, 12).tolist() for m in self.marking]
        if self.name:
            out["name"] = self.name
        if self.corners is not None:
            out["corners"] = list(self.corners)
        return out

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> Prototile:
        try:
            return cls(
                outline=np.asarray(data["outline"], dtype=float),
                edge_labels=tuple(data["edge_labels"]) if data.get("edge_labels") is not None else None,
                marking=tuple(np.asarray(m, dtype=float) for m in data.get("marking", ())),
                name=str(data.get("name", "")),
                corners=tuple(data["corners"]) if data.get("corners") is not None else None,
            )
        except (KeyError, TypeError, ValueError) as exc:
            raise ParseError(f"prototile spec is malformed: {exc}") from None


# --------------------------------------------------------------------------- Patch


@dataclass
class ValidationReport:
    """What ``Patch.validate`` found: overlapping pairs, invalid tiles, uncovered area."""

    tiles: int
    overlaps: list[tuple[int, int, float]] = field(default_factory=list)
    invalid_tiles: list[int] = field(default_factory=list)
    uncovered_area: float = 0.0
    region_area: float = 0.0
    uncovered_bounds: tuple[float, float, float, float] | None = None
    area_tolerance: float = 0.0

    @property
    def ok(self) -> bool:
        return not self.overlaps and not self.invalid_tiles and self.uncovered_area <= self.area_tolerance

    def __bool__(self) -> bool:
        return self.ok

    def summary(self) -> str:
        if self.ok:
            return f"valid: {self.tiles} tiles, no overlaps, region covered"
        parts = []
        if self.invalid_tiles:
            parts.append(f"{len(self.invalid_tiles)} invalid tile(s), first {self.invalid_tiles[:5]}")
        if self.overlaps:
            i, j, a = self.overlaps[0]
            parts.append(f"{len(self.overlaps)} overlapping pair(s), first tiles {i} and {j} (area {a:.3g})")
        if self.uncovered_area > self.area_tolerance:
            parts.append(
                f"gap: {self.uncovered_area:.3g} of the region's {self.region_area:.3g} uncovered "
                f"near {tuple(round(v, 3) for v in self.uncovered_bounds or ())}"
            )
        return "invalid patch: " + "; ".join(parts)

    def raise_if_invalid(self) -> None:
        if not self.ok:
            raise GeometryError(self.summary())


class Patch:
    """A finite set of placed tiles stored as columns.

    ``prototiles`` is the list of shapes; tile t is ``prototiles[prototile[t]]`` moved by
    ``transform[t]`` (3x3), with a symbolic ``colour[t]`` and ``aspect[t]`` (both ints).
    """

    __slots__ = ("prototiles", "prototile", "transform", "colour", "aspect", "_geoms")

    def __init__(
        self,
        prototiles: Sequence[Prototile],
        prototile: np.ndarray,
        transform: np.ndarray,
        colour: np.ndarray | None = None,
        aspect: np.ndarray | None = None,
    ) -> None:
        self.prototiles = list(prototiles)
        self.prototile = np.asarray(prototile, dtype=np.int64).reshape(-1)
        n = len(self.prototile)
        self.transform = np.asarray(transform, dtype=float).reshape(n, 3, 3)
        self.colour = (
            np.zeros(n, dtype=np.int64) if colour is None else np.asarray(colour, dtype=np.int64).reshape(n)
        )
        self.aspect = (
            np.zeros(n, dtype=np.int64) if aspect is None else np.asarray(aspect, dtype=np.int64).reshape(n)
        )
        if n and (self.prototile.min() < 0 or self.prototile.max() >= len(self.prototiles)):
            raise GeometryError("patch refers to a prototile index out of range")
        self._geoms: np.ndarray | None = None

    # construction ------------------------------------------------------------
    @classmethod
    def empty(cls, prototiles: Sequence[Prototile]) -> Patch:
        return cls(prototiles, np.zeros(0, dtype=np.int64), np.zeros((0, 3, 3)))

    @classmethod
    def concat(cls, patches: Sequence[Patch]) -> Patch:
        """Join patches that share the same prototile list."""
        if not patches:
            raise GeometryError("concat needs at least one patch")
        first = patches[0]
        for p in patches[1:]:
            if p.prototiles is not first.prototiles and p.prototiles != first.prototiles:
                raise GeometryError("concat: patches have different prototile lists")
        return cls(
            first.prototiles,
            np.concatenate([p.prototile for p in patches]),
            np.concatenate([p.transform for p in patches]),
            np.concatenate([p.colour for p in patches]),
            np.concatenate([p.aspect for p in patches]),
        )

    def subset(self, index: np.ndarray | Sequence[int] | slice) -> Patch:
        """The tiles at ``index`` (an int array, boolean mask or slice)."""
        return Patch(
            self.prototiles,
            self.prototile[index],
            self.transform[index],
            self.colour[index],
            self.aspect[index],
        )

    def transformed(self, m: np.ndarray) -> Patch:
        """The whole patch moved by the map ``m``."""
        return Patch(self.prototiles, self.prototile, np.asarray(m) @ self.transform, self.colour, self.aspect)

    def __len__(self) -> int:
        return len(self.prototile)

    def __repr__(self) -> str:
        return f"Patch({len(self)} tiles, {len(self.prototiles)} prototiles)"

    # geometry ----------------------------------------------------------------
    def groups(self) -> Iterator[tuple[int, np.ndarray, np.ndarray]]:
        """Per prototile: (prototile index, tile indices, outlines (m, k, 2)) in batches."""
        for p, proto in enumerate(self.prototiles):
            idx = np.flatnonzero(self.prototile == p)
            if len(idx):
                yield p, idx, Affine.apply(self.transform[idx], proto.outline)

    def polygons(self) -> list[np.ndarray]:
        """Every tile's outline as a (k, 2) array, in tile order."""
        out: list[np.ndarray] = [np.zeros((0, 2))] * len(self)
        for _, idx, pts in self.groups():
            for i, t in enumerate(idx):
                out[t] = pts[i]
        return out

    def geometries(self) -> np.ndarray:
        """Every tile as a shapely Polygon (an object array, built per prototile in batches)."""
        if self._geoms is None:
            geoms = np.empty(len(self), dtype=object)
            for _, idx, pts in self.groups():
                geoms[idx] = shapely.polygons(pts)
            self._geoms = geoms
        return self._geoms

    def tile_bounds(self) -> np.ndarray:
        """(n, 4) array of each tile's x0, y0, x1, y1."""
        if len(self) >= _COMPILED_BOUNDS:
            # measured start-up cost: numba's import (~0.3 s) pays only on large patches
            from tilekit.kernels import tile_bounds

            return tile_bounds(self.prototile, self.transform, [p.outline for p in self.prototiles])
        out = np.zeros((len(self), 4))
        for p, shape in enumerate(self.prototiles):
            idx = np.flatnonzero(self.prototile == p)
            if not len(idx):
                continue
            if len(shape.outline) > 16:  # shaped outlines: one batched product
                pts = Affine.apply(self.transform[idx], shape.outline)
                out[idx, :2] = pts.min(axis=1)
                out[idx, 2:] = pts.max(axis=1)
                continue
            # few corners: each corner's x and y from the map's components, no (m, k, 2) array
            t = self.transform[idx]
            a, b, c, d, e, f = (np.ascontiguousarray(t[:, i, j]) for i in (0, 1) for j in (0, 1, 2))
            xs = [a * vx + b * vy + c for vx, vy in shape.outline]
            ys = [d * vx + e * vy + f for vx, vy in shape.outline]
            out[idx, 0] = np.minimum.reduce(xs)
            out[idx, 1] = np.minimum.reduce(ys)
            out[idx, 2] = np.maximum.reduce(xs)
            out[idx, 3] = np.maximum.reduce(ys)
        return out

    def bounds(self) -> tuple[float, float, float, float]:
        if not len(self):
            raise GeometryError("an empty patch has no bounds")
        b = self.tile_bounds()
        return (float(b[:, 0].min()), float(b[:, 1].min()), float(b[:, 2].max()), float(b[:, 3].max()))

    def centres(self) -> np.ndarray:
        """(n, 2) centroids of the tiles (each prototile's centroid, transformed)."""

        out = np.zeros((len(self), 2))
        for p, idx, _ in self.groups():
            c = centroid(self.prototiles[p].outline)
            out[idx] = Affine.apply(self.transform[idx], c[None, :])[:, 0, :]
        return out

    def weld_tolerance(self) -> float:
        """Distance within which outline points are one point (adjacency, cut lines):
        POINT_TOL scaled by the median tile diameter, at least 1."""
        if not len(self):
            return POINT_TOL
        diam = np.array([float(np.ptp(p.outline, axis=0).max()) for p in self.prototiles])
        scale = np.sqrt(np.abs(np.linalg.det(self.transform[:, :2, :2])))
        return POINT_TOL * max(1.0, float(np.median(diam[self.prototile] * scale)))

    def orientations(self) -> tuple[np.ndarray, np.ndarray]:
        """Each tile's turn in degrees in [0, 360) and whether it is reflected (tile tables)."""
        lin = self.transform[:, :2, :2]
        angle = np.round(np.degrees(np.arctan2(lin[:, 1, 0], lin[:, 0, 0])), 9) % 360.0
        return angle, lin[:, 0, 0] * lin[:, 1, 1] - lin[:, 0, 1] * lin[:, 1, 0] < 0

    def clip(self, region: Any, mode: str = "intersects") -> Patch:
        """The tiles that meet ``region`` (mode 'intersects') or lie inside it ('within')."""
        return self.subset(self.clip_index(region, mode))

    def clip_index(self, region: Any, mode: str = "intersects") -> np.ndarray:
        """The indices (ascending) of the tiles :meth:`clip` keeps, for per-tile arrays kept
        beside the patch."""
        reg = as_region(region)
        if mode not in ("intersects", "within"):
            raise ParameterError(f"clip mode {mode!r} is not 'intersects' or 'within'")
        if not len(self):
            return np.zeros(0, dtype=np.int64)
        b = self.tile_bounds()
        x0, y0, x1, y1 = reg.bounds
        cand = np.flatnonzero((b[:, 2] >= x0) & (b[:, 0] <= x1) & (b[:, 3] >= y0) & (b[:, 1] <= y1))
        sure = cand[:0]
        if _is_box(reg):
            # a tile whose bounding box lies strictly inside the box is inside it: only the
            # tiles across the box's edges need the exact (shapely) test
            bc = b[cand]
            inside = (bc[:, 0] > x0) & (bc[:, 2] < x1) & (bc[:, 1] > y0) & (bc[:, 3] < y1)
            sure, cand = cand[inside], cand[~inside]
        g = self._geometries_at(cand)
        if mode == "intersects":
            # bounding boxes touching the region may still only touch it: test exactly
            keep = shapely.intersects(reg, g) & ~shapely.touches(reg, g)
        else:
            keep = shapely.covers(reg.buffer(1e-7), g)
        return np.sort(np.concatenate([sure, cand[keep]])) if len(sure) else cand[keep]

    def _geometries_at(self, index: np.ndarray) -> np.ndarray:
        """Polygons of the tiles at ``index`` (from the cache, or built for those alone)."""
        if self._geoms is not None or len(index) == len(self):
            return self.geometries()[index]
        out = np.empty(len(index), dtype=object)
        proto = self.prototile[index]
        for p, shape in enumerate(self.prototiles):
            at = np.flatnonzero(proto == p)
            if len(at):
                out[at] = shapely.polygons(Affine.apply(self.transform[index[at]], shape.outline))
        return out

    # validation --------------------------------------------------------------
    def validate(self, region: Any = None, tolerance: float = AREA_TOL) -> ValidationReport:
        """Check that no two tiles overlap and that ``region`` is covered.

        Overlaps are pairs whose interiors meet in more than ``tolerance`` times the median
        tile area (shared edges and float noise do not count). With a region, the part of
        it not covered by the union of the tiles must be below the same tolerance. Returns a
        report naming offending tiles; ``bool(report)`` is True when the patch is valid.

        How: tiles are cut into convex pieces (each prototile once); pieces whose bounding
        boxes overlap are found with a uniform grid and tested with separating axes in array
        code, with a slack that bounds what a pair it passes can overlap by a tenth of the
        tolerance. Only pairs no axis separates (real overlaps) reach shapely, whose overlay
        then runs on coordinates snapped once (:func:`tilekit.geometry.snap_noise`).
        Coverage is the sum of the tile areas inside the region (tiles on its boundary
        clipped) minus the overlaps there.
        """
        n = len(self)
        report = ValidationReport(tiles=n)
        if n == 0:
            if region is not None:
                reg = as_region(region)
                report.region_area = report.uncovered_area = float(reg.area)
                report.uncovered_bounds = tuple(reg.bounds)
            return report
        finite = np.isfinite(self.transform[:, :2, :]).all(axis=(1, 2))
        proto_area = np.array([abs(p.area) for p in self.prototiles])
        areas = np.abs(Affine.determinant(self.transform)) * proto_area[self.prototile]
        areas[~finite] = 0.0
        tol_area = tolerance * float(np.median(areas))
        report.area_tolerance = tol_area
        report.invalid_tiles = np.flatnonzero(~finite | (areas <= tol_area)).tolist()
        outlines = _Outlines(self, finite)
        scale = math.sqrt(max(float(np.median(areas)), EPS))
        decimals = max(0, round(9 - math.log10(scale)))  # snap to 1e-9 of the tile size
        pairs = _unseparated_pairs(self, outlines, tol_area)
        made: dict[int, Any] = {}

        def geoms_of(tiles: np.ndarray) -> np.ndarray:
            """shapely polygons of ``tiles`` from the snapped outlines (each made once)."""
            tiles = np.asarray(tiles, dtype=np.int64)
            new = np.array(sorted({int(t) for t in tiles} - made.keys()), dtype=np.int64)
            if len(new):
                made.update(zip(new.tolist(), outlines.polygons(new, decimals)))
            out = np.empty(len(tiles), dtype=object)
            out[:] = [made[t] for t in tiles.tolist()]
            return out

        if len(pairs):
            left, right = pairs[:, 0], pairs[:, 1]
            inter = shapely.area(_overlay(shapely.intersection, geoms_of(left), geoms_of(right), scale=scale))
            hit = inter > tol_area
            report.overlaps = [
                (int(i), int(j), float(a)) for i, j, a in zip(left[hit], right[hit], inter[hit])
            ]
        if region is not None:
            reg = as_region(region)
            report.region_area = float(reg.area)
            covered, near = _covered(self, reg, outlines, areas, geoms_of, scale)
            if report.overlaps:
                ov = _overlay(
                    shapely.intersection,
                    geoms_of(np.array([i for i, _, _ in report.overlaps])),
                    geoms_of(np.array([j for _, j, _ in report.overlaps])),
                    scale=scale,
                )
                covered -= float(shapely.area(_overlay(shapely.intersection, ov, reg, scale=scale)).sum())
            report.uncovered_area = max(0.0, report.region_area - covered)
            if report.uncovered_area > tol_area:
                # locate the gap (only for an invalid patch): quarter the region's box where
                # area sums show a deficit, and take unions only of the tiles in small boxes
                rest = None
                if _is_box(reg):
                    ov_geoms = ov if report.overlaps else np.zeros(0, dtype=object)
                    rest = _locate_gaps(reg.bounds, near, outlines, areas, geoms_of, ov_geoms, tol_area, scale)
                    if rest.area < 0.5 * report.uncovered_area:
                        rest = None  # spread too thin to locate by boxes
                if rest is None:
                    union = _overlay(shapely.union_all, geoms_of(near), scale=scale)
                    rest = _overlay(shapely.difference, reg, union, scale=scale)
                report.uncovered_area = float(rest.area)
                if not rest.is_empty:
                    report.uncovered_bounds = tuple(float(v) for v in rest.bounds)
        return report

    def covered_area(self, region: Any, *, _tiles: np.ndarray | None = None, _grid: float | None = None) -> float:
        """The sum over tiles of the area of tile ∩ region (overlaps counted twice).

        For a patch without overlaps, ``region.area - covered_area(region)`` is the gap.
        Box regions are clipped with ``clip_by_rect`` (exact, immune to overlay robustness
        problems); other regions with a snap-rounded intersection.
        """
        reg = as_region(region)
        geoms = self.geometries()
        if _tiles is not None:
            geoms = geoms[_tiles]
        if not len(geoms):
            return 0.0
        clipped = None
        if _is_box(reg):
            try:
                clipped = shapely.clip_by_rect(geoms, *reg.bounds)
            except shapely.errors.GEOSException:
                # GEOS can fail on a tile whose vertex lies within float noise of the box's
                # edge (a sliver ring of 3 points); the snap-rounded intersection copes
                clipped = None
        if clipped is None:
            grid = _grid if _grid is not None else 1e-9 * math.sqrt(float(np.median(shapely.area(geoms))))
            clipped = shapely.intersection(geoms, reg, grid_size=grid)
        return float(shapely.area(clipped).sum())

    # output ------------------------------------------------------------------
    def to_svg(self, **options: Any) -> str:
        """SVG text of the patch; options as for :func:`tilekit.render.patch_to_svg`."""

        return patch_to_svg(self, **options)

    def _repr_svg_(self) -> str | None:
        """Jupyter's picture of the patch; None (text only) over limits.MAX_REPR_TILES."""
        return _export().patch_svg_or_none(self)

    def _repr_mimebundle_(self, include: Any = None, exclude: Any = None) -> dict[str, str]:
        """The picture and a text line; over MAX_REPR_TILES a line saying why there is no picture."""
        return _export().patch_mimebundle(self)

    def plot(self, ax: Any = None, colours: str | Sequence[str] | None = None, edges: str | None = "#222",
             **options: Any) -> Any:
        """Draw on a matplotlib Axes as one PolyCollection (the ``plot`` extra); returns the Axes.
        See :func:`tilekit.export.plot_patch`."""
        return _export().plot_patch(self, ax, colours=colours, edges=edges, **options)

    def adjacency(self, tol: float | None = None) -> Adjacency:
        """Tiles sharing an edge (``.edge``), only a vertex (``.vertex``) or any point
        (``.touching``) as (k, 2) index pairs i < j, exact for non-edge-to-edge patches too."""
        return _export().adjacency(self, tol)

    def to_geojson(self, classes: np.ndarray | None = None) -> str:
        """GeoJSON FeatureCollection text, a Polygon feature per tile (prototile, name, colour,
        aspect, and ``transitivity_class`` when ``classes`` is given)."""
        return "".join(_export().iter_geojson(self, classes))

    @property
    def __geo_interface__(self) -> dict[str, Any]:
        """The GeoJSON as a mapping (geopandas.GeoDataFrame.from_features reads it)."""
        return json.loads(self.to_geojson())

    def to_shapely(self) -> np.ndarray:
        """Every tile as a shapely Polygon (object array, tile order, float noise snapped)."""
        return _export().to_shapely(self)

    def tile_table(self, labels: Sequence[str] | np.ndarray | None = None) -> TileTable:
        """A row per tile: centre, angle, reflected, prototile, colour, ``labels`` (a name per
        tile, when given) and edge neighbours (``tilekit render -o tiles.csv``; docs/exports.md)."""
        return _export().tile_table(self, labels)

    def to_geopandas(self, classes: np.ndarray | None = None) -> Any:
        """A GeoDataFrame with a row per tile (the ``geo`` extra)."""
        return _export().to_geopandas(self, classes)

    def to_networkx(self, kind: str = "edge") -> Any:
        """A networkx Graph of the tiles, edges between ``kind`` neighbours (the ``graph`` extra)."""
        return _export().to_networkx(self, kind)

    def to_cut_svg(self, layers: str = "one", **options: Any) -> str:
        """A layered SVG of the edges with each shared edge once, for cutters and plotters."""
        return "".join(_export().iter_cut_svg(self, layers, **options))

    def to_dxf(self, path: Any, layers: str = "one", **options: Any) -> int:
        """Write the edges (each shared edge once) as a DXF file (the ``dxf`` extra); returns the lines."""
        return _export().write_dxf(self, path, layers, **options)


def region_tile_estimate(region: BaseGeometry, prototiles: Sequence[Prototile]) -> float:
    """Tiles of the smallest prototile area that fit in ``region``'s box grown by the largest
    prototile diameter: an upper bound on the tiles meeting the region of any tiling without
    overlaps by these prototiles (float: may be inf for absurd regions)."""
    x0, y0, x1, y1 = region.bounds
    diam = max(float(np.ptp(p.outline, axis=0).max()) for p in prototiles)
    small = min(abs(p.area) for p in prototiles)
    with np.errstate(over="ignore"):
        return float((x1 - x0 + 2 * diam) * (y1 - y0 + 2 * diam) / small)


def _is_box(geom: BaseGeometry) -> bool:
    x0, y0, x1, y1 = geom.bounds
    return abs(geom.area - (x1 - x0) * (y1 - y0)) <= 1e-12 * max(1.0, geom.area)


# --------------------------------------------------------------------------- validate's pieces

#: Pairs of convex pieces tested at once by the separating-axis check (bounds the temporaries).
_SAT_CHUNK = 1 << 17


def _apply_xy(transforms: np.ndarray, pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(m, 3, 3) maps applied to (k, 2) points, as x and y arrays (m, k): element-wise FMAs."""
    px, py = pts[None, :, 0], pts[None, :, 1]
    x = transforms[:, 0, 0, None] * px + transforms[:, 0, 1, None] * py + transforms[:, 0, 2, None]
    y = transforms[:, 1, 0, None] * px + transforms[:, 1, 1, None] * py + transforms[:, 1, 2, None]
    return x, y


class _Outlines:
    """The outlines of a patch's chosen tiles as x / y arrays per prototile, and their boxes."""

    def __init__(self, patch: Patch, chosen: np.ndarray) -> None:
        n = len(patch)
        self.groups: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []  # tiles, x (m, k), y (m, k)
        self.box = np.full((n, 4), np.nan)
        self.where = np.full((n, 2), -1, dtype=np.int64)  # (group, row) of each chosen tile
        for p, proto in enumerate(patch.prototiles):
            idx = np.flatnonzero((patch.prototile == p) & chosen)
            if not len(idx):
                continue
            x, y = _apply_xy(patch.transform[idx], proto.outline)
            self.where[idx, 0] = len(self.groups)
            self.where[idx, 1] = np.arange(len(idx))
            self.groups.append((idx, x, y))
            self.box[idx] = np.column_stack([_rows_min(x), _rows_min(y), _rows_max(x), _rows_max(y)])

    def polygons(self, tiles: np.ndarray, decimals: int) -> np.ndarray:
        """shapely polygons of ``tiles`` (chosen ones) from outlines snapped by snap_noise."""
        out = np.empty(len(tiles), dtype=object)
        for g, (_, x, y) in enumerate(self.groups):
            sel = np.flatnonzero(self.where[tiles, 0] == g)
            if len(sel):
                rows = self.where[tiles[sel], 1]
                out[sel] = shapely.polygons(snap_noise(np.stack([x[rows], y[rows]], axis=-1), decimals=decimals))
        return out


def _convex_pieces(outline: np.ndarray) -> list[np.ndarray]:
    """The outline itself when convex, else its ear-clipped triangles."""
    if np.all(interior_angles(outline) <= math.pi + 1e-9):
        return [outline]
    return ear_clip(outline)


def _pad(pts: np.ndarray, k: int) -> np.ndarray:
    return pts if len(pts) == k else np.vstack([pts, np.repeat(pts[-1:], k - len(pts), axis=0)])


def _candidate_pairs(box: np.ndarray, slack: float) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """Pairs (a, b), a != b, of boxes (x0, y0, x1, y1) that overlap by more than ``slack`` in
    both directions, in batches: a uniform grid of cells as large as the largest box, each box
    filed under its lower-left corner, so overlapping boxes lie in the same or adjacent cells.
    Boxes of very different sizes (a crowded grid) go through an STRtree instead."""
    n = len(box)
    size = float(max((box[:, 2] - box[:, 0]).max(), (box[:, 3] - box[:, 1]).max(), EPS))
    cx = np.floor((box[:, 0] - box[:, 0].min()) / size).astype(np.int64)
    cy = np.floor((box[:, 1] - box[:, 1].min()) / size).astype(np.int64) + 1
    rows = int(cy.max()) + 2
    key = cx * rows + cy
    order = np.argsort(key, kind="stable")
    sk = key[order]
    _, counts = np.unique(sk, return_counts=True)

    x0, y0 = np.ascontiguousarray(box[:, 0]), np.ascontiguousarray(box[:, 1])
    x1, y1 = box[:, 2] - slack, box[:, 3] - slack

    def overlapping(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        keep = (x0[a] < x1[b]) & (x0[b] < x1[a])
        a, b = a[keep], b[keep]
        keep = (y0[a] < y1[b]) & (y0[b] < y1[a])
        return a[keep], b[keep]

    if float((counts.astype(float) ** 2).sum()) * 5 > 64.0 * n + 1e6:
        boxes = shapely.box(box[:, 0], box[:, 1], box[:, 2], box[:, 3])
        a, b = shapely.STRtree(boxes).query(boxes)
        keep = a < b
        yield overlapping(a[keep], b[keep])
        return
    pos = np.arange(n)
    for dx, dy in ((0, 0), (0, 1), (1, -1), (1, 0), (1, 1)):
        if dx == dy == 0:
            lo, hi = pos + 1, np.searchsorted(sk, sk, side="right")
        else:
            target = sk + dx * rows + dy
            lo, hi = np.searchsorted(sk, target, side="left"), np.searchsorted(sk, target, side="right")
        cnt = hi - lo
        total = int(cnt.sum())
        if not total:
            continue
        left = np.repeat(pos, cnt)
        right = np.repeat(lo - (np.cumsum(cnt) - cnt), cnt) + np.arange(total)
        yield overlapping(order[left], order[right])


def _rows_min(x: np.ndarray) -> np.ndarray:
    """Row minima of a narrow (m, k) array (NumPy's reduction over a short axis is slow)."""
    out = x[:, 0].copy()
    for j in range(1, x.shape[1]):
        np.minimum(out, x[:, j], out=out)
    return out


def _rows_max(x: np.ndarray) -> np.ndarray:
    return -_rows_min(-x)


def _unseparated_pairs(patch: Patch, outlines: _Outlines, tol_area: float) -> np.ndarray:
    """Tile pairs (i < j, sorted) whose convex pieces no separating axis keeps apart.

    A pair of convex pieces is separated when on some edge normal of either piece their
    projections meet by at most ``slack``; then their overlap lies in a strip that thin, of
    area at most slack x the largest piece diameter. The slack is chosen so that this, summed
    over the piece pairs of two tiles, stays under a tenth of ``tol_area``: a pair passed here
    cannot overlap by more than the tolerance, and float noise on shared edges (1e-12 of the
    tile size) is far inside the slack.
    """
    pieces = [_convex_pieces(p.outline) for p in patch.prototiles]
    k = max(len(pc) for pcs in pieces for pc in pcs)
    most = max(len(pcs) for pcs in pieces)
    owners, xs, ys = [], [], []
    for idx, x, y in outlines.groups:
        pcs = pieces[int(patch.prototile[idx[0]])]
        for pc in pcs:
            if len(pcs) == 1 and len(pc) == k:  # the outline is the piece: reuse its vertices
                px, py = x, y
            else:
                px, py = _apply_xy(patch.transform[idx], _pad(pc, k))
            owners.append(idx)
            xs.append(px)
            ys.append(py)
    if not owners:
        return np.zeros((0, 2), dtype=np.int64)
    owner = np.concatenate(owners)
    px, py = np.concatenate(xs), np.concatenate(ys)
    box = np.column_stack([_rows_min(px), _rows_min(py), _rows_max(px), _rows_max(py)])
    diameter = float(np.hypot(box[:, 2] - box[:, 0], box[:, 3] - box[:, 1]).max())
    slack = 0.1 * tol_area / (max(diameter, EPS) * most * most)
    nx = np.roll(py, -1, axis=1) - py  # edge normals (unnormalised; outward for CCW pieces)
    ny = px - np.roll(px, -1, axis=1)
    length = np.hypot(nx, ny)
    lo, hi = np.full_like(px, np.inf), np.full_like(px, -np.inf)  # own projections per axis
    for j in range(k):
        v = nx * px[:, j, None] + ny * py[:, j, None]
        np.minimum(lo, v, out=lo)
        np.maximum(hi, v, out=hi)
    # another piece is outside axis e when its projections are >= hi - margin or <= lo + margin;
    # padding repeats a vertex, whose zero-length "edge" is no axis: never separating
    real = length > EPS * max(diameter, EPS)
    hi = np.where(real, hi - slack * length, np.inf)
    lo = np.where(real, lo + slack * length, -np.inf)
    packed = np.concatenate([px, py, nx, ny, hi, lo], axis=1)  # one gather per side of a pair

    def outside(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Rows where some axis of the pieces in ``a`` has every vertex of ``b`` outside."""
        anx, any_, ahi, alo = a[:, 2 * k : 3 * k], a[:, 3 * k : 4 * k], a[:, 4 * k : 5 * k], a[:, 5 * k :]
        bmin = np.full_like(anx, np.inf)
        bmax = np.full_like(anx, -np.inf)
        for j in range(k):
            v = anx * b[:, j, None] + any_ * b[:, k + j, None]
            np.minimum(bmin, v, out=bmin)
            np.maximum(bmax, v, out=bmax)
        sep = (bmin >= ahi) | (bmax <= alo)
        out = sep[:, 0].copy()
        for e in range(1, k):
            out |= sep[:, e]
        return out

    found = []
    for a, b in _candidate_pairs(box, slack):
        keep = owner[a] != owner[b]
        a, b = a[keep], b[keep]
        for s in range(0, len(a), _SAT_CHUNK):
            ca, cb = a[s : s + _SAT_CHUNK], b[s : s + _SAT_CHUNK]
            ra, rb = packed[ca], packed[cb]
            bad = ~outside(ra, rb)
            bad[bad] = ~outside(rb[bad], ra[bad])
            if bad.any():
                found.append(np.column_stack([owner[ca[bad]], owner[cb[bad]]]))
    if not found:
        return np.zeros((0, 2), dtype=np.int64)
    pairs = np.sort(np.concatenate(found), axis=1)
    return np.unique(pairs, axis=0)


def _overlay(fn: Any, *args: Any, scale: float) -> Any:
    """A shapely overlay on the snapped coordinates; GEOS's snap-rounding if the floating
    overlay fails (a TopologyException on nearly coincident edges)."""
    try:
        return fn(*args)
    except shapely.errors.GEOSException:
        return fn(*args, grid_size=1e-9 * scale)


def _locate_gaps(bounds: tuple[float, float, float, float], tiles: np.ndarray, outlines: _Outlines,
                 areas: np.ndarray, geoms_of: Any, overlaps: np.ndarray, tol_area: float, scale: float) -> Any:
    """The uncovered part of the box ``bounds``: boxes whose covered area (tile areas inside,
    boundary tiles clipped, known overlaps subtracted) falls short are quartered until they
    hold few tiles; only there is a union of tiles taken."""
    found = []
    stack = [(bounds, tiles)]
    while stack:
        (x0, y0, x1, y1), idx = stack.pop()
        b = outlines.box[idx]
        idx = idx[(b[:, 2] > x0) & (b[:, 0] < x1) & (b[:, 3] > y0) & (b[:, 1] < y1)]
        cell = shapely.box(x0, y0, x1, y1)
        if len(idx) <= 256:
            union = _overlay(shapely.union_all, geoms_of(idx), scale=scale)
            rest = _overlay(shapely.difference, cell, union, scale=scale)
            if rest.area > 0:
                found.append(rest)
            continue
        b = outlines.box[idx]
        inside = (b[:, 0] >= x0) & (b[:, 2] <= x1) & (b[:, 1] >= y0) & (b[:, 3] <= y1)
        covered = areas[idx[inside]].sum()
        covered += shapely.area(shapely.clip_by_rect(geoms_of(idx[~inside]), x0, y0, x1, y1)).sum()
        if len(overlaps):
            covered -= shapely.area(shapely.clip_by_rect(overlaps, x0, y0, x1, y1)).sum()
        if (x1 - x0) * (y1 - y0) - covered <= tol_area / 64:
            continue
        xm, ym = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        stack += [((x0, y0, xm, ym), idx), ((xm, y0, x1, ym), idx), ((x0, ym, xm, y1), idx), ((xm, ym, x1, y1), idx)]
    return shapely.union_all(found) if found else shapely.Polygon()


def _covered(patch: Patch, reg: BaseGeometry, outlines: _Outlines, areas: np.ndarray,
             geoms_of: Any, scale: float) -> tuple[float, np.ndarray]:
    """(the sum over tiles of area(tile ∩ region), the tiles meeting the region): tiles whose
    box lies inside the region count their whole area, the others are clipped."""
    box = outlines.box
    rx0, ry0, rx1, ry1 = reg.bounds
    with np.errstate(invalid="ignore"):
        cand = (box[:, 2] >= rx0) & (box[:, 0] <= rx1) & (box[:, 3] >= ry0) & (box[:, 1] <= ry1)
    if _is_box(reg):
        inside = cand & (box[:, 0] >= rx0) & (box[:, 2] <= rx1) & (box[:, 1] >= ry0) & (box[:, 3] <= ry1)
        edge = np.flatnonzero(cand & ~inside)
        clipped = shapely.clip_by_rect(geoms_of(edge), rx0, ry0, rx1, ry1) if len(edge) else np.zeros(0)
        return float(areas[inside].sum() + shapely.area(clipped).sum()), np.flatnonzero(cand)
    idx = np.flatnonzero(cand)
    boxes = shapely.box(box[idx, 0], box[idx, 1], box[idx, 2], box[idx, 3])
    shapely.prepare(reg)
    inside = shapely.contains(reg, boxes)
    edge = idx[~inside & shapely.intersects(reg, boxes)]
    part = shapely.area(_overlay(shapely.intersection, geoms_of(edge), reg, scale=scale)).sum() if len(edge) else 0.0
    near = np.union1d(idx[inside], edge)
    return float(areas[idx[inside]].sum() + part), near


# --------------------------------------------------------------------------- Tiling


class Tiling(ABC):
    """A tiling of the plane, whatever its family (the answer to exercise 2.8).

    Every tiling knows its ``family`` and ``name``, its ``prototiles``, can produce a
    ``patch(region)`` covering a region, reports ``properties()`` for the catalogue, and
    round-trips through ``spec()`` / the family's ``from_spec`` as plain JSON.
    """

    family: str = ""
    name: str = ""

    @property
    @abstractmethod
    def prototiles(self) -> list[Prototile]:
        """The distinct tile shapes (k of them for a k-hedral tiling)."""

    @abstractmethod
    def patch(self, region: Any) -> Patch:
        """Tiles covering ``region`` (a shapely geometry or an (x0, y0, x1, y1) box)."""

    #: Whether :meth:`iter_patches` yields bounded chunks (families that can stream a patch
    #: larger than memory set it); otherwise it yields the one patch.
    streams: bool = False

    #: Peak bytes per tile while :meth:`patch` makes a patch (measured per engine, limits.py):
    #: what the memory checks multiply :meth:`estimate_tiles` by.
    bytes_per_tile: int = GENERATION_BYTES_PER_TILE

    def iter_patches(self, region: Any = None, chunk_tiles: int = STREAM_CHUNK_TILES) -> Iterator[Patch]:
        """The tiles of ``patch(region)`` (``region=None``: the default region) as a stream
        of patches with the same prototiles, whose union is that patch, each of about
        ``chunk_tiles`` tiles or fewer when the family streams (:attr:`streams`). Here: the
        one patch."""
        check_chunk_tiles(chunk_tiles)
        yield self.patch(self.default_region() if region is None else region)

    @abstractmethod
    def spec(self) -> dict[str, Any]:
        """A JSON-serialisable description from which the family rebuilds this tiling."""

    def properties(self) -> dict[str, Any]:
        """Facts about this tiling the catalogue indexes (JSON scalars or lists)."""
        return {}

    def describe(self) -> str:
        """Extra human-readable text for ``tilekit show`` (e.g. an isohedral template)."""
        return ""

    def configure(self, **options: Any) -> Tiling:
        """A new tiling with user options applied (parameters, edge shapes, depth ...).

        The CLI passes ``params`` (list of floats), ``edges`` (list of 'name=x,y:x,y'
        strings), ``depth`` (int) and ``colours``/free ``KEY=VALUE`` options here. The base
        class accepts none; families override and reject what they do not understand.
        """
        if options:
            raise ParameterError(
                f"{self.name or type(self).__name__} takes no options "
                f"({', '.join(sorted(options))} given)"
            )
        return self

    def options_help(self) -> str:
        """The options ``configure`` takes (``tilekit render --set KEY=VALUE``, --param, --edge,
        --depth), one line each, for ``tilekit show FAMILY``."""
        return "(no options)"

    def default_region(self) -> BaseGeometry:
        """A region showing a representative piece of the tiling (used when none is given)."""
        scale = math.sqrt(max(abs(p.area) for p in self.prototiles))
        return shapely.box(-4 * scale, -4 * scale, 4 * scale, 4 * scale)

    def estimate_tiles(self, region: Any = None) -> float:
        """About how many tiles ``patch(region)`` makes (``region=None``: the default region),
        computed cheaply and before anything is allocated; an upper bound up to a small factor.

        Callers compare it with :data:`tilekit.limits.MAX_TILES` (``tilekit render
        --max-tiles``). The default counts tiles of the smallest prototile's area in the
        region grown by the largest prototile's diameter; families override it with what they
        know (lattice cells times unit size, substitution counts).
        """
        reg = self.default_region() if region is None else as_region(region)
        return region_tile_estimate(reg, self.prototiles)

    def tile_labels(self, patch: Patch, region: Any = None) -> np.ndarray | None:
        """A name per tile of ``patch`` (made by ``self.patch(region)``) for tile tables, e.g.
        the hat's level-0 metatile H, T, P or F, or None when the family has none (the
        table's ``label`` column is then left out)."""
        return None

    def render_svg(self, patch: Patch, **options: Any) -> str:
        """SVG text of a patch of this tiling (``tilekit render`` draws through it); options as
        for :func:`tilekit.render.patch_to_svg`. Families with their own picture (Wang tiles'
        edge colours) override it."""
        return patch_to_svg(patch, **options)

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.family}/{self.name}>"

    def _repr_mimebundle_(self, include: Any = None, exclude: Any = None) -> dict[str, str]:
        """Jupyter draws a patch of the default region (estimated first; over
        limits.MAX_REPR_TILES a line of text instead)."""
        return _export().tiling_mimebundle(self)

    def _repr_svg_(self) -> str | None:
        """The picture of :meth:`_repr_mimebundle_`, or None over limits.MAX_REPR_TILES."""
        return _export().tiling_mimebundle(self).get("image/svg+xml")


#: A periodic tiling's default picture: about this many translational units ...
DEFAULT_UNITS = 9
#: ... and at least this many tiles' area.
DEFAULT_MIN_TILES = 30


class PeriodicTiling(Tiling):
    """A tiling given by a translational unit (placed tiles) and two translation vectors.

    ``unit_prototile[i]`` / ``unit_transform[i]`` place tile i of the unit; ``unit_aspect[i]``
    is its aspect number (default i); the ``colouring`` assigns colours per aspect and
    permutes them from unit to unit (§5.4.3).
    """

    bytes_per_tile = PERIODIC_BYTES_PER_TILE

    def __init__(
        self,
        prototiles: Sequence[Prototile],
        unit_prototile: Sequence[int],
        unit_transform: np.ndarray,
        v1: Sequence[float],
        v2: Sequence[float],
        colouring: Colouring | None = None,
        unit_aspect: Sequence[int] | None = None,
        *,
        family: str = "",
        name: str = "",
    ) -> None:
        self._prototiles = list(prototiles)
        self.unit_prototile = np.asarray(unit_prototile, dtype=np.int64).reshape(-1)
        m = len(self.unit_prototile)
        if m == 0:
            raise GeometryError("a translational unit needs at least one tile")
        if self.unit_prototile.min() < 0 or self.unit_prototile.max() >= len(self._prototiles):
            raise GeometryError(
                f"translational unit names prototile(s) outside 0..{len(self._prototiles) - 1}"
            )
        self.unit_transform = np.asarray(unit_transform, dtype=float).reshape(m, 3, 3)
        self.unit_aspect = (
            np.arange(m, dtype=np.int64) if unit_aspect is None else np.asarray(unit_aspect, dtype=np.int64)
        )
        if len(self.unit_aspect) != m or (m and self.unit_aspect.min() < 0):
            raise GeometryError(f"translational unit needs {m} aspect numbers >= 0, got {self.unit_aspect.tolist()}")
        self.v1 = np.asarray(v1, dtype=float).reshape(2)
        self.v2 = np.asarray(v2, dtype=float).reshape(2)
        if not (np.isfinite(self.v1).all() and np.isfinite(self.v2).all()):
            raise GeometryError(f"translation vectors {self.v1.tolist()}, {self.v2.tolist()} must be finite")
        det = self.v1[0] * self.v2[1] - self.v1[1] * self.v2[0]
        if not np.isfinite(det) or abs(det) < EPS:
            raise GeometryError(
                f"translation vectors {self.v1.tolist()} and {self.v2.tolist()} are parallel or zero"
            )
        aspects = int(self.unit_aspect.max()) + 1
        self.colouring = colouring or Colouring.by_aspect(self._default_colours())
        if len(self.colouring.aspects) < aspects:
            raise ParameterError(
                f"colouring {self.colouring} gives {len(self.colouring.aspects)} aspect colours, "
                f"the unit has {aspects} aspects"
            )
        self.family = family
        self.name = name
        self._unit_bounds: np.ndarray | None = None

    def _default_colours(self) -> list[int]:
        """Default: colour by prototile."""
        colours = [0] * (int(self.unit_aspect.max()) + 1)
        for a, p in zip(self.unit_aspect, self.unit_prototile):
            colours[int(a)] = int(p)
        return colours

    @property
    def prototiles(self) -> list[Prototile]:
        return self._prototiles

    @property
    def basis(self) -> np.ndarray:
        """2x2 matrix with v1 and v2 as columns."""
        return np.column_stack([self.v1, self.v2])

    def unit(self) -> Patch:
        """The translational unit as a patch (lattice point (0, 0))."""
        colours = self.colouring.colour(self.unit_aspect, np.zeros(len(self.unit_aspect)), np.zeros(len(self.unit_aspect)))
        return Patch(self._prototiles, self.unit_prototile, self.unit_transform, colours, self.unit_aspect)

    def unit_tile_bounds(self) -> np.ndarray:
        if self._unit_bounds is None:
            self._unit_bounds = Patch(self._prototiles, self.unit_prototile, self.unit_transform).tile_bounds()
        return self._unit_bounds

    def _lattice_corners(self, reg: BaseGeometry) -> tuple[tuple[float, float, float, float], np.ndarray]:
        rx0, ry0, rx1, ry1 = reg.bounds
        ub = self.unit_tile_bounds()
        ux0, uy0 = ub[:, 0].min(), ub[:, 1].min()
        ux1, uy1 = ub[:, 2].max(), ub[:, 3].max()
        ex0, ex1 = rx0 - ux1, rx1 - ux0
        ey0, ey1 = ry0 - uy1, ry1 - uy0
        inv = np.linalg.inv(self.basis)
        corners = np.array([[ex0, ey0], [ex1, ey0], [ex1, ey1], [ex0, ey1]]) @ inv.T
        return (float(ex0), float(ey0), float(ex1), float(ey1)), corners

    def _lattice_box(self, reg: BaseGeometry) -> tuple[tuple[float, float, float, float], float]:
        """The translation box R (-) U and the number of lattice cells to enumerate (a float,
        computed without allocating; inf for absurd regions)."""
        box, corners = self._lattice_corners(reg)
        span = np.floor(corners.max(axis=0) + 1e-9) - np.floor(corners.min(axis=0) - 1e-9) + 2
        with np.errstate(over="ignore", invalid="ignore"):
            cells = float(span[0] * span[1])
        return box, cells if math.isfinite(cells) else math.inf

    def _lattice_range(self, reg: BaseGeometry) -> tuple[np.ndarray, np.ndarray]:
        _, corners = self._lattice_corners(reg)
        lo = np.floor(corners.min(axis=0) - 1e-9).astype(np.int64)
        hi = np.ceil(corners.max(axis=0) + 1e-9).astype(np.int64)
        return lo, hi

    def estimate_tiles(self, region: Any = None) -> float:
        """Lattice cells the rasterization enumerates times the tiles of the unit."""
        reg = self.default_region() if region is None else as_region(region)
        return self._lattice_box(reg)[1] * len(self.unit_prototile)

    def lattice_points(self, region: Any) -> np.ndarray:
        """Integer (a, b) whose unit copy's bounding box can meet the region's bounding box.

        The set of translations t for which the unit's box meets the region's box is the box
        R (-) U (Minkowski difference); its preimage under the lattice basis is a
        parallelogram whose integer points we enumerate. No ring count is guessed (§3.5).
        """
        return self._lattice(region)[0]

    def _lattice(self, region: Any) -> tuple[np.ndarray, np.ndarray]:
        """The lattice points (L, 2) of :meth:`lattice_points` and their translations (L, 2)."""
        reg = as_region(region)
        (ex0, ey0, ex1, ey1), cells = self._lattice_box(reg)
        if cells > MAX_LATTICE_CELLS:
            raise ParameterError(
                f"region {tuple(round(v, 3) for v in reg.bounds)} needs {cells:.3g} translational units; "
                f"the limit is {MAX_LATTICE_CELLS} (use a smaller region)"
            )
        lo, hi = self._lattice_range(reg)
        # for each a, the b whose translation can lie in the box (solved from the two linear
        # constraints, one wider each side), then the exact test below on those candidates only
        a = np.arange(lo[0], hi[0] + 1)
        b_lo = np.full(len(a), float(lo[1]))
        b_hi = np.full(len(a), float(hi[1]))
        tol = 1e-9
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            for axis, (e0, e1) in enumerate(((ex0, ex1), (ey0, ey1))):
                u, w = self.v1[axis], self.v2[axis]
                if abs(w) > EPS:
                    r0, r1 = (e0 - tol - a * u) / w, (e1 + tol - a * u) / w
                    b_lo = np.maximum(b_lo, np.floor(np.minimum(r0, r1)) - 1)
                    b_hi = np.minimum(b_hi, np.ceil(np.maximum(r0, r1)) + 1)
        count = np.maximum(0, b_hi - b_lo + 1).astype(np.int64)
        total = int(count.sum())
        ab = np.empty((total, 2), dtype=np.int64)
        ab[:, 0] = np.repeat(a, count)
        ab[:, 1] = np.repeat(b_lo.astype(np.int64) - (np.cumsum(count) - count), count) + np.arange(total)
        t = ab @ self.basis.T
        keep = (t[:, 0] >= ex0 - tol) & (t[:, 0] <= ex1 + tol) & (t[:, 1] >= ey0 - tol) & (t[:, 1] <= ey1 + tol)
        return ab[keep], t[keep]

    def patch(self, region: Any) -> Patch:
        """Every tile whose bounding box meets the region's, by lattice rasterization (§3.4).

        The per-tile box test runs over blocks of lattice points small enough to stay in the
        cache, and each block's tiles are written straight into the output columns, so the
        cost per tile stays flat from 10^4 to 10^7 tiles.
        """
        reg = as_region(region)
        ab, t = self._lattice(reg)  # (L, 2) lattice points and their translations
        rx0, ry0, rx1, ry1 = reg.bounds
        ub = self.unit_tile_bounds()  # (m, 4)
        m = len(ub)
        ux0, uy0, ux1, uy1 = (np.ascontiguousarray(ub[:, j]) for j in range(4))
        step = max(1, _PATCH_BLOCK // m)
        blocks = []
        for s in range(0, len(t), step):
            tx, ty = t[s : s + step, 0, None], t[s : s + step, 1, None]
            hit = (ux1 + tx > rx0 + EPS) & (ux0 + tx < rx1 - EPS) & (uy1 + ty > ry0 + EPS) & (uy0 + ty < ry1 - EPS)
            if hit.all():
                blocks.append((s, None, None))
            else:
                li, ti = np.nonzero(hit)
                blocks.append((s, li, ti))
        sizes = [len(t[s : s + step]) * m if li is None else len(li) for s, li, _ in blocks]
        n = int(sum(sizes))
        transforms = np.empty((n, 3, 3))
        prototile = np.empty(n, dtype=np.int64)
        aspect = np.empty(n, dtype=np.int64)
        colour = np.empty(n, dtype=np.int64)
        at = 0
        template: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        ident = tuple(range(len(self.colouring.p)))
        fixed = self.colouring.p == ident and self.colouring.q == ident  # colours by aspect only
        by_aspect = np.asarray(self.colouring.aspects, dtype=np.int64)
        for (s, li, ti), size in zip(blocks, sizes):
            end = at + size
            if li is None:  # every tile of every unit in the block: copy the tiled unit
                count = size // m
                if template is None:
                    template = (np.tile(self.unit_transform, (step, 1, 1)), np.tile(self.unit_prototile, step),
                                np.tile(self.unit_aspect, step))
                transforms[at:end] = template[0][:size]
                flat = transforms[at:end].reshape(count, m, 9)
                flat[:, :, 2] += t[s : s + count, 0, None]
                flat[:, :, 5] += t[s : s + count, 1, None]
                prototile[at:end] = template[1][:size]
                aspect[at:end] = template[2][:size]
                a_of = b_of = None
                if not fixed:
                    a_of, b_of = np.repeat(ab[s : s + count, 0], m), np.repeat(ab[s : s + count, 1], m)
            else:
                np.take(self.unit_transform, ti, axis=0, out=transforms[at:end])
                transforms[at:end, :2, 2] += t[s + li]
                np.take(self.unit_prototile, ti, out=prototile[at:end])
                np.take(self.unit_aspect, ti, out=aspect[at:end])
                a_of, b_of = (None, None) if fixed else (ab[s + li, 0], ab[s + li, 1])
            if fixed:
                np.take(by_aspect, aspect[at:end], out=colour[at:end])
            else:
                colour[at:end] = self.colouring.colour(aspect[at:end], a_of, b_of)
            at = end
        patch = Patch(self._prototiles, prototile, transforms, colour, aspect)
        if not _is_box(reg):
            patch = patch.clip(reg)
        return patch

    def default_region(self) -> BaseGeometry:
        """A square of about DEFAULT_UNITS translational units (and DEFAULT_MIN_TILES tiles),
        at least three tile diameters wide: a few units, whatever the lattice's shape (a box
        round the unit's tiles would hold thousands of tiles for a long, thin period cell)."""
        cell = abs(float(np.linalg.det(self.basis)))
        tiles = max(1, len(self.unit_prototile))
        area = max(DEFAULT_UNITS * cell, DEFAULT_MIN_TILES * cell / tiles)
        diameter = max(float(np.ptp(p.outline, axis=0).max()) for p in self._prototiles)
        half = max(math.sqrt(area), 3 * diameter) / 2
        return shapely.box(-half, -half, half, half)

    def properties(self) -> dict[str, Any]:
        return {
            "periodic": True,
            "k_hedral": len(self._prototiles),
            "tiles_per_unit": int(len(self.unit_prototile)),
            "aspects": int(self.unit_aspect.max()) + 1,
            "colours": self.colouring.colours,
        }

    def spec(self) -> dict[str, Any]:
        """A self-contained JSON description (families may store something more compact)."""
        return {
            "kind": "periodic",
            "prototiles": [p.to_json() for p in self._prototiles],
            "unit": [
                {"prototile": int(p), "transform": np.round(tr[:2], 12).tolist(), "aspect": int(a)}
                for p, tr, a in zip(self.unit_prototile, self.unit_transform, self.unit_aspect)
            ],
            "v1": self.v1.tolist(),
            "v2": self.v2.tolist(),
            "colouring": str(self.colouring),
            "name": self.name,
            "family": self.family,
        }

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> PeriodicTiling:
        try:
            protos = [Prototile.from_json(p) for p in spec["prototiles"]]
            unit = spec["unit"]
            transforms = np.array([np.vstack([u["transform"], [0.0, 0.0, 1.0]]) for u in unit], dtype=float)
            return cls(
                protos,
                [u["prototile"] for u in unit],
                transforms,
                spec["v1"],
                spec["v2"],
                Colouring.parse(spec["colouring"]) if spec.get("colouring") else None,
                [u.get("aspect", i) for i, u in enumerate(unit)],
                family=spec.get("family", ""),
                name=spec.get("name", ""),
            )
        except (KeyError, TypeError, ValueError, IndexError, AttributeError, OverflowError) as exc:
            if isinstance(exc, ParseError | GeometryError | ParameterError):
                raise
            raise ParseError(f"periodic tiling spec is malformed: {str(exc)[:120]!r}") from None
