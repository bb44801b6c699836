"""Split isohedral tilings (Kaplan and Salesin's dihedral Escherization, 2004; Kaplan 2009,
§7.3): an isohedral tile divided into two prototiles by a splitting path between two points
of its boundary, every copy of the tile split the same way, so the tiling is dihedral.

A split is ``{"ends": [s, t], "path": "x,y:...:1,0"}``. An end ``s`` names a boundary point
by tiling edge and position along that edge's drawn path: edge ``floor(s)`` (numbered as the
incidence symbol's edges, 0-based), a fraction ``s - floor(s)`` of the way along its segments.
``path`` is a polyline from (0, 0) to (1, 0) (the :class:`~.shapes.EdgeShape` syntax) in the
frame of the chord from end s to end t, so the path follows the tile when its parameters or
edge shapes are edited. Piece 0 is the part of the tile to the left of the path walked from s
to t (the boundary from s to t counter-clockwise, then the path back), piece 1 the rest.

:func:`piece_rows` describes both pieces as rows of (vertex, next vertex, fraction) over the
tile's outline followed by the path's interior points; the tiling here and the fit
(:mod:`.dihedral`, where the rows act on a linear model of the outline) both use it.

On the command line and in the editor's URL a split is one option, ``split=S,T`` (a straight
path) or ``split=S,T;PATH`` (``--set split=0.4,3.6;0,0:0.3,0.15:1,0``, ``set=split=...`` in a
query): :func:`split_text` writes it, :func:`parse_split` reads it back and
``IsohedralTiling.configure(split=...)`` builds the split tiling (``split=none`` removes it).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from tilekit.edgeshapes import EdgeShape
from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.geometry import snap_noise
from tilekit.polygon import signed_area
from tilekit.schema import Field, check, finite_number
from tilekit.tiling import Patch, PeriodicTiling, Prototile

if TYPE_CHECKING:  # engine.py imports this module when a split is asked for
    from tilekit.plugins.isohedral.engine import IsohedralTiling

#: The spec's ``split`` table.
SPLIT = Field("table", fields={
    "ends": Field("list", items=Field("number"), length=(2, 2), required=True,
                  missing="'ends' is missing; give two boundary positions [s, t] (edge index + fraction)"),
    "path": Field("str"),
    "colour": Field("str"),
})
#: How a split tiling's pieces are coloured (``--set split_colour=...``, the spec's split.colour):
#: by piece (the two prototiles, the default), by the base tile they split (the isohedral
#: tiling's own colouring, both pieces alike), or by transitivity class under the split
#: tiling's symmetry group (tilekit.symmetry.tile_orbits: a Heaven-and-Hell split whose pieces
#: are congruent by a symmetry of the tiling has one class).
SPLIT_COLOURS = ("piece", "tile", "class")
#: Relative tolerance of the pieces' areas summing to the tile's.
AREA_TOL = 1e-9


def checked_split(split: Any, edges: int) -> tuple[float, float, EdgeShape]:
    """``{"ends": [s, t], "path": ...}`` checked: two positions in [0, edges) that differ and a
    path (straight when absent); a ParseError/ParameterError naming what is wrong."""
    if not isinstance(split, Mapping):
        raise ParseError(f'isohedral spec split {split!r} is not an object like {{"ends": [0.5, 2.5], "path": "0,0:1,0"}}')
    data = check(SPLIT, dict(split), "isohedral spec split")
    s, t = (float(v) for v in data["ends"])
    for v in (s, t):
        if not (0.0 <= v < edges):
            raise ParameterError(f"split end {v:g} must lie in [0, {edges}): the tile has {edges} tiling edges "
                                 "(integer part: edge index, fraction: position along it)")
    if s == t:
        raise ParameterError(f"split ends {s:g} and {t:g} are the same point; give two different boundary positions")
    path = EdgeShape.parse(data["path"]) if data.get("path") else EdgeShape.straight()
    return s, t, path


def parse_split(value: Any) -> dict[str, Any] | None:
    """A split option as the spec's table: ``"S,T"``, ``"S,T;PATH"``, a ``{"ends", "path"}``
    mapping, or ``"none"``/``""`` (no split: None); a ParseError naming the syntax otherwise."""
    if value is None or isinstance(value, Mapping):
        return None if value is None else dict(value)
    if not isinstance(value, str):
        raise ParseError(f"split {value!r} is not text like '0.4,3.6;0,0:0.3,0.15:1,0' (ends S,T; path)")
    text = value.strip()
    if text.lower() in ("", "none"):
        return None
    ends, _, path = text.partition(";")
    parts = [v for v in ends.split(",")]
    if len(parts) != 2:
        raise ParseError(f"split {text[:80]!r}: give two ends 'S,T' (boundary positions: edge index + fraction), "
                         "then optionally ';' and a path 'x,y:x,y:...' from 0,0 to 1,0")
    try:
        s, t = (float(v) for v in parts)
    except ValueError:
        raise ParseError(f"split ends {ends[:60]!r} are not two numbers 'S,T' (edge index + fraction)") from None
    out: dict[str, Any] = {"ends": [s, t]}
    if path.strip():
        out["path"] = path.strip()
    return out


def number_text(value: float) -> str:
    """The shortest text that float() reads back as exactly ``value`` (repr, without ``.0``)."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def split_text(split: Mapping[str, Any]) -> str:
    """The option text of a spec's split table (the inverse of :func:`parse_split`; numbers as
    their shortest round-trip text, the path as given)."""
    ends = ",".join(number_text(finite_number(v, "split end")) for v in split["ends"])
    path = split.get("path")
    return f"{ends};{path}" if path else ends


def outline_position(counts: np.ndarray, s: float) -> float:
    """Boundary position ``s`` (edge + fraction) as a fractional outline vertex index, for an
    outline whose tiling edge e has ``counts[e]`` segments."""
    e = min(int(math.floor(s)), len(counts) - 1)
    first = np.concatenate([[0], np.cumsum(counts)])
    return float(first[e] + (s - e) * counts[e])


def boundary_position(counts: np.ndarray, u: float) -> float:
    """The inverse of :func:`outline_position`: fractional vertex index -> edge + fraction."""
    first = np.concatenate([[0], np.cumsum(counts)])
    m = float(first[-1])
    u = u % m
    e = int(np.searchsorted(first, u, side="right") - 1)
    e = min(max(e, 0), len(counts) - 1)
    return float(e + (u - first[e]) / counts[e])


def end_row(m: int, w: float) -> tuple[float, float, float]:
    """The row (i, i + 1, f) of the boundary point at fractional vertex index w of an m-gon."""
    i = int(math.floor(w)) % m
    return float(i), float((i + 1) % m), w - math.floor(w)


def piece_rows(m: int, u: float, v: float, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The two pieces of an m-vertex outline cut at fractional vertex indices u and v by a path
    of k interior points, as (rows, 3) arrays ``(i, j, f)``: piece vertex = (1 - f) P[i] + f P[j]
    over the point table P = outline vertices 0..m-1, then the path's points m..m+k-1 (from u
    to v). Piece 0 walks the outline from u to v then the path back, piece 1 from v to u then
    the path forward: both counter-clockwise when the outline is and the path lies inside."""

    def between(a: float, b: float) -> list[tuple[float, float, float]]:
        span = (b - a) % m
        lo, hi = math.floor(a) + 1, math.ceil(a + span) - 1
        return [(float(i % m), float(i % m), 0.0) for i in range(lo, hi + 1)]

    path = [(float(m + j), float(m + j), 0.0) for j in range(k)]
    p0 = [end_row(m, u), *between(u, v), end_row(m, v), *path[::-1]]
    p1 = [end_row(m, v), *between(v, u), end_row(m, u), *path]
    return np.array(p0, dtype=float), np.array(p1, dtype=float)


def apply_rows(rows: np.ndarray, table: np.ndarray) -> np.ndarray:
    """Evaluate :func:`piece_rows` rows on a point table (complex (R,) or any (R, ...) array)."""
    i, j, f = rows[:, 0].astype(np.int64), rows[:, 1].astype(np.int64), rows[:, 2]
    f = f.reshape((-1,) + (1,) * (table.ndim - 1))
    return (1 - f) * table[i] + f * table[j]


def split_pieces(outline: np.ndarray, counts: np.ndarray, s: float, t: float, path: EdgeShape) -> list[np.ndarray]:
    """The two piece outlines ((k, 2) arrays) of a tile outline split from position s to t."""
    z = np.asarray(outline, dtype=float)
    z = z[:, 0] + 1j * z[:, 1]
    m = len(z)
    u, v = outline_position(counts, s), outline_position(counts, t)
    zu, zv = apply_rows(np.array([end_row(m, u), end_row(m, v)]), z)
    local = path.path()[1:-1]
    inner = zu + (zv - zu) * (local[:, 0] + 1j * local[:, 1])
    table = np.concatenate([z, inner])
    out = []
    for rows in piece_rows(m, u, v, len(inner)):
        w = apply_rows(rows, table)
        keep = np.abs(w - np.roll(w, 1)) > 1e-12 * max(1.0, float(np.abs(z).max()))
        w = w[keep]
        out.append(np.column_stack([w.real, w.imag]))
    return out


def check_pieces(tile_area: float, pieces: list[np.ndarray]) -> str:
    """'' if both pieces are simple, counter-clockwise polygons whose areas sum to the tile's
    (the path runs inside the tile, crossing neither the boundary nor itself), else why not."""
    areas = []
    for i, q in enumerate(pieces):
        if len(q) < 3:
            return f"piece {i} has fewer than 3 distinct vertices"
        if not shapely.is_simple(shapely.linearrings(q)):
            return f"piece {i} crosses itself (the splitting path crosses the tile's boundary or itself)"
        areas.append(signed_area(q))
    if min(areas) <= AREA_TOL * abs(tile_area):
        return "a piece has no area (the splitting path leaves the tile)"
    if abs(sum(areas) - tile_area) > 1e-7 * abs(tile_area):
        return f"the pieces' areas {areas[0]:.6g} + {areas[1]:.6g} are not the tile's {tile_area:.6g}"
    return ""


class SplitTiling(PeriodicTiling):
    """A dihedral tiling: every tile of an isohedral tiling split by the same path
    (``SplitTiling(IsohedralTiling("IH1"), 0.5, 3.5, EdgeShape.parse("0.5,0.2"))``).

    The prototiles are the two pieces; the translational unit is the isohedral unit with each
    tile replaced by its two pieces under the same transform, coloured by piece.
    """

    def __init__(self, base: IsohedralTiling, s: float, t: float, path: EdgeShape | None = None,
                 colour: str = "piece") -> None:
        if colour not in SPLIT_COLOURS:
            raise ParameterError(f"split colour {colour!r} is not one of {', '.join(SPLIT_COLOURS)}")
        self.base = base
        self.colour = colour
        path = path or EdgeShape.straight()
        self.ends = (float(s), float(t))
        self.path = path
        counts = np.array([len(p) - 1 for p in base.edge_paths], dtype=np.int64)
        self.counts = counts
        s, t, path = checked_split({"ends": [s, t], "path": path.to_text()}, len(counts))
        outline = np.asarray(base.prototile.outline, dtype=float)
        pieces = split_pieces(outline, counts, s, t, path)
        why = check_pieces(signed_area(outline), pieces)
        if why:
            raise GeometryError(f"{base.name} split {self.ends[0]:g} -> {self.ends[1]:g}: {why}; "
                                "give ends on different parts of the boundary and a path inside the tile")
        protos = [Prototile(q, name=f"{base.name} piece {i}") for i, q in enumerate(pieces)]
        n = len(base.unit_prototile)
        transforms = np.repeat(base.unit_transform, 2, axis=0)
        if colour == "tile":  # the base tile's aspect and colouring on both its pieces
            colouring, aspect = base.colouring, np.repeat(base.unit_aspect, 2)
        else:
            colouring, aspect = None, np.tile([0, 1], n)
        super().__init__(protos, np.tile([0, 1], n), transforms, base.v1, base.v2, colouring, aspect,
                         family=base.family, name=f"{base.name} split")
        if colour == "class":  # start-up cost: the symmetry search, only for this colouring
            from tilekit.symmetry import tile_orbits

            orbits = tile_orbits(self)
            super().__init__(protos, np.tile([0, 1], n), transforms, base.v1, base.v2, None, orbits,
                             family=base.family, name=f"{base.name} split")

    def patch(self, region: Any) -> Patch:
        """The base tiling's tiles, each as its two pieces (transforms snapped as the base's)."""
        out = super().patch(region)
        out.transform = snap_noise(out.transform, 0.0, decimals=12)
        out._geoms = None
        return out

    def configure(self, **options: Any) -> PeriodicTiling:
        """The base tiling configured (params, edges, colouring), split by ``split`` if given
        (``"none"``: unsplit) or else by this tiling's split again (so the path follows the
        tile); the split is checked on the new tile."""
        split = options.pop("split", self._split_table())
        colour = options.pop("split_colour", None)
        if colour is None and isinstance(split, Mapping) and "colour" not in split:
            colour = self.colour
        return with_split(self.base.configure(**options), split, colour)

    def options_help(self) -> str:
        return self.base.options_help()

    def default_region(self) -> Any:
        return self.base.default_region()

    def _split_table(self) -> dict[str, Any]:
        out: dict[str, Any] = {"ends": list(self.ends), "path": self.path.to_text()}
        if self.colour != "piece":
            out["colour"] = self.colour
        return out

    def spec(self) -> dict[str, Any]:
        out = self.base.spec()
        out["split"] = self._split_table()
        return out

    def properties(self) -> dict[str, Any]:
        return {"prototiles": 2, "isohedral_type": self.base.template.ih, "split": True}

    def describe(self) -> str:
        return (self.base.describe() + f"\nsplit from boundary position {self.ends[0]:g} to {self.ends[1]:g} "
                f"along {self.path.to_text()} (two prototiles)")


def split_from_spec(spec: Mapping[str, Any], base: IsohedralTiling) -> SplitTiling:
    """The split tiling of ``spec["split"]`` over the isohedral tiling ``base``."""
    s, t, path = checked_split(spec["split"], len(base.edge_paths))
    return SplitTiling(base, s, t, path, str(spec["split"].get("colour") or "piece"))


def with_split(base: IsohedralTiling, split: Any, colour: str | None = None) -> PeriodicTiling:
    """``base`` split by a split option (:func:`parse_split`: text, a table, or none), its
    pieces coloured by ``colour`` (one of SPLIT_COLOURS; default the table's, else by piece)."""
    table = parse_split(split)
    if table is None:
        if colour is not None:
            raise ParameterError("split_colour applies to a split tiling; give split=S,T too")
        return base
    if colour is not None:
        table["colour"] = colour
    return split_from_spec({"split": table}, base)
