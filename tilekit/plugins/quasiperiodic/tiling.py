"""QuasiperiodicTiling: n-fold rhombic tilings by de Bruijn's multigrid, with random access.

Options (``configure`` / ``tilekit render --set``): ``n`` (the rotational order, 4..50),
``gamma`` (the N grid offsets, or one value for every grid; default: a generic vector summing
to 0, which for n = 5 is a Penrose rhomb tiling) and ``singular`` (``refuse``: singular offsets
are a one-line error; ``perturb``: the offsets gamma + delta are used, delta a fixed zero-sum
vector of size 1e-6, with a warning when gamma itself is singular near the origin).

``patch(region)`` computes the region's rhombs from the grid lines crossing it
(:func:`.multigrid.rhombs`), wherever the region is; ``iter_patches`` cuts the region into
bands and computes each alone, so a stream holds one band at a time.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np
import shapely
from shapely.geometry.base import BaseGeometry

from tilekit.errors import ParameterError, ParseError
from tilekit.geometry import as_region
from tilekit.limits import (
    GENERATION_BYTES_PER_TILE,
    STREAM_CHUNK_TILES,
    check_chunk_tiles,
    refuse_over_memory,
)
from tilekit.plugins.quasiperiodic import multigrid, project
from tilekit.plugins.quasiperiodic.star import MAX_N, Star, check_order, star
from tilekit.tiling import Patch, Prototile, Tiling

FAMILY = "quasiperiodic"
#: Largest |gamma_j| accepted: an integer shift of gamma_j only translates the tiling by -e_j,
#: and beyond this the grid's offsets lose the precision the fractions need.
MAX_GAMMA = 1e6
#: Size of the fixed perturbation of ``singular=perturb`` (far above SINGULAR_TOL, far below
#: anything a picture shows).
PERTURBATION = 1e-6
#: Half the side of the default region (about 500 tiles for every n).
DEFAULT_HALF = 10.0
SINGULAR_CHOICES = ("refuse", "perturb")

__all__ = ["FAMILY", "QuasiperiodicTiling", "SingularWarning", "default_gamma", "parse_gamma"]


class SingularWarning(UserWarning):
    """Offsets that are singular were perturbed (``singular=perturb``)."""


def default_gamma(n: int) -> np.ndarray:
    """A generic offset vector for order ``n``: gamma_j the fractional part of
    0.1431 + j (sqrt 5 - 1) / 2 to four decimals, and the last one the fractional part that
    makes the sum a whole number (as a decimal), so that n = 5 gives a Penrose tiling (de
    Bruijn: sum gamma = 0 mod 1)."""
    grids = star(n).grids
    golden = (math.sqrt(5) - 1) / 2
    g = [round((0.1431 + j * golden) % 1.0, 4) for j in range(grids - 1)]
    return np.array(g + [round(-sum(g) % 1.0, 4)])


def perturbation(grids: int) -> np.ndarray:
    """The fixed zero-sum vector of ``singular=perturb``: PERTURBATION times the fractional
    parts of (j + 1) sqrt 2 less their mean (the sum of gamma, which decides the Penrose
    case, is kept)."""
    u = np.array([((j + 1) * math.sqrt(2)) % 1.0 for j in range(grids)])
    return PERTURBATION * (u - u.mean())


def parse_gamma(value: Any, grids: int, n: int) -> np.ndarray:
    """Offsets from a number, a sequence of N numbers or the text 'g0,g1,...' (one number:
    every grid), each finite with |gamma_j| <= MAX_GAMMA; a one-line ParameterError otherwise."""
    if isinstance(value, str):
        parts = [p.strip() for p in value.split(",")]
        if not value.strip() or any(not p for p in parts):
            raise ParameterError(f"gamma={value[:60]!r} is not a comma-separated list of numbers")
        items: list[Any] = parts
    elif isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool):
        items = [value]
    else:
        try:
            items = list(value)
        except TypeError:
            raise ParameterError(f"gamma={value!r} is not a number or a list of numbers") from None
    out = []
    for item in items:
        if isinstance(item, bool):
            raise ParameterError(f"gamma value {item!r} is not a number")
        try:
            x = float(item)
        except (TypeError, ValueError, OverflowError):
            raise ParameterError(f"gamma value {str(item)[:30]!r} is not a number") from None
        if not math.isfinite(x) or abs(x) > MAX_GAMMA:
            raise ParameterError(f"gamma value {str(item)[:30]} is not a finite number within ±{MAX_GAMMA:g}")
        out.append(x)
    if len(out) == 1:
        out = out * grids
    if len(out) != grids:
        raise ParameterError(
            f"gamma has {len(out)} values; n={n} has {grids} grids: give {grids} comma-separated offsets (or one for all)"
        )
    return np.array(out, dtype=float)


class QuasiperiodicTiling(Tiling):
    """The multigrid tiling of rotational order ``n`` with offsets ``gamma`` (see the module)."""

    family = FAMILY
    streams = True

    def __init__(self, n: int = 5, gamma: Any = None, singular: str = "refuse", *, name: str = "",
                 title: str = "") -> None:
        self.star: Star = star(n)
        self.n = self.star.n
        if singular not in SINGULAR_CHOICES:
            raise ParameterError(f"singular={singular!r} is not one of {', '.join(SINGULAR_CHOICES)}")
        self.singular = singular
        self.gamma = default_gamma(self.n) if gamma is None else parse_gamma(gamma, self.star.grids, self.n)
        self.name = name or f"multigrid-{self.n}"
        self.title = title
        self.offsets = self.gamma
        if singular == "perturb":
            try:
                self._check(self.gamma)
            except multigrid.SingularGrid as exc:
                warnings.warn(SingularWarning(f"{exc}; perturbed by up to {PERTURBATION:g}"), stacklevel=2)
            self.offsets = self.gamma + perturbation(self.star.grids)
        self._check(self.offsets)

    def _check(self, gamma: np.ndarray) -> None:
        """SingularGrid when three grid lines meet near the origin (the default region)."""
        multigrid.rhombs(self.star, gamma, self.default_region().bounds)

    # ------------------------------------------------------------------ Tiling API
    @property
    def prototiles(self) -> list[Prototile]:
        return self.star.prototiles

    def default_region(self) -> BaseGeometry:
        return shapely.box(-DEFAULT_HALF, -DEFAULT_HALF, DEFAULT_HALF, DEFAULT_HALF)

    def estimate_tiles(self, region: Any = None) -> float:
        """The tiles of the region's box grown by a tile diameter on every side, at the
        tiling's exact density (sum of the grid pairs' |sin| over (N / 2)²): an upper bound
        up to the boundary's share."""
        reg = self.default_region() if region is None else as_region(region)
        x0, y0, x1, y1 = reg.bounds
        d = self.star.diameter
        with np.errstate(over="ignore"):
            return float((x1 - x0 + 2 * d) * (y1 - y0 + 2 * d) * self.star.density)

    def patch(self, region: Any = None) -> Patch:
        """Every rhomb whose bounding box overlaps the region's box (then clipped to the
        region when it is not a box), computed from the grid lines crossing the region."""
        reg = self.default_region() if region is None else as_region(region)
        refuse_over_memory("tiles", self.estimate_tiles(reg), GENERATION_BYTES_PER_TILE,
                           hint="ask for a smaller region, or stream it (iter_patches, or render to .svg / .geojson)")
        patch = self._patch(multigrid.rhombs(self.star, self.offsets, reg.bounds))
        return patch if _is_box(reg) else patch.clip(reg)

    def _patch(self, rh: multigrid.Rhombs) -> Patch:
        """The Patch of some rhombs: prototile (kind) and map from each pair's placement."""
        # start-up cost: numba, loaded by multigrid.rhombs already
        from tilekit.plugins.quasiperiodic import kernels

        st = self.star
        maps = np.empty((len(rh), 3, 3))
        kind = np.empty(len(rh), dtype=np.int64)
        kernels.place(rh.pair, rh.lower, st.pair_turn, st.pair_offset, st.pair_kind, maps, kind)
        return Patch(st.prototiles, kind, maps, colour=kind, aspect=rh.pair)

    def iter_patches(self, region: Any = None, chunk_tiles: int = STREAM_CHUNK_TILES) -> Iterator[Patch]:
        """``patch(region)`` as bands across the region's longer side of about ``chunk_tiles``
        tiles each (at least one unit thick), each computed alone: a tile belongs to the band
        holding its centre, and a band's edge is moved off any centre within float noise of
        it, so the bands' union is ``patch(region)``, each tile once."""
        chunk_tiles = check_chunk_tiles(chunk_tiles)
        reg = self.default_region() if region is None else as_region(region)
        x0, y0, x1, y1 = reg.bounds
        across = 1 if (y1 - y0) >= (x1 - x0) else 0  # cut across the longer side
        lo, hi = (y0, y1) if across else (x0, x1)
        width = (x1 - x0) if across else (y1 - y0)
        d = self.star.diameter
        thick = max(1.0, chunk_tiles / (self.star.density * (width + 2 * d)))
        bands = max(1, math.ceil((hi - lo) / thick))
        refuse_over_memory("tiles in one band", self.estimate_tiles(reg) / bands, GENERATION_BYTES_PER_TILE,
                           hint="give a smaller chunk size")
        half = self.star.pair_corners.sum(axis=1) / 4  # each pair's centre, from the lower vertex
        start = -math.inf
        for b in range(bands):
            end = math.inf if b == bands - 1 else lo + (hi - lo) * (b + 1) / bands
            g_lo = lo if b == 0 else max(lo, start - d)
            g_hi = hi if b == bands - 1 else min(hi, end + d)
            box = (x0, g_lo, x1, g_hi) if across else (g_lo, y0, g_hi, y1)
            rh = multigrid.rhombs(self.star, self.offsets, box)
            centre = rh.lower[:, across] + half[rh.pair, across]
            if math.isfinite(end):
                end = _clear_cut(centre, end)
            keep = (centre >= start) & (centre < end)
            # a rhomb of the band that only the band's box (not the region's) saw is dropped
            bx = rh.lower + self.star.pair_bounds[rh.pair, :2]
            bX = rh.lower + self.star.pair_bounds[rh.pair, 2:]
            keep &= (bX[:, 0] > x0 + 1e-9) & (bx[:, 0] < x1 - 1e-9) & (bX[:, 1] > y0 + 1e-9) & (bx[:, 1] < y1 - 1e-9)
            start = end
            if not keep.any():
                continue
            patch = self._patch(multigrid.Rhombs(rh.pair[keep], rh.lower[keep], None, rh.candidates))
            if not _is_box(reg):
                patch = patch.clip(reg)
            if len(patch):
                yield patch

    # ------------------------------------------------------------------ facts
    def properties(self) -> dict[str, Any]:
        st = self.star
        freq = project.frequencies(st)
        props: dict[str, Any] = {
            "n": self.n,
            "grids": st.grids,
            "symmetry_order": 2 * st.grids,
            "rhomb_kinds": st.kinds,
            "rhomb_angles": [round(math.degrees(a), 6) for a in st.kind_angles],
            "tile_frequencies": [round(float(f), 12) for f in freq],
            "tiles_per_unit_area": round(st.density, 12),
            "gamma": [float(g) for g in self.gamma],
            "gamma_sum": round(float(math.fsum(self.gamma)), 12),
            "periodic": self.n in (4, 6),
            "k_hedral": st.kinds,
            "sides": [4],  # rhombs
            "aperiodic": False,  # each rhomb alone tiles periodically: no matching rules here
            "edge_to_edge": True,
            "method": "de Bruijn multigrid",
        }
        if self.n == 5:
            props["penrose"] = abs(math.remainder(math.fsum(self.gamma), 1.0)) < 1e-9
        if self.singular != "refuse":
            props["singular"] = self.singular
        return props

    def describe(self) -> str:
        st = self.star
        kinds = ", ".join(f"{p.name} {f:.6f}" for p, f in zip(st.prototiles, project.frequencies(st)))
        lines = [
            f"{self.title or self.name}: de Bruijn's multigrid of order n = {self.n}, {st.grids} grids of lines "
            f"z . e_j - gamma_j = k, e_j at 360/{self.n} degree steps; every crossing of two lines is a rhomb",
            f"offsets gamma = {', '.join(f'{g:g}' for g in self.gamma)} (sum {round(math.fsum(self.gamma), 10):g})"
            + (f", perturbed by up to {PERTURBATION:g}" if self.singular == "perturb" else ""),
            f"rhomb kinds and frequencies (from the cut-and-project window): {kinds}",
            f"{st.density:.6f} tiles per unit area; edges in {2 * st.grids} directions",
        ]
        return "\n".join(lines)

    def options_help(self) -> str:
        return "\n".join([
            f"--set n=N              rotational order, 4..{MAX_N} (5 Penrose, 8 Ammann-Beenker)",
            "--set gamma=G[,G...]   the N grid offsets, or one for every grid (default: generic, sum 0)",
            "--set singular=MODE    refuse (default) or perturb singular offsets (three lines through a point)",
            "--region x0,y0,x1,y1   any box, anywhere: the tiles come from the grid lines crossing it",
        ])

    def configure(self, **options: Any) -> QuasiperiodicTiling:
        """A new tiling with ``n``, ``gamma`` and/or ``singular`` changed (values may be the
        command line's text); the name and title stay when n and gamma do."""
        n = options.pop("n", None)
        gamma = options.pop("gamma", None)
        singular = options.pop("singular", self.singular)
        if options:
            raise ParameterError(
                f"{self.name} does not take option(s) {', '.join(sorted(options))}; valid: n, gamma, singular"
            )
        n = self.n if n is None else check_order(n)
        if gamma is None and n == self.n:
            gamma = self.gamma
        out = QuasiperiodicTiling(n, gamma, str(singular))
        if n == self.n and np.array_equal(out.gamma, self.gamma):
            out.name, out.title = self.name, self.title
        return out

    def spec(self) -> dict[str, Any]:
        out: dict[str, Any] = {"n": self.n, "gamma": [float(g) for g in self.gamma]}
        if self.singular != "refuse":
            out["singular"] = self.singular
        if self.name != f"multigrid-{self.n}":
            out["name"] = self.name
        if self.title:
            out["title"] = self.title
        return out

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> QuasiperiodicTiling:
        if not isinstance(spec, Mapping):
            raise ParseError(f"quasiperiodic spec must be a table, got {type(spec).__name__}")
        unknown = set(spec) - {"n", "gamma", "singular", "name", "title"}
        if unknown:
            raise ParseError(f"quasiperiodic spec has unknown key(s) {', '.join(sorted(map(str, unknown)))}; "
                             "valid: n, gamma, singular, name, title")
        return cls(spec.get("n", 5), spec.get("gamma"), str(spec.get("singular", "refuse")),
                   name=str(spec.get("name", "")), title=str(spec.get("title", "")))


def _clear_cut(centre: np.ndarray, at: float) -> float:
    """``at`` moved down until no centre lies within float noise of it (1e-7, more far from
    the origin), so that two bands computing the same centres agree on which side each is."""
    eps = 1e-7 + 1e-14 * abs(at)
    while np.any(np.abs(centre - at) < eps):
        at -= 3 * eps
    return at



def _is_box(geom: BaseGeometry) -> bool:
    """Whether the region is its bounding box (then no clip is needed)."""
    x0, y0, x1, y1 = geom.bounds
    return bool(geom.area >= (x1 - x0) * (y1 - y0) * (1 - 1e-12))
