"""The ``polyforms`` search: free polyforms on any grid of :mod:`tilekit.lattice`, stored.

``tilekit search polyforms --grid kite --max-cells 8`` enumerates the free polyforms of up
to 8 cells of a grid (Redelmeier's algorithm from every cell type, split into chunks by tree
prefixes exactly as the ``polyominoes`` search does) and stores one row per form in the
polyomino family's result table, with its ``grid``, canonical code (``kite:1,1;5,2``), cells,
holes, symmetry and outer boundary word. On the square grid it is the ``polyominoes``
search (same chunks, same rows, the isohedral test included). On the other grids the
isohedral columns are left empty (NULL: not tested by this run); the classification
search fills them.

Before a run is created the request is estimated: the number of forms (exact counts of
fixed forms to a small size, extrapolated by their last growth ratio, divided by the
grid's symmetries) and the time; past :data:`MAX_STORED_FORMS` the run is refused with
the estimate and the largest size that fits.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from functools import cache
from typing import Any

import numpy as np

from tilekit.lattice import (
    GRIDS,
    SQUARE,
    Grid,
    boundary_word,
    count_fixed,
    encode,
    enumerate_free,
    get_grid,
    hole_count,
    prefixes,
    symmetry_from_mask,
    word_text,
)
from tilekit.limits import LimitError
from tilekit.plugins import ChunkResult, Search, SearchParam
from tilekit.plugins.polyomino import search as polyominoes

#: Most forms (all sizes together) one run stores: the square grid's stored limit of 14 cells
#: is 1.2 million rows; a larger table is a count, not a catalogue.
MAX_STORED_FORMS = 1_500_000
#: Largest --max-cells any grid accepts (the estimate refuses far earlier on most grids).
MAX_CELLS = 40
#: Measured cost of one stored form (enumeration, hole count, symmetry, boundary word and the
#: row), seconds: 0.2-0.4 ms on the kite, hex and octasquare grids (one core, load ~14,
#: docs/benchmarks.md "Polyform enumeration"); the estimate uses the upper end.
SECONDS_PER_FORM = 4e-4
#: The fixed forms counted exactly for the estimate: sizes while their count stays below this.
_EXACT_FIXED = 20_000


@cache
def estimate_forms(grid_name: str, n: int) -> list[float]:
    """Estimated free forms of each size 1..n (index 0 unused): fixed forms counted exactly
    while they are few, then extrapolated by the last growth ratio (which rises towards the
    grid's growth constant, so the extrapolation errs low), divided by the group order."""
    grid = get_grid(grid_name)
    m = 1
    c = count_fixed(grid, 1)["fixed"]
    while m < n:
        c2 = count_fixed(grid, m + 1)["fixed"]
        if c2[m + 1] > _EXACT_FIXED and m >= 3:
            break
        m, c = m + 1, c2
    fixed = [float(v) for v in c[: m + 1]]
    ratio = fixed[m] / fixed[m - 1] if m >= 2 else 2.0
    while len(fixed) <= n:
        fixed.append(fixed[-1] * ratio)
    order = len(grid.group)
    return [0.0] + [max(1.0, f / order) for f in fixed[1:]]


def check_params(params: Mapping[str, Any]) -> None:
    """Refuse a run that would store more than MAX_STORED_FORMS, with the estimate."""
    grid = get_grid(params["grid"])
    n = int(params["max_cells"])
    if grid is SQUARE:
        polyominoes.check_params({"max_cells": n})
    est = estimate_forms(grid.name, n)
    total = sum(est)
    if total > MAX_STORED_FORMS:
        fit = max([k for k in range(1, n + 1) if sum(est[: k + 1]) <= MAX_STORED_FORMS] or [0])
        secs = total * SECONDS_PER_FORM
        raise LimitError(
            f"--max-cells {n} on the {grid.name} grid would store about {total:,.0f} polyforms "
            f"(about {_duration(secs)} at {SECONDS_PER_FORM * 1e3:g} ms each), over the limit of "
            f"{MAX_STORED_FORMS:,}; the largest size within it is --max-cells {fit}"
        )


def _duration(secs: float) -> str:
    if secs < 120:
        return f"{secs:.0f} s"
    if secs < 7200:
        return f"{secs / 60:.0f} min"
    return f"{secs / 3600:.1f} h"


def chunks(params: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Per cell type (root), the top chunk and one chunk per node of size ``depth`` of its
    Redelmeier tree: together they emit every free form once (each from the type of the
    least cell of its canonical image)."""
    check_params(params)
    grid = get_grid(params["grid"])
    n = int(params["max_cells"])
    depth = polyominoes.prefix_depth(n, int(params.get("prefix_depth") or 0))
    out: list[dict[str, Any]] = []
    for r in range(len(grid.roots)):
        if depth > 1:
            out.append({"root": r, "prefix": [], "below": depth})
        out += [{"root": r, "prefix": p} for p in prefixes(grid, n, depth, r)]
    return out


def polyform_row(grid: Grid, cells, has_holes: bool, symmetry: str) -> dict[str, Any]:
    """One row of the polyominoes table for a canonical polyform on a grid other than the
    square one: the isohedral columns are NULL (not tested here)."""
    cells = cells[np.lexsort((cells[:, 0], cells[:, 1]))]  # (y, x) order, as canonical() gives
    row = {
        "code": encode(grid, cells, is_canonical=True),
        "name": None,
        "grid": grid.name,
        "cells": int(len(cells)),
        "cell_list": json.dumps(cells.tolist()),  # fine coordinates (tilekit.lattice)
        "holes": bool(has_holes),
        "hole_count": hole_count(grid, cells) if has_holes else 0,
        "symmetry": symmetry,
        "boundary": word_text(boundary_word(grid, cells)[1]),  # the outer boundary
        "translation": None, "halfturn": None, "quarterturn": None, "reflection": None,
        "isohedral": None,
        "ih_types": "",
        "factorisations": "[]",
    }
    if has_holes:
        # copies filling a hole would need copies in their own holes, without end
        row |= {"tiles": "false", "verdict": "does not tile: it has a hole"}
    return row


def chunk_rows(params: Mapping[str, Any], chunk: Mapping[str, Any]) -> tuple[dict[str, list[dict]], dict[str, int]]:
    """(rows by table name, counts) of one chunk."""
    grid = get_grid(params["grid"])
    n = int(params["max_cells"])
    if grid is SQUARE:
        return polyominoes.chunk_rows({"max_cells": n, "prefix_depth": params.get("prefix_depth", 0)}, chunk)
    maxsize = int(chunk["below"]) - 1 if "below" in chunk else n
    polys, hole_flags, masks, c = enumerate_free(grid, n, prefix=list(chunk.get("prefix") or []),
                                                 root=int(chunk.get("root", 0)), maxsize=maxsize,
                                                 with_symmetry=True)
    rows = [polyform_row(grid, cells, bool(h), symmetry_from_mask(grid, int(m)))
            for cells, h, m in zip(polys, hole_flags.tolist(), masks.tolist())]
    counts: dict[str, int] = {}
    for kind in ("fixed", "free", "holey"):
        for size in range(1, n + 1):
            v = int(c[kind][size])
            if v:
                counts[f"{kind}_{size}"] = v
    return {"polyominoes": rows}, counts


def run_chunk(params: Mapping[str, Any], chunk: Mapping[str, Any]) -> ChunkResult:
    rows, counts = chunk_rows(params, chunk)
    return ChunkResult(rows=rows, counts=counts)


def summarize(params: Mapping[str, Any], results: list[dict[str, Any]]) -> dict[str, Any]:
    """The grid and size (the summed ``fixed_N`` / ``free_N`` / ``holey_N`` counts are added)."""
    return {"grid": get_grid(params["grid"]).name, "max_cells": int(params["max_cells"])}


SEARCH = Search(
    "polyforms",
    "free polyforms on any grid (square, hex, iamond, kite, octasquare, ...) by Redelmeier's algorithm, "
    "with holes, symmetry and boundary word",
    "polyomino",
    [
        SearchParam("grid", str, "square", "the cell grid", choices=tuple(GRIDS)),
        SearchParam("max_cells", int, 8,
                    f"largest size (refused, with the estimate, past {MAX_STORED_FORMS:,} stored forms)",
                    min=1, max=MAX_CELLS),
        SearchParam("prefix_depth", int, 0, "size of the tree prefix naming a chunk (0: automatic)", min=0, max=10),
    ],
    chunks,
    run_chunk,
    summarize,
)
