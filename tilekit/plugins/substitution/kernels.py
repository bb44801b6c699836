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

from tilekit.jit import njit


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


@njit(cache=True, nogil=True)
def _key_groups(keys):  # pragma: no cover - compiled
    """For every key, the index of its first occurrence (open addressing, one pass)."""
    n = keys.shape[0]
    bits = 1
    while (1 << bits) < 2 * n + 2:
        bits += 1
    size = 1 << bits
    table = np.full(size, -1, dtype=np.int64)
    first = np.empty(n, dtype=np.int64)
    mult = np.uint64(0x9E3779B97F4A7C15)
    shift = np.uint64(64 - bits)
    for i in range(n):
        k = keys[i]
        h = np.int64((np.uint64(k) * mult) >> shift)
        while True:
            j = table[h]
            if j < 0:
                table[h] = i
                first[i] = i
                break
            if keys[j] == k:
                first[i] = j
                break
            h = (h + 1) & (size - 1)
    return first


@njit(cache=True, nogil=True)
def _centre_groups(proto, transform, centres, quantum):  # pragma: no cover - compiled
    n = proto.shape[0]
    x = np.empty(n)
    y = np.empty(n)
    pmax = 1
    for i in range(n):
        p = proto[i]
        pmax = max(pmax, p)
        x[i] = transform[i, 0, 0] * centres[p, 0] + transform[i, 0, 1] * centres[p, 1] + transform[i, 0, 2]
        y[i] = transform[i, 1, 0] * centres[p, 0] + transform[i, 1, 1] * centres[p, 1] + transform[i, 1, 2]
    x0 = x.min()
    y0 = y.min()
    cells = max(x.max() - x0, y.max() - y0) / quantum + 2.0
    bits = 1
    while (1 << bits) < cells and bits < 63:
        bits += 1
    bits_p = 1
    while (1 << bits_p) <= pmax:
        bits_p += 1
    if 2 * bits + bits_p > 63:
        return np.full(1, -1, dtype=np.int64)  # the packed key would not fit
    rep = np.arange(n)
    keep = np.arange(n)
    for offset in (0.0, 0.5):
        # group the representatives so far on this grid; rows follow their representative
        m = keep.shape[0]
        keys = np.empty(m, dtype=np.int64)
        for k in range(m):
            i = keep[k]
            qx = np.int64(np.floor((x[i] - x0) / quantum + offset))
            qy = np.int64(np.floor((y[i] - y0) / quantum + offset))
            keys[k] = (proto[i] << (2 * bits)) | (qx << bits) | qy
        first = _key_groups(keys)
        now = np.arange(n)
        for k in range(m):
            now[keep[k]] = keep[first[k]]
        for i in range(n):
            rep[i] = now[rep[i]]
        count = 0
        for k in range(m):
            if first[k] == k:
                count += 1
        survivors = np.empty(count, dtype=np.int64)
        count = 0
        for k in range(m):
            if first[k] == k:
                survivors[count] = keep[k]
                count += 1
        keep = survivors
    return rep


def centre_groups(proto: np.ndarray, transform: np.ndarray, centres: np.ndarray, quantum: float) -> np.ndarray | None:
    """For every tile, the index of the first tile with its prototile and placed centroid
    (quantised at ``quantum`` on two grids offset by half a cell); None when the packed key
    would not fit in 63 bits (the caller groups rows instead)."""
    n = len(proto)
    if n < 2:
        return np.arange(n)
    rep = _centre_groups(
        np.ascontiguousarray(proto, dtype=np.int64), np.ascontiguousarray(transform, dtype=float),
        np.ascontiguousarray(centres, dtype=float), float(quantum),
    )
    return None if len(rep) and rep[0] < 0 else rep


@njit(cache=True, nogil=True)
def _meets(label, maps, centres, radii, box, similar, out):  # pragma: no cover - compiled
    x0, y0, x1, y1 = box[0], box[1], box[2], box[3]
    for i in range(label.shape[0]):
        j = label[i]
        cx = maps[i, 0, 0] * centres[j, 0] + maps[i, 0, 1] * centres[j, 1] + maps[i, 0, 2]
        cy = maps[i, 1, 0] * centres[j, 0] + maps[i, 1, 1] * centres[j, 1] + maps[i, 1, 2]
        r = radii[j]
        if similar:
            r *= np.sqrt(abs(maps[i, 0, 0] * maps[i, 1, 1] - maps[i, 0, 1] * maps[i, 1, 0]))
        dx = max(max(x0 - cx, cx - x1), 0.0)
        dy = max(max(y0 - cy, cy - y1), 0.0)
        out[i] = dx * dx + dy * dy <= r * r


def meets(label: np.ndarray, maps: np.ndarray, centres: np.ndarray, radii: np.ndarray, box, similar: bool) -> np.ndarray:
    """Mask of placed supertiles whose bounding disc (``centres[label]``, ``radii[label]``,
    scaled by the map's linear factor when ``similar``) meets the box (x0, y0, x1, y1)."""
    out = np.empty(len(label), dtype=np.bool_)
    if len(label):
        _meets(np.ascontiguousarray(label, dtype=np.int64), np.ascontiguousarray(maps, dtype=float),
               np.ascontiguousarray(centres, dtype=float), np.ascontiguousarray(radii, dtype=float),
               np.asarray(box, dtype=float), bool(similar), out)
    return out
