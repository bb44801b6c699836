"""Lay a D-symbol out in the plane as unit-edge regular polygons, and read off its lattice.

Every flag of the tiling is a point (the vertex), an edge direction and a side (the face to
the left or to the right of the edge, seen from the vertex). The base flag, chamber 0, is
the origin, direction 0, face on the left; the three involutions act on flags by
geometry — σ0 moves to the edge's other end and turns the direction round, σ1 turns about
the vertex by the face's interior angle, σ2 swaps the side — and on chambers by the symbol,
so a breadth-first walk labels every flag within a radius. Directions are whole multiples
of 15° (the interior angles of triangles, squares, hexagons, octagons and dodecagons are),
kept as integers mod 24, so only the vertex points are floating point. A flag reached twice
with two labels would mean the symbol does not tile the plane; it raises.

The translations of the tiling are the flags labelled 0 with direction 0 and the face on the
left; the shortest one and the shortest one not parallel to it are a basis of the lattice
(in the plane the two successive minima always are). The faces whose centres fall in the
fundamental parallelogram of that basis are the translational unit.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from tilekit.colouring import Colouring
from tilekit.errors import GeometryError
from tilekit.geometry import Affine
from tilekit.plugins.kuniform.dsymbol import DSymbol
from tilekit.regular.tiles import regular_prototiles, size_colour
from tilekit.tiling import PeriodicTiling

#: Directions are multiples of 360° / STEPS.
STEPS = 24
_COS = np.cos(np.arange(STEPS) * 2 * math.pi / STEPS)
_SIN = np.sin(np.arange(STEPS) * 2 * math.pi / STEPS)
_Q = 1e6  # points are hashed at this resolution
#: The largest radius a layout may need (edge lengths); a symbol needing more is refused.
MAX_RADIUS = 120.0


def interior_steps(p: int) -> int:
    """The interior angle of a regular p-gon in steps of 15°."""
    steps = STEPS * (p - 2)
    if steps % (2 * p):
        raise GeometryError(f"a regular {p}-gon's angle is not a multiple of 15°, so it is not laid out here")
    return steps // (2 * p)


class Flags(NamedTuple):
    """The flags a walk reached, in the order reached: chamber, vertex x and y, edge direction
    (in steps of 15°) and side (1: the face is on the left)."""

    chamber: np.ndarray
    x: np.ndarray
    y: np.ndarray
    direction: np.ndarray
    side: np.ndarray


def develop(sym: DSymbol, radius: float) -> Flags:
    """Every flag whose vertex lies within ``radius`` of the base vertex (a compiled loop,
    :func:`.kernels.develop_flags`; flags are told apart by their vertex rounded at 1e-6,
    direction and side)."""
    # start-up cost: the compiled kernels (numba) load only when a layout is developed
    from tilekit.plugins.kuniform.kernels import develop_flags

    inner = np.array([interior_steps(p) for p in sym.face], dtype=np.int64)
    s0, s1, s2 = (np.asarray(s, dtype=np.int64) for s in (sym.s0, sym.s1, sym.s2))
    # at most 2 x 6 flags per vertex, at most 2 / sqrt(3) vertices per unit area (3^6)
    cap = int(14 * math.pi * (radius + 1) ** 2) + 64
    while True:
        n, c, x, y, a, side = develop_flags(s0, s1, s2, inner, float(radius), _COS, _SIN, _Q, cap)
        if n != -2:
            break
        cap *= 2
    if n == -1:
        raise GeometryError("the D-symbol does not lay out in the plane: a flag got two chambers")
    return Flags(c, x, y, a, side)


def _lattice(flags: Flags, radius: float) -> tuple[np.ndarray, np.ndarray] | None:
    base = (flags.chamber == 0) & (flags.direction == 0) & (flags.side == 1)
    pts = np.column_stack([flags.x[base], flags.y[base]])
    if len(pts) < 3:
        return None
    norms = np.hypot(pts[:, 0], pts[:, 1])
    order = np.argsort(norms, kind="stable")
    pts, norms = pts[order], norms[order]
    nonzero = norms > 1e-6
    if not nonzero.any():
        return None
    i = int(np.argmax(nonzero))
    v1 = pts[i]
    cross = np.abs(v1[0] * pts[:, 1] - v1[1] * pts[:, 0])
    independent = cross > 1e-6 * norms[i]
    if not independent.any():
        return None
    v2 = pts[int(np.argmax(independent))]
    if np.hypot(*v1) + np.hypot(*v2) + 4.0 > radius:
        return None
    if v1[0] * v2[1] - v1[1] * v2[0] < 0:
        v2 = -v2
    return v1, v2


@lru_cache(maxsize=4)
def layout(sym: DSymbol) -> tuple[Flags, np.ndarray, np.ndarray]:
    """The flags round the base vertex out to a radius that shows a lattice basis and a
    whole fundamental parallelogram, with that basis (the last few kept: a stored record is
    laid out for its unit and again for its GomJau-Hogg notation; callers only read it)."""
    radius = 6.0 + math.sqrt(sym.size)
    while True:
        flags = develop(sym, radius)
        basis = _lattice(flags, radius)
        if basis is not None:
            return flags, basis[0], basis[1]
        if radius >= MAX_RADIUS:
            raise GeometryError(
                f"the D-symbol's translational unit does not fit in a disc of radius {MAX_RADIUS:g} "
                f"(the layout limit); it has {sym.size} chambers"
            )
        radius = min(MAX_RADIUS, radius * 1.5)


#: Affine.rotation by each direction, and the inradius of each polygon size (edge 1).
_ROT = np.array([Affine.rotation(a * 2 * math.pi / STEPS) for a in range(STEPS)])
_HALF = np.array([0.5 / math.tan(math.pi / p) if p >= 3 else 0.0 for p in range(43)])


def _face_arrays(sym: DSymbol, flags: Flags) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`faces` as arrays (size, centre, placement, chamber), computed for all flags at
    once; a face is kept at the first of its flags in the walk's order."""
    on = flags.side == 1
    a, c, x, y = flags.direction[on], flags.chamber[on], flags.x[on], flags.y[on]
    p = np.asarray(sym.face, dtype=np.int64)[c]
    half = _HALF[p]
    cx = x + 0.5 * _COS[a] - half * _SIN[a]
    cy = y + 0.5 * _SIN[a] + half * _COS[a]
    key = np.column_stack([np.rint(cx * 1e4), np.rint(cy * 1e4)])
    _, first = np.unique(key, axis=0, return_index=True)
    first = np.sort(first)
    m = _ROT[a[first]].copy()
    m[:, 0, 2], m[:, 1, 2] = x[first], y[first]
    return p[first], np.column_stack([cx[first], cy[first]]), m, c[first]


def faces(sym: DSymbol, flags: Flags) -> list[tuple[int, np.ndarray, np.ndarray, int]]:
    """One (size, centre, placement, chamber) per face with a flag in ``flags``: the placement
    maps the unit regular polygon (first edge from the origin along +x, counter-clockwise)
    onto the face, and the chamber is that of the flag (its corner 0, its edge 0-1, the face)."""
    p, centre, m, c = _face_arrays(sym, flags)
    return list(zip(p.tolist(), centre, m, c.tolist()))


def periodic_tiling(sym: DSymbol, *, name: str = "", family: str = "k-uniform", cls: type = PeriodicTiling,
                    **kw) -> PeriodicTiling:
    """The tiling of ``sym`` as a PeriodicTiling (reduced lattice basis, unit in the
    fundamental parallelogram), coloured by polygon size."""
    flags, v1, v2 = layout(sym)
    inv = np.linalg.inv(np.column_stack([v1, v2]))
    sizes = tuple(sorted(set(sym.face)))
    p, centre, m, _c = _face_arrays(sym, flags)
    f0 = inv[0, 0] * centre[:, 0] + inv[0, 1] * centre[:, 1]
    f1 = inv[1, 0] * centre[:, 0] + inv[1, 1] * centre[:, 1]
    inside = (np.floor(f0 + 1e-7) == 0) & (np.floor(f1 + 1e-7) == 0)
    if not inside.any():
        raise GeometryError("the layout found no face in the fundamental parallelogram")
    protos = [sizes.index(q) for q in p[inside].tolist()]
    transforms = list(m[inside])
    order = sorted(range(len(protos)), key=lambda i: (protos[i], round(transforms[i][0, 2], 6), round(transforms[i][1, 2], 6)))
    protos = [protos[i] for i in order]
    transforms = np.array([transforms[i] for i in order])
    colouring = Colouring.by_aspect([size_colour(sizes[p]) for p in protos])
    return cls(regular_prototiles(sizes), protos, transforms, v1, v2, colouring, family=family, name=name, **kw)
