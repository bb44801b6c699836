"""Escher-like (shaped-edge) tiles on the curved Laves tilings (issue 35, item 3;
tilekit/plugins/curved/laves.py with the edge-shape pieces of curved/shaped.py).

Facts checked: a shaped Laves tile still tiles — the sphere's patch validates as a 2-chain
(every boundary segment met by its reverse once, Girard areas summing to 4π: shaping a tile of a
tiling conserves its area, 4π over the face count), a hyperbolic patch validates on a disc —; every
edge's curve, carried onto the surface, equals its partner's reversed within 1e-9, the partner
found geometrically (the neighbouring tile whose edge has the same two corners), not from the
incidence symbol; an S edge's curve is symmetric under the half-turn about its midpoint, on the
unit segment and on the surface (§5.3.1); under the rotation group the tiles are chiral (every
tile placed by a proper motion, the J curves not mirror-symmetric); bad shapes are one-line errors.
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
from test_curved_isohedral_symmetric import assert_tiles_or_refused

from tilekit.edgeshapes import FLIP, ROFL, ROT, apply_unit
from tilekit.errors import ParameterError, ParseError
from tilekit.incidence import IncidenceSymbol
from tilekit.plugins.curved import model
from tilekit.plugins.curved.laves import LavesTiling
from tilekit.plugins.curved.patch import _spherical_area
from tilekit.plugins.curved.shaped import edge_points

J_SHAPE = "0.3,0.15:0.6,-0.1"
S_SHAPE = "0.2,0.12:0.35,0.1"

# (configuration, group, edges, radius): sphere and hyperbolic plane, J pairs and S edges
CASES = [
    ("3.4.3.4", "rotations", {"a": J_SHAPE}, None),          # rhombic dodecahedron, JJJJ, 432
    ("3.3.3.3.5", "full", {"a": S_SHAPE, "b": J_SHAPE, "d": "0.4,-0.1"}, None),  # snub's dual: 532
    ("3.6.6", "rotations", {}, None),                        # the default shapes, JJS
    ("3.4.4.4", "rotations", {"a": "bezier:0,0:0.3,0.3:0.7,-0.2:1,0"}, None),
    ("7.7.7", "rotations", {"a": S_SHAPE}, 1.2),             # SSS on 732
    ("3.7.3.7", "rotations", {"a": J_SHAPE}, 1.2),           # JJJJ on 732
]


def _tiling(config, group, edges, radius):
    return LavesTiling(config, group=group, edges=edges, radius=radius)


def _tile_edges(t: LavesTiling, transform: np.ndarray) -> list[np.ndarray]:
    g = model.Geometry(t.construction.space.sign)
    local = edge_points(g, t.frames, t.edge_lengths, t.edge_curves(), t.samples)
    return [pts @ transform.T for pts in local]


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_shaped_laves_patches_validate(case):
    t = _tiling(*case)
    patch = t.patch()
    assert t.edge_shapes is not None
    if not t.hyperbolic:
        report = patch.validate()
        assert report.ok and len(patch) == t.faces
        assert report.uncovered_area < 1e-9                   # the tiles' areas sum to 4π
    else:
        inner = math.tanh((t.radius - t.circumradius) / 2)    # covered: radius - circumradius
        assert inner > 0.2
        assert patch.validate(shapely.Point(0, 0).buffer(inner, 64)).ok


@pytest.mark.parametrize("case", [c for c in CASES if c[3] is None], ids=lambda c: c[0])
def test_shaping_conserves_the_tiles_area_on_the_sphere(case):
    """The shaped tile is a fundamental domain of the same group (times the tile's stabiliser),
    so its area is the straight tile's, 4π over the number of tiles (Girard per triangle)."""
    t = _tiling(*case)
    proto = t.prototiles[0]
    area = sum(_spherical_area(proto.points[list(tri)]) for tri in proto.triangles)
    assert abs(area - 4 * math.pi / t.faces) < 1e-9
    straight = LavesTiling(case[0], group=case[1])
    assert len(t.corners) == len(straight.corners)


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_every_edge_equals_its_partner_reversed(case):
    assert_partners_match(_tiling(*case))


def assert_partners_match(t: LavesTiling, proper: bool = True) -> None:
    """Every edge carried onto the surface equals its partner's within 1e-9, the partner found by
    its corners (the neighbouring tile whose edge has the same two ends), not by the symbol: run
    the other way round (reversed) when the two tiles have the same handedness, the same way when
    one is a mirror image; every tile has all its partners (sphere) or the central one has (a
    hyperbolic disc). ``proper``: no tile is placed by a reflection (the rotations, a snub's
    group); a subgroup with improper elements (tests/plugins/test_curved_laves_types.py) passes False."""
    patch = t.patch()
    ends: dict[tuple, list[tuple[int, int]]] = {}
    tiles = [_tile_edges(t, m) for m in patch.transform]
    for ti, edges in enumerate(tiles):
        if proper and np.linalg.det(patch.transform[ti]) < 0:
            raise AssertionError("a shaped Laves tiling places no tile by a reflection")
        for ei, pts in enumerate(edges):
            ends.setdefault((tuple(np.round(pts[0], 6)), tuple(np.round(pts[-1], 6))), []).append((ti, ei))
    matched = 0
    worst = 0.0
    for (a, b), owners in ends.items():
        for ti, ei in owners:
            others = [(o, True) for o in ends.get((b, a), [])] + [(o, False) for o in owners if o[0] != ti]
            if not others:
                continue  # on the patch's rim (hyperbolic)
            assert len(others) == 1 and others[0][0][0] != ti
            (oi, oe), reverse = others[0]
            mine, theirs = tiles[ti][ei], tiles[oi][oe]
            assert mine.shape == theirs.shape
            worst = max(worst, float(np.abs(mine - (theirs[::-1] if reverse else theirs)).max()))
            matched += 1
    assert worst < 1e-9
    k = len(t.corners)
    if not t.hyperbolic:
        assert matched == k * len(patch)   # every edge of every tile has its partner
    else:
        central = int(np.argmin(patch.transform[:, 2, 2]))
        assert all((tuple(np.round(p[-1], 6)), tuple(np.round(p[0], 6))) in ends for p in tiles[central])
    assert proper or (np.linalg.det(patch.transform) < 0).any()  # mirror images met: both ways checked
    # the shapes really bend the edges (not all straight)
    assert any(np.abs(c[:, 1]).max() > 0.05 for c in t.edge_curves())


shape_point = st.tuples(st.floats(0.05, 0.95), st.floats(-0.25, 0.25))


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.lists(shape_point, min_size=1, max_size=3), min_size=3, max_size=3),
       st.sampled_from([("3.4.3.4", "rotations", None), ("3.6.6", "rotations", None), ("3.3.3.5", "full", None),
                        ("3.3.3.3.4", "full", None), ("7.7.7", "rotations", 1.0), ("3.14.14", "rotations", 1.0)]))
def test_random_shapes_still_tile(polylines, case) -> None:
    """Any shapes: the tile either still tiles (validate) or is refused in one line."""
    config, group, radius = case
    owners = sorted(LavesTiling(config, group=group, edges={}, radius=radius).edge_shapes)
    edges = {lab: ":".join(f"{x},{y}" for x, y in sorted(pts)) for lab, pts in zip(owners, polylines)}
    assert_tiles_or_refused(lambda: LavesTiling(config, group=group, edges=edges, radius=radius), 0.2)


@pytest.mark.parametrize("case", [CASES[1], CASES[2], CASES[4]], ids=lambda c: c[0])
def test_s_edges_are_symmetric_by_the_half_turn(case):
    """§5.3.1: an S edge is turned onto itself by the half-turn about its midpoint."""
    t = _tiling(*case)
    kinds = t.tile_symbol.edge_kinds()
    assert "S" in kinds
    g = model.Geometry(t.construction.space.sign)
    local = edge_points(g, t.frames, t.edge_lengths, t.edge_curves(), t.samples)
    for i, kind in enumerate(kinds):
        curve = t.edge_curves()[i]
        if kind != "S":
            continue
        assert np.abs(apply_unit(ROT, curve) - curve).max() < 1e-12
        half_turn = t.frames[i] @ np.diag([-1.0, -1.0, 1.0]) @ np.linalg.inv(t.frames[i])
        pts = local[i]
        assert np.abs((pts @ half_turn.T)[::-1] - pts).max() < 1e-9
        assert np.abs(curve[:, 1]).max() > 0.01


def test_rotation_tiles_are_chiral():
    """Under the rotations no element reverses orientation: every tile is placed by a proper
    motion, the symbol has no U or I edge and no reflecting tile symmetry, and a J curve is
    not its own mirror image (in the edge's line or its perpendicular bisector)."""
    t = LavesTiling("3.4.3.4", group="rotations", edges={"a": J_SHAPE})
    assert (np.linalg.det(t.patch().transform) > 0).all()
    assert set(t.tile_symbol.edge_kinds()) == {"J"}
    assert all(not reflect for _, reflect in t.tile_symbol.tile_symmetries())
    for curve in t.edge_curves():
        for mirror in (FLIP, ROFL):
            image = apply_unit(mirror, curve)
            assert image.shape != curve.shape or np.abs(image - curve).max() > 0.05


def test_tile_symbol_names_the_canonical_labels():
    """``edges`` names labels of the canonical incidence symbol: the tile's own reading uses
    them, and is the same type (its canonical form is the symbol's)."""
    for config in ("3.3.3.3.5", "3.6.6", "3.3.3.3.4", "3.4.4.4"):
        t = LavesTiling(config, group="rotations")
        assert t.tile_symbol.canonical() == t.incidence_symbol
        assert sorted(t.tile_symbol.labels) == sorted(t.incidence_symbol.labels)
    for text in ("[a+b+c+c-b-a-; a-c+b+]", "[a+b+c+d+e+; a+c+b+e-d-]", "[abab; ba]"):
        sym = IncidenceSymbol.parse(text)
        for v in sym.variants():
            lab = v.canonical_labelling()
            assert lab.canonical() == sym.canonical() and lab.edge_kinds() == v.edge_kinds()


def test_spec_and_configure_keep_the_shapes():
    t = LavesTiling("3.4.3.4", group="rotations", edges={"a": J_SHAPE})
    again = LavesTiling.from_spec(t.spec())
    assert again.spec() == t.spec() and "edges" in t.spec()
    assert np.allclose(again.prototiles[0].points, t.prototiles[0].points)
    moved = t.configure(samples=2)
    assert moved.edge_shapes is not None and moved.spec()["edges"] == t.spec()["edges"]
    other = t.configure(configuration="3.6.6")              # another tile: its labels differ
    assert other.edge_shapes is None
    plain = LavesTiling("3.4.3.4", group="rotations")
    assert plain.edge_shapes is None and "edges" not in plain.spec()


@pytest.mark.parametrize("kwargs, needle", [
    ({"group": "rotations", "edges": {"a": "0.5,0.9:0.5,-0.9"}}, "cross: the tile must stay a simple polygon"),
    ({"group": "rotations", "edges": {"c": J_SHAPE}}, "has no shaped edge 'c'; its shaped edges are a"),
    ({"edges": {"a": J_SHAPE}}, "its shaped edges are none (all I: straight)"),
    ({"group": "rotations", "edges": '{"a": 3'}, "edges must be JSON"),
    ({"group": "rotations", "edges": 3}, "edges must map edge letters to shapes"),
    ({"group": "rotations", "edges": ["a"]}, "is not 'LABEL=x,y:x,y:...'"),       # the --edge / edge= list form
    ({"group": "rotations", "edges": ["a=0.2,0.1", "a=0.3,0.1"]}, "edge 'a' is given twice"),
    ({"group": "rotations", "edges": {"a": "0.3,x"}}, "is not points"),
])
def test_bad_shapes_are_one_line(kwargs, needle):
    with pytest.raises((ParameterError, ParseError)) as err:
        LavesTiling("3.4.3.4", **kwargs)
    assert needle in str(err.value) and "\n" not in str(err.value)


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "curved")


def test_cli_renders_shaped_laves_tiles(cli):
    edges = f'{{"a": "{J_SHAPE}"}}'
    r = cli("render", "[3.4.3.4]", "--geometry", "sphere", "--set", "group=rotations", "--set", f"edges={edges}",
            "-o", "rd.svg")
    assert r.exit_code == 0 and "(12 tiles)" in r.output, r.output
    r = cli("render", "[3.7.3.7]", "--set", "group=rotations", "--set", "radius=1.5", "--set", f"edges={edges}",
            "-o", "h.svg")
    assert r.exit_code == 0, r.output
    assert_one_line_error(cli("render", "[3.4.3.4]", "--set", "group=rotations", "--set",
                              'edges={"a": "0.5,0.9:0.5,-0.9"}', "-o", "x.svg"), "cross")
    assert_one_line_error(cli("render", "[3.4.3.4]", "--set", f"edges={edges}", "-o", "x.svg"),
                          "none (all I: straight)")


@pytest.mark.parametrize("config, group, colours", [("3.6.6", "rotations", 3), ("3.3.3.5", "full", 2),
                                                    ("3.4.3.4", "rotations", 1), ("3.3.3.3.5", "full", 1)])
def test_shaped_tiles_take_a_perfect_colouring_where_one_exists(config, group, colours):
    """The colour is a homomorphism onto an abelian group, zero on the tile's symmetries: every
    symmetry of the tiling (each placing element, acting on the left) shifts all colours by one
    constant, and across each edge the colour moves by the homomorphism's value on its hop. 332 (A4) maps
    onto Z3; the rotation groups 432 with a half-turn in the tile's stabiliser (S4's transpositions
    are odd) and 532 (A5, perfect) have no nontrivial abelian quotient allowed: one colour."""
    t = LavesTiling(config, group=group, edges={})
    patch = t.patch()
    (a, b), _phi = t.perfect_colouring
    assert a * b == colours == len(set(patch.colour.tolist()))
    centres = patch.transform[:, :, 2]
    def tile_at(points):
        d = np.abs(points[:, None, :] - centres[None]).max(axis=2)
        assert (d.min(axis=1) < 1e-9).all()
        return d.argmin(axis=1)
    elems = patch.transform @ np.linalg.inv(t.frame)             # the group's elements placing the tiles
    for e in elems:
        moved = tile_at(centres @ e.T)
        shift = {((patch.colour[m] // b - c // b) % a, (patch.colour[m] % b - c % b) % b)
                 for c, m in zip(patch.colour.tolist(), moved.tolist())}
        assert len(shift) == 1
    # across edge i the colour moves by φ_i (the homomorphism's value on the hop): neighbours
    # differ exactly across the edges where it is nonzero (Z3 has no element of order 2 for an
    # S edge's half-turn, so those neighbours share a colour)
    (a, b), phi = t.perfect_colouring
    for hop, f in zip(t.motions, phi):
        across = tile_at((patch.transform @ hop)[:, :, 2])
        c, d = patch.colour, patch.colour[across]
        assert (((d // b - c // b) % a == f // b) & ((d % b - c % b) % b == f % b)).all()
    assert colours == 1 or any(phi)
