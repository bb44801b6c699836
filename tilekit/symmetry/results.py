"""What the symmetry analysis returns: operations, symmetry groups, wallpaper groups and
colouring reports (plain frozen dataclasses)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tilekit.geometry import Affine, Isometry
from tilekit.symmetry.lattice import _in_lattice


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
