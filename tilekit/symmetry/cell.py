"""A periodic tiling's period cell in array form (outlines, signature points, centres, labels,
colours over a lattice): what matching and the group search work on."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from tilekit.colouring import permutation_order
from tilekit.errors import ParameterError
from tilekit.geometry import Affine
from tilekit.symmetry.lattice import _frac
from tilekit.symmetry.results import SymmetryGroup
from tilekit.tiling import PeriodicTiling

#: Default tolerance, relative to the tiling's length scale (square root of the median tile area).
DEFAULT_TOL = 1e-6


@dataclass
class _Cell:
    """A periodic tile set in array form: tiles of one period cell and its lattice."""

    outlines: list[np.ndarray]  # per tile, the placed outline (k, 2), cyclic order
    points: np.ndarray  # (m, K, 2) outline + marking points, padded with point 0
    count: np.ndarray  # (m,) real signature points
    centre: np.ndarray  # (m, 2) mean of outline points
    label: np.ndarray  # (m,) class that must match (point counts, prototile, colour)
    colour: np.ndarray  # (m,) tile colours
    basis: np.ndarray  # (2, 2) lattice basis as rows
    tol: float

    def __len__(self) -> int:
        return len(self.count)


def _tile_geometry(tiling: PeriodicTiling) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Per unit tile: the placed outline and its signature (outline + marking points)."""
    outlines, sigs = [], []
    for p, m in zip(tiling.unit_prototile, tiling.unit_transform):
        proto = tiling.prototiles[int(p)]
        out = Affine.apply(m, proto.outline)
        extra = [Affine.apply(m, mk) for mk in proto.marking if len(mk)]
        outlines.append(out)
        sigs.append(np.vstack([out, *extra]) if extra else out)
    return outlines, sigs


def _make_cell(
    outlines: list[np.ndarray],
    sigs: list[np.ndarray],
    keys: np.ndarray,
    colour: np.ndarray,
    basis: np.ndarray,
    tol: float,
) -> _Cell:
    m = len(outlines)
    kmax = max(len(s) for s in sigs)
    points = np.empty((m, kmax, 2))
    count = np.empty(m, dtype=np.int64)
    for i, s in enumerate(sigs):
        points[i, : len(s)] = s
        points[i, len(s) :] = s[0]
        count[i] = len(s)
    centre = np.array([o.mean(axis=0) for o in outlines])
    nout = np.array([len(o) for o in outlines])
    rows = np.column_stack([np.asarray(keys).reshape(m, -1), count, nout])
    _, label = np.unique(rows, axis=0, return_inverse=True)
    return _Cell(outlines, points, count, centre, label.reshape(-1), np.asarray(colour), basis, tol)


def _scale(tiling: PeriodicTiling) -> float:
    areas = np.array([abs(proto.area) for proto in tiling.prototiles])  # each prototile once
    return math.sqrt(float(np.median(areas[np.asarray(tiling.unit_prototile, dtype=np.int64)])))


def _check(tiling: Any) -> PeriodicTiling:
    if not isinstance(tiling, PeriodicTiling):
        raise ParameterError(
            f"symmetry analysis needs a PeriodicTiling (a translational unit and two vectors), "
            f"not {type(tiling).__name__}"
        )
    return tiling


def _abs_tol(tiling: PeriodicTiling, tol: float) -> float:
    if not (isinstance(tol, int | float) and 0 < tol < 0.1):
        raise ParameterError(f"tolerance {tol!r} must be a number in (0, 0.1) (relative to the tile size)")
    return tol * _scale(tiling)


def _base_cell(tiling: PeriodicTiling, tol: float, match_prototiles: bool) -> _Cell:
    outlines, sigs = _tile_geometry(tiling)
    keys = tiling.unit_prototile if match_prototiles else np.zeros(len(outlines), dtype=np.int64)
    colour = tiling.unit().colour
    return _make_cell(outlines, sigs, keys, colour, np.array([tiling.v1, tiling.v2]), tol)


def _colour_cell(
    tiling: PeriodicTiling, group: SymmetryGroup, tol: float, match_prototiles: bool
) -> tuple[_Cell, int]:
    """A cell of the coloured tiling over a lattice that every symmetry maps onto itself.

    The colours repeat under e*v1 and e*v2 (e the lcm of the two permutation orders); with
    i the index of the given lattice in the true lattice L, the lattice n*L (n = i*e) lies
    inside that colour lattice and, being a multiple of L, is preserved by the point group.
    Returns the cell (tiles matched by geometry; colours in ``cell.colour``) and n.
    """
    col = tiling.colouring
    e = math.lcm(permutation_order(list(col.p)), permutation_order(list(col.q)))
    n = group.lattice_index * e
    big = group.lattice * n
    outlines0, sigs0 = _tile_geometry(tiling)
    m = len(outlines0)
    # translates of the unit by a*v1 + b*v2, 0 <= a, b < n, cover every class modulo n*L;
    # tiles that coincide modulo n*L are kept once
    a, b = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    ab = np.column_stack([a.ravel(), b.ravel()])
    shifts = ab @ np.array([tiling.v1, tiling.v2])
    tile = np.tile(np.arange(m), len(ab))
    cell_i = np.repeat(np.arange(len(ab)), m)
    centres0 = np.array([o.mean(axis=0) for o in outlines0])
    f = _frac(centres0[tile] + shifts[cell_i], big)
    keyf = np.round((f - np.floor(f)) * 1e6).astype(np.int64) % 1_000_000
    _, first = np.unique(np.column_stack([keyf, tile]), axis=0, return_index=True)
    first = np.sort(first)
    tile, cell_i = tile[first], cell_i[first]
    colours = col.colour(tiling.unit_aspect[tile], ab[cell_i, 0], ab[cell_i, 1])
    outlines = [outlines0[t] + shifts[c] for t, c in zip(tile, cell_i)]
    sigs = [sigs0[t] + shifts[c] for t, c in zip(tile, cell_i)]
    proto = tiling.unit_prototile[tile] if match_prototiles else np.zeros(len(tile), dtype=np.int64)
    return _make_cell(outlines, sigs, proto, colours, big, tol), n


def absolute_tolerance(tiling: PeriodicTiling, tol: float = DEFAULT_TOL) -> float:
    """``tol`` (relative) times the tiling's length scale, the square root of the median tile
    area: the absolute tolerance every symmetry function works with."""
    return _abs_tol(_check(tiling), tol)
