"""The ``polyomino-classify`` search: :func:`classify.classify` over every free polyform of one
grid (``--grid square|hex|iamond``), chunked like the enumeration (Redelmeier prefixes), rows
into the polyominoes table with their ``grid``; or, with ``--codes``, over the forms named
(one chunk each: the ones an earlier run left undecided, again with larger bounds)."""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from tilekit.errors import ParameterError
from tilekit.lattice import (
    SQUARE,
    Grid,
    count_fixed,
    encode,
    enumerate_free,
    holes,
    symmetry_from_mask,
)
from tilekit.plugins import ChunkResult, Search, SearchParam
from tilekit.plugins.polyomino.classify import (
    CLASSIFIED_GRIDS,
    CLASSIFY_SOLVER,
    DEFAULT_TORUS_TILES,
    MAX_TORUS_TILES,
    check_bounds,
    check_grid,
    check_torus_cost,
    classify,
)
from tilekit.plugins.polyomino.heesch import MAX_LEVEL_LIMIT
from tilekit.plugins.polyomino.isohedral import analyse, analyse_many
from tilekit.plugins.polyomino.model import Polyomino, grid_of, make_row
from tilekit.plugins.polyomino.search import prefix_chunks, prefix_depth
from tilekit.sat import SAT_SOLVERS, check_solver

#: The classification stores rows up to this size (the enumeration's own limit).
MAX_CLASSIFY = 14
#: Other grids' largest size (Kaplan's tables go to 24-iamonds); the estimate of the forms
#: (:func:`check_size`) is what stops most grids well before it.
MAX_CLASSIFY_OTHER = 24
#: Sizes counted exactly by the estimate of a run's forms (beyond, the last ratio extrapolates).
_COUNTED = 8


def estimated_forms(grid: Grid, n: int) -> int:
    """Free forms of sizes 1..n on ``grid``: counted to 8 cells (Redelmeier, under a second),
    beyond that extrapolated with the growth of the last counted size (an underestimate: the
    ratio still grows)."""
    k = min(n, _COUNTED)
    free = count_fixed(grid, k, free=True)["free"]
    total = float(free[1:k + 1].sum())
    last, growth = float(free[k]), float(free[k]) / max(1.0, float(free[k - 1])) if k > 1 else 1.0
    for _ in range(k, n):
        last *= growth
        total += last
    return int(total)


def check_size(grid: Grid, n: int) -> None:
    """Refuse a run that would take on more forms than the square grid's largest (MAX_CLASSIFY
    cells), with the estimate, before the run is created."""
    if grid.name == SQUARE.name:
        return
    mine, limit = estimated_forms(grid, n), estimated_forms(SQUARE, MAX_CLASSIFY)
    if mine > limit:
        raise ParameterError(f"--max-cells {n} on the {grid.name} grid means about {mine:,} free forms (estimated), "
                             f"over the classification's limit of {limit:,} (the square grid's {MAX_CLASSIFY} cells); "
                             f"ask for fewer cells")


def check_params(params: dict[str, Any]) -> None:
    n = params.get("max_cells")
    if not isinstance(n, int) or n < 1:
        raise ParameterError(f"--max-cells must be a positive integer, got {n!r}")
    grid = grid_of(params.get("grid") or "square")
    check_grid(grid)
    most = MAX_CLASSIFY if grid.name == SQUARE.name else MAX_CLASSIFY_OTHER
    if n > most:
        raise ParameterError(f"parameter 'max_cells' (--max-cells) {n} is beyond the classification's limit of "
                             f"{most} cells on the {grid.name} grid")
    lo = int(params.get("min_cells") or 1)
    if not 1 <= lo <= n:
        raise ParameterError(f"--min-cells must be between 1 and --max-cells ({n}), got {lo}")
    bounds = _bounds(params)
    check_bounds(**bounds)
    forms = named_forms(params, grid, lo, n)
    check_torus_cost(grid, max((f.n for f in forms), default=n), bounds["torus_tiles"], bounds["escalate_torus_tiles"])
    if not forms:
        check_size(grid, n)
    check_solver(str(params.get("solver") or CLASSIFY_SOLVER))  # a missing pycryptosat: before the run


#: Most forms one ``--codes`` run names.
MAX_CODES = 10_000


def named_forms(params: dict[str, Any], grid: Grid, lo: int, n: int) -> list[Polyomino]:
    """The forms ``--codes`` names (codes or usual names, separated by spaces), each checked to
    be a form of the run's grid with ``lo``..``n`` cells; [] without ``--codes``."""
    words = str(params.get("codes") or "").split()
    if len(words) > MAX_CODES:
        raise ParameterError(f"--codes names {len(words):,} forms, more than the limit of {MAX_CODES:,}")
    out = []
    for w in words:
        f = Polyomino.parse(w)
        if f.grid.name != grid.name:
            raise ParameterError(f"--codes: {w} is a form of the {f.grid.name} grid, not of --grid {grid.name}")
        if not lo <= f.n <= n:
            raise ParameterError(f"--codes: {w} has {f.n} cells, outside --min-cells ({lo}) .. --max-cells ({n})")
        out.append(f)
    return out


def chunks(params: dict[str, Any]) -> list[dict[str, Any]]:
    """The enumeration's chunks (:func:`search.prefix_chunks`): each free polyomino is in
    exactly one; with ``--codes``, one chunk per form named (each once)."""
    check_params(params)
    n = int(params["max_cells"])
    grid = grid_of(params.get("grid") or "square")
    named = named_forms(params, grid, int(params.get("min_cells") or 1), n)
    if named:
        return [{"code": c} for c in dict.fromkeys(f.code for f in named)]
    # deeper than the enumeration's: a classification chunk should be seconds of SAT work
    return prefix_chunks(n, prefix_depth(n, int(params.get("prefix_depth") or 0), spare=4, most=8),
                         grid_of(params.get("grid") or "square"))


def run_chunk(params: dict[str, Any], chunk: dict[str, Any]):
    """Classify every free polyform of the chunk (or the one form it names); rows for the
    polyominoes table, counts."""
    grid = grid_of(params.get("grid") or "square")
    n = int(params["max_cells"])
    lo = int(params.get("min_cells") or 1)
    bounds = _bounds(params) | {"time_limit": float(params.get("time_limit") or 0) or None,
                                "solver": str(params.get("solver") or CLASSIFY_SOLVER)}
    tally = _Tally()
    if "code" in chunk:  # one form named by --codes
        f = Polyomino.parse(str(chunk["code"]))
        t0 = time.process_time()
        analysis = None if f.has_holes else analyse(grid, f.cells, construct=False)
        c = classify(grid, f.cells, analysis, has_holes=f.has_holes, **bounds)
        row = make_row(f.cells, f.has_holes, len(f.hole_list), analysis, code=f.code, symmetry=f.symmetry, grid=grid)
        tally.add(row | c.columns(), f.n, c, f.has_holes, time.process_time() - t0)
        return tally.result()
    maxsize = int(chunk["below"]) - 1 if "below" in chunk else n
    polys, hole_flags, masks, _ = enumerate_free(grid, n, prefix=list(chunk.get("prefix") or []),
                                                 root=int(chunk.get("root", 0)), maxsize=maxsize,
                                                 with_symmetry=True)
    keep = [i for i, c in enumerate(polys) if len(c) >= lo]
    # the boundary-word test of the whole chunk in one compiled call (isohedral.analyse_many)
    t0 = time.process_time()
    plain = [polys[i] for i in keep if not hole_flags[i]]
    analysed = iter(analyse_many(grid, plain))
    bulk = (time.process_time() - t0) / max(1, len(keep))
    for i in keep:
        cells, holey, mask = polys[i], hole_flags[i], int(masks[i])
        t0 = time.process_time() - bulk
        analysis = None if holey else next(analysed)
        c = classify(grid, cells, analysis, has_holes=bool(holey), **bounds)
        hc = len(holes(grid, cells)) if holey else 0
        # the enumeration's cells are canonical but in search-tree order: other grids' codes list
        # them in (y, x) order (as Polyomino.code does), so a code names one form
        cells = cells[np.lexsort((cells[:, 0], cells[:, 1]))]
        row = make_row(cells, bool(holey), hc, analysis, code=encode(grid, cells, is_canonical=True),
                       symmetry=symmetry_from_mask(grid, mask), grid=grid)
        tally.add(row | c.columns(), len(cells), c, bool(holey), time.process_time() - t0)
    return tally.result()


class _Tally:
    """A chunk's rows and per-size counts."""

    def __init__(self) -> None:
        self.rows: list[dict] = []
        self.counts: dict[str, int | float] = {}

    def bump(self, key: str, by: int | float = 1) -> None:
        self.counts[key] = self.counts.get(key, 0) + by

    def add(self, row: dict, size: int, c, holey: bool, seconds: float) -> None:
        self.rows.append(row)
        bump = self.bump
        bump(f"free_{size}")
        bump(f"tiles_{size}" if c.tiles == "true" else f"nontilers_{size}" if c.tiles == "false" else f"undecided_{size}")
        if c.tiles == "true" and not c.isohedral:
            bump(f"anisohedral_{size}")
            bump(f"anisohedral_{size}_k{c.anisohedral_k}")
        if c.tiles == "true" and c.isohedral:
            bump(f"isohedral_{size}")
        if c.tiles == "false" and not holey:
            bump(f"holefree_nontilers_{size}")
            bump(f"hc_{size}_{c.heesch}")
            bump(f"hh_{size}_{c.heesch_holes}")
        bump(f"seconds_{size}", round(seconds, 4))

    def result(self) -> ChunkResult:
        return ChunkResult(rows={"polyominoes": self.rows}, counts=self.counts)


def summarize(params: dict[str, Any], results: list[dict[str, Any]]) -> dict[str, Any]:
    """The bounds of the run (the per-size tallies are the summed counts; ``seconds_N`` is the
    CPU seconds of the size-N forms, the process's: runs stored before 2026-12-04 hold wall-clock
    seconds under the same key)."""
    b = _bounds(params)
    return {"max_cells": int(params["max_cells"]), "max_level": b["max_level"], "torus_tiles": b["torus_tiles"],
            "escalate_torus_tiles": b["escalate_torus_tiles"], "grid": str(params.get("grid") or "square")}


def _bounds(params: dict[str, Any]) -> dict[str, int]:
    """The run's search bounds, the defaults filled in (one copy for checking, classifying
    and summarising)."""
    return {"probe": int(params.get("probe", 2)), "max_level": int(params.get("max_level", 5)),
            "torus_tiles": int(params.get("torus_tiles", DEFAULT_TORUS_TILES)),
            "escalate_torus_tiles": int(params.get("escalate_torus_tiles") or 0)}


def _search() -> Search:
    return Search(
        "polyomino-classify",
        "classify every free polyform of a grid: isohedral, anisohedral (least k found on tori), or a "
        "non-tiler with its Heesch numbers (Kaplan 2022, by SAT)",
        "polyomino",
        [
            SearchParam("grid", str, "square", "the cell grid: square (polyominoes), hex (polyhexes), iamond "
                        "(polyiamonds), kite (polykites), octasquare, trihex, drafter, abolo, halfcairo, "
                        "bevelhex (copies on the grid only)", choices=list(CLASSIFIED_GRIDS)),
            SearchParam("max_cells", int, 10, f"largest size (at most {MAX_CLASSIFY} on the square grid, "
                        f"{MAX_CLASSIFY_OTHER} on the others, and no more free forms than the square grid's "
                        f"{MAX_CLASSIFY} cells: refused with the estimate)", min=1, max=MAX_CLASSIFY_OTHER),
            SearchParam("min_cells", int, 1, "smallest size classified (smaller ones are skipped)", min=1,
                        max=MAX_CLASSIFY_OTHER),
            SearchParam("probe", int, 2, "coronas tried before the torus search", min=1, max=MAX_LEVEL_LIMIT),
            SearchParam("max_level", int, 5, "most coronas tried before 'undecided'", min=1, max=MAX_LEVEL_LIMIT),
            SearchParam("torus_tiles", int, DEFAULT_TORUS_TILES, "most tiles per translational unit tried on tori "
                        "for every form (what it costs is estimated first and refused when too large)", min=2,
                        max=MAX_TORUS_TILES),
            SearchParam("escalate_torus_tiles", int, 0, "tori of up to this many tiles per unit for the forms still "
                        "undecided after --torus-tiles and --max-level, within --time-limit (0: none)", min=0,
                        max=MAX_TORUS_TILES),
            SearchParam("codes", str, "", "classify only these forms (codes or names, separated by spaces; each of "
                        "--grid, with --min-cells..--max-cells cells), e.g. the ones a run left undecided"),
            SearchParam("time_limit", float, 300.0, "CPU seconds per polyform (its classifying thread and solver processes) before 'undecided' "
                        "(0: none)",
                        min=0, max=86400),
            SearchParam("solver", str, CLASSIFY_SOLVER, "SAT solver", choices=list(SAT_SOLVERS)),
            SearchParam("prefix_depth", int, 0, "size of the tree prefix naming a chunk (0: automatic)", min=0,
                        max=10),
        ],
        chunks,
        run_chunk,
        summarize,
    )


SEARCH = _search()
