"""What ``--depth N`` draws for substitution tilings (issue 14): a full, well-framed patch.

The depth-N patch is N substitutions of the seed cluster: the seed's *whole* tile for a system
assembled from halves, turned into a sun or star about a vertex of angle 360/n; a depth with
a region covers the region (or says which depth would); ``tiles_per_generation`` counts the
tiles of the depth-N patch.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from tilekit.cli import cli
from tilekit.plugins.substitution import builtin_systems, tiling
from tilekit.plugins.substitution.tiling import system_properties

ASSEMBLED = ["penrose-p2", "penrose-p3", "ammann-beenker", "kite-domino"]
#: Systems whose halves are assembled by [assemble] (every half yields its whole tile); a
#: [pairing] system (kite-domino) keeps only halves whose partner is generated too.
ASSEMBLE_TABLE = ["penrose-p2", "penrose-p3", "ammann-beenker"]


def test_p3_depth_8_is_a_star_not_a_wedge():
    # tilekit render penrose-p3 --depth 8 (the README's example): five thick rhombs at a vertex,
    # substituted 8 times, centred on the origin; it used to be a wedge of 1,330 rhombs
    t = tiling("penrose-p3", depth=8)
    patch = t.patch()
    assert len(patch) == system_properties(t.system, 8)["tiles_per_generation"][8] > 5 * 1330
    x0, y0, x1, y1 = patch.bounds()
    assert abs(x0 + x1) < 0.2 * (x1 - x0) and abs(y0 + y1) < 0.2 * (y1 - y0)  # centred
    centres = np.array([g.centroid.coords[0] for g in patch.geometries()])
    angles = np.arctan2(centres[:, 1], centres[:, 0])
    sectors = np.bincount(((angles + math.pi) // (2 * math.pi / 5)).astype(int) % 5, minlength=5)
    assert sectors.min() > 0.9 * sectors.max()  # five-fold: every sector alike


@pytest.mark.parametrize("name,n", [("penrose-p3", 5), ("penrose-p2", 5), ("ammann-beenker", 8)])
def test_depth_zero_is_a_sun_or_star(name, n):
    # tilekit render penrose-p2 --depth 0: the sun of five kites; P3 the star of five rhombs
    patch = tiling(name, depth=0).patch()
    assert len(patch) == n
    assert patch.validate().ok


@pytest.mark.parametrize("name", ASSEMBLED)
def test_tiles_per_generation_is_the_patch(name):
    # tilekit show penrose-p3's tiles_per_generation = the tiles of render --depth n
    props = system_properties(builtin_systems()[name])
    counts = props["tiles_per_generation"]
    assert len(counts) >= 4 and counts[0] >= 1  # kite-domino depth 0 is no longer empty
    for n, c in enumerate(counts[:4]):
        patch = tiling(name, depth=n).patch()
        assert len(patch) == c
        assert patch.validate().ok  # no overlaps, each whole tile once


@pytest.mark.parametrize("name", ASSEMBLE_TABLE)
def test_depth_patch_covers_its_seed(name):
    # the depth-N patch covers the inflated seed cluster; whole tiles may reach one tile beyond
    t = tiling(name, depth=3)
    patch = t.patch()
    union = shapely.union_all(patch.geometries(), grid_size=1e-9)
    seed = t._cluster_polygon(3)
    assert seed.difference(union).area < 1e-6 * seed.area
    reach = max(float(np.ptp(p.outline, axis=0).max()) for p in t.prototiles)
    assert union.difference(seed.buffer(reach)).area < 1e-6 * seed.area


def test_depth_with_region_covers_the_region(tmp_path):
    # tilekit render penrose-p3 --depth 6 --region -10,-10,10,10: the whole region, no blank half
    region = (-10, -10, 10, 10)
    for name in ("penrose-p3", "penrose-p2", "chair", "ammann-beenker"):
        patch = tiling(name, depth=7).patch(region)
        assert patch.validate(region).ok, name
    patch = tiling("penrose-p3", depth=8).patch((30, 30, 40, 40))  # off the star: the seed moves
    assert patch.validate((30, 30, 40, 40)).ok


def test_depth_too_small_for_region_says_so(tmp_path):
    # tilekit render penrose-p3 --depth 2 --region -50,-50,50,50: one line naming the depth needed
    db = f"sqlite:///{tmp_path / 'c.sqlite'}"
    res = CliRunner().invoke(cli, ["--catalogue", db, "render", "penrose-p3", "--depth", "2", "--region",
                                   "-50,-50,50,50", "-o", str(tmp_path / "x.svg")])
    assert res.exit_code == 2
    lines = res.stderr.splitlines()
    assert len(lines) == 1 and "needs depth" in lines[0] and "--depth" in lines[0]
    assert not (tmp_path / "x.svg").exists()
