"""The curved plugin (issue 35): regular tilings {p, q} of the sphere and the hyperbolic plane.

Facts checked: the published layer sequences (OEIS A001354 for {7,3}, A054888 {5,4},
A054889 {5,5}, A054890 {7,6}), the Platonic solids' face, edge and vertex counts, the
layer counts and tile positions of the PyPI package hypertiling (an independent generator),
q tiles and an angle sum of 2π at every full vertex, no overlap by separating axes in the
Klein model (written here, not the core's validate) and by the core's validate on exact
triangles, the Gauss–Bonnet areas, and the one-line errors.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import shapely
from cliutil import assert_one_line_error
from family_cli import family_cli

from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.plugins import curved as plugin
from tilekit.plugins.curved import layers, model
from tilekit.plugins.curved.patch import ModelPatch, vertex_angle_sums
from tilekit.plugins.curved.render import arc_commands
from tilekit.plugins.curved.tiling import MAX_RADIUS, RegularTiling

# OEIS, layer counts from the central tile (offset 0): "layer counting sequence for hyperbolic
# tessellation by ... under successive side-reflections" (P. Dominici), and A001354, the
# coordination sequence of {3,7}, whose vertices are the tiles of its dual {7,3}.
OEIS = {
    (7, 3): ("A001354", [1, 7, 21, 56, 147, 385, 1008, 2639, 6909, 18088]),
    (5, 4): ("A054888", [1, 5, 15, 40, 105, 275, 720, 1885, 4935, 12920]),
    (5, 5): ("A054889", [1, 5, 20, 70, 245, 860, 3015, 10570, 37060]),
    (7, 6): ("A054890", [1, 7, 42, 245, 1428, 8323, 48510]),
}

#: The Platonic solids (faces, edges, vertices): V - E + F = 2 and pF = 2E = qV.
PLATONIC = {(3, 3): (4, 6, 4), (3, 4): (8, 12, 6), (4, 3): (6, 12, 8), (3, 5): (20, 30, 12), (5, 3): (12, 30, 20)}

HYPERBOLIC_PQ = [(7, 3), (3, 7), (5, 4), (4, 5), (8, 3), (6, 4), (4, 6), (5, 5), (3, 9), (9, 3), (12, 3), (3, 12),
                 (4, 20), (7, 7)]


# ------------------------------------------------------------------ counts


@pytest.mark.parametrize("pq", sorted(OEIS))
def test_layer_counts_are_the_published_sequences(pq):
    _, seq = OEIS[pq]
    depth = len(seq) - 1
    assert layers.layer_counts(*pq, depth) == seq
    assert [len(t) for t in layers.hyperbolic_layers(*pq, depth)] == seq


@pytest.mark.parametrize("pq", HYPERBOLIC_PQ)
def test_compiled_and_numpy_automata_agree(pq):
    depth = 7 if min(pq) > 3 or max(pq) < 9 else 6
    assert [len(t) for t in layers.hyperbolic_layers(*pq, depth)] == layers.layer_counts(*pq, depth)


@pytest.mark.parametrize("pq", [(7, 3), (5, 4), (4, 5), (3, 7), (8, 3), (5, 5)])
def test_counts_and_centres_equal_hypertiling(pq):
    """hypertiling's GR kernel counts layers by reflections across edges, as here; its
    polygon centres, rotated by its starting angle, are this patch's centres."""
    ht = pytest.importorskip("hypertiling")
    depth = 5
    ours = np.concatenate(list(layers.hyperbolic_layers(*pq, depth)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tiling = ht.HyperbolicTiling(*pq, depth + 1, kernel="GR")
        theirs = np.array([tiling.get_center(i) for i in range(len(tiling))])
    assert len(theirs) == len(ours)
    mine = model.poincare(ours[:, :, 2])
    z = mine[:, 0] + 1j * mine[:, 1]
    # both are rotations of the same centre set: match after rotating by the angle that
    # takes some tile of layer 1 of theirs onto one of ours
    ring = theirs[np.argsort(np.abs(theirs))][1]
    best = None
    for w in z[1:1 + pq[0]]:
        rot = theirs * (w / ring) * abs(ring) / abs(w)
        d = np.abs(rot[:, None] - z[None, :]).min(axis=1).max()
        best = d if best is None else min(best, d)
    assert best < 1e-9


@pytest.mark.parametrize("pq", sorted(PLATONIC))
def test_platonic_face_edge_vertex_counts(pq):
    t = RegularTiling(*pq)
    faces, edges, vertices = PLATONIC[pq]
    props = t.properties()
    assert (props["faces"], props["edges"], props["vertices"]) == (faces, edges, vertices)
    patch = t.patch()
    assert len(patch) == faces
    v = np.round(patch.model_vertices().reshape(-1, 3), 9)
    assert len(np.unique(v, axis=0)) == vertices
    report = patch.validate()
    assert report.ok, report.summary()
    sums, counts = vertex_angle_sums(patch)
    assert (counts == pq[1]).all() and np.allclose(sums, 2 * np.pi, atol=1e-9)


def test_estimates_bound_the_counts():
    for pq in [(7, 3), (5, 4), (3, 7), (4, 5)]:
        exact = np.cumsum(layers.layer_counts(*pq, 14))
        for depth in (3, 9, 14):
            est = RegularTiling(*pq, depth=depth).estimate_tiles()
            assert exact[depth] <= est <= 1.2 * exact[depth], (pq, depth, est, exact[depth])
    t = RegularTiling(7, 3, radius=5.0)
    assert len(t.patch()) <= t.estimate_tiles() <= 4 * len(t.patch())


# ------------------------------------------------------------------ geometry


def klein_polygons(patch):
    return model.klein(patch.model_vertices())


def separated_pairs_klein(polys, pairs):
    """Whether each pair of convex polygons (Klein model, straight edges) is separated by an
    edge line of one of them: the separating-axis test, written for this test."""
    ok = np.zeros(len(pairs), dtype=bool)
    for side in (0, 1):
        a, b = polys[pairs[:, side]], polys[pairs[:, 1 - side]]
        e = np.roll(a, -1, axis=1) - a                        # (m, p, 2) CCW edges
        normal = np.stack([e[..., 1], -e[..., 0]], axis=-1)   # outward
        # every vertex of b on the outer side of some edge of a (touching allowed)
        proj = np.einsum("mpc,mkc->mpk", normal, b) - np.einsum("mpc,mpc->mp", normal, a)[..., None]
        scale = np.linalg.norm(normal, axis=-1)[..., None]
        ok |= (proj >= -1e-9 * scale).all(axis=2).any(axis=1)
    return ok


@pytest.mark.parametrize("pq", [(7, 3), (5, 4), (3, 7), (4, 5), (6, 4)])
def test_no_two_tiles_overlap_in_the_klein_model(pq):
    t = RegularTiling(*pq, depth=5 if pq[0] > 3 else 9)
    patch = t.patch()
    polys = klein_polygons(patch)
    c = patch.model_centres()
    # every pair whose centres are within two circumradii could touch; all of them are tested
    g = model.HYPERBOLIC_GEOMETRY
    d = g.acos(-(c[:, None, 0] * c[None, :, 0] + c[:, None, 1] * c[None, :, 1] - c[:, None, 2] * c[None, :, 2]))
    i, j = np.nonzero(np.triu(d < 2 * t.polygon.circumradius + 1e-6, 1))
    assert len(i) >= len(patch)  # neighbours exist
    assert separated_pairs_klein(polys, np.column_stack([i, j])).all()
    # distinct tiles are at least twice the inradius apart (no tile twice)
    np.fill_diagonal(d, np.inf)
    assert d.min() >= 2 * t.polygon.inradius - 1e-9


def test_the_klein_check_finds_an_overlap():
    t = RegularTiling(7, 3, depth=2)
    patch = t.patch()
    nudge = model.HYPERBOLIC_GEOMETRY.translation(0.2)
    bad = ModelPatch.concat([patch, patch.subset(np.array([3])).transformed(nudge)])
    polys = klein_polygons(bad)
    pairs = np.array([[3, len(bad) - 1]])
    assert not separated_pairs_klein(polys, pairs).all()
    report = bad.validate()
    assert not report.ok and any(len(bad) - 1 in (i, j) for i, j, _ in report.overlaps)


@pytest.mark.parametrize("pq", [(7, 3), (5, 4), (3, 7), (4, 6), (8, 3)])
def test_every_full_vertex_has_q_tiles_and_angle_sum_two_pi(pq):
    """The q tiles around a vertex of tile T are within q // 2 edge steps of T, so every
    vertex of a tile in layers 0..depth − q // 2 is full: q tiles, angles summing to 2π."""
    depth = 4 if pq[0] > 3 else 7
    patch = RegularTiling(*pq, depth=depth).patch()
    sums, counts = vertex_angle_sums(patch)
    assert counts.max() == pq[1]
    full = counts == pq[1]
    assert np.allclose(sums[full], 2 * np.pi, atol=1e-9)
    assert (sums[~full] < 2 * np.pi - 0.5 * (2 * np.pi / pq[1])).all()
    inner = patch.subset(patch.colour <= depth - pq[1] // 2)
    keys = np.round(patch.model_vertices().reshape(-1, 3), 9)
    inner_keys = np.round(inner.model_vertices().reshape(-1, 3), 9)
    uniq, inv = np.unique(keys, axis=0, return_inverse=True)
    at = {tuple(k): i for i, k in enumerate(uniq)}
    assert all(full[at[tuple(k)]] for k in inner_keys)


@pytest.mark.parametrize("pq, radius", [((7, 3), 4.5), ((5, 4), 4.0), ((3, 7), 4.0)])
def test_radius_patch_covers_its_disc_without_gap_or_overlap(pq, radius):
    """The core's validate on the Klein triangles: every point within radius − circumradius
    lies in a tile whose centre is within radius."""
    t = RegularTiling(*pq, radius=radius)
    patch = t.patch()
    cosh = patch.model_centres()[:, 2]
    assert (cosh <= math.cosh(radius) + 1e-9).all()
    inner = math.tanh((radius - t.polygon.circumradius) / 2)  # Poincaré radius of the covered disc
    region = shapely.Point(0, 0).buffer(inner, 64)
    report = patch.validate(region)
    assert report.ok, report.summary()
    # Gauss–Bonnet: every tile has the area |2π − p(π − 2π/q)|; their Klein triangles' sum is
    # a Euclidean check of the same patch
    assert t.polygon.area == pytest.approx(abs(2 * math.pi - pq[0] * (math.pi - 2 * math.pi / pq[1])))


def test_radius_patch_is_exactly_the_tiles_within_the_radius():
    """Against a deeper layer patch filtered by distance: the radius walk stops no earlier."""
    t = RegularTiling(5, 4, radius=4.2)
    got = np.sort(t.patch().model_centres()[:, 2])
    deep = np.concatenate(list(layers.hyperbolic_layers(5, 4, 9)))
    want = np.sort(deep[deep[:, 2, 2] <= math.cosh(4.2), 2, 2])
    assert len(got) == len(want) and np.allclose(got, want)


def test_validate_reports_a_gap():
    t = RegularTiling(7, 3, depth=3)
    patch = t.patch()
    holed = patch.subset(np.arange(len(patch)) != 5)
    report = holed.validate(shapely.Point(0, 0).buffer(0.6, 32))
    assert not report.ok and report.uncovered_area > 0


def test_arcs_are_orthogonal_circles_through_both_points():
    rng = np.random.default_rng(35)
    r = np.sqrt(rng.uniform(0, 0.9, (200, 2)))
    ang = rng.uniform(0, 2 * np.pi, (200, 2))
    a = np.column_stack([r[:, 0] * np.cos(ang[:, 0]), r[:, 0] * np.sin(ang[:, 0])])
    b = np.column_stack([r[:, 1] * np.cos(ang[:, 1]), r[:, 1] * np.sin(ang[:, 1])])
    cmds = arc_commands(a, b)
    for (ax, ay), (bx, by), cmd in zip(a, b, cmds):
        assert cmd.startswith("A")
        rad = float(cmd[1:].split()[0])
        # the centre on the perpendicular bisector at distance sqrt(r^2 - |ab|^2/4) from the
        # midpoint, and orthogonal to the unit circle: |c|^2 = 1 + r^2 for one of the two
        mx, my = (ax + bx) / 2, (ay + by) / 2
        half = math.hypot(bx - ax, by - ay) / 2
        h = math.sqrt(max(rad * rad - half * half, 0))
        ux, uy = -(by - ay) / (2 * half), (bx - ax) / (2 * half)
        ok = [abs((mx + s * h * ux) ** 2 + (my + s * h * uy) ** 2 - 1 - rad * rad) < 1e-6 for s in (1, -1)]
        assert any(ok)
    # a diameter is a straight line
    assert arc_commands(np.array([[0.3, 0.3]]), np.array([[-0.2, -0.2]]))[0].startswith("L")


def test_svg_draws_arcs_and_a_png_renders(tmp_path):
    cairosvg = pytest.importorskip("cairosvg")
    t = RegularTiling(5, 4, depth=3)
    svg = t.render_svg(t.patch())
    assert svg.count(" A") + svg.count("dA") > 0 and "<circle" in svg
    png = tmp_path / "t.png"
    cairosvg.svg2png(bytestring=svg.encode(), write_to=str(png))
    assert png.stat().st_size > 1000
    s = RegularTiling(3, 5)
    assert 'fill-opacity="0.2"' in s.render_svg(s.patch())


def test_streamed_layers_are_the_patch():
    t = RegularTiling(7, 3, depth=6)
    chunks = list(t.iter_patches(None, chunk_tiles=100))
    assert max(len(c) for c in chunks) <= 100
    whole = t.patch()
    assert sum(len(c) for c in chunks) == len(whole) == 1 + 7 + 21 + 56 + 147 + 385 + 1008
    assert np.allclose(np.concatenate([c.transform for c in chunks]), whole.transform)
    assert list(np.bincount(whole.colour)) == layers.layer_counts(7, 3, 6)


def test_region_keeps_the_tiles_meeting_it():
    t = RegularTiling(7, 3, depth=4)
    box = (0.0, 0.0, 0.9, 0.9)
    part = t.patch(box)
    whole = t.patch()
    meets = shapely.intersects(shapely.box(*box), whole.geometries()) & ~shapely.touches(shapely.box(*box),
                                                                                          whole.geometries())
    assert len(part) == int(meets.sum()) and 0 < len(part) < len(whole)


def test_model_matrices_preserve_the_form():
    for pq in [(7, 3), (4, 3)]:
        poly = model.RegularPolygon(*pq)
        j = poly.geometry.form()
        for h in poly.half_turns():
            assert np.allclose(h.T @ j @ h, j, atol=1e-12)
            assert np.allclose(h @ h, np.eye(3), atol=1e-12)  # a half-turn is an involution
    # deep tiles stay on the hyperboloid: <c, c> = -1 to 1e-9 relative
    deep = list(layers.hyperbolic_layers(7, 3, 12))[-1]
    c = deep[:, :, 2]
    form = c[:, 0] ** 2 + c[:, 1] ** 2 - c[:, 2] ** 2
    assert np.allclose(form / c[:, 2] ** 2, -1 / c[:, 2] ** 2, atol=1e-9)


# ------------------------------------------------------------------ specs, records, errors


def test_spec_round_trip_and_records():
    t = RegularTiling(5, 4, depth=3, name="hyperbolic-5-4")
    again = RegularTiling.from_spec(t.spec(), want="hyperbolic")
    assert (again.p, again.q, again.depth, again.name) == (5, 4, 3, "hyperbolic-5-4")
    records = {r.name: r for r in plugin.curved_records()}
    assert {r.family for r in records.values()} == {"spherical", "hyperbolic"}
    assert records["icosahedron"].properties["faces"] == 20
    for rec in records.values():
        if rec.properties.get("oeis"):
            pq = (rec.properties["p"], rec.properties["q"])
            assert rec.properties["oeis"] == OEIS[pq][0]
            n = min(len(rec.properties["layer_counts"]), len(OEIS[pq][1]))
            assert n >= 7 and rec.properties["layer_counts"][:n] == OEIS[pq][1][:n]
    assert plugin.SPHERICAL == model.SPHERE and plugin.HYPERBOLIC == model.HYPERBOLIC


@pytest.mark.parametrize("kwargs, exc, needle", [
    ({"p": 2, "q": 5}, ParameterError, "p must be an integer 3..60"),
    ({"p": 4, "q": 4}, ParameterError, "Euclidean plane"),
    ({"p": 7, "q": 3.5}, ParameterError, "q must be an integer"),
    ({"p": 7, "q": 3, "depth": -1}, ParameterError, "depth must be an integer 0..60"),
    ({"p": 7, "q": 3, "radius": MAX_RADIUS + 1}, ParameterError, "radius must be a number 0..25"),
    ({"p": 7, "q": 3, "radius": float("nan")}, ParameterError, "radius must be a number"),
    ({"p": 7, "q": 3, "depth": 2, "radius": 1}, ParameterError, "depth or radius, not both"),
    ({"p": 3, "q": 3, "want": "hyperbolic"}, ParameterError, "is spherical, not hyperbolic"),
])
def test_bad_parameters_are_one_line(kwargs, exc, needle):
    with pytest.raises(exc) as err:
        RegularTiling(**kwargs)
    assert needle in str(err.value) and "\n" not in str(err.value)


def test_bad_specs_and_options():
    with pytest.raises(ParseError, match="unknown key"):
        RegularTiling.from_spec({"p": 7, "q": 3, "colour": 1})
    with pytest.raises(ParseError, match="needs p and q"):
        RegularTiling.from_spec({"p": 7})
    with pytest.raises(ParameterError, match="valid: p, q, depth, radius, samples, plane"):
        RegularTiling(7, 3).configure(size=3)
    with pytest.raises(ParameterError, match="drawn whole"):
        RegularTiling(4, 3).configure(depth=2)
    with pytest.raises(GeometryError, match="inside the unit"):
        RegularTiling(7, 3, depth=1).patch().validate((-2, -2, 2, 2))


def test_a_sphere_cannot_be_grown_by_the_disc_automaton():
    with pytest.raises(GeometryError):
        list(layers.hyperbolic_layers(4, 3, 5))


# ------------------------------------------------------------------ the command line


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "curved")


def test_cli_list_show_render(cli, tmp_path):
    r = cli("list", "--family", "hyperbolic", "--count")
    assert r.exit_code == 0 and r.output.split()[-1] == "9"
    r = cli("list", "--family", "spherical", "--where", "faces=20")
    assert r.exit_code == 0 and "icosahedron" in r.output
    r = cli("show", "{7,3}")
    assert r.exit_code == 0 and "A001354" in r.output and "1, 7, 21, 56" in r.output
    r = cli("render", "{5,4}", "--depth", "3", "-o", "h.svg")
    assert r.exit_code == 0 and "(61 tiles)" in r.output, r.output
    r = cli("render", "hyperbolic-7-3", "--set", "radius=3", "-o", "h.geojson")
    assert r.exit_code == 0, r.output
    r = cli("render", "dodecahedron", "-o", "d.svg")
    assert r.exit_code == 0 and "(12 tiles)" in r.output


@pytest.mark.parametrize("args, needle", [
    (["{7,3}", "--depth", "40"], "over the limit of 2,000,000"),
    (["{7,3}", "--set", "radius=24"], "over the limit"),
    (["{7,3}", "--set", "p=4", "--set", "q=4"], "Euclidean plane"),
    (["{7,3}", "--set", "q=two"], "q must be an integer 3..60"),
    (["{7,3}", "--set", "colour=red"], "valid: p, q, depth, radius, samples, plane"),
    (["{7,3}", "--set", "plane=upper"], "plane must be one of poincare, klein, halfplane"),
    (["cube", "--set", "plane=klein"], "plane applies to hyperbolic tilings"),
    (["cube", "--depth", "3"], "drawn whole"),
    (["cube", "--set", "p=7"], "is hyperbolic, not spherical"),
])
def test_cli_bad_input_is_one_line(cli, args, needle):
    assert_one_line_error(cli("render", *args, "-o", "x.svg"), needle)


def test_compiled_outlines_equal_numpy():
    patch = RegularTiling(7, 3, depth=9).patch()
    assert len(patch) == 29261  # A001354 summed to layer 9: past the compiled threshold
    fast = patch.projected()
    slow = model.poincare(model.apply(patch.transform, patch.proto.points))
    assert np.abs(fast - slow).max() < 1e-12


def test_bytes_per_tile_bounds_the_peak():
    import tracemalloc

    RegularTiling(5, 4, depth=2).patch()  # compile / load the kernels outside the measurement
    for pq, depth in [((7, 3), 10), ((5, 4), 10), ((3, 7), 20)]:
        t = RegularTiling(*pq, depth=depth)
        tracemalloc.start()
        n = len(t.patch())
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        assert 96 <= peak / n <= t.bytes_per_tile, (pq, peak / n)


def test_klein_plane_draws_chords():
    """In the Klein model a geodesic is a straight chord: every sampled edge point lies on the
    segment between its edge's ends, and the SVG has no arcs; the patch validates there too."""
    t = RegularTiling(5, 4, depth=3, samples=6, plane="klein")
    patch = t.patch()
    out = patch.projected().reshape(len(patch), 5, 6, 2)
    a, b = out[:, :, 0], np.roll(out[:, :, 0], -1, axis=1)
    for k in range(1, 6):
        pt = out[:, :, k]
        cross = (b[..., 0] - a[..., 0]) * (pt[..., 1] - a[..., 1]) - (b[..., 1] - a[..., 1]) * (pt[..., 0] - a[..., 0])
        assert np.abs(cross).max() < 1e-12
    svg = t.render_svg(patch)
    assert " A" not in svg and "L" in svg
    assert patch.validate(shapely.Point(0, 0).buffer(0.5, 32)).ok
    assert RegularTiling.from_spec(t.spec()).plane == "klein"


def test_a_stream_of_layers_exports_as_geojson_and_svg(tmp_path):
    """What `tilekit render` does with a patch larger than memory: the core's streamed
    writers over iter_patches, one chunk at a time."""
    import json

    from tilekit.export import write_patches

    t = RegularTiling(7, 3, depth=6)
    n = write_patches(t.iter_patches(chunk_tiles=500), tmp_path / "s.geojson")
    assert n == 1625
    features = json.loads((tmp_path / "s.geojson").read_text())["features"]
    assert len(features) == 1625
    ring = np.array(features[100]["geometry"]["coordinates"][0])
    assert len(ring) == 7 * t.samples + 1 and (np.hypot(ring[:, 0], ring[:, 1]) < 1).all()
    n = write_patches(t.iter_patches(chunk_tiles=500), tmp_path / "s.svg", region=t.default_region())
    assert n == 1625 and (tmp_path / "s.svg").read_text().count("M") >= 1625


def test_adjacency_pairs_are_the_tiles_two_inradii_apart():
    """The core's adjacency on the projected outlines: edge neighbours are exactly the tiles
    whose centres are 2 * inradius apart (the half-turn about an edge's midpoint)."""
    t = RegularTiling(7, 3, depth=4)
    patch = t.patch()
    pairs = {tuple(e) for e in np.sort(np.asarray(patch.adjacency().edge), axis=1).tolist()}
    c = patch.model_centres()
    d = model.HYPERBOLIC_GEOMETRY.acos(c[:, None, 2] * c[None, :, 2] - c[:, None, 0] * c[None, :, 0]
                                       - c[:, None, 1] * c[None, :, 1])
    i, j = np.nonzero(np.triu(np.abs(d - 2 * t.polygon.inradius) < 1e-7, 1))
    assert pairs == set(zip(i.tolist(), j.tolist())) and len(pairs) == 546


def test_tile_table_rows():
    """The tile table of a curved patch: centres in the disc, turns in [0, 360), nothing
    reflected, the centre tile's edge neighbours the seven tiles of layer 1."""
    patch = RegularTiling(7, 3, depth=2).patch()
    table = patch.tile_table()
    assert (np.hypot(table.centre[:, 0], table.centre[:, 1]) < 1).all()
    assert ((table.angle >= 0) & (table.angle < 360)).all() and not table.reflected.any()
    assert table.angle[0] == 0
    assert sorted(table.index[table.offsets[0]:table.offsets[1]].tolist()) == list(range(1, 8))
