"""Metamorphoses of isohedral tilings (Kaplan 2009, §7.3 and exercise 5.13's parquet
deformations): a strip whose tiles change from one tiling's tile (left) to another's (right)
of the same type and tiling vertices, e.g. from a simple tile to an Escherized figure.

Every edge of every tile takes the shapes interpolated at the x of its straight midpoint across
the strip (control points ``(1 - t) * start + t * end``). An edge shared by two tiles has one
midpoint, so one shape: the strip is a tiling whose tiles change from column to column. The
tiling vertices stay fixed, so the tiles' transforms (which depend on them only) come from one
patch of the end tiling. This generalises the web editor's parquet deformation (4^4 types with
fixed square tiling vertices, straight to shaped) to every unmarked type, any shared parameters
and any two edge-shape keyframes with the same numbers of points.
"""

from __future__ import annotations

import math

import numpy as np

from tilekit.edgeshapes import EdgeShape
from tilekit.errors import ParameterError
from tilekit.geometry import Affine
from tilekit.plugins.isohedral.engine import IsohedralTiling
from tilekit.tiling import Patch, Prototile

#: Strip size bounds (columns and rows of tile-sized cells): the strip is built tile by tile.
MAX_COLUMNS, MAX_ROWS = 40, 20
#: Interpolation steps (t is rounded to 1/STEPS, so tiles are built at most STEPS + 1 times).
STEPS = 1000


def _keyframe_shapes(start: IsohedralTiling, end: IsohedralTiling) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """Both keyframes' shapes as point arrays of equal length per label (a missing shape is
    straight, with the other keyframe's number of points), or a ParameterError."""
    if start.template.ih != end.template.ih:
        raise ParameterError(f"a metamorphosis needs two tilings of one type, got {start.name} and {end.name}")
    if not np.allclose(start.params, end.params, rtol=0, atol=1e-12):
        raise ParameterError(f"{end.name}: a metamorphosis keeps the tiling vertices fixed; the keyframes' parameters "
                             f"{list(start.params)} and {list(end.params)} differ (give both the same params)")
    a, b = {}, {}
    for label in set(start.edge_shapes) | set(end.edge_shapes):
        sa, sb = start.edge_shapes.get(label), end.edge_shapes.get(label)
        if (sa is not None and sa.smooth) or (sb is not None and sb.smooth):
            raise ParameterError(f"{end.name}: edge {label}: a metamorphosis interpolates polylines, not Bézier shapes")
        pa = sa.points if sa is not None else None
        pb = sb.points if sb is not None else None
        k = len(pa if pa is not None else pb)
        straight = np.column_stack([np.linspace(0.0, 1.0, k), np.zeros(k)])
        pa = straight if pa is None else pa
        pb = straight if pb is None else pb
        if len(pa) != len(pb):
            raise ParameterError(f"{end.name}: edge {label} has {len(pa)} points at the start and {len(pb)} at the end; "
                                 "a metamorphosis interpolates shapes with the same number of points")
        a[label], b[label] = np.asarray(pa), np.asarray(pb)
    return a, b


def metamorphosis(start: IsohedralTiling, end: IsohedralTiling, columns: int = 12, rows: int = 3
                  ) -> tuple[Patch, tuple[float, float, float, float]]:
    """The strip ``[0, W] x [0, H]`` (W, H: ``columns`` and ``rows`` times the tile's size) of
    tiles interpolated from ``start`` (t = 0 at x <= 0) to ``end`` (t = 1 at x >= W), as a Patch
    (one prototile per tile, colours of the end tiling's colouring) and the strip's box."""
    if not (isinstance(columns, int) and 2 <= columns <= MAX_COLUMNS and isinstance(rows, int) and 1 <= rows <= MAX_ROWS):
        raise ParameterError(f"a metamorphosis takes 2..{MAX_COLUMNS} columns and 1..{MAX_ROWS} rows, "
                             f"not {columns!r} x {rows!r}")
    shapes_a, shapes_b = _keyframe_shapes(start, end)
    size = math.sqrt(abs(end.prototile.area))
    width, height = columns * size, rows * size
    patch = end.patch((-size, -size, width + size, height + size))  # tiles poking into the strip too
    corners = list(end.prototile.corners or ())
    if len(corners) != len(end.edge_paths):
        raise ParameterError(f"{end.name}: the prototile does not name its tiling vertices; cannot interpolate edges")
    straight = np.asarray(end.prototile.outline)[corners]
    cache: dict[int, list[np.ndarray]] = {}

    def edge_paths(t: float) -> list[np.ndarray]:
        q = int(round(min(1.0, max(0.0, t)) * STEPS))
        if q not in cache:
            u = q / STEPS
            shapes = {lab: EdgeShape((1 - u) * shapes_a[lab] + u * shapes_b[lab]) for lab in shapes_a}
            cache[q] = IsohedralTiling(end.template.ih, list(end.params), shapes, end.colouring, check=False).edge_paths
        return cache[q]

    n = len(corners)
    mids = (straight + np.roll(straight, -1, axis=0)) / 2  # straight midpoints, prototile frame
    outlines = []
    for k in range(len(patch)):
        m = patch.transform[k]
        mx = Affine.apply(m, mids)[:, 0]
        pts = [Affine.apply(m, edge_paths(float(mx[e]) / width)[e])[:-1] for e in range(n)]
        outlines.append(np.vstack(pts))
    protos = [Prototile(q, name=f"{end.name} t") for q in outlines]
    out = Patch(protos, np.arange(len(protos)), np.repeat(np.eye(3)[None], len(protos), axis=0), patch.colour,
                patch.aspect)
    return out, (0.0, 0.0, width, height)
