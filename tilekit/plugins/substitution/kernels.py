"""Compiled loops of the substitution engine (numba): one level's children, placed maps.

NumPy's batched ``(k, 1, 3, 3) @ (1, m, 3, 3)`` product is a loop of tiny matrix products
(about 1 M tiles/s at 10^6 tiles); composing the same affine maps as element-wise
expressions over component arrays is faster but still makes several passes over memory per
level. These loops make one pass: for every parent they read its 2x3 affine part once and
write each child's map in place, in parent order (the children of tile t are contiguous).
Maps are affine (last row 0, 0, 1); integer maps (the hat's lattice maps) stay exact.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def _expand(label, maps, starts, kids, mats, out_label, out_maps):  # pragma: no cover - compiled
    pos = 0
    for i in range(label.shape[0]):
        j = label[i]
        a00 = maps[i, 0, 0]
        a01 = maps[i, 0, 1]
        a02 = maps[i, 0, 2]
        a10 = maps[i, 1, 0]
        a11 = maps[i, 1, 1]
        a12 = maps[i, 1, 2]
        for c in range(starts[j], starts[j + 1]):
            out_label[pos] = kids[c]
            out_maps[pos, 0, 0] = a00 * mats[c, 0, 0] + a01 * mats[c, 1, 0]
            out_maps[pos, 0, 1] = a00 * mats[c, 0, 1] + a01 * mats[c, 1, 1]
            out_maps[pos, 0, 2] = a00 * mats[c, 0, 2] + a01 * mats[c, 1, 2] + a02
            out_maps[pos, 1, 0] = a10 * mats[c, 0, 0] + a11 * mats[c, 1, 0]
            out_maps[pos, 1, 1] = a10 * mats[c, 0, 1] + a11 * mats[c, 1, 1]
            out_maps[pos, 1, 2] = a10 * mats[c, 0, 2] + a11 * mats[c, 1, 2] + a12
            out_maps[pos, 2, 0] = 0
            out_maps[pos, 2, 1] = 0
            out_maps[pos, 2, 2] = 1
            pos += 1


@njit(cache=True, nogil=True)
def _sandwich(left, maps, right, out):  # pragma: no cover - compiled
    """out[i] = left @ maps[i] @ right for affine 3x3 left, maps[i], right."""
    for i in range(maps.shape[0]):
        # t = maps[i] @ right (affine: last rows are 0, 0, 1)
        t00 = maps[i, 0, 0] * right[0, 0] + maps[i, 0, 1] * right[1, 0]
        t01 = maps[i, 0, 0] * right[0, 1] + maps[i, 0, 1] * right[1, 1]
        t02 = maps[i, 0, 0] * right[0, 2] + maps[i, 0, 1] * right[1, 2] + maps[i, 0, 2]
        t10 = maps[i, 1, 0] * right[0, 0] + maps[i, 1, 1] * right[1, 0]
        t11 = maps[i, 1, 0] * right[0, 1] + maps[i, 1, 1] * right[1, 1]
        t12 = maps[i, 1, 0] * right[0, 2] + maps[i, 1, 1] * right[1, 2] + maps[i, 1, 2]
        out[i, 0, 0] = left[0, 0] * t00 + left[0, 1] * t10
        out[i, 0, 1] = left[0, 0] * t01 + left[0, 1] * t11
        out[i, 0, 2] = left[0, 0] * t02 + left[0, 1] * t12 + left[0, 2]
        out[i, 1, 0] = left[1, 0] * t00 + left[1, 1] * t10
        out[i, 1, 1] = left[1, 0] * t01 + left[1, 1] * t11
        out[i, 1, 2] = left[1, 0] * t02 + left[1, 1] * t12 + left[1, 2]
        out[i, 2, 0] = 0.0
        out[i, 2, 1] = 0.0
        out[i, 2, 2] = 1.0


def expand(
    label: np.ndarray, maps: np.ndarray, children: list[np.ndarray], matrices: list[np.ndarray]
) -> tuple[np.ndarray, np.ndarray]:
    """Children of every placed supertile: tile t of label j becomes ``children[j]`` placed
    by ``maps[t] @ matrices[j]``, the children of one tile contiguous and in rule order."""
    counts = np.array([len(k) for k in children], dtype=np.int64)
    starts = np.zeros(len(children) + 1, dtype=np.int64)
    np.cumsum(counts, out=starts[1:])
    kids = np.concatenate([np.asarray(k, dtype=np.int64) for k in children]) if len(children) else np.zeros(0, np.int64)
    dtype = np.result_type(maps.dtype, *[np.asarray(m).dtype for m in matrices])
    mats = np.concatenate([np.asarray(m, dtype=dtype).reshape(-1, 3, 3) for m in matrices])
    label = np.ascontiguousarray(label, dtype=np.int64)
    maps = np.ascontiguousarray(maps, dtype=dtype)
    total = int(counts[label].sum()) if len(label) else 0
    out_label = np.empty(total, dtype=np.int64)
    out_maps = np.empty((total, 3, 3), dtype=dtype)
    if total:
        _expand(label, maps, starts, kids, np.ascontiguousarray(mats), out_label, out_maps)
    return out_label, out_maps


def sandwich(left: np.ndarray, maps: np.ndarray, right: np.ndarray) -> np.ndarray:
    """``left @ maps[i] @ right`` for every map, as float64 (n, 3, 3), in one pass."""
    out = np.empty((len(maps), 3, 3))
    if len(maps):
        _sandwich(np.asarray(left, dtype=float), np.ascontiguousarray(maps), np.asarray(right, dtype=float), out)
    return out
