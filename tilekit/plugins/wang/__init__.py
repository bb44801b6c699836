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
from typing import TYPE_CHECKING, Any

import tilekit
from tilekit.errors import ParameterError
from tilekit.lazy import lazy_exports
from tilekit.limits import DEFAULT_SOLVER_SECONDS
from tilekit.plugins import CatalogueRecord, ChunkResult, Family, Sampler, Search, SearchParam

if TYPE_CHECKING:  # pragma: no cover
    from tilekit.plugins.wang.solve import WangProcedureResult
    from tilekit.plugins.wang.tileset import WangTileSet
    from tilekit.plugins.wang.tiling import WangTiling

#: The family's name (tilekit.plugins.wang.tiling.FAMILY, which a test keeps equal): spelled
#: here so that loading the plugin does not import the tiling module.
FAMILY = "wang"

#: Public names, imported on first use (PEP 562): measured start-up cost, the fills, solvers
#: and tiling load NumPy, shapely, the builder and python-sat (about 0.5-1 s of
#: `python -X importtime` on the 2-core dev box), which every `tilekit` command would pay when
#: pluggy loads this plugin.
_LAZY = {
    "check_grid": "tilekit.plugins.wang.check",
    "grid_mismatches": "tilekit.plugins.wang.check",
    "patch_mismatches": "tilekit.plugins.wang.check",
    "grid_to_patch": "tilekit.plugins.wang.fill",
    "random_access_fill": "tilekit.plugins.wang.fill",
    "random_access_tiles": "tilekit.plugins.wang.fill",
    "scanline_fill": "tilekit.plugins.wang.fill",
    "load_texture": "tilekit.plugins.wang.render",
    "wang_svg": "tilekit.plugins.wang.render",
    "write_wang_image": "tilekit.plugins.wang.render",
    "SolveResult": "tilekit.plugins.wang.sat",
    "sat_solve": "tilekit.plugins.wang.sat",
    "WangProcedureResult": "tilekit.plugins.wang.solve",
    "backtrack_solve": "tilekit.plugins.wang.solve",
    "builder_solve": "tilekit.plugins.wang.solve",
    "solve": "tilekit.plugins.wang.solve",
    "wang_procedure": "tilekit.plugins.wang.solve",
    "WangTileSet": "tilekit.plugins.wang.tileset",
    "builtin_sets": "tilekit.plugins.wang.tileset",
    "from_corners": "tilekit.plugins.wang.tileset",
    "from_tuples": "tilekit.plugins.wang.tileset",
    "get_tileset": "tilekit.plugins.wang.tileset",
    "load_tileset": "tilekit.plugins.wang.tileset",
    "parse_tileset": "tilekit.plugins.wang.tileset",
    "FILL_METHODS": "tilekit.plugins.wang.tiling",
    "WangTiling": "tilekit.plugins.wang.tiling",
    "periodic_unit": "tilekit.plugins.wang.tiling",
    "set_facts": "tilekit.plugins.wang.tiling",
    "TextureTiles": "tilekit.plugins.wang.texture",
    "load_texture_tiles": "tilekit.plugins.wang.texture",
    "make_texture_tiles": "tilekit.plugins.wang.texture",
    "render_texture": "tilekit.plugins.wang.synth",
    "texture_rows": "tilekit.plugins.wang.synth",
    "texture_window": "tilekit.plugins.wang.synth",
    "write_texture": "tilekit.plugins.wang.synth",
    "scatter_points": "tilekit.plugins.wang.scatter",
}
__getattr__, __dir__ = lazy_exports(__name__, _LAZY, pinned=("solve",))


__all__ = [
    "FILL_METHODS",
    "SolveResult",
    "TextureTiles",
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
    "load_texture_tiles",
    "load_tileset",
    "make_texture_tiles",
    "parse_tileset",
    "patch_mismatches",
    "periodic_unit",
    "random_access_fill",
    "random_access_tiles",
    "record_for",
    "render_texture",
    "sat_solve",
    "scanline_fill",
    "scatter_points",
    "set_facts",
    "solve",
    "texture_rows",
    "texture_window",
    "wang_procedure",
    "wang_svg",
    "write_texture",
    "write_wang_image",
]

def record_for(ts: WangTileSet, procedure: WangProcedureResult | None = None) -> CatalogueRecord:
    """The catalogue record of a set (``procedure``: a run of Wang's procedure to report)."""
    # measured start-up cost: the tiling module (NumPy, shapely, the solvers; ~0.5-1 s)
    from tilekit.plugins.wang.tiling import WangTiling, _facts, set_facts

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
    # measured start-up cost: the tile-set module loads NumPy (~0.2 s)
    from tilekit.plugins.wang.tileset import get_tileset, load_tileset

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
    # measured start-up cost: the solvers load NumPy, the builder and python-sat (~0.5-1 s)
    from tilekit.plugins.wang.solve import wang_procedure

    ts = _search_set(params)
    method = str(params.get("method") or "sat")
    limit = params.get("time_limit")
    result = wang_procedure(
        ts, int(chunk["to_m"]), method=method, time_limit=DEFAULT_SOLVER_SECONDS if limit in (None, "") else float(limit),
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
        SearchParam("time_limit", float, DEFAULT_SOLVER_SECONDS, "CPU seconds per solver call (SAT, builder or backtrack)", min=0.01, max=86_400.0),
    ),
    chunks=periodicity_chunks,
    run_chunk=periodicity_run_chunk,
    summarize=periodicity_summary,
)


# ---------------------------------------------------------------------- hooks


def _from_file(path: str) -> WangTiling:
    # measured start-up cost: the tiling module (NumPy, shapely, the solvers; ~0.5-1 s)
    from tilekit.plugins.wang.tileset import load_tileset
    from tilekit.plugins.wang.tiling import WangTiling  # start-up cost: as above

    return WangTiling(load_tileset(path))


def _from_spec(spec: Mapping[str, Any]) -> WangTiling:
    # measured start-up cost: as in _from_file
    from tilekit.plugins.wang.tiling import WangTiling

    return WangTiling.from_spec(spec)


@tilekit.hookimpl
def tilekit_families() -> list[Family]:
    return [
        Family(
            name=FAMILY,
            summary="Wang tiles: edge- or corner-coloured unit squares placed by translation (§6.2, §7.5)",
            from_spec=_from_spec,
            description=(
                "Tile sets live in catalogue/wang/*.wang. Complete sets fill by Cohen et al.'s "
                "scanline method, corner sets by hashed random access, others by a SAT solver. "
                "Options: seed=N, method=auto|random-access|scanline|solver. Textures from an example "
                "image: tilekit wang texture / synth (docs/families/wang-textures.md)."
            ),
            from_file=_from_file,
        )
    ]


@tilekit.hookimpl
def tilekit_catalogue_records() -> list[CatalogueRecord]:
    # measured start-up cost: the tile sets load NumPy (records are built only when seeding)
    from tilekit.plugins.wang.tileset import builtin_sets

    return [record_for(ts) for ts in builtin_sets().values()]


@tilekit.hookimpl
def tilekit_searches() -> list[Search]:
    return [PERIODICITY]


@tilekit.hookimpl
def tilekit_cli_commands(cli: Any) -> None:
    # wang/cli.py imports only click and the core's cheap modules at its top (its commands
    # import the library when they run); measured start-up cost: a few milliseconds
    from tilekit.plugins.wang.cli import wang_group

    cli.add_command(wang_group)


@tilekit.hookimpl
def tilekit_claim_file(path: str) -> str | None:
    """Wang tile sets are ``.wang`` files."""
    return FAMILY if Path(path).suffix.lower() == ".wang" else None


def _sample_candidates(density: Any, tau_lo: float, tau_hi: float, seed: int = 0) -> Any:
    # measured start-up cost: the sampler loads NumPy and the fills, when it runs
    from tilekit.plugins.wang.sampling import candidates

    return candidates(density, tau_lo, tau_hi, seed)


@tilekit.hookimpl
def tilekit_samplers() -> list[Sampler]:
    """Recursive corner Wang tiles with progressive point sets (§7.4, §7.5)."""
    return [
        Sampler("wang", "recursive corner Wang tiles with progressive point sets, points kept by rank",
                FAMILY, _sample_candidates,
                "J. Kopf, D. Cohen-Or, O. Deussen, D. Lischinski, Recursive Wang tiles for real-time blue "
                "noise, SIGGRAPH 2006 (here on Lagae and Dutre's corner tiles)"),
    ]
