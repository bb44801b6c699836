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
from collections import deque
from functools import lru_cache

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
# the walk adds these to Python floats: plain floats keep round() and + off NumPy scalars
_COS_F, _SIN_F = _COS.tolist(), _SIN.tolist()
_Q = 1e6  # points are hashed at this resolution
#: The largest radius a layout may need (edge lengths); a symbol needing more is refused.
MAX_RADIUS = 120.0


def interior_steps(p: int) -> int:
    """The interior angle of a regular p-gon in steps of 15°."""
    steps = STEPS * (p - 2)
    if steps % (2 * p):
        raise GeometryError(f"a regular {p}-gon's angle is not a multiple of 15°, so it is not laid out here")
    return steps // (2 * p)


def develop(sym: DSymbol, radius: float) -> dict[tuple[int, int, int, int], tuple[int, float, float]]:
    """Every flag whose vertex lies within ``radius`` of the base vertex: key (x, y
    quantised, direction, side) -> (chamber, x, y)."""
    inner = {p: interior_steps(p) for p in set(sym.face)}
    flags: dict[tuple[int, int, int, int], tuple[int, float, float]] = {}
    start = (0, 0, 0, 1)
    flags[start] = (0, 0.0, 0.0)
    queue = deque([(0, 0.0, 0.0, 0, 1)])
    r2 = radius * radius
    s0, s1, s2, face = sym.s0, sym.s1, sym.s2, sym.face
    cos, sin = _COS_F, _SIN_F
    while queue:
        c, x, y, a, s = queue.popleft()
        nxt = (
            (s0[c], x + cos[a], y + sin[a], (a + STEPS // 2) % STEPS, -s),
            (s1[c], x, y, (a + s * inner[face[c]]) % STEPS, -s),
            (s2[c], x, y, a, -s),
        )
        for c2, x2, y2, a2, t in nxt:
            if x2 * x2 + y2 * y2 > r2:
                continue
            key = (round(x2 * _Q), round(y2 * _Q), a2, t)
            got = flags.get(key)
            if got is None:
                flags[key] = (c2, x2, y2)
                queue.append((c2, x2, y2, a2, t))
            elif got[0] != c2:
                raise GeometryError("the D-symbol does not lay out in the plane: a flag got two chambers")
    return flags


def _lattice(flags: dict, radius: float) -> tuple[np.ndarray, np.ndarray] | None:
    pts = np.array([(x, y) for (_kx, _ky, a, s), (c, x, y) in flags.items() if c == 0 and a == 0 and s == 1])
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
def layout(sym: DSymbol) -> tuple[dict, np.ndarray, np.ndarray]:
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


def faces(sym: DSymbol, flags: dict) -> list[tuple[int, np.ndarray, np.ndarray, int]]:
    """One (size, centre, placement, chamber) per face with a flag in ``flags``: the placement
    maps the unit regular polygon (first edge from the origin along +x, counter-clockwise)
    onto the face, and the chamber is that of the flag (its corner 0, its edge 0-1, the face)."""
    out: dict[tuple[int, int], tuple[int, np.ndarray, np.ndarray, int]] = {}
    for (_kx, _ky, a, s), (c, x, y) in flags.items():
        if s != 1:
            continue
        p = sym.face[c]
        half = 0.5 / math.tan(math.pi / p)
        cx = x + 0.5 * _COS_F[a] - half * _SIN_F[a]
        cy = y + 0.5 * _SIN_F[a] + half * _COS_F[a]
        key = (round(cx * 1e4), round(cy * 1e4))
        if key not in out:
            m = Affine.translation(x, y) @ Affine.rotation(a * 2 * math.pi / STEPS)
            out[key] = (p, np.array([cx, cy]), m, c)
    return list(out.values())


def periodic_tiling(sym: DSymbol, *, name: str = "", family: str = "k-uniform", cls: type = PeriodicTiling,
                    **kw) -> PeriodicTiling:
    """The tiling of ``sym`` as a PeriodicTiling (reduced lattice basis, unit in the
    fundamental parallelogram), coloured by polygon size."""
    flags, v1, v2 = layout(sym)
    inv = np.linalg.inv(np.column_stack([v1, v2]))
    sizes = tuple(sorted(set(sym.face)))
    protos, transforms = [], []
    for p, centre, m, _c in faces(sym, flags):
        f = inv @ centre
        if np.all(np.floor(f + 1e-7) == 0):
            protos.append(sizes.index(p))
            transforms.append(m)
    if not protos:
        raise GeometryError("the layout found no face in the fundamental parallelogram")
    order = sorted(range(len(protos)), key=lambda i: (protos[i], round(transforms[i][0, 2], 6), round(transforms[i][1, 2], 6)))
    protos = [protos[i] for i in order]
    transforms = np.array([transforms[i] for i in order])
    colouring = Colouring.by_aspect([size_colour(sizes[p]) for p in protos])
    return cls(regular_prototiles(sizes), protos, transforms, v1, v2, colouring, family=family, name=name, **kw)
