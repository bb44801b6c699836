"""k-uniform tilings by regular polygons (§4.1): the D-symbol search against published counts,
with every found tiling checked by geometry that does not use the D-symbol.

Published figures: OEIS A068599 (k-uniform tilings: 11, 20, 61, 151, ... for k = 1, 2, 3, 4;
Galebach's enumeration), OEIS A068600 (those with k distinct vertex types: 11, 20, 39, 33,
...), and Chavey, "Tilings by regular polygons II", Comput. Math. Appl. 17 (1989), whose
list of the 20 2-uniform tilings gives the multisets of vertex types below (Grünbaum &
Shephard, *Tilings and Patterns* §2.2 draw the same 20).
"""

from __future__ import annotations

import itertools
import math
import random
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

from tilekit.errors import ParseError
from tilekit.geometry import Affine
from tilekit.plugins.kuniform.dsymbol import (
    DSymbol,
    Star,
    minimal_symbols,
    stars,
    symbols,
    vertex_types,
)
from tilekit.plugins.kuniform.search import (
    chunks,
    from_spec,
    linked,
    records_for,
    star_choices,
    star_rows,
    tiling_of,
    tilings_with_types,
    types_text,
)
from tilekit.regular.notation import VertexType
from tilekit.symmetry import congruence, congruent, vertex_orbits, wallpaper_group
from tilekit.tiling import PeriodicTiling

A068599 = [11, 20, 61, 151, 332, 673]
A068600 = [11, 20, 39, 33, 15, 10]

#: Chavey (1989): the 2-uniform tilings by their vertex-type multisets.
TWO_UNIFORM = Counter({
    "[3^6; 3^4.6]": 2, "[3^6; 3^3.4^2]": 2, "[3^6; 3^2.4.3.4]": 1, "[3^6; 3^2.4.12]": 1,
    "[3^6; 3^2.6^2]": 1, "[3^4.6; 3^2.6^2]": 1, "[3^3.4^2; 3^2.4.3.4]": 2, "[3^3.4^2; 3.4.6.4]": 1,
    "[3^3.4^2; 4^4]": 2, "[3^2.4.3.4; 3.4.6.4]": 1, "[3^2.6^2; 3.6.3.6]": 1, "[3.4.3.12; 3.12^2]": 1,
    "[3.4^2.6; 3.4.6.4]": 1, "[3.4^2.6; 3.6.3.6]": 2, "[3.4.6.4; 4.6.12]": 1,
})


def all_symbols(k: int) -> list[DSymbol]:
    out = []
    for types in itertools.combinations_with_replacement([t.polygons for t in vertex_types()], k):
        out += tilings_with_types(types)
    return out


# --------------------------------------------------------------------------- independent geometry


def vertex_types_by_geometry(tiling) -> list[tuple[int, ...]]:
    """The vertex type at each vertex of one translational unit, read from a patch: the
    polygons that have the point as a corner, in angular order round it."""
    verts = np.asarray(tiling_vertices(tiling))
    span = np.abs(tiling.v1) + np.abs(tiling.v2)
    lo = verts.min(axis=0) - span - 4
    hi = verts.max(axis=0) + span + 4
    patch = tiling.patch((lo[0], lo[1], hi[0], hi[1]))
    polys = patch.polygons()
    corners = np.concatenate(polys)
    owner = np.concatenate([[i] * len(p) for i, p in enumerate(polys)])
    out = []
    for v in verts:
        near = owner[np.hypot(*(corners - v).T) < 1e-6]
        angles = [math.atan2(*(polys[i].mean(axis=0) - v)[::-1]) for i in near]
        seq = tuple(len(polys[i]) for _, i in sorted(zip(angles, near)))
        out.append(VertexType.of(seq).polygons)
    return out


def tiling_vertices(tiling):
    from tilekit.symmetry import tiling_vertices as tv

    return tv(tiling)


def check_tiling(sym: DSymbol, k: int) -> tuple:
    """Validate a found tiling and recompute its vertex orbits from its symmetry group; return
    an invariant that congruent tilings share (group, vertex-type densities)."""
    tiling = tiling_of(sym)
    span = np.abs(tiling.v1) + np.abs(tiling.v2) + 3
    report = tiling.patch((-span[0], -span[1], span[0], span[1])).validate((-1, -1, 1, 1))
    assert report, report
    points, orbit = vertex_orbits(tiling)
    assert orbit.max() + 1 == k
    types = vertex_types_by_geometry(tiling)
    names = {t.polygons for t in vertex_types()}
    assert set(types) <= names
    per_orbit = sorted({(int(o), types[i]) for i, o in enumerate(orbit)})
    assert len(per_orbit) == k  # one type per orbit
    area = abs(tiling.v1[0] * tiling.v2[1] - tiling.v1[1] * tiling.v2[0])
    density = sorted((t, round(float(np.sum(orbit == o)) / area, 6)) for o, t in per_orbit)
    assert sorted(t for _o, t in per_orbit) == sorted(sym.vertex_type(o[0]) for o in sym.vertex_orbits())
    return wallpaper_group(tiling).iuc, tuple(density)


def distinct_up_to_congruence(syms: list[DSymbol], k: int) -> None:
    invariants = [check_tiling(s, k) for s in syms]
    for (i, a), (j, b) in itertools.combinations(enumerate(invariants), 2):
        if a == b:
            assert not congruent(tiling_of(syms[i]), tiling_of(syms[j])), (a, syms[i].encode(), syms[j].encode())


# --------------------------------------------------------------------------- tests


def test_one_uniform_recovers_the_archimedean_records():
    """k = 1: the 11 Archimedean tilings (§4.1, Figure 4.2), with the vertex types and the
    wallpaper groups of the archimedean family's records."""
    from tilekit.plugins.archimedean.records import catalogue_records

    syms = all_symbols(1)
    assert len(syms) == A068599[0]
    shipped = {r.properties["vertex_type"]: r.properties["wallpaper_group"]
               for r in catalogue_records() if r.family == "archimedean" and "wallpaper_group" in r.properties}
    assert len(shipped) == 11
    found = {}
    for sym in syms:
        (vt,) = {sym.vertex_type(o[0]) for o in sym.vertex_orbits()}
        found[str(VertexType(vt))] = check_tiling(sym, 1)[0]
    assert found == shipped


def test_two_uniform_are_chaveys_twenty():
    syms = all_symbols(2)
    assert len(syms) == A068599[1] == 20
    got = Counter(types_text([sym.vertex_type(o[0]) for o in sym.vertex_orbits()]) for sym in syms)
    assert got == TWO_UNIFORM
    distinct_up_to_congruence(syms, 2)


@pytest.mark.slow
def test_three_uniform_are_sixty_one():
    """k = 3: 61 tilings (A068599), 39 with three vertex types (A068600) and 22 with two."""
    syms = all_symbols(3)
    assert len(syms) == A068599[2]
    kinds = Counter(len({sym.vertex_type(o[0]) for o in sym.vertex_orbits()}) for sym in syms)
    assert kinds == {3: A068600[2], 2: A068599[2] - A068600[2]}
    distinct_up_to_congruence(syms, 3)


def raw_search(types) -> list:
    """The D-symbol search on a type multiset with none of the run's shortcuts."""
    out = []
    for combo in star_choices(types):
        out += symbols(combo).values()
    return out


def test_skipped_multisets_hold_no_k_uniform_tiling():
    """Runs skip multisets of one vertex type for k >= 2 (the eleven Archimedean tilings are the
    only tilings with one vertex type, §4.1) and multisets that are not linked by shared edge
    pairs (a D-symbol is connected); the plain search agrees on every such multiset for k = 2,
    and on the one-type multisets of the four types with most stabilizer classes for k = 3."""
    kinds = [t.polygons for t in vertex_types()]
    skipped = [c for c in itertools.combinations_with_replacement(kinds, 2) if len(set(c)) == 1 or not linked(c)]
    assert len(skipped) == math.comb(22, 2) - 40
    for types in skipped:
        assert raw_search(types) == [], types
    for seq in [(4, 4, 4, 4), (3, 3, 3, 3, 3, 3), (3, 3, 3, 4, 4), (3, 6, 3, 6)]:
        assert raw_search([seq] * 3) == []
    listed = list(chunks({"k": 2}))
    assert len(listed) == 40
    assert all(len(set(c["types"])) == 2 for c in listed)
    assert not linked([(3, 7, 42), (3, 3, 3, 3, 3, 3)]) and linked([(3, 3, 4, 12), (3, 12, 12)])


def test_canonical_form_ignores_labels():
    """A random relabelling of a D-symbol's chambers keeps its encoding (isomorphic symbols
    are one record), and decode(encode) is an isomorphic symbol."""
    rng = random.Random(5)
    for sym in all_symbols(2)[:6]:
        n = sym.size
        perm = list(range(n))
        rng.shuffle(perm)
        inv = [0] * n
        for i, p in enumerate(perm):
            inv[p] = i
        relabelled = DSymbol(*(tuple(perm[s[inv[x]]] for x in range(n)) for s in (sym.s0, sym.s1, sym.s2)),
                             tuple(sym.face[inv[x]] for x in range(n)), tuple(sym.degree[inv[x]] for x in range(n)))
        assert relabelled.encode() == sym.encode()
        assert DSymbol.decode(sym.encode()).encode() == sym.encode()


def test_a_symbol_of_a_subgroup_is_not_minimal():
    """The square tiling with a trivial vertex stabilizer is a symbol of 8 chambers of a
    subgroup; its minimal image is the 1-chamber symbol of *442."""
    star = Star((4, 4, 4, 4), len(__import__("tilekit.plugins.kuniform.dsymbol", fromlist=["x"])
                                   .stabilizer_classes((4, 4, 4, 4))) - 1)
    assert len(star.group) == 1
    from tilekit.plugins.kuniform.dsymbol import gluings

    found = list(gluings([star]))
    assert found and all(not s.is_minimal() and len(set(s.minimal_classes())) == 1 for s in found)
    assert symbols([star]) == {}


def test_records_name_the_orbit_types_and_group():
    recs = records_for([(3, 3, 3, 3, 3, 3), (3, 3, 3, 3, 6)])
    assert sorted(r.name for r in recs) == ["[3^6; 3^4.6] p6", "[3^6; 3^4.6] p6m"]
    for r in recs:
        assert r.properties["k"] == 2 and r.properties["vertex_types"] == 2
        assert r.properties["vertex_type"] == ["3^4.6", "3^6"]
        rebuilt = from_spec(r.spec)
        assert rebuilt.symbol.encode() == r.spec["dsymbol"]


@pytest.mark.parametrize("spec, needle", [
    ({}, "needs 'dsymbol'"),
    ({"dsymbol": "3/6/0"}, "5 '/'-separated lists"),
    ({"dsymbol": "3,3/6,6/0,0/1,0/1,0"}, "σ0 is not an involution"),
    ({"dsymbol": "3/6/0/0/x"}, "k-uniform spec"),
    ({"dsymbol": "3,3/6,6/0,1/0,1/0,1"}, "connected"),
    ({"dsymbol": "3/3/0/0/0"}, "curvature 1/6"),  # the tetrahedron: spherical
    ({"dsymbol": "/".join([",".join(["3"] * 100)] * 5)}, "at most 96 chambers"),
])
def test_bad_specs_are_refused(spec, needle):
    with pytest.raises(ParseError, match=needle):
        from_spec(spec)


def test_search_through_the_catalogue(catalogue_cli):
    """The run layer stores the 20 records; the catalogue answers by property."""
    r = catalogue_cli.run("search", "k-uniform", "--k", "2")
    assert r.exit_code == 0, r.output
    assert catalogue_cli.count("k-uniform") == 20
    assert catalogue_cli.count("k-uniform", "k=2", "vertex_types=2") == 20
    assert catalogue_cli.count("k-uniform", "wallpaper_group=p6m") == 8
    assert catalogue_cli.count("k-uniform", "vertex_type=3^6") == 7
    r = catalogue_cli.run("show", "[3^6; 3^4.6] p6")
    assert r.exit_code == 0 and "2-uniform" in r.output and "632" in r.output, r.output
    assert "20 3-gons, 1 6-gon" in r.output  # the unit: angles 20π + 4π = 12 vertices x 2π
    out = Path(catalogue_cli.url.removeprefix("sqlite:///")).with_name("p6.svg")
    r = catalogue_cli.run("render", "[3^6; 3^4.6] p6", "-o", str(out))
    assert r.exit_code == 0 and out.read_text().count("<path") >= 2, r.output


@pytest.mark.parametrize("value", ["0", "9", "two"])
def test_bad_k_is_refused(catalogue_cli, value):
    import subprocess
    import sys

    res = subprocess.run([sys.executable, "-m", "tilekit", "--catalogue", catalogue_cli.url, "search", "k-uniform",
                          "--k", value], capture_output=True, text=True)
    assert res.returncode == 2, res.stderr
    assert "k" in res.stderr and "Traceback" not in res.stderr and res.stderr.strip().count("\n") == 0, res.stderr


def test_stars_cover_the_21_vertex_types():
    assert len(vertex_types()) == 21
    assert {s.polygons for s in stars()} == {t.polygons for t in vertex_types()}


def run_symbols(max_k: int) -> list[DSymbol]:
    """Every tiling the run's chunks find for k = 1..max_k, one symbol per canonical form."""
    found: dict = {}
    for k in range(1, max_k + 1):
        for chunk in chunks({"k": k}):
            rows = star_rows([VertexType.parse(t).polygons for t in chunk["types"]])
            for _row, sym in minimal_symbols(rows):
                found.setdefault(sym.canonical_form(), sym)
    return list(found.values())


def tile_densities(tiling) -> tuple:
    """Tiles of each size per unit area: congruent tilings have the same."""
    area = abs(tiling.v1[0] * tiling.v2[1] - tiling.v1[1] * tiling.v2[0])
    sizes = np.array([len(tiling.prototiles[int(p)].outline) for p in tiling.unit_prototile])
    return tuple((int(n), round(float(np.sum(sizes == n)) / area, 6)) for n in np.unique(sizes))


def moved(tiling, g: np.ndarray) -> PeriodicTiling:
    """The tiling carried by the isometry g (3, 3): its unit and its lattice vectors."""
    lin = g[:2, :2]
    return PeriodicTiling(tiling.prototiles, tiling.unit_prototile, g @ tiling.unit_transform,
                          lin @ tiling.v1, lin @ tiling.v2, tiling.colouring)


def test_no_two_tilings_to_k4_are_congruent():
    """All 243 tilings with k <= 4 (11 + 20 + 61 + 151, A068599), every pair: a pair whose
    tiles of each size per unit area differ is not congruent; each of the 408 pairs that agree
    goes to the isometry search of tilekit.symmetry.congruence (geometry only, not the
    D-symbol), both ways, and none is congruent. The search can say yes: every third tiling,
    turned, mirrored and shifted by a random isometry, is congruent to itself, by a map that
    carries one onto the other."""
    syms = run_symbols(4)
    assert len(syms) == sum(A068599[:4])
    tilings = [tiling_of(s) for s in syms]
    classes: dict = {}
    for i, t in enumerate(tilings):
        classes.setdefault(tile_densities(t), []).append(i)
    pairs = [p for group in classes.values() for p in itertools.combinations(group, 2)]
    assert len(pairs) == 408
    for i, j in pairs:
        assert congruence(tilings[i], tilings[j]) is None and congruence(tilings[j], tilings[i]) is None, (
            syms[i].encode(), syms[j].encode())
    rng = np.random.default_rng(31)
    for t in tilings[::3]:
        g = Affine.translation(*rng.uniform(-5, 5, 2)) @ Affine.rotation(rng.uniform(0, 2 * math.pi))
        if rng.random() < 0.5:
            g = g @ np.diag([1.0, -1.0, 1.0])
        h = congruence(t, moved(t, g))
        assert h is not None
        # h maps t onto its copy, so g^-1 h maps t onto itself: each unit tile's centre
        # lands on the centre of a tile of the same size, modulo the lattice
        polys = t.unit().polygons()
        centre = np.array([p.mean(axis=0) for p in polys])
        size = np.array([len(p) for p in polys])
        image = Affine.apply(np.linalg.inv(g) @ h, centre)
        f = (image[:, None, :] - centre[None, :, :]) @ np.linalg.inv(np.column_stack([t.v1, t.v2])).T
        hit = (np.abs(f - np.rint(f)).max(axis=2) < 1e-6) & (size[:, None] == size[None, :])
        assert hit.any(axis=1).all()


def test_the_congruence_check_sees_moved_copies_and_tells_near_twins_apart():
    """The test's congruence check (used when two found tilings share their invariants):
    a tiling laid out from another base chamber (so moved, turned or mirrored) is congruent
    to itself; the two [3^6; 3^4.6] tilings (p6 and p6m, same vertex types) are not."""
    p6, p6m = tilings_with_types([(3, 3, 3, 3, 3, 3), (3, 3, 3, 3, 6)])
    for sym in (p6, p6m):
        n = sym.size
        perm = [(i + 3) % n for i in range(n)]  # chamber 0 becomes another chamber
        inv = [perm.index(i) for i in range(n)]
        moved = DSymbol(*(tuple(perm[s[inv[x]]] for x in range(n)) for s in (sym.s0, sym.s1, sym.s2)),
                        tuple(sym.face[inv[x]] for x in range(n)), tuple(sym.degree[inv[x]] for x in range(n)))
        a, b = tiling_of(sym), tiling_of(moved)
        assert not np.allclose(a.unit_transform[0], b.unit_transform[0]) or not np.allclose(a.v1, b.v1)
        assert congruent(a, b)
    assert not congruent(tiling_of(p6), tiling_of(p6m))
    assert not congruent(tiling_of(p6m), tiling_of(p6))


#: The catalogue's split by number of vertex types (tes-catalog folders; FACTS.md), m = 2..k.
SPLITS = {4: [33, 85, 33], 5: [74, 149, 94, 15]}


# 196 s CPU in all (2026-12-03, workers included; 9.5 min wall at load 7 under nice), so about
# 100 s on two idle cores since the notation writer is bounded (it took tens of minutes before)
@pytest.mark.slow
def test_five_uniform_through_the_run_layer(tmp_path):
    """k = 5 with two worker processes: 332 tilings (A068599), split 74 / 149 / 94 / 15 by the
    number of vertex types (the last is A068600), each stored once with k = 5."""
    from tilekit.catalogue import open_catalogue
    from tilekit.search import run_search

    cat = open_catalogue(f"sqlite:///{tmp_path / 'k5.sqlite'}")
    run = run_search(cat, "k-uniform", {"k": 5}, executor="process", workers=2)
    summary = cat.run(run).summary
    records = list(cat.query(family="k-uniform"))
    cat.close()
    assert summary["found"] == summary["tilings"] == A068599[4]
    assert [summary[f"with_{m}_types"] for m in range(2, 6)] == SPLITS[5]
    assert len({r.name for r in records}) == A068599[4] and all(r.properties["k"] == 5 for r in records)


@pytest.mark.slow
def test_four_uniform_through_the_run_layer(tmp_path):
    """k = 4 with two worker processes: 151 tilings (A068599), 33 with four vertex types
    (A068600), each stored as a record whose orbit types are among the 21 and whose k is 4."""
    from tilekit.catalogue import open_catalogue
    from tilekit.search import run_search

    cat = open_catalogue(f"sqlite:///{tmp_path / 'k4.sqlite'}")
    run = run_search(cat, "k-uniform", {"k": 4}, executor="process", workers=2)
    summary = cat.run(run).summary
    assert summary["found"] == summary["tilings"] == A068599[3]
    assert summary["with_4_types"] == A068600[3]
    assert sum(summary[f"with_{m}_types"] for m in (2, 3, 4)) == A068599[3]
    names = {str(t) for t in vertex_types()}
    records = list(cat.query(family="k-uniform"))
    cat.close()
    assert len(records) == A068599[3] and len({r.name for r in records}) == A068599[3]
    for r in records:
        listed = r.properties["vertex_type"]
        assert r.properties["k"] == 4 and set(listed if isinstance(listed, list) else [listed]) <= names
