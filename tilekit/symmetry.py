"""The symmetry group of a periodic tiling (§3.5), its wallpaper type (§3.2, §3.6.3), colourings (§3.6.1).

``symmetries(tiling)`` finds every isometry that maps the tiling onto itself, by testing the
congruences of one tile onto the tiles of the translational unit against the geometry of
the whole unit (outlines and markings); ``wallpaper_group(tiling)`` names the group among
the 17 (orbifold and IUC names); ``colouring_report(tiling)`` / ``is_perfect_colouring``
decide whether every symmetry of the uncoloured tiling permutes the colours (§3.6.1);
``tile_orbits`` / ``vertex_orbits`` give the transitivity classes (k-isohedral,
k-isogonal). The method, tolerances and limits are described in docs/symmetry.md.

The group is returned as a lattice of translations plus one coset representative per
element of the point group: every symmetry is ``T(L) @ op`` for exactly one representative
``op`` and one lattice vector ``L``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import Any

import numpy as np

from tilekit.colouring import permutation_order
from tilekit.errors import GeometryError, ParameterError
from tilekit.geometry import Affine, Isometry
from tilekit.tiling import PeriodicTiling

#: Default tolerance, relative to the tiling's length scale (square root of the median tile area).
DEFAULT_TOL = 1e-6

#: Point-to-point distances computed per block when comparing located tiles.
_BLOCK_PAIRS = 2_000_000

#: The 17 wallpaper groups: IUC short name -> Conway's orbifold symbol (x for a cross-cap).
ORBIFOLD: dict[str, str] = {
    "p1": "o",
    "p2": "2222",
    "pm": "**",
    "pg": "xx",
    "cm": "*x",
    "pmm": "*2222",
    "pmg": "22*",
    "pgg": "22x",
    "cmm": "2*22",
    "p4": "442",
    "p4m": "*442",
    "p4g": "4*2",
    "p3": "333",
    "p3m1": "*333",
    "p31m": "3*3",
    "p6": "632",
    "p6m": "*632",
}
#: Orbifold symbol -> IUC short name.
IUC: dict[str, str] = {v: k for k, v in ORBIFOLD.items()}


# --------------------------------------------------------------------------- results


@dataclass(frozen=True, eq=False)
class Operation:
    """One isometry of a symmetry group: its 3x3 matrix and its classification (§3.1)."""

    matrix: np.ndarray
    isometry: Isometry

    @property
    def kind(self) -> str:
        return self.isometry.kind

    def __repr__(self) -> str:
        iso = self.isometry
        if iso.kind == "rotation":
            deg = math.degrees(iso.angle)
            return f"Operation(rotation {deg:.6g} deg about {_fmt(iso.centre)})"
        if iso.kind in ("reflection", "glide reflection"):
            deg = math.degrees(iso.angle)
            extra = f", glide {_fmt(iso.vector)}" if iso.kind == "glide reflection" else ""
            return f"Operation({iso.kind} axis {deg:.6g} deg through {_fmt(iso.centre)}{extra})"
        if iso.kind == "translation":
            return f"Operation(translation {_fmt(iso.vector)})"
        return "Operation(identity)"


def _fmt(v: Sequence[float]) -> str:
    return "(" + ", ".join(f"{float(x):.6g}" for x in v) + ")"


def _operation(m: np.ndarray) -> Operation:
    m = np.array(m, dtype=float)
    m[2] = (0.0, 0.0, 1.0)
    return Operation(m, Affine.classify(m, tol=1e-6))


@dataclass(frozen=True, eq=False)
class SymmetryGroup:
    """The symmetries of a periodic tiling: a translation lattice and point-group cosets.

    ``lattice`` holds the (Lagrange-reduced) basis of every translation symmetry as rows;
    ``operations`` has one representative per point-group element (identity first; a pure
    reflection is chosen where the coset holds one, otherwise the glide with the shortest
    glide vector); ``lattice_index`` is how many times finer the true lattice is than the
    one spanned by the tiling's v1, v2 (1 when the given unit is primitive) — for a group
    of colour-preserving symmetries (``coloured``), how many times coarser its lattice is
    than the uncoloured tiling's; ``tol`` is the absolute tolerance used.
    """

    lattice: np.ndarray
    operations: tuple[Operation, ...]
    lattice_index: int
    tol: float
    coloured: bool = False

    @property
    def point_group_order(self) -> int:
        return len(self.operations)

    @property
    def primitive(self) -> bool:
        """True when the tiling's v1, v2 already span every translation symmetry."""
        return self.lattice_index == 1

    def translations(self) -> tuple[Operation, Operation]:
        return (
            _operation(Affine.translation(*self.lattice[0])),
            _operation(Affine.translation(*self.lattice[1])),
        )

    def contains(self, m: np.ndarray) -> bool:
        """Whether the isometry ``m`` is in the group (some representative times a lattice translation)."""
        m = np.asarray(m, dtype=float)
        for op in self.operations:
            if np.allclose(op.matrix[:2, :2], m[:2, :2], atol=1e-6):
                d = m[:2, 2] - op.matrix[:2, 2]
                return _in_lattice(d, self.lattice, self.tol)
        return False

    def elements(self, radius: int = 1) -> np.ndarray:
        """Group elements ``T(a w1 + b w2) @ op`` for |a|, |b| <= radius, as (n, 3, 3)."""
        rng = np.arange(-radius, radius + 1)
        a, b = np.meshgrid(rng, rng, indexing="ij")
        shifts = np.column_stack([a.ravel(), b.ravel()]) @ self.lattice
        reps = np.array([op.matrix for op in self.operations])
        out = np.broadcast_to(reps, (len(shifts),) + reps.shape).copy()
        out[:, :, :2, 2] += shifts[:, None, :]
        return out.reshape(-1, 3, 3)


@dataclass(frozen=True, eq=False)
class WallpaperGroup:
    """The wallpaper type of a periodic tiling's symmetry group, with the evidence.

    ``iuc`` is the short International (IUC) name (p1 ... p6m) and ``orbifold`` Conway's
    symbol (o, 2222, **, xx, *x, ...; an ASCII x stands for the cross-cap).
    ``rotation_orders`` lists the distinct orders of the rotation centres (stabiliser
    orders, so p6 gives (2, 3, 6)); ``reflections`` / ``glide_reflections`` say whether
    there are mirrors and essential glides (glides that are not a reflection followed by a
    lattice translation along its axis); ``mirror_directions`` are the mirror axis angles in
    [0, π). ``generators`` generate the group: the two lattice translations, a rotation of
    the highest order and one reflection or glide where they exist. ``rotation_centres``
    holds (x, y, order) for one centre of each class modulo the lattice.
    """

    iuc: str
    orbifold: str
    group: SymmetryGroup
    rotation_orders: tuple[int, ...]
    reflections: bool
    glide_reflections: bool
    mirror_directions: tuple[float, ...]
    generators: tuple[Operation, ...]
    rotation_centres: tuple[tuple[float, float, int], ...] = field(default=(), repr=False)

    @property
    def lattice(self) -> np.ndarray:
        return self.group.lattice

    @property
    def operations(self) -> tuple[Operation, ...]:
        return self.group.operations

    @property
    def point_group_order(self) -> int:
        return self.group.point_group_order

    @property
    def lattice_index(self) -> int:
        return self.group.lattice_index

    def properties(self) -> dict[str, Any]:
        """JSON-scalar facts for a catalogue record (snake_case keys)."""
        return {
            "wallpaper_group": self.iuc,
            "orbifold": self.orbifold,
            "point_group_order": self.point_group_order,
            "rotation_orders": list(self.rotation_orders),
            "reflections": self.reflections,
            "glide_reflections": self.glide_reflections,
        }

    def __str__(self) -> str:
        return f"{self.iuc} ({self.orbifold})"


@dataclass(frozen=True, eq=False)
class ColouringReport:
    """Whether a tiling's colouring is perfect (§3.6.1), and why.

    ``permutations[i]`` is the permutation of colours (a tuple, colour c -> perm[c], 0-based)
    that ``generators[i]`` of the uncoloured group induces, or None when that symmetry
    sends two tiles of one colour to tiles of different colours (or two colours to one).
    ``colour_group`` is the wallpaper group of the colour-preserving symmetries and
    ``index`` its index in the uncoloured group (the size of the induced permutation
    group when the colouring is perfect).
    """

    perfect: bool
    colours: int
    symmetry: WallpaperGroup
    colour_group: WallpaperGroup
    index: int
    generators: tuple[Operation, ...]
    permutations: tuple[tuple[int, ...] | None, ...]
    violation: str | None = None

    def summary(self) -> str:
        head = (
            f"{'perfect' if self.perfect else 'not perfect'} {self.colours}-colouring; "
            f"tiling {self.symmetry}, colour-preserving {self.colour_group} (index {self.index})"
        )
        return head + (f"; {self.violation}" if self.violation else "")


# --------------------------------------------------------------------------- the cell


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
    areas = [abs(tiling.prototiles[int(p)].area) for p in tiling.unit_prototile]
    return math.sqrt(float(np.median(areas)))


# --------------------------------------------------------------------------- lattice helpers


def _reduce(b1: np.ndarray, b2: np.ndarray) -> np.ndarray:
    """Lagrange-Gauss reduction of a 2D lattice basis; rows, positively oriented."""
    b1, b2 = np.array(b1, dtype=float), np.array(b2, dtype=float)
    for _ in range(200):
        if b1 @ b1 > b2 @ b2:
            b1, b2 = b2, b1
        mu = round(float(b1 @ b2) / float(b1 @ b1))
        if mu == 0:
            break
        b2 = b2 - mu * b1
    if b1[0] * b2[1] - b1[1] * b2[0] < 0:
        b2 = -b2
    return np.array([b1, b2])


def _inv2(basis: np.ndarray) -> np.ndarray:
    """Inverse of a 2x2 matrix in closed form (for the lattice-coordinate map)."""
    (a, b), (c, d) = basis
    det = a * d - b * c
    return np.array([[d, -b], [-c, a]]) / det


def _frac(vectors: np.ndarray, basis: np.ndarray) -> np.ndarray:
    """Coordinates of vectors (..., 2) in the basis whose rows are the lattice vectors."""
    return np.asarray(vectors) @ _inv2(basis)


def _lattice_residual(v: np.ndarray, basis: np.ndarray) -> np.ndarray:
    """Distance of each vector (..., 2) from the nearest lattice point."""
    f = _frac(v, basis)
    return np.linalg.norm((f - np.rint(f)) @ basis, axis=-1)


def _in_lattice(v: np.ndarray, basis: np.ndarray, tol: float) -> bool:
    return bool(np.all(_lattice_residual(v, basis) < tol))


@cache
def _grid(r: int) -> np.ndarray:
    """Integer pairs (a, b) with |a|, |b| <= r, as a read-only (n, 2) float array."""
    rng = np.arange(-r, r + 1, dtype=float)
    a, b = np.meshgrid(rng, rng, indexing="ij")
    out = np.column_stack([a.ravel(), b.ravel()])
    out.setflags(write=False)
    return out


def _small_combos(basis: np.ndarray, r: int) -> np.ndarray:
    return _grid(r) @ basis


def _lattice_from(translations: np.ndarray, given: np.ndarray, index: int, tol: float) -> np.ndarray:
    """Reduced basis of the lattice spanned by ``given`` (rows) and ``translations``."""
    g = _reduce(given[0], given[1])
    if index == 1:
        return g
    f = _frac(translations, g)
    reps = (f - np.floor(f + 1e-9)) @ g  # representatives in the given cell
    cand = (reps[:, None, :] + _small_combos(g, 2)[None, :, :]).reshape(-1, 2)
    lengths = np.hypot(cand[:, 0], cand[:, 1])
    order = np.argsort(lengths, kind="stable")
    cand, lengths = cand[order], lengths[order]
    nz = lengths > tol
    cand, lengths = cand[nz], lengths[nz]
    w1 = cand[0]
    area = abs(g[0, 0] * g[1, 1] - g[0, 1] * g[1, 0]) / index
    cross = np.abs(w1[0] * cand[:, 1] - w1[1] * cand[:, 0])
    ok = np.flatnonzero(np.abs(cross - area) < tol * max(1.0, lengths[0]))
    if not len(ok):
        raise GeometryError(
            f"the {index} translations found do not form a lattice refining v1, v2 (tolerance {tol:g})"
        )
    basis = _reduce(w1, cand[ok[0]])
    bad = _lattice_residual(np.vstack([translations, given]), basis) >= tol * 10
    if bad.any():
        t = np.vstack([translations, given])[np.argmax(bad)]
        raise GeometryError(f"translation {t.tolist()} is not in the lattice found; raise the tolerance")
    return basis


# --------------------------------------------------------------------------- matching


def _congruences(a: np.ndarray, b: np.ndarray, tol: float) -> np.ndarray:
    """Every isometry mapping the cyclic outline ``a`` onto ``b`` (same point count), (c, 3, 3)."""
    k = len(a)
    za = a[:, 0] + 1j * a[:, 1]
    zb = b[:, 0] + 1j * b[:, 1]
    ca, cb = za.mean(), zb.mean()
    a0, b0 = za - ca, zb - cb
    i = int(np.argmax(np.abs(a0)))
    if abs(a0[i]) < tol:
        return np.zeros((0, 3, 3))
    j = np.arange(k)
    out = []
    forward = (j[:, None] + j[None, :]) % k  # row s: b[(s + j) % k]
    backward = (j[:, None] - j[None, :]) % k  # row s: b[(s - j) % k]
    # placed outlines may run either way round (a reflected placement reverses its
    # order), so both traversal directions are tried for direct and opposite maps
    for opposite, idx in ((False, forward), (False, backward), (True, forward), (True, backward)):
        src = np.conj(a0) if opposite else a0
        tgt = b0[idx]
        r = tgt[:, i] / src[i]
        ok = np.abs(np.abs(r) - 1.0) < tol / abs(a0[i])
        r = r / np.where(np.abs(r) > 0, np.abs(r), 1.0)
        ok &= np.max(np.abs(r[:, None] * src[None, :] - tgt), axis=1) < tol
        for rr in r[ok]:
            if opposite:
                lin = np.array([[rr.real, rr.imag], [rr.imag, -rr.real]])
                t = cb - rr * np.conj(ca)
            else:
                lin = np.array([[rr.real, -rr.imag], [rr.imag, rr.real]])
                t = cb - rr * ca
            m = np.eye(3)
            m[:2, :2] = lin
            m[:2, 2] = (t.real, t.imag)
            out.append(m)
    return np.array(out) if out else np.zeros((0, 3, 3))


def _candidate_pairs(cell: _Cell, centre: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(image, cell tile) pairs whose centres may agree modulo the lattice: a grid hash.

    Cell centres are reduced to fractional coordinates in [0, 1) and binned on a G x G
    grid (about one tile per bin); an image centre is compared only with the tiles in its
    own bin and the eight around it (wrapping round the cell), so the work grows with
    the number of images, not images x tiles.
    """
    m = len(cell)
    grid = max(1, int(math.isqrt(m)))
    inv = _inv2(cell.basis)
    fc = cell.centre @ inv
    cb = np.floor((fc - np.floor(fc)) * grid).astype(np.int64) % grid
    cid = cb[:, 0] * grid + cb[:, 1]
    order = np.argsort(cid, kind="stable")
    sorted_cid = cid[order]
    fi = centre @ inv
    ib = np.floor((fi - np.floor(fi)) * grid).astype(np.int64) % grid
    steps = sorted({d % grid for d in (-1, 0, 1)})
    ii_all, jj_all = [], []
    n = len(centre)
    for dx in steps:
        for dy in steps:
            nb = ((ib[:, 0] + dx) % grid) * grid + (ib[:, 1] + dy) % grid
            start = np.searchsorted(sorted_cid, nb, side="left")
            end = np.searchsorted(sorted_cid, nb, side="right")
            counts = end - start
            total = int(counts.sum())
            if not total:
                continue
            ii = np.repeat(np.arange(n), counts)
            pos = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts) + np.repeat(start, counts)
            ii_all.append(ii)
            jj_all.append(order[pos])
    if not ii_all:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(ii_all), np.concatenate(jj_all)


def _locate(cell: _Cell, pts: np.ndarray, centre: np.ndarray, label: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For image tiles (points (N, K, 2), centres (N, 2), labels (N,)) find the cell tile.

    Returns (j, shift): j[n] is the index of the cell tile that image n equals after
    translating it by the lattice vector shift[n], or -1 when image n is no tile. Centres
    are matched through a grid hash modulo the lattice; the point sets of matching pairs
    are then compared both ways, in blocks of bounded size.
    """
    n = len(pts)
    found = np.full(n, -1, dtype=np.int64)
    shift = np.zeros((n, 2))
    if n == 0:
        return found, shift
    tol = cell.tol
    ii, jj = _candidate_pairs(cell, centre)
    f = (centre[ii] - cell.centre[jj]) @ _inv2(cell.basis)
    r = np.rint(f)
    hit = (np.linalg.norm((f - r) @ cell.basis, axis=1) < tol) & (label[ii] == cell.label[jj])
    ii, jj, sh = ii[hit], jj[hit], r[hit] @ cell.basis
    k = pts.shape[1]
    block = max(1, _BLOCK_PAIRS // (k * k))
    same = np.zeros(len(ii), dtype=bool)
    for s in range(0, len(ii), block):
        sl = slice(s, s + block)
        a = pts[ii[sl]]  # (P, K, 2)
        b = cell.points[jj[sl]] + sh[sl, None, :]
        d = np.linalg.norm(a[:, :, None, :] - b[:, None, :, :], axis=3)  # (P, K, K)
        same[sl] = (d.min(axis=2).max(axis=1) < tol) & (d.min(axis=1).max(axis=1) < tol)
    ii, jj, sh = ii[same], jj[same], sh[same]
    # one match per image (a tile equals at most one tile of the cell): keep the first
    order = np.lexsort((jj, ii))
    ii, jj, sh = ii[order], jj[order], sh[order]
    first = np.ones(len(ii), dtype=bool)
    first[1:] = ii[1:] != ii[:-1]
    found[ii[first]] = jj[first]
    shift[ii[first]] = sh[first]
    return found, shift


def _images(
    cell: _Cell, maps: np.ndarray, idx: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cell tiles (all, or those at ``idx``) moved by every map: points (C*m, K, 2), centres, labels."""
    points, centre, label = cell.points, cell.centre, cell.label
    if idx is not None:
        points, centre, label = points[idx], centre[idx], label[idx]
    c, m, k = len(maps), len(label), points.shape[1]
    pts = Affine.apply(maps, points.reshape(-1, 2)).reshape(c * m, k, 2)
    cen = Affine.apply(maps, centre).reshape(c * m, 2)
    lab = np.tile(label, c)
    return pts, cen, lab


# --------------------------------------------------------------------------- the group


def _cosets(maps: np.ndarray, lattice: np.ndarray, tol: float) -> tuple[Operation, ...]:
    """One canonical representative per distinct linear part of ``maps`` (identity first)."""
    key = np.round(maps[:, :2, :2].reshape(-1, 4) * 1e5).astype(np.int64)
    _, first = np.unique(key, axis=0, return_index=True)
    out = [_canonical(maps[i], lattice, tol) for i in np.sort(first)]
    out.sort(key=_op_sort_key)
    return tuple(out)


def _op_sort_key(op: Operation) -> tuple:
    kinds = ["identity", "translation", "rotation", "reflection", "glide reflection"]
    iso = op.isometry
    ang = iso.angle % (2 * math.pi) if iso.kind == "rotation" else iso.angle
    return (kinds.index(iso.kind) if iso.kind in kinds else 9, round(ang, 6))


def _canonical(g: np.ndarray, lattice: np.ndarray, tol: float) -> Operation:
    """A tidy representative of the coset g + lattice.

    Identity for the translation coset; a rotation centre in the cell nearest the origin;
    for an opposite map, a pure reflection if the coset has one, else the shortest glide.
    """
    g = np.array(g, dtype=float)
    lin, t = g[:2, :2], g[:2, 2]
    f = _frac(t, lattice)
    t = (f - np.floor(f + 1e-9)) @ lattice
    det = lin[0, 0] * lin[1, 1] - lin[0, 1] * lin[1, 0]
    combos = _small_combos(lattice, 4)
    if det > 0:
        if np.allclose(lin, np.eye(2), atol=1e-6):
            return _operation(np.eye(3))
        # rotation: choose the translation whose centre is closest to the origin
        ts = t[None, :] + combos
        centres = np.linalg.solve(np.eye(2) - lin, ts.T).T
        best = int(np.argmin(np.round(np.hypot(centres[:, 0], centres[:, 1]) / tol)))
        m = np.eye(3)
        m[:2, :2] = lin
        m[:2, 2] = ts[best]
        return _operation(m)
    phi = 0.5 * math.atan2(lin[1, 0], lin[0, 0])
    u = np.array([math.cos(phi), math.sin(phi)])
    nrm = np.array([-u[1], u[0]])
    ts = t[None, :] + combos
    glide = np.abs(ts @ u)
    offset = np.abs(ts @ nrm)
    key = np.round(glide / tol) * 1e6 + np.round(offset / tol) * 1e-3
    best = int(np.argmin(key))
    m = np.eye(3)
    m[:2, :2] = lin
    m[:2, 2] = ts[best]
    return _operation(m)


def _assemble(accepted: np.ndarray, given: np.ndarray, tol: float, coloured: bool) -> SymmetryGroup:
    """Build the group from maps accepted modulo the lattice ``given`` (rows)."""
    lin = accepted[:, :2, :2]
    is_t = np.all(np.abs(lin - np.eye(2)) < 1e-6, axis=(1, 2))
    trans = accepted[is_t, :2, 2]
    index = int(is_t.sum())
    lattice = _lattice_from(trans, given, max(index, 1), tol)
    # a candidate that maps the cell's tiles onto tiles is a symmetry only if its linear part
    # maps the lattice into the translation group (then it maps every translate correctly)
    moved = np.einsum("kj,nij->nki", lattice, accepted[:, :2, :2])  # R w for each map, basis row
    keep = (_lattice_residual(moved, lattice) < tol * 10).all(axis=1)
    ops = _cosets(accepted[keep], lattice, tol)
    return SymmetryGroup(lattice=lattice, operations=ops, lattice_index=index, tol=tol, coloured=coloured)


#: Tiles near the anchor on which every candidate is tried before the whole cell.
_PROBE = 6


def _accepts(cell: _Cell, maps: np.ndarray, anchor: int) -> np.ndarray:
    """Which maps send every tile of the cell onto a tile of the tiling.

    Candidates are first tried on the few tiles nearest the anchor, which rejects almost
    every wrong one, and only the survivors on the whole cell.
    """
    ok = np.zeros(len(maps), dtype=bool)
    if not len(maps):
        return ok
    m = len(cell)
    alive = np.arange(len(maps))
    if m > _PROBE:
        near = np.argsort(np.hypot(*(cell.centre - cell.centre[anchor]).T), kind="stable")[:_PROBE]
        pts, cen, lab = _images(cell, maps, near)
        found, _ = _locate(cell, pts, cen, lab)
        alive = alive[(found >= 0).reshape(len(maps), len(near)).all(axis=1)]
    if len(alive):
        pts, cen, lab = _images(cell, maps[alive])
        found, _ = _locate(cell, pts, cen, lab)
        ok[alive[(found >= 0).reshape(len(alive), m).all(axis=1)]] = True
    return ok


def _primitive(cell: _Cell, lattice: np.ndarray) -> _Cell:
    """The cell's tiles modulo a finer lattice (one tile per class), over that lattice."""
    f = _frac(cell.centre, lattice)
    key = np.round((f - np.floor(f)) * 1e6).astype(np.int64) % 1_000_000
    _, first = np.unique(np.column_stack([key, cell.label]), axis=0, return_index=True)
    keep = np.sort(first)
    return _Cell(
        [cell.outlines[i] for i in keep],
        cell.points[keep],
        cell.count[keep],
        cell.centre[keep],
        cell.label[keep],
        cell.colour[keep],
        lattice,
        cell.tol,
    )


def _group_of_cell(cell: _Cell) -> SymmetryGroup:
    counts = np.bincount(cell.label)
    anchor = int(np.argmin(counts[cell.label] * 10_000 + np.arange(len(cell))))
    a = cell.outlines[anchor]
    cands = [
        _congruences(a, cell.outlines[j], cell.tol)
        for j in range(len(cell))
        if cell.label[j] == cell.label[anchor]
    ]
    maps = np.concatenate([c for c in cands if len(c)]) if any(len(c) for c in cands) else np.zeros((0, 3, 3))
    if not len(maps):
        raise GeometryError("no tile of the unit is congruent to its first tile: the unit is malformed")
    # translations first: when the unit is not primitive, continue on a primitive cell
    is_t = np.all(np.abs(maps[:, :2, :2] - np.eye(2)) < 1e-6, axis=(1, 2))
    trans = maps[is_t][_accepts(cell, maps[is_t], anchor)]
    if not len(trans):
        raise GeometryError(
            "the identity is not a symmetry of the unit: tiles overlap or repeat within the unit"
        )
    if len(trans) > 1:
        lattice = _lattice_from(trans[:, :2, 2], cell.basis, len(trans), cell.tol)
        prim = _primitive(cell, lattice)
        if len(prim) * len(trans) != len(cell):
            raise GeometryError(
                f"the unit's {len(cell)} tiles do not fall into {len(trans)} translates of a "
                "primitive cell: tiles overlap or repeat within the unit"
            )
        sub = _group_of_cell(prim)
        return SymmetryGroup(sub.lattice, sub.operations, len(trans) * sub.lattice_index, sub.tol)
    rest = maps[~is_t]
    accepted = np.concatenate([trans, rest[_accepts(cell, rest, anchor)]])
    return _assemble(accepted, cell.basis, cell.tol, coloured=False)


def _check(tiling: Any) -> PeriodicTiling:
    if not isinstance(tiling, PeriodicTiling):
        raise ParameterError(
            f"symmetry analysis needs a PeriodicTiling (a translational unit and two vectors), "
            f"not {type(tiling).__name__}"
        )
    return tiling


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


def symmetries(
    tiling: PeriodicTiling,
    tol: float = DEFAULT_TOL,
    *,
    colours: bool = False,
    match_prototiles: bool = False,
) -> SymmetryGroup:
    """The symmetry group of a periodic tiling (§3.5).

    Every symmetry maps the unit's anchor tile onto some tile, and modulo the lattice onto
    a tile of the unit, so the candidates are the congruences (rotations and reflections of
    the outline's point cycle) of the anchor onto each unit tile. A candidate is accepted
    when it maps every tile of the unit onto a tile of the tiling — compared by outline and
    marking point sets, up to a lattice translation — and its linear part preserves the
    translation lattice. Candidates that are translations reveal the true lattice, which
    may be finer than v1, v2 (``lattice_index`` > 1).

    ``tol`` is relative to the tiling's length scale (the square root of the median tile
    area). With ``colours=True`` only colour-preserving symmetries count. Tiles are matched
    by geometry; ``match_prototiles=True`` also requires the same prototile index (for
    congruent prototiles that a family wants kept apart).
    """
    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    group = _group_of_cell(_base_cell(tiling, abs_tol, match_prototiles))
    if not colours:
        return group
    cell, n = _colour_cell(tiling, group, abs_tol, match_prototiles)
    return _colour_group(cell, group, n)


def _colour_group(cell: _Cell, group: SymmetryGroup, n: int) -> SymmetryGroup:
    """The colour-preserving subgroup: elements (modulo n*L) that keep every tile's colour.

    Each element T(s) op of the group modulo n*L permutes the cell's tiles; the permutation
    is composed from those of the coset representatives and of the two lattice
    translations, so only |P| + 2 maps are ever located, not |P| n^2.
    """
    reps = np.array([op.matrix for op in group.operations])
    steps = np.array([Affine.translation(*v) for v in group.lattice])
    perm = _tile_perm(cell, np.concatenate([reps, steps]))
    rep_perm, (w1, w2) = perm[: len(reps)], perm[len(reps) :]
    ident = np.arange(len(cell))
    shift_perm = []
    pa = ident
    for _a in range(n):
        pb = pa
        for _b in range(n):
            shift_perm.append(pb)
            pb = w2[pb]
        pa = w1[pa]
    moved = np.array(shift_perm)[:, rep_perm]  # (n^2, |P|, m): tile t -> shift(rep(t))
    good = (cell.colour[moved] == cell.colour).all(axis=2).reshape(-1)
    elems = _elements_mod(group, n)
    sub = _assemble(elems[good], cell.basis, cell.tol, coloured=True)
    coarser = int(round(_cell_area(sub.lattice) / _cell_area(group.lattice)))
    return SymmetryGroup(sub.lattice, sub.operations, coarser, sub.tol, coloured=True)


def _tile_perm(cell: _Cell, maps: np.ndarray) -> np.ndarray:
    """(len(maps), m): the cell tile (modulo the cell's lattice) each map sends each tile to."""
    pts, cen, lab = _images(cell, maps)
    found, _ = _locate(cell, pts, cen, lab)
    if (found < 0).any():
        raise GeometryError("a symmetry of the tiling failed to map the coloured cell onto itself")
    return found.reshape(len(maps), len(cell))


def _elements_mod(group: SymmetryGroup, n: int) -> np.ndarray:
    """The group's elements modulo the lattice n * L (L the group's lattice), as (|P| n^2, 3, 3)."""
    a, b = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    shifts = np.column_stack([a.ravel(), b.ravel()]) @ group.lattice
    reps = np.array([op.matrix for op in group.operations])
    out = np.broadcast_to(reps, (len(shifts),) + reps.shape).copy()
    out[:, :, :2, 2] += shifts[:, None, :]
    return out.reshape(-1, 3, 3)


def _colour_maps(cell: _Cell, maps: np.ndarray) -> list[tuple[int, ...] | None]:
    """For each symmetry in ``maps``, the colour permutation it induces on ``cell``, or None."""
    found = _tile_perm(cell, maps)
    k = int(cell.colour.max()) + 1
    used = np.unique(cell.colour)
    out: list[tuple[int, ...] | None] = []
    for row in found:
        src, dst = cell.colour, cell.colour[row]
        perm = np.arange(k)
        perm[src] = dst
        consistent = np.array_equal(perm[src], dst) and len(np.unique(perm[used])) == len(used)
        out.append(tuple(int(x) for x in perm) if consistent else None)
    return out


# --------------------------------------------------------------------------- classification


def _mirror_facts(op: Operation, lattice: np.ndarray, tol: float) -> tuple[bool, bool]:
    """For an opposite coset: (has a pure reflection, has an essential glide)."""
    lin, t = op.matrix[:2, :2], op.matrix[:2, 2]
    phi = 0.5 * math.atan2(lin[1, 0], lin[0, 0])
    u = np.array([math.cos(phi), math.sin(phi)])
    combos = _small_combos(lattice, 6)
    lengths = np.hypot(combos[:, 0], combos[:, 1])
    nz = lengths > tol
    cross = np.abs(combos[:, 0] * u[1] - combos[:, 1] * u[0])
    par = nz & (cross < tol)
    d_par = float(lengths[par].min())  # shortest lattice vector along the axis
    proj = np.abs(combos @ u)
    proj_d = float(proj[proj > tol].min())  # spacing of the lattice's projection on the axis
    g = float(t @ u)
    reflection = abs(g / proj_d - round(g / proj_d)) * proj_d < tol
    centred = abs(proj_d - d_par) > tol
    glide = centred or abs(g / d_par - round(g / d_par)) * d_par > tol
    return bool(reflection), bool(glide)


def _fixes(op: Operation, c: np.ndarray, lattice: np.ndarray, tol: float) -> bool:
    """Whether some element of op's coset fixes the point c."""
    lin, t = op.matrix[:2, :2], op.matrix[:2, 2]
    return _in_lattice(c - lin @ c - t, lattice, tol)


def _rotation_centres(group: SymmetryGroup) -> list[tuple[np.ndarray, int]]:
    """Rotation centres modulo the lattice with their orders (stabiliser sizes).

    The centres of the rotations in the coset of (R, t) are (I - R)^-1 (t + L) for lattice
    vectors L; modulo the lattice, L need only run over L / (I - R)L, whose classes have
    representatives with coordinates 0..2 (the index det(I - R) is 4, 3, 2 or 1).
    """
    lat, tol = group.lattice, group.tol * 10
    direct = [op for op in group.operations if op.kind == "rotation"]
    if not direct:
        return []
    shifts = np.array([(a, b) for a in range(3) for b in range(3)], dtype=float) @ lat
    cands = []
    for op in direct:
        lin, t = op.matrix[:2, :2], op.matrix[:2, 2]
        cands.append(np.linalg.solve(np.eye(2) - lin, (t + shifts).T).T)
    c = np.vstack(cands)
    f = _frac(c, lat)
    f = f - np.floor(f + 1e-9)
    c = f @ lat
    # deduplicate modulo the lattice
    keep: list[int] = []
    for i in range(len(c)):
        if not keep or (_lattice_residual(c[keep] - c[i], lat) >= tol).all():
            keep.append(i)
    c = c[keep]
    # the order of a centre is 1 + the number of rotation cosets with an element fixing it
    lins = np.array([op.matrix[:2, :2] for op in direct])
    ts = np.array([op.matrix[:2, 2] for op in direct])
    moved = c[None, :, :] - np.einsum("nij,kj->nki", lins, c) - ts[:, None, :]  # (r, k, 2)
    fixes = _lattice_residual(moved, lat) < tol
    orders = 1 + fixes.sum(axis=0)
    return [(c[i], int(orders[i])) for i in range(len(c))]


def classify_group(group: SymmetryGroup) -> WallpaperGroup:
    """Name the wallpaper type of a symmetry group (all 17 distinguished).

    n, the highest rotation order in the point group, and whether the point group has
    reflections split the 17 into families; within them: pm / cm / pg by whether mirrors
    exist and whether essential glides run parallel to them; pmm / cmm / pmg / pgg by
    mirrors and glides in the two perpendicular directions; p4m / p4g and p3m1 / p31m by
    whether every rotation centre of the highest order lies on a mirror.
    """
    ops = group.operations
    lat, tol = group.lattice, group.tol * 10
    direct = [op for op in ops if Affine.determinant(op.matrix) > 0]
    opposite = [op for op in ops if Affine.determinant(op.matrix) < 0]
    n = len(direct)
    if n not in (1, 2, 3, 4, 6) or (opposite and len(opposite) != n):
        raise GeometryError(f"the symmetries found ({len(ops)} cosets) do not form a wallpaper group")
    facts = [_mirror_facts(op, lat, tol) for op in opposite]
    refl = [f[0] for f in facts]
    glide = [f[1] for f in facts]
    centres = _rotation_centres(group)
    top = [c for c, o in centres if o == n]

    def on_mirror(c: np.ndarray) -> bool:
        return any(_fixes(op, c, lat, tol) for op in opposite)

    if n == 1:
        iuc = "p1" if not opposite else ("pg" if not refl[0] else ("cm" if glide[0] else "pm"))
    elif n == 2:
        if not opposite:
            iuc = "p2"
        else:
            nref = sum(refl)
            if nref == 2:
                iuc = "cmm" if any(glide) else "pmm"
            else:
                iuc = "pmg" if nref == 1 else "pgg"
    elif n == 3:
        iuc = "p3" if not opposite else ("p3m1" if all(on_mirror(c) for c in top) else "p31m")
    elif n == 4:
        iuc = "p4" if not opposite else ("p4m" if all(on_mirror(c) for c in top) else "p4g")
    else:
        iuc = "p6" if not opposite else "p6m"
    mirror_dirs = sorted(
        round(op.isometry.angle % math.pi, 12) for op, r in zip(opposite, refl) if r
    )
    generators: list[Operation] = list(group.translations())
    rot = [op for op in direct if op.kind == "rotation" and op.isometry.order == n]
    if rot:
        generators.append(min(rot, key=lambda op: op.isometry.angle % (2 * math.pi)))
    if opposite:
        generators.append(opposite[0])
    return WallpaperGroup(
        iuc=iuc,
        orbifold=ORBIFOLD[iuc],
        group=group,
        rotation_orders=tuple(sorted({o for _, o in centres})),
        reflections=any(refl),
        glide_reflections=any(glide),
        mirror_directions=tuple(float(d) for d in mirror_dirs),
        generators=tuple(generators),
        rotation_centres=tuple((float(c[0]), float(c[1]), int(o)) for c, o in centres),
    )


def wallpaper_group(
    tiling: PeriodicTiling,
    tol: float = DEFAULT_TOL,
    *,
    colours: bool = False,
    match_prototiles: bool = False,
) -> WallpaperGroup:
    """The wallpaper group of a periodic tiling: orbifold, IUC name, generators (§3.2, §3.6.3).

    ``colours=True`` gives the group of the colour-preserving symmetries instead.
    """
    return classify_group(symmetries(tiling, tol, colours=colours, match_prototiles=match_prototiles))


# --------------------------------------------------------------------------- orbits


def _union_find(n: int, pairs: np.ndarray) -> np.ndarray:
    """Connected components of 0..n-1 under the (k, 2) pairs, labelled 0.. in first-seen order."""
    parent = np.arange(n)

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b in pairs:
        ra, rb = root(int(a)), root(int(b))
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    roots = np.array([root(i) for i in range(n)])
    _, labels = np.unique(roots, return_inverse=True)
    # relabel in order of first appearance so tile 0 is in orbit 0
    order = {r: k for k, r in enumerate(dict.fromkeys(labels.tolist()))}
    return np.array([order[x] for x in labels.tolist()], dtype=np.int64)


def _generator_maps(group: SymmetryGroup) -> np.ndarray:
    ops = [op.matrix for op in group.operations if op.kind != "identity"]
    ops += [Affine.translation(*v) for v in group.lattice]
    return np.array(ops)


def tile_orbits(
    tiling: PeriodicTiling, tol: float = DEFAULT_TOL, *, match_prototiles: bool = False
) -> np.ndarray:
    """The transitivity class of each tile of the unit under the symmetry group (§3.5, §5.1).

    Returns one label per unit tile (0 for tile 0's orbit, then in order of first
    appearance); the number of labels is the k of a k-isohedral tiling.
    """
    tiling = _check(tiling)
    cell = _base_cell(tiling, _abs_tol(tiling, tol), match_prototiles)
    return _tile_orbits_of(cell, _group_of_cell(cell))


def _tile_orbits_of(cell: _Cell, group: SymmetryGroup) -> np.ndarray:
    maps = _generator_maps(group)
    pts, cen, lab = _images(cell, maps)
    found, _ = _locate(cell, pts, cen, lab)
    src = np.tile(np.arange(len(cell)), len(maps))
    if (found < 0).any():
        raise GeometryError("a symmetry failed to map the unit's tiles onto tiles (tolerance too tight?)")
    return _union_find(len(cell), np.column_stack([src, found]))


def isohedrality(tiling: PeriodicTiling, tol: float = DEFAULT_TOL) -> int:
    """k such that the tiling is k-isohedral: the number of transitivity classes of tiles."""
    return int(tile_orbits(tiling, tol).max()) + 1


def tiling_vertices(tiling: PeriodicTiling, tol: float = DEFAULT_TOL) -> np.ndarray:
    """One point per vertex of the tiling modulo the lattice of v1, v2 (§5.1).

    A vertex is a point where three or more tiles meet. Candidates are the tiles' corners
    (``Prototile.corners`` where given, else every outline point); a candidate is kept when
    at least three tiles of the surrounding patch reach it, so points that only shape an
    edge, or the straight angle of a tile drawn with a point mid-edge, are not vertices.
    """
    import shapely

    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    basis = np.array([tiling.v1, tiling.v2])
    cand = []
    for p, m in zip(tiling.unit_prototile, tiling.unit_transform):
        proto = tiling.prototiles[int(p)]
        pts = proto.outline if proto.corners is None else proto.outline[list(proto.corners)]
        cand.append(Affine.apply(m, pts))
    cand = np.vstack(cand)
    f = _frac(cand, basis)
    f = f - np.floor(f + 1e-9)
    reduced = f @ basis
    key = np.round(f * 1e6).astype(np.int64) % 1_000_000
    _, first = np.unique(key, axis=0, return_index=True)
    reduced = reduced[np.sort(first)]
    # tiles around the fundamental cell
    lo, hi = reduced.min(axis=0), reduced.max(axis=0)
    ub = tiling.unit_tile_bounds()
    pad = float(max(ub[:, 2].max() - ub[:, 0].min(), ub[:, 3].max() - ub[:, 1].min()))
    patch = tiling.patch((lo[0] - pad, lo[1] - pad, hi[0] + pad, hi[1] + pad))
    geoms = patch.geometries()
    tree = shapely.STRtree(geoms)
    points = shapely.points(reduced)
    qi, _ = tree.query(points, predicate="dwithin", distance=abs_tol * 10)
    valence = np.bincount(qi, minlength=len(reduced))
    return reduced[valence >= 3]


def vertex_orbits(tiling: PeriodicTiling, tol: float = DEFAULT_TOL) -> tuple[np.ndarray, np.ndarray]:
    """Vertices modulo the lattice (as ``tiling_vertices``) and their transitivity classes.

    The number of classes is the k of a k-isogonal tiling (1 for the regular and the
    Archimedean tilings, §5.1).
    """
    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    group = _group_of_cell(_base_cell(tiling, abs_tol, False))
    return _vertex_orbits_of(tiling, group, tol)


def _vertex_orbits_of(tiling: PeriodicTiling, group: SymmetryGroup, tol: float) -> tuple[np.ndarray, np.ndarray]:
    abs_tol = _abs_tol(tiling, tol)
    verts = tiling_vertices(tiling, tol)
    basis = np.array([tiling.v1, tiling.v2])
    inv = _inv2(basis)
    pairs = []
    for g in _generator_maps(group):
        img = Affine.apply(g, verts)
        f = (img[:, None, :] - verts[None, :, :]) @ inv
        resid = np.linalg.norm((f - np.rint(f)) @ basis, axis=2)
        hit = resid < abs_tol * 10
        if not hit.any(axis=1).all():
            raise GeometryError("a symmetry failed to map the tiling's vertices onto vertices")
        pairs.append(np.column_stack([np.arange(len(verts)), hit.argmax(axis=1)]))
    labels = _union_find(len(verts), np.vstack(pairs)) if pairs else np.zeros(len(verts), dtype=np.int64)
    return verts, labels


def isogonality(tiling: PeriodicTiling, tol: float = DEFAULT_TOL) -> int:
    """k such that the tiling is k-isogonal: the number of transitivity classes of vertices."""
    return int(vertex_orbits(tiling, tol)[1].max()) + 1


# --------------------------------------------------------------------------- colourings


def colouring_report(
    tiling: PeriodicTiling, tol: float = DEFAULT_TOL, *, match_prototiles: bool = False
) -> ColouringReport:
    """Decide whether the tiling's colouring is perfect (§3.6.1, §5.4.3), with the evidence.

    A colouring is perfect when every symmetry of the uncoloured tiling maps all tiles of
    one colour onto tiles of one colour (so it induces a permutation of the colours). It
    suffices to test a generating set of the group — the lattice translations and one
    representative per point-group coset — on a cell of the coloured tiling whose lattice
    every symmetry preserves, since induced permutations compose. The report also gives
    the wallpaper group of the colour-preserving symmetries and its index.
    """
    perfect, gens, perms, cell, group, n = _perfect(tiling, tol, match_prototiles)
    violation = None
    if not perfect:
        bad = perms.index(None)
        violation = f"the symmetry {gens[bad]!r} sends tiles of one colour to tiles of different colours"
    colour_group = _colour_group(cell, group, n)
    index = (group.point_group_order * _cell_area(colour_group.lattice)) / (
        colour_group.point_group_order * _cell_area(group.lattice)
    )
    return ColouringReport(
        perfect=perfect,
        colours=len(np.unique(cell.colour)),
        symmetry=classify_group(group),
        colour_group=classify_group(colour_group),
        index=int(round(index)),
        generators=gens,
        permutations=tuple(perms),
        violation=violation,
    )


def _cell_area(lattice: np.ndarray) -> float:
    return abs(float(lattice[0, 0] * lattice[1, 1] - lattice[0, 1] * lattice[1, 0]))


def _perfect(
    tiling: PeriodicTiling, tol: float, match_prototiles: bool, group: SymmetryGroup | None = None
) -> tuple[bool, tuple[Operation, ...], list[tuple[int, ...] | None], _Cell, SymmetryGroup, int]:
    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    if group is None:
        group = _group_of_cell(_base_cell(tiling, abs_tol, match_prototiles))
    cell, n = _colour_cell(tiling, group, abs_tol, match_prototiles)
    gens = group.translations() + tuple(op for op in group.operations if op.kind != "identity")
    perms = _colour_maps(cell, np.array([g.matrix for g in gens]))
    return all(p is not None for p in perms), gens, perms, cell, group, n


def _abs_tol(tiling: PeriodicTiling, tol: float) -> float:
    if not (isinstance(tol, int | float) and 0 < tol < 0.1):
        raise ParameterError(f"tolerance {tol!r} must be a number in (0, 0.1) (relative to the tile size)")
    return tol * _scale(tiling)


def is_perfect_colouring(
    tiling: PeriodicTiling, tol: float = DEFAULT_TOL, *, match_prototiles: bool = False
) -> bool:
    """True when every symmetry of the uncoloured tiling permutes the colours (§3.6.1)."""
    return _perfect(tiling, tol, match_prototiles)[0]


# --------------------------------------------------------------------------- everything at once


def symmetry_properties(
    tiling: PeriodicTiling, tol: float = DEFAULT_TOL, *, colouring: bool = True, vertices: bool = True
) -> dict[str, Any]:
    """The symmetry facts a catalogue record wants, from one computation of the group.

    Keys: wallpaper_group, orbifold, point_group_order, rotation_orders, reflections,
    glide_reflections (as ``WallpaperGroup.properties``), k_isohedral (tile classes),
    k_isogonal (vertex classes; omitted with ``vertices=False``) and perfect_colouring
    (whether the tiling's own colouring is perfect; omitted with ``colouring=False``).
    All values are JSON scalars or lists.
    """
    tiling = _check(tiling)
    abs_tol = _abs_tol(tiling, tol)
    cell = _base_cell(tiling, abs_tol, False)
    group = _group_of_cell(cell)
    props = classify_group(group).properties()
    props["k_isohedral"] = int(_tile_orbits_of(cell, group).max()) + 1
    if vertices:
        props["k_isogonal"] = int(_vertex_orbits_of(tiling, group, tol)[1].max()) + 1
    if colouring:
        props["perfect_colouring"] = bool(_perfect(tiling, tol, False, group)[0])
    return props
