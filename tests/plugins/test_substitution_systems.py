"""The built-in substitution systems: counts, eigen-data, validity at several depths, records."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from test_substitution import assert_valid

from tilekit.geometry import Affine
from tilekit.plugins import catalogue_records, get_family
from tilekit.plugins.substitution import builtin_systems, tiling
from tilekit.plugins.substitution.engine import assemble, generate

PHI = (1 + math.sqrt(5)) / 2
SILVER = 1 + math.sqrt(2)
SIMILARITY_SYSTEMS = [
    "penrose-p2",
    "penrose-p3",
    "ammann-a3",
    "kite-domino",
    "chair",
    "sphinx",
    "ammann-beenker",
    "pinwheel",
]


def test_every_book_system_ships() -> None:
    assert set(SIMILARITY_SYSTEMS) <= set(builtin_systems())


@pytest.mark.parametrize("name", SIMILARITY_SYSTEMS)
def test_tile_counts_per_generation_are_powers_of_the_substitution_matrix(name: str) -> None:
    s = builtin_systems()[name]
    m = s.substitution_matrix()
    for seed in range(s.n):
        e = np.zeros(s.n, dtype=np.int64)
        e[seed] = 1
        for n in range(1, 5):
            proto, _ = generate(s, n, seed_prototile=seed)
            assert np.bincount(proto, minlength=s.n).tolist() == (np.linalg.matrix_power(m, n) @ e).tolist()
        assert [sum(c) for c in s.counts(4, seed)] == [
            int((np.linalg.matrix_power(m, n) @ e).sum()) for n in range(5)
        ]


@pytest.mark.parametrize("name", SIMILARITY_SYSTEMS)
def test_self_similar_systems_have_eigenvalue_s_squared(name: str) -> None:
    """Areas scale by s^2 under inflation, so the area vector is a left eigenvector of the
    substitution matrix with eigenvalue s^2, the Perron-Frobenius eigenvalue."""
    s = builtin_systems()[name]
    eig, freq = s.perron_frobenius()
    assert eig == pytest.approx(s.scale**2)
    areas = np.array([p.area for p in s.prototiles])
    assert areas @ s.substitution_matrix() == pytest.approx(s.scale**2 * areas)
    assert freq.sum() == pytest.approx(1.0)


@pytest.mark.parametrize("name", SIMILARITY_SYSTEMS)
@pytest.mark.parametrize("depth", [1, 3, 5])
def test_fixed_depth_patches_validate(name: str, depth: int) -> None:
    """No overlaps, and no gap inside the inflated seed tile: exact rules cover it, whole
    tiles assembled from halves cover it too (each half lies in its whole tile); systems
    pairing halves across edges lose unpaired halves at the rim, so the claim is the seed
    shrunk by two tile diameters."""
    s = builtin_systems()[name]
    if depth == 5 and s.scale**2 > 4.9:  # keep the test fast: about s^(2 depth) tiles
        depth = 4
    patch = tiling(name, depth=depth).patch()
    assert len(patch) > 0
    seed_region = shapely.Polygon(Affine.apply(Affine.scaling(s.scale**depth), s.prototiles[s.seed].outline))
    if s.pairing_edge is not None:
        rim = 2 * max(float(np.ptp(t.outline, axis=0).max()) for t in s.tiles)
        seed_region = seed_region.buffer(-rim)
    if seed_region.is_empty:
        assert_valid(patch)
    else:
        assert_valid(patch, seed_region)


@pytest.mark.parametrize("name", SIMILARITY_SYSTEMS)
def test_region_patches_cover_their_region(name: str) -> None:
    t = tiling(name)
    for region in [t.default_region(), (37.5, -12.0, 51.0, -3.0)]:
        patch = t.patch(region)
        assert_valid(patch, region)
        # every tile returned meets the region
        assert len(patch.clip(region)) == len(patch)


def test_ammann_a3_is_figure_6_5() -> None:
    """Figure 6.5: T1 -> {T2, T1}, T2 -> {T1, T3, T1, T1}, T3 -> {T3, T1, T1}; s = phi."""
    s = builtin_systems()["ammann-a3"]
    assert s.scale == pytest.approx(PHI)
    assert s.substitution_matrix().tolist() == [[1, 3, 2], [1, 0, 0], [0, 1, 1]]
    eig, freq = s.perron_frobenius()
    assert eig == pytest.approx(PHI**2)
    # all rule matrices are rotations by multiples of 90 degrees times 1/phi (Figure 6.5)
    for rule in s.rules:
        lin = rule.matrices[:, :2, :2] * PHI
        assert np.allclose(np.round(lin), lin)


def test_ammann_beenker_ratio_tends_to_sqrt2() -> None:
    """Rhombs outnumber squares by sqrt(2) in the limit (Baake & Grimm, Aperiodic Order I,
    §6.1): the half-square matrix [[3, 2], [4, 3]] has eigenvalue (1 + sqrt2)^2 = 3 + 2 sqrt2
    with eigenvector (1, sqrt2) (rhombs, half-squares)."""
    s = builtin_systems()["ammann-beenker"]
    assert s.substitution_matrix().tolist() == [[3, 2], [4, 3]]
    eig, freq = s.perron_frobenius()
    assert eig == pytest.approx(3 + 2 * math.sqrt(2))
    assert freq[1] / freq[0] == pytest.approx(math.sqrt(2))
    proto, tr = generate(s, 6, Affine.scaling(SILVER**6), 0)
    whole, _ = assemble(s, proto, tr)
    rhombs, squares = np.bincount(whole, minlength=2)
    assert rhombs / squares == pytest.approx(math.sqrt(2), rel=2e-2)


@pytest.mark.parametrize("name, k", [("chair", 4), ("sphinx", 4), ("pinwheel", 5)])
def test_rep_tiles(name: str, k: int) -> None:
    """§6.1: the chair and sphinx are 4-rep-tiles; the pinwheel triangle is a 5-rep-tile."""
    s = builtin_systems()[name]
    assert s.rep_tile() == k
    assert s.scale**2 == pytest.approx(k)
    assert tiling(name).properties()["rep_tile"] == k


def test_pinwheel_orientations_keep_multiplying() -> None:
    """Radin (1994): pinwheel tiles occur in infinitely many orientations; each level adds
    rotations by multiples of atan(1/2), an irrational multiple of pi."""
    s = builtin_systems()["pinwheel"]
    seen = []
    for n in (1, 2, 3, 4):
        _, tr = generate(s, n)
        angles = np.round(np.degrees(np.arctan2(tr[:, 1, 0], tr[:, 0, 0])) % 360, 6)
        seen.append(len(np.unique(angles)))
    assert seen == sorted(seen) and seen[-1] > seen[0] * 2


def test_kite_domino_pairs_triangles_into_kites_and_dominoes() -> None:
    """Each kite is a mirror pair and each domino a half-turn pair of pinwheel triangles
    sharing a hypotenuse (exercise 6.10's pairing); both occur."""
    s = builtin_systems()["kite-domino"]
    patch = tiling("kite-domino").patch((-8, -8, 8, 8))
    counts = np.bincount(patch.prototile, minlength=2)
    assert counts.min() > 10
    areas = shapely.area(patch.geometries())
    assert np.allclose(areas, 2.0)  # both are two unit-area triangles
    assert s.tiles[0].name == "kite" and s.tiles[1].name == "domino"


def test_chair_keeps_its_diagonal_symmetry_and_still_places_each_tile_once() -> None:
    s = builtin_systems()["chair"]
    assert len(s.symmetries[0]) == 2
    proto, tr = generate(s, 4, Affine.scaling(16), dedupe=True)
    assert len(proto) == 4**4


def test_catalogue_records_and_family() -> None:
    records = {r.name: r for r in catalogue_records() if r.family == "substitution"}
    for name in SIMILARITY_SYSTEMS:
        props = records[name].properties
        assert props["k_hedral"] >= 1
        assert props["periodic"] is False
        assert props["perron_frobenius_eigenvalue"] == pytest.approx(props["expansion_constant"] ** 2)
        system = builtin_systems()[name]
        if system.output_prototiles is None:  # whole tiles: M^n e_seed
            assert props["tiles_per_generation"][:2] == [1, sum(row[system.seed] for row in props["substitution_matrix"])]
        else:  # assembled from halves: the whole tiles of `render NAME --depth n` (issue 14)
            assert props["tiles_per_generation"] == [
                len(tiling(name, depth=n).patch()) for n in range(len(props["tiles_per_generation"]))
            ]
    assert records["penrose-p3"].properties["k_hedral"] == 2
    assert records["sphinx"].properties["k_hedral"] == 1
    fam = get_family("substitution")
    t = fam.from_spec(records["ammann-a3"].spec)
    assert t.name == "ammann-a3"
    assert fam.from_file is not None
