"""Uniform tilings by Wythoff's construction (issue 35 item 1; the curved plugin's `curved` family).

Facts checked: the Archimedean solids' face counts per polygon and vertex counts (Cromwell,
*Polyhedra*, 1997, table 2.2 / ch. 5; Grünbaum & Shephard, *Tilings and Patterns*, §2.1),
prisms and antiprisms (2 n-gons and n squares / 2n triangles), the vertex configuration of
every generated tiling found from the patch itself (faces round each vertex in angular
order), the faces' angles summing to 2π at each vertex, Descartes' total angle defect 4π
over the sphere's vertices counted on the patch, no overlap and no gap through the geometry's validate, the plane's ten
Wythoffian Archimedean tilings equal to the archimedean family's (wallpaper group and vertex
type), and one-line errors.
"""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest
import shapely
from cliutil import assert_one_line_error
from family_cli import family_cli

from tilekit.errors import ParameterError, ParseError
from tilekit.plugins.curved import model, notation, wythoff
from tilekit.plugins.curved.uniform import UniformTiling, euclidean_tiling

# Cromwell, Polyhedra (1997), table of the Archimedean solids: faces per polygon size, vertices.
ARCHIMEDEAN = {
    "3.6.6": ({3: 4, 6: 4}, 12),
    "3.4.3.4": ({3: 8, 4: 6}, 12),
    "3.8.8": ({3: 8, 8: 6}, 24),
    "4.6.6": ({4: 6, 6: 8}, 24),
    "3.4.4.4": ({3: 8, 4: 18}, 24),
    "4.6.8": ({4: 12, 6: 8, 8: 6}, 48),
    "3.3.3.3.4": ({3: 32, 4: 6}, 24),
    "3.5.3.5": ({3: 20, 5: 12}, 30),
    "3.10.10": ({3: 20, 10: 12}, 60),
    "5.6.6": ({5: 12, 6: 20}, 60),
    "3.4.5.4": ({3: 20, 4: 30, 5: 12}, 60),
    "4.6.10": ({4: 30, 6: 20, 10: 12}, 120),
    "3.3.3.3.5": ({3: 80, 5: 12}, 60),
}
# The Platonic solids as Wythoff symbols p | q 2: faces, vertices.
PLATONIC = {"3 | 2 3": ({3: 4}, 4), "4 | 2 3": ({3: 8}, 6), "3 | 2 4": ({4: 6}, 8), "5 | 2 3": ({3: 20}, 12),
            "3 | 2 5": ({5: 12}, 20)}

HYPERBOLIC = ["3.14.14", "3.3.3.3.7", "3.7.3.7", "3.4.7.4", "4.6.14", "7.7.7", "5.8.8", "4.10.10", "3.3.4.3.5",
              "4.5.4.5", "3.4.3.4.3.4", "6.6.6.6", "3.3.3.3.3.4", "4.8.10"]


def vertex_table(patch):
    """Each vertex of the patch (welded at 1e-7 on the model) with its faces' sizes in angular
    order round it and the faces' interior angles there, computed here from the vertices."""
    sign = patch.prototiles[0].sign
    form = np.diag([1.0, 1.0, float(sign)])
    entries = []  # (vertex key, direction angle, sides, interior angle)
    for face in patch.vertex_lists():
        k = len(face)
        for i in range(k):
            v, a, b = face[i], face[i - 1], face[(i + 1) % k]
            ta = a - sign * (a @ form @ v) * v    # tangents at v towards the neighbours
            tb = b - sign * (b @ form @ v) * v
            cos = (ta @ form @ tb) / math.sqrt((ta @ form @ ta) * (tb @ form @ tb))
            entries.append((v, ta, tb, k, math.acos(max(-1.0, min(1.0, cos)))))
    keys = np.round(np.array([e[0] for e in entries]), 7)
    _, inv = np.unique(keys, axis=0, return_inverse=True)
    groups: dict[int, list] = {}
    for j, e in zip(inv.reshape(-1), entries):
        groups.setdefault(int(j), []).append(e)
    out = []
    for members in groups.values():
        v = members[0][0]
        # a frame of the tangent plane at v: the bisector direction of each face's angle
        e1 = members[0][1] / math.sqrt(abs(members[0][1] @ form @ members[0][1]))
        e2 = np.cross(v, e1) if sign > 0 else form @ np.cross(v, e1)
        e2 = e2 / math.sqrt(abs(e2 @ form @ e2))
        order = []
        for _, ta, tb, k, ang in members:
            mid = ta / math.sqrt(abs(ta @ form @ ta)) + tb / math.sqrt(abs(tb @ form @ tb))
            order.append((math.atan2(mid @ form @ e2, mid @ form @ e1), k, ang))
        order.sort()
        out.append((v, tuple(k for _, k, _ in order), sum(a for _, _, a in order)))
    return out


# ------------------------------------------------------------------ the sphere


@pytest.mark.parametrize("config", sorted(ARCHIMEDEAN))
def test_archimedean_solids_faces_vertices_and_angle_defect(config):
    faces, vertices = ARCHIMEDEAN[config]
    t = UniformTiling(config)
    patch = t.patch()
    sides = [len(f) for f in patch.vertex_lists()]
    assert {n: sides.count(n) for n in set(sides)} == faces
    assert t.face_counts() == faces  # the group-order formula agrees with the patch
    report = patch.validate()
    assert report.ok, report.summary()
    table = vertex_table(patch)
    assert len(table) == vertices
    want = notation.canonical(notation.parse(config))
    for _, seq, angle in table:
        assert notation.canonical(seq) == want
        assert angle == pytest.approx(2 * math.pi, abs=1e-9)  # the faces close round the vertex
    # Descartes: the flat faces' angle defects at the V vertices (counted on the patch) sum to 4π
    flat = sum(math.pi * (n - 2) / n for n in want)
    assert len(table) * (2 * math.pi - flat) == pytest.approx(4 * math.pi)


def test_named_examples_of_the_issue():
    """Truncated icosahedron 12 + 20, snub cube 32 + 6, rhombicosidodecahedron 20 + 30 + 12."""
    def count(config):
        sides = [len(f) for f in UniformTiling(config).patch().vertex_lists()]
        return sorted((n, sides.count(n)) for n in set(sides))

    assert count("5.6.6") == [(5, 12), (6, 20)]
    assert count("3.3.3.3.4") == [(3, 32), (4, 6)]
    assert count("3.4.5.4") == [(3, 20), (4, 30), (5, 12)]


@pytest.mark.parametrize("symbol", sorted(PLATONIC))
def test_platonic_solids_by_wythoff(symbol):
    faces, vertices = PLATONIC[symbol]
    patch = UniformTiling(symbol=symbol).patch()
    sides = [len(f) for f in patch.vertex_lists()]
    assert {n: sides.count(n) for n in set(sides)} == faces
    assert patch.validate().ok
    assert len(vertex_table(patch)) == vertices


@pytest.mark.parametrize("n", [3, 5, 7, 12, 24])
def test_prisms_and_antiprisms(n):
    prism = UniformTiling(f"4.4.{n}").patch()
    anti = UniformTiling(f"3.3.3.{n}").patch()
    for patch, want in ((prism, Counter({n: 2}) + Counter({4: n})), (anti, Counter({n: 2}) + Counter({3: 2 * n}))):
        counts = Counter(len(f) for f in patch.vertex_lists())
        assert counts == want, (n, counts)
        assert patch.validate().ok


def test_snubs_are_chiral_and_every_vertex_alike():
    """| 2 3 5 uses the rotation group only: the patch's faces are its orbits, and every
    vertex sees 3.3.3.3.5 in the same turning sense (the sequence itself, not its mirror,
    up to rotation)."""
    table = vertex_table(UniformTiling("3.3.3.3.5").patch())
    rotations = {tuple(s[i:] + s[:i]) for _, s, _ in table for i in range(len(s))}
    assert (3, 3, 3, 3, 5) in rotations


# ------------------------------------------------------------------ the hyperbolic plane


@pytest.mark.parametrize("config", HYPERBOLIC)
def test_hyperbolic_vertex_configuration_angles_and_validate(config):
    radius = 2.0
    t = UniformTiling(config, radius=radius)
    patch = t.patch()
    # the faces cover the disc of the radius, without overlap
    report = patch.validate(shapely.Point(0, 0).buffer(math.tanh(radius / 2), 64))
    assert report.ok, report.summary()
    want = notation.canonical(notation.parse(config))
    full = 0
    for v, seq, angle in vertex_table(patch):
        if np.arccosh(max(v[2], 1.0)) < radius:  # every face round it meets the disc
            full += 1
            assert notation.canonical(seq) == want, (config, seq)
            assert angle == pytest.approx(2 * math.pi, abs=1e-9)
    assert full >= 1


def test_radius_keeps_exactly_the_faces_that_can_meet_its_disc():
    t = UniformTiling("3.14.14", radius=3.0)
    patch = t.patch()
    rho = np.array([f.circumradius for f in t.construction.face_types])
    d = np.arccosh(patch.transform[:, 2, 2])
    assert (d <= 3.0 + rho[patch.prototile] + 1e-9).all()
    bigger = UniformTiling("3.14.14", radius=4.0).patch()
    db = np.arccosh(bigger.transform[:, 2, 2])
    assert (db <= 3.0 + rho[bigger.prototile] + 1e-9).sum() == len(patch)
    # no face twice: centres of faces of one kind are at least an edge apart
    for k in range(len(t.prototiles)):
        c = model.poincare(patch.transform[patch.prototile == k, :, 2])
        diff = np.hypot(*(c[:, None] - c[None]).transpose(2, 0, 1))
        np.fill_diagonal(diff, 1.0)
        assert diff.min() > 1e-6


def test_estimate_bounds_the_count():
    for config in ("3.14.14", "3.3.3.3.7", "4.5.4.5"):
        t = UniformTiling(config, radius=4.0)
        n = len(t.patch())
        assert n <= t.estimate_tiles() <= 3 * n


def test_the_motions_preserve_the_form():
    patch = UniformTiling("3.3.4.3.5", radius=3.0).patch()
    j = np.diag([1.0, 1.0, -1.0])
    err = np.abs(np.einsum("nji,jk,nkl->nil", patch.transform, j, patch.transform) - j).max()
    assert err < 1e-9
    assert np.allclose(np.linalg.det(patch.transform), 1.0)


# ------------------------------------------------------------------ the plane


# The ten Wythoffian Archimedean tilings and their symbols; 3^3.4^2 is not Wythoffian.
EUCLIDEAN = {"3.3.3.3.3.3": "6 | 2 3", "4.4.4.4": "4 | 2 4", "6.6.6": "3 | 2 6", "3.6.3.6": "2 | 3 6",
             "3.12.12": "2 3 | 6", "4.8.8": "2 4 | 4", "3.4.6.4": "3 6 | 2", "4.6.12": "2 3 6 |",
             "3.3.3.3.6": "| 2 3 6", "3.3.4.3.4": "| 2 4 4"}


def _archimedean_records():
    from tilekit.plugins import archimedean

    return [r for r in archimedean.tilekit_catalogue_records() if r.family == "archimedean"]


@pytest.mark.parametrize("config", sorted(EUCLIDEAN))
def test_euclidean_wythoff_tilings_equal_the_archimedean_family(config):
    from tilekit.symmetry import wallpaper_group

    t = euclidean_tiling(config)
    records = _archimedean_records()
    name = notation.exponent(notation.canonical(notation.parse(config)))
    rec = next(r for r in records if r.properties["vertex_type"] == name)
    assert wallpaper_group(t).iuc == rec.properties["wallpaper_group"]
    region = shapely.box(-4, -4, 4, 4)
    patch = t.patch(region)
    assert patch.validate(shapely.box(-2, -2, 2, 2)).ok
    # the vertex type from the patch: faces round each inner vertex, by angle
    pts = [np.asarray(p) for p in patch.polygons()]
    seen: dict[tuple, list] = {}
    for poly in pts:
        c = poly.mean(axis=0)
        for v in poly:
            key = tuple(np.round(v, 6))
            seen.setdefault(key, []).append((math.atan2(*(c - v)[::-1]), len(poly), poly, v))
    want = notation.canonical(notation.parse(config))
    inner = [k for k in seen if max(abs(k[0]), abs(k[1])) < 2]
    assert inner
    for k in inner:
        members = sorted(seen[k], key=lambda e: e[0])
        assert notation.canonical(tuple(m[1] for m in members)) == want
        total = 0.0
        for _, n, _, _ in members:
            total += math.pi * (n - 2) / n
        assert total == pytest.approx(2 * math.pi)


def test_euclidean_symbols_and_the_non_wythoffian_one():
    for config, symbol in EUCLIDEAN.items():
        got = [str(s) for s in wythoff.symbols_for(notation.parse(config))]
        assert symbol.replace(" ", "") in [g.replace(" ", "") for g in got], (config, got)
    with pytest.raises(ParameterError, match="no uniform tiling by Wythoff"):
        wythoff.symbol_for(notation.parse("3.3.3.4.4"))


# ------------------------------------------------------------------ symbols, records, errors


def test_symbol_parsing_and_configurations():
    assert wythoff.Symbol.parse("2 3 | 7").configuration == (3, 14, 14)
    assert wythoff.Symbol.parse("| 2 3 7").configuration == (3, 3, 3, 3, 7)
    assert wythoff.Symbol.parse("2 3 7 |").configuration == (4, 6, 14)
    assert wythoff.Symbol.parse("7 | 2 3").configuration == (3,) * 7
    assert wythoff.Symbol.parse("2 | 2 5").configuration is None  # a dihedron
    for bad in ("2 3 7", "2 | 3 | 7", "2 x | 7", "2 3 | 7 8", "| 1 3 7", "2 3 | 61"):
        with pytest.raises((ParseError, ParameterError)):
            wythoff.Symbol.parse(bad)


def _types(max_sides, valences):
    from tilekit.regular.notation import bounded_species, types_of_species

    for k in valences:
        for species in bounded_species(max_sides, k, k):
            yield from types_of_species(species)


def _records():
    from tilekit.plugins import curved

    return {r.properties["vertex_configuration"]: r for r in curved.curved_records() + curved.uniform_records()}


def test_species_polyhedra_are_the_records():
    """Every spherical vertex type the vertex-species search (default max_sides 12) calls a
    polyhedron (Platonic, Archimedean, prism, antiprism) is Wythoffian, no other is, and a
    record of the curved or the regular families answers to each. (No spherical type has
    six polygons: 3^6 is flat.)"""
    from tilekit.plugins.archimedean.species import classify_sequence

    records = _records()
    solids = 0
    for vt in _types(12, range(3, 6)):
        if vt.geometry != "spherical":
            continue
        props = classify_sequence(vt)
        wythoffian = bool(wythoff.symbols_for(vt.polygons))
        assert wythoffian == (props["status"] == "polyhedron"), str(vt)
        if wythoffian:
            solids += 1
            assert notation.dotted(notation.canonical(vt.polygons)) in records, str(vt)
    # 5 Platonic, 13 Archimedean, prisms 4.4.n (n = 3, 5..12: 4.4.4 is the cube) and
    # antiprisms 3.3.3.n (n = 4..12: 3.3.3.3 is the octahedron)
    assert solids == 5 + 13 + 9 + 9


def test_every_hyperbolic_species_type_that_is_uniform_has_a_record_that_renders():
    """The search's defaults (hyperbolic polygons up to 6 sides, 3..6 at a vertex) and its
    largest bound for three or four polygons (10 sides): each uniform type has a record, and
    the curved records among them draw (every fifth, at radius 1.5, is made and validated)."""
    records = _records()
    hits = 0
    seen = set()
    for vt in [*_types(6, range(3, 7)), *_types(10, range(3, 5))]:
        key = notation.dotted(notation.canonical(vt.polygons))
        if vt.geometry != "hyperbolic" or key in seen or not wythoff.symbols_for(vt.polygons):
            continue
        seen.add(key)
        assert key in records, key
        hits += 1
        rec = records[key]
        if rec.family == "curved" and hits % 5 == 0:
            t = UniformTiling.from_spec({**rec.spec, "radius": 1.5})
            patch = t.patch()
            assert len(patch) >= 1 and patch.validate().overlaps == []
    assert hits > 50


def test_spec_round_trip():
    t = UniformTiling("3.14.14", radius=2.0, samples=4)
    again = UniformTiling.from_spec(t.spec())
    assert again.spec() == t.spec() and again.symbol == t.symbol
    s = UniformTiling(symbol="| 2 4 5")
    assert UniformTiling.from_spec(s.spec()).configuration == "3.3.4.3.5"
    assert s.configure(radius=1.0).radius == 1.0


@pytest.mark.parametrize("kwargs, needle", [
    ({"configuration": "3.4.5"}, "no uniform tiling by Wythoff's construction"),
    ({"configuration": "3.4.6.4"}, "tiles the Euclidean plane"),
    ({"configuration": "3.4.4.4", "geometry": "hyperbolic"}, "is spherical, not hyperbolic"),
    ({"configuration": "3.x.4"}, "cannot read"),
    ({"symbol": "2 3 | 99"}, "r must be an integer 2..60"),
    ({"symbol": "2 2 | 2"}, "fewer than three faces"),
    ({"configuration": "3.14.14", "radius": 13}, "radius must be a number 0..12"),
    ({"configuration": "3.4.4.4", "radius": 2}, "radius applies to hyperbolic tilings"),
    ({"configuration": "3.14.14", "geometry": "torus"}, "geometry must be one of"),
])
def test_bad_input_is_one_line(kwargs, needle):
    with pytest.raises((ParameterError, ParseError), match=None) as err:
        UniformTiling(**kwargs)
    assert needle in str(err.value) and "\n" not in str(err.value)


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "curved")


def test_cli_names_by_vertex_configuration(cli):
    r = cli("render", "3.3.3.3.3.3.3", "-o", "h.svg")
    assert r.exit_code == 0, r.output
    r = cli("render", "3.4.4.4", "--geometry", "sphere", "-o", "s.svg")
    assert r.exit_code == 0 and "(26 tiles)" in r.output, r.output
    r = cli("render", "4.3.4.4", "-o", "s2.svg")  # another rotation of the same configuration
    assert r.exit_code == 0 and "(26 tiles)" in r.output, r.output
    r = cli("render", "3.14.14", "--set", "radius=2", "-o", "t.svg")
    assert r.exit_code == 0, r.output
    r = cli("list", "--family", "curved", "--where", "faces=62")
    assert r.exit_code == 0 and "rhombicosidodecahedron" in r.output and "truncated-icosidodecahedron" in r.output
    r = cli("show", "snub-cube")
    assert r.exit_code == 0 and "| 2 3 4" in r.output and "32 triangles + 6 squares" in r.output


@pytest.mark.parametrize("args, needle", [
    (["3.4.5"], "no uniform tiling by Wythoff's construction"),
    (["3.4.4.4", "--geometry", "hyperbolic"], "is spherical, not hyperbolic"),
    (["3.3.3.3.3.3.3", "--geometry", "sphere"], "is hyperbolic, not spherical"),
    (["3.14.14", "--set", "symbol=2 3 | 99"], "r must be an integer 2..60"),
    (["3.14.14", "--set", "radius=12", "--max-tiles", "1000"], "over the limit"),
    (["4.6.22"], "has no catalogue record"),
    (["3.14.14", "--set", "depth=3"], "valid: configuration, symbol, radius"),
])
def test_cli_bad_input_is_one_line(cli, args, needle):
    assert_one_line_error(cli("render", *args, "-o", "x.svg"), needle)


# ------------------------------------------------------------------ output: meshes and the half-plane


@pytest.mark.parametrize("config", ["5.6.6", "3.3.3.3.4", "4.4.7"])
def test_sphere_mesh_is_closed_and_a_slicer_reads_it(tmp_path, config):
    """Our own check (every edge in exactly two triangles, Euler characteristic 2, outward
    normals) and trimesh's (PyPI, the test oracle: watertight, consistent winding, the
    volume of the ball within the polygonal approximation's error)."""
    from tilekit.plugins.curved.mesh import sphere_mesh, write_mesh

    t = UniformTiling(config)
    v, tri, owner = sphere_mesh(t.patch(), rings=4)
    edges = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert (counts == 2).all()
    assert len(v) - len(counts) + len(tri) == 2
    normal = np.cross(v[tri[:, 1]] - v[tri[:, 0]], v[tri[:, 2]] - v[tri[:, 0]])
    assert ((normal * v[tri].mean(axis=1)).sum(axis=1) > 0).all()
    assert set(owner.tolist()) == set(range(len(t.patch())))
    trimesh = pytest.importorskip("trimesh")
    write_mesh(t, tmp_path / "ball.stl", size_mm=60.0)
    m = trimesh.load(tmp_path / "ball.stl")
    assert m.is_watertight and m.is_winding_consistent
    assert m.volume == pytest.approx(4 / 3 * math.pi * 30.0 ** 3, rel=0.02)
    write_mesh(t, tmp_path / "ball.obj", size_mm=60.0)
    assert (tmp_path / "ball.mtl").exists()
    o = trimesh.load(tmp_path / "ball.obj", force="mesh")
    o = trimesh.Trimesh(o.vertices, o.faces)  # trimesh splits vertices per material; weld them again
    o.merge_vertices()
    assert o.is_watertight and o.volume == pytest.approx(m.volume, rel=1e-4)


def test_sphere_mesh_cli_and_errors(cli):
    r = cli("sphere-mesh", "truncated-icosahedron", "-o", "ball.stl", "--size-mm", "80")
    assert r.exit_code == 0 and "(32 tiles," in r.output, r.output
    r = cli("sphere-mesh", "icosahedron", "-o", "ico.obj", "--rings", "2")
    assert r.exit_code == 0 and "(20 tiles," in r.output, r.output
    assert_one_line_error(cli("sphere-mesh", "3.14.14", "-o", "x.stl"), "is not a tiling of the sphere")
    assert_one_line_error(cli("sphere-mesh", "cube", "-o", "x.ply"), "written as .stl or .obj")
    assert_one_line_error(cli("sphere-mesh", "cube", "-o", "x.stl", "--rings", "99"), "99")


def test_mesh_module_and_cli_agree_on_rings():
    from tilekit.plugins.curved import cli as curved_cli
    from tilekit.plugins.curved import mesh

    assert (curved_cli.DEFAULT_RINGS, curved_cli.MAX_RINGS) == (mesh.DEFAULT_RINGS, mesh.MAX_RINGS)


def test_halfplane_is_the_cayley_image_and_draws_half_circles():
    from tilekit.plugins.curved.render import halfplane_arc_commands

    t = UniformTiling("3.14.14", radius=2.0, plane="halfplane")
    patch = t.patch()
    pts = patch.model_vertices(patch.prototile == 0)
    uv = model.halfplane(pts)
    assert (uv[..., 1] > 0).all()
    z = model.poincare(pts)
    zc = z[..., 0] + 1j * z[..., 1]
    w = 1j * (1 + zc) / (1 - zc)
    assert np.allclose(uv[..., 0], w.real) and np.allclose(uv[..., 1], w.imag)
    assert np.allclose(model.halfplane_to_poincare(uv), z)
    # each edge's arc: a circle centred on the real axis through both ends (a geodesic)
    a, b = uv.reshape(-1, 2), np.roll(uv, -1, axis=1).reshape(-1, 2)
    for cmd, p, q in zip(halfplane_arc_commands(a, b)[:50], a, b):
        if cmd.startswith("L"):
            assert abs(p[0] - q[0]) < 1e-9
            continue
        r = float(cmd[1:].split()[0])
        cx = (p @ p - q @ q) / (2 * (p[0] - q[0]))
        assert math.hypot(p[0] - cx, p[1]) == pytest.approx(r, rel=1e-6)
        assert math.hypot(q[0] - cx, q[1]) == pytest.approx(r, rel=1e-6)
    assert t.patch().validate(shapely.box(-0.5, 0.5, 0.5, 1.5)).ok
    svg = t.render_svg(patch)
    assert svg.count(" A") > 100 and "<line" in svg


def assert_peak_within_bound(t) -> None:
    """The patch's peak memory (tracemalloc) is within the tiling's bytes_per_tile per tile,
    and its tile count within the estimate (test_curved_laves.py uses it too)."""
    import tracemalloc

    tracemalloc.start()
    try:
        patch = t.patch()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak <= t.bytes_per_tile * len(patch), (t.name, peak / len(patch))
    assert len(patch) <= t.estimate_tiles()


def test_bytes_per_tile_bounds_the_peak():
    for config, radius in (("3.14.14", 6.5), ("5.8.8", 5.0), ("3.3.3.3.7", 5.0)):
        assert_peak_within_bound(UniformTiling(config, radius=radius))


def test_geometry_option_for_other_families():
    from tilekit.cli_types import geometry_option

    class Flat:
        name = "3.4.6.4"

    assert geometry_option(Flat(), None) == {} and geometry_option(Flat(), "plane") == {}
    with pytest.raises(ParameterError, match="tiles the Euclidean plane, not spherical"):
        geometry_option(Flat(), "sphere")
    assert geometry_option(UniformTiling("3.4.4.4"), "sphere") == {"geometry": "sphere"}
