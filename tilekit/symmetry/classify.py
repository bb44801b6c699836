"""Naming a symmetry group among the 17 wallpaper groups (§3.2, §3.6.3) from its lattice and
point-group cosets (the rules are tabulated in docs/symmetry.md)."""

from __future__ import annotations

import math

import numpy as np

from tilekit.errors import GeometryError
from tilekit.geometry import Affine
from tilekit.symmetry.cell import DEFAULT_TOL
from tilekit.symmetry.group import symmetries
from tilekit.symmetry.lattice import _frac, _in_lattice, _lattice_residual, _small_combos
from tilekit.symmetry.names import ORBIFOLD
from tilekit.symmetry.results import Operation, SymmetryGroup, WallpaperGroup
from tilekit.tiling import PeriodicTiling


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
