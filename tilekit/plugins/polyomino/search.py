"""The ``polyominoes`` search: Redelmeier enumeration split by prefixes of its search tree.

Chunk completeness: Redelmeier's tree (rooted at the least cell, cells added from an untried
list) has every fixed polyomino as exactly one node. A chunk is either the *top* chunk (all
nodes of size < depth) or the subtree below one node of size == depth, named by its path of
choices; these partition the nodes. A chunk writes a fixed polyomino only if it is the least
of its eight images (the canonical representative of its free class), which is one fixed
polyomino per free class; so each free polyomino is written by exactly one chunk.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from tilekit.errors import ParameterError
from tilekit.lattice import (
    SQUARE,
    count_fixed,
    encode,
    enumerate_free,
    hole_count,
    prefixes,
    symmetry_from_mask,
)
from tilekit.plugins import ChunkResult, Search, SearchParam
from tilekit.plugins.polyomino.isohedral import analyse_many
from tilekit.plugins.polyomino.model import make_row

#: The stored enumeration holds polyominoes up to this size; beyond it, --count-only.
MAX_STORED = 14
#: Counting mode refuses sizes past this (the counts overflow nothing, but a run would take days).
MAX_COUNT = 22


def prefix_depth(n: int, requested: int = 0, *, spare: int = 6, most: int = 7) -> int:
    """The prefix size naming a chunk of a run to n cells: ``requested``, or (0) ``n - spare``
    kept within 2..``most`` (a deeper prefix makes more, smaller chunks)."""
    d = requested if requested > 0 else max(2, min(most, n - spare))
    return min(d, n)


def _depth(params: Mapping[str, Any]) -> int:
    return prefix_depth(int(params["max_cells"]), int(params.get("prefix_depth") or 0))


def check_params(params: Mapping[str, Any]) -> None:
    n = params.get("max_cells")
    if not isinstance(n, int) or n < 1:
        raise ParameterError(f"--max-cells must be a positive integer, got {n!r}")
    if params.get("count_only"):
        if n > MAX_COUNT:
            raise ParameterError(f"--max-cells {n} is beyond the counting limit of {MAX_COUNT} cells")
    elif n > MAX_STORED:
        raise ParameterError(
            f"--max-cells {n} is beyond the stored enumeration's limit of {MAX_STORED} cells; "
            f"count larger sizes with --count-only (counting mode stores no rows)"
        )


def prefix_chunks(n: int, depth: int, grid=SQUARE) -> list[dict[str, Any]]:
    """The top chunk (every node of size < depth) and one chunk per node of size ``depth``
    of Redelmeier's tree for sizes up to n (see the module docstring: a partition)."""
    out: list[dict[str, Any]] = []
    # one tree per cell type: a canonical form starts at a cell of any type (kites: six)
    for r in range(len(grid.roots)):
        if depth > 1:
            out.append({"root": r, "prefix": [], "below": depth})
        for p in prefixes(grid, n, depth, r):
            out.append({"root": r, "prefix": p})
    return out


def chunks(params: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The top chunk and one chunk per node of size ``depth`` of Redelmeier's tree."""
    check_params(params)
    return prefix_chunks(int(params["max_cells"]), _depth(params))


def chunk_rows(params: Mapping[str, Any], chunk: Mapping[str, Any]) -> tuple[dict[str, list[dict]], dict[str, int]]:
    """(rows by table name, counts) of one chunk: the contract's pure function."""

    n = int(params["max_cells"])
    prefix = list(chunk.get("prefix") or [])
    maxsize = int(chunk["below"]) - 1 if "below" in chunk else n
    counts: dict[str, int] = {}
    if params.get("count_only"):
        c = count_fixed(SQUARE, n, free=bool(params.get("free_counts", True)), prefix=prefix,
                        root=int(chunk.get("root", 0)), maxsize=maxsize)
        rows: list[dict] = []
    else:
        polys, hole_flags, masks, c = enumerate_free(SQUARE, n, prefix=prefix, root=int(chunk.get("root", 0)),
                                                     maxsize=maxsize, with_symmetry=True)
        rows = []
        # the isohedral test of every hole-free polyomino of the chunk: one compiled call
        flags = hole_flags.tolist()
        plain = iter(analyse_many(SQUARE, [c for c, h in zip(polys, flags) if not h]))
        for cells, holey, mask in zip(polys, flags, masks.tolist()):
            analysis = None if holey else next(plain)
            hc = hole_count(SQUARE, cells) if holey else 0
            rows.append(make_row(cells, bool(holey), hc, analysis, code=encode(SQUARE, cells, is_canonical=True),
                                 symmetry=symmetry_from_mask(SQUARE, mask)))
        for r in rows:
            for key in ("translation", "halfturn", "quarterturn", "reflection", "isohedral"):
                if r[key]:
                    k = f"{key}_{r['cells']}"
                    counts[k] = counts.get(k, 0) + 1
            if r["isohedral"] and not r["translation"] and not r["halfturn"]:
                k = f"other_isohedral_{r['cells']}"
                counts[k] = counts.get(k, 0) + 1
    for kind in ("fixed", "free", "holey"):
        for size in range(1, n + 1):
            v = int(c[kind][size])
            if v:
                counts[f"{kind}_{size}"] = counts.get(f"{kind}_{size}", 0) + v
    return {"polyominoes": rows}, counts


def run_chunk(params: Mapping[str, Any], chunk: Mapping[str, Any]) -> ChunkResult:
    """One chunk: its rows for the polyominoes table and its counts (summed into the run summary)."""
    rows, counts = chunk_rows(params, chunk)
    return ChunkResult(rows=rows, counts=counts)


def summarize(params: Mapping[str, Any], results: list[dict[str, Any]]) -> dict[str, Any]:
    """Nothing beyond the summed counts (``fixed_N``, ``free_N``, ``holey_N``, ``isohedral_N`` ...)."""
    return {"max_cells": int(params["max_cells"]), "count_only": bool(params.get("count_only"))}


SEARCH = Search(
    "polyominoes",
    "free polyominoes by Redelmeier's algorithm, with holes, symmetry, boundary word and the isohedral test",
    "polyomino",
    [
        SearchParam("max_cells", int, 12, f"largest size (stored up to {MAX_STORED}; beyond, use --count-only)",
                    min=1, max=MAX_COUNT),
        SearchParam("count_only", bool, False, "count fixed/free/holey polyominoes per size, store no rows"),
        SearchParam("free_counts", bool, True, "in counting mode also count free and holey ones (slower)"),
        SearchParam("prefix_depth", int, 0, "size of the tree prefix naming a chunk (0: automatic)", min=0, max=10),
    ],
    chunks,
    run_chunk,
    summarize,
)
