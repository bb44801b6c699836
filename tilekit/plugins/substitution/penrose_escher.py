"""Penrose Escherization (Kaplan 2009, §7.3: "Escher-like tilings based on the shape
parameterizations of the Penrose tilings in Section 6.3"): the P3 rhombs deformed by the
quasivertex parameters r1, theta1, r2, theta2 (Figure 6.13), or P2's kite and dart by theirs
(derived in :mod:`.quasivertex_p2`), and by Figure 6.14's interlocking edge shapes, fitted to
one goal (both tiles compared with it) or to two (the thick rhomb or the kite with the first,
the thin rhomb or the dart with the second); the objective is the larger of the two distances
of the core's Escherization metric (:mod:`tilekit.escher`), as in dihedral Escherization.
What follows says "rhombs"; P2's tiles go through the same steps.

The tile space. For fixed quasivertex parameters q, the two rhombs' quasivertices are fixed
points (:func:`~.quasivertex.book_outlines`) and every edge between consecutive quasivertices
carries the shape of its label: a polyline of ``edge_points`` interior points on a label of
the pairs' primary side (a, b, c, f), its complement on the partner (g, e, d, h). Each
outline is therefore affine in the shapes' control coordinates x (:class:`PenroseModel`), the
linearity the isohedral fit uses (Koizumi and Sugihara 2011): each evaluation of q alternates
resampling, alignment over all shifts and one joint least-squares projection of x for both
rhombs (:func:`tilekit.escher.piece_system` / :func:`~tilekit.escher.solve_pieces`), and only
the four numbers q are left to Nelder-Mead, from several starts. A joint least-squares polish
of q, x and the goals' continuous starting offsets follows; then the deformed rhombs are
built by the family (:func:`~.quasivertex.deformed_tiles`: simple outlines), a patch is
generated and checked (``Patch.validate``: no gap, no overlap) together with the matching
rules (:func:`~.quasivertex.matching_report`: every shared edge pairs a label with its
partner and the two tiles' drawn edges coincide); a fit that fails is shrunk towards
straight edges until it passes.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from tilekit import escher
from tilekit.errors import GeometryError, ParameterError
from tilekit.plugins.substitution import quasivertex as qv
from tilekit.plugins.substitution import tiling as substitution_tiling
from tilekit.plugins.substitution.penrose_limits import (
    DEFAULT_EDGE_POINTS,
    DEFAULT_STARTS,
    MAX_EDGE_POINTS,
    MAX_STARTS,
    POLISH_EVALUATIONS,
    POLISH_ROUNDS,
    START_EVALUATIONS,
)

#: The tilings with a quasivertex parameterization (P3: Figure 6.13; P2: derived in
#: quasivertex_p2.py).
SYSTEMS = qv.BY_TILING
TILINGS = tuple(SYSTEMS)
#: The goal each tile is compared with, in order (goal A: thick / kite, goal B: thin / dart).
GOAL_TILES = {"penrose-p3": ("thick", "thin"), "penrose-p2": ("kite", "dart")}
TILES = GOAL_TILES["penrose-p3"]
#: Alternations (resample, align, project) per evaluation of q, and before the polish.
INNER_STEPS = 6
FINAL_STEPS = 30
#: Ridge pull of the control points towards straight edges, one per start in turn.
RIDGES = (1e-4, 1e-6)
#: The least-squares polish's pull towards straight edges (tiny: a larger pull biased exact
#: recoveries to ~2e-6).
POLISH_RIDGE = 1e-14
#: Added to the objective when a projected rhomb's outline touches or crosses itself.
CROSSING_PENALTY = 0.05
#: Factors the fitted edge shapes are shrunk by until the patch is a tiling.
BACKOFF = (1.0, 0.9, 0.8, 0.65, 0.5, 0.35, 0.2, 0.1, 0.0)
#: The region (edge length 1) whose patch is validated, and that the picture shows.
CHECK_REGION = (-4.0, -4.0, 4.0, 4.0)
#: Initial Nelder-Mead simplex steps of (r1, theta1, r2, theta2), theta in radians.
SIMPLEX_STEPS = np.array([0.08, 0.3, 0.08, 0.3])


def check_tiling(name: str) -> str:
    """The system of ``--tiling NAME``, or a one-line ParameterError naming the valid ones."""
    key = str(name).lower()
    if key not in SYSTEMS:
        raise ParameterError(
            f"--tiling {name!r} is not a Penrose tiling with quasivertex parameters; valid: {', '.join(TILINGS)}"
        )
    return SYSTEMS[key]


def _params(qvec: np.ndarray) -> qv.QuasivertexParams:
    """(r1, theta1 rad, r2, theta2 rad) -> the family's parameters (degrees), r >= 0 and theta
    in (-180, 180] (a negative r is the same point as -r turned by a half turn)."""
    r1, t1, r2, t2 = (float(v) for v in qvec)
    out = []
    for r, t in ((r1, t1), (r2, t2)):
        deg = math.degrees(t) + (180.0 if r < 0 else 0.0)
        deg = -((-deg + 180.0) % 360.0 - 180.0)
        out += [abs(r), deg]
    return qv.QuasivertexParams(out[0], out[1], out[2], out[3])


@dataclass
class PenroseModel:
    """Both tiles (goal A's first) as functions of q (four numbers) and x (the control
    coordinates of the primary labels' shapes, ``edge_points`` (x, y) pairs each): each
    outline is ``Z(q) @ x + g(q)`` (complex), vertices in the system's frame."""

    edge_points: int
    system: str = "penrose-p3"
    rows: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]] = field(init=False)
    c0: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        k = self.edge_points
        spec = qv.SPECS[self.system]
        self.tiles = GOAL_TILES[self.system]
        xs = np.arange(1, k + 1) / (k + 1)
        self.c0 = np.tile(np.column_stack([xs, np.zeros(k)]).ravel(), len(spec.primary))
        self.rows = {}
        for name in self.tiles:
            labels = spec.labels[name]
            edge, col, sign = [], [], []
            for i, lab in enumerate(labels):
                edge.append(i)
                col.append(0)
                sign.append(0)
                primary = lab in spec.primary
                j = spec.primary.index(lab if primary else spec.partner[lab])
                for p in range(k):
                    edge.append(i)
                    # a partner edge runs the complement: point p is 1 - s[k - 1 - p]
                    col.append(2 * k * j + 2 * (p if primary else k - 1 - p))
                    sign.append(1 if primary else -1)
            self.rows[name] = (np.array(edge), np.array(col), np.array(sign))

    @property
    def nx(self) -> int:
        return len(self.c0)

    def corners(self, qvec: np.ndarray) -> dict[str, np.ndarray]:
        """The quasivertices of both tiles (complex, unmerged: 12 and 10 points for P3, 10 and 10 for P2)."""
        out = qv.system_outlines(_params(qvec), self.system)
        return {name: escher._complex(out[name][0]) for name in self.tiles}

    def bad(self, qvec: np.ndarray) -> bool:
        """Whether a tile's quasivertex outline is not simple at q."""
        return bool(qv._bad_tiles(_params(qvec), self.system))

    def linear(self, qvec: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        """[(Z, g)] for goal A's tile and goal B's at q."""
        corners = self.corners(qvec)
        out = []
        for name in self.tiles:
            pts = corners[name]
            d = np.roll(pts, -1) - pts
            edge, col, sign = self.rows[name]
            z = np.zeros((len(edge), self.nx), dtype=complex)
            shaped = np.flatnonzero(sign)
            de = d[edge[shaped]] * sign[shaped]
            z[shaped, col[shaped]] = de
            z[shaped, col[shaped] + 1] = 1j * de
            g = pts[edge] + np.where(sign < 0, d[edge], 0.0)
            out.append((z, g))
        return out

    def outlines(self, qvec: np.ndarray, x: np.ndarray) -> list[np.ndarray]:
        return [z @ x + g for z, g in self.linear(qvec)]

    def shapes(self, x: np.ndarray) -> dict[str, np.ndarray]:
        """The primary labels' interior points ((k, 2) each), as quasivertex.deformed_tiles takes them."""
        k = self.edge_points
        return {lab: np.asarray(x[2 * k * j : 2 * k * (j + 1)], dtype=float).reshape(k, 2)
                for j, lab in enumerate(qv.SPECS[self.system].primary)}


def project(model: PenroseModel, qvec: np.ndarray, banks: Sequence[escher.GoalBank], steps: int, ridge: float,
            x: np.ndarray) -> tuple[float, list[float], np.ndarray]:
    """Alternate ``steps`` times: resample and align both rhombs to their goal banks, then the
    joint projection of x. Returns (larger distance, both distances, x)."""
    rows = model.linear(qvec)
    x = x.copy()
    ds = [1.0, 1.0]
    for step in range(steps + 1):
        systems = [escher.piece_system(z, g, x, bank) for (z, g), bank in zip(rows, banks)]
        ds = [s[0] for s in systems]
        if step == steps or any(s[1] is None for s in systems):
            break
        x = escher.solve_pieces(systems, model.nx, model.nx, ridge, model.c0)
    return max(ds), ds, x


@dataclass(frozen=True)
class PenroseSettings(escher.FitSettings):
    """Sizes of the search (samples, starts, edge points of each of a, b, c, f), reflection and seed."""

    starts: int = DEFAULT_STARTS
    edge_points: int = DEFAULT_EDGE_POINTS
    max_starts: ClassVar[int] = MAX_STARTS
    max_edge_points: ClassVar[int] = MAX_EDGE_POINTS


@dataclass
class PenroseResult:
    """A fitted pair of deformed P3 rhombs: the quasivertex parameters (degrees), the edge
    shapes of the primary labels, the larger distance and each rhomb's."""

    system: str
    params: dict[str, float]
    edges: dict[str, str]  # label -> "x,y:x,y" interior points (substitution --edge syntax)
    distance: float
    distances: list[float]  # goal A's tile (thick / kite), goal B's (thin / dart)
    mirrored: list[bool]
    evaluations: int = 0
    seconds: float = 0.0
    shrink: float = 1.0
    fitted_distance: float = 0.0
    note: str = ""
    goals: int = 1

    def tiling(self) -> Any:
        """The substitution family's tiling with these rhombs (``SubstitutionTiling``)."""
        return substitution_tiling(self.system).configure(**self.params, edges=[f"{k}={v}" for k, v in self.edges.items()])

    def spec(self) -> dict[str, Any]:
        return self.tiling().spec()

    def render_options(self) -> list[str]:
        """``tilekit render`` arguments that draw this tiling."""
        out = [self.system]
        out += [f"--set={k}={v:.12g}" for k, v in self.params.items()]
        out += [f"--edge={k}={v}" for k, v in self.edges.items()]
        return out

    def to_json(self) -> dict[str, Any]:
        return {"system": self.system, "distance": self.distance, "distances": self.distances,
                "fitted_distance": self.fitted_distance, "shrink": self.shrink, "mirrored": self.mirrored,
                "params": self.params, "edges": self.edges, "spec": self.spec(), "evaluations": self.evaluations,
                "seconds": self.seconds, "note": self.note}


def _shape_text(pts: np.ndarray) -> str:
    return ":".join(f"{x:.12g},{y:.12g}" for x, y in np.asarray(pts, dtype=float))


def _starts(settings: PenroseSettings, model: PenroseModel) -> list[np.ndarray]:
    """Start 0 is r1 = r2 = 0 (the straight rhombs' corners, shapes free); the others are drawn
    (seeded) with r in [0, 0.35] and theta within a quarter turn, redrawn until both rhombs
    are simple (at most 50 draws each)."""
    rng = np.random.default_rng([settings.seed, 33])
    out = [np.zeros(4)]
    while len(out) < settings.starts:
        for _ in range(50):
            q = np.array([rng.uniform(0, 0.35), rng.uniform(-math.pi / 2, math.pi / 2),
                          rng.uniform(0, 0.35), rng.uniform(-math.pi / 2, math.pi / 2)])
            if not model.bad(q):
                break
        out.append(q)
    return out


def escherize_penrose(goal_a: Any, goal_b: Any | None = None, *, tiling: str = "p3",
                      settings: PenroseSettings = PenroseSettings()) -> PenroseResult:
    """The deformed P3 rhombs nearest the goal(s): Nelder-Mead over the quasivertex parameters
    from ``settings.starts`` starts (each evaluation projecting the edge shapes), the joint
    polish, then the family's checks (simple tiles, a validated patch, matching rules),
    shrinking the edge shapes towards straight until they pass."""
    from threadpoolctl import threadpool_limits  # start-up cost: loaded only for a search

    system = check_tiling(tiling)
    settings.check()
    goals = [escher.check_goal(goal_a, "goal A" if goal_b is not None else "goal")]
    goals.append(escher.check_goal(goal_b, "goal B") if goal_b is not None else goals[0])
    with threadpool_limits(limits=1, user_api="blas"):  # tiny matrices: BLAS threads only cost
        result = _fit(goals, system, settings)
    result.goals = 1 if goal_b is None else 2
    return result


def _fit(goals: list[np.ndarray], system: str, settings: PenroseSettings) -> PenroseResult:
    from scipy.optimize import minimize  # start-up cost: scipy (~0.3 s), only for a search

    t0 = time.perf_counter()
    model = PenroseModel(settings.edge_points, system)
    banks = [escher.GoalBank.build(g, settings.samples, settings.reflection) for g in goals]
    evaluations = 0

    def f(qvec: np.ndarray, ridge: float) -> float:
        nonlocal evaluations
        evaluations += 1
        if model.bad(qvec):
            return 2.0
        d, _, x = project(model, qvec, banks, INNER_STEPS, ridge, model.c0)
        bad = any(escher.crossings(z) for z in model.outlines(qvec, x))
        return d + CROSSING_PENALTY * bad

    best_q, best_f, best_ridge = np.zeros(4), math.inf, RIDGES[0]
    for i, s in enumerate(_starts(settings, model)):
        ridge = RIDGES[i % len(RIDGES)]
        simplex = np.vstack([s, s + np.diag(SIMPLEX_STEPS)])
        res = minimize(f, s, args=(ridge,), method="Nelder-Mead",
                       options={"maxfev": START_EVALUATIONS, "xatol": 1e-5, "fatol": 1e-8, "initial_simplex": simplex})
        if float(res.fun) < best_f:
            best_q, best_f, best_ridge = np.asarray(res.x, dtype=float), float(res.fun), ridge
    _, _, x = project(model, best_q, banks, FINAL_STEPS, best_ridge, model.c0)
    candidates = [(best_q, x)]
    # the polish minimises a weighted sum of the two squared distances; the score is the larger
    # one, so later rounds weight each rhomb by its share of the larger distance (damped: full
    # reweighting oscillated between the rhombs on the fish), keeping the best round
    weights, q, xx = [1.0, 1.0], best_q, x
    for _ in range(POLISH_ROUNDS):
        polished = _polish(model, q, xx, goals, banks, weights)
        if polished is None:
            break
        q, xx, ds, nfev = polished
        evaluations += nfev
        candidates.insert(0, (q, xx))
        if max(ds) <= 0:  # an exact fit
            break
        weights = [0.5 * (w + d / max(ds)) for w, d in zip(weights, ds)]
    result = escher.best_valid(candidates, lambda q, xx: _valid_result(model, q, xx, goals, system, settings),
                               f"{system} Escherization")
    result.evaluations = evaluations
    result.seconds = time.perf_counter() - t0
    return result


def _polish(model: PenroseModel, qvec: np.ndarray, x: np.ndarray, goals: Sequence[np.ndarray],
            banks: Sequence[escher.GoalBank], weights: Sequence[float] = (1.0, 1.0)
            ) -> tuple[np.ndarray, np.ndarray, list[float], int] | None:
    """q, x and both goals' continuous starting offsets refined jointly by scipy's
    least_squares on the two rhombs' stacked metric residuals (rhomb i's scaled by
    ``weights[i]``): (q, x, both distances, evaluations), or None if the larger distance does
    not improve."""
    from scipy.optimize import least_squares  # start-up cost: scipy (~0.3 s), only for a search

    n = banks[0].samples
    nx = model.nx
    srcs, bases, d0 = escher.aligned_sources(model.outlines(qvec, x), goals, banks)
    ridge = math.sqrt(POLISH_RIDGE)

    def resid(z: np.ndarray) -> np.ndarray:
        out = []
        for i, outline in enumerate(model.outlines(z[:4], z[4 : 4 + nx])):
            r = escher.similarity_residual(escher.resample(outline, n), escher.resample(srcs[i], n, bases[i] + z[-2 + i]))
            out += [weights[i] * r.real, weights[i] * r.imag]
        out.append(ridge * (z[4 : 4 + nx] - model.c0))
        return np.concatenate(out)

    try:
        res = least_squares(resid, np.concatenate([qvec, x, [0.0, 0.0]]), method="trf",
                            max_nfev=POLISH_EVALUATIONS, x_scale=0.1, ftol=1e-12, xtol=1e-12, gtol=1e-12)
    except ValueError:  # a degenerate outline at a trial point: keep the projection's answer
        return None
    z = res.x
    if not np.all(np.isfinite(z)) or model.bad(z[:4]):
        return None
    r = res.fun
    ds = [math.sqrt(float(np.sum(r[2 * n * i : 2 * n * (i + 1)] ** 2))) / weights[i] for i in range(2)]
    if max(ds) >= d0:
        return None
    return z[:4], z[4 : 4 + nx], ds, int(res.nfev)


def _valid_result(model: PenroseModel, qvec: np.ndarray, x: np.ndarray, goals: Sequence[np.ndarray], system: str,
                  settings: PenroseSettings) -> PenroseResult:
    """Shrink the fitted shapes towards straight until the family's tiles are simple, a patch
    of CHECK_REGION validates and the matching rules hold; report the accepted rhombs' distances."""
    from shapely.geometry import box  # start-up cost: shapely (~0.1 s), loaded by the family anyway

    params = _params(qvec)
    region = box(*CHECK_REGION)
    fitted = max(escher._distance(z, g, settings.samples, settings.reflection, refine=True)[0]
                 for z, g in zip(model.outlines(qvec, x), goals))
    note = ""
    for alpha in BACKOFF:
        xx = model.c0 + alpha * (x - model.c0)
        edges = {lab: _shape_text(pts) for lab, pts in model.shapes(xx).items()}
        result = PenroseResult(system, params.as_dict(), edges, 0.0, [], [], shrink=alpha, fitted_distance=fitted)
        try:
            tiling = result.tiling()
        except (ParameterError, GeometryError) as exc:
            note = str(exc)
            continue
        patch = tiling.patch(region)
        report = patch.validate(region)
        matching = qv.matching_report(patch)
        if not report or not matching.ok:
            note = report.summary() if not report else matching.summary()
            continue
        tiles = {t.name: t for t in tiling.prototiles}
        infos = [escher._distance(escher._complex(np.asarray(tiles[name].outline)), g, settings.samples,
                                  settings.reflection, refine=True) for name, g in zip(model.tiles, goals)]
        result.distances = [float(d) for d, _ in infos]
        result.mirrored = [bool(info["mirrored"]) for _, info in infos]
        result.distance = max(result.distances)
        result.note = "" if alpha == 1.0 else f"edge shapes shrunk to {alpha:g}: {note}"
        return result
    raise GeometryError(f"{system}: no valid Penrose tiling near the fit ({note})")


# ------------------------------------------------------------------------ output


def tiles_svg(result: PenroseResult, goals: Sequence[np.ndarray], size: int = 400) -> str:
    """The two tiles side by side in the system's prototile order (P3: thin, thick; P2: kite,
    dart; light and dark, the patch's colours), each with its goal aligned onto it (dashed)."""
    prototiles = result.tiling().prototiles
    order = [t.name for t in prototiles]
    fitted = list(GOAL_TILES[result.system])  # goal A's tile, goal B's tile
    shapes = [np.asarray(t.outline, dtype=float) for t in prototiles]
    shapes[1] = shapes[1] + [float(shapes[0][:, 0].max() - shapes[1][:, 0].min()) + 0.3, 0.0]
    idx = [fitted.index(name) for name in order]
    pair = [goals[min(i, len(goals) - 1)] for i in idx]  # one goal: both tiles against it
    aligned = [escher.align_onto(s, g, result.mirrored[i]) for s, g, i in zip(shapes, pair, idx)]
    title = (f"{result.system}  d = {result.distance:.4f} ("
             + ", ".join(f"{name} {result.distances[i]:.4f}" for name, i in zip(order, idx)) + ")")
    return escher.overlay_svg(title, shapes, aligned, size)


def write_outputs(result: PenroseResult, goals: Sequence[np.ndarray], out_dir: Any) -> list[Any]:
    """``penrose.json`` (spec and fit), ``tiles.svg`` (the rhombs with the aligned goals) and
    ``patch.svg`` (a patch of the tiling over CHECK_REGION) in ``out_dir``."""
    import json
    from pathlib import Path

    from shapely.geometry import box  # start-up cost: as in _valid_result

    from tilekit.files import check_output
    from tilekit.render import write_svg  # start-up cost: the renderer (~0.1 s)

    out = Path(out_dir)
    names = ["penrose.json", "tiles.svg", "patch.svg"]
    for name in names:
        check_output(out / name)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ParameterError(f"output directory {str(out)!r} cannot be made: {exc.strerror or exc}") from None
    (out / names[0]).write_text(json.dumps({"family": "substitution", "spec": result.spec(),
                                            "escherize": result.to_json()}, indent=1) + "\n")
    (out / names[1]).write_text(tiles_svg(result, goals))
    tiling = result.tiling()
    region = box(*CHECK_REGION)
    write_svg(tiling.render_svg(tiling.patch(region)), out / names[2])
    return [out / name for name in names]
