"""The Wang family (§6.2, §7.5): tile sets as data, fills for graphics, exact solvers.

A :class:`WangTiling` is a tile set plus a way to fill regions: the random-access hash fill
(Lagae and Dutré) for sets with a tile for every corner/edge colouring, Cohen et al.'s
scanline fill for complete sets, repetition of a small torus unit for sets that have one,
and the exact SAT solver for every other set (an aperiodic set tiles any finite rectangle,
but only a search finds how). The catalogue
records one entry per shipped set (catalogue/wang/*.wang) and the ``wang-periodicity``
search runs Wang's procedure on a set and stores what it showed.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry.base import BaseGeometry

import tilekit
from tilekit.errors import GeometryError, ParameterError, ParseError, SolverLimit
from tilekit.geometry import as_region
from tilekit.plugins import CatalogueRecord, ChunkResult, Family, Search, SearchParam
from tilekit.plugins.wang.check import check_grid, grid_mismatches, patch_mismatches
from tilekit.plugins.wang.fill import (
    grid_to_patch,
    random_access_fill,
    random_access_tiles,
    scanline_fill,
    supports_random_access,
)
from tilekit.plugins.wang.render import load_texture, wang_svg, write_wang_image
from tilekit.plugins.wang.sat import SolveResult, sat_solve
from tilekit.plugins.wang.solve import (
    WangProcedureResult,
    backtrack_solve,
    builder_solve,
    solve,
    wang_procedure,
)
from tilekit.plugins.wang.tileset import (
    WangTileSet,
    builtin_sets,
    from_corners,
    from_tuples,
    get_tileset,
    load_tileset,
    parse_tileset,
    tile_prototiles,
)
from tilekit.tiling import Patch, Prototile, Tiling

__all__ = [
    "FILL_METHODS",
    "SolveResult",
    "WangProcedureResult",
    "WangTileSet",
    "WangTiling",
    "backtrack_solve",
    "builder_solve",
    "builtin_sets",
    "check_grid",
    "from_corners",
    "from_tuples",
    "get_tileset",
    "grid_mismatches",
    "grid_to_patch",
    "load_texture",
    "load_tileset",
    "parse_tileset",
    "patch_mismatches",
    "periodic_unit",
    "random_access_fill",
    "random_access_tiles",
    "record_for",
    "sat_solve",
    "scanline_fill",
    "set_facts",
    "solve",
    "wang_procedure",
    "wang_svg",
    "write_wang_image",
]

FAMILY = "wang"
#: How WangTiling.patch fills a region: 'auto' picks the first that applies of
#: random-access, scanline, periodic (a torus unit of side <= BUILD_MAX_M exists), solver.
FILL_METHODS = ("auto", "random-access", "scanline", "periodic", "solver")
#: Wang's procedure runs up to this m when records are built (cheap for every shipped set).
BUILD_MAX_M = 6
#: Largest region (in tiles) the exact solver is asked to fill by ``patch``.
MAX_SOLVER_TILES = 10_000


# ---------------------------------------------------------------------- the tiling


class WangTiling(Tiling):
    """A Wang tile set with a fill method; ``patch(region)`` covers the lattice squares that
    meet the region (unit squares with corners at integer points)."""

    family = FAMILY

    def __init__(self, tileset: WangTileSet, seed: int = 0, method: str = "auto", time_limit: float = 60.0) -> None:
        if method not in FILL_METHODS:
            raise ParameterError(f"Wang fill method {method!r} is not one of {', '.join(FILL_METHODS)}")
        self.tileset = tileset
        self.name = tileset.name
        self.seed = int(seed)
        self.method = method
        self.time_limit = float(time_limit)

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
        if periodic_unit(self.tileset) is not None:
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
            unit = periodic_unit(self.tileset)
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

    def default_region(self) -> BaseGeometry:
        return shapely.box(0, 0, 12, 8)

    def spec(self) -> dict[str, Any]:
        out: dict[str, Any] = {"set": self.tileset.name, "seed": self.seed, "method": self.method}
        builtin = builtin_sets().get(self.tileset.name)
        if builtin is not self.tileset:
            out["tileset"] = self.tileset.to_json()
        return out

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> WangTiling:
        """Rebuild from :meth:`spec` output: a shipped set by name, or an inline ``tileset``."""
        if not isinstance(spec, Mapping) or ("set" not in spec and "tileset" not in spec):
            raise ParseError(f"Wang spec must name a 'set' or give a 'tileset', got {spec!r}")
        ts = WangTileSet.from_json(spec["tileset"]) if "tileset" in spec else get_tileset(str(spec["set"]))
        try:
            seed = int(spec.get("seed", 0))
        except (TypeError, ValueError):
            raise ParseError(f"Wang spec seed {spec.get('seed')!r} is not an integer") from None
        return cls(ts, seed=seed, method=str(spec.get("method", "auto")))

    def properties(self) -> dict[str, Any]:
        return dict(set_facts(self.tileset))

    def describe(self) -> str:
        ts = self.tileset
        head = f"{len(ts)} {ts.kind} tiles; patches fill by {self.fill_method()} (seed {self.seed})"
        return head + "\n" + ts.to_text().rstrip()

    def configure(self, **options: Any) -> WangTiling:
        """Options: ``seed`` (int), ``method`` (one of FILL_METHODS), ``time_limit`` (s)."""
        seed, method, limit = self.seed, self.method, self.time_limit
        for key, value in options.items():
            if value is None or (key in ("params", "edges") and not value):
                continue  # the CLI passes empty defaults for options this family ignores
            if key == "seed":
                try:
                    seed = int(value)
                except (TypeError, ValueError):
                    raise ParameterError(f"seed={value!r} is not an integer") from None
            elif key == "method":
                method = str(value)
            elif key == "time_limit":
                try:
                    limit = float(value)
                except (TypeError, ValueError):
                    raise ParameterError(f"time_limit={value!r} is not a number of seconds") from None
            else:
                raise ParameterError(
                    f"Wang tilings take the options seed, method and time_limit, not {key!r}"
                )
        return WangTiling(self.tileset, seed=seed, method=method, time_limit=limit)


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
        "known_aperiodic": ts.known_aperiodic,
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
            props["tiles_plane"] = True
        elif procedure.outcome == "does_not_tile":
            props["does_not_tile_beyond"] = (procedure.m or 1) - 1
            props["periodic"] = False
            props["tiles_plane"] = False
    return props


@cache
def _build_time_procedure(name: str) -> WangProcedureResult:
    return wang_procedure(get_tileset(name), BUILD_MAX_M)


def periodic_unit(ts: WangTileSet) -> np.ndarray | None:
    """An m x m torus tiling (m <= BUILD_MAX_M) of the set, or None if Wang's procedure found
    none that small (cached: the build-time run for shipped sets, else one run per set)."""
    if builtin_sets().get(ts.name) is ts:
        proc = _build_time_procedure(ts.name)
    else:
        proc = ts.__dict__.get("_procedure")
        if proc is None:
            try:
                proc = wang_procedure(ts, BUILD_MAX_M, time_limit=10.0)
            except SolverLimit:
                proc = WangProcedureResult(ts.name, BUILD_MAX_M, "no_answer", None, None)
            ts.__dict__["_procedure"] = proc
    return proc.unit if proc.outcome == "periodic" else None


def set_facts(ts: WangTileSet) -> dict[str, Any]:
    """Properties of a set, with Wang's procedure run cheaply (m <= BUILD_MAX_M) for
    shipped sets; other sets report only what needs no search."""
    proc = _build_time_procedure(ts.name) if builtin_sets().get(ts.name) is ts else None
    return _facts(ts, proc)


def record_for(ts: WangTileSet, procedure: WangProcedureResult | None = None) -> CatalogueRecord:
    """The catalogue record of a set (``procedure``: a run of Wang's procedure to report)."""
    tiling = WangTiling(ts)
    props = _facts(ts, procedure) if procedure is not None else set_facts(ts)
    return CatalogueRecord(
        family=FAMILY,
        name=ts.name,
        spec=tiling.spec(),
        title=ts.title or f"Wang tile set {ts.name}",
        properties=props,
        aliases=list(ts.aliases),
    )


# ---------------------------------------------------------------------- the search


def _search_set(params: Mapping[str, Any]) -> WangTileSet:
    name = params.get("set")
    if not name:
        raise ParameterError("wang-periodicity needs --set NAME (a shipped set or a .wang file)")
    name = str(name)
    if name.endswith(".wang") and Path(name).exists():
        return load_tileset(name)
    return get_tileset(name)


def _max_m(params: Mapping[str, Any]) -> int:
    raw = params.get("max_m", 8)
    try:
        value = int(8 if raw is None else raw)
    except (TypeError, ValueError):
        raise ParameterError(f"--max-m {raw!r} is not an integer") from None
    if value < 1:
        raise ParameterError(f"--max-m {value} must be at least 1")
    return value


def periodicity_chunks(params: Mapping[str, Any]) -> list[dict[str, Any]]:
    """One chunk: Wang's procedure stops at its first answer, so m values are not independent."""
    ts = _search_set(params)
    return [{"set": ts.name, "from_m": 1, "to_m": _max_m(params)}]


def periodicity_run_chunk(params: Mapping[str, Any], chunk: Mapping[str, Any]) -> ChunkResult:
    """Run Wang's procedure on the chunk's m range; return its report and the updated record."""
    ts = _search_set(params)
    method = str(params.get("method") or "sat")
    limit = params.get("time_limit")
    result = wang_procedure(
        ts, int(chunk["to_m"]), method=method, time_limit=None if limit in (None, "") else float(limit),
        start_m=int(chunk.get("from_m", 1)),
    )
    return ChunkResult(results=[result.to_json()], records=[record_for(ts, result)])


def periodicity_summary(params: Mapping[str, Any], results: list[dict[str, Any]]) -> dict[str, Any]:
    if not results:
        return {"outcome": "not run"}
    last = results[-1]
    return {"outcome": last["outcome"], "m": last["m"], "statement": last["statement"]}


PERIODICITY = Search(
    name="wang-periodicity",
    summary="Wang's procedure (§6.2): look for an m x m torus or an untileable m x m square, m = 1..max_m",
    family=FAMILY,
    params=(
        SearchParam("set", str, None, "a shipped Wang set name or a .wang file", required=True),
        SearchParam("max_m", int, 8, "largest m to try", min=1, max=64),
        SearchParam("method", str, "sat", "solver for the tori and squares", choices=("sat", "builder", "backtrack")),
        SearchParam("time_limit", float, None, "seconds per solver call (none: no limit)", min=0.01, max=86_400.0),
    ),
    chunks=periodicity_chunks,
    run_chunk=periodicity_run_chunk,
    summarize=periodicity_summary,
)


# ---------------------------------------------------------------------- hooks


def _from_file(path: str) -> WangTiling:
    return WangTiling(load_tileset(path))


@tilekit.hookimpl
def tilekit_families() -> list[Family]:
    return [
        Family(
            name=FAMILY,
            summary="Wang tiles: edge- or corner-coloured unit squares placed by translation (§6.2, §7.5)",
            from_spec=WangTiling.from_spec,
            description=(
                "Tile sets live in catalogue/wang/*.wang. Complete sets fill by Cohen et al.'s "
                "scanline method, corner sets by hashed random access, others by a SAT solver. "
                "Options: seed=N, method=auto|random-access|scanline|solver."
            ),
            from_file=_from_file,
        )
    ]


@tilekit.hookimpl
def tilekit_catalogue_records() -> list[CatalogueRecord]:
    return [record_for(ts) for ts in builtin_sets().values()]


@tilekit.hookimpl
def tilekit_searches() -> list[Search]:
    return [PERIODICITY]


@tilekit.hookimpl
def tilekit_cli_commands(cli: Any) -> None:
    from tilekit.plugins.wang.cli import wang_group

    cli.add_command(wang_group)
