"""Dihedral Escherization (Kaplan and Salesin 2004; Kaplan 2009, §7.3): an isohedral tile
split by a path between two boundary points (:mod:`.split`) whose two pieces resemble two
goal shapes; the objective is the larger of the two Kaplan-Salesin distances.

The search reuses the monohedral fit's pieces (:mod:`.escher`): the type's linear tile model
(:func:`~.escher.type_model`), the goal banks and their FFT alignment, and the projection
idea of Koizumi and Sugihara. For fixed tiling vertex parameters and fixed path ends, both
pieces are linear in the unknowns x = (edge control points, the path's interior points), so
each evaluation alternates (resample both pieces, align each to its goal over all shifts,
one joint linear least squares over x with a translation per piece, each piece's rows
weighted so that its squared residual is its squared distance). Nelder-Mead searches the
parameters and the two ends; end pairs are screened first at the default parameters; a joint
``least_squares`` polish and the engine's checks (with shrinking towards straight) finish.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.edgeshapes import EdgeShape
from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.plugins.isohedral import escher
from tilekit.plugins.isohedral.engine import IsohedralTiling
from tilekit.plugins.isohedral.escher import (
    BACKOFF,
    CROSSING_PENALTY,
    FINAL_STEPS,
    INNER_STEPS,
    POLISH_EVALUATIONS,
    POLISH_RIDGE,
    RIDGES,
    GoalBank,
    TypeModel,
    check_goal,
    resample,
    type_model,
)
from tilekit.plugins.isohedral.escher_limits import (
    DEFAULT_PATH_POINTS,
    DEFAULT_SAMPLES,
    MAX_GOAL_AREA_RATIO,
    MAX_PATH_POINTS,
    MAX_WORKERS,
)
from tilekit.plugins.isohedral.spec import tiling_from_spec
from tilekit.plugins.isohedral.split import (
    SplitTiling,
    apply_rows,
    boundary_position,
    end_row,
    piece_rows,
)
from tilekit.polygon import signed_area

#: The pieces' area ratio may differ from the goals' by this factor before the search is
#: steered back (the goals are drawn at their relative size, like Escher's two figures).
AREA_SLACK = 2.0
#: Weight of that steering (per unit of log ratio beyond the slack).
AREA_PENALTY = 0.2
#: Alternation steps when screening the end pairs (6 ranked the pairs near a known answer
#: below their symmetric images' worse ones on the IH1 test pair; 15 ranked them first).
SCREEN_STEPS = 15
#: Ends closer than this many outline vertices (either way round) make a sliver piece.
MIN_END_GAP = 1.0


def check_goals(goal_a: Any, goal_b: Any) -> tuple[np.ndarray, np.ndarray]:
    """Both goals checked (:func:`~.escher.check_goal`) and of comparable areas: the pieces of
    one tile are matched at the goals' relative size, so a ratio over MAX_GOAL_AREA_RATIO is a
    ParseError."""
    a = check_goal(goal_a, "goal A")
    b = check_goal(goal_b, "goal B")
    ra, rb = signed_area(a), signed_area(b)
    ratio = max(ra, rb) / min(ra, rb)
    if ratio > MAX_GOAL_AREA_RATIO:
        big = "A" if ra > rb else "B"
        raise ParseError(f"goal {big}'s area is {ratio:.3g}x the other's; the two pieces of one tile are matched at "
                         f"the goals' relative size, so give goals within {MAX_GOAL_AREA_RATIO:g}x of each other's area")
    return a, b


def split_distances(tiling: SplitTiling, goal_a: Any, goal_b: Any, samples: int = DEFAULT_SAMPLES,
                    reflection: bool = True) -> tuple[float, float]:
    """The Kaplan-Salesin distance of each piece of a split tiling from its goal (the search
    minimises the larger)."""
    a, b = check_goals(goal_a, goal_b)
    pieces = [np.asarray(p.outline, dtype=float) for p in tiling.prototiles]
    return (escher.shape_distance(pieces[0], a, samples, reflection),
            escher.shape_distance(pieces[1], b, samples, reflection))


@dataclass(frozen=True)
class DihedralSettings(escher.Settings):
    """The monohedral search's settings and the splitting path's interior points."""

    path_points: int = DEFAULT_PATH_POINTS

    def check(self) -> None:
        super().check()
        if not (isinstance(self.path_points, int) and 1 <= self.path_points <= MAX_PATH_POINTS):
            raise ParameterError(f"path points {self.path_points!r} must be an integer from 1 to {MAX_PATH_POINTS}")


# ------------------------------------------------------------------------ the split tile space


@dataclass
class SplitModel:
    """A type's tiles split by a path of ``k`` interior points. The point table (outline
    vertices, then the path's points) is ``F @ x + g`` with x = (control points, path x's,
    path y's); for fixed ends, :func:`~.split.piece_rows` turns it into both pieces."""

    tile: TypeModel
    k: int
    counts: np.ndarray = field(init=False)  # outline segments per tiling edge

    def __post_init__(self) -> None:
        e = len(self.tile.vertices(self.tile.default))
        self.counts = np.bincount(self.tile.edge_of, minlength=e).astype(np.int64)

    @property
    def m(self) -> int:
        return len(self.tile.local0)

    @property
    def nc(self) -> int:
        return len(self.tile.c0)

    def table(self, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        a, b = self.tile.linear(p)
        m, nc, k = self.m, self.nc, self.k
        f = np.zeros((m + k, nc + 2 * k), dtype=complex)
        f[:m, :nc] = a
        f[m:, nc : nc + k] = np.eye(k)
        f[m:, nc + k :] = 1j * np.eye(k)
        return f, np.concatenate([b, np.zeros(k, dtype=complex)])

    def chord(self, f: np.ndarray, g: np.ndarray, u: float, v: float) -> tuple[np.ndarray, np.ndarray]:
        """(C, h): the straight path's interior points as C @ x + h (for the pull towards it)."""
        ends = np.array([end_row(self.m, u), end_row(self.m, v)])
        fu, fv = apply_rows(ends, f)
        gu, gv = apply_rows(ends, g)
        t = (np.arange(1, self.k + 1) / (self.k + 1))[:, None]
        return (1 - t) * fu + t * fv, (1 - t[:, 0]) * gu + t[:, 0] * gv

    def start(self, p: np.ndarray, u: float, v: float) -> np.ndarray:
        """Straight edges and a straight path: x at which the path is the chord."""
        f, g = self.table(p)
        c, h = self.chord(f, g, u, v)
        x = np.concatenate([self.tile.c0, np.zeros(2 * self.k)])
        q = c @ x + h
        x[self.nc : self.nc + self.k], x[self.nc + self.k :] = q.real, q.imag
        return x

    def pieces(self, p: np.ndarray, x: np.ndarray, u: float, v: float) -> list[np.ndarray]:
        f, g = self.table(p)
        z = f @ x + g
        return [apply_rows(r, z) for r in piece_rows(self.m, u, v, self.k)]

    def candidate_ends(self) -> np.ndarray:
        """Corners and edge midpoints (fractional outline indices), the screened end points."""
        first = np.concatenate([[0], np.cumsum(self.counts)[:-1]])
        return np.sort(np.concatenate([first, first + self.counts / 2.0])).astype(float)


def project_split(model: SplitModel, p: np.ndarray, u: float, v: float, banks: Sequence[GoalBank], steps: int,
                  ridge: float = RIDGES[0], x: np.ndarray | None = None) -> tuple[float, list[float], np.ndarray]:
    """Alternate ``steps`` times: resample and align both pieces, then the joint projection
    of x (with one free translation per piece). Returns (max distance, both distances, x)."""
    x = model.start(p, u, v) if x is None else x
    return project_pieces(model, p, piece_rows(model.m, u, v, model.k), banks, steps, ridge, x, (u, v))


def project_pieces(model: SplitModel, p: np.ndarray, rows: Sequence[np.ndarray], banks: Sequence[GoalBank],
                   steps: int, ridge: float, x: np.ndarray, ends: tuple[float, float] | None = None
                   ) -> tuple[float, list[float], np.ndarray]:
    """The alternation of :func:`project_split` for any outlines given as rows over the point
    table (each matched to its goal bank): the split's two pieces, or (Heaven and Hell) the
    whole tile twice. With ``ends``, the path is pulled towards its chord."""
    f, g = model.table(p)
    fr = [apply_rows(r, f) for r in rows]
    gr = [apply_rows(r, g) for r in rows]
    x = x.copy()
    nx, nc, k = len(x), model.nc, model.k
    pull_rows = pull_rhs = None
    if ends is not None and k:
        # the pull of the path towards its chord: q - (C x + h), as rows R x - h
        cm, ch = model.chord(f, g, *ends)
        sel = np.zeros((k, nx), dtype=complex)
        sel[:, nc : nc + k] = np.eye(k)
        sel[:, nc + k :] = 1j * np.eye(k)
        pull = sel - cm
        pull_rows = np.vstack([pull.real, pull.imag])
        pull_rhs = np.concatenate([ch.real, ch.imag])
    verts = model.tile.vertices(p)
    scale2 = float(np.mean(np.abs(np.roll(verts, -1) - verts) ** 2))
    ds = [1.0, 1.0]
    for step in range(steps + 1):
        systems = [escher.piece_system(fr[i], gr[i], x, banks[i]) for i in range(len(rows))]
        ds = [s[0] for s in systems]
        if step == steps or any(s[1] is None for s in systems):
            break
        extra = None
        if pull_rows is not None:
            rq = ridge / scale2
            extra = (rq * (pull_rows.T @ pull_rows), rq * (pull_rows.T @ pull_rhs))
        x = escher.solve_pieces(systems, nx, nc, ridge, model.tile.c0, extra)
    return max(ds), ds, x


# ------------------------------------------------------------------------ fitting one type


@dataclass
class DihedralResult(escher.TypeFit):
    """The best split tile of one type for a pair of goals."""

    ih: int
    distance: float  # the larger of the two pieces' distances
    distances: tuple[float, float]
    params: list[float]
    edges: dict[str, str]
    ends: tuple[float, float]  # boundary positions (edge + fraction) of the path's ends
    path: str  # EdgeShape text in the chord frame
    evaluations: int = 0
    seconds: float = 0.0
    shrink: float = 1.0
    fitted_distance: float = 0.0
    mirrored: tuple[bool, bool] = (False, False)
    note: str = ""
    area_ratio: float = 1.0  # piece 0's area over piece 1's (the goals' is matched within AREA_SLACK)

    def spec(self) -> dict[str, Any]:
        """The isohedral family's spec with its ``split`` table (``tiling_from_spec`` reads it)."""
        out = self.base_spec()
        out["split"] = {"ends": list(self.ends), "path": self.path}
        return out

    def tiling(self) -> SplitTiling:
        return tiling_from_spec(self.spec())  # type: ignore[return-value]

    def to_json(self) -> dict[str, Any]:
        return {"ih": self.ih, "name": self.name, "distance": self.distance, "distances": list(self.distances),
                "fitted_distance": self.fitted_distance, "shrink": self.shrink, "mirrored": list(self.mirrored),
                "area_ratio": self.area_ratio, "spec": self.spec(), "evaluations": self.evaluations,
                "seconds": self.seconds, "note": self.note}


def _wrap(model: SplitModel, u: float, v: float) -> tuple[float, float, float]:
    """Ends modulo the outline and the violation of the minimum gap between them (0 if none)."""
    m = model.m
    u, v = u % m, v % m
    gap = min((v - u) % m, (u - v) % m)
    return u, v, max(0.0, MIN_END_GAP - gap)


def _area_excess(pieces: Sequence[np.ndarray], log_goal_ratio: float) -> float:
    """How far (in log ratio) the pieces' area ratio strays beyond AREA_SLACK from the goals'
    (complex outlines; a piece without positive area: 10)."""
    a0 = 0.5 * float(np.sum((np.conj(pieces[0]) * np.roll(pieces[0], -1)).imag))
    a1 = 0.5 * float(np.sum((np.conj(pieces[1]) * np.roll(pieces[1], -1)).imag))
    if a0 <= 0 or a1 <= 0:
        return 10.0
    return max(0.0, abs(math.log(a0 / a1) - log_goal_ratio) - math.log(AREA_SLACK))


def _area_penalty(pieces: list[np.ndarray], log_goal_ratio: float) -> float:
    return AREA_PENALTY * _area_excess(pieces, log_goal_ratio)


def _bad_pieces(pieces: list[np.ndarray], outline: np.ndarray) -> int:
    """1 if the tile's outline or a piece crosses itself, or a piece is inside out, else 0."""
    if escher.crossings(outline):
        return 1
    for q in pieces:
        if escher.crossings(q) or 0.5 * float(np.sum((np.conj(q) * np.roll(q, -1)).imag)) <= 0:
            return 1
    return 0


@escher.one_blas_thread
def escherize_dihedral_type(goal_a: Any, goal_b: Any, ih: int,
                            settings: DihedralSettings = DihedralSettings()) -> DihedralResult:
    """The split tile of type ``ih`` whose pieces best resemble ``goal_a`` and ``goal_b``:
    end pairs screened, Nelder-Mead over (parameters, ends) with the projection inside, a
    joint least-squares polish, then the engine's checks (:class:`~.split.SplitTiling`)."""
    from scipy.optimize import minimize  # start-up cost: scipy (~0.3 s), only for a search

    settings.check()
    t0 = time.perf_counter()
    goals = check_goals(goal_a, goal_b)
    model = SplitModel(type_model(ih, settings.edge_points), settings.path_points)
    banks = [GoalBank.build(g, settings.samples, settings.reflection) for g in goals]
    log_ratio = math.log(signed_area(goals[0]) / signed_area(goals[1]))
    npar = model.tile.n_params
    evaluations = 0

    def f(y: np.ndarray, ridge: float, steps: int = INNER_STEPS) -> float:
        nonlocal evaluations
        evaluations += 1
        p = y[:npar]
        bad = model.tile.polygon_ok(p)
        if bad:
            return 1.0 + bad
        u, v, short = _wrap(model, y[npar], y[npar + 1])
        if short:
            return 1.0 + short
        d, _, x = project_split(model, p, u, v, banks, steps, ridge)
        pieces = model.pieces(p, x, u, v)
        outline = model.tile.outline(p, x[: model.nc])
        return d + CROSSING_PENALTY * _bad_pieces(pieces, outline) + _area_penalty(pieces, log_ratio)

    # screen every ordered pair of candidate ends (corners, edge midpoints) at the default
    # parameters; the best pairs start the searches
    cands = model.candidate_ends()
    pairs = [(a, b) for a in cands for b in cands if min((b - a) % model.m, (a - b) % model.m) >= MIN_END_GAP]
    p0 = model.tile.default
    scored = sorted((f(np.concatenate([p0, [a, b]]), RIDGES[0], SCREEN_STEPS), i) for i, (a, b) in enumerate(pairs))
    # a symmetric default tile scores its symmetric images of a pair alike: keep one of each
    distinct = [scored[0]]
    for sc in scored[1:]:
        if sc[0] - distinct[-1][0] > 1e-9:
            distinct.append(sc)
    scored = distinct
    rng = np.random.default_rng([settings.seed, ih, 2])
    spread = 0.25 * max(1.0, float(np.max(np.abs(p0)))) if npar else 0.0
    best_y, best_f, best_ridge = np.concatenate([p0, pairs[scored[0][1]]]), math.inf, RIDGES[0]
    for i in range(settings.starts):
        a, b = pairs[scored[i % len(scored)][1]]
        p = p0 + (spread * rng.standard_normal(npar) if i >= len(scored) else 0.0)
        ridge = RIDGES[i % len(RIDGES)]
        y0 = np.concatenate([p, [a, b]])
        simplex = np.vstack([y0] + [y0 + np.eye(len(y0))[j] * (0.1 * max(spread, 0.4) if j < npar else 0.5)
                                    for j in range(len(y0))])
        res = minimize(f, y0, args=(ridge,), method="Nelder-Mead",
                       options={"maxfev": 40 * (len(y0) + 1), "xatol": 1e-4, "fatol": 1e-7,
                                "initial_simplex": simplex})
        if float(res.fun) < best_f:
            best_y, best_f, best_ridge = np.asarray(res.x, dtype=float), float(res.fun), ridge
    p = best_y[:npar]
    u, v, _ = _wrap(model, best_y[npar], best_y[npar + 1])
    _, _, x_short = project_split(model, p, u, v, banks, INNER_STEPS, best_ridge)
    _, _, x_long = project_split(model, p, u, v, banks, FINAL_STEPS, best_ridge)
    candidates: list[tuple[np.ndarray, np.ndarray, float, float]] = [(p, x_long, u, v), (p, x_short, u, v)]
    polished = _polish(model, p, x_long, u, v, goals, banks)
    if polished is not None:
        candidates.insert(0, polished[:4])
        evaluations += polished[4]
    # candidates scored as the search scores them: distance plus the area steering
    result = escher.best_valid(candidates, lambda *c: _valid_result(model, *c, goals, settings), f"IH{ih} split",
                               lambda r: r.distance + AREA_PENALTY * max(
                                   0.0, abs(math.log(r.area_ratio) - log_ratio) - math.log(AREA_SLACK)))
    result.evaluations = evaluations
    result.seconds = time.perf_counter() - t0
    return result


def _polish(model: SplitModel, p: np.ndarray, x: np.ndarray, u: float, v: float, goals: Sequence[np.ndarray],
            banks: Sequence[GoalBank], max_nfev: int = POLISH_EVALUATIONS
            ) -> tuple[np.ndarray, np.ndarray, float, float, int] | None:
    """Joint refinement of everything (parameters, x, both ends and both goals' continuous
    starting offsets) by scipy's least_squares on the two pieces' stacked residual vectors
    (each the metric's, so its norm is that piece's distance). None if it does not improve."""
    from scipy.optimize import least_squares  # start-up cost: scipy (~0.3 s), only for a search

    n = banks[0].samples
    npar, nx = len(p), len(x)
    srcs, bases, d0 = escher.aligned_sources(model.pieces(p, x, u, v), goals, banks)
    ridge = math.sqrt(POLISH_RIDGE)
    c0 = model.tile.c0
    log_ratio = math.log(signed_area(goals[0]) / signed_area(goals[1]))

    def resid(z: np.ndarray) -> np.ndarray:
        uu, vv, short = _wrap(model, z[npar + nx], z[npar + nx + 1])
        out = []
        pieces = model.pieces(z[:npar], z[npar : npar + nx], uu, vv)
        # the pieces' relative size, as in the search (a hinge: zero within AREA_SLACK)
        out.append([AREA_PENALTY * _area_excess(pieces, log_ratio)])
        for i, piece in enumerate(pieces):
            r = escher.similarity_residual(resample(piece, n), resample(srcs[i], n, bases[i] + z[-2 + i]))
            out += [r.real, r.imag]
        out.append(ridge * (z[npar : npar + model.nc] - c0))
        out.append([10.0 * short])
        return np.concatenate(out)

    z0 = np.concatenate([p, x, [u, v, 0.0, 0.0]])
    try:
        res = least_squares(resid, z0, method="trf", max_nfev=max_nfev, x_scale=0.1)
    except ValueError:  # a non-finite residual (a degenerate piece) at a trial point
        return None
    z = res.x
    if not np.all(np.isfinite(z)) or model.tile.polygon_ok(z[:npar]):
        return None
    r = res.fun[1:]
    d = max(math.sqrt(float(np.sum(r[: 2 * n] ** 2))), math.sqrt(float(np.sum(r[2 * n : 4 * n] ** 2))))
    if d >= d0:
        return None
    uu, vv, _ = _wrap(model, z[npar + nx], z[npar + nx + 1])
    return z[:npar], z[npar : npar + nx], uu, vv, int(res.nfev)


def _valid_result(model: SplitModel, p: np.ndarray, x: np.ndarray, u: float, v: float,
                  goals: Sequence[np.ndarray], settings: DihedralSettings) -> DihedralResult:
    """Shrink the edge shapes towards straight and the path towards its chord until the engine
    accepts the tile and the split; report the distances of the accepted pieces."""
    note = ""
    nc, k = model.nc, model.k
    f, g = model.table(p)
    for alpha in BACKOFF:
        c = model.tile.c0 + alpha * (x[:nc] - model.tile.c0)
        xs = np.concatenate([c, x[nc:]])
        cm, ch = model.chord(f, g, u, v)
        straight = cm @ xs + ch
        q = x[nc : nc + k] + 1j * x[nc + k :]
        q = straight + alpha * (q - straight)
        ends = apply_rows(np.array([end_row(model.m, u), end_row(model.m, v)]), f @ xs + g)
        chord = ends[1] - ends[0]
        if abs(chord) <= 0:
            note = "the path's ends coincide"
            continue
        local = (q - ends[0]) / chord
        try:
            base = IsohedralTiling(model.tile.ih, [float(t) for t in p], model.tile.shapes(c), check=True)
            counts = np.array([len(e) - 1 for e in base.edge_paths], dtype=np.int64)
            s, t = boundary_position(counts, u), boundary_position(counts, v)
            path = EdgeShape(np.vstack([[0.0, 0.0], np.column_stack([local.real, local.imag]), [1.0, 0.0]]))
            tiling = SplitTiling(base, s, t, path)
        except (ParameterError, GeometryError) as exc:
            note = str(exc)
            continue
        ds, mirrored = [], []
        for proto, goal in zip(tiling.prototiles, goals):
            d, info = escher._distance(escher._complex(np.asarray(proto.outline)), goal, settings.samples,
                                       settings.reflection, refine=True)
            ds.append(d)
            mirrored.append(bool(info["mirrored"]))
        fitted = max(ds) if alpha == 1.0 else max(
            escher._distance(piece, goal, settings.samples, settings.reflection, refine=True)[0]
            for piece, goal in zip(model.pieces(p, x, u, v), goals))
        edges = {lab: sh.to_text() for lab, sh in base.edge_shapes.items()}
        areas = [p.area for p in tiling.prototiles]
        return DihedralResult(model.tile.ih, max(ds), (ds[0], ds[1]), [float(t) for t in p], edges, (s, t),
                              path.to_text(), shrink=alpha, fitted_distance=fitted, mirrored=(mirrored[0], mirrored[1]),
                              note="" if alpha == 1.0 else f"shapes shrunk to {alpha:g}: {note}",
                              area_ratio=areas[0] / areas[1])
    raise GeometryError(f"IH{model.tile.ih}: no valid split tiling found near the fit ({note})")


# ------------------------------------------------------------------------ all types


def escherize_dihedral(goal_a: Any, goal_b: Any, types: Iterable[int] | None = None, *,
                       settings: DihedralSettings = DihedralSettings(), workers: int = 1,
                       progress: Callable[[DihedralResult | tuple[int, str]], None] | None = None
                       ) -> tuple[list[DihedralResult], list[tuple[int, str]]]:
    """Fit every type in ``types`` (default: the 81 unmarked types) to the goal pair; the
    results sorted by distance (the larger of the two) and the types without a valid tiling."""
    settings.check()
    a, b = check_goals(goal_a, goal_b)
    todo = list(types) if types is not None else escher.unmarked_types()
    for ih in todo:
        if escher.get_template(ih).marked:
            raise ParameterError(f"IH{ih} is a marked type; escherization takes the 81 unmarked types")
    if not (isinstance(workers, int) and 1 <= workers <= MAX_WORKERS):
        raise ParameterError(f"workers {workers!r} must be an integer from 1 to {MAX_WORKERS}")
    outs = escher.run_jobs(escher.run_guarded, [(escherize_dihedral_type, ih, (a, b, ih, settings)) for ih in todo],
                           workers, progress)
    good = sorted((o for o in outs if isinstance(o, DihedralResult)), key=lambda r: (r.distance, r.ih))
    failed = [o for o in outs if not isinstance(o, DihedralResult)]
    return good, failed


# ------------------------------------------------------------------------ output


def pieces_svg(result: DihedralResult, goals: Sequence[np.ndarray], size: int = 400) -> str:
    """SVG of the split tile (piece 0 and piece 1 filled) with each goal aligned onto its
    piece (dashed)."""
    pieces = [np.asarray(p.outline, dtype=float) for p in result.tiling().prototiles]
    title = (f"{result.name} split  d = {result.distance:.4f} (A {result.distances[0]:.4f}, "
             f"B {result.distances[1]:.4f})")
    return escher.overlay_svg(title, pieces, [escher.align_onto(pc, g, mir) for pc, g, mir in zip(pieces, goals, result.mirrored)],
                       size)


def spec_file(result: Any) -> dict[str, Any]:
    """The JSON written next to the pictures: the family's export form plus the fit."""
    kind = "split" if isinstance(result, DihedralResult) else "heaven and hell"
    return {"family": "isohedral", "name": f"{result.name} {kind}", "spec": result.spec(),
            "escherize": {k: v for k, v in result.to_json().items() if k != "spec"}}


def write_outputs(results: Sequence[Any], goals: Sequence[np.ndarray], out_dir: str | Path) -> list[Path]:
    """For each result ``NN-IHn-split.isohedral.json`` (the spec, reopened by ``tilekit render
    --system``), ``NN-IHn-pieces.svg`` (the pieces, goals aligned) and ``NN-IHn-tiling.svg``;
    and ``ranking.json``. Heaven-and-Hell results (:mod:`.heaven`) are written the same way
    as ``NN-IHn-hh.isohedral.json`` and ``NN-IHn-tile.svg`` (the tile with both goals).
    Returns the files written."""
    if all(isinstance(r, DihedralResult) for r in results):
        return escher.write_ranked(results, out_dir, ("-split.isohedral.json", "-pieces.svg"), spec_file,
                                   lambda r: pieces_svg(r, goals))
    return escher.write_ranked(results, out_dir, ("-hh.isohedral.json", "-tile.svg"), spec_file,
                               lambda r: r.tile_svg(goals))
