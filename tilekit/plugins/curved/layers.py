"""Layers of a regular tiling {p, q}, exactly: layer 0 is the central tile, layer k + 1 the
tiles sharing an edge with layers 0..k (the "successive side-reflections" of OEIS A054888).

Hyperbolic tilings grow by a boundary automaton that never compares coordinates, so no tile
is made twice and none is lost, whatever the float error of the matrices. The patch of
layers 0..k is a disc; its boundary is a cycle of vertices, each with the number of patch
tiles at it (``count``), and of edges, each with the tile it belongs to (``owner``, an index
into the last layer) and that tile's edge number (``slot``). A vertex with q − 1 tiles has
one tile missing, and that one tile lies across both boundary edges at the vertex: so the
next layer has one tile per maximal run of boundary edges joined at such vertices, attached
by the half-turn of the run's first edge. The new boundary is each new tile's free edges;
where two new tiles meet at an old vertex that they fill (count q), they share an edge, and
the two copies of it cancel. A layer is one compiled pass over the boundary (kernels.py);
``layer_counts`` is the same automaton in NumPy (runs by flatnonzero and repeat,
cancellations in vectorised passes), the tests' second formulation. Layers stream: only the
last layer and the boundary are kept.

The sphere's tilings are finite (at most 20 faces): a breadth-first search over the edge
half-turns with faces told apart by their centres, which lie at least an edge apart.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from tilekit.errors import GeometryError
from tilekit.plugins.curved.model import RegularPolygon


def _cancel(count: np.ndarray, owner: np.ndarray, slot: np.ndarray, q: int
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cancel the shared edges at vertices that are full (count == q): vertex i goes with its
    two edges i − 1 and i (the same edge, walked there and back), and its neighbours i − 1 and
    i + 1 become one vertex whose count is the sum. Sites far enough apart (no other site
    within two places) are done together in each pass."""
    while True:
        n = len(count)
        site = count == q
        if not site.any():
            return count, owner, slot
        if n <= 3:
            raise GeometryError("the boundary of the patch closed up: a tiling of the sphere is not grown by layers")
        near = np.roll(site, 1) | np.roll(site, -1) | np.roll(site, 2) | np.roll(site, -2)
        pick = site & ~near
        if not pick.any():  # every site has another near it: do the first alone this pass
            pick = np.zeros(n, dtype=bool)
            pick[np.flatnonzero(site)[0]] = True
        i = np.flatnonzero(pick)
        before, after = (i - 1) % n, (i + 1) % n
        count = count.copy()
        count[after] = count[before] + count[after]
        keep = np.ones(n, dtype=bool)
        keep[i] = False
        keep[before] = False
        count, owner, slot = count[keep], owner[keep], slot[keep]
        if (count > q).any():
            raise GeometryError("layer growth found a vertex with more than q tiles (not a disc)")


_GROW_ERRORS = {
    -1: "no open vertex on the boundary: the tiling closed up",
    -2: "a new tile would be enclosed by the patch: the tiling closed up",
    -3: "a cancellation reached past the start of the boundary: the patch is not a disc",
    -4: "layer growth found a vertex with more than q tiles (not a disc)",
}


def _start(p: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The central tile's boundary: p vertices with one tile each, edge j its edge j."""
    return np.ones(p, dtype=np.int32), np.zeros(p, dtype=np.int32), np.arange(p, dtype=np.int32)


def hyperbolic_layers(p: int, q: int, depth: int | None = None) -> Iterator[np.ndarray]:
    """The transforms (n_k, 3, 3) of layer k = 0, 1, ..., depth (forever when depth is None),
    each layer made by one compiled pass (:func:`tilekit.plugins.curved.kernels.grow`)."""
    # measured start-up cost: numba's import (~0.3 s) only when a patch is made
    from tilekit.plugins.curved.kernels import grow

    half = np.ascontiguousarray(RegularPolygon(p, q).half_turns())
    layer = np.eye(3)[None].copy()
    yield layer
    count, owner, slot = _start(p)
    k = 0
    while depth is None or k < depth:
        k += 1
        out = np.empty((len(count), 3, 3))
        g, count, owner, slot = grow(count, owner, slot, layer, half, p, q, out)
        if g < 0:
            raise GeometryError(f"{{{p},{q}}} layer {k}: " + _GROW_ERRORS[int(g)])
        layer = out[:g]
        yield layer


def hyperbolic_transforms(p: int, q: int, depth: int, capacity: int = 0) -> tuple[np.ndarray, list[int]]:
    """Layers 0..depth in one (N, 3, 3) array, written in place layer after layer (no
    concatenation), and the layer sizes. ``capacity``: the expected N (an estimate; the
    buffer grows when it is short, and an untouched tail costs no memory)."""
    # measured start-up cost: as in hyperbolic_layers
    from tilekit.plugins.curved.kernels import grow

    half = np.ascontiguousarray(RegularPolygon(p, q).half_turns())
    buf = np.empty((max(capacity, 64), 3, 3))
    buf[0] = np.eye(3)
    start, end = 0, 1
    sizes = [1]
    count, owner, slot = _start(p)
    for k in range(1, depth + 1):
        need = end + int(np.count_nonzero(count != q - 1))  # the next layer's size exactly
        if need > len(buf):
            bigger = np.empty((max(need, 2 * len(buf)), 3, 3))
            bigger[:end] = buf[:end]
            buf = bigger
        g, count, owner, slot = grow(count, owner, slot, buf[start:end], half, p, q, buf[end:])
        if g < 0:
            raise GeometryError(f"{{{p},{q}}} layer {k}: " + _GROW_ERRORS[int(g)])
        start, end = end, end + g
        sizes.append(g)
    return buf[:end], sizes


def layer_counts(p: int, q: int, depth: int, stop_over: int | None = None) -> list[int]:
    """Tiles in layers 0..depth from the boundary automaton in NumPy alone (no matrices, no
    compiled code): the independent formulation the tests hold the compiled one to.
    ``stop_over``: stop after the first layer with more tiles than this."""
    out = [1]
    count = np.ones(p, dtype=np.int64)
    owner = np.zeros(p, dtype=np.int64)
    slot = np.arange(p, dtype=np.int64)
    for _ in range(depth):
        starts = np.flatnonzero(count != q - 1)
        s0 = int(starts[0])
        count, slot = np.roll(count, -s0), np.roll(slot, -s0)
        starts = starts - s0
        run = np.diff(np.append(starts, len(count)))
        free = p - run
        out.append(len(starts))
        if stop_over is not None and out[-1] > stop_over:
            break
        g = np.repeat(np.arange(len(starts)), free)
        offset = np.arange(int(free.sum())) - np.repeat(np.cumsum(free) - free, free)
        new_slot = (slot[starts][g] + 1 + offset) % p
        new_count = np.where(offset == 0, count[starts][g] + 2, 1)
        count, owner, slot = _cancel(new_count, g, new_slot, q)
    return out


def spherical_layers(p: int, q: int) -> list[np.ndarray]:
    """The faces of the spherical {p, q} as layers of transforms (breadth-first over half-turns)."""
    poly = RegularPolygon(p, q)
    half = poly.half_turns()
    min_sep = poly.inradius  # centres of distinct faces are 2 * inradius apart
    centres = [np.array([0.0, 0.0, 1.0])]
    layers = [np.eye(3)[None].copy()]
    while True:
        cand = np.matmul(layers[-1][:, None], half[None]).reshape(-1, 3, 3)
        new: list[np.ndarray] = []
        for m in cand:
            c = m[:, 2]
            if all(np.linalg.norm(c - d) > min_sep for d in centres):
                centres.append(c)
                new.append(m)
        if not new:
            return layers
        layers.append(np.array(new))
