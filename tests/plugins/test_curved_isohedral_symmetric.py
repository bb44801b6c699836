"""Curved isohedral tiles with U and I edges, glide-paired edges and tiles with their own symmetry
(issue 35: tilekit.plugins.curved.delaney and the incidence symbols of tilekit.incidence).

Facts checked: on the sphere a type's group has order 2/χ (Conway's orbifold characteristic),
and a tile-transitive group with tile stabiliser S of order |S| has |Γ| = faces · |S|, the faces
being the Platonic solid's (4, 6, 8, 12, 20); the regular tile with all-I edges has the full
group of the regular tiling, *332, *432, *532 on the sphere and *2pq (written *pq2) in the
hyperbolic plane (the triangle groups of §3.6.2); in the hyperbolic plane the orbifold's area
−2πχ equals the tile's area over |S| (Gauss–Bonnet); every enumerated type's patch passes the
geometry's validate (no gap, no overlap) and so do random deformations of its shaped edges; the
edge rule of §5.3.1 — I straight, U symmetric in the perpendicular bisector, S in the half-turn —
holds on the curves drawn; the colouring is perfect (every hop and tile symmetry, applied to the
whole patch, shifts all colours by one constant, found geometrically); bad symbols are one-line
errors.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tilekit.errors import ParameterError, ParseError
from tilekit.incidence import IncidenceSymbol
from tilekit.plugins.curved import delaney
from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling

PLATONIC_FACES = {(3, 3): 4, (4, 3): 6, (3, 4): 8, (5, 3): 12, (3, 5): 20}


def orbifold_chi(text: str) -> Fraction:
    """χ read off an orbifold symbol (2 − 2 per o − 1 per x − 1 per mirror boundary − (n−1)/n
    per cone − (n−1)/2n per corner)."""
    head, *rings = text.split("*")

    def orders(part: str) -> list[int]:
        digits = part.replace("o", "").replace("x", "")
        return [int(c) for c in (digits.split(",") if "," in digits else digits) if c]

    chi = Fraction(2) - len(rings) - 2 * head.count("o") - text.count("x")
    chi -= sum((Fraction(n - 1, n) for n in orders(head)), Fraction(0))
    chi -= sum((Fraction(n - 1, 2 * n) for r in rings for n in orders(r)), Fraction(0))
    return chi


@pytest.mark.parametrize("pq", sorted(PLATONIC_FACES))
def test_sphere_types_tile_and_their_groups_have_the_right_order(pq: tuple[int, int]) -> None:
    p, q = pq
    types = list(delaney.enumerate_types(p, q))
    assert any(s.edge_kinds() == "I" * p and len(s.tile_symmetries()) == 2 * p for s in types)
    for sym in types:
        t = CurvedIsohedralTiling(p, q, symbol=str(sym))
        patch = t.patch()
        assert len(patch) == PLATONIC_FACES[pq]
        chi = orbifold_chi(t.properties()["orbifold"])
        assert chi == delaney.euler_characteristic(t.delaney, q)
        assert 2 / chi == PLATONIC_FACES[pq] * len(sym.tile_symmetries())
        assert patch.validate().ok, sym


@pytest.mark.parametrize("p, q, group", [(3, 3, "*332"), (4, 3, "*432"), (3, 4, "*432"), (5, 3, "*532"),
                                         (3, 5, "*532"), (7, 3, "*732"), (4, 5, "*542"), (6, 4, "*642")])
def test_regular_tile_with_mirror_edges_has_the_triangle_group(p: int, q: int, group: str) -> None:
    t = CurvedIsohedralTiling(p, q, symbol="[" + "a" * p + "; a]", radius=1.0 if (p - 2) * (q - 2) > 4 else None)
    assert t.properties()["orbifold"] == group
    assert t.properties()["edge_kinds"] == "I" * p and t.properties()["edge_shapes"] == 0


@pytest.mark.parametrize("p, q", [(7, 3), (4, 5), (5, 4), (3, 7)])
def test_hyperbolic_types_tile_and_their_orbifold_area_is_the_tile_over_its_symmetry(p: int, q: int) -> None:
    types = list(delaney.enumerate_types(p, q))
    assert types
    for sym in types:
        t = CurvedIsohedralTiling(p, q, symbol=str(sym), radius=1.6)
        chi = orbifold_chi(t.properties()["orbifold"])
        assert math.isclose(-2 * math.pi * float(chi), t.polygon.area / len(sym.tile_symmetries()), rel_tol=1e-12)
        patch = t.patch()
        inner = math.tanh(max(0.05, 1.6 - t.polygon.circumradius - 0.2) / 2)
        assert patch.validate(shapely.Point(0, 0).buffer(inner, 32)).ok, sym


def test_edge_curves_follow_the_edge_rule() -> None:
    t = CurvedIsohedralTiling(4, 5, symbol="[abab; ba]", radius=1.0)   # U edges, a tile with a 2-fold turn
    assert t.properties()["edge_kinds"] == "UUUU"
    for c in t.edge_curves():
        mirrored = np.column_stack([1 - c[::-1, 0], c[::-1, 1]])
        assert np.allclose(c, mirrored)               # U: symmetric in the perpendicular bisector
        assert np.abs(c[:, 1]).max() > 0.01
    t = CurvedIsohedralTiling(3, 4, symbol="[a+b+c+; a+b-c-]")      # an S edge and two I edges
    curves = t.edge_curves()
    assert np.allclose(curves[0], np.column_stack([1 - curves[0][::-1, 0], -curves[0][::-1, 1]]))
    assert np.allclose(curves[1][:, 1], 0) and np.allclose(curves[2][:, 1], 0)


def _centres_match(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    d = np.abs(a[:, None, :] - b[None, :, :]).max(axis=2)
    j = d.argmin(axis=1)
    return np.where(d[np.arange(len(a)), j] < 1e-7 * max(1.0, float(np.abs(b).max())), j, -1)


@pytest.mark.parametrize("p, q, symbol, radius", [(4, 3, "[a+b+a+b+; b+a+]", None), (4, 5, "[abab; ba]", 3.0),
                                                  (3, 4, "[a+b+c+; a-c+b+]", None), (5, 4, None, 2.5)])
def test_colouring_of_symmetric_tiles_is_perfect(p: int, q: int, symbol: str | None, radius: float | None) -> None:
    if symbol is None:   # a hyperbolic type with a tile symmetry and mirrors, from the enumeration
        symbol = str(next(s for s in delaney.enumerate_types(p, q)
                          if len(s.tile_symmetries()) > 1 and "S" in s.edge_kinds()))
    t = CurvedIsohedralTiling(p, q, symbol=symbol, radius=radius)
    patch = t.patch()
    centres = patch.model_centres()
    a, b = t.quotient
    assert t.colour_count >= 2
    for m in list(t.motions) + list(t.tile_symmetries):
        moved = _centres_match(centres @ m.T, centres)
        have = moved >= 0
        assert have.sum() >= min(len(patch), 3)
        c0, c1 = patch.colour[have], patch.colour[moved[have]]
        diff = {(((y // b) - (x // b)) % a, ((y % b) - (x % b)) % b) for x, y in zip(c0.tolist(), c1.tolist())}
        assert len(diff) == 1
    assert len(set(patch.colour.tolist())) == t.colour_count


shape_point = st.tuples(st.floats(0.05, 0.95), st.floats(-0.2, 0.2))


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(shape_point, min_size=1, max_size=3), st.lists(shape_point, min_size=1, max_size=3),
       st.sampled_from([(4, 3, "[abab; ba]"), (4, 3, "[a+b+a+b+; b+a+]"), (3, 4, "[a+b+c+; a-c+b+]"),
                        (4, 5, "[abab; ba]"), (5, 3, "[a+a-b+cb-; b-a-c]"), (3, 4, "[a+b+c+; a+b-c-]")]))
def test_random_deformations_of_symmetric_types_still_tile(first, second, case) -> None:
    p, q, symbol = case
    owners = sorted(CurvedIsohedralTiling(p, q, symbol=symbol).edge_shapes)
    edges = {lab: ":".join(f"{x},{y}" for x, y in sorted(pts)) for lab, pts in zip(owners, (first, second))}
    radius = 2.0 if (p - 2) * (q - 2) > 4 else None
    assert_tiles_or_refused(lambda: CurvedIsohedralTiling(p, q, symbol=symbol, edges=edges, radius=radius), 0.3)


def assert_tiles_or_refused(build, inner: float) -> None:
    """A tiling with random edge shapes: ``build()`` either refuses the shapes in one line (the
    tile is not simple, or leaves its hemisphere) or its patch validates (the sphere whole, a
    hyperbolic patch on the disc of hyperbolic radius 2·inner round the centre)."""
    try:
        t = build()
    except ParameterError as exc:
        assert "\n" not in str(exc) and ("simple" in str(exc) or "hemisphere" in str(exc)), str(exc)
        return
    patch = t.patch()
    if t.hyperbolic:
        report = patch.validate(shapely.Point(0, 0).buffer(math.tanh(inner), 32))
    else:
        report = patch.validate()
    assert report.ok, t.spec()


def test_bad_symbols_are_one_line_errors() -> None:
    cases = [
        (dict(p=3, q=3, symbol="[abc; abc]"), ParameterError, "does not tile {3,3}"),   # three mirrors need even q
        (dict(p=4, q=3, symbol="[aaa; a]"), ParameterError, "3 edges"),
        (dict(p=3, q=3, symbol="[a+b+; a+]"), ParseError, "adjacency"),
        (dict(p=3, q=3, symbol="[aaa; a]", pairing="a b c"), ParameterError, "not both"),
        (dict(p=4, q=5, symbol="[abab; ba]", edges={"b": "0.2,0.1"}), ParameterError, "no shaped edge"),
    ]
    for kwargs, err, text in cases:
        with pytest.raises(err, match=text.replace("{", r"\{").replace("}", r"\}")) as exc:
            CurvedIsohedralTiling(**kwargs)
        assert "\n" not in str(exc.value)


def test_enumeration_past_its_p_bound_is_refused_before_any_work() -> None:
    from tilekit.limits import LimitError

    with pytest.raises(LimitError, match="up to 10") as exc:
        delaney.enumerate_types(delaney.MAX_TYPES_P + 1, 3)
    assert "\n" not in str(exc.value)


def test_pairings_are_incidence_symbols() -> None:
    # the family's older spelling: 'a b c a b c d' is the symbol with a J pair per repeated letter
    t = CurvedIsohedralTiling(6, 4, pairing="a a b b c d")
    assert str(t.symbol) == "[a+e+b+f+c+d+; e+a+f+b+c+d+]"
    again = CurvedIsohedralTiling(6, 4, symbol=str(t.symbol), radius=2.0)
    assert again.properties()["orbifold"] == t.properties()["orbifold"]
    assert len(again.patch()) == len(CurvedIsohedralTiling(6, 4, pairing="a a b b c d", radius=2.0).patch())
    assert IncidenceSymbol.parse(str(t.symbol)).edge_kinds() == "JJJJSS"


@pytest.mark.parametrize("topology, p, q", [("3^6", 6, 3), ("4^4", 4, 4), ("6^3", 3, 6)])
def test_enumeration_on_the_plane_gives_grunbaum_shephards_types(topology: str, p: int, q: int) -> None:
    # The same Delaney rule on the Euclidean {p,q} (1/p + 1/q = 1/2) gives exactly the isohedral
    # types of Grünbaum and Shephard with that topological type (§5.2: 20 with Laves type [3^6],
    # 36 with [4^4], 11 with [6^3]), as the planar family's shipped templates list them.
    from tilekit.plugins.isohedral.templates import load_templates

    published = {str(t.symbol.canonical()) for t in load_templates().values() if t.topology == topology}
    assert len(published) == {"3^6": 20, "4^4": 36, "6^3": 11}[topology]
    assert {str(s) for s in delaney.enumerate_types(p, q)} == published


def test_every_record_draws_and_tiles() -> None:
    from tilekit.plugins import curved as plugin

    records = plugin.isohedral_records()
    assert len({r.name for r in records}) == len(records)
    by_pq: dict[tuple[int, int], int] = {}
    for rec in records:
        p, q = rec.properties["p"], rec.properties["q"]
        by_pq[p, q] = by_pq.get((p, q), 0) + 1
        spec = dict(rec.spec)
        if rec.properties["geometry"] == "hyperbolic":
            spec["radius"] = 0.8
        t = CurvedIsohedralTiling.from_spec(spec)
        props = t.properties()
        assert {k: props[k] for k in rec.properties} == rec.properties, rec.name
        patch = t.patch()
        if t.hyperbolic:
            assert patch.validate(shapely.Point(0, 0).buffer(0.05, 16)).ok, rec.name
        else:
            assert len(patch) * len(t.symbol.tile_symmetries()) == 2 / delaney.euler_characteristic(t.delaney, q)
            assert patch.validate().ok, rec.name
    # the sphere's five {p,q} are all shipped, with their regular all-I tile among the types
    assert {pq for pq in by_pq if (pq[0] - 2) * (pq[1] - 2) < 4} == set(PLATONIC_FACES)


@pytest.fixture
def cli(tmp_path, monkeypatch):
    from family_cli import family_cli

    return family_cli(tmp_path, monkeypatch, "curved")


@pytest.mark.slow   # seeding a fresh catalogue with the curved plugin's records: about 8 s
def test_records_list_by_geometry_and_render_by_name(cli, tmp_path) -> None:
    from tilekit.plugins import curved as plugin

    hyperbolic = {r.name for r in plugin.isohedral_records() if r.properties["geometry"] == "hyperbolic"}
    res = cli("list", "--family", "curved-isohedral", "--where", "geometry=hyperbolic", "--format", "csv")
    assert res.exit_code == 0, res.output
    listed = {line.split(",")[0] for line in res.output.strip().splitlines()[1:]}
    assert listed == hyperbolic
    res = cli("list", "--family", "curved-isohedral", "--where", "orbifold=*532")
    assert res.exit_code == 0 and "curved-ih-5-3-4" in res.output and "curved-ih-3-5-2" in res.output
    res = cli("list", "--family", "curved-isohedral", "--where", "incidence_symbol=[aaa; a]", "--format", "csv")
    assert {line.split(",")[0] for line in res.output.strip().splitlines()[1:]} == {
        "curved-ih-3-3-5", "curved-ih-3-4-8", "curved-ih-3-5-2", "curved-ih-3-7-2"}   # the regular triangle, mirrors
    res = cli("render", "curved-ih-4-5-2", "-o", "t.svg")
    assert res.exit_code == 0, res.output
    assert (tmp_path / "t.svg").read_text().count("<path") >= 5


def test_symbol_spec_file_reopens_and_configure_switches_type(tmp_path) -> None:
    from tilekit.plugins.curved.isohedral import from_file, write_spec

    t = CurvedIsohedralTiling(5, 4, symbol="[a+b+c+d+e+; a-e+d+c+b+]", radius=1.5, edges={"b": "0.3,0.1:0.6,-0.1"})
    write_spec(t, tmp_path / "t.json")
    again = from_file(str(tmp_path / "t.json"))
    assert again.spec() == t.spec() and "pairing" not in again.spec()
    assert np.allclose(again.prototiles[0].points, t.prototiles[0].points)
    other = t.configure(symbol="[aaaaaa; a]")           # p follows the new symbol's edges, q stays
    assert (other.p, other.q, other.symbol.edge_kinds(), other.radius) == (6, 4, "IIIIII", 1.5)
    with pytest.raises(ParameterError, match="Euclidean"):
        t.configure(symbol="[aaaa; a]")                   # {4,4}: the planar isohedral family's
