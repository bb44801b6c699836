"""The isohedral types of the sphere's Laves topologies under every face-transitive subgroup
(issue 35, item 3; tilekit/plugins/curved/subgroups.py and laves.py's face_transitive_subgroups,
isohedral_types and group=<orbifold>).

Sources and facts checked:
- Grünbaum and Shephard, "Spherical tilings with transitivity properties" (The Geometric Vein,
  1981, 65-98), as Akama and Sakano quote it (arXiv:1312.3026, abstract): an isohedral normal
  tiling of the sphere by congruent tiles has the graph of a Platonic solid, a Catalan solid (an
  Archimedean dual), a bipyramid or a trapezohedron — the Laves topologies here. No per-topology
  count of isohedral types was readable to us (the 1981 chapter is not public), so the counts are
  checked against an independent enumeration instead: on the five Platonic topologies the types
  found from the subgroups are exactly the incidence symbols that delaney.enumerate_types finds
  from the combinatorics alone (Delaney symbols that close round every vertex), and every type's
  orbifold read from its Delaney symbol equals the name read from the subgroup's geometry.
- The subgroup enumeration: the rotation groups 432 ≅ S4 and 532 ≅ A5 have 30 and 59 subgroups in
  11 and 9 conjugacy classes (standard group theory, e.g. the subgroup lattices of S4 and A5 in
  the GroupNames database); *432 = S4 × C2 has 98 and *532 = A5 × C2 has 164 subgroups (H and
  H × C2 for each H of the rotation group, and one twisted subgroup per index-2 pair N < K).
- Orbit-stabiliser: a face-transitive H has |H| = faces × |H ∩ Stab(tile)|; the cube's 6 faces
  with stabiliser C4v (order 8) in *432 are one orbit under exactly *432, 432, *332 (T_d), 3*2
  (T_h), 332 (T), 2*3 (D_3d), 223 (D_3) and 3x (S_6).
"""

from __future__ import annotations

import numpy as np
import pytest
from cliutil import assert_one_line_error
from family_cli import family_cli
from test_curved_laves_shaped import J_SHAPE, S_SHAPE, assert_partners_match

from tilekit.errors import GeometryError, ParameterError
from tilekit.plugins.curved import delaney, subgroups
from tilekit.plugins.curved.laves import LavesTiling, face_transitive_subgroups, isohedral_types

CUBE = "| 2 2 3"  # the octahedron's dual (the antiprism | 2 2 3), whose group is *432

# the topologies the tests walk: Platonic, Catalan (octahedral and one icosahedral), a bipyramid
# (the hexagonal prism's dual 4.4.6) and a trapezohedron (3.3.3.5)
TOPOLOGIES = ["3.3.3", "3.3.3.3", "4.4.4", "3.4.3.4", "3.6.6", "3.8.8", "4.6.6", "3.4.4.4", "4.6.8",
              "3.3.3.3.4", "3.5.3.5", "4.4.6", "3.3.3.5", "3.3.3.3.5"]


def _table(config: str, group: str = "full") -> np.ndarray:
    return subgroups.cayley_table(LavesTiling(config, group=group).group_matrices())


def test_the_cubes_types():
    """The cube under its eight face-transitive subgroups (see the module), each with its
    order, tile symmetry and edge kinds: the square under 332 keeps a half-turn only (J edges),
    under 223 and 3x nothing (J and S edges; 3x pairs two edges by rotary reflections), under
    3*2 the mirrors through its edge midpoints make U edges."""
    types = isohedral_types(LavesTiling(symbol=CUBE))
    got = {t.group: (t.order, t.tile_symmetry, t.edge_kinds) for t in types}
    assert got == {"*432": (48, 8, "IIII"), "432": (24, 4, "SSSS"), "*332": (24, 4, "IIII"),
                   "3*2": (24, 4, "UUUU"), "332": (12, 2, "JJJJ"), "2*3": (12, 2, "SSII"),
                   "223": (6, 1, "SSJJ"), "3x": (6, 1, "JJJJ")}
    assert [t.group for t in types][0] == "*432"
    assert all(not t.same_symbol for t in types)   # eight types, eight incidence symbols
    assert next(t for t in types if t.group == "3x").incidence_symbol == "[a+b+c+d+; b+a+d-c-]"


@pytest.mark.parametrize("config", TOPOLOGIES)
def test_orders_over_tile_symmetry_are_the_faces_and_every_type_tiles(config):
    """|H| · 1/|H ∩ Stab(tile)| = faces (orbit-stabiliser); placed by H the straight tiles
    number the faces and validate (no gap, no overlap: the areas sum to 4π)."""
    full = LavesTiling(config)
    for t in isohedral_types(full):
        assert t.order == full.faces * t.tile_symmetry
        h = LavesTiling(config, group=t.group)
        patch = h.patch()
        assert len(patch) == full.faces and patch.validate().ok, t.group
        assert len(h.stabiliser) == t.tile_symmetry and str(h.incidence_symbol) == t.incidence_symbol
        # the group the tiles are placed by is H: its order, its name from the Delaney symbol
        assert len(h.group_matrices()) == t.order
        assert h.properties()["symbol_group"] == t.group == h.symbol_orbifold()


@pytest.mark.parametrize("config, p, q", [("3.3.3", 3, 3), ("3.3.3.3", 4, 3), ("4.4.4", 3, 4),
                                          ("3.3.3.3.3", 5, 3), ("5.5.5", 3, 5)])
def test_platonic_types_are_the_delaney_enumerations(config, p, q):
    """On {p, q} the types from the subgroups are exactly the incidence symbols of
    delaney.enumerate_types (the combinatorial enumeration of the curved-isohedral family):
    tetrahedron 5, cube 8, octahedron 8, dodecahedron 4, icosahedron 2."""
    mine = sorted(t.incidence_symbol for t in isohedral_types(LavesTiling(config)))
    theirs = sorted(str(s.canonical()) for s in delaney.enumerate_types(p, q))
    assert mine == theirs
    assert len(mine) == {(3, 3): 5, (4, 3): 8, (3, 4): 8, (5, 3): 4, (3, 5): 2}[(p, q)]


@pytest.mark.parametrize("config", TOPOLOGIES)
def test_full_and_rotations_give_todays_symbols(config):
    """The whole group's type is group=full's, the rotation subgroup's (when it is transitive:
    not on an omnitruncation's dual) group=rotations'."""
    full = LavesTiling(config)
    types = {t.group: t for t in isohedral_types(full)}
    assert types[full.group_notation()].incidence_symbol == str(full.incidence_symbol)
    assert next(iter(types)) == full.group_notation()           # the largest first
    rot = full.symmetry.group.rotations().notation
    if full.symbol.form == "omni":
        assert rot not in types
    else:
        assert types[rot].incidence_symbol == str(LavesTiling(config, group="rotations").incidence_symbol)


def test_subgroup_counts_of_the_rotation_and_full_groups():
    """S4 (432): 30 subgroups in 11 classes; A5 (532): 59 in 9; *432: 98; *532: 164."""
    for config, group, count, classes in [("3.4.3.4", "rotations", 30, 11), ("3.5.3.5", "rotations", 59, 9),
                                          ("3.4.3.4", "full", 98, None), ("3.5.3.5", "full", 164, None)]:
        table = _table(config, group)
        subs = subgroups.subgroups(table)
        assert len(subs) == count
        assert len(subs[0]) == 1 and len(subs[-1]) == len(table)
        if classes is not None:
            inv = subgroups.inverses(table)
            assert len({subgroups.conjugacy_key(table, inv, s) for s in subs}) == classes


def test_orbifold_names_of_the_point_groups():
    """*432 (m-3m) has 33 conjugacy classes of subgroups, of 25 kinds: the 32 crystallographic
    point groups less the seven hexagonal ones (International Tables for Crystallography A); *532
    (A5 × C2) has 22 classes, each of its own kind (A5's 9 classes, those times the centre, and
    the four twisted ones *, *22, *33, *55). Every name agrees with Conway's characteristic
    2/|H| (checked inside orbifold_name); among them the cross-caps (S_2n: 2x, 3x, 5x, x) and
    the mirrors without corners (C_nh: 2*, 4*)."""
    for config, classes, kinds in [
        ("3.4.3.4", 33, {"1", "x", "22", "*", "2*", "222", "*22", "*222", "44", "2x", "4*", "224", "*44", "2*2",
                         "*224", "33", "3x", "223", "*33", "2*3", "332", "3*2", "432", "*332", "*432"}),
        ("3.5.3.5", 22, {"1", "x", "22", "*", "2*", "222", "*22", "*222", "33", "3x", "223", "*33", "2*3", "55",
                         "5x", "225", "*55", "2*5", "332", "3*2", "532", "*532"})]:
        mats = LavesTiling(config).group_matrices()
        table = subgroups.cayley_table(mats)
        inv = subgroups.inverses(table)
        reps = {subgroups.conjugacy_key(table, inv, s): s for s in subgroups.subgroups(table)}
        assert len(reps) == classes
        assert {subgroups.orbifold_name(mats[s]) for s in reps.values()} == kinds
    with pytest.raises(GeometryError, match="not a group"):
        subgroups.cayley_table(mats[:5])


@pytest.mark.parametrize("config, group, edges, proper", [
    (CUBE, "332", {"a": J_SHAPE}, True),                         # J edges, a half-turn tile
    (CUBE, "223", {"a": S_SHAPE, "c": J_SHAPE}, True),           # no tile symmetry: S and J
    (CUBE, "3x", {"a": J_SHAPE, "c": "0.4,0.1:0.7,-0.05"}, False),  # rotary reflections pair c, d
    (CUBE, "3*2", {"a": "0.25,0.1:0.5,0.15"}, True),             # U edges (the tile has mirrors: placed by rotations)
    ("3.4.3.4", "332", {"a": J_SHAPE, "c": "0.4,0.1"}, True),     # the rhombus without symmetry
    ("3.3.3.5", "5x", {}, False),                                 # the default shapes
])
def test_shaped_edges_under_a_subgroup_match_their_partners(config, group, edges, proper):
    t = LavesTiling(symbol=config, group=group, edges=edges) if "|" in config else \
        LavesTiling(config, group=group, edges=edges)
    report = t.patch().validate()
    assert report.ok and report.uncovered_area < 1e-9
    assert_partners_match(t, proper=proper)
    assert (np.linalg.det(t.patch().transform) > 0).all() == proper


def test_group_spellings_spec_and_configure():
    t = LavesTiling(symbol=CUBE, group="3×")                     # Conway's × read as x
    assert t.group == "3x" and t.default_name() == "[3^4]-3x"
    again = LavesTiling.from_spec(t.spec())
    assert again.group == "3x" and str(again.incidence_symbol) == str(t.incidence_symbol)
    assert t.configure(group="332").properties()["tile_symmetry"] == 2
    assert list(face_transitive_subgroups(LavesTiling("3.6.6").symbol)) == ["*332", "332"]


@pytest.mark.parametrize("kwargs, needle", [
    ({"symbol": CUBE, "group": "*22"}, "*22 is not a subgroup of *432 transitive on its 6 faces; valid groups: "
                                       "*432, *332, 3*2, 432, 2*3, 332, 223, 3x (or full, rotations)"),
    ({"configuration": "4.6.8", "group": "432"}, "valid groups: *432 (or full, rotations)"),
    ({"configuration": "4.6.14", "group": "732"}, "tiles the hyperbolic plane, whose group is infinite"),
    ({"configuration": "3.4.3.4", "group": "mirrors"}, "group must be one of full, rotations or"),
    ({"configuration": "3.4.3.4", "group": 3}, "group must be one of full, rotations or"),
    ({"configuration": "3.4.3.4", "group": "*432" * 10}, "group must be one of full, rotations or"),
    ({"symbol": CUBE, "group": "*332", "edges": {"a": J_SHAPE}}, "has no shaped edge 'a'"),
])
def test_bad_groups_are_one_line(kwargs, needle):
    with pytest.raises(ParameterError) as err:
        LavesTiling(**kwargs)
    assert needle in str(err.value) and "\n" not in str(err.value)


def test_hyperbolic_has_no_type_list():
    with pytest.raises(ParameterError, match="its isohedral types are not listed"):
        isohedral_types(LavesTiling("4.6.14"))


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "curved")


def test_cli_lists_types_and_renders_under_a_subgroup(cli):
    r = cli("laves-types", "[3^4]")
    assert r.exit_code == 0, r.output
    lines = r.output.splitlines()
    assert lines[0] == "[3.3.3.3]: 6 faces, 8 isohedral types"
    assert lines[1].split() == ["GROUP", "ORDER", "INCIDENCE", "SYMBOL", "TILE", "SYMMETRY", "EDGES", "SAME", "SYMBOL"]
    assert [ln.split()[0] for ln in lines[2:]] == ["*432", "*332", "3*2", "432", "2*3", "332", "223", "3x"]
    r = cli("render", "rhombic-dodecahedron", "--set", "group=332", "--set", 'edges={"a": "0.3,0.15:0.6,-0.1"}',
            "-o", "rd.svg")
    assert r.exit_code == 0 and "(12 tiles)" in r.output, r.output


@pytest.mark.parametrize("args, needle", [
    (["render", "[3^4]", "--set", "group=*22", "-o", "x.svg"], "valid groups: *432, *332, 3*2, 432"),
    (["render", "[4.6.14]", "--set", "group=732", "-o", "x.svg"], "group must be full or rotations there"),
    (["laves-types", "[4.6.14]"], "its isohedral types are not listed"),
    (["laves-types", "cube"], "is not a Laves tiling of the curved family"),
])
def test_cli_bad_input_is_one_line(cli, args, needle):
    assert_one_line_error(cli(*args), needle)


@pytest.mark.slow   # every spherical Laves record's subgroups: about 18 s on the loaded 2-core machine
def test_no_two_types_of_a_topology_share_a_symbol_or_an_orbifold():
    """On every spherical Laves record (the 13 Catalan solids, the trapezohedra n = 3..24) and
    the bipyramids n = 3..8: no two face-transitive classes share an orbifold name (none is
    numbered #k) or an incidence symbol (same_symbol is empty). The combinatorial automorphisms
    of these topologies are their symmetries, so equal symbols would mean conjugate groups; the
    list holds them apart when they are not, and here it never has to."""
    configs = ["3.6.6", "3.4.3.4", "3.8.8", "4.6.6", "3.4.4.4", "4.6.8", "3.3.3.3.4", "3.5.3.5", "3.10.10", "5.6.6",
               "3.4.5.4", "4.6.10", "3.3.3.3.5"]
    configs += [f"3.3.3.{n}" for n in range(3, 25)] + [f"4.4.{n}" for n in range(3, 9)]
    for config in configs:
        types = isohedral_types(LavesTiling(config))
        assert not any("#" in t.group or t.same_symbol for t in types), config
        assert len({t.incidence_symbol for t in types}) == len(types)
