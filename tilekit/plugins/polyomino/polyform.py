"""A polyform on any grid of :mod:`tilekit.lattice`, drawn cell by cell (``show`` / ``render``).

The polyomino family reads a spec whose code names another grid (``{"code": "kite:1,1;5,2"}``,
as the ``polyforms`` search stores it) through :func:`from_spec` here: the tiling's patch is
the form's cells, each a translate of its cell type's exact polygon (so holes show as gaps),
coloured by cell shape.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import shapely

from tilekit.errors import ParseError
from tilekit.lattice import Grid, canonical, encode, get_grid, hole_count, parse_polyform
from tilekit.tiling import Patch, Prototile, Tiling

FAMILY = "polyomino"


def grid_of_code(code: str) -> Grid | None:
    """The grid a code names (``kite:...``), or None for a square-grid code / usual name."""
    head, sep, _ = str(code).partition(":")
    if not sep:
        return None
    return get_grid(head.strip())


class PolyformCells(Tiling):
    """One free polyform on a grid; its patch is its cells (one tile per cell)."""

    def __init__(self, grid: Grid, cells: np.ndarray, name: str = "") -> None:
        self.grid = grid
        self.cells = canonical(grid, cells, "free")
        self.code = encode(grid, self.cells, is_canonical=True)
        self.family = FAMILY
        self.name = name or self.code
        polys = grid.cell_polygons(grid.roots)
        self._protos = [Prototile(p, name=f"{grid.name} {grid.shapes[t]}") for t, p in enumerate(polys)]

    @property
    def prototiles(self) -> list[Prototile]:
        return self._protos

    def patch(self, region: Any = None) -> Patch:
        g = self.grid
        t = g.cell_type(self.cells)
        shift = g.xy(self.cells - g.roots[t])  # exact: translations are linear
        tr = np.repeat(np.eye(3)[None], len(t), axis=0)
        tr[:, :2, 2] = shift
        shapes = sorted(set(g.shapes))
        colour = np.array([shapes.index(g.shapes[k]) for k in t], dtype=np.int64)
        return Patch(self._protos, t, tr, colour=colour)

    def default_region(self):
        pts = np.concatenate(self.grid.cell_polygons(self.cells))
        (x0, y0), (x1, y1) = pts.min(axis=0), pts.max(axis=0)
        m = 0.1 * max(x1 - x0, y1 - y0, 1e-9)
        return shapely.box(x0 - m, y0 - m, x1 + m, y1 + m)

    def spec(self) -> dict[str, Any]:
        return {"code": self.code, "name": self.name}

    def properties(self) -> dict[str, Any]:
        holes = hole_count(self.grid, self.cells)
        return {"grid": self.grid.name, "cells": int(len(self.cells)), "holes": bool(holes),
                "hole_count": holes, "periodic": False}

    def describe(self) -> str:
        return f"a {len(self.cells)}-cell polyform on the {self.grid.name} grid, drawn cell by cell"

    def configure(self, **options: Any) -> Tiling:
        if options:
            raise ParseError(f"a {self.grid.name} polyform takes no options (got {', '.join(options)})")
        return self


def from_spec(spec: Mapping[str, Any]) -> Tiling:
    """``{"code": "GRID:x,y;...", "name": ...}`` -> :class:`PolyformCells` (cells validated)."""
    code = spec.get("code") or spec.get("name")
    grid = grid_of_code(code)
    if grid is None:
        raise ParseError(f"polyform code {str(code)[:60]!r} names no grid (write GRID:x,y;x,y;...)")
    return PolyformCells(grid, parse_polyform(grid, code), name=str(spec.get("name") or ""))
