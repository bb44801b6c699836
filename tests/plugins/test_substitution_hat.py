"""The hat monotile through its metatiles H, T, P, F.

Source: D. Smith, J. S. Myers, C. S. Kaplan, C. Goodman-Strauss, "An aperiodic monotile",
arXiv:2303.10798 (2023): the hat is a polykite (8 kites of the [3.4.6.4] Laves tiling); its
tilings are built from four metatiles H (4 hats, one reflected), T (1), P (2), F (2) and their
supertile substitution H -> 3H+T+3P+3F, T -> H, P -> 2H+P+2F, F -> 2H+P+3F.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from test_substitution import assert_valid

from tilekit.errors import ParameterError, ParseError
from tilekit.geometry import Affine
from tilekit.plugins.substitution import builtin_systems, from_spec, tiling
from tilekit.plugins.substitution.hat import (
    LATTICE,
    hat_system_from_data,
    lattice_points,
    to_lattice,
)

PHI = (1 + math.sqrt(5)) / 2
KITE = math.sqrt(3)  # kite with sides 1, 1, sqrt3, sqrt3 (angles 60, 90, 120, 90)


def hat():
    return builtin_systems()["hat"]


def test_hat_is_a_13_gon_made_of_8_kites() -> None:
    """The hat is the union of 8 kites of the [3.4.6.4] Laves tiling (arXiv:2303.10798 §1):
    its edges have lengths 1, sqrt3 and 2 (two collinear unit edges), its angles are
    multiples of 30 degrees, and exactly 8 kites of the kite tiling (each regular hexagon of
    side 2 cut into 6 kites from its centre to its edge midpoints) lie inside it and fill it."""
    s = hat()
    pts = s.tile.outline
    assert len(pts) == 13
    assert s.tile.area == pytest.approx(8 * KITE)
    edges = np.roll(pts, -1, axis=0) - pts
    lengths = np.linalg.norm(edges, axis=1)
    assert sorted(np.round(lengths**2).astype(int).tolist()) == [1] * 6 + [3] * 6 + [4]
    angles = np.degrees(np.arctan2(edges[:, 1], edges[:, 0]))
    assert np.allclose(angles / 30, np.round(angles / 30))
    # the kite tiling: hexagons of circumradius 2 centred on the lattice spanned by [2, 2], [-2, 4]
    ring = [(2, 0), (1, 1), (0, 2), (-1, 2), (-2, 2), (-2, 1), (-2, 0), (-1, -1), (0, -2), (1, -2), (2, -2), (2, -1)]
    kites = []
    for i in range(-3, 4):
        for j in range(-3, 4):
            c = i * np.array([2, 2]) + j * np.array([-2, 4])
            for k in range(0, 12, 2):
                kites.append(shapely.Polygon(lattice_points([c, c + ring[k - 1], c + ring[k], c + ring[k + 1]])))
    kites = np.array(kites)
    assert np.allclose(shapely.area(kites), KITE)
    body = shapely.Polygon(pts)
    meet = shapely.area(shapely.intersection(kites, body))
    inside = kites[meet > 1e-9]
    assert len(inside) == 8
    assert np.allclose(meet[meet > 1e-9], KITE)  # no kite is cut by the outline
    assert shapely.union_all(inside).symmetric_difference(body).area < 1e-9


def test_substitution_matrix_and_perron_frobenius_eigenvalue_phi4() -> None:
    """Children H -> 3H+T+3P+3F, T -> H, P -> 2H+P+2F, F -> 2H+P+3F (arXiv:2303.10798, the
    metatile substitution); its Perron-Frobenius eigenvalue is phi^4 = (7 + 3 sqrt5)/2, the
    area growth per level, so the linear expansion is phi^2."""
    s = hat()
    m = s.substitution_matrix()  # column j = children of label j (labels H, T, P, F)
    assert m.tolist() == [[3, 1, 2, 2], [1, 0, 0, 0], [3, 0, 1, 1], [3, 0, 2, 3]]
    eig, freq = s.perron_frobenius()
    assert eig == pytest.approx(PHI**4, rel=1e-12)
    assert eig == pytest.approx((7 + 3 * math.sqrt(5)) / 2, rel=1e-12)
    assert s.scale == pytest.approx(PHI**2, rel=1e-12)
    assert np.allclose(m @ freq, eig * freq)
    props = tiling("hat").properties()
    assert props["perron_frobenius_eigenvalue"] == pytest.approx(PHI**4)
    assert props["aperiodic"] is True and props["periodic"] is False
    assert "2303.10798" in props["aperiodic_source"]
    assert props["k_hedral"] == 1
    assert props["hats_per_metatile"] == [4, 1, 2, 2]
    assert props["reflected_hats_per_metatile"] == [1, 0, 0, 0]


@pytest.mark.parametrize("label", [0, 1, 2, 3])
def test_metatile_counts_are_matrix_powers(label: int) -> None:
    """The level-0 metatiles of a level-n supertile of label j are M^n e_j, and its hats
    (4, 1, 2, 2 per H, T, P, F) number (4, 1, 2, 2) . M^n e_j; the reflected hats are exactly
    one per H metatile."""
    s = hat()
    m = s.substitution_matrix()
    e = np.zeros(4, dtype=np.int64)
    e[label] = 1
    for n in range(5):
        labels, _ = s.supertiles(n, seed_label=label)
        want = np.linalg.matrix_power(m, n) @ e
        assert np.bincount(labels, minlength=4).tolist() == want.tolist()
        _, tr, colour = s.generate(n, seed_label=label)
        assert len(tr) == int(np.array([4, 1, 2, 2]) @ want)
        reflected = np.linalg.det(tr[:, :2, :2]) < 0
        assert int(reflected.sum()) == int(want[0])
        assert np.array_equal(colour == 1, reflected)
    assert s.tile_counts(4) == [4, 25, 169, 1156, 7921]


@pytest.mark.parametrize("seed", ["H", "T", "P", "F"])
def test_depth_3_supertiles_are_valid_hole_free_and_all_hats(seed: str) -> None:
    """Every tile is a rigid image of the hat (13 vertices, area of 8 kites), the tiles do not
    overlap, and a level-3 supertile is one polygon without holes."""
    patch = tiling("hat", depth=3, seed=seed).patch()
    assert_valid(patch)
    lin = patch.transform[:, :2, :2]
    assert np.allclose(np.einsum("nji,njk->nik", lin, lin), np.eye(2), atol=1e-9)  # isometries
    polys = patch.polygons()
    assert all(len(p) == 13 for p in polys)
    areas = shapely.area(patch.geometries())
    assert np.allclose(areas, 8 * KITE)
    union = shapely.union_all(patch.geometries(), grid_size=1e-9)
    assert union.geom_type == "Polygon" and len(union.interiors) == 0
    assert union.area == pytest.approx(len(patch) * 8 * KITE)


def test_disc_inside_depth_4_supertile_is_covered() -> None:
    """validate(region) on a disc well inside a level-4 supertile: no gaps, no overlaps."""
    patch = tiling("hat", depth=4).patch()
    union = shapely.union_all(patch.geometries(), grid_size=1e-9)
    centre = union.representative_point()
    far = shapely.Point(centre)
    # the largest disc about an interior point, shrunk: well inside the patch
    radius = 0.8 * union.exterior.distance(far)
    assert radius > 20
    disc = far.buffer(radius, 64)
    assert_valid(patch.clip(disc), disc)


def test_region_patches_cover_regions() -> None:
    t = tiling("hat")
    for region in [(-12, -12, 12, 12), (300, 40, 340, 60)]:
        patch = t.patch(region)
        assert len(patch) > 10
        assert_valid(patch, region)
        assert np.allclose(shapely.area(patch.geometries()), 8 * KITE)


def test_reflected_share_tends_to_one_in_phi4_plus_one() -> None:
    """Unreflected : reflected hats tends to phi^4 : 1 (arXiv:2303.10798: in the metatile
    tilings the reflected hats are the one special hat of each H, and the frequencies of the
    metatiles are the Perron-Frobenius eigenvector). Measured on generated patches: the
    ratio's error shrinks with depth, to below 3e-4 at depth 5."""
    s = hat()
    errors = []
    for depth in (2, 3, 5):
        _, tr, _ = s.generate(depth)
        reflected = int((np.linalg.det(tr[:, :2, :2]) < 0).sum())
        errors.append(abs((len(tr) - reflected) / reflected - PHI**4))
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 3e-4
    frac = s.reflected_fraction_limit()
    assert (1 - frac) / frac == pytest.approx(PHI**4, rel=1e-12)


def test_spec_round_trip_options_and_errors() -> None:
    t = tiling("hat").configure(depth=2, seed="P")
    back = from_spec(t.spec())
    assert back.spec() == {"system": "hat", "depth": 2, "seed": "P"}
    assert len(back.patch()) == hat().tile_counts(2, start=2)[-1] == 96
    with pytest.raises(ParameterError, match="not a supertile label"):
        t.configure(seed="Q")
    with pytest.raises(ParameterError, match="does not take option"):
        t.configure(colour="red")
    # 4 * (growth ~6.85)^9 hats: refused with the count, not attempted
    with pytest.raises(ParameterError, match="hat depth 9 would make 119814916 hats"):
        tiling("hat", depth=9).patch()


def test_loader_rejects_bad_data() -> None:
    data = dict(hat().data)
    cluster = dict(data["cluster"])
    attach = list(cluster["attach"])
    attach[3] = [2, 0, "Q", 2]
    with pytest.raises(ParseError, match=r"bad\.toml: \[cluster\] attach entry #3"):
        hat_system_from_data({**data, "cluster": {**cluster, "attach": attach}}, "bad.toml")
    attach[3] = [2, 1, "P", 2]  # glues edges of different lengths
    with pytest.raises(ParseError, match=r"bad\.toml: cluster entry \[2, 1, 'P', 2\]: segments of lengths"):
        hat_system_from_data({**data, "cluster": {**cluster, "attach": attach}}, "bad.toml")
    metas = {k: dict(v) for k, v in data["metatiles"].items()}
    metas["P"]["hats"] = [{"rotate": 0, "translate": [2, 2]}, {"rotate": 0, "translate": [2, 2]}]
    with pytest.raises(ParseError, match="overlapping hats"):
        hat_system_from_data({**data, "metatiles": metas}, "bad.toml")


def test_cli_renders_hat(tmp_path) -> None:
    from tilekit.cli import cli

    out = tmp_path / "hat.svg"
    db = f"sqlite:///{tmp_path / 'cat.sqlite'}"  # not the user's catalogue (another version may own it)
    result = CliRunner().invoke(cli, ["--catalogue", db, "render", "hat", "--depth", "2", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "(169 tiles)" in result.output
    assert out.read_text().count("<path") >= 1


def test_seed_transform_moves_the_supertile() -> None:
    s = hat()
    _, a, _ = s.generate(2)
    _, b, _ = s.generate(2, Affine.translation(5, 7))
    assert np.allclose(b[:, :2, 2] - a[:, :2, 2], [5, 7])


def test_hats_lie_exactly_on_the_kite_lattice() -> None:
    """Every hat of a hat tiling is a union of kites of one [3.4.6.4] Laves tiling
    (arXiv:2303.10798 §1), so its placement is a symmetry of the triangular lattice: the
    engine composes placements as integer matrices in lattice coordinates. At depth 4 the
    hats' linear parts are the 12 point symmetries of the lattice (6 rotations, 6
    reflections) and their vertices are lattice points up to one float conversion."""
    s = hat()
    _, exact = s.lattice_supertiles(4)
    assert exact.dtype == np.int64
    _, tr, _ = s.generate(4)
    lat = np.linalg.solve(LATTICE, Affine.apply(tr, s.tile.outline).reshape(-1, 2).T)
    assert np.abs(lat - np.round(lat)).max() < 1e-12
    linear = {tuple(m[:2, :2].ravel()) for m in to_lattice(tr)}
    assert len(linear) == 12
    assert all(abs(round(np.linalg.det(np.reshape(m, (2, 2))))) == 1 for m in linear)
