"""The Spectre monotile through its nine-hexagon supertile substitution (arXiv:2305.17743)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from test_substitution import assert_valid

from tilekit.errors import ParameterError, ParseError
from tilekit.geometry import Affine
from tilekit.plugins.substitution import builtin_systems, from_spec, tiling
from tilekit.plugins.substitution.keypoint import keypoint_system_from_data


def spectre():
    return builtin_systems()["spectre"]


def test_spectre_outline_is_tile_1_1() -> None:
    """Tile(1,1): 14 unit edges, turning by multiples of 30 degrees (arXiv:2305.17743 §1)."""
    pts = spectre().tile.outline
    edges = np.roll(pts, -1, axis=0) - pts
    assert len(pts) == 14
    assert np.allclose(np.linalg.norm(edges, axis=1), 1.0)
    angles = np.degrees(np.arctan2(edges[:, 1], edges[:, 0]))
    assert np.allclose(angles / 30, np.round(angles / 30))


def test_growth_factor_is_4_plus_sqrt15() -> None:
    """The paper's substitution on nine hexagons has growth factor 4 + sqrt(15)."""
    eig, freq = spectre().perron_frobenius()
    assert eig == pytest.approx(4 + math.sqrt(15))
    assert freq.sum() == pytest.approx(1)


def test_tile_counts_are_matrix_powers() -> None:
    s = spectre()
    m = s.substitution_matrix()
    per_label = np.array([len(b) for b in s.base])  # the Mystic (Gamma) holds two spectres
    assert per_label.tolist() == [2, 1, 1, 1, 1, 1, 1, 1, 1]
    for label in range(s.n):
        e = np.zeros(s.n, dtype=np.int64)
        e[label] = 1
        for n in range(4):
            _, tr, _ = s.generate(n, seed_label=label)
            assert len(tr) == int(per_label @ np.linalg.matrix_power(m, n) @ e)
    assert s.tile_counts(3) == [1, 9, 71, 559]


@pytest.mark.parametrize("depth", [1, 2, 3])
def test_supertiles_are_valid_homochiral_and_hole_free(depth: int) -> None:
    s = spectre()
    for label in (0, 1, 8):
        patch = tiling("spectre", depth=depth, seed=s.labels[label]).patch()
        assert_valid(patch)
        # strictly chiral: no tile is reflected
        det = np.linalg.det(patch.transform[:, :2, :2])
        assert np.allclose(det, 1.0)
        union = shapely.union_all(patch.geometries(), grid_size=1e-9)
        assert union.geom_type == "Polygon" and len(union.interiors) == 0
        assert union.area == pytest.approx(len(patch) * s.tile.area)


def test_region_patches_cover_regions() -> None:
    t = tiling("spectre")
    for region in [(-12, -12, 12, 12), (200, 40, 230, 52)]:
        patch = t.patch(region)
        assert_valid(patch, region)
    assert t.properties()["periodic"] is False


def test_spec_round_trip_and_options() -> None:
    t = tiling("spectre").configure(depth=2, seed="Psi")
    back = from_spec(t.spec())
    assert back.spec() == {"system": "spectre", "depth": 2, "seed": "Psi"}
    assert len(back.patch()) == spectre().tile_counts(2, start=8)[-1]
    with pytest.raises(ParameterError, match="not a supertile label"):
        t.configure(seed="Omega")


def test_keypoint_loader_rejects_bad_data() -> None:
    data = dict(spectre().data)
    rules = dict(data["rules"])
    rules["Delta"] = rules["Delta"][:-1]
    with pytest.raises(ParseError, match=r"bad\.toml: rule for 'Delta' must list 8 slots"):
        keypoint_system_from_data({**data, "rules": rules}, "bad.toml")
    rules["Delta"] = ["Omega"] * 8
    with pytest.raises(ParseError, match="unknown label 'Omega'"):
        keypoint_system_from_data({**data, "rules": rules}, "bad.toml")
    placement = dict(data["placement"])
    placement["steps"] = [[60, 3, 1], [0, 2, 0], [60, 3, 1], [60, 3, 1], [0, 2, 0], [60, 3, 1], [-120, 3, 2]]
    with pytest.raises(ParseError, match="overlapping tiles"):
        keypoint_system_from_data({**data, "placement": placement}, "bad.toml")


def test_seed_transform_places_the_supertile() -> None:
    s = spectre()
    _, a, _ = s.generate(2)
    _, b, _ = s.generate(2, Affine.translation(5, 7))
    assert np.allclose(b[:, :2, 2] - a[:, :2, 2], [5, 7])
