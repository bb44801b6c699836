"""The polyomino family: the isohedral test, its tilings, the search's chunks and rows, the plugin.

The isohedral test follows S. Langerman and A. Winslow, "A quasilinear-time algorithm for
tiling the plane isohedrally with a polyomino", SoCG 2016 (arXiv:1507.02762). Published
counts: Joseph Myers' polyomino tiling data (http://www.polyomino.org.uk/mathematics/polyform-tiling/)
as in the OEIS (offset 1), terms read from the OEIS's own data files (github.com/oeis/oeisdata,
seq/A075/A075198.seq ... A075205.seq):

- A075198 tile by translation; A075202 tile by 180-degree rotation (Conway criterion),
  translations allowed too (its a(5) = 12 counts every pentomino);
- A075199 by translation but not by half-turn; A075200 by both; A075201 by half-turn but not
  by translation; A075203 by either (so A075202 = A075200 + A075201 and A075203 = A075198 +
  A075201, which the tests check as well);
- A075204 isohedral but neither by translation nor by half-turn; A075205 isohedral.

"Tile by translation" there means any tiling by translates, which for a polyomino exists iff
it has a lattice tiling (Beauquier-Nivat), i.e. iff the translation factorisation exists;
"by 180-degree rotation" means Conway's criterion, the half-turn factorisation. So each
sequence compares like with like with one flag of the analysis. The MathWorld misindexing of
A075201 is noted in FACTS.md.
"""

from __future__ import annotations

import functools
import json
from collections import Counter
from math import gcd

import numpy as np
import pytest

import tilekit
from tilekit.errors import GeometryError, NotFoundError, ParameterError, ParseError
from tilekit.lattice import SQUARE, boundary_word, encode, enumerate_free
from tilekit.plugins.polyomino import search as psearch
from tilekit.plugins.polyomino.isohedral import (
    analyse,
    analyse_many,
    build,
    factorisations,
    ih_groups,
)

# Myers' counts from n = 1 to 12 (the OEIS data files named above)
A075198 = [1, 1, 2, 5, 9, 24, 41, 121, 213, 522, 783, 2712]          # by translation
A075199 = [0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 10, 135]                    # translation, not half-turn
A075200 = [1, 1, 2, 5, 9, 24, 41, 121, 212, 520, 773, 2577]          # translation and half-turn
A075201 = [0, 0, 0, 0, 3, 11, 60, 199, 748, 2181, 5391, 17193]       # half-turn, not translation
A075202 = [1, 1, 2, 5, 12, 35, 101, 320, 960, 2701, 6164, 19770]     # by half-turn (Conway)
A075203 = [1, 1, 2, 5, 12, 35, 101, 320, 961, 2703, 6174, 19905]     # translation or half-turn
A075204 = [0, 0, 0, 0, 0, 0, 3, 22, 80, 323, 338, 3322]              # isohedral, neither
A075205 = [1, 1, 2, 5, 12, 35, 104, 342, 1041, 3026, 6512, 23227]    # isohedral
MYERS = {"tr": A075198, "tr_not_ht": A075199, "both": A075200, "ht_not_tr": A075201, "ht": A075202,
         "either": A075203, "other": A075204, "iso": A075205}


@pytest.fixture(scope="module")
def upto10():
    polys, flags, _ = enumerate_free(SQUARE, 10, with_holes=True)
    out = []
    for p, h in zip(polys, flags):
        out.append((p, bool(h), None if h else analyse(SQUARE, p, construct=False)))
    return out


def _tally(items):
    c = Counter()
    for p, h, a in items:
        n = len(p)
        if h:
            continue
        tr, ht = a["translation"], a["halfturn"]
        c["iso", n] += a["isohedral"]
        c["tr", n] += tr
        c["ht", n] += ht
        c["both", n] += tr and ht
        c["either", n] += tr or ht
        c["tr_not_ht", n] += tr and not ht
        c["ht_not_tr", n] += ht and not tr
        c["other", n] += a["isohedral"] and not tr and not ht
    return c


def test_myers_sequences_are_consistent():
    """The published terms themselves: the both/either/not splits add up."""
    for n in range(12):
        assert A075202[n] == A075200[n] + A075201[n]
        assert A075198[n] == A075200[n] + A075199[n]
        assert A075203[n] == A075198[n] + A075201[n]
        assert A075205[n] == A075203[n] + A075204[n]


def test_isohedral_counts_against_myers_data(upto10):
    """n <= 10 against A075198-A075205 (n = 11, 12: the slow test below)."""
    c = _tally(upto10)
    for key, seq in MYERS.items():
        assert [c[key, n] for n in range(1, 11)] == seq[:10], key


@pytest.mark.slow
def test_isohedral_counts_against_myers_data_11_and_12():
    """n = 11 and 12 (63,600 free 12-ominoes) through the bulk path the search uses."""
    polys, flags, _ = enumerate_free(SQUARE, 12, maxsize=12, with_holes=True)
    big = [p for p, h in zip(polys, flags) if not h and len(p) >= 11]
    c = _tally([(p, False, a) for p, a in zip(big, analyse_many(SQUARE, big))])
    for key, seq in MYERS.items():
        assert [c[key, 11], c[key, 12]] == seq[10:12], key


def test_bulk_analysis_equals_one_by_one(upto10):
    """analyse_many (one compiled call for a chunk) gives exactly analyse(construct=False)."""
    items = [(p, a) for p, h, a in upto10 if not h and len(p) <= 9]
    bulk = analyse_many(SQUARE, [p for p, _ in items])
    for (_, a), b in zip(items, bulk):
        assert {k: v for k, v in a.items() if k != "boundary"} == {k: v for k, v in b.items() if k != "boundary"}
        assert a["boundary"].tolist() == b["boundary"].tolist()


# --------------------------------------------------------------------------- independent oracle

def _hnf_lattices(area: int):
    for a in range(1, area + 1):
        if area % a == 0:
            d = area // a
            for b in range(d):
                yield a, b, d


def _reduce(pts: np.ndarray, a: int, b: int, d: int) -> np.ndarray:
    """Index in [0, a*d) of integer points modulo the lattice with rows (a, b), (0, d)."""
    q = np.floor_divide(pts[..., 0], a)
    return (pts[..., 0] - q * a) * d + np.mod(pts[..., 1] - q * b, d)


# the eight symmetries of the square grid, as matrices acting on cell pairs (x, y)
_ORIENT = [np.array(m) for m in ([[1, 0], [0, 1]], [[0, -1], [1, 0]], [[-1, 0], [0, -1]], [[0, 1], [-1, 0]],
                                  [[1, 0], [0, -1]], [[0, 1], [1, 0]], [[-1, 0], [0, 1]], [[0, -1], [-1, 0]])]
I_, R90, R180, R270, SX, SD, SY, SA = range(8)
#: the orientation sets of the translational units the oracle looks for
UNIT_SETS = {
    "T": [(I_,)],                                   # one tile per unit: a lattice tiling
    "C": [(I_, R180)],                              # the tile and its half-turn
    "G": [(I_, SX), (I_, SY), (I_, SD), (I_, SA)],  # the tile and one mirror image
    "C4": [(I_, R90, R180, R270)],                  # the four quarter-turns
    "CG": [(I_, R180, SX, SY), (I_, R180, SD, SA)],  # half-turn and two perpendicular mirrors
}


def torus_tiles(pairs: np.ndarray, orients: tuple[int, ...]) -> bool:
    """Exact cover on tori, by SAT through the shared layer (``tilekit.sat``): a periodic
    tiling whose translational unit is one copy of the tile in each orientation of
    ``orients`` (as point sets: a symmetric tile's copies may coincide in shape, which is
    allowed)?

    Every lattice of index len(orients)*n (Hermite normal form rows (a, b), (0, d)); the
    identity copy at offset 0 (translating the tiling); one variable per offset of each
    further orientation's copy; exactly one copy per orientation, exactly one copy on every
    torus cell the identity copy leaves free (none can lie on its cells). A tiling exists iff
    some lattice's formula is satisfiable. Written from the cells only, independently of the
    boundary words and of tilekit's torus search (``polyomino.torus``).
    """
    from tilekit.sat import CNF, solve

    n = len(pairs)
    area = len(orients) * n
    for a, b, d in _hnf_lattices(area):
        base = set(_reduce(pairs, a, b, d).tolist())
        if len(base) != n:
            continue
        offs = np.array([(tx, ty) for tx in range(a) for ty in range(d)], dtype=np.int64)
        cnf = CNF()
        on_cell: list[list[int]] = [[] for _ in range(area)]
        for g in orients[1:]:
            copies = []
            for row in _reduce((pairs @ _ORIENT[g].T)[None, :, :] + offs[:, None, :], a, b, d).tolist():
                if len(set(row)) == n and base.isdisjoint(row):
                    v = cnf.new_var()
                    copies.append(v)
                    for c in row:
                        on_cell[c].append(v)
            if not copies:
                break
            cnf.exactly(copies, 1)
        else:
            free = [lits for c, lits in enumerate(on_cell) if c not in base]
            if all(free):
                for lits in free:
                    cnf.exactly(lits, 1)
                if solve(cnf).satisfiable:
                    return True
    return False


def _has_unit(pairs: np.ndarray, cache: dict[str, bool], kind: str) -> bool:
    if kind not in cache:
        cache[kind] = any(torus_tiles(pairs, o) for o in UNIT_SETS[kind])
    return cache[kind]


def _unit_kind(f: dict) -> str:
    """The orientation set of the translational unit of a factorisation's tiling (see below)."""
    h = f["heesch"]
    if "C4" in h:
        return "C4"
    if "G" in h:
        perpendicular = f["template"] == "halfturn-reflection-2" and "G2" in h
        return "CG" if "C" in h.replace("C4", "") or perpendicular else "G"
    return "C" if "C" in h else "T"


@pytest.mark.slow
def test_verdicts_agree_with_torus_search_up_to_8(upto10):
    """Every verdict for n <= 8 against exhaustive exact cover on tori (cells only, by SAT).

    What is provable, and asserted for every hole-free polyomino of at most 8 cells:

    - translation <=> a torus tiling with one tile per unit (a lattice tiling). Beauquier-Nivat:
      a polyomino tiles by translations iff it has a lattice tiling, iff its word has a
      translation factorisation.
    - half-turn <=> a torus tiling whose unit is the tile and its half-turn. (=>) the tiling
      built from Conway's criterion has the translations and half-turns as its group, point
      group {I, R180}: two tiles per unit (one, when the tile is itself centrosymmetric; then
      an index-2 sublattice gives two). (<=) for a unit {T, t - T}, x -> t - x swaps T and
      t - T and normalises the lattice, so the tiling is isohedral with every neighbour of T
      an image under a translation or a half-turn, at least one a half-turn (the translates of
      T alone cannot fill the plane); by Langerman and Winslow's characterisation its boundary
      then has the half-turn factorisation.
    - every other factorisation found => a torus tiling whose unit is one tile per element of
      the point group its letters generate: a glide pair alone (parallel axes) {I, s}; with a
      half-turn, or two glides with perpendicular axes, {I, R180, s, R180 s}; a quarter-turn,
      {I, R90, R180, R270}. Same argument: the built tiling's group acts transitively, so its
      tiles modulo the translations are the point group's images of T (a sublattice makes up
      for a tile's own symmetry). The converse fails for these (copies in a 2- or 4-tile unit
      need not be related by a symmetry of the tiling), so it is not asserted.
    - not isohedral => no unit of any of these kinds, except for anisohedral tilers: Myers'
      A075206 counts none up to 7 cells and one octomino, so at most one octomino may have one.
    """
    exceptions = []
    checked = 0
    for p, h, a in upto10:
        if h or len(p) > 8:
            continue
        pairs = (p - 1) // 2
        code = encode(SQUARE, p)
        cache: dict[str, bool] = {}
        has = functools.partial(_has_unit, pairs, cache)
        assert a["translation"] == has("T"), code
        assert a["halfturn"] == has("C"), code
        for f in a["factorisations"]:
            assert has(_unit_kind(f)), (code, f)
        if not a["isohedral"] and any(has(k) for k in ("G", "C4", "CG")):
            exceptions.append(code)
        checked += 1
    assert checked == 1 + 1 + 2 + 5 + 12 + 35 + 107 + 363
    assert len(exceptions) <= 1 and all(code.count("x") == 8 for code in exceptions), exceptions


def test_every_match_up_to_8_builds_an_exact_tiling(upto10):
    """Langerman-Winslow: each factorisation of each template yields a tiling (checked exactly)."""
    for p, h, _ in upto10:
        if h or len(p) > 8:
            continue
        verts, letters = boundary_word(SQUARE, p)
        for f in factorisations(SQUARE, letters):
            assert build(SQUARE, p, verts, f) is not None, (encode(SQUARE, p), f)


def test_tilings_validate_and_wallpaper_groups_match_ih_types():
    from tilekit.symmetry import wallpaper_group

    groups = ih_groups()
    checked = 0
    for name in ("pentomino-F", "pentomino-N", "pentomino-P", "pentomino-Y", "L-tetromino", "pentomino-W"):
        poly = tilekit.polyomino(name)
        assert poly.is_isohedral()
        for til in poly.tilings():
            region = (-8, -8, 8, 8)
            report = til.patch(region).validate(region)
            assert report.ok, (name, til.heesch_type, report.summary())
            wg = wallpaper_group(til)
            assert til.ih is not None
            if poly.symmetry == "C1":
                assert wg.iuc == groups[til.ih], (name, til.heesch_type, wg.iuc, groups[til.ih])
            checked += 1
    assert checked >= 20


def test_usual_names_and_api():
    x = tilekit.polyomino("pentomino-X")
    assert x.code == ".x./xxx/.x." and x.symmetry == "D4" and x.n == 5
    assert x.is_isohedral() and "TTTT" in {f["heesch"] for f in x.factorisations()}
    assert tilekit.polyomino(".xx/xx./.x.").name == "pentomino-F"
    assert tilekit.polyomino([[0, 0], [1, 0], [2, 0], [1, 1]]).name == "T-tetromino"
    assert tilekit.polyomino("xxx/x.x/xx.").has_holes
    assert not tilekit.polyomino("xxx/x.x/xx.").is_isohedral()
    # the heptominoes that do not tile isohedrally: 108 - 1 holey - 104 = 3
    polys, flags, _ = enumerate_free(SQUARE, 7, maxsize=7, with_holes=True)
    sevens = [tilekit.polyomino(encode(SQUARE, p)) for p, h in zip(polys, flags) if len(p) == 7 and not h]
    assert sum(not q.is_isohedral() for q in sevens) == 3


def test_bad_input_one_line_errors():
    with pytest.raises(GeometryError, match="empty"):
        tilekit.polyomino([])
    with pytest.raises(GeometryError, match="disconnected"):
        tilekit.polyomino([[0, 0], [2, 0]])
    with pytest.raises(ParseError, match="equal length"):
        tilekit.polyomino("xx/x")
    with pytest.raises(NotFoundError, match="did you mean .pentomino-"):
        tilekit.polyomino("pentomino-Q")
    with pytest.raises(ParameterError, match="limit of 14 cells.*--count-only"):
        psearch.check_params({"max_cells": 16})
    psearch.check_params({"max_cells": 16, "count_only": True})


# --------------------------------------------------------------------------- search chunks and rows

def test_chunk_rows_cover_every_free_polyomino_once():
    params = {"max_cells": 8}
    chunks = psearch.chunks(params)
    json.dumps(chunks)
    codes = []
    counts = Counter()
    for ch in chunks:
        rows, cnt = psearch.chunk_rows(params, ch)
        codes += [r["code"] for r in rows["polyominoes"]]
        counts.update(cnt)
    assert len(codes) == len(set(codes)) == 1 + 1 + 2 + 5 + 12 + 35 + 108 + 369
    assert [counts[f"isohedral_{n}"] for n in range(1, 9)] == A075205[:8]
    assert counts["holey_8"] == 6 and counts["fixed_8"] == 2725


def test_counting_mode_stores_no_rows():
    params = {"max_cells": 15, "count_only": True, "free_counts": False}
    total = Counter()
    chunks = psearch.chunks(params)
    for ch in chunks:
        rows, cnt = psearch.chunk_rows(params, ch)
        assert rows["polyominoes"] == []
        total.update(cnt)
    assert total["fixed_15"] == 27394666  # A001168
    res = psearch.run_chunk(params, chunks[1])
    assert res.rows == {"polyominoes": []} and res.counts["fixed_15"] > 0


def test_row_columns_match_the_table():
    from tilekit.plugins.polyomino.tables import TABLE

    # the enumeration writes every column it can decide, and leaves the classification's
    # (anisohedral_k, Heesch numbers, witness; tiles/verdict of a hole-free non-isohedral
    # polyomino) alone, so that a re-run never erases what polyomino-classify stored
    classification = {"anisohedral_k", "heesch", "heesch_holes", "witness"}
    enumeration = {c.name for c in TABLE.columns} - {"run_id"} - classification
    row = tilekit.polyomino("pentomino-F").row()
    assert set(row) == enumeration
    assert row["name"] == "pentomino-F" and row["isohedral"] and row["tiles"] == "true"
    holey = tilekit.polyomino("xxx/x.x/xxx").row()
    assert set(holey) == enumeration | {"heesch", "heesch_holes"} and holey["tiles"] == "false"
    plain = tilekit.polyomino("x...x/xxxxx").row()  # a non-tiling heptomino
    assert set(plain) == enumeration - {"tiles", "verdict"} and not plain["isohedral"]
    assert row["boundary"] and set(row["boundary"]) <= set("0123")


# --------------------------------------------------------------------------- plugin, catalogue, CLI

def test_migration_branch_upgrades_and_downgrades_with_data(tmp_path):
    import sqlalchemy as sa

    from tilekit.catalogue import open_catalogue
    from tilekit.plugins.polyomino.tables import TABLE

    cat = open_catalogue(f"sqlite:///{tmp_path / 'c.sqlite'}")
    with cat.engine.begin() as conn:
        conn.execute(TABLE.insert(), [tilekit.polyomino("pentomino-F").row()])
    with cat.engine.connect() as conn:
        assert conn.execute(sa.select(sa.func.count()).select_from(TABLE)).scalar() == 1
    cat.downgrade("polyomino@base")
    assert "polyominoes" not in sa.inspect(cat.engine).get_table_names()
    cat.upgrade()
    assert "polyominoes" in sa.inspect(cat.engine).get_table_names()


def test_catalogue_search_list_show_render(catalogue_cli, tmp_path):
    """The stored run through the run layer: rows in the polyominoes table, typed --where filters."""
    run = catalogue_cli.run

    res = run("search", "polyominoes", "--max-cells", "8", "--executor", "process", "--workers", "2")
    assert res.exit_code == 0, res.output

    def count(*where):
        return catalogue_cli.count("polyomino", *where)

    assert count("cells=8") == 369  # A000105
    assert count("cells=8", "isohedral=false") == 369 - 342  # 6 with holes + 21 (A075205)
    assert count("holes=true") == 1 + 6  # A001419
    assert count("cells=8", "translation=true") == 121
    assert count("cells=8", "halfturn=true") == 320
    code = tilekit.polyomino("pentomino-F").code
    res = run("show", code)
    assert res.exit_code == 0 and code in res.output
    res = run("show", "pentomino-X")
    assert res.exit_code == 0 and "pentomino-X" in res.output
    out = tmp_path / "x.svg"
    res = run("render", "pentomino-X", "-o", str(out))
    assert res.exit_code == 0 and out.read_text().startswith("<")
    res = run("render", code, "--set", "tiling=IH28", "-o", str(out))
    assert res.exit_code == 0, res.output
    res = run("render", "pentomino-F", "--tiling", "IH4", "-o", str(out))
    assert res.exit_code == 0, res.output
    res = run("render", "pentomino-F", "--tiling", "IH41", "-o", str(out))
    assert res.exit_code == 2 and "no tiling of type IH41" in res.stderr
    res = run("search", "polyominoes", "--max-cells", "20")
    assert res.exit_code == 2 and res.stderr.count("\n") == 1 and "--count-only" in res.stderr
    res = run("search", "polyominoes", "--max-cells", "30", "--count-only")
    assert res.exit_code == 2 and res.stderr.count("\n") == 1


def test_gcd_helper_sanity():
    assert gcd(12, 18) == 6


def test_no_match_is_dropped_by_the_buffer_size(upto10):
    """The matchers' first buffer (maxout) is a size, not a cap: with room for one match per
    template they find exactly the matches, and the verdicts, of the default buffer."""
    items = [(p, a) for p, h, a in upto10 if not h and len(p) <= 7]
    polys = [p for p, _ in items]
    small = analyse_many(SQUARE, polys, maxout=1)
    assert [b["factorisations"] for b in small] == [b["factorisations"] for b in analyse_many(SQUARE, polys)]
    many = 0
    for p, _ in items:
        _, letters = boundary_word(SQUARE, p)
        full = factorisations(SQUARE, letters)
        assert factorisations(SQUARE, letters, maxout=1) == full
        many += len(full) > 1
    assert many > 100  # the check is not vacuous: most words have several matches


def test_family_flags_follow_the_heesch_letters(upto10):
    """``reflection`` iff some Heesch type found uses a glide reflection (G), ``quarterturn``
    iff one uses a quarter-turn (C4): a reflection template whose glide factors are empty is a
    half-turn tiling."""
    for p, h, a in upto10:
        if h or len(p) > 9:
            continue
        letters = [f["heesch"] for f in a["factorisations"]]
        assert a["reflection"] == any("G" in w for w in letters), encode(SQUARE, p)
        assert a["quarterturn"] == any("C4" in w for w in letters), encode(SQUARE, p)
