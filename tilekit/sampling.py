"""Tile-based importance sampling (§7.4): N points following a density, by any family's sampler,
with the count hit by choosing the threshold; spectral and spacing measures; CSV/NPY/SVG/PNG.

A sampler (``tilekit_samplers`` hook, :class:`tilekit.plugins.Sampler`) reports candidate points
with threshold intervals [lo, hi): the point belongs to the set made with threshold tau
(the density integral one sample stands for) iff lo <= tau < hi. :func:`sample` asks for the
candidates of a bracket around tau0 = total / N and picks, by one sort of the interval ends,
the tau whose set has the count nearest N; the candidates are made again only when the
bracket must be widened (docs/sampling.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.density import Density
from tilekit.errors import NotFoundError, ParameterError
from tilekit.limits import MAX_PNG_PIXELS, refuse_over
from tilekit.plugins import samplers

#: Most points one call makes (``tilekit sample -n``; about 100 bytes each while made).
MAX_SAMPLES = 20_000_000
#: Relative miss of the count beyond which the bracket is widened and the candidates redone.
COUNT_TOLERANCE = 0.005
#: A request of n samples may widen the bracket while n x its width stays below this, even when
#: n falls in a jump of the count (small n: a few tiles more or less matter).
WIDEN_BUDGET = 100_000
#: Lloyd iterations at most (``--relax``).
MAX_RELAX = 50


@dataclass
class SampleSet:
    """The points (m, 2) in the unit square, the threshold chosen and how they were made."""

    points: np.ndarray
    method: str
    requested: int
    tau: float
    seed: int
    relax: int = 0

    @property
    def count(self) -> int:
        return len(self.points)


def choose_threshold(lo: np.ndarray, hi: np.ndarray, n: int, tau_lo: float, tau_hi: float) -> tuple[float, int]:
    """The tau in [tau_lo, tau_hi) whose count #{lo <= tau < hi} is nearest ``n`` (the largest
    such tau on ties), and that count: one sort of the 2m interval ends."""
    ends = np.concatenate([lo, hi])
    step = np.concatenate([np.ones(len(lo), dtype=np.int64), -np.ones(len(hi), dtype=np.int64)])
    order = np.argsort(ends, kind="stable")
    ends, step = ends[order], step[order]
    # count on [ends[i], ends[i+1]) is the sum of the steps up to and including the last equal end
    counts = np.cumsum(step)
    last = np.r_[ends[1:] != ends[:-1], True]
    ends, counts = ends[last], counts[last]
    base = int(np.sum(lo < tau_lo) - np.sum(hi <= tau_lo))  # count at tau_lo
    inside = (ends >= tau_lo) & (ends < tau_hi)
    cand_tau = np.r_[tau_lo, ends[inside]]
    cand_n = np.r_[base, counts[inside]]
    err = np.abs(cand_n - n)
    best = np.flatnonzero(err == err.min())[-1]
    return float(cand_tau[best]), int(cand_n[best])


def sample(density: Density, n: int, method: str = "penrose", seed: int = 0, relax: int = 0,
           pm: Any = None, correct: bool = True) -> SampleSet:
    """About ``n`` points distributed by ``density`` over the unit square with ``method``'s tiles
    (count within :data:`COUNT_TOLERANCE` for smooth densities), moved by the sampler's
    correction step (``correct``, when it has one), then ``relax`` Lloyd steps."""
    points, tau, _ = _select(density, n, method, seed, relax, pm)
    sampler = samplers(pm)[method]
    rng = np.random.default_rng(seed)
    order = rng.permutation(len(points[0]))  # the candidates' order says how they were made; drop it
    pts, extra = points[0][order], {k: v[order] for k, v in points[1].items()}
    if correct and sampler.finish is not None and extra:
        pts = sampler.finish(pts, extra, tau)
    if relax:
        pts = lloyd(pts, density, relax, rng)
    return SampleSet(points=pts, method=method, requested=n, tau=tau, seed=seed, relax=relax)


def _select(density: Density, n: int, method: str, seed: int, relax: int, pm: Any
            ) -> tuple[tuple[np.ndarray, dict[str, np.ndarray]], float, int]:
    """The chosen candidates (points and their extra arrays), tau and the count."""
    found = samplers(pm)
    if method not in found:
        raise NotFoundError("sampling method", method, sorted(found))
    if not isinstance(n, int) or isinstance(n, bool) or n <= 0:
        raise ParameterError(f"number of samples {n!r} must be a positive integer")
    refuse_over("samples", n, MAX_SAMPLES, "-n", hint=f"at most {MAX_SAMPLES:,} samples")
    if not 0 <= relax <= MAX_RELAX:
        raise ParameterError(f"relax {relax} must be in 0..{MAX_RELAX} Lloyd iterations")
    sampler = found[method]
    tau0 = density.total / n
    width = 1.25
    best: tuple[float, int, dict[str, np.ndarray], np.ndarray, np.ndarray, np.ndarray] | None = None
    for _ in range(6):
        tau_lo, tau_hi = tau0 / width, tau0 * width
        got = sampler.candidates(density, tau_lo, tau_hi, seed)
        pts, lo, hi = got[:3]
        extra = got[3] if len(got) > 3 else {}
        tau, count = choose_threshold(lo, hi, n, tau_lo, tau_hi) if len(lo) else (tau0, 0)
        if best is None or abs(count - n) < abs(best[1] - n):
            best = (tau, count, extra, pts, lo, hi)
        at_edge = not len(lo) or tau <= tau_lo * (1 + 1e-9) or tau >= tau_hi / (1 + 1e-3)
        if abs(count - n) <= COUNT_TOLERANCE * n or not (at_edge or n * width <= WIDEN_BUDGET):
            break  # hit, or n falls in a jump of the count inside the bracket
        # the count reaches n only outside the bracket, or a small n may be hit by a tau farther
        # out (a wider bracket holds the narrower one, so the best count can only improve)
        width *= 2.0
    assert best is not None
    tau, count, extra, pts, lo, hi = best
    chosen = (lo <= tau) & (tau < hi)
    return (pts[chosen], {k: v[chosen] for k, v in extra.items()}), tau, count


def train_corrections(method: str, bins: int, sizes: Any = (2000, 3000, 5000, 8000, 13000), seeds: int = 4,
                      iterations: int = 10, per_point: int = 40, pm: Any = None) -> np.ndarray:
    """Fit a sampler's correction vectors (Ostromoukhov et al.'s correction step) by Lloyd
    relaxation: uniform-density sets of several sizes and seeds are made without correction,
    relaxed (``iterations`` probabilistic Lloyd steps, ``per_point`` probes a point), and each
    point's displacement, taken back to its tile's frame, is averaged per (structural context
    ``extra["key"]``, bin of E = integral / tau in ``bins`` equal bins of (0, 1]).
    Returns rows (key, bin, dx, dy, count), one per pair seen."""
    uniform = Density(np.ones((64, 64)), name="uniform")
    sums: dict[tuple[int, int], np.ndarray] = {}
    for n in sizes:
        for seed in range(seeds):
            (pts, extra), tau, _ = _select(uniform, int(n), method, seed, 0, pm)
            if "key" not in extra:
                raise ParameterError(f"sampler {method!r} reports no structural context to train on")
            relaxed = lloyd(pts, uniform, iterations, np.random.default_rng(seed), per_point=per_point)
            moved = relaxed - pts
            # keep points away from the square's edges: there Lloyd moves them for the edge's sake
            spacing = 1.0 / math.sqrt(len(pts))
            inner = np.all((pts > 3 * spacing) & (pts < 1 - 3 * spacing), axis=1)
            local = np.linalg.solve(extra["frame"][inner], moved[inner][:, :, None])[:, :, 0]
            e = np.clip(extra["integral"][inner] / tau, 0.0, 1.0)
            b = np.minimum((e * bins).astype(np.int64), bins - 1)
            keys = extra["key"][inner] * bins + b
            uniq, inv = np.unique(keys, return_inverse=True)
            sx = np.bincount(inv, weights=local[:, 0], minlength=len(uniq))
            sy = np.bincount(inv, weights=local[:, 1], minlength=len(uniq))
            cnt = np.bincount(inv, minlength=len(uniq))
            for kb, ax, ay, c in zip(uniq.tolist(), sx.tolist(), sy.tolist(), cnt.tolist()):
                sums.setdefault(kb, np.zeros(3))[:] += (ax, ay, c)
    rows = [(kb // bins, kb % bins, a[0] / a[2], a[1] / a[2], int(a[2])) for kb, a in sorted(sums.items())]
    return np.array(rows, dtype=np.float64).reshape(-1, 5)


def write_corrections(rows: np.ndarray, path: str | Path, min_count: int = 5) -> Path:
    """Write a correction table as CSV (key, bin, dx, dy, count); pairs seen fewer than
    ``min_count`` times are left out (their correction is 0)."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    keep = rows[rows[:, 4] >= min_count]
    with open(p, "w", encoding="ascii") as fh:
        fh.write("key,bin,dx,dy,count\n")
        for k, b, dx, dy, c in keep.tolist():
            fh.write(f"{int(k)},{int(b)},{dx:.6f},{dy:.6f},{int(c)}\n")
    return p


def _kdtree() -> Any:
    try:
        from scipy.spatial import cKDTree  # optional: the 'sampling' extra
    except ImportError:
        raise ParameterError("Lloyd relaxation and the spacing measures need SciPy: pip install 'tilekit[sampling]' "
                             "(or --relax 0)") from None
    return cKDTree


def lloyd(points: np.ndarray, density: Density, iterations: int, rng: np.random.Generator,
          per_point: int = 12) -> np.ndarray:
    """Density-weighted Lloyd relaxation by random sampling (Ju, Du and Gunzburger's
    probabilistic Lloyd): each iteration draws ``per_point`` x N points from the density,
    gives each to its nearest sample (one k-d tree query) and moves every sample to the mean
    of its points; a sample given none stays. Vectorised: no Python per point."""
    cKDTree = _kdtree()
    pts = points.copy()
    for _ in range(iterations):
        probe = density.random_points(per_point * len(pts), rng)
        _, owner = cKDTree(pts).query(probe, workers=1)
        got = np.bincount(owner, minlength=len(pts))
        sx = np.bincount(owner, weights=probe[:, 0], minlength=len(pts))
        sy = np.bincount(owner, weights=probe[:, 1], minlength=len(pts))
        moved = got > 0
        pts[moved, 0] = sx[moved] / got[moved]
        pts[moved, 1] = sy[moved] / got[moved]
    return pts


# ---------------------------------------------------------------------- measures


def nearest_neighbour_distances(points: np.ndarray, torus: bool = False) -> np.ndarray:
    """Each point's distance to its nearest other point (k-d tree; optionally on the unit torus)."""
    cKDTree = _kdtree()
    pts = np.mod(points, 1.0) if torus else points
    d, _ = cKDTree(pts, boxsize=1.0 if torus else None).query(pts, k=2, workers=1)
    return d[:, 1]


def normalised_spacing(points: np.ndarray) -> tuple[float, float]:
    """(min, mean) nearest-neighbour distance over the spacing of N points in a unit square,
    sqrt(1 / N): comparable across N (a hexagonal lattice has 1.0746)."""
    d = nearest_neighbour_distances(points)
    scale = math.sqrt(1.0 / len(points))
    return float(d.min() / scale), float(d.mean() / scale)


def radial_power_spectrum(points: np.ndarray, size: int = 128, bins: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The radially averaged power spectrum of a point set in the unit square (periodogram
    |sum exp(-2 pi i f.x)|^2 / N on the integer frequencies |f_x|, |f_y| < size / 2, computed as
    a non-uniform DFT by separable outer products in blocks), and the radial frequencies.
    A uniform random set has the flat value 1; blue noise has little low-frequency power."""
    n = len(points)
    half = size // 2
    f = np.arange(-half, half)
    power = np.zeros((size, size), dtype=complex)
    block = max(1, 2_000_000 // size)
    for s in range(0, n, block):
        p = points[s : s + block]
        ex = np.exp(-2j * np.pi * np.outer(p[:, 0], f))  # (b, size)
        ey = np.exp(-2j * np.pi * np.outer(p[:, 1], f))
        power += ey.T @ ex  # (size_y, size_x): the sum over points of ey * ex
    spectrum = np.abs(power) ** 2 / n
    fx, fy = np.meshgrid(f, f)
    radius = np.hypot(fx, fy)
    nb = bins or half
    edges = np.linspace(0, half, nb + 1)
    which = np.digitize(radius.ravel(), edges) - 1
    ok = (which >= 0) & (which < nb) & (radius.ravel() > 0)
    sums = np.bincount(which[ok], weights=spectrum.ravel()[ok], minlength=nb)
    cnt = np.bincount(which[ok], minlength=nb)
    with np.errstate(invalid="ignore", divide="ignore"):
        radial = sums / cnt
    return 0.5 * (edges[1:] + edges[:-1]), radial


def density_fidelity(points: np.ndarray, density: Density, grid: int = 8) -> dict[str, float]:
    """How well counts follow the density over a grid x grid partition of the square: the
    chi-square statistic sum (O - E)^2 / E over cells with E > 0 (E = N x the cell's share of
    the integral), its degrees of freedom, and the largest relative error |O - E| / E among
    cells with E >= 20."""
    edges = np.linspace(0, 1, grid + 1)
    x0, y0 = np.meshgrid(edges[:-1], edges[:-1])
    share = density.box_integral(x0, y0, x0 + 1 / grid, y0 + 1 / grid) / density.total
    expected = share * len(points)
    observed, _, _ = np.histogram2d(points[:, 1], points[:, 0], bins=[edges, edges])
    ok = expected > 0
    chi2 = float(np.sum((observed[ok] - expected[ok]) ** 2 / expected[ok]))
    big = expected >= 20
    rel = float(np.max(np.abs(observed[big] - expected[big]) / expected[big])) if big.any() else float("nan")
    outside = float(observed[~ok].sum())
    return {"chi2": chi2, "dof": int(ok.sum()) - 1, "max_relative_error": rel, "points_where_zero": outside}


# ---------------------------------------------------------------------- output


def write_points(points: np.ndarray, path: str | Path) -> Path:
    """Write points as CSV (header ``x,y``) or NumPy ``.npy`` by the suffix."""
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".npy":
        np.save(p, points)
    elif suffix == ".csv":
        with open(p, "w", encoding="ascii") as fh:
            fh.write("x,y\n")
            np.savetxt(fh, points, fmt="%.9f", delimiter=",")
    else:
        raise ParameterError(f"output {p.name!r}: points are written as .csv or .npy; pictures as .svg or .png")
    return p


def stipple_svg(points: np.ndarray, size: int = 800, radius: float | None = None, dark: bool = True) -> str:
    """An SVG stipple picture: one disc per point, the unit square's y axis pointing up.
    ``dark``: light dots on black (bright density = many dots looks like the image);
    otherwise black dots on white."""
    n = max(len(points), 1)
    r = radius if radius is not None else 0.35 * size / math.sqrt(n)
    bg, fg = ("#000", "#fff") if dark else ("#fff", "#000")
    xs = points[:, 0] * size
    ys = (1.0 - points[:, 1]) * size
    body = "".join(f"M{x:.2f} {y:.2f}m-{r:.2f} 0a{r:.2f} {r:.2f} 0 1 0 {2 * r:.2f} 0a{r:.2f} {r:.2f} 0 1 0 -{2 * r:.2f} 0"
                   for x, y in zip(xs.tolist(), ys.tolist()))
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" viewBox="0 0 {size} {size}">'
            f'<rect width="{size}" height="{size}" fill="{bg}"/><path fill="{fg}" d="{body}"/></svg>\n')


def write_picture(points: np.ndarray, path: str | Path, size: int = 800, dark: bool = True) -> Path:
    """Write the stipple picture as .svg, or .png (through cairosvg, the 'png' extra)."""
    p = Path(path)
    refuse_over("pixels", size * size, MAX_PNG_PIXELS, "--size")
    svg = stipple_svg(points, size, dark=dark)
    if p.suffix.lower() == ".svg":
        p.write_text(svg, encoding="utf-8")
    elif p.suffix.lower() == ".png":
        try:
            import cairosvg  # optional: the 'png' extra
        except ImportError:
            raise ParameterError("PNG output needs cairosvg: pip install 'tilekit[png]'; or write .svg") from None
        cairosvg.svg2png(bytestring=svg.encode(), write_to=str(p), output_width=size, output_height=size)
    else:
        raise ParameterError(f"picture {p.name!r}: give a .svg or .png file")
    return p
