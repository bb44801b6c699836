"""The polyomino classification: Heesch numbers by SAT, anisohedral tilings on tori, the search.

Published figures (offset 1, from n = 1):

- OEIS A054359 (tile the plane), A054360 (do not tile), A054361 (hole-free non-tilers) and
  A075206 (anisohedral: tile, but not isohedrally) — Myers' data; FACTS.md for n = 7..10.
- Heesch numbers: C. S. Kaplan, "Heesch numbers of unmarked polyforms", Contributions to
  Discrete Mathematics 17(2), 2022 (arXiv:2105.09438), Table 1 (hole-free Hc) and Table 2
  (holes allowed in the outer corona, Hh) for the hole-free non-tiling n-ominoes.

Every witness is checked here by an independent checker written on shapely polygons (not on
the cells and placements the search uses), and every anisohedral tiling's number of
transitivity classes is recomputed from its symmetry group by ``tilekit.symmetry``.
"""

from __future__ import annotations

import json
from collections import Counter

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

import tilekit
from tilekit import symmetry
from tilekit.errors import ParameterError
from tilekit.lattice import SQUARE, enumerate_free
from tilekit.plugins.polyomino.classify import classify, corona_patch, torus_tiling
from tilekit.plugins.polyomino.heesch import heesch
from tilekit.plugins.polyomino.isohedral import analyse

A054359 = [1, 1, 2, 5, 12, 35, 104, 343, 1050, 3070]
A054360 = [0, 0, 0, 0, 0, 0, 4, 26, 235, 1585]
A054361 = [0, 0, 0, 0, 0, 0, 3, 20, 198, 1390]
A075206 = [0, 0, 0, 0, 0, 0, 0, 1, 9, 44]
# Kaplan 2022, Table 1 (Hc) and Table 2 (Hh): counts of hole-free non-tilers by Heesch number
KAPLAN_HC = {7: {0: 1, 1: 2}, 8: {0: 6, 1: 14}, 9: {0: 75, 1: 122, 2: 1}, 10: {0: 747, 1: 642, 2: 1}}
KAPLAN_HH = {7: {1: 3}, 8: {1: 19, 2: 1}, 9: {0: 36, 1: 157, 2: 5}, 10: {0: 355, 1: 1020, 2: 15}}


# --------------------------------------------------------------------------- independent checks

def check_coronas(patch, levels: np.ndarray, hole_free: bool) -> None:
    """Kaplan's definition, on polygons: corona i touches corona i-1 and nothing below it, the
    patch of coronas < i lies in the interior of the patch of coronas <= i, and (hole-free)
    the whole patch has no hole; with holes allowed, any hole is bounded by the outermost
    corona alone."""
    assert patch.validate().ok, patch.validate().summary()
    geoms = np.asarray(patch.geometries())
    k = int(levels.max())
    assert (levels == 0).sum() == 1
    unions = [shapely.union_all(geoms[levels <= i]) for i in range(k + 1)]
    for i in range(1, k + 1):
        inner = unions[i - 1]
        grown = inner.buffer(0.1, join_style="mitre")
        assert shapely.difference(grown, unions[i]).area < 1e-9, f"corona {i} does not surround the patch inside it"
        for g in geoms[levels == i]:
            assert g.intersects(unions[i - 1]), f"a tile of corona {i} does not touch corona {i - 1}"
            if i >= 2:
                assert g.distance(unions[i - 2]) > 0.5, f"a tile of corona {i} touches corona {i - 2}"
    outer = unions[k]
    assert isinstance(outer, shapely.Polygon)
    assert bool(outer.interiors) is (not hole_free)
    inner = shapely.union_all(geoms[levels < k])
    for ring in outer.interiors:
        assert shapely.Polygon(ring).distance(inner) > 0.5, "a hole touches an inner corona"


def check_anisohedral(tiling, k: int) -> None:
    """The tiling is exact, and its symmetry group (tilekit.symmetry, from the geometry) has k
    orbits on tiles — k > 1: the tile is not isohedral in this tiling."""
    region = shapely.box(-12, -12, 12, 12)
    patch = tiling.patch(region)
    report = patch.validate(region)
    assert report.ok, report.summary()
    assert symmetry.isohedrality(tiling) == k
    assert k >= 2


def _cells(text: str) -> np.ndarray:
    v = np.array(list(map(int, text.split()))).reshape(-1, 2)
    return 2 * v + 1


# --------------------------------------------------------------------------- coronas

@pytest.mark.parametrize("cells, hc, hh", [
    # the three hole-free non-tiling heptominoes with their (Hc, Hh) from Kaplan's 2022 dataset
    ("1 0 1 1 0 2 1 2 1 3 2 3 3 3", 1, 1),
    ("0 0 4 0 0 1 1 1 2 1 3 1 4 1", 1, 1),
    ("2 0 2 1 0 2 1 2 2 2 3 2 2 3", 0, 1),
])
def test_heptomino_heesch_numbers_and_witnesses(cells, hc, hh):
    c = _cells(cells)
    r = heesch(SQUARE, c, max_level=4)
    assert r.decided and (r.hc, r.hh) == (hc, hh)
    for part, free in ((r.hc_witness, True), (r.hh_witness, hh == hc)):
        patch = corona_patch(SQUARE, c, part.to_json())
        check_coronas(patch, patch.aspect, free)
        assert part.k == (hc if free else hh)


def test_every_octomino_decided_and_counts_match_the_published_figures():
    """n <= 8: every polyomino decided; A054359/A054360/A054361/A075206; Kaplan's Tables 1-2."""
    polys, flags, _ = enumerate_free(SQUARE, 8, with_holes=True)
    tally: Counter = Counter()
    for cells, holey in zip(polys, flags):
        n = len(cells)
        a = None if holey else analyse(SQUARE, cells, construct=False)
        c = classify(SQUARE, cells, a, has_holes=bool(holey))
        assert c.tiles in ("true", "false"), c.verdict
        tally["tiles", n] += c.tiles == "true"
        tally["not", n] += c.tiles == "false"
        tally["not_holefree", n] += c.tiles == "false" and not holey
        tally["aniso", n] += c.tiles == "true" and not c.isohedral
        if c.tiles == "false" and not holey:
            tally["hc", n, c.heesch] += 1
            tally["hh", n, c.heesch_holes] += 1
            w = c.witness
            for part, free in ((w["hc"], True), (w["hh"], not w["hh"]["holes"])):
                patch = corona_patch(SQUARE, cells, part)
                check_coronas(patch, patch.aspect, free)
        if c.tiles == "true" and not c.isohedral:
            check_anisohedral(torus_tiling(SQUARE, cells, c.witness), c.anisohedral_k)
    for n in range(1, 9):
        assert tally["tiles", n] == A054359[n - 1]
        assert tally["not", n] == A054360[n - 1]
        assert tally["not_holefree", n] == A054361[n - 1]
        assert tally["aniso", n] == A075206[n - 1]
    for n in (7, 8):
        assert {h: tally["hc", n, h] for h in range(4) if tally["hc", n, h]} == KAPLAN_HC[n]
        assert {h: tally["hh", n, h] for h in range(4) if tally["hh", n, h]} == KAPLAN_HH[n]


@pytest.mark.slow
def test_the_11_omino_whose_tilings_need_12_tiles_per_unit():
    """One of Myers' 108 anisohedral 11-ominoes (A075206(11) = 108) has no torus tiling with 8
    or fewer tiles per translational unit; the default bound (12) finds it, and its tiling is
    checked from the geometry: exact, and 3-isohedral by its own symmetry group."""
    poly = tilekit.polyomino("..x../..xxx/xxxx./xx.x.")
    assert not poly.is_isohedral()
    a = analyse(SQUARE, poly.cells, construct=False)
    assert classify(SQUARE, poly.cells, a, torus_tiles=8).tiles == "undecided"
    c = classify(SQUARE, poly.cells, a, time_limit=600)
    assert c.tiles == "true" and c.anisohedral_k == 3 and "12 tiles per translational unit" in c.verdict
    check_anisohedral(torus_tiling(SQUARE, poly.cells, c.witness), 3)


def test_the_anisohedral_octomino():
    """Exercise 5.4: the smallest anisohedral polyomino has 8 cells, and there is one (A075206).
    Its tiling found on a torus is exact and 2-isohedral by its own symmetry group."""
    polys, flags, _ = enumerate_free(SQUARE, 8, with_holes=True)
    found = []
    for cells, holey in zip(polys, flags):
        if holey or len(cells) != 8 or analyse(SQUARE, cells, construct=False)["isohedral"]:
            continue
        c = classify(SQUARE, cells, analyse(SQUARE, cells, construct=False))
        if c.tiles == "true":
            found.append((cells, c))
    assert len(found) == 1
    cells, c = found[0]
    assert c.anisohedral_k == 2 and "transitivity classes" in c.verdict
    til = torus_tiling(SQUARE, cells, c.witness)
    check_anisohedral(til, 2)
    # the same through the public API
    poly = tilekit.polyomino(((cells - 1) // 2).tolist())
    assert not poly.is_isohedral()
    shown = poly.classification()
    assert shown.tiles == "true" and shown.anisohedral_k == 2
    view = tilekit.polyomino(poly.code).classification()
    assert view.witness == shown.witness


def test_a_time_limit_after_a_tiling_is_found_keeps_the_tiling(monkeypatch):
    """The torus search goes on past a tiling with k > 2 classes to look for fewer; when the
    time limit ends that search, the tiling found stands (an anisohedral 12-omino of the n = 12
    run had come out 'undecided' so). The nonomino below first tiles with 8 tiles per unit and
    4 classes (p2); the search is made to time out right after."""
    from tilekit.plugins.polyomino import torus

    real = torus.TorusSearch.search

    def cut_after_first(self, m_range, **kw):
        for m, tt in real(self, m_range, **kw):
            yield m, tt
            if tt is not None:
                yield m + 1, None
                return

    monkeypatch.setattr(torus.TorusSearch, "search", cut_after_first)
    poly = tilekit.polyomino("....xx/xxx.x./..xxx.")
    c = classify(SQUARE, poly.cells, analyse(SQUARE, poly.cells, construct=False))
    assert c.tiles == "true" and c.anisohedral_k == 4
    assert "stopped by the time limit (120 CPU seconds) at 9 tiles per unit" in c.verdict
    check_anisohedral(torus_tiling(SQUARE, poly.cells, c.witness), 4)


def test_holes_and_bounds():
    holey = tilekit.polyomino("xxx/x.x/xxx")
    c = holey.classification()
    assert c.tiles == "false" and c.heesch is None and "hole" in c.verdict
    with pytest.raises(ParameterError, match="torus-tiles"):
        classify(SQUARE, holey.cells, None, torus_tiles=1)
    with pytest.raises(ParameterError, match="max-level"):
        classify(SQUARE, holey.cells, None, probe=3, max_level=2)


def test_undecided_is_reported_with_its_bounds():
    """An anisohedral tile with too small a torus bound is not guessed to be a non-tiler."""
    octo = "0 0 1 0 0 1 -1 1 -1 2 -1 3 -1 4 -2 3"
    cells = _cells(octo)
    a = analyse(SQUARE, cells, construct=False)
    assert not a["isohedral"]
    c = classify(SQUARE, cells, a, probe=2, max_level=3, torus_tiles=2)
    assert c.tiles == "undecided"
    assert c.verdict.startswith("undecided up to 3 coronas and 2 tiles per translational unit")


def test_a_corona_formula_over_the_limits_is_refused_before_it_is_built(monkeypatch):
    """The SAT encoding is estimated before it is allocated; over the limit, the polyomino is
    undecided with the limit named (never an allocation the machine cannot hold)."""
    from tilekit import limits

    monkeypatch.setattr(limits, "MAX_SAT_VARIABLES", 5000)
    c = classify(SQUARE, _cells("1 0 1 1 0 2 1 2 1 3 2 3 3 3"), None)  # Hc = 1: level 2 is refused
    assert c.tiles == "undecided"
    assert c.verdict.startswith("undecided up to 1 coronas") and "SAT variables for 2 coronas" in c.verdict
    assert "over the limit of 5,000" in c.verdict or "over the limit of 5000" in c.verdict


# --------------------------------------------------------------------------- the search

def test_classification_search_list_show_render(catalogue_cli, tmp_path):
    run = catalogue_cli.run

    res = run("search", "polyomino-classify", "--max-cells", "8", "--executor", "process", "--workers", "2")
    assert res.exit_code == 0, res.output

    def count(*where):
        return catalogue_cli.count("polyomino", *where)

    assert count("tiles=false") == sum(A054360[:8])
    assert count("tiles=false", "holes=false") == sum(A054361[:8])
    assert count("tiles=true") == sum(A054359[:8])
    assert count("anisohedral_k=2") == 1
    assert count("heesch>=1") == 2 + 14  # Kaplan 2022, Table 1: Hc = 1 for 2 heptominoes, 14 octominoes
    assert count("tiles=undecided") == 0
    # the enumeration run again keeps the classification (only its own columns are written)
    res = run("search", "polyominoes", "--max-cells", "8")
    assert res.exit_code == 0, res.output
    assert count("tiles=false") == sum(A054360[:8]) and count("anisohedral_k=2") == 1
    # show prints the verdict with how it was reached; render draws the witnesses
    r = run("list", "--family", "polyomino", "--where", "anisohedral_k=2", "--format", "json")
    assert r.exit_code == 0, r.output
    code = json.loads(r.output)[0]["code"]
    res = run("show", code)
    assert res.exit_code == 0 and "tiles anisohedrally" in res.output and "transitivity classes" in res.output
    out = tmp_path / "aniso.svg"
    res = run("render", code, "-o", str(out))
    assert res.exit_code == 0, res.output
    assert out.read_text().startswith("<")
    r = run("list", "--family", "polyomino", "--where", "heesch_holes=2", "--format", "json")
    code = json.loads(r.output)[0]["code"]
    res = run("show", code)
    assert res.exit_code == 0 and "Heesch number 1" in res.output
    res = run("render", code, "-o", str(out))
    assert res.exit_code == 0, res.output
    res = run("render", code, "--set", "view=holes", "-o", str(out))
    assert res.exit_code == 0, res.output
    res = run("render", code, "--set", "view=tiling", "-o", str(out))
    assert res.exit_code == 2 and "does not tile" in res.stderr


def test_classification_search_bad_input(tmp_path):
    from tilekit.cli import cli

    db = f"sqlite:///{tmp_path / 'c.sqlite'}"
    for args, needle in ((["--max-cells", "15"], "max_cells"), (["--torus-tiles", "1"], "torus_tiles"),
                         (["--max-level", "1", "--probe", "2"], "max-level"), (["--solver", "nope"], "solver")):
        res = CliRunner().invoke(cli, ["--catalogue", db, "search", "polyomino-classify", *args])
        assert res.exit_code == 2, res.output
        assert needle in res.stderr and res.stderr.strip().count("\n") == 0, res.stderr


@pytest.mark.slow
def test_classification_to_ten_cells_against_myers_and_kaplan(tmp_path):
    """n = 9, 10 through the run layer with two worker processes: every polyomino decided, the
    OEIS counts and Kaplan's Tables 1-2, and every stored witness checked independently."""
    from tilekit.catalogue import open_catalogue
    from tilekit.plugins.polyomino.tables import TABLE
    from tilekit.search import run_search

    cat = open_catalogue(f"sqlite:///{tmp_path / 'c10.sqlite'}")
    run = run_search(cat, "polyomino-classify", {"max_cells": 10, "min_cells": 9}, executor="process", workers=2)
    s = cat.run(run).summary
    for n in (9, 10):
        assert s.get(f"undecided_{n}", 0) == 0
        assert s[f"tiles_{n}"] == A054359[n - 1]
        assert s[f"nontilers_{n}"] == A054360[n - 1]
        assert s[f"holefree_nontilers_{n}"] == A054361[n - 1]
        assert s[f"anisohedral_{n}"] == A075206[n - 1]
        assert {h: s[f"hc_{n}_{h}"] for h in range(4) if s.get(f"hc_{n}_{h}")} == KAPLAN_HC[n]
        assert {h: s[f"hh_{n}_{h}"] for h in range(4) if s.get(f"hh_{n}_{h}")} == KAPLAN_HH[n]
    with cat.engine.connect() as conn:
        rows = conn.execute(TABLE.select().where(TABLE.c.witness.is_not(None))).mappings().all()
    cat.close()
    seen = Counter()
    for row in rows:
        poly = tilekit.polyomino(row["code"])
        w = json.loads(row["witness"])
        if w["kind"] == "torus":
            check_anisohedral(torus_tiling(SQUARE, poly.cells, w), row["anisohedral_k"])
            seen["torus"] += 1
        else:
            for part, free in ((w["hc"], True), (w["hh"], not w["hh"]["holes"])):
                patch = corona_patch(SQUARE, poly.cells, part)
                check_coronas(patch, patch.aspect, free)
            seen["coronas"] += 1
    assert seen["torus"] == A075206[8] + A075206[9]
    assert seen["coronas"] == A054361[8] + A054361[9]
