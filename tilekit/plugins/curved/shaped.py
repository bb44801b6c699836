"""Shaped (Escher-like) tile outlines on the sphere and the hyperbolic plane: the pieces the
curved family's isohedral tiles on {p, q} and its shaped Laves tiles share (issue 35).

A tile is a geodesic polygon given by its corners on the model. Each edge has a *frame*, the
proper motion taking the pole to the edge's midpoint and the x axis along the edge towards its
end, and a *chart* ``F · exp((x − ½)L, yL)`` (the exponential map at the pole, L the edge's
length) carrying the unit segment (0,0)–(1,0) onto the edge. The chart commutes with the four
motions fixing the edge (the half-turn about its midpoint, the mirrors in its line and in its
perpendicular bisector), so a curve put on one edge arrives on any edge the group relates to it
as the unit-segment image the incidence symbol names (:func:`tilekit.incidence.edge_curves`):
neighbours share their edges point for point. The outline is the geodesic polygon through the
charted points (straight in the Klein model, or the gnomonic one on the sphere), triangulated by
ear clipping; one whose boundary crosses itself is refused with a one-line error naming the
edges that cross.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Mapping, Sequence
from typing import Any, TypeVar

import numpy as np
import shapely

from tilekit.edgeshapes import EdgeShape, parse_edge_option
from tilekit.errors import ParameterError, ParseError
from tilekit.incidence import IncidenceSymbol, shape_classes
from tilekit.plugins.curved import model
from tilekit.plugins.curved.wythoff import Space
from tilekit.polygon import ear_clip, signed_area

T = TypeVar("T")

#: Unit-segment points closer than this to the chord of their neighbours are dropped (and
#: repeated points merged): they change the shape invisibly but leave slivers that no
#: triangulation or validation can tell from an overlap.
FLAT = 1e-6


def edge_frames(sign: int, corners: np.ndarray) -> np.ndarray:
    """(k, 3, 3): F_i takes the pole to the midpoint of edge i (corner i to corner i + 1 of the
    closed polygon ``corners`` (k, 3) on the model) and the x axis along the edge towards corner
    i + 1; proper motions (determinant +1)."""
    space = Space(sign)
    a, b = corners, np.roll(corners, -1, axis=0)
    mid = space.normalise(a + b)
    return np.array([space.frame(m, e) for m, e in zip(mid, b)])


def edge_lengths(sign: int, corners: np.ndarray) -> np.ndarray:
    """(k,): the geodesic length of each edge of the closed polygon ``corners``."""
    return Space(sign).distance(corners, np.roll(corners, -1, axis=0))


def chart(g: model.Geometry, frame: np.ndarray, length: float, uv: np.ndarray) -> np.ndarray:
    """Unit-segment points (m, 2) onto the surface through the edge's chart (see the module)."""
    u, v = (uv[:, 0] - 0.5) * length, uv[:, 1] * length
    pts = g.point(np.hypot(u, v), np.arctan2(v, u))
    return pts @ frame.T


def clean(curve: np.ndarray) -> np.ndarray:
    """The curve without repeated points and without points within FLAT of the chord between
    their neighbours (decided for every point at once, so an edge and its partner, images
    under an isometry of the unit segment, keep the same points)."""
    keep = np.ones(len(curve), dtype=bool)
    keep[1:] = np.abs(np.diff(curve, axis=0)).max(axis=1) > 1e-12
    c = curve[keep]
    if len(c) < 3:
        return np.array([curve[0], curve[-1]])
    a, b, m = c[:-2], c[2:], c[1:-1]
    d = b - a
    length = np.hypot(d[:, 0], d[:, 1])
    t = np.clip(((m - a) * d).sum(axis=1) / np.maximum(length, 1e-300) ** 2, 0.0, 1.0)
    near = np.hypot(*(a + t[:, None] * d - m).T) < FLAT
    return c[np.concatenate([[True], ~near, [True]])]


def densify(curve: np.ndarray, samples: int) -> np.ndarray:
    """The curve's segments each cut into ``samples`` pieces (end point kept)."""
    if samples <= 1:
        return curve
    t = np.arange(samples) / samples
    a, b = curve[:-1], curve[1:]
    pts = a[:, None, :] + t[None, :, None] * (b - a)[:, None, :]
    return np.vstack([pts.reshape(-1, 2), curve[-1:]])


def edge_points(g: model.Geometry, frames: np.ndarray, lengths: Sequence[float], curves: Sequence[np.ndarray],
                samples: int) -> list[np.ndarray]:
    """Each edge's curve (unit segment, in the tile's counter-clockwise direction) carried onto
    the surface: (m_i, 3) model points from the edge's start to its end, both included."""
    return [chart(g, frames[i], float(lengths[i]), densify(clean(c), samples)) for i, c in enumerate(curves)]


def shaped_outline(g: model.Geometry, frames: np.ndarray, lengths: Sequence[float], curves: Sequence[np.ndarray],
                   samples: int, what: str, label: Callable[[int], str]
                   ) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 3) on the model round the shaped tile, counter-clockwise; triangles (t, 3)
    indexing them): the geodesic polygon through every edge's charted curve. ``what`` names the
    tile in errors, ``label(i)`` edge i's label. A boundary that crosses itself, or (sphere) one
    that leaves the hemisphere round the tile's centre, is a one-line ParameterError."""
    parts, edge_of = [], []
    for i, pts in enumerate(edge_points(g, frames, lengths, curves, samples)):
        parts.append(pts[:-1])
        edge_of += [i] * (len(pts) - 1)
    pts = np.vstack(parts)
    flat = model.klein(pts) if g.sign < 0 else pts[:, :2] / pts[:, 2:3]  # Klein / gnomonic: geodesics straight
    if g.sign > 0 and (pts[:, 2] <= 1e-3).any():
        raise ParameterError(f"the edge shapes carry the tile of {what} past the hemisphere round its centre; "
                             "use smaller deflections")
    ring = shapely.LinearRing(flat)
    if not ring.is_simple or signed_area(flat) <= 0:
        raise ParameterError(crossing_message(flat, np.array(edge_of), label))
    tris = ear_clip(flat)
    index = {tuple(v): k for k, v in enumerate(flat.tolist())}
    triangles = np.array([[index[tuple(v)] for v in t.tolist()] for t in tris], dtype=np.int64)
    return pts, triangles


def crossing_message(flat: np.ndarray, edge_of: np.ndarray, label: Callable[[int], str]) -> str:
    """The one-line error for an outline ``flat`` (its points' edges ``edge_of``) that is not a
    simple counter-clockwise polygon: the first edge that crosses itself, or the first two that
    cross each other (neighbouring edges may share their corner only)."""
    k = int(edge_of.max()) + 1
    lines = []
    for i in range(k):
        sel = np.flatnonzero(edge_of == i)
        seg = np.vstack([flat[sel], flat[(sel[-1] + 1) % len(flat)][None]])
        lines.append(shapely.LineString(seg))
    for i in range(k):
        if not lines[i].is_simple:
            return (f"the shape of edge {i + 1} ({label(i)!r}) crosses itself: the tile must stay "
                    "a simple polygon")
        for j in range(i + 1, k):
            inter = lines[i].intersection(lines[j])
            adjacent = (j == i + 1) or (i == 0 and j == k - 1)
            if not inter.is_empty and (not adjacent or inter.geom_type != "Point"):
                return (f"the shapes of edges {i + 1} ({label(i)!r}) and {j + 1} ({label(j)!r}) cross: the "
                        "tile must stay a simple polygon; use smaller deflections")
    return "the edge shapes turn the tile inside out: the tile must stay a simple counter-clockwise polygon"


# --------------------------------------------------------------------------- edge shapes by label

#: Default shapes: an S edge's half (completed by the half-turn), a J edge's whole curve and a U
#: edge's half (completed by the mirror in the perpendicular bisector).
DEFAULT_S = "0.18,0.16:0.34,0.14"
DEFAULT_J = "0.25,0.16:0.55,-0.12:0.8,0.06"
DEFAULT_U = "0.2,0.12:0.36,-0.06"
#: Factors the default shapes are tried at, in turn, until the tile is simple.
DEFAULT_DAMPING = (1.0, 0.5, 0.25, 0.125)


def parse_edges(edges: Any) -> Mapping[str, Any]:
    """The ``edges`` option: a mapping of labels to shapes, its JSON text (as ``--set
    edges='{"a": "0.2,0.1:0.4,0.1"}'`` passes it), or a list of ``LABEL=SHAPE`` texts (as
    ``--edge a=0.2,0.1:0.4,0.1`` and the web API's ``edge=`` pass them, one per label); None is
    no shapes given."""
    if edges is None:
        return {}
    if isinstance(edges, list | tuple):
        out: dict[str, Any] = {}
        for item in edges:
            if not isinstance(item, str):
                raise ParameterError(f"edges must be 'LABEL=x,y:x,y:...' texts, got {type(item).__name__}")
            label, shape = parse_edge_option(item)
            if label in out:
                raise ParameterError(f"edge {label!r} is given twice; give one shape per label")
            out[label] = shape
        return out
    if isinstance(edges, str):
        try:
            edges = json.loads(edges)
        except json.JSONDecodeError:
            raise ParseError("edges must be JSON like '{\"a\": \"0.2,0.1:0.4,0.1\"}'") from None
    if not isinstance(edges, Mapping):
        raise ParameterError(f"edges must map edge letters to shapes, got {type(edges).__name__}")
    return edges


def edges_text(shapes: Mapping[str, EdgeShape] | None) -> dict[str, str] | None:
    """The ``edges`` option's value that gives ``shapes`` back: EdgeShape text per label, in
    label order (None, no shapes: the straight tile), as a spec stores it."""
    return None if shapes is None else {k: v.to_text() for k, v in sorted(shapes.items())}


def label_shapes(symbol: IncidenceSymbol, edges: Mapping[str, Any], what: str, scale: float,
                 order: Sequence[str] | None = None) -> dict[str, EdgeShape]:
    """A fundamental shape per label that owns one (:func:`tilekit.incidence.shape_classes`):
    the one given (an EdgeShape or its text), else the default of its kind with deflections
    times ``scale``. A label that owns no shape is a one-line ParameterError naming those that do
    (``what`` names the tile's type; ``order`` picks the owner of a pair of labels, as
    :func:`tilekit.incidence.shape_classes` does)."""
    edges = parse_edges(edges)
    owners = shape_classes(symbol, order)
    out: dict[str, EdgeShape] = {}
    for lab, shape in edges.items():
        if lab not in owners:
            raise ParameterError(f"{what} has no shaped edge {str(lab)[:10]!r}; its shaped edges are "
                                 f"{', '.join(sorted(owners)) or 'none (all I: straight)'}")
        out[lab] = shape if isinstance(shape, EdgeShape) else EdgeShape.parse(str(shape))
    for lab in owners:
        kind = symbol.label_kind(lab)
        base = EdgeShape.parse(DEFAULT_J if kind == "J" else DEFAULT_S if kind == "S" else DEFAULT_U)
        out.setdefault(lab, EdgeShape(base.points * np.array([1.0, scale])))
    return out


def first_simple(symbol: IncidenceSymbol, edges: Mapping[str, Any], what: str, scale: float,
                 build: Callable[[dict[str, EdgeShape]], T], order: Sequence[str] | None = None
                 ) -> tuple[dict[str, EdgeShape], T]:
    """(shapes, build(shapes)) for the first damping of the default shapes (DEFAULT_DAMPING) at
    which ``build`` accepts the tile: the defaults bend less, halved up to three times, until the
    tile is simple; a shape given is never changed, so when every label's is given, or the last
    damping fails too, build's one-line error stands."""
    given = parse_edges(edges)
    for damp in DEFAULT_DAMPING:
        shapes = label_shapes(symbol, given, what, scale * damp, order)
        try:
            return shapes, build(shapes)
        except ParameterError:
            if damp == DEFAULT_DAMPING[-1] or set(shape_classes(symbol, order)) <= set(given):
                raise
    raise AssertionError("unreachable: the last damping re-raises")
