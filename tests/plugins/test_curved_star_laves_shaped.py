"""Escher-like tiles on the duals of the non-Wythoffian uniform tilings (issue 35, item 3;
tilekit/plugins/curved/starlaves.py with the edge-shape pieces of curved/shaped.py): the
rotation subgroup (``group=rotations``) and shaped edges (``edges``).

Facts checked: the rotation subgroup is face-transitive exactly when every vertex of the
uniform tiling is reached by a proper symmetry (checked vertex by vertex on a developed patch,
not by the rule starlaves.py decides by); its symbol has no reflection (no U or I edge, no
reflecting tile symmetry); its orbifold is the full group's orientation double cover where the
full group has reflections (Conway: χ doubles, and Gauss–Bonnet holds, −2πχ = tile area over
|tile symmetry|) — 2*32 of [3^3.6^2] doubles to 3222 (a cone point n becomes two, a corner n
one cone point n); a shaped patch validates on a disc and every edge's curve equals its
partner's (reversed between tiles of one orientation, as it is between a tile and a mirror
image), the partner found geometrically; bad groups and labels are one-line errors (CLI exit 2).
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

from tilekit.errors import ParameterError
from tilekit.plugins.curved import _star_configurations, delaney, model, notation
from tilekit.plugins.curved.shaped import edge_points
from tilekit.plugins.curved.starlaves import StarLavesTiling
from tilekit.plugins.curved.stars import develop

J_SHAPE = "0.3,0.12:0.6,-0.08"
S_SHAPE = "0.2,0.1:0.35,0.08"

# (configuration, group, edges): the rotations of a group with mirrors (2*32, *3222, 3*22, 32*),
# one with none (3222: the rotations are the whole group), and a whole group with mirrors whose
# S edges lie on none (2*32: the tile's edges a)
CASES = [
    ("3.3.3.6.6", "rotations", {"a": S_SHAPE, "c": J_SHAPE}),
    ("4.4.6.6", "rotations", {}),
    ("3.6.3.6.6", "rotations", {"b": J_SHAPE}),
    ("3.4.3.4.4.4", "rotations", {}),
    ("3.3.3.3.4.4", "full", {"b": J_SHAPE}),
    ("3.3.3.6.6", "full", {"a": S_SHAPE}),
]
RADIUS = 1.6


def _edges_on_surface(t: StarLavesTiling, transform: np.ndarray) -> list[np.ndarray]:
    local = edge_points(model.Geometry(-1), t.frames, t.edge_lengths, t.edge_curves(), t.samples)
    return [pts @ transform.T for pts in local]


@pytest.mark.parametrize("case", CASES, ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_shaped_patch_validates_and_edges_meet_their_partners(case):
    config, group, edges = case
    t = StarLavesTiling(config, group=group, edges=edges, radius=RADIUS)
    patch = t.patch()
    inner = math.tanh((RADIUS - t.circumradius) / 2)       # the disc covered: radius - circumradius
    assert inner > 0.2
    assert patch.validate(shapely.Point(0, 0).buffer(inner, 64)).ok
    if group == "rotations":
        assert (np.linalg.det(patch.transform) > 0).all()  # every tile placed by a rotation
    # each edge by its two ends; the tile whose edge has the same ends is its partner
    by_ends: dict[frozenset, list[tuple[int, np.ndarray]]] = {}
    for k, m in enumerate(patch.transform):
        for pts in _edges_on_surface(t, m):
            key = frozenset((tuple(np.round(pts[0], 6)), tuple(np.round(pts[-1], 6))))
            by_ends.setdefault(key, []).append((k, pts))
    pairs = [v for v in by_ends.values() if len(v) == 2]
    assert all(len(v) <= 2 for v in by_ends.values())
    worst = 0.0
    for (ka, a), (kb, b) in pairs:
        assert ka != kb
        same = np.sign(np.linalg.det(patch.transform[ka])) == np.sign(np.linalg.det(patch.transform[kb]))
        assert a.shape == b.shape
        worst = max(worst, float(np.abs(a - (b[::-1] if same else b)).max()))
    assert worst < 1e-9 and len(pairs) >= len(patch)
    central = int(np.argmin(patch.transform[:, 2, 2]))
    for pts in _edges_on_surface(t, patch.transform[central]):  # the central tile: every edge has a partner
        assert len(by_ends[frozenset((tuple(np.round(pts[0], 6)), tuple(np.round(pts[-1], 6))))]) == 2
    assert any(np.abs(c[:, 1]).max() > 0.03 for c in t.edge_curves())  # the edges really bend


shape_point = st.tuples(st.floats(0.05, 0.95), st.floats(-0.25, 0.25))


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.lists(shape_point, min_size=1, max_size=3), min_size=4, max_size=4),
       st.sampled_from([("3.3.3.6.6", "rotations"), ("3.3.3.6.6", "full"), ("4.4.6.6", "rotations"),
                        ("3.6.3.6.6", "rotations"), ("3.3.3.3.4.4", "full")]))
def test_random_shapes_still_tile(polylines, case) -> None:
    """Any shapes on the labels that take one: the tile still tiles (validate on a disc) or is
    refused in one line."""
    config, group = case
    owners = sorted(StarLavesTiling(config, group=group, edges={}, radius=1.0).edge_shapes)
    edges = {lab: ":".join(f"{x},{y}" for x, y in sorted(pts)) for lab, pts in zip(owners, polylines)}
    assert_tiles_or_refused(lambda: StarLavesTiling(config, group=group, edges=edges, radius=1.0), 0.2)


@pytest.mark.parametrize("config, full, rotations", [
    ("3.3.3.6.6", "2*32", "3222"), ("4.4.6.6", "*3222", "3222"), ("3.6.3.6.6", "3*22", "3322"),
    ("3.4.3.4.4.4", "32*", "3322"), ("3.3.3.3.4.4", "3222", "3222"),
])
def test_rotation_groups_symbols(config, full, rotations):
    """The rotation subgroup's orbifold is the full group's orientation double cover (Conway:
    cone points doubled, corners made cone points, a mirror boundary closed; a group without
    reflections is its own); χ doubles with them, and Gauss–Bonnet holds for each group; the
    symbol has no reflection left."""
    whole = StarLavesTiling(config)
    rot = StarLavesTiling(config, group="rotations")
    assert whole.symbol_orbifold() == full and rot.symbol_orbifold() == rotations == rot.properties()["symbol_group"]
    assert rot.properties()["orbifold"] == full and rot.name == f"[{notation.exponent(rot.star.cfg)}]-rotations"
    chi_full = delaney.euler_characteristic(whole.delaney_symbol, whole.valences)
    chi_rot = delaney.euler_characteristic(rot.delaney_symbol, rot.valences)
    mirrors = "*" in full
    assert chi_rot == (2 * chi_full if mirrors else chi_full)
    for t, chi in ((whole, chi_full), (rot, chi_rot)):
        assert abs(-2 * math.pi * float(chi) - t.tile_area() / len(t.stabiliser)) < 1e-9
    assert set(rot.tile_symbol.edge_kinds()) <= {"J", "S"}
    assert not any(reflect for _, reflect in rot.tile_symbol.tile_symmetries())
    assert len(rot.stabiliser) == len(whole.stabiliser) // (2 if (np.linalg.det(whole.stabiliser) < 0).any() else 1)


def _proper_reach(config: str, pairing: str) -> bool:
    """Whether every vertex within 2.5 of the pole is carried there by a proper symmetry: the
    symmetries fixing the pole times each vertex's motion, enumerated."""
    t = StarLavesTiling(config, pairing=pairing)
    verts, _, _ = develop(t.star, t.pairing, 2.5)
    elems = np.matmul(verts[:, None], t.full_stabiliser[None])   # (vertices, |stab|, 3, 3)
    return bool((np.linalg.det(elems) > 0).any(axis=1).all())


def test_rotations_are_refused_exactly_where_they_split_the_tiles():
    """Over every vertex-star record: group=rotations builds exactly when every vertex is
    reached by a proper symmetry; else a one-line error naming the group and the valid one."""
    refused = 0
    for cfg, pairing in _star_configurations():
        dotted = notation.dotted(cfg)
        reach = _proper_reach(dotted, pairing)
        try:
            StarLavesTiling(dotted, pairing=pairing, group="rotations")
            built = True
        except ParameterError as exc:
            assert "two tile orbits" in str(exc) and "group must be full" in str(exc) and "\n" not in str(exc)
            built = False
        assert built == reach, dotted
        refused += not built
    assert refused == 23 and len(_star_configurations()) == 98  # docs/families/curved.md says so


def test_spec_and_configure_keep_group_and_shapes():
    t = StarLavesTiling("3.3.3.6.6", group="rotations", edges={"c": J_SHAPE}, radius=1.2)
    spec = t.spec()
    assert spec["group"] == "rotations" and spec["edges"]["c"].startswith("0,0:0.3,0.12")
    again = StarLavesTiling.from_spec(spec)
    assert again.spec() == spec and np.allclose(again.prototiles[0].points, t.prototiles[0].points)
    moved = t.configure(samples=2)
    assert moved.spec_edges() == t.spec_edges() and moved.group == "rotations" and moved.name == t.name
    assert t.configure(group="full").edge_shapes is None              # another symbol: its labels differ
    plain = StarLavesTiling("3.3.3.6.6")
    assert "group" not in plain.spec() and "edges" not in plain.spec() and plain.name == "[3^3.6^2]"


BAD = [
    ({"configuration": "4.4.6.6", "edges": {"a": J_SHAPE}}, "its shaped edges are none (all I: straight)"),
    ({"configuration": "3.3.3.6.6", "edges": {"b": J_SHAPE}}, "has no shaped edge 'b'; its shaped edges are a"),
    ({"configuration": "3.3.3.6.6", "group": "rotations", "edges": {"c": "0.5,0.9:0.5,-0.9"}}, "simple polygon"),
    ({"configuration": "3.3.3.6.6", "group": "mirrors"}, "group must be one of full, rotations"),
    # an orbifold names a subgroup of a spherical Laves tiling's finite group only (laves.py)
    ({"configuration": "3.3.3.6.6", "group": "3222"}, "group must be one of full, rotations for a vertex-star dual"),
    ({"configuration": "3.4.4.6.4", "group": "rotations"}, "under the rotations of its group 3*32 has two tile orbits"),
]


@pytest.mark.parametrize("kwargs, needle", BAD, ids=[b[1][:24] + str(i) for i, b in enumerate(BAD)])
def test_bad_groups_and_labels_are_one_line(kwargs, needle):
    message = ""
    try:
        StarLavesTiling(**kwargs)
    except ParameterError as exc:
        message = str(exc)
    assert needle in message and "\n" not in message


def test_cli_renders_shaped_star_duals(tmp_path, monkeypatch):
    cli = family_cli(tmp_path, monkeypatch, "curved")
    edges = f'{{"c": "{J_SHAPE}"}}'
    r = cli("render", "[3^3.6^2]", "--set", "group=rotations", "--set", f"edges={edges}", "--set", "radius=1.5",
            "-o", "s.svg")
    assert r.exit_code == 0, r.output
    assert_one_line_error(cli("render", "[3^3.6^2]", "--set", f"edges={edges}", "-o", "x.svg"),
                          "its shaped edges are a")
    assert_one_line_error(cli("render", "[3.4.4.6.4]", "--set", "group=rotations", "-o", "x.svg"),
                          "two tile orbits")
