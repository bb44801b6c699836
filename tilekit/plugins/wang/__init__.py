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

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import tilekit
from tilekit.errors import ParameterError
from tilekit.plugins import CatalogueRecord, ChunkResult, Family, Search, SearchParam
from tilekit.plugins.wang.check import check_grid, grid_mismatches, patch_mismatches
from tilekit.plugins.wang.cli import wang_group
from tilekit.plugins.wang.fill import (
    grid_to_patch,
    random_access_fill,
    random_access_tiles,
    scanline_fill,
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
)
from tilekit.plugins.wang.tiling import (
    FAMILY,
    FILL_METHODS,
    WangTiling,
    _facts,
    periodic_unit,
    set_facts,
)

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
    cli.add_command(wang_group)


@tilekit.hookimpl
def tilekit_claim_file(path: str) -> str | None:
    """Wang tile sets are ``.wang`` files."""
    return FAMILY if Path(path).suffix.lower() == ".wang" else None
