"""The Escherization metric and what every Escherization fit shares (Kaplan and Salesin,
SIGGRAPH 2000; Kaplan 2009, §7.3), for any family that fits tiles to goal shapes.

Goals: a simple polygon read from an SVG (one path, polygon or polyline) or a JSON point list,
checked (:func:`check_goal`, :func:`read_goal`). The metric: both outlines are resampled to
``samples`` points by arc length and aligned by the best similarity (a complex least-squares
fit, the 2D Procrustes problem) over every cyclic shift of the starting point, found for all
shifts at once by one FFT cross-correlation (:class:`GoalBank`); with ``reflection`` the
mirrored goal is tried too. The distance is ``sqrt(residual / sum |g - mean g|^2)``, the RMS
gap relative to the goal's RMS radius: 0 for similar shapes, at most 1
(:func:`shape_distance`; :func:`similarity_residual` is its residual vector for
least-squares polishing). The runners: :func:`run_guarded` / :func:`run_jobs` (one fit per
job, serially or in a process pool; a fit with no valid tiling is reported, not raised),
:func:`one_blas_thread`, :func:`best_valid`. Pictures: :func:`align_onto` (a goal drawn on
a fitted outline) and :func:`framed_path`.

The isohedral family (monohedral, dihedral and Heaven-and-Hell fits) and the substitution
family (Penrose Escherization over the quasivertex parameters) both use this one copy.
"""

from __future__ import annotations

import functools
import math
import os
import re
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.files import read_text
from tilekit.limits import (
    DEFAULT_SAMPLES,
    MAX_COORDINATE,
    MAX_GOAL_BYTES,
    MAX_GOAL_POINTS,
    MAX_SAMPLES,
    MIN_SAMPLES,
)
from tilekit.polygon import signed_area
from tilekit.schema import parse_json

#: Sub-sample offsets of the goal tried with every cyclic shift (alignment resolution).
SUBSHIFTS = 4


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


def similarity_residual(z: np.ndarray, w: np.ndarray) -> np.ndarray:
    """``(a z - w) / |w|`` for the complex samples ``z`` (the tile) and ``w`` (the goal), both
    centred first, with the best complex scale-rotation ``a``: the least-squares residual whose
    squared norm is the Procrustes distance the fits minimise."""
    zc = z - z.mean()
    wc = w - w.mean()
    zn = np.vdot(zc, zc).real
    a = np.vdot(zc, wc) / zn if zn > 0 else 0j
    return (a * zc - wc) / math.sqrt(np.vdot(wc, wc).real)


def run_guarded(job: tuple[Callable[..., Any], Any, tuple[Any, ...]]) -> Any:
    """One fit ``fit(*args)`` from a ``(fit, key, args)`` job, or ``(key, reason)`` when the
    fit finds no valid tile near the goal(s) (the job form :func:`run_jobs` takes for the
    isohedral monohedral, dihedral and Heaven-and-Hell searches and the Penrose fit alike)."""
    fit, ih, args = job
    try:
        return fit(*args)
    except (ParameterError, GeometryError) as exc:
        return ih, str(exc)


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





@dataclass(frozen=True)
class FitSettings:
    """A fit's sizes (samples, starts, edge points), reflection and seed; a family sets the
    defaults and the bounds ``max_starts`` / ``max_edge_points`` (checked by ``check``)."""

    samples: int = DEFAULT_SAMPLES
    starts: int = 4
    edge_points: int = 4
    reflection: bool = True
    seed: int = 0
    max_starts: ClassVar[int] = 64
    max_edge_points: ClassVar[int] = 24

    def check(self) -> None:
        check_samples(self.samples)
        if not (isinstance(self.starts, int) and 1 <= self.starts <= self.max_starts):
            raise ParameterError(f"starts {self.starts!r} must be an integer from 1 to {self.max_starts}")
        if not (isinstance(self.edge_points, int) and 1 <= self.edge_points <= self.max_edge_points):
            raise ParameterError(f"edge points {self.edge_points!r} must be an integer from 1 to {self.max_edge_points}")


# ------------------------------------------------------------------------ linear projection


def piece_system(z_rows: np.ndarray, g_rows: np.ndarray, x: np.ndarray, bank: GoalBank
                 ) -> tuple[float, np.ndarray | None, np.ndarray | None, float]:
    """One outline ``z_rows @ x + g_rows`` (complex, affine in the real unknowns x) aligned to
    its goal bank, and its least-squares rows over x weighted so the squared residual is the
    squared distance: (distance, rows (2n, nx), right-hand side (2n,), weight)."""
    n = bank.samples
    z = z_rows @ x + g_rows
    q, q1, f = _samples_matrix(z, n)
    zs = (1 - f) * z[q] + f * z[q1]
    d, row, shift, a = bank.align(zs)
    if a == 0:
        return d, None, None, 0.0
    wgt = abs(a) / math.sqrt(float(bank.norms[row]))
    target = np.roll(bank.rows[row], -shift) / a
    ws = (1 - f)[:, None] * z_rows[q] + f[:, None] * z_rows[q1]
    bs = (1 - f) * g_rows[q] + f * g_rows[q1]
    return d, wgt * np.vstack([ws.real, ws.imag]), wgt * np.concatenate([(target - bs).real, (target - bs).imag]), wgt


def solve_pieces(systems: Sequence[tuple[float, np.ndarray, np.ndarray, float]], nx: int, nc: int, ridge: float,
                 c0: np.ndarray, extra: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """The projection step of Koizumi and Sugihara's linearity for several outlines at once:
    the x minimising the sum of the outlines' weighted squared residuals (:func:`piece_system`,
    one free translation per outline), plus ``ridge |x[:nc] - c0|^2`` and an optional extra
    quadratic ``(lhs, rhs)`` over x, by the normal equations (nx + 2 per outline unknowns)."""
    n2 = systems[0][1].shape[0]
    half = n2 // 2
    big = np.zeros((len(systems) * n2, nx + 2 * len(systems)))
    for i, sysm in enumerate(systems):  # one translation (tx, ty) per outline, weighted as its rows
        big[i * n2 : (i + 1) * n2, :nx] = sysm[1]
        big[i * n2 : i * n2 + half, nx + 2 * i] = -sysm[3]
        big[i * n2 + half : (i + 1) * n2, nx + 2 * i + 1] = -sysm[3]
    rhs_vec = np.concatenate([sysm[2] for sysm in systems])
    lhs = big.T @ big
    rhs = big.T @ rhs_vec
    lhs[:nc, :nc] += ridge * np.eye(nc)
    rhs[:nc] += ridge * c0
    if extra is not None:
        lhs[:nx, :nx] += extra[0]
        rhs[:nx] += extra[1]
    return np.linalg.solve(lhs, rhs)[:nx]


def aligned_sources(outlines: Sequence[np.ndarray], goals: Sequence[np.ndarray], banks: Sequence[GoalBank]
                    ) -> tuple[list[np.ndarray], list[float], float]:
    """For a least-squares polish with continuous starting offsets: each goal as matched to its
    outline (complex vertices, mirrored and walked backwards when the bank's best row is the
    mirror image), the sample offset of the best alignment, and the largest distance."""
    srcs, bases, worst = [], [], 0.0
    for outline, goal, bank in zip(outlines, goals, banks):
        d, row, shift, _ = bank.align(resample(outline, bank.samples))
        worst = max(worst, d)
        g = _complex(goal)
        srcs.append(np.conj(g)[::-1] if bank.mirrored[row] else g)
        bases.append(float(bank.offsets[row]) + shift)
    return srcs, bases, worst


def overlay_svg(title: str, shapes: Sequence[np.ndarray], goals: Sequence[np.ndarray], size: int = 400) -> str:
    """SVG of filled shapes (first light, second dark) and aligned goals (dashed, red then
    blue) in one frame, with a title."""
    path = framed_path([*shapes, *goals], size)

    fills, strokes = ("#f4c27a", "#7fb0d6"), ("#c0392b", "#1f4e79")
    body = "".join(f'<path d="{path(q)}" fill="{fills[i % 2]}" fill-opacity="0.85" stroke="#222" stroke-width="1.5"/>'
                   for i, q in enumerate(shapes))
    body += "".join(f'<path d="{path(q)}" fill="none" stroke="{strokes[i % 2]}" stroke-width="1.5" '
                    'stroke-dasharray="5,3"/>' for i, q in enumerate(goals))
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" viewBox="0 0 {size} {size}">'
            f'<rect width="{size}" height="{size}" fill="white"/>{body}'
            f'<text x="8" y="18" font-family="sans-serif" font-size="13">{title}</text></svg>')
