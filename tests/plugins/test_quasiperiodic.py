"""The quasiperiodic family (issue 32): de Bruijn's multigrid checked against geometry
(Patch.validate), against cut-and-project (an independent construction in the internal
space), against the substitution family's Penrose P3 and Ammann-Beenker patches, and on
the facts of the n-fold star.

References: N. G. de Bruijn, "Algebraic theory of Penrose's non-periodic tilings of the
plane", Indag. Math. 43 (1981) 39-66 (pentagrids, Sum gamma = 0 gives Penrose's rhombs);
Gähler and Rhyner, "Equivalence of the generalised grid and projection methods for the
construction of quasiperiodic tilings", J. Phys. A 19 (1986) 267 (the canonical projection
is the multigrid's dual); Grünbaum and Shephard, Tilings and Patterns, §10.3-10.4 (thick :
thin = phi in P3; rhombs : squares = sqrt 2 in Ammann-Beenker).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from cliutil import assert_one_line_error
from family_cli import family_cli
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tilekit.errors import ParameterError, ParseError, TilekitError
from tilekit.limits import LimitError
from tilekit.plugins import quasiperiodic as plugin
from tilekit.plugins.quasiperiodic import project
from tilekit.plugins.quasiperiodic.multigrid import SingularGrid, rhombs
from tilekit.plugins.quasiperiodic.star import MAX_N, star
from tilekit.plugins.quasiperiodic.tiling import (
    FAMILY,
    QuasiperiodicTiling,
    SingularWarning,
    default_gamma,
)
from tilekit.plugins.substitution import tiling as substitution
from tilekit.polygon import area, vertex_stars

PHI = (1 + math.sqrt(5)) / 2
ORDERS = range(4, 13)
#: Region centres: the origin, far away (the issue's (10^6, 10^6)) and somewhere generic.
CENTRES = [(0.0, 0.0), (1e6, 1e6), (-734_512.25, 291_003.5)]


def box(centre, half):
    x, y = centre
    return (x - half, y - half, x + half, y + half)


def random_gamma(n, seed):
    return np.random.default_rng(seed).random(star(n).grids)


def tile_keys(patch, decimals=6):
    """Each tile as (prototile, map's rotation and translation rounded): a set that two
    computations of the same tiles agree on."""
    t = np.round(patch.transform[:, :2, :].reshape(len(patch), 6), decimals) + 0.0
    return {(int(p), *row) for p, row in zip(patch.prototile.tolist(), t.tolist())}


# ------------------------------------------------------------------ the n-fold star


@pytest.mark.parametrize("n", ORDERS)
def test_star_grids_and_rhomb_kinds(n):
    st = star(n)
    grids = n if n % 2 else n // 2
    assert st.grids == grids and st.kinds == grids // 2
    # the pairs' rhombs have exactly the acute angles k pi / N, k = 1 .. N // 2
    e = st.directions
    r, s = st.pairs.T
    angle = np.arccos(np.clip(np.abs((e[r] * e[s]).sum(1)), 0, 1))
    assert sorted({round(math.degrees(a), 9) for a in angle}) == [round(180 * k / grids, 9) for k in range(1, grids // 2 + 1)]
    assert [p.edges for p in st.prototiles] == [4] * st.kinds
    assert np.allclose([area(p.outline) for p in st.prototiles], np.sin(st.kind_angles))


def test_penrose_and_ammann_beenker_shapes():
    assert [round(math.degrees(a), 9) for a in star(5).kind_angles] == [36, 72]  # thin, thick
    assert [round(math.degrees(a), 9) for a in star(8).kind_angles] == [45, 90]  # rhomb, square
    assert [p.name for p in star(8).prototiles] == ["rhomb-45", "square"]


@pytest.mark.parametrize("n", ORDERS)
def test_density_times_areas_covers_the_plane(n):
    # sum over pairs of (intersections per unit area) x (rhomb area) = 1: for N unit vectors
    # of a tight frame, sum_{r<s} sin^2(theta_r - theta_s) = N^2 / 4 = scale^2
    st = star(n)
    assert (st.pair_sines**2).sum() / st.scale**2 == pytest.approx(1.0, abs=1e-12)


# ------------------------------------------------------------------ geometry


@pytest.mark.parametrize("n", ORDERS)
@pytest.mark.parametrize("centre", CENTRES)
def test_patches_have_no_gap_and_no_overlap(n, centre):
    t = QuasiperiodicTiling(n, random_gamma(n, n))
    region = box(centre, 12)
    patch = t.patch(region)
    report = patch.validate(region)
    assert report.ok, report.summary()
    assert len(patch) <= t.estimate_tiles(region) <= 1.8 * len(patch)


@pytest.mark.parametrize("centre", CENTRES)
def test_the_default_offsets_are_regular_for_every_order(centre):
    for n in range(4, MAX_N + 1):
        g = default_gamma(n)
        assert abs(math.remainder(math.fsum(g), 1)) < 1e-12
        rhombs(star(n), g, box(centre, 25))  # raises SingularGrid if three lines met


@pytest.mark.parametrize("n", [5, 8, 12])
@pytest.mark.parametrize("centre", CENTRES)
def test_random_access_gives_the_same_tiles_in_any_window(n, centre):
    t = QuasiperiodicTiling(n)
    small = box((centre[0] + 3.3, centre[1] - 1.7), 6)
    big = t.patch(box(centre, 20))
    b = big.tile_bounds()
    x0, y0, x1, y1 = small
    inside = big.subset((b[:, 2] > x0 + 1e-9) & (b[:, 0] < x1 - 1e-9) & (b[:, 3] > y0 + 1e-9) & (b[:, 1] < y1 - 1e-9))
    assert tile_keys(t.patch(small)) == tile_keys(inside)


@pytest.mark.parametrize("n", [5, 11])
def test_work_is_the_region_s_not_its_distance(n):
    st, g = star(n), default_gamma(n)
    near = rhombs(st, g, box((0, 0), 60))
    far = rhombs(st, g, box((1e6, 1e6), 60))
    # the intersections computed are those of the region's window, wherever it is
    assert abs(far.candidates - near.candidates) <= 0.02 * near.candidates
    assert near.candidates <= 1.15 * len(near) and far.candidates <= 1.15 * len(far)


def test_n4_is_the_square_grid():
    # two grids at right angles: the vertices K_0 e_0 + K_1 e_1 are the integer points
    patch = QuasiperiodicTiling(4, [0.3, 0.6]).patch((-5, -5, 5, 5))
    assert [p.name for p in patch.prototiles] == ["square"] and len(patch) == 100
    assert np.allclose(patch.transform[:, :2, :2], np.eye(2))
    corners = patch.transform[:, :2, 2]
    assert np.array_equal(corners, np.round(corners))
    assert {tuple(c) for c in corners.tolist()} == {(a, b) for a in range(-5, 5) for b in range(-5, 5)}


# ------------------------------------------------------------------ cut-and-project


def multigrid_vertices(st, rh):
    """The four corners' index vectors of every rhomb (rows of K)."""
    k = rh.k
    r, s = st.pairs[rh.pair].T
    rows = np.arange(len(k))
    corners = [k.copy() for _ in range(4)]
    corners[1][rows, r] += 1
    corners[2][rows, r] += 1
    corners[2][rows, s] += 1
    corners[3][rows, s] += 1
    return np.unique(np.concatenate(corners), axis=0)


@pytest.mark.parametrize("n", ORDERS)
@pytest.mark.parametrize("centre", CENTRES[:2])
def test_multigrid_equals_the_canonical_projection(n, centre):
    st, g = star(n), random_gamma(n, 100 + n)
    region = box(centre, 10)
    rh = rhombs(st, g, region, with_k=True)
    # the index vectors draw the tiles the multigrid placed
    assert np.allclose(rh.k @ st.directions, rh.lower, atol=1e-6)
    # every vertex passes the window test, every tile its dual parallelotope's
    verts = multigrid_vertices(st, rh)
    assert project.accepts(st, verts, g).all()
    assert (project.tile_accepts(st, rh.k, rh.pair, g) > 0).all()
    # and the window's lattice points, walked from one of them, are exactly the vertices
    inner = box(centre, 6)
    pos = verts @ st.directions
    x0, y0, x1, y1 = inner
    mine = verts[(pos[:, 0] >= x0) & (pos[:, 0] <= x1) & (pos[:, 1] >= y0) & (pos[:, 1] <= y1)]
    walked = project.vertices(st, g, inner, mine[0])
    assert {v.tobytes() for v in walked} == {v.tobytes() for v in mine}
    assert len(mine) > 50


def test_the_window_rejects_lattice_points_next_to_it():
    # each accepted vertex has neighbours K +- unit vector that the window refuses (the
    # test is not vacuous): those are not vertices of the multigrid either
    st, g = star(5), default_gamma(5)
    rh = rhombs(st, g, box((0, 0), 5), with_k=True)
    verts = multigrid_vertices(st, rh)
    steps = np.concatenate([np.eye(5, dtype=np.int64), -np.eye(5, dtype=np.int64)])
    around = np.unique((verts[:, None, :] + steps[None]).reshape(-1, 5), axis=0)
    known = {v.tobytes() for v in verts}
    fresh = np.array([a for a in around if a.tobytes() not in known])
    pos = fresh @ st.directions
    inner = np.abs(pos).max(axis=1) < 3
    assert inner.sum() > 20 and not project.accepts(st, fresh[inner], g).any()


@pytest.mark.parametrize("n", ORDERS)
def test_window_frequencies_are_the_sines(n):
    st = star(n)
    win = project.window(st)
    vols = np.array([abs(np.linalg.det(win.generators[[j for j in range(st.grids) if j not in (r, s)]]))
                     if st.grids > 2 else 1.0 for r, s in st.pairs.tolist()])
    # complementary minors of an orthogonal matrix: the dual parallelotope of the (r, s)
    # rhombs has volume (2 / N) |sin(theta_r - theta_s)|, and together they tile the window
    if st.grids > 2:
        assert np.allclose(vols, 2 / st.grids * st.pair_sines, atol=1e-12)
        assert win.volume() == pytest.approx(vols.sum(), rel=1e-12)
    expected = np.bincount(st.pair_kind, weights=st.pair_sines, minlength=st.kinds)
    assert np.allclose(project.frequencies(st), expected / expected.sum(), atol=1e-12)


def test_exact_frequencies_penrose_and_ammann_beenker():
    thin, thick = project.frequencies(star(5))
    assert thick / thin == pytest.approx(PHI, abs=1e-12)  # Grünbaum-Shephard 10.3
    rhomb, square = project.frequencies(star(8))
    assert rhomb / square == pytest.approx(math.sqrt(2), abs=1e-12)  # Grünbaum-Shephard 10.4


@pytest.mark.parametrize("n", [5, 7, 8, 12])
def test_counted_frequencies_tend_to_the_window_s(n):
    t = QuasiperiodicTiling(n)
    want = project.frequencies(t.star)
    errors = []
    for half in (15, 150):
        patch = t.patch(box((0.5e6, -0.25e6), half))
        got = np.bincount(patch.prototile, minlength=t.star.kinds) / len(patch)
        errors.append(np.abs(got - want).max())
    assert errors[1] < 0.004 and errors[1] < errors[0]


def test_thick_to_thin_tends_to_phi():
    t = QuasiperiodicTiling(5)
    patch = t.patch(box((0, 0), 250))  # about 3 x 10^5 rhombs
    thin, thick = np.bincount(patch.prototile, minlength=2)
    assert abs(thick / thin - PHI) < 0.002


# ------------------------------------------------------------------ against the substitution family


def shape_labels(patch):
    """A tile's label: its prototile's area to 1e-3 (tells the rhomb kinds apart, in either
    family's prototile order)."""
    by_prototile = [round(float(area(p.outline)), 3) for p in patch.prototiles]
    return [by_prototile[p] for p in patch.prototile.tolist()]


def local_codes(patch, inner, radius):
    """(vertex stars, neighbourhoods of ``radius``) up to congruence, at the vertices inside
    the box ``inner`` (far enough from the patch's edge that nothing is cut off)."""
    polys = patch.polygons()
    labels = shape_labels(patch)
    stars = vertex_stars(polys)
    centres = np.array([p.mean(axis=0) for p in polys])
    x0, y0, x1, y1 = inner
    pts = stars.points
    at = np.flatnonzero((pts[:, 0] >= x0) & (pts[:, 0] <= x1) & (pts[:, 1] >= y0) & (pts[:, 1] <= y1))
    tree = shapely.STRtree(shapely.points(centres))
    where, tiles = tree.query(shapely.points(pts[at]), predicate="dwithin", distance=radius)
    near: dict[int, list[int]] = {}
    for v, t in zip(at[where].tolist(), tiles.tolist()):
        near.setdefault(v, []).append(t)
    # a centre at the radius within float noise would make the codes depend on rounding
    d = np.hypot(*(centres[tiles] - pts[at[where]]).T)
    assert np.all(np.abs(d - radius) > 1e-6)
    ring = np.hypot(*(centres[:, None, :] - pts[None, at[:50], :]).transpose(2, 0, 1))
    assert np.all(np.abs(ring - radius) > 1e-6)
    star_set = {stars.star_code(v, polys, labels) for v in at.tolist()}
    hood_set = {stars.neighbourhood_code(v, polys, labels, centres, np.array(near.get(v, []), dtype=np.int64))
                for v in at.tolist()}
    assert None not in star_set
    return star_set, hood_set


#: Radii of the compared neighbourhoods (edge lengths; chosen away from centre distances).
RADIUS = 2.1


def test_pentagrid_with_zero_sum_is_penrose_p3():
    half = 22
    region = box((0, 0), half)
    inner = box((0, 0), half - RADIUS - 3)
    mine = QuasiperiodicTiling(5).patch(region)
    assert abs(math.remainder(math.fsum(default_gamma(5)), 1)) < 1e-12
    theirs = substitution("penrose-p3").patch(region)
    stars_a, hoods_a = local_codes(mine, inner, RADIUS)
    stars_b, hoods_b = local_codes(theirs, inner, RADIUS)
    assert stars_a == stars_b  # every vertex star of each is one of the other's
    assert hoods_a == hoods_b and len(hoods_a) > 15  # both directions, up to congruence
    # far away and with other zero-sum offsets it is the same tiling up to local isomorphism
    far = QuasiperiodicTiling(5, [0.31, 0.77, 0.05, 0.48, 0.39]).patch(box((1e6, 1e6), half))
    stars_c, hoods_c = local_codes(far, box((1e6, 1e6), half - RADIUS - 3), RADIUS)
    assert stars_c == stars_b and hoods_c == hoods_b


def test_a_pentagrid_with_sum_one_half_is_not_penrose():
    # the test above can fail: sum gamma = 1/2 gives another tiling by the same rhombs
    half = 22
    region = box((0, 0), half)
    inner = box((0, 0), half - 4)
    g = default_gamma(5)
    g[-1] += 0.5
    other, _ = local_codes(QuasiperiodicTiling(5, g).patch(region), inner, 1.3)
    p3, _ = local_codes(substitution("penrose-p3").patch(region), inner, 1.3)
    assert other - p3


def test_octagonal_multigrid_is_ammann_beenker():
    half = 22
    region = box((0, 0), half)
    inner = box((0, 0), half - RADIUS - 3)
    mine = QuasiperiodicTiling(8).patch(region)
    assert {p.name for p in mine.prototiles} == {"rhomb-45", "square"}
    theirs = substitution("ammann-beenker").patch(region)
    stars_a, hoods_a = local_codes(mine, inner, RADIUS)
    stars_b, hoods_b = local_codes(theirs, inner, RADIUS)
    assert stars_a == stars_b
    assert hoods_a == hoods_b and len(hoods_a) > 15


def corner_sets(patch):
    """Each tile as the set of its corners (rounded): placement conventions aside."""
    return {tuple(sorted(map(tuple, np.round(p, 6).tolist()))) for p in patch.polygons()}


def test_ten_fold_is_the_pentagrid_with_two_grids_reversed():
    # the 36- and 108-degree grids of n = 10 are the pentagrid's grids 3 and 4 turned round:
    # lines z . (-e_3) = k + g are z . e_3 = -k - g, so K'_1 = 1 - K_3 (and K'_3 = 1 - K_4),
    # and the tiling is the pentagrid's with offsets (g0, g2, g4, -g1, -g3), moved by -(e_3 + e_4)
    g = np.array([0.13, 0.71, 0.29, 0.57, 0.83])
    ten = QuasiperiodicTiling(10, g)
    five = QuasiperiodicTiling(5, [g[0], g[2], g[4], -g[1], -g[3]])
    shift = star(5).directions[3] + star(5).directions[4]
    region = (-9.37, -8.11, 10.29, 9.53)
    moved = ten.patch(region).transformed(np.array([[1.0, 0, shift[0]], [0, 1, shift[1]], [0, 0, 1]]))
    there = (region[0] + shift[0], region[1] + shift[1], region[2] + shift[0], region[3] + shift[1])
    assert corner_sets(moved) == corner_sets(five.patch(there))


# ------------------------------------------------------------------ singular offsets


def test_singular_offsets_are_refused_in_one_line():
    with pytest.raises(SingularGrid) as err:
        QuasiperiodicTiling(5, 0.0)  # a line of each of the five grids through the origin
    assert isinstance(err.value, ParameterError)
    assert "singular" in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("gamma, singular", [((0.1, 0.2, 0.1), True), ((0.5, 0.25, 0.75), True),
                                             ((0.1, 0.2, 0.3), False), ((0.3, 0.3, 0.3), False)])
def test_three_grids_are_singular_exactly_when_g0_minus_g1_plus_g2_is_whole(gamma, singular):
    # n = 6: e_1 = e_0 + e_2, so lines of the three grids meet iff (k0 + g0) + (k2 + g2) = k1 + g1
    whole = abs(math.remainder(gamma[0] - gamma[1] + gamma[2], 1)) < 1e-12
    assert whole == singular
    if singular:
        with pytest.raises(SingularGrid):
            QuasiperiodicTiling(6, gamma)
    else:
        assert QuasiperiodicTiling(6, gamma).patch(box((0, 0), 8)).validate(box((0, 0), 8))


def test_perturb_warns_and_keeps_the_sum():
    with pytest.warns(SingularWarning, match="perturbed"):
        t = QuasiperiodicTiling(5, 0.0, "perturb")
    assert math.fsum(t.offsets) == pytest.approx(0.0, abs=1e-15)
    assert 0 < np.abs(t.offsets).max() <= 1e-6
    region = box((0, 0), 10)
    assert t.patch(region).validate(region)
    assert t.properties()["penrose"] is True


def test_singular_far_away_is_found_where_it_is():
    # n = 6 with a whole g0 - g1 + g2 is singular everywhere, so also at (10^6, 10^6)
    st = star(6)
    with pytest.raises(SingularGrid):
        rhombs(st, np.array([0.1, 0.2, 0.1]), box((1e6, 1e6), 3))


# ------------------------------------------------------------------ options, sizes, streams


@pytest.mark.parametrize("options, needle", [
    ({"n": 3}, "n=3 is outside 4..50"),
    ({"n": 51}, "n=51 is outside"),
    ({"n": "seven"}, "not a whole number"),
    ({"n": True}, "not a whole number"),
    ({"n": 4.5}, "not a whole number"),
    ({"gamma": "0.1,0.2"}, "5 grids"),
    ({"gamma": "nan"}, "not a finite number"),
    ({"gamma": [0, 0, 0, 0, float("inf")]}, "not a finite number"),
    ({"gamma": "1e7"}, "within"),
    ({"gamma": "a,b,c,d,e"}, "not a number"),
    ({"gamma": "0.1,,0.3"}, "comma-separated"),
    ({"singular": "ignore"}, "refuse, perturb"),
    ({"depth": 3}, "does not take option(s) depth"),
])
def test_bad_options_are_one_line_errors(options, needle):
    with pytest.raises(ParameterError) as err:
        QuasiperiodicTiling(5).configure(**options)
    assert needle in str(err.value) and "\n" not in str(err.value)


@pytest.mark.parametrize("spec", [{"n": 5, "depth": 2}, [5]])
def test_bad_specs_are_refused(spec):
    with pytest.raises(ParseError):
        QuasiperiodicTiling.from_spec(spec)


def test_an_oversize_region_is_refused_before_anything_is_made():
    t = QuasiperiodicTiling(7)
    region = box((0, 0), 5e5)  # about 1.2 x 10^12 rhombs
    assert t.estimate_tiles(region) > 1e12
    with pytest.raises(LimitError, match="memory"):
        t.patch(region)


@pytest.mark.parametrize("centre", CENTRES[:2])
@pytest.mark.parametrize("n", [5, 12])
def test_streamed_bands_are_the_patch(n, centre):
    t = QuasiperiodicTiling(n)
    region = (centre[0] - 30, centre[1] - 12, centre[0] + 30, centre[1] + 12)  # cut across x
    whole = t.patch(region)
    chunks = list(t.iter_patches(region, chunk_tiles=400))
    assert len(chunks) > 5 and max(len(c) for c in chunks) < 2 * 400
    assert sum(len(c) for c in chunks) == len(whole)
    joined = set().union(*(tile_keys(c) for c in chunks))
    assert joined == tile_keys(whole)


def test_a_polygon_region_is_clipped_and_streams_alike():
    t = QuasiperiodicTiling(7)
    region = shapely.Point(1e6, 2e5).buffer(15)
    whole = t.patch(region)
    assert whole.validate(region)
    chunks = list(t.iter_patches(region, chunk_tiles=200))
    assert set().union(*(tile_keys(c) for c in chunks)) == tile_keys(whole)


def test_spec_round_trip_and_configure():
    t = QuasiperiodicTiling(7, [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.2], name="mine", title="Mine")
    again = QuasiperiodicTiling.from_spec(t.spec())
    assert again.spec() == t.spec() and tile_keys(again.patch()) == tile_keys(t.patch())
    assert t.configure(singular="refuse").name == "mine"
    nine = t.configure(n=9)
    assert nine.n == 9 and np.array_equal(nine.gamma, default_gamma(9)) and nine.name == "multigrid-9"
    assert t.configure(gamma="0.3").gamma.tolist() == [0.3] * 7


def test_records_and_family_name():
    assert plugin.FAMILY == FAMILY
    records = {r.name: r for r in plugin.multigrid_records()}
    assert sorted(r.properties["n"] for r in records.values()) == [5, 7, 8, 9, 10, 11, 12]
    p3 = records["multigrid-5"].properties
    assert p3["penrose"] is True and p3["rhomb_kinds"] == 2 and p3["symmetry_order"] == 10
    assert p3["tile_frequencies"][1] / p3["tile_frequencies"][0] == pytest.approx(PHI, abs=1e-9)
    assert records["multigrid-8"].properties["rhomb_angles"] == [45.0, 90.0]
    assert records["multigrid-12"].properties["rhomb_kinds"] == 3
    assert all(r.properties["periodic"] is False for r in records.values())


# ------------------------------------------------------------------ the command line


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "quasiperiodic")


def test_cli_list_show_render(cli, tmp_path):
    r = cli("list", "--family", "quasiperiodic", "--count")
    assert r.exit_code == 0 and r.output.split()[-1] == "7"
    r = cli("show", "pentagrid")
    assert r.exit_code == 0 and "penrose" in r.output and "0.381966, 0.618034" in r.output
    r = cli("render", "multigrid-5", "--set", "gamma=0.31,0.77,0.05,0.48,0.39", "--region", "999990,999990,1000010,1000010",
            "-o", "p3.svg")
    assert r.exit_code == 0, r.output
    r = cli("render", "multigrid-7", "--set", "n=9", "-o", "n9.geojson")
    assert r.exit_code == 0, r.output
    assert '"name": "rhomb-80"' in (tmp_path / "n9.geojson").read_text()


@pytest.mark.parametrize("args, needle", [
    (["--set", "n=3"], "n=3 is outside 4..50"),
    (["--set", "n=1000000000000"], "not a whole number"),
    (["--set", "gamma=0"], "singular"),
    (["--set", "gamma=inf"], "not a finite number"),
    (["--set", "gamma=1,2,3"], "5 grids"),
    (["--set", "singular=yes"], "refuse, perturb"),
    (["--region", "0,0,1e6,1e6"], "over the limit"),
    (["--depth", "3"], "does not take option(s) depth"),
])
def test_cli_bad_input_is_one_line_exit_2(cli, args, needle):
    r = cli("render", "multigrid-5", *args, "-o", "x.svg")
    assert_one_line_error(r, needle)


def test_errors_are_tilekit_errors():
    for bad in (lambda: star(2), lambda: QuasiperiodicTiling(5, "x")):
        with pytest.raises(TilekitError):
            bad()


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(["n", "gamma", "singular", "depth"]),
       st.one_of(st.text(alphabet="0123456789.-+e, naif_", max_size=24), st.integers(-10**20, 10**20),
                 st.floats(allow_nan=True, allow_infinity=True),
                 st.lists(st.one_of(st.floats(), st.text(max_size=5)), max_size=14)))
def test_any_option_value_makes_a_tiling_or_a_tilekit_error(key, value):
    # --set KEY=VALUE reaches configure() as text (the Python API may pass anything): either a
    # tiling whose patch is valid, or a TilekitError, never another exception
    try:
        t = QuasiperiodicTiling(5).configure(**{key: value})
    except TilekitError as exc:
        assert "\n" not in str(exc)
        return
    assert t.patch((-4, -4, 4, 4)).validate((-4, -4, 4, 4))


def test_cli_streams_a_region_over_the_memory_estimate(cli, tmp_path, monkeypatch):
    # render writes a patch that would not fit in memory band by band (Tiling.iter_patches)
    import json

    from tilekit import limits

    monkeypatch.setattr(limits, "available_memory", lambda: 2e5)  # 3,147 tiles need 630 kB
    r = cli("render", "multigrid-7", "--region", "0,0,60,40", "-o", "big.geojson")
    assert r.exit_code == 0 and "streamed in chunks" in r.output, r.output
    features = json.loads((tmp_path / "big.geojson").read_text())["features"]
    monkeypatch.undo()
    want = QuasiperiodicTiling(7).patch((0, 0, 60, 40))
    assert len(features) == len(want)
