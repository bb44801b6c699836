"""The Wang family's tiling: a tile set filling any region (random access, scanline, a
periodic torus unit, or an exact solver), and the facts the catalogue stores about a set."""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from functools import cache
from typing import Any

import numpy as np
import shapely
from shapely.geometry.base import BaseGeometry

from tilekit.errors import GeometryError, ParameterError, ParseError, SolverLimit
from tilekit.geometry import as_region
from tilekit.limits import DEFAULT_SOLVER_SECONDS, MAX_SOLVER_SECONDS
from tilekit.plugins.wang.fill import (
    grid_to_patch,
    random_access_fill,
    scanline_fill,
    supports_random_access,
)
from tilekit.plugins.wang.render import wang_svg
from tilekit.plugins.wang.sat import sat_solve
from tilekit.plugins.wang.solve import (
    WangProcedureResult,
    wang_procedure,
)
from tilekit.plugins.wang.tileset import (
    WangTileSet,
    builtin_sets,
    get_tileset,
    tile_prototiles,
)
from tilekit.schema import Field, check, shown
from tilekit.tiling import Patch, Prototile, Tiling

FAMILY = "wang"
#: How WangTiling.patch fills a region: 'auto' picks the first that applies of
#: random-access, scanline, periodic (a torus unit of side <= BUILD_MAX_M exists), solver.
FILL_METHODS = ("auto", "random-access", "scanline", "periodic", "solver")
#: Wang's procedure runs up to this m when records are built (cheap for every shipped set).
BUILD_MAX_M = 6
#: Seconds ``method='auto'`` spends looking for a small torus unit of a user's set.
PERIODIC_PROBE_SECONDS = 10.0
#: Largest region (in tiles) the exact solver is asked to fill by ``patch``.
MAX_SOLVER_TILES = 10_000


# ---------------------------------------------------------------------- the tiling


class WangTiling(Tiling):
    """A Wang tile set with a fill method; ``patch(region)`` covers the lattice squares that
    meet the region (unit squares with corners at integer points)."""

    family = FAMILY

    def __init__(self, tileset: WangTileSet, seed: int = 0, method: str = "auto",
                 time_limit: float = DEFAULT_SOLVER_SECONDS) -> None:
        if method not in FILL_METHODS:
            raise ParameterError(f"Wang fill method {shown(method)} is not one of {', '.join(FILL_METHODS)}")
        self.tileset = tileset
        self.name = tileset.name
        self.seed = _seed(seed)
        self.method = method
        self.time_limit = _seconds(time_limit)

    # -- Tiling API ------------------------------------------------------------
    @property
    def prototiles(self) -> list[Prototile]:
        return tile_prototiles(self.tileset)

    def fill_method(self) -> str:
        """The method ``patch`` uses ('auto' resolved for this set)."""
        if self.method != "auto":
            return self.method
        if supports_random_access(self.tileset):
            return "random-access"
        if self.tileset.complete:
            return "scanline"
        if periodic_unit(self.tileset, min(PERIODIC_PROBE_SECONDS, self.time_limit)) is not None:
            return "periodic"
        return "solver"

    def grid(self, x0: int, y0: int, rows: int, cols: int) -> np.ndarray:
        """The tiles of the lattice squares x0 <= x < x0 + cols, y0 <= y < y0 + rows (row 0
        north), by this tiling's fill method."""
        method = self.fill_method()
        if method == "random-access":
            return random_access_fill(self.tileset, rows, cols, x0, y0, seed=self.seed)
        if method == "scanline":
            # one seed per (tiling seed, region origin): the same region gives the same patch
            seq = np.random.SeedSequence([self.seed & 0xFFFFFFFF, x0 & 0xFFFFFFFF, y0 & 0xFFFFFFFF])
            return scanline_fill(self.tileset, rows, cols, seed=int(seq.generate_state(1)[0]))
        if method == "periodic":
            unit = periodic_unit(self.tileset, min(PERIODIC_PROBE_SECONDS, self.time_limit))
            if unit is None:
                raise ParameterError(
                    f"set {self.tileset.name!r} has no torus tiling of side <= {BUILD_MAX_M}; "
                    "use method='solver' (or 'auto')"
                )
            # lattice square (x, y) takes unit[(-y) mod m, x mod m]: rows run southwards, and
            # the unit is a torus, so the pattern is the same whatever the region
            m = unit.shape[0]
            ys = y0 + rows - 1 - np.arange(rows)
            xs = x0 + np.arange(cols)
            return unit[np.ix_((-ys) % m, xs % m)]
        if rows * cols > MAX_SOLVER_TILES:
            raise ParameterError(
                f"a {rows} x {cols} region is too large for the exact solver (limit {MAX_SOLVER_TILES} tiles); "
                f"set {self.tileset.name!r} has no stochastic or random-access fill"
            )
        result = sat_solve(self.tileset, rows, cols, time_limit=self.time_limit)
        if not result.tiles:
            raise GeometryError(
                f"set {self.tileset.name!r} does not tile a {rows} x {cols} rectangle (proved by SAT), "
                "so no patch of this region exists"
            )
        return result.grid

    def patch(self, region: Any) -> Patch:
        reg = as_region(region)
        x0, y0, x1, y1 = reg.bounds
        cx0, cy0 = math.floor(x0 + 1e-9), math.floor(y0 + 1e-9)
        cx1, cy1 = math.ceil(x1 - 1e-9), math.ceil(y1 - 1e-9)
        cols, rows = max(1, cx1 - cx0), max(1, cy1 - cy0)
        patch = grid_to_patch(self.grid(cx0, cy0, rows, cols), self.tileset, cx0, cy0)
        bx0, by0, bx1, by1 = reg.bounds
        is_box = abs(reg.area - (bx1 - bx0) * (by1 - by0)) <= 1e-12 * max(1.0, reg.area)
        return patch if is_box else patch.clip(reg)

    def estimate_tiles(self, region: Any = None) -> float:
        """The lattice squares meeting the region's box (one tile each)."""
        reg = self.default_region() if region is None else as_region(region)
        x0, y0, x1, y1 = reg.bounds
        return float((math.ceil(x1 - 1e-9) - math.floor(x0 + 1e-9)) * (math.ceil(y1 - 1e-9) - math.floor(y0 + 1e-9)))

    def default_region(self) -> BaseGeometry:
        return shapely.box(0, 0, 12, 8)

    def render_svg(self, patch: Patch, **options: Any) -> str:
        """The picture ``tilekit wang render`` draws (each side a triangle of its edge colour),
        for a patch of whole lattice squares; other patches are drawn as plain squares."""
        t = patch.transform
        if not len(patch) or not np.allclose(t[:, :2, 2], np.round(t[:, :2, 2])) or options.get("labels"):
            return super().render_svg(patch, **options)
        xy = np.round(t[:, :2, 2]).astype(np.int64)
        x0, y0 = xy.min(axis=0)
        cols, rows = (xy.max(axis=0) - (x0, y0) + 1).tolist()
        if rows * cols != len(patch):
            return super().render_svg(patch, **options)
        grid = np.full((rows, cols), -1, dtype=np.int64)
        grid[rows - 1 - (xy[:, 1] - y0), xy[:, 0] - x0] = patch.prototile
        if (grid < 0).any():
            return super().render_svg(patch, **options)
        width, height = options.get("width"), options.get("height")
        size = int(options.get("size", 800))
        if width is not None:
            size = int(width * max(rows, cols) / cols)
        elif height is not None:
            size = int(height * max(rows, cols) / rows)
        return wang_svg(grid, self.tileset, size=size, stroke=str(options.get("stroke", "#222")))

    def spec(self) -> dict[str, Any]:
        out: dict[str, Any] = {"set": self.tileset.name, "seed": self.seed, "method": self.method}
        builtin = builtin_sets().get(self.tileset.name)
        if builtin is not self.tileset:
            out["tileset"] = self.tileset.to_json()
        return out

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> WangTiling:
        """Rebuild from :meth:`spec` output: a shipped set by name, or an inline ``tileset``
        (checked against :data:`SPEC`)."""
        if isinstance(spec, Mapping):
            spec = check(SPEC, {k: v for k, v in spec.items() if v is not None}, "Wang spec")
        if not isinstance(spec, Mapping) or ("set" not in spec and "tileset" not in spec):
            raise ParseError(f"Wang spec must name a 'set' or give a 'tileset', got {shown(spec)}")
        ts = WangTileSet.from_json(spec["tileset"]) if "tileset" in spec else get_tileset(spec["set"])
        return cls(ts, seed=spec.get("seed", 0), method=spec.get("method", "auto"),
                   time_limit=spec.get("time_limit", DEFAULT_SOLVER_SECONDS))

    def properties(self) -> dict[str, Any]:
        return dict(set_facts(self.tileset))

    def describe(self) -> str:
        ts = self.tileset
        head = f"{len(ts)} {ts.kind} tiles; patches fill by {self.fill_method()} (seed {self.seed})"
        return head + "\n" + ts.to_text().rstrip()

    def options_help(self) -> str:
        return "\n".join([
            "--set seed=N           the fill's random seed",
            "--set method=M         " + ", ".join(FILL_METHODS),
            f"--set time_limit=S     CPU seconds for the exact (SAT) solver (default {DEFAULT_SOLVER_SECONDS:g})",
        ])

    def configure(self, **options: Any) -> WangTiling:
        """Options: ``seed`` (int), ``method`` (one of FILL_METHODS), ``time_limit`` (s)."""
        seed, method, limit = self.seed, self.method, self.time_limit
        for key, value in options.items():
            if value is None or (key in ("params", "edges") and not value):
                continue  # the CLI passes empty defaults for options this family ignores
            if key == "seed":
                seed = _seed(value.strip() if isinstance(value, str) else value)
            elif key == "method":
                method = str(value)
            elif key == "time_limit":
                limit = _seconds(value)
            else:
                raise ParameterError(
                    f"Wang tilings take the options seed, method and time_limit, not {key!r}"
                )
        return WangTiling(self.tileset, seed=seed, method=method, time_limit=limit)


#: A Wang tiling's spec (what :meth:`WangTiling.spec` writes).
SPEC = Field("table", fields={
    "set": Field("str"),
    "tileset": Field("table"),
    "seed": Field("int", range=(-2**63, 2**63 - 1)),
    "method": Field("str", choices=FILL_METHODS),
    "time_limit": Field("number", range=(1e-3, MAX_SOLVER_SECONDS)),
})


def _seed(value: Any) -> int:
    """A fill seed: an integer (or its decimal text) within int64, else a ParameterError."""
    if isinstance(value, str) and value.lstrip("-").isascii() and value.lstrip("-").isdigit() and len(value) <= 20:
        value = int(value)
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or not -2**63 <= value < 2**63:
        raise ParameterError(f"seed={shown(value)} is not an integer (within ±2**63)")
    return int(value)


def _seconds(value: Any) -> float:
    """A time limit in seconds: a finite number in 0.001 .. MAX_SOLVER_SECONDS."""
    try:
        seconds = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(f"time_limit={shown(value)} is not a number of seconds") from None
    if not 1e-3 <= seconds <= MAX_SOLVER_SECONDS:  # false for nan too
        raise ParameterError(f"time_limit={shown(value)} must be a number of seconds in 0.001..{MAX_SOLVER_SECONDS:g}")
    return seconds


# ---------------------------------------------------------------------- facts and records


def _facts(ts: WangTileSet, procedure: WangProcedureResult | None) -> dict[str, Any]:
    """The catalogue properties of a set, given what Wang's procedure showed (if run)."""
    colours = len(ts.corner_colours) if ts.corners is not None else len(ts.colours)
    props: dict[str, Any] = {
        "tiles": len(ts),
        "k_hedral": len(ts),
        "kind": ts.kind,
        "colours": colours,
        "horizontal_colours": len(ts.horizontal_colours),
        "vertical_colours": len(ts.vertical_colours),
        "complete": ts.complete,
        "stochastic": ts.stochastic,
        "random_access": supports_random_access(ts),
        "aperiodic": True if ts.known_aperiodic else None,  # false once a periodic tiling is found
        "sides": [4],
        "aperiodic_source": ts.source if ts.known_aperiodic else None,
        "source": ts.source or None,
        "periodic_unit": None,
        "does_not_tile_beyond": None,
        "tiles_plane": True if ts.known_aperiodic else None,
        "periodic": False if ts.known_aperiodic else None,
        "edge_to_edge": True,
    }
    if procedure is not None:
        props["wang_searched_up_to"] = procedure.m if procedure.m is not None else procedure.max_m
        props["wang_outcome"] = procedure.outcome
        if procedure.outcome == "periodic":
            props["periodic_unit"] = procedure.m
            props["periodic"] = True
            props["aperiodic"] = False
            props["tiles_plane"] = True
        elif procedure.outcome == "does_not_tile":
            props["does_not_tile_beyond"] = (procedure.m or 1) - 1
            props["periodic"] = False
            props["aperiodic"] = False  # tiles nothing, so not an aperiodic set
            props["tiles_plane"] = False
    return props


@cache
def _build_time_procedure(name: str) -> WangProcedureResult:
    return wang_procedure(get_tileset(name), BUILD_MAX_M)


def periodic_unit(ts: WangTileSet, seconds: float = PERIODIC_PROBE_SECONDS) -> np.ndarray | None:
    """An m x m torus tiling (m <= BUILD_MAX_M) of the set, or None if Wang's procedure found
    none that small within ``seconds`` (cached: the build-time run for shipped sets, else one
    run per set)."""
    if builtin_sets().get(ts.name) is ts:
        proc = _build_time_procedure(ts.name)
    else:
        proc = ts.__dict__.get("_procedure")
        if proc is None:
            try:
                proc = wang_procedure(ts, BUILD_MAX_M, time_limit=None, total_limit=seconds)
            except SolverLimit:
                proc = WangProcedureResult(ts.name, BUILD_MAX_M, "no_answer", None, None)
            ts.__dict__["_procedure"] = proc
    return proc.unit if proc.outcome == "periodic" else None


def set_facts(ts: WangTileSet) -> dict[str, Any]:
    """Properties of a set, with Wang's procedure run cheaply (m <= BUILD_MAX_M) for
    shipped sets; other sets report only what needs no search."""
    proc = _build_time_procedure(ts.name) if builtin_sets().get(ts.name) is ts else None
    return _facts(ts, proc)
