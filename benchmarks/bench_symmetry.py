"""Symmetry-analysis speed: wallpaper_group, colouring_report and orbits on small units.

Run: pytest benchmarks/bench_symmetry.py --benchmark-enable
(with the project's default ``--benchmark-disable`` each function runs once, untimed).

wallpaper_group is called for every catalogue record when records are built, so it must
stay well under a second for units of a dozen tiles.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tilekit import Affine, Colouring, PeriodicTiling, Prototile
from tilekit.geometry import regular_polygon
from tilekit.symmetry import colouring_report, isogonality, isohedrality, wallpaper_group

S3 = math.sqrt(3.0)


def hexagons(colouring: str | None = None) -> PeriodicTiling:
    ang = np.arange(6) * math.pi / 3
    hexagon = np.column_stack([np.cos(ang), np.sin(ang)])
    col = Colouring.parse(colouring) if colouring else None
    return PeriodicTiling([Prototile(hexagon)], [0], np.eye(3)[None], (1.5, S3 / 2), (0, S3), col)


def triangles() -> PeriodicTiling:
    return PeriodicTiling(
        [Prototile(regular_polygon(3))],
        [0, 0],
        np.array([np.eye(3), Affine.half_turn((0.75, S3 / 4))]),
        (1, 0),
        (0.5, S3 / 2),
    )


def rhombitrihexagonal() -> PeriodicTiling:
    """3.4.6.4 with a 6-tile unit (1 hexagon, 3 squares, 2 triangles)."""
    corner = [np.array([math.cos(k * math.pi / 3), math.sin(k * math.pi / 3)]) for k in range(7)]
    normal = [
        np.array([math.cos(math.pi / 6 + k * math.pi / 3), math.sin(math.pi / 6 + k * math.pi / 3)])
        for k in range(-1, 6)
    ]
    tiles = [np.array(corner[:6])]
    for k in range(3):
        n = normal[k + 1]
        tiles.append(np.array([corner[k], corner[k] + n, corner[k + 1] + n, corner[k + 1]]))
    for k in range(2):
        tiles.append(np.array([corner[k], corner[k] + normal[k], corner[k] + normal[k + 1]]))
    s = S3 + 1
    return PeriodicTiling(
        [Prototile(t) for t in tiles], list(range(6)), np.array([np.eye(3)] * 6), s * normal[1], s * normal[2]
    )


def supercell(tiling: PeriodicTiling, n: int) -> PeriodicTiling:
    """The same tiling described by an n x n block of units (a non-primitive unit)."""
    shifts = [a * tiling.v1 + b * tiling.v2 for a in range(n) for b in range(n)]
    transforms = np.concatenate([[Affine.translation(*s) @ m for m in tiling.unit_transform] for s in shifts])
    protos = np.tile(tiling.unit_prototile, n * n)
    return PeriodicTiling(tiling.prototiles, protos, transforms, n * tiling.v1, n * tiling.v2)


@pytest.mark.parametrize(
    "name, build, expected",
    [
        ("triangles", triangles, "p6m"),
        ("hexagons", hexagons, "p6m"),
        ("3.4.6.4", rhombitrihexagonal, "p6m"),
        ("3.4.6.4 as 2x2 units (24 tiles)", lambda: supercell(rhombitrihexagonal(), 2), "p6m"),
        ("3.4.6.4 as 4x4 units (96 tiles)", lambda: supercell(rhombitrihexagonal(), 4), "p6m"),
    ],
)
def test_wallpaper_group_speed(benchmark, name, build, expected) -> None:
    tiling = build()
    group = benchmark(wallpaper_group, tiling)
    assert group.iuc == expected


def test_colouring_report_speed(benchmark) -> None:
    """The perfect 3-colouring of 6^3, with the colour-preserving group."""
    report = benchmark(colouring_report, hexagons("(1)(2 3 1)(3 1 2)"))
    assert report.perfect and report.index == 6


def test_orbits_speed(benchmark) -> None:
    tiling = rhombitrihexagonal()
    result = benchmark(lambda: (isohedrality(tiling), isogonality(tiling)))
    assert result == (3, 1)
