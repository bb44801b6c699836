"""Tiles raised in relief on the printed sphere (issue 35 item 4; book §7.3: Yen and Séquin's
Escher Sphere Construction Kit printed its isohedral spheres with the tiles in relief).

Every check here is independent of the writer's bookkeeping: closedness and orientation from
the triangles alone (every undirected edge in exactly two triangles, traversed once each way;
Euler characteristic V − E + F = 2), outward normals by the generalised winding number (a point
just outside a face is outside the solid, just inside is inside), and the enclosed volume by the
divergence theorem against the ball's 4/3 π R³ plus the raised shells' ((R + H)³ − R³)/3 times
the raised tiles' solid angle, the solid angle computed from the tiling's own outlines (Van
Oosterom and Strackee's formula for a triangle's solid angle, IEEE Trans. Biomed. Eng. 30, 1983).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from cliutil import assert_one_line_error
from family_cli import family_cli

from tilekit.errors import ParameterError
from tilekit.plugins.curved import mesh
from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling
from tilekit.plugins.curved.mesh import raise_tiles, sphere_mesh, write_mesh
from tilekit.plugins.curved.uniform import UniformTiling


def solid_angle(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Signed solid angles of the triangles (a, b, c) seen from the origin (rows of points)."""
    num = np.einsum("ij,ij->i", a, np.cross(b, c))
    la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
    den = la * lb * lc + (a * b).sum(1) * lc + (b * c).sum(1) * la + (c * a).sum(1) * lb
    return 2 * np.arctan2(num, den)


def assert_closed_oriented_sphere(v: np.ndarray, tri: np.ndarray) -> None:
    directed = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    assert (directed[:, 0] != directed[:, 1]).all()
    undirected, counts = np.unique(np.sort(directed, axis=1), axis=0, return_counts=True)
    assert (counts == 2).all(), np.bincount(counts)
    keys = directed[:, 0] * len(v) + directed[:, 1]
    assert len(np.unique(keys)) == len(keys)                       # each way once ...
    assert np.isin(directed[:, 1] * len(v) + directed[:, 0], keys).all()  # ... and the other way too
    assert len(np.unique(tri)) == len(v)
    assert len(v) - len(undirected) + len(tri) == 2


def winding(v: np.ndarray, tri: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The generalised winding number of the closed mesh round each point."""
    out = np.empty(len(points))
    for i, q in enumerate(points):
        out[i] = solid_angle(v[tri[:, 0]] - q, v[tri[:, 1]] - q, v[tri[:, 2]] - q).sum() / (4 * math.pi)
    return out


def raised_solid_angle(patch, raised: np.ndarray) -> float:
    """The raised tiles' solid angle from their outlines: a fan from the tile's centre."""
    total = 0.0
    for _, idx, proto in patch.parts():
        pts = proto.points
        c = np.repeat((pts.mean(axis=0) / np.linalg.norm(pts.mean(axis=0)))[None], len(pts), axis=0)
        total += float(solid_angle(c, pts, np.roll(pts, -1, axis=0)).sum()) * int(raised[idx].sum())
    return total


def escher_octahedron(**kw):
    """{3,4} with pairing 'a a b' and a shaped J pair: 8 tiles in a perfect 2-colouring, so at
    every vertex two raised tiles touch only at the corner (4 tiles alternate round it)."""
    return CurvedIsohedralTiling(3, 4, pairing="a a b", edges={"a": "0.3,0.15:0.6,-0.1"}, **kw)


CASES = {
    "cuboctahedron-triangles": (lambda **kw: UniformTiling("3.4.3.4", **kw), 0),
    "truncated-icosahedron-pentagons": (lambda **kw: UniformTiling("5.6.6", **kw), 0),
    "rhombicuboctahedron-class-2": (lambda **kw: UniformTiling("3.4.4.4", **kw), 2),
    "escher-octahedron": (escher_octahedron, 0),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_relief_mesh_is_one_closed_outward_surface(case):
    make, colour = CASES[case]
    patch = make().patch()
    raised = patch.colour == colour
    assert 0 < raised.sum() < len(patch)
    v, tri, owner = raise_tiles(*sphere_mesh(patch, rings=2), raised, 0.1)
    assert_closed_oriented_sphere(v, tri)
    assert set(owner.tolist()) == set(range(len(patch)))
    radius = np.linalg.norm(v, axis=1)
    assert np.isin(np.round(radius, 9), [1.0, 1.05, 1.1]).all()   # ball, wall middles, raised tops
    # outward: just outside every sampled face the winding number is 0, just inside 1
    a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    walls = np.flatnonzero(np.abs((n * (a + b + c)).sum(axis=1)) < 1e-9)   # planes through the centre
    assert len(walls)
    rng = np.random.default_rng(35)
    pick = np.concatenate([rng.choice(walls, 60), rng.choice(len(tri), 60)])
    centroid = (a + b + c)[pick] / 3
    assert np.allclose(winding(v, tri, centroid + 1e-5 * n[pick]), 0, atol=1e-6)
    assert np.allclose(winding(v, tri, centroid - 1e-5 * n[pick]), 1, atol=1e-6)


@pytest.mark.parametrize("case", ["cuboctahedron-triangles", "escher-octahedron"])
def test_relief_volume_is_the_ball_plus_the_raised_shells(case):
    """Divergence theorem: V = Σ det(a, b, c)/6. The mesh is inscribed in its spheres, so it is
    below the exact volume, by an error of order 1/rings² (samples grow with rings): the
    error times rings² stays put (measured 0.124 for the cuboctahedron, 0.17 for the octahedron)
    and each doubling of rings divides the error by about 4."""
    make, colour = CASES[case]
    h = 0.1
    errors = []
    for rings in (2, 4, 8):
        patch = make(samples=2 * rings).patch()
        raised = patch.colour == colour
        v, tri, _ = raise_tiles(*sphere_mesh(patch, rings=rings), raised, h)
        volume = np.einsum("ij,ij->i", v[tri[:, 0]], np.cross(v[tri[:, 1]], v[tri[:, 2]])).sum() / 6
        expected = 4 / 3 * math.pi + ((1 + h) ** 3 - 1) / 3 * raised_solid_angle(patch, raised)
        errors.append((expected - volume) / expected)
        assert 0 < errors[-1] < 0.25 / rings ** 2, (rings, errors)
    assert 3.5 < errors[0] / errors[1] < 4.5 and 3.5 < errors[1] / errors[2] < 4.5, errors


def test_mirrored_tiles_keep_the_winding():
    """A tile placed by a reflection (group 3x of the cube, curved-ih-4-3-2's) is wound the
    other way in its frame; the mesh still turns every face outward."""
    t = CurvedIsohedralTiling(4, 3, symbol="[a+b+c+d+; b+a+d-c-]", edges={"a": "0.25,0.16:0.55,-0.12:0.8,0.06",
                                                                    "c": "0.25,0.16:0.55,-0.12:0.8,0.06"})
    patch = t.patch()
    assert (np.linalg.det(patch.transform) < 0).any()
    v, tri, owner = sphere_mesh(patch, rings=2)
    assert_closed_oriented_sphere(v, tri)
    n = np.cross(v[tri[:, 1]] - v[tri[:, 0]], v[tri[:, 2]] - v[tri[:, 0]])
    assert ((n * v[tri].mean(axis=1)).sum(axis=1) > 0).all()
    v, tri, _ = raise_tiles(v, tri, owner, patch.colour == 0, 0.2)
    assert_closed_oriented_sphere(v, tri)


@pytest.mark.slow  # seeding a catalogue, 450 sphere patches, 224 relief meshes: 27 s at load 4.5 on 2 cores
def test_every_sphere_record_and_colour_class_gives_a_closed_relief(tmp_path):
    """Every catalogue tiling of the sphere (uniform, Laves, stars, curved-isohedral), each of its
    colour classes but the last raised in turn: a closed, consistently oriented sphere."""
    from tilekit.catalogue import open_catalogue  # start-up cost: the catalogue, for this test only

    cat = open_catalogue(f"sqlite:///{tmp_path / 'c.sqlite'}")
    meshes = 0
    for name in cat.names():
        t = cat.tiling(name)
        if getattr(t, "hyperbolic", True):                        # the plane's and hyperbolic records
            continue
        patch = t.patch()
        base = sphere_mesh(patch, rings=1)
        for c in sorted(set(patch.colour.tolist()))[:-1]:
            v, tri, _ = raise_tiles(*base, patch.colour == c, 0.1)
            assert_closed_oriented_sphere(v, tri)
            meshes += 1
    assert meshes >= 200


def read_binary_stl(path) -> np.ndarray:
    """(T, 3, 3) corners of a binary STL, parsed by the format (80-byte header, uint32 count,
    50-byte records) rather than by the writer's code."""
    data = path.read_bytes()
    count = int(np.frombuffer(data, "<u4", 1, 80)[0])
    assert len(data) == 84 + 50 * count
    rec = np.frombuffer(data, np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]), count, 84)
    return rec["v"].astype(float)


def test_stl_and_obj_read_back_watertight(tmp_path):
    t = escher_octahedron(samples=8)
    tiles, triangles = write_mesh(t, tmp_path / "ball.stl", size_mm=60.0, rings=4, relief_mm=2.0)
    corners = read_binary_stl(tmp_path / "ball.stl")
    assert tiles == 8 and len(corners) == triangles
    v, tri = np.unique(np.round(corners.reshape(-1, 3), 3), axis=0, return_inverse=True)
    tri = tri.reshape(-1, 3)
    # where raised tiles touch at a corner the STL has coincident points that the indexed mesh
    # keeps apart; welded by position, every edge is still run as often one way as the other
    directed = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    keys, counts = np.unique(directed[:, 0] * len(v) + directed[:, 1], return_counts=True)
    back = np.searchsorted(keys, (keys % len(v)) * len(v) + keys // len(v))
    assert (back < len(keys)).all() and np.array_equal(keys[back] // len(v), keys % len(v))
    assert np.array_equal(counts[back], counts)
    r = np.linalg.norm(v, axis=1)
    assert r.min() == pytest.approx(30.0, abs=1e-3) and r.max() == pytest.approx(32.0, abs=1e-3)
    volume = np.einsum("ij,ij->i", corners[:, 0], np.cross(corners[:, 1], corners[:, 2])).sum() / 6
    patch = t.patch()
    expected = 4 / 3 * math.pi * 30 ** 3 + (32.0 ** 3 - 30.0 ** 3) / 3 * raised_solid_angle(patch, patch.colour == 0)
    assert 0 < (expected - volume) / expected < 0.25 / 4 ** 2                  # as in the test above
    write_mesh(t, tmp_path / "ball.obj", size_mm=60.0, rings=4, relief_mm=2.0)
    lines = (tmp_path / "ball.obj").read_text().splitlines()
    ov = np.array([[float(x) for x in s.split()[1:]] for s in lines if s.startswith("v ")])
    of = np.array([[int(x) - 1 for x in s.split()[1:]] for s in lines if s.startswith("f ")])
    assert len(of) == triangles and (tmp_path / "ball.mtl").read_text().count("newmtl") == 2
    assert_closed_oriented_sphere(ov, of)
    trimesh = pytest.importorskip("trimesh")
    m = trimesh.Trimesh(ov, of, process=False)      # the OBJ's own vertices, as a slicer indexes them
    assert m.is_watertight and m.is_winding_consistent and m.volume == pytest.approx(volume, rel=1e-4)


@pytest.mark.parametrize("value", [0.0, -1.0, float("nan"), float("inf"), 15.01])
def test_bad_relief_is_a_parameter_error(tmp_path, value):
    with pytest.raises(ParameterError, match=r"0 < relief <= 15 \(half the radius"):
        write_mesh(UniformTiling("3.4.3.4"), tmp_path / "x.stl", size_mm=60.0, relief_mm=value)
    assert not (tmp_path / "x.stl").exists()


def test_walls_count_against_the_triangle_limit(tmp_path, monkeypatch):
    """5.6.6 at 4 rings is 10,080 triangles; its 12 pentagons raised add 4 per boundary
    segment of a pentagon (12 x 5 edges x 8 samples x 4 = 1,920): the limit sees the total."""
    monkeypatch.setattr(mesh, "MAX_TRIANGLES", 11_000)
    t = UniformTiling("5.6.6")
    assert write_mesh(t, tmp_path / "plain.stl", rings=4) == (32, 10_080)
    with pytest.raises(ParameterError, match="12,000 triangles, over the limit of 11,000"):
        write_mesh(t, tmp_path / "relief.stl", rings=4, relief_mm=2.0)


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "curved")


def test_relief_cli_and_errors(cli):
    r = cli("sphere-mesh", "3.4.3.4", "-o", "relief.stl", "--relief-mm", "3")
    assert r.exit_code == 0 and "(14 tiles," in r.output, r.output
    r = cli("sphere-mesh", "3.4.3.4", "-o", "relief.obj", "--relief-mm", "3", "--raise-colour", "1")
    assert r.exit_code == 0, r.output
    for value in ("0", "-2", "nan", "16"):
        assert_one_line_error(cli("sphere-mesh", "3.4.3.4", "-o", "x.stl", "--relief-mm", value),
                              "0 < relief <= 15")
    assert_one_line_error(cli("sphere-mesh", "3.4.3.4", "-o", "x.stl", "--relief-mm", "2", "--raise-colour", "5"),
                          "colour class 5 is not one of this tiling's colour classes 0, 1")
    assert_one_line_error(cli("sphere-mesh", "3.4.3.4", "-o", "x.stl", "--relief-mm", "2", "--raise-colour", "0",
                              "--raise-colour", "1"), "lifts every tile")
    assert_one_line_error(cli("sphere-mesh", "3.4.3.4", "-o", "x.stl", "--raise-colour", "1"), "give --relief-mm")
