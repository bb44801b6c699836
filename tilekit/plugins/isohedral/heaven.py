"""Heaven-and-Hell Escherization (Kaplan and Salesin 2004 after Dress; Kaplan 2009, §7.3): one
tile shape, in two colours so that edge-adjacent tiles always differ, that resembles two
goals at once, so the light tiles read as one figure and the dark ones as the other.

The tile is fitted to the larger of its two distances from the goals with the dihedral fit's
projection (:func:`~.dihedral.project_pieces`, the whole tile matched to both goal banks) and
the same polish and checks. Only types whose tilings admit such a colouring can be used: the
colouring is found among the two-colourings of the type's aspects and translations
(:func:`two_colouring`), which exist exactly when the tiling's adjacency graph is bipartite
(the topologies 4^4, 6^3, 4.8^2 and 4.6.12, whose tiling vertices all have even valence).
"""

from __future__ import annotations

import functools
import itertools
import math
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from tilekit.colouring import Colouring
from tilekit.errors import GeometryError, ParameterError
from tilekit.geometry import Affine
from tilekit.plugins.isohedral import escher
from tilekit.plugins.isohedral.dihedral import (
    DihedralSettings,
    SplitModel,
    check_goals,
    project_pieces,
)
from tilekit.plugins.isohedral.engine import IsohedralTiling
from tilekit.plugins.isohedral.escher import (
    BACKOFF,
    CROSSING_PENALTY,
    FINAL_STEPS,
    INNER_STEPS,
    POLISH_EVALUATIONS,
    RIDGES,
    GoalBank,
    resample,
    type_model,
)
from tilekit.plugins.isohedral.escher_limits import MAX_WORKERS
from tilekit.plugins.isohedral.spec import tiling_from_spec
from tilekit.tiling import Patch

DEFAULT_SETTINGS = DihedralSettings()
#: Aspects up to which every two-colouring is tried (2^aspects * 4 candidates, vectorised).
MAX_COLOURING_ASPECTS = 12


def two_colouring(tiling: IsohedralTiling) -> Colouring | None:
    """A colouring ``(c_1..c_m)(p)(q)`` with two colours under which no two tiles sharing an
    edge have the same colour, or None. Checked on the unit and its 8 neighbouring units:
    a tile's colour is ``c[aspect]``, swapped once per odd step along v1 (if p swaps) and
    along v2 (if q swaps)."""
    m = len(tiling.unit_aspect)
    if m > MAX_COLOURING_ASPECTS:
        return None
    unit = tiling.unit()
    cells = [(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1)]
    patch = Patch.concat([unit.transformed(Affine.translation(*(a * tiling.v1 + b * tiling.v2))) for a, b in cells])
    aspect = np.tile(np.asarray(tiling.unit_aspect), len(cells))
    odd_a = np.repeat([a % 2 for a, _ in cells], m)
    odd_b = np.repeat([b % 2 for _, b in cells], m)
    pairs = patch.adjacency().edge
    if not len(pairs):
        return None
    cs = np.array(list(itertools.product((0, 1), repeat=m)), dtype=np.int64)  # (2^m, m)
    for pa, qb in ((0, 0), (1, 0), (0, 1), (1, 1)):
        colour = cs[:, aspect] ^ (pa * odd_a) ^ (qb * odd_b)  # (2^m, tiles)
        ok = np.all(colour[:, pairs[:, 0]] != colour[:, pairs[:, 1]], axis=1)
        if ok.any():
            c = cs[int(np.argmax(ok))]
            return Colouring(tuple(int(v) for v in c), (1, 0) if pa else (0, 1), (1, 0) if qb else (0, 1))
    return None


@dataclass
class HeavenResult(escher.TypeFit):
    """The best two-coloured tile of one type for a pair of goals."""

    ih: int
    distance: float  # the larger of the tile's distances from the two goals
    distances: tuple[float, float]
    params: list[float]
    edges: dict[str, str]
    colouring: str
    evaluations: int = 0
    seconds: float = 0.0
    shrink: float = 1.0
    mirrored: tuple[bool, bool] = (False, False)

    def spec(self) -> dict[str, Any]:
        """The isohedral spec of the tile with its two-colouring."""
        out = self.base_spec()
        out["colouring"] = self.colouring
        return out

    def tiling(self) -> IsohedralTiling:
        return tiling_from_spec(self.spec())  # type: ignore[return-value]

    def tile_svg(self, goals: Sequence[np.ndarray]) -> str:
        """The tile drawn twice (light and dark), each with one goal aligned onto it."""
        tile = np.asarray(self.tiling().prototile.outline, dtype=float)
        aligned = [escher.align_onto(tile, g, mir) for g, mir in zip(goals, self.mirrored)]
        span = float(np.ptp(tile, axis=0).max())
        shift = np.array([1.3 * span, 0.0])
        title = f"{self.name} heaven and hell  d = {self.distance:.4f} (A {self.distances[0]:.4f}, B {self.distances[1]:.4f})"
        return escher.overlay_svg(title, [tile, tile + shift], [aligned[0], aligned[1] + shift])

    def to_json(self) -> dict[str, Any]:
        return {"ih": self.ih, "name": self.name, "distance": self.distance, "distances": list(self.distances),
                "shrink": self.shrink, "mirrored": list(self.mirrored), "spec": self.spec(),
                "evaluations": self.evaluations, "seconds": self.seconds}


@escher.one_blas_thread
def heaven_hell_type(goal_a: Any, goal_b: Any, ih: int, settings: DihedralSettings = DEFAULT_SETTINGS) -> HeavenResult:
    """The tile of type ``ih`` nearest both goals (the larger distance), two-coloured so that
    neighbours differ; GeometryError when the type has no such colouring."""
    # start-up cost: scipy (~0.3 s), only for a search
    from scipy.optimize import least_squares, minimize

    settings.check()
    t0 = time.perf_counter()
    goals = check_goals(goal_a, goal_b)
    if ih not in _types():
        raise GeometryError(f"IH{ih}: no two-colouring in which neighbouring tiles differ (a tiling vertex of odd "
                            "valence); Heaven and Hell needs a type of topology 4^4, 6^3, 4.8^2 or 4.6.12")
    model = SplitModel(type_model(ih, settings.edge_points), 0)
    banks = [GoalBank.build(g, settings.samples, settings.reflection) for g in goals]
    whole = np.column_stack([np.arange(model.m), np.arange(model.m), np.zeros(model.m)]).astype(float)
    rows = [whole, whole]
    npar = model.tile.n_params
    evaluations = 0

    def f(p: np.ndarray, ridge: float) -> float:
        nonlocal evaluations
        evaluations += 1
        bad = model.tile.polygon_ok(p)
        if bad:
            return 1.0 + bad
        d, _, x = project_pieces(model, p, rows, banks, INNER_STEPS, ridge, model.tile.c0)
        return d + CROSSING_PENALTY * escher.crossings(model.tile.outline(p, x))

    rng = np.random.default_rng([settings.seed, ih, 3])
    p0 = model.tile.default
    spread = 0.25 * max(1.0, float(np.max(np.abs(p0)))) if npar else 0.0
    best_p, best_f, best_ridge = p0.copy(), math.inf, RIDGES[0]
    for i in range(settings.starts):
        s = p0 + (spread * rng.standard_normal(npar) if i else 0.0)
        ridge = RIDGES[i % len(RIDGES)]
        if model.tile.polygon_ok(s):
            continue
        if npar:
            res = minimize(f, s, args=(ridge,), method="Nelder-Mead",
                           options={"maxfev": 40 * (npar + 1), "xatol": 1e-4, "fatol": 1e-7})
            x, fx = np.asarray(res.x, dtype=float), float(res.fun)
        else:
            x, fx = s, f(s, ridge)
        if fx < best_f:
            best_p, best_f, best_ridge = x, fx, ridge
    _, _, c = project_pieces(model, best_p, rows, banks, FINAL_STEPS, best_ridge, model.tile.c0)
    candidates = [(best_p, c)]

    # the polish: parameters, control points and both goals' starting offsets jointly
    n = settings.samples
    tile = model.tile.outline(best_p, c)
    srcs, bases, _ = escher.aligned_sources([tile, tile], goals, banks)

    def resid(z: np.ndarray) -> np.ndarray:
        zc = resample(model.tile.outline(z[:npar], z[npar:-2]), n)
        out = []
        for i in range(2):
            r = escher.similarity_residual(zc, resample(srcs[i], n, bases[i] + z[-2 + i]))
            out += [r.real, r.imag]
        return np.concatenate(out)

    try:
        res = least_squares(resid, np.concatenate([best_p, c, [0.0, 0.0]]), method="trf",
                            max_nfev=POLISH_EVALUATIONS, x_scale=0.1)
        if np.all(np.isfinite(res.x)) and not model.tile.polygon_ok(res.x[:npar]):
            candidates.insert(0, (res.x[:npar], res.x[npar:-2]))
            evaluations += int(res.nfev)
    except ValueError:  # a degenerate outline at a trial point: keep the projection's answer
        pass
    result = escher.best_valid(candidates, lambda p, cc: _valid(model, p, cc, goals, settings), f"IH{ih}")
    result.evaluations = evaluations
    result.seconds = time.perf_counter() - t0
    return result


def _valid(model: SplitModel, p: np.ndarray, c: np.ndarray, goals: Sequence[np.ndarray],
           settings: DihedralSettings) -> HeavenResult:
    note = ""
    for alpha in BACKOFF:
        cc = model.tile.c0 + alpha * (c - model.tile.c0)
        try:
            base = IsohedralTiling(model.tile.ih, [float(t) for t in p], model.tile.shapes(cc), check=True)
        except (ParameterError, GeometryError) as exc:
            note = str(exc)
            continue
        colouring = two_colouring(base)
        if colouring is None:  # the colouring depends on the type only; kept as a check
            note = "no two-colouring"
            continue
        outline = escher._complex(np.asarray(base.prototile.outline))
        ds, mirrored = [], []
        for goal in goals:
            d, info = escher._distance(outline, goal, settings.samples, settings.reflection, refine=True)
            ds.append(d)
            mirrored.append(bool(info["mirrored"]))
        edges = {lab: sh.to_text() for lab, sh in base.edge_shapes.items()}
        return HeavenResult(model.tile.ih, max(ds), (ds[0], ds[1]), [float(t) for t in p], edges, str(colouring),
                            shrink=alpha, mirrored=(mirrored[0], mirrored[1]))
    raise GeometryError(f"IH{model.tile.ih}: no valid tiling found near the fit ({note})")


@functools.cache
def _types() -> tuple[int, ...]:
    return tuple(ih for ih in escher.unmarked_types() if two_colouring(IsohedralTiling(ih)) is not None)


def heaven_hell_types() -> list[int]:
    """The unmarked types whose tilings have a two-colouring in which neighbours differ (43:
    those of the topologies with only even vertex valences: 4^4, 6^3, 4.8^2 and 4.6.12)."""
    return list(_types())


def heaven_hell(goal_a: Any, goal_b: Any, types: Iterable[int] | None = None, *,
                settings: DihedralSettings = DEFAULT_SETTINGS, workers: int = 1
                ) -> tuple[list[HeavenResult], list[tuple[int, str]]]:
    """Fit every type in ``types`` (default: :func:`heaven_hell_types`), in ``workers``
    processes; results sorted by distance and the types that gave none (with the reason)."""
    settings.check()
    a, b = check_goals(goal_a, goal_b)
    todo = list(types) if types is not None else heaven_hell_types()
    for ih in todo:
        if escher.get_template(ih).marked:
            raise ParameterError(f"IH{ih} is a marked type; escherization takes the 81 unmarked types")
    if not (isinstance(workers, int) and 1 <= workers <= MAX_WORKERS):
        raise ParameterError(f"workers {workers!r} must be an integer from 1 to {MAX_WORKERS}")
    outs = escher.run_jobs(escher.run_guarded, [(heaven_hell_type, ih, (a, b, ih, settings)) for ih in todo], workers)
    good = sorted((o for o in outs if isinstance(o, HeavenResult)), key=lambda r: (r.distance, r.ih))
    return good, [o for o in outs if not isinstance(o, HeavenResult)]
