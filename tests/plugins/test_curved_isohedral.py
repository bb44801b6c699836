"""Escher-like isohedral tiles on the sphere and the hyperbolic plane (issue 35 item 3:
tilekit.plugins.curved.isohedral).

Facts checked: Poincaré's polygon theorem — a side pairing of {p,q}'s polygon whose vertex
cycles have lengths dividing q makes a group with the polygon as fundamental domain — so on the
sphere the number of tiles equals the group's order read from its orbifold (2/χ, Conway) and the
Platonic solid's face count, and in the hyperbolic plane the orbifold's area −2πχ equals the
polygon's (Gauss–Bonnet); {3,3} with three S edges is the group 222 (the Klein four-group acting
on the tetrahedron's faces) and its colouring needs Z2 x Z2 (four colours); the colouring is
perfect (every pairing motion, applied to the whole patch, shifts all colours by one constant,
found geometrically here), and neighbours differ when every motion's colour is nonzero; random
edge deformations that keep the tile simple still tile (no gap, no overlap, by the geometry's
validate); self-crossing tiles and pairings that do not close are one-line errors; a spec file
reopens to the same tiling.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import shapely
from cliutil import assert_one_line_error
from family_cli import family_cli
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_curved_isohedral_symmetric import orbifold_chi

from tilekit.errors import ParameterError, ParseError
from tilekit.plugins.curved import model
from tilekit.plugins.curved.isohedral import (
    CurvedIsohedralTiling,
    Pairing,
    example_pairing,
    from_file,
    orbifold,
    write_spec,
)
from tilekit.plugins.curved.orbifold import OrbifoldGroup

PLATONIC_FACES = {(3, 3): 4, (4, 3): 6, (3, 4): 8, (5, 3): 12}


def _group(text: str) -> OrbifoldGroup:
    assert "o" not in text and "*" not in text
    return OrbifoldGroup(tuple(int(c) for c in text), (), False)


@pytest.mark.parametrize("pq", sorted(PLATONIC_FACES))
def test_sphere_tiles_are_the_group(pq: tuple[int, int]) -> None:
    t = CurvedIsohedralTiling(*pq)
    patch = t.patch()
    assert len(patch) == PLATONIC_FACES[pq]
    assert _group(orbifold(t.pairing, t.q)).order() == len(patch)
    assert patch.validate().ok


def test_tetrahedron_with_s_edges() -> None:
    t = CurvedIsohedralTiling(3, 3, pairing="a b c")
    assert orbifold(t.pairing, 3) == "222"
    assert t.properties()["colour_group"] == "Z2 x Z2"
    patch = t.patch()
    assert sorted(patch.colour.tolist()) == [0, 1, 2, 3]   # four tiles, four colours


@pytest.mark.parametrize("p, q", [(6, 4), (7, 3), (5, 4), (4, 8), (8, 3), (4, 6), (3, 12)])
def test_hyperbolic_orbifold_area_is_the_polygon(p: int, q: int) -> None:
    pairing = Pairing.parse(example_pairing(p, q), p)
    chi = orbifold_chi(orbifold(pairing, q))
    assert math.isclose(-2 * math.pi * float(chi), model.RegularPolygon(p, q).area, rel_tol=1e-12)


def _centres_match(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """For each point of a, the index of the equal point of b (-1: none)."""
    d = np.abs(a[:, None, :] - b[None, :, :]).max(axis=2)
    j = d.argmin(axis=1)
    return np.where(d[np.arange(len(a)), j] < 1e-7 * max(1.0, float(np.abs(b).max())), j, -1)


@pytest.mark.parametrize("p, q, radius", [(3, 3, None), (5, 3, None), (6, 4, 3.5), (7, 3, 3.0)])
def test_colouring_is_perfect(p: int, q: int, radius: float | None) -> None:
    t = CurvedIsohedralTiling(p, q, radius=radius)
    patch = t.patch()
    centres = patch.model_centres()
    k = t.colour_count
    a, b = t.quotient
    for m in t.motions:
        moved = _centres_match(centres @ m.T, centres)   # the whole patch moved by the motion
        have = moved >= 0
        assert have.sum() >= min(len(patch), 3)
        c0, c1 = patch.colour[have], patch.colour[moved[have]]
        diff = {(((y // b) - (x // b)) % a, ((y % b) - (x % b)) % b) for x, y in zip(c0.tolist(), c1.tolist())}
        assert len(diff) == 1   # one shift of Z_a x Z_b for the whole patch: the colouring is perfect
    assert len(set(patch.colour.tolist())) == k


def test_neighbours_differ_when_every_motion_is_coloured() -> None:
    t = CurvedIsohedralTiling(6, 4, radius=3.5)
    assert all(f != 0 for f in t.phi)
    patch = t.patch()
    g = model.HYPERBOLIC_GEOMETRY
    c = patch.model_centres()
    d = g.acos(-(c[:, None, 0] * c[None, :, 0] + c[:, None, 1] * c[None, :, 1] - c[:, None, 2] * c[None, :, 2]))
    near = np.abs(d - 2 * t.polygon.inradius) < 1e-6      # centres of edge neighbours are 2 inradii apart
    i, j = np.nonzero(near)
    assert len(i) > 20
    assert (patch.colour[i] != patch.colour[j]).all()


shape_point = st.tuples(st.floats(0.05, 0.95), st.floats(-0.22, 0.22))


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(shape_point, min_size=1, max_size=3), st.lists(shape_point, min_size=1, max_size=3),
       st.sampled_from([(6, 4, "a a b b c d"), (4, 3, "a a b c"), (7, 3, "a a b c d b e")]))
def test_random_deformations_still_tile(first, second, case) -> None:
    p, q, pairing = case
    owners = sorted({lab for lab in pairing.split()})
    edges = {}
    for lab, pts in zip(owners, (first, second)):
        pts = sorted(pts)
        edges[lab] = ":".join(f"{x},{y}" for x, y in pts)
    try:
        t = CurvedIsohedralTiling(p, q, pairing=pairing, edges=edges, radius=None if q == 3 and p == 4 else 2.0)
    except ParameterError as exc:
        assert "\n" not in str(exc) and ("simple" in str(exc) or "hemisphere" in str(exc))
        return
    patch = t.patch()
    if t.hyperbolic:
        inner = math.tanh((2.0 - t.polygon.circumradius - 0.3) / 2) if 2.0 > t.polygon.circumradius + 0.3 else 0.05
        report = patch.validate(shapely.Point(0, 0).buffer(inner, 32))
    else:
        report = patch.validate()
    assert report.ok, report.summary()


def test_validate_finds_a_wrong_patch() -> None:
    """The checks can fail: a sphere patch with one tile missing leaves a gap (unmatched edges),
    one with a tile twice overlaps."""
    patch = CurvedIsohedralTiling(4, 3).patch()
    assert not patch.subset(np.arange(len(patch) - 1)).validate().ok
    assert not patch.subset(np.r_[np.arange(len(patch)), 0]).validate().ok
    hyper = CurvedIsohedralTiling(6, 4, radius=3.0).patch()
    doubled = hyper.subset(np.r_[np.arange(len(hyper)), 0])
    assert doubled.validate().overlaps


def test_self_crossing_tile_is_refused() -> None:
    with pytest.raises(ParameterError, match="cross") as exc:
        CurvedIsohedralTiling(6, 4, pairing="a a b b c d", edges={"a": "0.5,0.9:0.5,-0.9"})
    assert "\n" not in str(exc.value)


def test_bad_pairings() -> None:
    with pytest.raises(ParameterError, match="divides q"):
        CurvedIsohedralTiling(7, 3, pairing="a b c d e f g")    # all S: one cycle of 7 corners
    with pytest.raises(ParseError, match="one per edge"):
        CurvedIsohedralTiling(6, 4, pairing="a b")
    with pytest.raises(ParseError, match="names 3 edges"):
        CurvedIsohedralTiling(4, 3, pairing="a a a b")
    with pytest.raises(ParameterError, match="no side pairing"):
        CurvedIsohedralTiling(3, 5)     # no fixed-point-free rotation group of {3,5} acts on its 20 faces
    with pytest.raises(ParameterError, match="no shaped edge"):
        CurvedIsohedralTiling(6, 4, pairing="a a b b c d", edges={"z": "0.3,0.1"})


def test_pairing_of_28_edges_labels_past_z() -> None:
    """28 edges need 28 labels in the incidence symbol: a-z, then A, B (incidence.LABELS);
    what is written parses back to the same symbol, and the tile draws and validates."""
    from tilekit.incidence import LABELS, IncidenceSymbol
    from tilekit.plugins.curved.isohedral import pairing_symbol

    letters = "abcdefghijklmn"      # edge i paired with edge i + 14 (J pairs, a half-turn each)
    t = CurvedIsohedralTiling(28, 28, pairing=" ".join(letters + letters))
    sym = pairing_symbol(t.pairing)
    assert [lab for lab, _ in sym.edges] == list(LABELS[:28])
    text = str(sym)
    assert text.startswith("[a+b+") and "z+A+B+;" in text
    assert IncidenceSymbol.parse(text, len(LABELS)) == sym
    assert sym.canonical() == IncidenceSymbol.parse(str(sym.canonical()), len(LABELS))
    # the 28-gon of {28,28} has area 26π − 28·2π/28 = 24π, so χ = −12 = 2 − 2g: g = 7 handles
    # (one corner cycle of angle 2π, no cone; J pairs by fixed-point-free motions, no mirror)
    assert t.properties()["orbifold"] == "o" * 7
    patch = t.patch()
    assert patch.validate().ok and len(patch.transform) >= 1
    with pytest.raises(ParseError, match="at most 12 tiling edges"):
        IncidenceSymbol.parse(text)    # the planar families' bound stays 12


def test_spec_file_reopens(tmp_path) -> None:
    t = CurvedIsohedralTiling(6, 4, radius=2.5, edges={"a": "0.3,0.1:0.6,-0.1", "c": "0.2,0.1:0.4,0.1"}, samples=2)
    path = tmp_path / "tile.json"
    write_spec(t, path)
    again = from_file(str(path))
    assert again.spec() == t.spec()
    assert np.array_equal(again.patch().transform, t.patch().transform)
    assert np.array_equal(again.prototiles[0].points, t.prototiles[0].points)


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "curved")


def test_cli_render_and_errors(cli, tmp_path) -> None:
    spec = {"p": 6, "q": 4, "pairing": "a a b b c d", "radius": 2.5, "edges": {"a": "0.3,0.12:0.6,-0.1"}}
    (tmp_path / "t.json").write_text(json.dumps(spec))
    res = cli("render", "--system", "t.json", "--family", "curved-isohedral", "-o", "t.svg")
    assert res.exit_code == 0, res.output
    assert (tmp_path / "t.svg").read_text().count("<path") >= 2
    (tmp_path / "bad.json").write_text(json.dumps({**spec, "pairing": "a b c d e f"}))
    assert_one_line_error(cli("render", "--system", "bad.json", "--family", "curved-isohedral", "-o", "x.svg"),
                          "divides q")
    (tmp_path / "cross.json").write_text(json.dumps({**spec, "edges": {"a": "0.5,0.9:0.5,-0.9"}}))
    assert_one_line_error(cli("render", "--system", "cross.json", "--family", "curved-isohedral", "-o", "x.svg"),
                          "simple polygon")
    assert_one_line_error(cli("render", "--system", "t.json", "--family", "curved-isohedral", "--set",
                              "geometry=sphere", "-o", "x.svg"), "not spherical")


@pytest.mark.parametrize("p, q, radius", [(6, 4, 4.0), (7, 3, 3.5), (5, 4, 3.5)])
def test_tiles_are_the_regular_tilings_tiles(p: int, q: int, radius: float) -> None:
    """The pairing group's tiles within a radius sit exactly on the regular tiling's tiles within
    it, found by the regular family's boundary automaton (an independent generator)."""
    from tilekit.plugins.curved.tiling import RegularTiling

    ours = CurvedIsohedralTiling(p, q, radius=radius).patch().model_centres()
    theirs = RegularTiling(p, q, radius=radius).patch().model_centres()
    assert len(ours) == len(theirs)
    assert (_centres_match(ours, theirs) >= 0).all()
