"""Escherization (Kaplan and Salesin, SIGGRAPH 2000; Kaplan 2009, §7.3): the isohedral tile
that best resembles a goal polygon, searched over the types, their tiling vertex parameters
and their edge shapes.

The metric is Kaplan and Salesin's: both outlines are resampled to ``samples`` points by arc
length and aligned by the best similarity (a complex least-squares fit, the 2D Procrustes
problem) over every cyclic shift of the starting point, found for all shifts at once by one
FFT cross-correlation; with ``reflection`` the mirrored goal is tried too (a type's tilings
are closed under reflection, so a mirrored tile is as good a tile). The distance is
``sqrt(residual / sum |g - mean g|^2)``, the RMS gap relative to the goal's RMS radius: 0 for
similar shapes, at most 1.

The optimisation follows Koizumi and Sugihara (2011): for fixed tiling vertices the tile's
outline is linear in the edge shapes' control points, so given an alignment the best control
points are a linear least-squares projection. Each evaluation of the tiling vertex
parameters therefore alternates (resample, align over all shifts, project) a few times, and
only the parameters (0 to 6 per type) are left to scipy's Nelder-Mead, from several starts.
The outline is built from the family's engine (:class:`~.engine.HopEngine`): its local edge
curves are an affine function of the control points, read once per type from the engine.
"""

from __future__ import annotations

import functools
import json
import math
import os
import re
import time
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.files import check_output, read_text
from tilekit.limits import MAX_COORDINATE
from tilekit.plugins.isohedral.engine import HopEngine, IsohedralTiling, shape_classes
from tilekit.plugins.isohedral.escher_limits import (
    DEFAULT_EDGE_POINTS,
    DEFAULT_SAMPLES,
    DEFAULT_STARTS,
    MAX_EDGE_POINTS,
    MAX_GOAL_BYTES,
    MAX_GOAL_POINTS,
    MAX_SAMPLES,
    MAX_STARTS,
    MAX_WORKERS,
    MIN_SAMPLES,
)
from tilekit.plugins.isohedral.shapes import EdgeShape
from tilekit.plugins.isohedral.spec import editor_path
from tilekit.plugins.isohedral.templates import get_template, load_parameterizations
from tilekit.polygon import signed_area
from tilekit.schema import parse_json

# ------------------------------------------------------------------------ limits

#: Sub-sample offsets of the goal tried with every cyclic shift (alignment resolution).
SUBSHIFTS = 4
#: Alternations (resample, align, project) per evaluation of the parameters, and at the end.
INNER_STEPS = 6
FINAL_STEPS = 30
#: Weights of the pull of control points towards the straight edge (tile units, per sample),
#: one per start in turn: the alternation is a local method, and which weight leads to the
#: best basin varies from type to type (measured on the fish goal), so starts vary it too.
RIDGES = (1e-4, 1e-6, 1e-3, 1e-5)
#: Function evaluations of the final joint least-squares polish, and its (tiny) pull of the
#: control points towards straight edges.
POLISH_EVALUATIONS = 40
POLISH_RIDGE = 1e-8
#: Added to the distance of a fit whose outline touches or crosses itself.
CROSSING_PENALTY = 0.05
#: How far the edge shapes are shrunk towards straight when a fitted tile does not tile.
BACKOFF = (1.0, 0.9, 0.8, 0.65, 0.5, 0.35, 0.2, 0.1, 0.0)


def unmarked_types() -> list[int]:
    """The 81 unmarked types, the ones with tiling vertex parameterizations."""
    return [ih for ih in range(1, 94) if not get_template(ih).marked]


def parse_types(text: str) -> list[int]:
    """``IH1,IH4,16`` -> [1, 4, 16]; every name must be an unmarked type."""
    valid = set(unmarked_types())
    out: list[int] = []
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        m = re.fullmatch(r"(?i)(?:ih)?0*(\d{1,3})", part)
        ih = int(m.group(1)) if m else None
        if ih is None or ih not in valid:
            why = " (a marked type: no tiling vertex parameterization)" if ih in range(1, 94) else ""
            raise ParameterError(
                f"--types: {part!r} is not an unmarked isohedral type{why}; valid: IH1..IH93 "
                "without the 12 marked ones (IH19, 35, 48, 60, 63, 65, 70, 75, 80, 87, 89, 92)"
            )
        if ih not in out:
            out.append(ih)
    if not out:
        raise ParameterError(f"--types {text!r} names no type; give e.g. IH1,IH4,IH16")
    return out


# ------------------------------------------------------------------------ goals


def check_goal(points: Any, what: str = "goal") -> np.ndarray:
    """A simple polygon as a (k, 2) counter-clockwise array, or a ParseError saying why not.

    Repeated consecutive points and a closing copy of the first point are dropped.
    """
    # measured start-up cost: shapely (~0.1 s) is needed only for the simplicity test
    import shapely

    try:
        pts = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise ParseError(f"{what}: the points are not numbers; give [[x, y], ...]") from None
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise ParseError(f"{what}: the points are not a list of [x, y] pairs (got shape {list(pts.shape)})")
    if not np.all(np.isfinite(pts)):
        raise ParseError(f"{what}: every coordinate must be a finite number")
    if len(pts) and float(np.abs(pts).max()) > MAX_COORDINATE:
        raise ParseError(f"{what}: coordinates must lie within ±{MAX_COORDINATE:.0e} (the goal is scaled to "
                         f"the tile anyway), got {float(np.abs(pts).max()):.3g}")
    if len(pts) > MAX_GOAL_POINTS:
        raise ParseError(f"{what}: {len(pts)} points is more than the limit of {MAX_GOAL_POINTS}")
    if len(pts):
        keep = np.ones(len(pts), dtype=bool)
        keep[1:] = np.any(pts[1:] != pts[:-1], axis=1)
        pts = pts[keep]
        if len(pts) > 1 and np.all(pts[-1] == pts[0]):
            pts = pts[:-1]
    if len(pts) < 3:
        raise ParseError(f"{what}: a polygon needs at least 3 distinct points, got {len(pts)}")
    span = float(np.ptp(pts, axis=0).max())
    area = signed_area(pts)
    zero = f"{what}: the polygon has zero area; give a simple polygon enclosing a region"
    if span == 0 or np.linalg.svd(pts - pts.mean(axis=0), compute_uv=False)[1] <= 1e-9 * span:
        raise ParseError(zero)  # all points on one line
    if not shapely.LinearRing(pts).is_simple:
        raise ParseError(f"{what}: the polygon crosses itself; give a simple polygon (no self-intersections)")
    if abs(area) <= 1e-9 * span * span:
        raise ParseError(zero)
    return pts if area > 0 else pts[::-1].copy()


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_PATH_TOKEN = re.compile(r"([MmLlHhVvZzCcSsQqTtAa])|" + _NUMBER.pattern)


def _svg_numbers(text: str, what: str) -> list[float]:
    rest = _NUMBER.sub(" ", text).replace(",", " ").strip()
    if rest:
        raise ParseError(f"{what}: {rest[:20]!r} is not a number")
    return [float(v) for v in _NUMBER.findall(text)]


def svg_path_points(d: str, what: str = "SVG path") -> np.ndarray:
    """The vertices of one closed subpath of M/L/H/V/Z commands (absolute or relative)."""
    tokens = [m.group(0) for m in _PATH_TOKEN.finditer(d)]
    leftover = _PATH_TOKEN.sub(" ", d).replace(",", " ").strip()
    if leftover:
        raise ParseError(f"{what}: {leftover[:20]!r} is not path data (M/L/H/V/Z commands and numbers)")
    pts: list[tuple[float, float]] = []
    cmd = ""
    x = y = 0.0
    i = 0
    closed = False
    while i < len(tokens):
        tok = tokens[i]
        if tok.isalpha():
            if tok in "CcSsQqTtAa":
                raise ParseError(
                    f"{what}: curve command {tok!r} is not supported; give a polygon (M, L, H, V, Z "
                    "commands only; flatten curves to line segments first)"
                )
            if closed and tok not in "Zz":
                raise ParseError(f"{what}: more than one subpath; the goal must be one simple polygon")
            cmd = tok
            i += 1
            if tok in "Zz":
                closed = True
            continue
        if not cmd:
            raise ParseError(f"{what}: path data must start with a move command M")
        need = 1 if cmd in "HhVv" else 2
        if i + need > len(tokens) or any(t.isalpha() for t in tokens[i : i + need]):
            raise ParseError(f"{what}: command {cmd!r} is missing coordinates")
        vals = [float(t) for t in tokens[i : i + need]]
        i += need
        rel = cmd.islower()
        if cmd in "Mm":
            if pts:
                raise ParseError(f"{what}: more than one subpath; the goal must be one simple polygon")
            x, y = (x + vals[0], y + vals[1]) if rel else (vals[0], vals[1])
            cmd = "l" if rel else "L"  # coordinates after a move are line-tos
        elif cmd in "Ll":
            x, y = (x + vals[0], y + vals[1]) if rel else (vals[0], vals[1])
        elif cmd in "Hh":
            x = x + vals[0] if rel else vals[0]
        else:
            y = y + vals[0] if rel else vals[0]
        pts.append((x, y))
    return np.array(pts, dtype=float).reshape(-1, 2)


def read_svg_goal(text: str, name: str) -> np.ndarray:
    """The one polygon, polyline or path element of an SVG document, as displayed: SVG's y
    axis points down and tilekit's up (the renderer flips it), so y is negated; otherwise
    the goal would be matched as its mirror image, which matters with ``reflection=False``."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as exc:
        raise ParseError(f"{name}: not readable SVG/XML ({exc})") from None
    shapes = [el for el in root.iter() if isinstance(el.tag, str) and el.tag.rpartition("}")[2] in ("path", "polygon", "polyline")]
    if not shapes:
        raise ParseError(f"{name}: no <path>, <polygon> or <polyline> element; the goal must be one polygon")
    if len(shapes) > 1:
        raise ParseError(f"{name}: {len(shapes)} shape elements; the goal must be exactly one <path>, <polygon> or <polyline>")
    el = shapes[0]
    for node in root.iter():
        if node.get("transform"):
            raise ParseError(f"{name}: transform attributes are not supported; apply them to the coordinates first")
    tag = el.tag.rpartition("}")[2]
    if tag == "path":
        pts = svg_path_points(el.get("d") or "", f"{name}: <path d>")
    else:
        nums = _svg_numbers(el.get("points") or "", f"{name}: <{tag} points>")
        if len(nums) % 2:
            raise ParseError(f"{name}: <{tag} points> has an odd count of numbers ({len(nums)})")
        pts = np.array(nums, dtype=float).reshape(-1, 2)
    return pts * [1.0, -1.0]


def read_goal(path: str | os.PathLike) -> np.ndarray:
    """A goal polygon from an SVG file (one path/polygon/polyline) or a JSON point list
    (``[[x, y], ...]`` or ``{"points": [[x, y], ...]}``), checked by :func:`check_goal`."""
    p = Path(path)
    name = p.name
    suffix = p.suffix.lower()
    if suffix not in (".svg", ".json"):
        raise ParseError(f"goal {name!r} must be an .svg or .json file")
    text = read_text(p, "goal file", MAX_GOAL_BYTES)
    if suffix == ".svg":
        pts = read_svg_goal(text, name)
    else:
        data = parse_json(text, name)
        if isinstance(data, dict):
            data = data.get("points")
        if not isinstance(data, list) or not all(
            isinstance(q, list) and len(q) == 2 and all(isinstance(v, int | float) and not isinstance(v, bool) for v in q)
            for q in data
        ):
            raise ParseError(f'{name}: the goal must be a JSON list of [x, y] number pairs (or {{"points": [...]}})')
        try:
            pts = np.array(data, dtype=float).reshape(-1, 2)
        except OverflowError:
            raise ParseError(f"{name}: a coordinate is too large to be a number (every coordinate must be finite)") from None
    return check_goal(pts, name)


# ------------------------------------------------------------------------ the metric


def _complex(points: np.ndarray) -> np.ndarray:
    pts = np.asarray(points, dtype=float)
    return pts[..., 0] + 1j * pts[..., 1]


def resample(z: np.ndarray, n: int, offsets: np.ndarray | float = 0.0) -> np.ndarray:
    """A closed outline (complex vertices) resampled to n points equally spaced by arc length,
    starting ``offset`` samples along from vertex 0; with an array of offsets, one row each."""
    z = np.asarray(z, dtype=complex)
    seg = np.abs(np.roll(z, -1) - z)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    total = cum[-1]
    off = np.atleast_1d(np.asarray(offsets, dtype=float))
    t = ((np.arange(n)[None, :] + off[:, None]) * (total / n)) % total
    closed = np.append(z, z[0])
    out = np.interp(t, cum, closed.real) + 1j * np.interp(t, cum, closed.imag)
    return out if np.ndim(offsets) else out[0]


@dataclass
class GoalBank:
    """The goal resampled at every sub-sample offset (and mirrored), centred, with FFTs."""

    samples: int
    rows: np.ndarray  # (o * r, n) complex, centred
    spectra: np.ndarray  # FFT of rows
    norms: np.ndarray  # sum |row|^2
    mirrored: np.ndarray  # (o * r,) bool
    offsets: np.ndarray  # (o * r,) sub-sample offset of each row
    centre: complex
    scale: float  # sqrt(mean |g - centre|^2), the goal's RMS radius

    @classmethod
    def build(cls, goal: np.ndarray, samples: int, reflection: bool, subshifts: int = SUBSHIFTS) -> GoalBank:
        z = _complex(goal)
        offs = np.arange(subshifts) / subshifts
        rows = [resample(z, samples, offs)]
        mirrored = [np.zeros(subshifts, dtype=bool)]
        if reflection:
            # the mirror image, walked backwards to stay counter-clockwise
            rows.append(resample(np.conj(z)[::-1], samples, offs))
            mirrored.append(np.ones(subshifts, dtype=bool))
        r = np.vstack(rows)
        centre = complex(r[0].mean())
        r = r - r.mean(axis=1, keepdims=True)
        norms = np.sum(np.abs(r) ** 2, axis=1)
        return cls(samples, r, np.fft.fft(r, axis=1), norms, np.concatenate(mirrored), np.tile(offs, len(rows)),
                   centre, float(np.sqrt(norms[0] / samples)))

    def align(self, zs: np.ndarray) -> tuple[float, int, int, complex]:
        """Best alignment of tile samples zs (n,): (distance, row, shift, a) with
        ``a * (zs - mean) ~ row[(i + shift) % n]``."""
        zc = zs - zs.mean()
        zn = float(np.sum(np.abs(zc) ** 2))
        if zn <= 0:
            return 1.0, 0, 0, 0j
        corr = np.fft.ifft(np.conj(np.fft.fft(zc))[None, :] * self.spectra, axis=1)
        score = np.abs(corr) ** 2 / (zn * self.norms[:, None])
        flat = int(np.argmax(score))
        row, shift = divmod(flat, self.samples)
        d2 = max(0.0, 1.0 - float(score[row, shift]))
        return math.sqrt(d2), row, shift, complex(corr[row, shift] / zn)


def shape_distance(a: Any, b: Any, samples: int = DEFAULT_SAMPLES, reflection: bool = True, refine: bool = True) -> float:
    """Kaplan and Salesin's distance of outline ``a`` from goal ``b`` (both (k, 2) polygons).

    Both are resampled to ``samples`` points by arc length and ``a`` is aligned to ``b`` by the
    best similarity over cyclic shifts (and the mirror image when ``reflection``). The result
    is the RMS gap over the RMS radius of ``b`` (in [0, 1]). ``refine`` searches the starting
    offset continuously around the best sub-sample shift instead of on the grid alone.
    """
    check_samples(samples)
    a_pts = check_goal(a, "outline")
    b_pts = check_goal(b, "goal")
    return _distance(_complex(a_pts), b_pts, samples, reflection, refine)[0]


def _distance(za: np.ndarray, goal: np.ndarray, samples: int, reflection: bool, refine: bool,
              bank: GoalBank | None = None) -> tuple[float, dict[str, Any]]:
    bank = bank or GoalBank.build(goal, samples, reflection)
    zs = resample(za, samples)
    d, row, shift, a = bank.align(zs)
    best = (d, bool(bank.mirrored[row]), float(bank.offsets[row]) + shift, a)
    if refine:
        from scipy.optimize import minimize_scalar  # start-up cost: scipy (~0.3 s), only here

        g = _complex(goal)
        src = np.conj(g)[::-1] if best[1] else g
        base = best[2]

        def cost(u: float) -> float:
            w = resample(src, samples, base + u)
            w = w - w.mean()
            zc = zs - zs.mean()
            c = np.vdot(zc, w)
            return max(0.0, 1.0 - abs(c) ** 2 / (np.vdot(zc, zc).real * np.vdot(w, w).real))

        h = 1.0 / SUBSHIFTS
        res = minimize_scalar(cost, bounds=(-h, h), method="bounded", options={"xatol": 1e-6})
        if res.fun < best[0] ** 2:
            best = (math.sqrt(res.fun), best[1], base + float(res.x), best[3])
    return best[0], {"mirrored": best[1], "offset": best[2]}


def check_samples(samples: int) -> None:
    if not (isinstance(samples, int) and MIN_SAMPLES <= samples <= MAX_SAMPLES):
        raise ParameterError(f"samples {samples!r} must be an integer from {MIN_SAMPLES} to {MAX_SAMPLES}")


# ------------------------------------------------------------------------ one type's tile space


@dataclass
class TypeModel:
    """The tiles of one type as (parameters, control points): the outline is
    ``P[e] + D[e] * (L0 + Lb @ c)`` for tiling vertices P, edge vectors D = P[i+1] - P[i] and the
    local (unit-segment) coordinates L of each outline vertex, affine in the control points c.
    L0 and Lb are read from the engine once; they do not depend on the tiling vertices."""

    ih: int
    edge_points: int
    labels: tuple[str, ...]  # shape classes (labels that own a fundamental shape)
    coefficients: np.ndarray  # the parameterization's (2k, n+1) matrix, rolled to the symbol's edges
    default: np.ndarray
    edge_of: np.ndarray  # (m,) tiling edge of each outline vertex
    local0: np.ndarray  # (m,) complex
    local_basis: np.ndarray  # (m, nc) complex
    c0: np.ndarray  # (nc,) straight edges

    @property
    def name(self) -> str:
        return f"IH{self.ih}"

    @property
    def n_params(self) -> int:
        return len(self.default)

    def vertices(self, p: np.ndarray) -> np.ndarray:
        v = self.coefficients @ np.append(np.asarray(p, dtype=float), 1.0)
        return v[0::2] + 1j * v[1::2]

    def linear(self, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(A, b): the outline is A @ c + b (complex) at parameters p."""
        verts = self.vertices(p)
        d = np.roll(verts, -1) - verts
        de = d[self.edge_of]
        return de[:, None] * self.local_basis, verts[self.edge_of] + de * self.local0

    def outline(self, p: np.ndarray, c: np.ndarray) -> np.ndarray:
        a, b = self.linear(p)
        return a @ c + b

    def shapes(self, c: np.ndarray) -> dict[str, EdgeShape]:
        k = self.edge_points
        out = {}
        for j, lab in enumerate(self.labels):
            inner = np.asarray(c[2 * k * j : 2 * k * (j + 1)], dtype=float).reshape(k, 2)
            out[lab] = EdgeShape(np.vstack([[0.0, 0.0], inner, [1.0, 0.0]]))
        return out

    def tiling(self, p: np.ndarray, c: np.ndarray) -> IsohedralTiling:
        """The engine's tiling (checked: simple tile, no overlapping neighbours)."""
        return IsohedralTiling(self.ih, [float(v) for v in p], self.shapes(c), check=True)

    def polygon_ok(self, p: np.ndarray) -> float:
        """0 if the tiling polygon is simple and counter-clockwise, else a positive violation."""
        z = self.vertices(p)
        n = len(z)
        d = np.roll(z, -1) - z
        area = 0.5 * float(np.sum((np.conj(z) * np.roll(z, -1)).imag))
        scale = float(np.max(np.abs(d)))
        if scale <= 0 or area <= 1e-6 * scale * scale:
            return 1.0 + max(0.0, -area)
        if np.min(np.abs(d)) < 1e-3 * scale:
            return 1.0
        # non-adjacent edges must not cross (at most 6 edges: 9 pairs)
        i, j = np.triu_indices(n, 2)
        keep = (j - i) % n != n - 1
        i, j = i[keep], j[keep]
        if len(i):
            def cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
                return (np.conj(u) * v).imag
            a0, a1, b0, b1 = z[i], z[(i + 1) % n], z[j], z[(j + 1) % n]
            s1 = cross(a1 - a0, b0 - a0) * cross(a1 - a0, b1 - a0)
            s2 = cross(b1 - b0, a0 - b0) * cross(b1 - b0, a1 - b0)
            if np.any((s1 < 0) & (s2 < 0)):
                return 1.0
        return 0.0


@functools.cache
def type_model(ih: int, edge_points: int = DEFAULT_EDGE_POINTS) -> TypeModel:
    """The :class:`TypeModel` of an unmarked type (cached): local outline coordinates read from
    the engine's outline for the straight shapes and for each control coordinate moved by 1."""
    t = get_template(ih)
    if t.marked:
        raise ParameterError(f"IH{ih} is a marked type; escherization takes the 81 unmarked types")
    tv = load_parameterizations()[t.parameterization or ""]
    coeff = np.roll(tv.coefficients.reshape(-1, 2, tv.coefficients.shape[1]), -t.edge_offset, axis=0)
    coeff = coeff.reshape(tv.coefficients.shape)
    verts = (coeff @ np.append(np.asarray(tv.default, dtype=float), 1.0)).reshape(-1, 2)
    labels = tuple(shape_classes(t.symbol))
    k = edge_points
    xs = np.arange(1, k + 1) / (k + 1)
    c0 = np.tile(np.column_stack([xs, np.zeros(k)]).ravel(), len(labels))
    engine = HopEngine(t.symbol, verts)
    inv = engine.inverse_frames

    def local(c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        shapes = {}
        for j, lab in enumerate(labels):
            inner = c[2 * k * j : 2 * k * (j + 1)].reshape(k, 2)
            shapes[lab] = EdgeShape(np.vstack([[0.0, 0.0], inner, [1.0, 0.0]]))
        _, _, paths = engine.outline(shapes)
        loc, edge = [], []
        for i, path in enumerate(paths):
            q = path[:-1] @ inv[i][:2, :2].T + inv[i][:2, 2]
            loc.append(q[:, 0] + 1j * q[:, 1])
            edge.append(np.full(len(q), i))
        return np.concatenate(loc), np.concatenate(edge)

    base, edge_of = local(c0)
    basis = np.empty((len(base), len(c0)), dtype=complex)
    for j in range(len(c0)):
        step = c0.copy()
        step[j] += 1.0
        basis[:, j] = local(step)[0] - base
    basis[np.abs(basis) < 1e-12] = 0.0
    local0 = base - basis @ c0
    return TypeModel(ih, k, labels, coeff, np.asarray(tv.default, dtype=float), edge_of, local0, basis, c0)


# ------------------------------------------------------------------------ fitting one type


def crossings(z: np.ndarray) -> int:
    """1 if the closed outline z (complex) touches or crosses itself, else 0 (GEOS's simplicity
    test of the ring: the engine's check of edges that cross, without the neighbours)."""
    import shapely  # start-up cost: shapely (~0.1 s), loaded by the engine anyway

    ring = shapely.linearrings(np.column_stack([z.real, z.imag]))
    return 0 if shapely.is_simple(ring) else 1


def _samples_matrix(z: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Arc-length resampling of the closed outline z as a 2-sparse linear map: sample j is
    ``(1 - f[j]) z[q[j]] + f[j] z[q1[j]]``."""
    m = len(z)
    seg = np.abs(np.roll(z, -1) - z)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    t = np.arange(n) * (cum[-1] / n)
    q = np.clip(np.searchsorted(cum, t, side="right") - 1, 0, m - 1)
    f = (t - cum[q]) / np.where(seg[q] > 0, seg[q], 1.0)
    return q, (q + 1) % m, f


def _project(model: TypeModel, p: np.ndarray, bank: GoalBank, steps: int, ridge: float = RIDGES[0],
             c: np.ndarray | None = None) -> tuple[float, np.ndarray]:
    """Alternate ``steps`` times: resample the tile, align the goal to it over all shifts,
    then project the control points onto the aligned goal (linear least squares)."""
    a_mat, b_vec = model.linear(p)
    c = model.c0.copy() if c is None else c.copy()
    n = bank.samples
    nc = len(c)
    scale2 = float(np.mean(np.abs(np.roll(model.vertices(p), -1) - model.vertices(p)) ** 2))
    ridge2 = ridge * n * scale2
    d = 1.0
    for step in range(steps + 1):
        z = a_mat @ c + b_vec
        q, q1, f = _samples_matrix(z, n)
        zs = (1 - f) * z[q] + f * z[q1]
        d, row, shift, a = bank.align(zs)
        if step == steps or nc == 0 or a == 0:
            break
        # target: a * (zs - mean) ~ w  =>  zs ~ w / a + mean; the mean is a free translation
        target = np.roll(bank.rows[row], -shift) / a
        ws = (1 - f)[:, None] * a_mat[q] + f[:, None] * a_mat[q1]
        bs = (1 - f) * b_vec[q] + f * b_vec[q1]
        # normal equations of the ridge-regularised least squares (nc + 2 unknowns; an SVD
        # solver costs ~10x more here and nothing is ill-posed with the ridge)
        x = np.zeros((2 * n, nc + 2))
        x[:n, :nc], x[n:, :nc] = ws.real, ws.imag
        x[:n, nc], x[n:, nc + 1] = -1.0, -1.0  # translation (tx, ty)
        y = np.concatenate([(target - bs).real, (target - bs).imag])
        lhs = x.T @ x
        lhs[:nc, :nc] += ridge2 * np.eye(nc)
        rhs = x.T @ y
        rhs[:nc] += ridge2 * model.c0
        sol = np.linalg.solve(lhs, rhs)
        c = sol[:nc]
    return d, c


class TypeFit:
    """What every fitted tile of a type has: its name and the isohedral spec of its
    parameters and edges (results of one goal, two pieces, or Heaven and Hell add to it)."""

    ih: int
    params: list[float]
    edges: dict[str, str]

    @property
    def name(self) -> str:
        return f"IH{self.ih}"

    def base_spec(self) -> dict[str, Any]:
        out: dict[str, Any] = {"ih": self.ih, "params": list(self.params)}
        if self.edges:
            out["edges"] = dict(self.edges)
        return out


@dataclass
class EscherResult(TypeFit):
    """The best tile of one type for a goal."""

    ih: int
    distance: float
    params: list[float]
    edges: dict[str, str]  # label -> EdgeShape text (the spec's "edges")
    evaluations: int
    seconds: float
    shrink: float = 1.0  # factor the fitted edge shapes were scaled by to make a valid tiling
    fitted_distance: float = 0.0  # before that shrinking
    mirrored: bool = False
    note: str = ""

    def spec(self) -> dict[str, Any]:
        """The isohedral family's spec (``tiling_from_spec`` / ``IsohedralTiling.from_spec``)."""
        return self.base_spec()

    def tiling(self) -> IsohedralTiling:
        return IsohedralTiling.from_spec(self.spec())

    def editor(self) -> str:
        """The web editor's path on this tile's tiling: ``/editor/IHn?params=...&edge=...``."""
        return editor_path(self.spec())

    def to_json(self) -> dict[str, Any]:
        return {"ih": self.ih, "name": self.name, "distance": self.distance, "fitted_distance": self.fitted_distance,
                "shrink": self.shrink, "mirrored": self.mirrored, "spec": self.spec(), "editor": self.editor(),
                "evaluations": self.evaluations, "seconds": self.seconds, "note": self.note}


@dataclass(frozen=True)
class Settings:
    """The search's sizes (samples, starts, edge points), reflection and seed (checked by ``check``)."""

    samples: int = DEFAULT_SAMPLES
    starts: int = DEFAULT_STARTS
    edge_points: int = DEFAULT_EDGE_POINTS
    reflection: bool = True
    seed: int = 0

    def check(self) -> None:
        check_samples(self.samples)
        if not (isinstance(self.starts, int) and 1 <= self.starts <= MAX_STARTS):
            raise ParameterError(f"starts {self.starts!r} must be an integer from 1 to {MAX_STARTS}")
        if not (isinstance(self.edge_points, int) and 1 <= self.edge_points <= MAX_EDGE_POINTS):
            raise ParameterError(f"edge points {self.edge_points!r} must be an integer from 1 to {MAX_EDGE_POINTS}")


def escherize_type(goal: np.ndarray, ih: int, settings: Settings = Settings()) -> EscherResult:
    """The tile of type ``ih`` nearest ``goal``: Nelder-Mead over the tiling vertex parameters
    from ``settings.starts`` starts (the default parameters, then random perturbations of
    them), each evaluation projecting the control points (:func:`_project`), then a joint
    least-squares polish (:func:`_polish`) and the engine's validity check."""
    from threadpoolctl import threadpool_limits  # start-up cost: loaded only for a search

    # the matrices are tiny (a few hundred by a few dozen): BLAS threads only add overhead,
    # and on a loaded 2-core machine OpenBLAS's spinning threads made a fit 10-20x slower
    with threadpool_limits(limits=1, user_api="blas"):
        return _escherize_type(goal, ih, settings)


def _escherize_type(goal: np.ndarray, ih: int, settings: Settings) -> EscherResult:
    from scipy.optimize import minimize  # start-up cost: scipy (~0.3 s), only for a search

    settings.check()
    t0 = time.perf_counter()
    goal = check_goal(goal)
    model = type_model(ih, settings.edge_points)
    bank = GoalBank.build(goal, settings.samples, settings.reflection)
    evaluations = 0

    def f(p: np.ndarray, ridge: float) -> float:
        nonlocal evaluations
        evaluations += 1
        bad = model.polygon_ok(p)
        if bad:
            return 1.0 + bad
        d, c = _project(model, p, bank, INNER_STEPS, ridge)
        # a fit whose outline crosses itself is no tile: steer the parameters away from it
        # (the engine's full check, with the neighbours, runs once at the end)
        return d + CROSSING_PENALTY * crossings(model.outline(p, c))

    # start i: the default parameters (i = 0) or a Gaussian perturbation of them, and the
    # ridge weight RIDGES[i % 4]; a type without parameters only varies the weight
    rng = np.random.default_rng([settings.seed, ih])
    spread = 0.25 * max(1.0, float(np.max(np.abs(model.default)))) if model.n_params else 0.0
    best_p, best_f, best_ridge = model.default.copy(), math.inf, RIDGES[0]
    for i in range(settings.starts):
        s = model.default + (spread * rng.standard_normal(model.n_params) if i else 0.0)
        ridge = RIDGES[i % len(RIDGES)]
        if model.polygon_ok(s):
            continue
        if model.n_params:
            res = minimize(f, s, args=(ridge,), method="Nelder-Mead",
                           options={"maxfev": 40 * (model.n_params + 1), "xatol": 1e-4, "fatol": 1e-7})
            x, fx = np.asarray(res.x, dtype=float), float(res.fun)
        else:
            x, fx = s, f(s, ridge)
        if fx < best_f:
            best_p, best_f, best_ridge = x, fx, ridge
    # candidates, in order: the polish of the long projection, the long projection, and the
    # projection the search scored (its outline was checked for crossings)
    _, c_short = _project(model, best_p, bank, INNER_STEPS, best_ridge)
    _, c = _project(model, best_p, bank, FINAL_STEPS, best_ridge)
    candidates = [(best_p, c), (best_p, c_short)]
    polished = _polish(model, best_p, c, goal, bank)
    if polished is not None:
        candidates.insert(0, polished)
        evaluations += polished[2]
    result = None
    for p, cc, *_ in candidates:
        if result is not None and bank.align(resample(model.outline(p, cc), bank.samples))[0] >= result.distance:
            continue  # cannot beat the valid tile already found (shrinking only moves away)
        try:
            r = _valid_result(model, p, cc, goal, settings, bank)
        except GeometryError:
            continue
        if result is None or r.distance < result.distance:
            result = r
    if result is None:
        raise GeometryError(f"IH{ih}: no valid tiling found near the fit")
    result.evaluations = evaluations
    result.seconds = time.perf_counter() - t0
    return result


def _polish(model: TypeModel, p: np.ndarray, c: np.ndarray, goal: np.ndarray, bank: GoalBank,
            max_nfev: int = POLISH_EVALUATIONS) -> tuple[np.ndarray, np.ndarray, int] | None:
    """Joint refinement of parameters, control points and the starting offset of the goal's
    resampling (continuous, not the sub-sample grid) by scipy's least_squares on the metric's
    residual vector, from the projection's answer. None if it does not improve."""
    from scipy.optimize import least_squares  # start-up cost: scipy (~0.3 s), only for a search

    n = bank.samples
    zs = resample(model.outline(p, c), n)
    d0, row, shift, _ = bank.align(zs)
    g = _complex(goal)
    src = np.conj(g)[::-1] if bank.mirrored[row] else g
    base = float(bank.offsets[row]) + shift
    npar = model.n_params
    ridge = math.sqrt(POLISH_RIDGE)

    def resid(x: np.ndarray) -> np.ndarray:
        r = similarity_residual(resample(model.outline(x[:npar], x[npar:-1]), n), resample(src, n, base + x[-1]))
        return np.concatenate([r.real, r.imag, ridge * (x[npar:-1] - model.c0)])

    x0 = np.concatenate([p, c, [0.0]])
    res = least_squares(resid, x0, method="trf", max_nfev=max_nfev, x_scale=0.1)
    x = res.x
    if not np.all(np.isfinite(x)) or model.polygon_ok(x[:npar]):
        return None
    d = math.sqrt(max(0.0, float(np.sum(res.fun[: 2 * n] ** 2))))
    if d >= d0:
        return None
    return x[:npar], x[npar:-1], int(res.nfev)


def _valid_result(model: TypeModel, p: np.ndarray, c: np.ndarray, goal: np.ndarray, settings: Settings,
                  bank: GoalBank) -> EscherResult:
    """Shrink the fitted edge shapes towards straight until the engine accepts the tiling
    (simple tile, no overlapping neighbours); report the distance of the tile it accepts."""
    note = ""
    for alpha in BACKOFF:
        cc = model.c0 + alpha * (c - model.c0)
        try:
            tiling = model.tiling(p, cc)
        except (ParameterError, GeometryError) as exc:
            note = str(exc)
            continue
        outline = _complex(tiling.prototile.outline)
        d, info = _distance(outline, goal, settings.samples, settings.reflection, refine=True, bank=bank)
        fitted = d if alpha == 1.0 else _distance(model.outline(p, c), goal, settings.samples,
                                                  settings.reflection, refine=True, bank=bank)[0]
        edges = {lab: s.to_text() for lab, s in tiling.edge_shapes.items()}
        return EscherResult(model.ih, d, [float(v) for v in p], edges, evaluations=0, seconds=0.0, shrink=alpha,
                            fitted_distance=fitted, mirrored=info["mirrored"],
                            note="" if alpha == 1.0 else f"edge shapes shrunk to {alpha:g}: {note}")
    raise GeometryError(f"IH{model.ih}: no valid tiling found near the fit ({note})")


# ------------------------------------------------------------------------ all types


def similarity_residual(z: np.ndarray, w: np.ndarray) -> np.ndarray:
    """``(a z - w) / |w|`` for the complex samples ``z`` (the tile) and ``w`` (the goal), both
    centred first, with the best complex scale-rotation ``a``: the least-squares residual whose
    squared norm is the Procrustes distance the fits minimise."""
    zc = z - z.mean()
    wc = w - w.mean()
    zn = np.vdot(zc, zc).real
    a = np.vdot(zc, wc) / zn if zn > 0 else 0j
    return (a * zc - wc) / math.sqrt(np.vdot(wc, wc).real)


def run_guarded(job: tuple[Callable[..., Any], int, tuple[Any, ...]]) -> Any:
    """One type's fit ``fit(*args)`` from a ``(fit, ih, args)`` job, or ``(ih, reason)`` when
    the type has no valid tile near the goal(s) (the job form :func:`run_jobs` takes for the
    monohedral, dihedral and Heaven-and-Hell searches alike)."""
    fit, ih, args = job
    try:
        return fit(*args)
    except (ParameterError, GeometryError) as exc:
        return ih, str(exc)


def escherize(goal: Any, types: Iterable[int] | None = None, *, settings: Settings = Settings(), workers: int = 1,
              progress: Callable[[EscherResult | tuple[int, str]], None] | None = None
              ) -> tuple[list[EscherResult], list[tuple[int, str]]]:
    """Fit every type in ``types`` (default: the 81 unmarked types) to ``goal``; return the
    results sorted by distance and the types that gave no valid tiling (with the reason).
    ``workers`` > 1 fits types in that many processes."""
    settings.check()
    goal = check_goal(goal)
    todo = list(types) if types is not None else unmarked_types()
    for ih in todo:
        if get_template(ih).marked:
            raise ParameterError(f"IH{ih} is a marked type; escherization takes the 81 unmarked types")
    if not (isinstance(workers, int) and 1 <= workers <= MAX_WORKERS):
        raise ParameterError(f"workers {workers!r} must be an integer from 1 to {MAX_WORKERS}")
    outs = run_jobs(run_guarded, [(escherize_type, ih, (goal, ih, settings)) for ih in todo], workers, progress)
    good = sorted((o for o in outs if isinstance(o, EscherResult)), key=lambda r: (r.distance, r.ih))
    failed = [o for o in outs if not isinstance(o, EscherResult)]
    return good, failed


def run_jobs(run_one: Callable[[Any], Any], jobs: Sequence[Any], workers: int,
             progress: Callable[[Any], None] | None = None) -> list[Any]:
    """``run_one`` over ``jobs`` in order, in ``workers`` processes when more than one
    (``concurrent.futures.ProcessPoolExecutor``), calling ``progress`` with each outcome."""
    outs: list[Any] = []
    if workers == 1 or len(jobs) == 1:
        for job in jobs:
            outs.append(run_one(job))
            if progress:
                progress(outs[-1])
        return outs
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=min(workers, len(jobs))) as pool:
        for out in pool.map(run_one, jobs, chunksize=1):
            outs.append(out)
            if progress:
                progress(out)
    return outs


def one_blas_thread(fit: Callable[..., Any]) -> Callable[..., Any]:
    """``fit`` run with one BLAS thread (threadpoolctl): its matrices are tiny, and on a loaded
    2-core machine OpenBLAS's spinning threads made fits 10-20x slower."""

    @functools.wraps(fit)
    def run(*args: Any, **kwargs: Any) -> Any:
        from threadpoolctl import threadpool_limits  # start-up cost: loaded only for a search

        with threadpool_limits(limits=1, user_api="blas"):
            return fit(*args, **kwargs)

    return run


def best_valid(candidates: Iterable[tuple[Any, ...]], make: Callable[..., Any], name: str,
               score: Callable[[Any], float] | None = None) -> Any:
    """The result of smallest ``score`` (default: its ``distance``) among ``make(*candidate)``
    that the engine accepts (``make`` raises GeometryError for a candidate with no valid
    tiling), or GeometryError."""
    score = score or (lambda r: r.distance)
    result = None
    for cand in candidates:
        try:
            r = make(*cand)
        except GeometryError:
            continue
        if result is None or score(r) < score(result):
            result = r
    if result is None:
        raise GeometryError(f"{name}: no valid tiling found near the fit")
    return result


def aligned_goal(result: EscherResult, goal: np.ndarray, samples: int = DEFAULT_SAMPLES) -> np.ndarray:
    """The goal polygon moved by the similarity that best fits it onto the result's tile
    (mirrored first when the fit matched the mirror image), for drawing the two together:
    the metric's alignment, with the goal's starting offset refined continuously."""
    return align_onto(np.asarray(result.tiling().prototile.outline, dtype=float), goal, result.mirrored, samples)


def align_onto(outline: np.ndarray, goal: np.ndarray, mirrored: bool, samples: int = DEFAULT_SAMPLES) -> np.ndarray:
    """The goal (mirrored first if ``mirrored``) moved by the similarity that best fits it onto
    the closed ``outline`` ((k, 2)), the starting offset refined continuously."""
    from scipy.optimize import minimize_scalar  # start-up cost: scipy (~0.3 s), only here

    tile = _complex(np.asarray(outline, dtype=float))
    g = _complex(check_goal(goal))
    src = np.conj(g)[::-1] if mirrored else g
    zs = resample(tile, samples)
    zc = zs - zs.mean()
    bank = GoalBank.build(np.column_stack([src.real, src.imag]), samples, reflection=False)
    _, row, shift, _ = bank.align(zs)
    base = float(bank.offsets[row]) + shift

    def fit(u: float) -> tuple[float, complex, complex]:
        w = resample(src, samples, base + u)
        c = np.vdot(zc, w - w.mean())
        resid = np.vdot(w - w.mean(), w - w.mean()).real - abs(c) ** 2 / np.vdot(zc, zc).real
        return resid, c / np.vdot(zc, zc).real, w.mean()

    h = 1.0 / SUBSHIFTS
    u = minimize_scalar(lambda v: fit(v)[0], bounds=(-h, h), method="bounded", options={"xatol": 1e-7}).x
    _, a, w_mean = fit(float(u))  # a * (zs - mean) ~ goal samples - their mean
    moved = (src - w_mean) / a + zs.mean()
    return np.column_stack([moved.real, moved.imag])


def framed_path(shapes: Sequence[np.ndarray], size: int) -> Callable[[np.ndarray], str]:
    """An SVG path writer for outlines framed together: all of ``shapes`` fit a ``size``
    square with a 4 % margin, y up."""
    pts = np.vstack(list(shapes))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = float(max(hi - lo)) * 1.08 or 1.0
    mid = (lo + hi) / 2

    def path(q: np.ndarray) -> str:
        xy = (np.asarray(q, dtype=float) - mid) / span * size + size / 2
        xy[:, 1] = size - xy[:, 1]
        return "M" + " L".join(f"{x:.2f},{y:.2f}" for x, y in xy) + " Z"

    return path


def outline_svg(result: EscherResult, goal: np.ndarray, size: int = 400) -> str:
    """SVG of the tile (filled) with the aligned goal (dashed outline)."""
    tile = np.asarray(result.tiling().prototile.outline, dtype=float)
    g = aligned_goal(result, goal)
    path = framed_path([tile, g], size)

    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" viewBox="0 0 {size} {size}">'
            f'<rect width="{size}" height="{size}" fill="white"/>'
            f'<path d="{path(tile)}" fill="#f4c27a" stroke="#222" stroke-width="1.5"/>'
            f'<path d="{path(g)}" fill="none" stroke="#c0392b" stroke-width="1.5" stroke-dasharray="5,3"/>'
            f'<text x="8" y="18" font-family="sans-serif" font-size="13">{result.name}  d = {result.distance:.4f}</text>'
            "</svg>")


def spec_file(result: EscherResult) -> dict[str, Any]:
    """The JSON written next to the pictures: the web editor's export form plus the fit."""
    return {"family": "isohedral", "name": result.name, "spec": result.spec(),
            "escherize": {k: v for k, v in result.to_json().items() if k != "spec"}}


def render_options(result: EscherResult) -> list[str]:
    """The ``tilekit render`` arguments that rebuild the tiling (params and edges)."""
    out = [result.name]
    if result.params:
        out.append("--param=" + ",".join(f"{v:.12g}" for v in result.params))
    out += [f"--edge={lab}={text}" for lab, text in result.edges.items()]
    return out


def write_outputs(results: Sequence[EscherResult], goal: np.ndarray, out_dir: str | os.PathLike) -> list[Path]:
    """For each result, ``NN-IHn.isohedral.json`` (spec), ``NN-IHn-tile.svg`` (tile and aligned
    goal) and ``NN-IHn-tiling.svg``; and ``ranking.json``. Returns the files written."""
    return write_ranked(results, out_dir, (".isohedral.json", "-tile.svg"), spec_file, lambda r: outline_svg(r, goal))


def write_ranked(results: Sequence[Any], out_dir: str | os.PathLike, ends: tuple[str, str],
                 spec_of: Callable[[Any], dict[str, Any]], picture: Callable[[Any], str]) -> list[Path]:
    """The ranked results' files: per result ``NN-IHn{ends[0]}`` (its spec file), ``NN-IHn{ends[1]}``
    (its picture) and ``NN-IHn-tiling.svg``, then ``ranking.json``; every path checked first."""
    from tilekit.render import write_svg  # start-up cost: the renderer loads shapely (~0.1 s)

    out = Path(out_dir)
    names = [f"{rank:02d}-{r.name}{end}" for rank, r in enumerate(results, 1) for end in (*ends, "-tiling.svg")]
    for name in [*names, "ranking.json"]:
        check_output(out / name)  # a FIFO among them would block the writer
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ParameterError(f"output directory {str(out)!r} cannot be made: {exc.strerror or exc}") from None
    written = []
    for rank, r in enumerate(results, 1):
        stem = f"{rank:02d}-{r.name}"
        p = out / f"{stem}{ends[0]}"
        p.write_text(json.dumps(spec_of(r), indent=1) + "\n")
        written.append(p)
        p = out / f"{stem}{ends[1]}"
        p.write_text(picture(r))
        written.append(p)
        tiling = r.tiling()
        patch = tiling.patch(tiling.default_region())
        written.append(write_svg(tiling.render_svg(patch), out / f"{stem}-tiling.svg"))
    p = out / "ranking.json"
    p.write_text(json.dumps([dict(rank=i, **r.to_json()) for i, r in enumerate(results, 1)], indent=1) + "\n")
    written.append(p)
    return written
