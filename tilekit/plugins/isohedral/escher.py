"""Escherization (Kaplan and Salesin, SIGGRAPH 2000; Kaplan 2009, §7.3): the isohedral tile
that best resembles a goal polygon, searched over the types, their tiling vertex parameters
and their edge shapes.

The metric, the goal readers and the runners are the core's (:mod:`tilekit.escher`, shared with
the substitution family's Penrose Escherization) and re-exported here.

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
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from tilekit.edgeshapes import EdgeShape
from tilekit.errors import GeometryError, ParameterError, TilekitError
from tilekit.escher import (  # noqa: F401 - the metric's names, re-exported for the dihedral and Heaven-and-Hell fits
    SUBSHIFTS,
    FitSettings,
    GoalBank,
    _complex,
    _distance,
    _samples_matrix,
    align_onto,
    aligned_sources,
    best_valid,
    check_goal,
    check_samples,
    crossings,
    framed_path,
    one_blas_thread,
    overlay_svg,
    piece_system,
    read_goal,
    read_svg_goal,
    resample,
    run_guarded,
    run_jobs,
    shape_distance,
    similarity_residual,
    solve_pieces,
    svg_path_points,
)
from tilekit.files import check_output
from tilekit.plugins.isohedral.engine import HopEngine, IsohedralTiling, shape_classes
from tilekit.plugins.isohedral.escher_limits import (
    DEFAULT_EDGE_POINTS,
    DEFAULT_SAMPLES,
    DEFAULT_STARTS,
    MAX_EDGE_POINTS,
    MAX_STARTS,
    MAX_WORKERS,
)
from tilekit.plugins.isohedral.spec import editor_path
from tilekit.plugins.isohedral.templates import get_template, load_parameterizations

# ------------------------------------------------------------------------ limits

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
class Settings(FitSettings):
    """The search's sizes (samples, starts, edge points), reflection and seed (checked by ``check``)."""

    starts: int = DEFAULT_STARTS
    edge_points: int = DEFAULT_EDGE_POINTS
    max_starts: ClassVar[int] = MAX_STARTS
    max_edge_points: ClassVar[int] = MAX_EDGE_POINTS


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


@dataclass
class GoalFit:
    """What :func:`fit_goal_file` did: the goal's corners, the types tried, the ``best``
    results (ranked), how many types fitted, the types without a valid tiling, the files written."""

    sides: int
    types: list[int]
    best: list[EscherResult]
    fitted: int
    failed: list[tuple[int, str]]
    written: list[Path]


def fit_goal_file(goal_path: str, out_dir: str, types: Sequence[int] | None = None, *, top: int = 5,
                  settings: Settings = Settings(), workers: int = 1) -> GoalFit:
    """``tilekit escherize GOAL``: the goal read from its file (:func:`read_goal`), every type of
    ``types`` (default the 81 unmarked types) fitted (:func:`escherize`), the best ``top``
    written to ``out_dir`` (:func:`write_outputs`); a TilekitError when no type tiles."""
    chosen = list(types) if types is not None else unmarked_types()
    target = read_goal(goal_path)
    results, failed = escherize(target, chosen, settings=settings, workers=workers)
    if not results:
        raise TilekitError(f"no type gave a valid tiling for {goal_path}: "
                           + "; ".join(f"IH{ih}: {why}" for ih, why in failed[:3]))
    best = results[:top]
    return GoalFit(len(target), chosen, best, len(results), failed, write_outputs(best, target, out_dir))


def aligned_goal(result: EscherResult, goal: np.ndarray, samples: int = DEFAULT_SAMPLES) -> np.ndarray:
    """The goal polygon moved by the similarity that best fits it onto the result's tile
    (mirrored first when the fit matched the mirror image), for drawing the two together:
    the metric's alignment, with the goal's starting offset refined continuously."""
    return align_onto(np.asarray(result.tiling().prototile.outline, dtype=float), goal, result.mirrored, samples)


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
