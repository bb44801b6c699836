"""A patch where Python users work: notebooks, matplotlib, GeoJSON / shapely / GeoPandas,
tile adjacency (NumPy arrays, networkx), and line files for cutters and plotters (layered
SVG and DXF with every shared edge once). See docs/exports.md.

Everything here starts from the patch's columns: outlines come per prototile in batches
(``Patch.groups``), vertices are welded by sorting (:func:`weld`), tile edges are split at
every vertex lying inside them (so non-edge-to-edge patches — bricks, chair, Penrose halves —
are exact too) and matched by packed integer keys. Optional libraries (matplotlib, geopandas,
networkx, ezdxf) are imported inside the functions that need them, through :func:`optional`.
"""

from __future__ import annotations

import html
import importlib
import json
import operator
import shutil
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

import numpy as np
import shapely

from tilekit import limits
from tilekit.errors import MissingDependency, ParameterError, TilekitError, optional  # noqa: F401  (re-exported)
from tilekit.geometry import snap_noise
from tilekit.limits import (
    ADJACENCY_BYTES_PER_VERTEX,
    EXPORT_BYTES_PER_VERTEX,
    GENERATION_BYTES_PER_TILE,
    MAX_DXF_TILES,
    MAX_REPR_TILES,
    MAX_TILES,
    MEMORY_FRACTION,
    RENDER_BYTES_PER_TILE,
    STREAM_CHUNK_TILES,
    LimitError,
    fits_in_memory,
    refuse_over,
    refuse_over_memory,
)
from tilekit.render import PALETTE, is_colour, parse_palette, patch_to_svg, svg_lines

if TYPE_CHECKING:  # only for annotations: tiling.py imports this module
    from tilekit.tiling import Patch, Tiling

#: The output suffixes ``tilekit render`` and :func:`write_patch` know, and what each writes.
FORMATS: dict[str, str] = {
    ".svg": "picture (SVG)",
    ".png": "picture (PNG, png extra)",
    ".geojson": "GeoJSON FeatureCollection, one Polygon feature per tile",
    ".json": "tiles (outline, prototile, colour, aspect, centre, angle, reflected) with their neighbours",
    ".cut.svg": "layered SVG of edges, each shared edge once (cutters, plotters)",
    ".dxf": "DXF of edges, each shared edge once (dxf extra)",
    ".csv": "tile table: index, centre, angle, reflected, prototile, colour, label, edge neighbours",
}

#: Strokes of a cut SVG's colour layers (``--layers colour``): saturated and far apart, as
#: laser software maps stroke colours to operations; ``--colours`` replaces them.
CUT_PALETTE: tuple[str, ...] = ("#ff0000", "#0000ff", "#00a000", "#ff00ff", "#00a0a0", "#c08000",
                                "#000000", "#8000ff", "#ff8000", "#0080ff", "#808000", "#ff0080")

#: Ways of layering the edges of a cut file.
LAYERINGS = ("one", "colour")

#: Tiles formatted per step of a streamed writer (bounds the text held at once).
_CHUNK = 4096
#: Segments tested per step when looking for vertices inside edges (bounds the temporaries).
_SPLIT_CHUNK = 1 << 16


# MissingDependency and optional live in tilekit.errors (the CLI's guards use them too)


def output_format(path: str | Path) -> str:
    """The output kind of ``path`` by its suffix (a key of :data:`FORMATS`), or ParameterError
    naming the valid ones."""
    name = Path(path).name.lower()
    for suffix in sorted(FORMATS, key=len, reverse=True):  # '.cut.svg' before '.svg'
        if name.endswith(suffix) and len(name) > len(suffix):
            return suffix
    raise ParameterError(f"output file {str(path)!r} must end in one of {', '.join(FORMATS)}")


# --------------------------------------------------------------------------- edges


def _flat_outlines(patch: Patch) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every tile's outline points, flattened: points (N, 2), owning tile (N,), and the index
    of the next point round the same outline (N,). Built per prototile in one batch."""
    pts, tile, nxt = [], [], []
    base = 0
    for _p, idx, outl in patch.groups():
        m, k, _ = outl.shape
        pts.append(outl.reshape(m * k, 2))
        tile.append(np.repeat(idx, k))
        ring = (np.arange(k) + 1) % k
        nxt.append((base + np.arange(m)[:, None] * k + ring[None, :]).reshape(-1))
        base += m * k
    if not pts:
        return np.zeros((0, 2)), np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(pts), np.concatenate(tile), np.concatenate(nxt)


def weld_tolerance(patch: Patch) -> float:
    """The tolerance within which the patch's outline points are one point
    (:meth:`Patch.weld_tolerance`: POINT_TOL scaled by the median tile diameter)."""
    return patch.weld_tolerance()


def weld(points: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Integer ids for points, equal for points within ``tol`` of each other: (ids (N,),
    representative points (V, 2)). Points are cleaned by snap_noise, chained into clusters
    along x (neighbours in x order closer than ``tol``), then along y inside each x cluster,
    all by sorting; unlike rounding to a grid, two copies of a vertex a hair apart can never
    fall into different cells. Distinct vertices of a tiling are far more than ``tol`` apart."""
    pts = snap_noise(points)
    n = len(pts)
    if n == 0:
        return np.zeros(0, dtype=np.int64), np.zeros((0, 2))
    ox = np.argsort(pts[:, 0], kind="stable")
    xs = pts[ox, 0]
    xcl = np.empty(n, dtype=np.int64)
    xcl[ox] = np.concatenate([[0], np.cumsum(np.diff(xs) > tol)])
    oy = np.lexsort((pts[:, 1], xcl))
    ys, xo = pts[oy, 1], xcl[oy]
    new = np.concatenate([[True], (np.diff(xo) != 0) | (np.diff(ys) > tol)])
    ids = np.empty(n, dtype=np.int64)
    ids[oy] = np.cumsum(new) - 1
    return ids, pts[oy[new]]


@dataclass(frozen=True)
class Edges:
    """A patch's boundaries as elementary segments: every tile edge split at each vertex of
    the patch lying inside it, so two tiles whose boundaries share a piece of positive length
    share whole elementary segments with equal end ids.

    ``points`` (V, 2) are the welded vertices; segment s runs from ``points[u[s]]`` to
    ``points[v[s]]`` on the boundary of tile ``tile[s]``; ``key[s]`` packs its unordered
    ends into one int64 (``order`` sorts them); ``split`` counts the vertices that lay inside tile edges (0 for an
    edge-to-edge patch).
    """

    points: np.ndarray
    u: np.ndarray
    v: np.ndarray
    tile: np.ndarray
    key: np.ndarray
    split: int
    tiles: int
    order: np.ndarray  # segment indices sorted by key (a stable argsort)


def tile_edges(patch: Patch, tol: float | None = None) -> Edges:
    """The elementary segments of every tile's boundary (see :class:`Edges`)."""
    tol = weld_tolerance(patch) if tol is None else float(tol)
    pts, tile, nxt = _flat_outlines(patch)
    ids, P = weld(pts, tol)
    u, v = ids, ids[nxt]
    keep = u != v  # repeated outline points make no segment
    u, v, tile = u[keep], v[keep], tile[keep]
    key = np.minimum(u, v) * max(len(P), 1) + np.maximum(u, v)
    order = np.argsort(key, kind="stable")
    u, v, tile, split = _split_at_vertices(P, u, v, tile, tol, key, order)
    if split:  # new segments: new keys and their order
        key = np.minimum(u, v) * max(len(P), 1) + np.maximum(u, v)
        order = np.argsort(key, kind="stable")
    return Edges(P, u, v, tile, key, split, len(patch), order)


def _split_at_vertices(P: np.ndarray, u: np.ndarray, v: np.ndarray, tile: np.ndarray, tol: float,
                       key: np.ndarray, o: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Split each segment (u, v) at every point of P strictly inside it. The search runs once
    per distinct edge (most edges are two tiles' segments); only the segments of edges with a
    vertex inside are rebuilt, each in its own direction, so the segment starts of a tile are
    still its boundary's vertices, once each. ``key`` packs each segment's ends and ``o``
    sorts it."""
    ns = len(u)
    if ns == 0:
        return u, v, tile, 0
    ks = key[o]
    new = np.concatenate([[True], ks[1:] != ks[:-1]])
    rep = o[new]  # one segment per distinct edge
    inv = np.empty(ns, dtype=np.int64)
    inv[o] = np.cumsum(new) - 1
    hs, hp, ht = _vertices_inside(P, u[rep], v[rep], tol)
    if not len(hs):
        return u, v, tile, 0
    hord = np.lexsort((ht, hs))
    hs, hp, ht = hs[hord], hp[hord], ht[hord]
    hcount = np.bincount(hs, minlength=len(rep))
    hfirst = np.cumsum(hcount) - hcount
    aff = np.flatnonzero(hcount[inv] > 0)  # segments whose edge has vertices inside
    e = inv[aff]
    c = hcount[e]
    seg = np.repeat(np.arange(len(aff)), c)
    at = np.repeat(hfirst[e] - (np.cumsum(c) - c), c) + np.arange(int(c.sum()))
    same_way = np.repeat(u[aff] == u[rep[e]], c)
    t = np.where(same_way, ht[at], 1.0 - ht[at])
    m = len(aff)
    stop_seg = np.concatenate([np.arange(m), seg, np.arange(m)])
    stop_t = np.concatenate([np.zeros(m), t, np.ones(m)])
    stop_p = np.concatenate([u[aff], hp[at], v[aff]])
    so = np.lexsort((stop_t, stop_seg))
    ss, sp = stop_seg[so], stop_p[so]
    cont = (ss[1:] == ss[:-1]) & (sp[1:] != sp[:-1])
    keep = np.ones(ns, dtype=bool)
    keep[aff] = False
    return (np.concatenate([u[keep], sp[:-1][cont]]), np.concatenate([v[keep], sp[1:][cont]]),
            np.concatenate([tile[keep], tile[aff][ss[:-1][cont]]]), len(np.unique(hp)))


def _vertices_inside(P: np.ndarray, u: np.ndarray, v: np.ndarray,
                     tol: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(segment, point, t) for every point of P strictly inside a segment (u, v): within
    ``tol`` of it and beyond ``tol`` from its ends, at fraction t along it. Candidates come
    from a uniform grid (cells of the median segment's length): each segment is paired with
    the cells its box meets, and those with the points in them, by sorting; the exact test
    is array code over the candidate pairs, a chunk of segments at a time."""
    ns = len(u)
    A, B = P[u], P[v]
    length = np.hypot(*(B - A).T)
    # cells of the median edge's length (at least an eighth of the longest, so that no
    # segment's box spans more than 9 x 9 cells): few points per cell, few cells per segment
    h = max(float(np.median(length)), float(length.max()) / 8) * (1 + 1e-9) + 4 * tol
    origin = P.min(axis=0) - 2 * tol
    cell = np.floor((P - origin) / h).astype(np.int64)
    rows = int(cell[:, 1].max()) + 3
    pkey = cell[:, 0] * rows + cell[:, 1]
    porder = np.argsort(pkey, kind="stable")
    pk = pkey[porder]
    lo_c = np.floor((np.minimum(A, B) - tol - origin) / h).astype(np.int64)
    span = np.floor((np.maximum(A, B) + tol - origin) / h).astype(np.int64) - lo_c + 1  # cells per axis
    cells = span[:, 0] * span[:, 1]
    hits_s, hits_p, hits_t = [], [], []
    for s0 in range(0, ns, _SPLIT_CHUNK):
        sl = slice(s0, min(ns, s0 + _SPLIT_CHUNK))
        c = cells[sl]
        cs_ = np.repeat(np.arange(sl.start, sl.stop), c)  # one row per (segment, cell of its box)
        local = np.arange(len(cs_)) - np.repeat(np.cumsum(c) - c, c)
        ny = span[cs_, 1]
        ck_ = (lo_c[cs_, 0] + local // ny) * rows + lo_c[cs_, 1] + local % ny
        left = np.searchsorted(pk, ck_, "left")
        count = np.searchsorted(pk, ck_, "right") - left
        total = int(count.sum())
        if not total:
            continue
        s = np.repeat(cs_, count)
        first = np.cumsum(count) - count
        p = porder[np.repeat(left - first, count) + np.arange(total)]
        cand = (p != u[s]) & (p != v[s])
        s, p = s[cand], p[cand]
        a = A[s]
        d = B[s] - a
        w = P[p] - a
        L = length[s]
        along = (w[:, 0] * d[:, 0] + w[:, 1] * d[:, 1]) / L
        off = np.abs(w[:, 0] * d[:, 1] - w[:, 1] * d[:, 0]) / L
        inside = (off <= tol) & (along > tol) & (along < L - tol)
        hits_s.append(s[inside])
        hits_p.append(p[inside])
        hits_t.append(along[inside] / L[inside])
    if not hits_s:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64), np.zeros(0)
    return np.concatenate(hits_s), np.concatenate(hits_p), np.concatenate(hits_t)


# --------------------------------------------------------------------------- adjacency


@dataclass(frozen=True)
class Adjacency:
    """Which tiles of a patch touch, as (k, 2) int64 arrays of index pairs i < j, sorted.

    ``edge``: the boundaries share a segment of positive length. ``vertex``: they share a
    point but no such segment (corner contacts). ``touching``: either (edge ∪ vertex).
    ``split`` counts vertices that lay inside other tiles' edges (0 when edge-to-edge).
    """

    tiles: int
    edge: np.ndarray
    vertex: np.ndarray
    touching: np.ndarray
    split: int

    def neighbours(self, kind: str = "edge") -> tuple[np.ndarray, np.ndarray]:
        """CSR form of one kind: tile t's neighbours are ``index[offsets[t]:offsets[t + 1]]``."""
        pairs = self._kind(kind)
        both = np.concatenate([pairs, pairs[:, ::-1]])
        o = np.lexsort((both[:, 1], both[:, 0]))
        both = both[o]
        offsets = np.zeros(self.tiles + 1, dtype=np.int64)
        np.cumsum(np.bincount(both[:, 0], minlength=self.tiles), out=offsets[1:])
        return offsets, both[:, 1].copy()

    def degree(self, kind: str = "edge") -> np.ndarray:
        """Neighbours of each tile, (n,) ints."""
        pairs = self._kind(kind)
        return np.bincount(pairs.reshape(-1), minlength=self.tiles)

    def _kind(self, kind: str) -> np.ndarray:
        if kind not in ("edge", "vertex", "touching"):
            raise ParameterError(f"adjacency kind {kind!r} is not one of edge, vertex, touching")
        return getattr(self, kind)


def _unique(keys: np.ndarray) -> np.ndarray:
    """Sorted distinct values (a sort and a mask: faster here than np.unique's hashing)."""
    s = np.sort(keys)
    return s[np.concatenate([[True], s[1:] != s[:-1]])] if len(s) else s


def _pair_keys(a: np.ndarray, b: np.ndarray, n: int) -> np.ndarray:
    """Packed keys min * n + max of tile pairs, self-pairs dropped (not deduplicated)."""
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    ok = lo != hi
    return lo[ok] * n + hi[ok]


def _unpack(keys: np.ndarray, n: int) -> np.ndarray:
    return np.column_stack([keys // n, keys % n]).astype(np.int64).reshape(-1, 2)


def adjacency_of(edges: Edges) -> Adjacency:
    """Edge and vertex adjacency from a patch's elementary segments (:func:`tile_edges`)."""
    n = max(edges.tiles, 1)
    o = edges.order
    k, t = edges.key[o], edges.tile[o]
    same = k[1:] == k[:-1]
    ekey = _unique(_pair_keys(t[:-1][same], t[1:][same], n))
    # tiles at each vertex: (vertex, tile) incidences from the segments' starts, which after
    # splitting include every vertex lying on a tile's boundary (once per tile: the outlines
    # are simple polygons)
    ov = np.argsort(edges.u, kind="stable")
    vid, vt = edges.u[ov], edges.tile[ov]
    found = [ekey]
    d = 1
    while d < len(vid):
        ok = vid[d:] == vid[:-d]
        if not ok.any():
            break
        found.append(_pair_keys(vt[:-d][ok], vt[d:][ok], n))
        d += 1
    tkey = _unique(np.concatenate(found))
    pos = np.minimum(np.searchsorted(ekey, tkey), max(len(ekey) - 1, 0))
    is_edge = ekey[pos] == tkey if len(ekey) else np.zeros(len(tkey), dtype=bool)
    return Adjacency(edges.tiles, _unpack(ekey, n), _unpack(tkey[~is_edge], n), _unpack(tkey, n), edges.split)


def adjacency(patch: Patch, tol: float | None = None) -> Adjacency:
    """Tiles sharing an edge, a vertex only, or any point (see :class:`Adjacency`); refused
    before any work when its arrays would not fit in memory."""
    vertices = outline_vertices(patch.prototiles)
    refuse_over_memory("tiles", len(patch), ADJACENCY_BYTES_PER_VERTEX * vertices,
                       hint=f"tiles of {vertices} vertices; adjacency of a smaller patch")
    return adjacency_of(tile_edges(patch, tol))


# --------------------------------------------------------------------------- cut lines


def _cut_layers(patch: Patch, layers: str, edges: Edges | None) -> tuple[Edges, list[tuple[str, int | None, np.ndarray]]]:
    """The patch's elementary segments and, per layer, the indices of the segments it cuts
    (see :func:`cut_segments`)."""
    if layers not in LAYERINGS:
        raise ParameterError(f"layers {layers!r} is not one of {', '.join(LAYERINGS)}")
    e = tile_edges(patch) if edges is None else edges
    if layers == "one":
        ks = e.key[e.order]
        first = e.order[np.concatenate([[True], ks[1:] != ks[:-1]])] if len(ks) else e.order
        return e, [("cut", None, first)]
    col = patch.colour[e.tile]
    o = np.lexsort((e.key, col))
    k, c = e.key[o], col[o]
    first = o[np.concatenate([[True], (k[1:] != k[:-1]) | (c[1:] != c[:-1])])]
    return e, [(f"colour-{colour}", int(colour), first[col[first] == colour])
               for colour in np.unique(col[first]).tolist()]


def cut_segments(patch: Patch, layers: str = "one",
                 edges: Edges | None = None) -> list[tuple[str, int | None, np.ndarray]]:
    """The lines a cutter follows, each shared edge once: ``[(layer name, colour or None,
    segments (m, 2, 2))]``.

    ``layers='one'``: one layer "cut" holding every elementary segment of the patch once.
    ``layers='colour'``: a layer "colour-c" per colour holding the outlines of that colour's
    tiles, with edges shared by two tiles of the colour once (each colour's pieces can be cut
    from their own sheet; an edge between two colours is in both layers).
    """
    e, groups = _cut_layers(patch, layers, edges)
    return [(name, colour, np.stack([e.points[e.u[sel]], e.points[e.v[sel]]], axis=1))
            for name, colour, sel in groups]


@dataclass(frozen=True)
class CutPaths:
    """One layer's cut lines chained into paths: path t runs through ``points[starts[t]:
    starts[t + 1]]`` (a closed path ends where it starts); ``segments`` elementary segments
    in all, each once, as :func:`cut_segments` gives them."""

    name: str
    colour: int | None
    points: np.ndarray
    starts: np.ndarray
    segments: int

    def __len__(self) -> int:
        return len(self.starts) - 1


def cut_paths(patch: Patch, layers: str = "one", edges: Edges | None = None) -> list[CutPaths]:
    """:func:`cut_segments` chained into paths (``kernels.trails``: walks that use every
    segment once, started at odd-degree vertices first), so that a cutter lifts its head
    once per path rather than once per segment: a square grid's lines become a few long
    paths, a trivalent tiling's about one per two vertices of odd degree."""
    from tilekit import kernels  # start-up cost: numba, only when a cut file is written

    e, groups = _cut_layers(patch, layers, edges)
    out = []
    for name, colour, sel in groups:
        vertices, starts = kernels.trails(e.u[sel], e.v[sel], len(e.points))
        out.append(CutPaths(name, colour, e.points[vertices], starts, len(sel)))
    return out


def group_boundaries(patch: Patch, group: np.ndarray, outer: bool = False, edges: Edges | None = None) -> np.ndarray:
    """The lines between groups of tiles (the supertiles of a substitution tiling, say) as
    elementary segments (m, 2, 2), each once: the segments whose two tiles lie in different
    groups (``group``: one int per tile) and, with ``outer``, the segments of one tile only
    (the patch's own boundary). Exact for non-edge-to-edge patches (:class:`Edges`)."""
    group = np.asarray(group, dtype=np.int64).reshape(-1)
    if len(group) != len(patch):
        raise ParameterError(f"{len(group)} group numbers for {len(patch)} tiles")
    e = tile_edges(patch) if edges is None else edges
    o = e.order
    if not len(o):
        return np.zeros((0, 2, 2))
    k, g = e.key[o], group[e.tile[o]]
    start = np.flatnonzero(np.concatenate([[True], k[1:] != k[:-1]]))
    count = np.diff(np.append(start, len(k)))
    keep = np.minimum.reduceat(g, start) != np.maximum.reduceat(g, start)
    if outer:
        keep |= count == 1
    sel = o[start[keep]]
    return np.stack([e.points[e.u[sel]], e.points[e.v[sel]]], axis=1)


def _path_text(paths: CutPaths) -> Iterator[str]:
    """SVG path data of the paths, a chunk of points at a time: ``M`` at each path's start,
    ``L`` to each next point, ``Z`` instead of a last point that closes the path."""
    pts, starts = paths.points, paths.starts
    n = len(pts)
    if not n:
        return
    command = np.zeros(n, dtype=bool)
    command[starts[:-1]] = True  # a move to each path's first point
    ends = starts[1:] - 1
    closed = (ends > starts[:-1]) & np.all(pts[ends] == pts[starts[:-1]], axis=1)
    drop = np.zeros(n, dtype=bool)
    drop[ends[closed]] = True
    z_after = np.zeros(n, dtype=bool)
    z_after[ends[closed] - 1] = True
    keep = np.flatnonzero(~drop)
    kind = command.astype(np.int64) + 2 * z_after
    for s in range(0, len(keep), _CHUNK * 8):
        idx = keep[s : s + _CHUNK * 8]
        cells = _PATH_CELLS[kind[idx]].tolist()
        xy = np.column_stack([pts[idx, 0], -pts[idx, 1]])
        yield " ".join(cells) % tuple(xy.reshape(-1).tolist())
        yield "\n"


#: A point of SVG path data: line to it, move to it, and either followed by closing the path.
_PATH_CELLS = np.array(["L%.10g %.10g", "M%.10g %.10g", "L%.10g %.10g Z", "M%.10g %.10g Z"], dtype=object)


def iter_cut_svg(patch: Patch, layers: str = "one", mm_per_unit: float = 10.0,
                 stroke: str = "#ff0000", palette: Sequence[str] | None = None) -> Iterator[str]:
    """A layered SVG of the patch's edges, each shared edge once, chained into paths
    (:func:`cut_paths`), as text chunks. Sizes are in millimetres (``mm_per_unit`` per tiling unit); each layer is a
    ``<g>`` that Inkscape reads as a layer; with ``layers='colour'`` layer c is stroked in
    ``palette[c % len]`` (default CUT_PALETTE), otherwise in ``stroke``."""
    if not (mm_per_unit > 0 and np.isfinite(mm_per_unit)):
        raise ParameterError(f"mm per unit must be a positive number, not {mm_per_unit}")
    if not is_colour(stroke):
        raise ParameterError(f"stroke colour {stroke[:40]!r} is not a CSS colour name or #rgb / #rrggbb")
    pal = tuple(palette) if palette else CUT_PALETTE
    groups = cut_paths(patch, layers)
    x0, y0, x1, y1 = patch.bounds() if len(patch) else (0.0, 0.0, 1.0, 1.0)
    w, h = x1 - x0, y1 - y0
    yield ('<?xml version="1.0" encoding="UTF-8"?>\n<svg xmlns="http://www.w3.org/2000/svg" '
           'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
           f'width="{w * mm_per_unit:.6g}mm" height="{h * mm_per_unit:.6g}mm" '
           f'viewBox="{x0:.10g} {-y1:.10g} {w:.10g} {h:.10g}">\n')
    sw = 0.1 / mm_per_unit  # a 0.1 mm hairline
    for paths in groups:
        name, colour = paths.name, paths.colour
        ink = pal[colour % len(pal)] if colour is not None else stroke
        yield (f'<g id="{name}" inkscape:groupmode="layer" inkscape:label="{name}" fill="none" '
               f'stroke="{html.escape(ink)}" stroke-width="{sw:.4g}" data-segments="{paths.segments}" '
               f'data-paths="{len(paths)}">\n<path d="')
        yield from _path_text(paths)
        yield '"/>\n</g>\n'
    yield "</svg>\n"


def write_dxf(patch: Patch, path: str | Path, layers: str = "one", mm_per_unit: float = 10.0) -> int:
    """Write the patch's edges (each shared edge once, chained into paths: :func:`cut_paths`)
    as LWPOLYLINE entities of a DXF file in millimetres, one DXF layer per layer; returns the
    number of elementary segments they draw. ezdxf
    (the ``dxf`` extra) holds the whole drawing in memory, so the patch is refused over
    MAX_DXF_TILES."""
    refuse_over("tiles", len(patch), MAX_DXF_TILES, hint="a DXF drawing is built in memory (MAX_DXF_TILES)")
    ezdxf = optional("ezdxf", "dxf", "DXF output")  # optional dependency: imported when used
    if not (mm_per_unit > 0 and np.isfinite(mm_per_unit)):
        raise ParameterError(f"mm per unit must be a positive number, not {mm_per_unit}")
    doc = ezdxf.new("R2010", units=4)  # 4 = millimetres
    msp = doc.modelspace()
    count = 0
    for i, paths in enumerate(cut_paths(patch, layers)):
        doc.layers.add(paths.name, color=1 + i % 255)
        attribs = {"layer": paths.name}
        pts = (paths.points * mm_per_unit).tolist()
        for a, b in zip(paths.starts[:-1].tolist(), paths.starts[1:].tolist(), strict=True):
            closed = b - a > 2 and pts[a] == pts[b - 1]
            # ezdxf adds one entity per call: a path, not a segment
            msp.add_lwpolyline(pts[a : b - 1] if closed else pts[a:b], close=closed, dxfattribs=attribs)
        count += paths.segments
    try:
        doc.saveas(str(path))
    except OSError as exc:
        raise TilekitError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from None
    return count


# --------------------------------------------------------------------------- GeoJSON / JSON


def _rings(patch: Patch, idx: np.ndarray) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """(tile indices, closed counter-clockwise rings (m, k + 1, 2)) per prototile among
    ``idx`` (clockwise outlines, i.e. reflected tiles', are reversed, as RFC 7946 asks).
    The outlines come from the patch's own ``groups`` (a Patch subclass whose transforms
    are not affine, such as the curved family's, draws its tiles there)."""
    for _, local, pts in patch.subset(idx).groups():
        x, y = pts[..., 0], pts[..., 1]
        flip = (x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y).sum(axis=1) < 0
        pts[flip] = pts[flip, ::-1]
        yield idx[local], np.concatenate([pts, pts[:, :1]], axis=1)


def _chunks(n: int) -> Iterator[np.ndarray]:
    for s in range(0, n, _CHUNK):
        yield np.arange(s, min(n, s + _CHUNK))


def _classes(classes: np.ndarray | None, n: int) -> np.ndarray | None:
    if classes is None:
        return None
    out = np.asarray(classes, dtype=np.int64).reshape(-1)
    if len(out) != n:
        raise ParameterError(f"{len(out)} transitivity classes for {n} tiles")
    return out


def iter_geojson(patch: Patch, classes: np.ndarray | None = None) -> Iterator[str]:
    """The patch as a GeoJSON FeatureCollection, streamed in chunks of text: one Polygon
    feature per tile (id = tile index) with properties ``prototile`` (index), ``name``
    (the prototile's), ``colour``, ``aspect`` and, when ``classes`` is given (one int per
    tile, e.g. from :func:`tilekit.symmetry.orbits.patch_tile_classes`), ``transitivity_class``."""
    return iter_geojson_patches([patch], None if classes is None else [classes])


def iter_geojson_patches(patches: Iterable[Patch], classes: Iterable[np.ndarray] | None = None) -> Iterator[str]:
    """One GeoJSON FeatureCollection of the tiles of a stream of patches (e.g.
    ``Tiling.iter_patches``), as :func:`iter_geojson` writes one patch; ids run on across
    the patches, and only one patch's text is held at once. ``classes``: one array per patch."""
    yield '{"type": "FeatureCollection", "features": [\n'
    sep = ""
    first = 0
    class_iter = iter(classes) if classes is not None else None
    for patch in patches:
        cls = _classes(next(class_iter), len(patch)) if class_iter is not None else None
        for text in _geojson_features(patch, cls, first):
            yield sep + text
            sep = ",\n"
        first += len(patch)
    yield "\n]}\n"


def _geojson_features(patch: Patch, classes: np.ndarray | None, first: int) -> Iterator[str]:
    """The patch's features, _CHUNK tiles per text piece, ids from ``first``."""
    names = [json.dumps(p.name) for p in patch.prototiles]
    for idx in _chunks(len(patch)):
        text: list[str] = [""] * len(idx)
        for at, ring in _rings(patch, idx):
            k = ring.shape[1]
            p = int(patch.prototile[at[0]])
            fmt = ('{"type": "Feature", "id": %d, "geometry": {"type": "Polygon", "coordinates": [['
                   + ", ".join(["[%.12g, %.12g]"] * k) + ']]}, "properties": {"prototile": %d, "name": '
                   + names[p].replace("%", "%%") + ', "colour": %d, "aspect": %d'
                   + (', "transitivity_class": %d' if classes is not None else "") + "}}")
            cols = [first + at[:, None], ring.reshape(len(at), 2 * k), np.full((len(at), 1), p),
                    patch.colour[at, None], patch.aspect[at, None]]
            if classes is not None:
                cols.append(classes[at, None])
            rows = np.concatenate([c.astype(object) for c in cols], axis=1).tolist()
            for j, row in zip((at - idx[0]).tolist(), rows):
                text[j] = fmt % tuple(row)
        yield ",\n".join(text)


@dataclass(frozen=True)
class TileTable:
    """One row per tile of a patch, as columns: ``centre`` (n, 2) the tile's centroid,
    ``angle`` (n,) its turn in degrees in [0, 360) and ``reflected`` (n,) whether it is the
    mirror image (tile = prototile, reflected in the x axis if ``reflected``, turned by
    ``angle`` about the origin, then moved), ``prototile`` and ``colour`` (n,), ``label`` (n,)
    a name per tile or None, and the edge neighbours in CSR form: tile t's are
    ``index[offsets[t]:offsets[t + 1]]`` (:meth:`Adjacency.neighbours`)."""

    centre: np.ndarray
    angle: np.ndarray
    reflected: np.ndarray
    prototile: np.ndarray
    colour: np.ndarray
    label: np.ndarray | None
    offsets: np.ndarray
    index: np.ndarray

    def __len__(self) -> int:
        return len(self.angle)

    def neighbours(self, t: int) -> np.ndarray:
        """The tiles sharing an edge with tile ``t``."""
        return self.index[self.offsets[t]:self.offsets[t + 1]]


def tile_table(patch: Patch, labels: Sequence[str] | np.ndarray | None = None,
               adj: Adjacency | None = None) -> TileTable:
    """The :class:`TileTable` of ``patch``, with ``labels`` (one name per tile) when given;
    neighbours from :func:`adjacency` (edge neighbours: their boundaries share a segment)."""
    n = len(patch)
    lab = None
    if labels is not None:
        lab = np.asarray(labels, dtype=object).reshape(-1)
        if len(lab) != n:
            raise ParameterError(f"{len(lab)} labels for {n} tiles")
    angle, reflected = patch.orientations()
    offsets, index = (adjacency(patch) if adj is None else adj).neighbours("edge")
    return TileTable(patch.centres(), angle + 0.0, reflected, patch.prototile.copy(), patch.colour.copy(), lab,
                     offsets, index)


def _csv_cell(text: str) -> str:
    """A CSV cell (RFC 4180): quoted when it holds a comma, a quote or a line break."""
    return '"' + text.replace('"', '""') + '"' if any(c in text for c in ',"\r\n') else text


def iter_csv(patch: Patch, labels: Sequence[str] | np.ndarray | None = None,
             adj: Adjacency | None = None) -> Iterator[str]:
    """The patch's :func:`tile_table` as CSV, streamed: a header ``index,x,y,angle,reflected,
    prototile,colour[,label],neighbours`` and a row per tile, its edge neighbours'
    indices separated by spaces in one cell (centres with 12 significant digits)."""
    table = tile_table(patch, labels, adj)
    cols = ["index", "x", "y", "angle", "reflected", "prototile", "colour"]
    cols += ["label"] if table.label is not None else []
    yield ",".join(cols + ["neighbours"]) + "\n"
    fmt = "%d,%.12g,%.12g,%.12g,%d,%d,%d"
    for idx in _chunks(len(table)):
        rows = np.column_stack([idx, table.centre[idx], table.angle[idx], table.reflected[idx],
                                table.prototile[idx], table.colour[idx]]).astype(object).tolist()
        lines = []
        for t, row in zip(idx.tolist(), rows):
            cells = fmt % tuple(row)
            if table.label is not None:
                cells += "," + _csv_cell(str(table.label[t]))
            lines.append(cells + "," + " ".join(map(str, table.neighbours(t).tolist())) + "\n")
        yield "".join(lines)


def iter_json(patch: Patch, adj: Adjacency | None = None, classes: np.ndarray | None = None,
              labels: Sequence[str] | np.ndarray | None = None) -> Iterator[str]:
    """The patch as JSON, streamed: ``{"prototiles": [{name, outline}], "tiles": [{"outline",
    "prototile", "colour", "aspect", "centre", "angle", "reflected", "neighbours",
    "vertex_neighbours"}]}`` where a tile's ``neighbours`` share an edge with it and its
    ``vertex_neighbours`` only a point, and ``centre``, ``angle``, ``reflected`` are its
    :func:`tile_table` row; with ``classes`` (one int per tile) each tile also has its
    ``transitivity_class``, with ``labels`` (one name per tile) its ``label``."""
    classes = _classes(classes, len(patch))
    adj = adjacency(patch) if adj is None else adj
    table = tile_table(patch, labels, adj)
    eo, ei = table.offsets, table.index
    vo, vi = adj.neighbours("vertex")
    protos = [{"name": p.name, "outline": np.round(p.outline, 12).tolist()} for p in patch.prototiles]
    yield '{"prototiles": ' + json.dumps(protos) + ', "tiles": [\n'
    sep = ""
    for idx in _chunks(len(patch)):
        text: list[str] = [""] * len(idx)
        for at, ring in _rings(patch, idx):
            k = ring.shape[1] - 1
            fmt = ('{"outline": [' + ", ".join(["[%.12g, %.12g]"] * k) + '], "prototile": %d, "colour": %d, "aspect": %d, '
                   + '"centre": [%.12g, %.12g], "angle": %.12g, '
                   + ('"transitivity_class": %d, ' if classes is not None else ""))
            ints = [patch.prototile[at], patch.colour[at], patch.aspect[at]]
            rows = np.concatenate([ring[:, :-1].reshape(len(at), 2 * k).astype(object),
                                   np.column_stack(ints).astype(object),
                                   table.centre[at].astype(object), table.angle[at, None].astype(object)]
                                  + ([classes[at, None].astype(object)] if classes is not None else []),
                                  axis=1).tolist()
            for t, row in zip(at.tolist(), rows):
                extra = '"reflected": ' + ("true" if table.reflected[t] else "false") + ", "
                if table.label is not None:
                    extra += '"label": ' + json.dumps(str(table.label[t])) + ", "
                text[t - int(idx[0])] = (fmt % tuple(row) + extra + '"neighbours": ' + str(ei[eo[t]:eo[t + 1]].tolist())
                                         + ', "vertex_neighbours": ' + str(vi[vo[t]:vo[t + 1]].tolist()) + "}")
        yield sep + ",\n".join(text)
        sep = ",\n"
    yield "\n]}\n"


def write_text(chunks: Iterator[str], path: str | Path | IO[str]) -> None:
    """Write streamed text to a path (or an open text file)."""
    if hasattr(path, "write"):
        for c in chunks:
            path.write(c)  # type: ignore[union-attr]
        return
    try:
        with open(path, "w", encoding="utf-8") as fh:
            for c in chunks:
                fh.write(c)
    except OSError as exc:
        raise TilekitError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from None


# --------------------------------------------------------------------------- shapely, geopandas, networkx


def to_shapely(patch: Patch) -> np.ndarray:
    """Every tile as a shapely Polygon (an object array in tile order), coordinates cleaned
    by snap_noise so that shared edges coincide bit for bit for shapely's overlays."""
    out = np.empty(len(patch), dtype=object)
    for _, idx, pts in patch.groups():
        out[idx] = shapely.polygons(snap_noise(pts, decimals=12))
    return out


def to_geopandas(patch: Patch, classes: np.ndarray | None = None) -> Any:
    """A GeoDataFrame (geopandas, the ``geo`` extra): one row per tile with columns
    prototile, name, colour, aspect (and transitivity_class when given) and geometry."""
    refuse_over("tiles", len(patch), MAX_TILES, hint="a GeoDataFrame holds a shapely object per tile; use a smaller patch")
    gpd = optional("geopandas", "geo", "to_geopandas")  # optional dependency: imported when used
    cols: dict[str, Any] = {
        "prototile": patch.prototile.copy(),
        "name": np.array([p.name for p in patch.prototiles], dtype=object)[patch.prototile],
        "colour": patch.colour.copy(),
        "aspect": patch.aspect.copy(),
    }
    if classes is not None:
        cols["transitivity_class"] = np.asarray(classes, dtype=np.int64)
    return gpd.GeoDataFrame(cols, geometry=to_shapely(patch))


def to_networkx(patch: Patch, kind: str = "edge", adj: Adjacency | None = None) -> Any:
    """A networkx Graph (the ``graph`` extra): a node per tile (attributes prototile, colour,
    aspect, centre) and an edge per adjacent pair of ``kind`` (edge, vertex or touching)."""
    refuse_over("tiles", len(patch), MAX_TILES, hint="a networkx Graph holds Python dicts per tile; use a smaller patch")
    nx = optional("networkx", "graph", "to_networkx")  # optional dependency: imported when used
    adj = adjacency(patch) if adj is None else adj
    pairs = adj._kind(kind)
    g = nx.Graph()
    centres = patch.centres()
    g.add_nodes_from(
        (t, {"prototile": p, "colour": c, "aspect": a, "centre": (x, y)})
        for t, p, c, a, x, y in zip(range(len(patch)), patch.prototile.tolist(), patch.colour.tolist(),
                                    patch.aspect.tolist(), centres[:, 0].tolist(), centres[:, 1].tolist())
    )
    g.add_edges_from(pairs.tolist())
    return g


# --------------------------------------------------------------------------- matplotlib


def plot_patch(patch: Patch, ax: Any = None, colours: str | Sequence[str] | None = None,
               edges: str | None = "#222", linewidth: float = 0.5, **kwargs: Any) -> Any:
    """Draw the patch on a matplotlib Axes (a new one when ``ax`` is None) as ONE
    PolyCollection; ``colours`` is the palette (colour c fills with ``colours[c % len]``),
    ``edges`` the outline colour (None: no outlines). Returns the Axes."""
    refuse_over("tiles", len(patch), MAX_TILES, hint="plot a clipped patch")
    palette = parse_palette(colours) or PALETTE
    if edges is not None and not is_colour(edges):
        raise ParameterError(f"edge colour {str(edges)[:40]!r} is not a CSS colour name or #rgb / #rrggbb")
    optional("matplotlib", "plot", "Patch.plot")  # optional dependency: imported when used
    collections = importlib.import_module("matplotlib.collections")
    colors = importlib.import_module("matplotlib.colors")
    if ax is None:
        plt = importlib.import_module("matplotlib.pyplot")
        _, ax = plt.subplots()
    ks = {len(p.outline) for p in patch.prototiles}
    verts: Any
    if len(ks) == 1:  # one outline length: one (n, k, 2) array
        verts = np.zeros((len(patch), ks.pop(), 2))
        for _, idx, pts in patch.groups():
            verts[idx] = pts
    else:  # (k, 2) views of each prototile's batch, put in tile order by one C-level gather
        tiles, views = [], []
        for _, idx, pts in patch.groups():
            tiles.append(idx)
            views.extend(pts)
        where = np.empty(len(patch), dtype=np.int64)
        where[np.concatenate(tiles)] = np.arange(len(patch))
        verts = list(operator.itemgetter(*where.tolist())(views)) if len(patch) > 1 else views
    rgba = np.array([colors.to_rgba(c) for c in palette])
    face = rgba[patch.colour % len(palette)]
    coll = collections.PolyCollection(verts, facecolors=face,
                                      edgecolors="none" if edges is None else edges,
                                      linewidths=0 if edges is None else linewidth, **kwargs)
    ax.add_collection(coll)
    if len(patch):
        x0, y0, x1, y1 = patch.bounds()
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    return ax


# --------------------------------------------------------------------------- notebooks


def _too_many(what: str, count: float) -> str:
    return (f"{what}: about {int(count):,} tiles, over the notebook drawing limit MAX_REPR_TILES = "
            f"{MAX_REPR_TILES:,} (draw a smaller region, or use .plot() / .to_svg())")


def patch_svg_or_none(patch: Patch, size: int = 400) -> str | None:
    """SVG for a notebook, or None for a patch over MAX_REPR_TILES."""
    if len(patch) > MAX_REPR_TILES:
        return None
    return patch_to_svg(patch, size=size)


def patch_mimebundle(patch: Patch) -> dict[str, str]:
    """What Jupyter shows for a patch: its picture (under MAX_REPR_TILES) and a text line."""
    svg = patch_svg_or_none(patch)
    if svg is None:
        return {"text/plain": _too_many(repr(patch), len(patch))}
    return {"text/plain": repr(patch), "image/svg+xml": svg}


def tiling_mimebundle(tiling: Tiling, region: Any = None) -> dict[str, str]:
    """What Jupyter shows for a tiling: a patch of its default region (the estimate is
    checked against MAX_REPR_TILES before anything is made) and a text line."""
    text = repr(tiling)
    estimate = tiling.estimate_tiles(region)
    if estimate > MAX_REPR_TILES:
        return {"text/plain": _too_many(text, estimate)}
    patch = tiling.patch(tiling.default_region() if region is None else region)
    if len(patch) > MAX_REPR_TILES:
        return {"text/plain": _too_many(text, len(patch))}
    return {"text/plain": text, "image/svg+xml": tiling.render_svg(patch, size=400)}


# --------------------------------------------------------------------------- one entry point


#: Formats written from a stream of patches (:func:`write_patches`), so that ``tilekit render``
#: can write a patch larger than memory: GeoJSON features and SVG paths need nothing of the
#: tiles before them (the SVG's view box is the region). JSON lists neighbours and the cut
#: files each shared edge once, which need the whole patch; PNG and DXF are drawn in memory.
STREAM_FORMATS = (".geojson", ".svg")

#: File bytes per tile of each text format: (fixed, per outline vertex), from the sizes
#: measured on Penrose P3 rhombs (4 vertices: 325 / 64 / 357 / 64 / 62 bytes a tile as
#: .geojson / .svg / .json / .cut.svg / .csv), the hat (13: 473 / 165 / 492 / 135 / 56, with
#: metatile labels) and the spectre (14: 651 / 221 / 681 / 216 / 66, with labels), rounded up
#: with room for a small file's header and for the longer indices of large patches
#: (docs/benchmarks.md; the cut SVG's since its lines are chained into paths).
FILE_BYTES_PER_TILE: dict[str, tuple[int, int]] = {
    ".geojson": (190, 36), ".svg": (40, 16), ".json": (240, 34), ".cut.svg": (20, 17), ".csv": (130, 0),
}


def memory_per_tile(fmt: str, vertices: int = 4, making: int = GENERATION_BYTES_PER_TILE) -> int:
    """Peak bytes per tile of making a patch (``making``: the tiling's ``bytes_per_tile``)
    and writing it as ``fmt``, for tiles of ``vertices`` outline vertices: the larger of the
    format's cost per tile and per vertex (limits.EXPORT_BYTES_PER_VERTEX: a tile with shaped
    edges costs its vertices; docs/benchmarks.md "Limits, measured")."""
    fixed = RENDER_BYTES_PER_TILE if fmt in (".svg", ".png") else 0
    per_vertex = EXPORT_BYTES_PER_VERTEX.get(fmt, ADJACENCY_BYTES_PER_VERTEX)
    return making + max(fixed, per_vertex * vertices)


def outline_vertices(prototiles: Sequence[Any]) -> int:
    """The most outline vertices of any of these prototiles (what a tile costs to draw)."""
    return max((len(p.outline) for p in prototiles), default=4)


def check_export_size(estimate: float, fmt: str, max_tiles: float = MAX_TILES, memory: bool = True,
                      vertices: int = 4, making: int = GENERATION_BYTES_PER_TILE) -> None:
    """Refuse an export of about ``estimate`` tiles before anything is made: over
    ``max_tiles`` (``--max-tiles``), over MAX_DXF_TILES for DXF, or (``memory``) when the
    patch and the export's arrays, for tiles of ``vertices`` vertices, would not fit in memory."""
    refuse_over("tiles", estimate, max_tiles, "--max-tiles")
    if fmt == ".dxf":
        refuse_over("tiles", estimate, MAX_DXF_TILES,
                    hint=f"a DXF drawing is built in memory, at most MAX_DXF_TILES = {MAX_DXF_TILES:,} tiles")
    if memory:
        refuse_over_memory("tiles", estimate, memory_per_tile(fmt, vertices, making),
                           hint=f"tiles of {vertices} vertices; ask for a smaller depth or region")


def export_fits_in_memory(estimate: float, fmt: str, vertices: int = 4,
                          making: int = GENERATION_BYTES_PER_TILE) -> bool:
    """Whether :func:`check_export_size` lets the whole patch be made in memory."""
    return fits_in_memory(estimate, memory_per_tile(fmt, vertices, making))


def stream_chunk_tiles(fmt: str, vertices: int = 4) -> int:
    """Tiles per chunk of a streamed export: STREAM_CHUNK_TILES, or what half the memory
    :func:`check_export_size` allows holds, when less."""
    fit = MEMORY_FRACTION * limits.available_memory() / (2 * memory_per_tile(fmt, vertices))
    return int(max(1, min(STREAM_CHUNK_TILES, fit)))


def file_size_estimate(estimate: float, fmt: str, prototiles: Sequence[Any]) -> float | None:
    """Bytes of a ``fmt`` file of about ``estimate`` tiles of these prototiles
    (FILE_BYTES_PER_TILE), or None for formats without a measure (PNG, DXF)."""
    per = FILE_BYTES_PER_TILE.get(fmt)
    if per is None:
        return None
    vertices = max((len(p.outline) for p in prototiles), default=0)
    return estimate * (per[0] + per[1] * vertices)


def check_disk_space(path: str | Path, estimate: float, fmt: str, prototiles: Sequence[Any]) -> None:
    """LimitError (one line) when the file of about ``estimate`` tiles would not fit in the
    free space of the file system it is written to (``shutil.disk_usage``)."""
    size = file_size_estimate(estimate, fmt, prototiles)
    folder = Path(path).absolute().parent
    if size is None or not folder.is_dir():
        return  # (a missing folder fails when the file is opened)
    free = float(shutil.disk_usage(folder).free)
    if size > free:
        raise LimitError(
            f"{Path(path).name} would take about {size / 2**30:.3g} GiB ({int(estimate):,} tiles as {fmt}), "
            f"more than the {free / 2**30:.3g} GiB free in {folder}; ask for a smaller depth or region"
        )


def write_patches(patches: Iterable[Patch], path: str | Path, **svg_options: Any) -> int:
    """Write a stream of patches (``Tiling.iter_patches``) as one .geojson or .svg file,
    one patch at a time (STREAM_FORMATS); returns the number of tiles written. An SVG needs
    ``region`` (its view box) among ``svg_options``, the options of
    :func:`tilekit.render.svg_lines`."""
    fmt = output_format(path)
    if fmt not in STREAM_FORMATS:
        raise ParameterError(f"{fmt} cannot be written from a stream of patches; stream {' or '.join(STREAM_FORMATS)}")
    count = 0

    def counted() -> Iterator[Patch]:
        nonlocal count
        for p in patches:
            count += len(p)
            yield p

    if fmt == ".geojson":
        if svg_options:
            raise ParameterError(f"options {', '.join(sorted(svg_options))} apply to .svg, not .geojson")
        write_text(iter_geojson_patches(counted()), path)
    else:
        if svg_options.get("region") is None:
            raise ParameterError("a streamed SVG needs its region (the view box) before the first tile")
        write_text(_joined(svg_lines(counted(), **svg_options)), path)
    return count


def _joined(lines: Iterator[str]) -> Iterator[str]:
    """The text of ``"\n".join(lines)``, a line at a time."""
    sep = ""
    for line in lines:
        yield sep + line
        sep = "\n"


def write_patch(patch: Patch, path: str | Path, *, classes: np.ndarray | None = None, layers: str = "one",
                mm_per_unit: float = 10.0, palette: Sequence[str] | None = None, stroke: str | None = None,
                labels: Sequence[str] | np.ndarray | None = None) -> str:
    """Write ``patch`` as the format its suffix names (.geojson, .json, .csv, .cut.svg, .dxf;
    the pictures .svg / .png go through tilekit.render); returns the format's suffix.
    ``labels`` (a name per tile, e.g. ``Tiling.tile_labels``) go into .json and .csv."""
    fmt = output_format(path)
    if fmt in (".svg", ".png"):
        raise ParameterError(f"{fmt} is a picture: draw it with Patch.to_svg / tilekit.render.write_image")
    if fmt in (".geojson", ".json", ".csv") and (layers != "one"):
        raise ParameterError(f"layers apply to .cut.svg and .dxf output, not {fmt}")
    if fmt == ".geojson":
        write_text(iter_geojson(patch, classes), path)
    elif fmt == ".json":
        write_text(iter_json(patch, classes=classes, labels=labels), path)
    elif fmt == ".csv":
        write_text(iter_csv(patch, labels), path)
    elif fmt == ".cut.svg":
        write_text(iter_cut_svg(patch, layers, mm_per_unit, stroke or "#ff0000", palette), path)
    else:
        write_dxf(patch, path, layers, mm_per_unit)
    return fmt
