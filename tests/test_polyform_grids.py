"""Polyforms on the hexagonal and triangular grids: the isohedral test and the classification
against Myers' and Kaplan's published counts.

Oracles (OEIS, offset 1; Joseph Myers' polyform tiling data):
A075214 polyhexes that tile isohedrally, A075215 anisohedral polyhexes, A070766 polyhexes that
tile, A070768 hole-free polyhexes that do not tile; A075223 / A075224 / A071332 / A071334 the
same for polyiamonds, A070764 polyiamonds with holes. The polyiamond terms for n = 13 to 16 are
read from the OEIS data files (github.com/oeis/oeisdata, seq/A071/A071332.seq,
seq/A075/A075223.seq, seq/A075/A075224.seq, seq/A071/A071334.seq, seq/A070/A070764.seq,
seq/A000/A000577.seq): 2,495 / 6,354 / 12,908 / 30,261 tile, 2,398 / 6,073 / 12,628 / 29,918
isohedral, 97 / 281 / 280 / 343 anisohedral, 6,290 / 18,099 / 54,808 / 159,048 hole-free
non-tilers, 450 / 1,713 / 6,267 / 21,988 with holes, of 9,235 / 26,166 / 73,983 / 211,297 free
forms (the n = 15 and 16 runs that reproduce them: docs/benchmarks.md, checked against these
lists by test_the_stored_runs_in_the_docs_equal_myers). The polyhex terms for n = 10 are read from
the same files (seq/A000/A000228.seq, seq/A070/A070766.seq, seq/A075/A075214.seq,
seq/A075/A075215.seq, seq/A070/A070768.seq, seq/A038/A038144.seq): 30,490 free, 11,326 tile,
11,068 isohedral, 258 anisohedral, 18,760 hole-free non-tilers, 404 with holes (the stored n = 10
run: docs/benchmarks.md).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from tilekit.lattice import HEXAGONAL, SQUARE, TRIANGULAR, encode, enumerate_free
from tilekit.plugins.polyomino.isohedral import _template_arrays, analyse, periodic_tiling

# n = 1.. ; the sequences' first terms
A075214 = [1, 1, 3, 7, 22, 76, 290, 1018, 3715, 11068]  # isohedral polyhexes
A075223 = [1, 1, 1, 3, 4, 12, 23, 66, 133, 316, 514, 1987, 2398, 6073, 12628, 29918]  # isohedral polyiamonds
A070766 = [1, 1, 3, 7, 22, 77, 294, 1054, 3788, 11326]  # polyhexes that tile
A075215 = [0, 0, 0, 0, 0, 1, 4, 36, 73, 258]  # anisohedral polyhexes
A070768 = [0, 0, 0, 0, 0, 4, 37, 381, 2717, 18760]  # hole-free polyhexes that do not tile
A038144 = [0, 0, 0, 0, 0, 1, 2, 13, 67, 404]  # polyhexes with holes
A071332 = [1, 1, 1, 3, 4, 12, 23, 66, 139, 341, 567, 2034, 2495, 6354, 12908, 30261]  # polyiamonds that tile
A075224 = [0, 0, 0, 0, 0, 0, 0, 0, 6, 25, 53, 47, 97, 281, 280, 343]  # anisohedral polyiamonds
A071334 = [0, 0, 0, 0, 0, 0, 1, 0, 20, 103, 594, 1192, 6290, 18099, 54808, 159048]  # hole-free polyiamonds that do not tile
A070764 = [0, 0, 0, 0, 0, 0, 0, 0, 1, 4, 25, 108, 450, 1713, 6267, 21988]  # polyiamonds with holes


def _free_forms(grid, n):
    """Every free n-form of ``grid`` by plain growth, independent of the library's enumeration
    (Redelmeier's tree from one root cell type, canonical codes, hole flags): the monomers of
    every cell type, then each (n-1)-form plus each edge neighbour of each of its cells, all
    children of a size at once; a form is the least (by rows) of its images under the point
    group, each image's cells sorted and moved by a grid translation into [0, period)^2."""
    period, group = grid.period, grid.group.astype(np.int64)
    forms = np.asarray(grid.roots, dtype=np.int64)[:, None, :]  # (F, 1, 2)

    def canonical(cand):  # (C, m, 2) -> the distinct canonical forms, in blocks (bounded memory)
        if len(cand) > 20000:
            parts = np.concatenate([canonical(cand[i:i + 20000]) for i in range(0, len(cand), 20000)])
            _, first = np.unique(parts.reshape(len(parts), -1), axis=0, return_index=True)
            return parts[np.sort(first)]
        img = np.einsum("gab,cmb->gcma", group, cand)  # (G, C, m, 2)
        key = img[..., 0] * (1 << 32) + img[..., 1]
        order = np.argsort(key, axis=-1)
        img = np.take_along_axis(img, order[..., None], axis=2)
        img = img - (img[:, :, :1, :] - np.mod(img[:, :, :1, :], period))
        G, C, m = img.shape[:3]
        rows = img.reshape(G * C, 2 * m)
        _, ids = np.unique(rows, axis=0, return_inverse=True)
        ids = ids.reshape(G, C)
        best = np.argmin(ids, axis=0)
        pick = img[best, np.arange(C)]
        _, first = np.unique(ids[best, np.arange(C)], return_index=True)
        return pick[np.sort(first)]

    forms = canonical(forms)
    for m in range(2, n + 1):
        types = grid.cell_type(forms.reshape(-1, 2)).reshape(forms.shape[:2])
        nb = forms[:, :, None, :] + grid.neighbours[types]  # (F, m-1, D, 2)
        F, k, D = nb.shape[:3]
        child = np.concatenate([np.repeat(forms[:, None, None], k, 1).repeat(D, 2),
                                nb[:, :, :, None, :]], axis=3).reshape(F * k * D, m, 2)
        # drop children whose new cell was already in the form
        fresh = ~(child[:, :-1, :] == child[:, -1:, :]).all(axis=2).any(axis=1)
        forms = canonical(child[fresh])
    return forms


def _has_hole(grid, cells):
    """Whether the cells enclose an empty cell: a flood fill over empty cells through edge
    neighbours within the bounding box grown by two periods, from every cell of that box more
    than one period away from the cells (a hole lies within one period of them: a hole cell's
    edge neighbours are cells of the form or of the hole); an empty cell left is in a hole."""
    period = grid.period
    filled = {tuple(c) for c in cells.tolist()}
    lo, hi = cells.min(axis=0) - 2 * period, cells.max(axis=0) + 2 * period
    nlo, nhi = cells.min(axis=0) - period, cells.max(axis=0) + period
    box = [(x, y) for x in range(lo[0], hi[0] + 1) for y in range(lo[1], hi[1] + 1)]
    empty = [c for c, t in zip(box, grid.cell_type(np.array(box))) if t >= 0 and c not in filled]
    stack = [c for c in empty if not (nlo[0] <= c[0] <= nhi[0] and nlo[1] <= c[1] <= nhi[1])]
    seen = set(stack)
    while stack:
        c = stack.pop()
        for d in grid.neighbours[grid.cell_type(np.array([c]))[0]].tolist():
            q = (c[0] + d[0], c[1] + d[1])
            if lo[0] <= q[0] <= hi[0] and lo[1] <= q[1] <= hi[1] and q not in filled and q not in seen:
                seen.add(q)
                stack.append(q)
    return len(seen) < len(empty)


def _hole_free(grid, n):
    """The hole-free free n-forms, found without the library's enumeration (:func:`_free_forms`,
    :func:`_has_hole`)."""
    return [p for p in _free_forms(grid, n) if not _has_hole(grid, p)]


A000228 = [1, 1, 3, 7, 22, 82, 333, 1448, 6572, 30490]  # free polyhexes (FACTS.md; 9-10: OEIS)
A000577 = [1, 1, 1, 3, 4, 12, 24, 66, 160, 448, 1186, 3334, 9235, 26166, 73983, 211297]  # free polyiamonds (FACTS.md; 13-16: OEIS)
A057786 = [1, 2, 4, 10, 27, 85, 262]  # free polykites (FACTS.md)


@pytest.mark.parametrize("grid,counts,upto", [(HEXAGONAL, A000228, 6), (TRIANGULAR, A000577, 10),
                                              ("kite", A057786, 6)])
def test_the_independent_enumeration_counts_free_forms_as_the_oeis(grid, counts, upto):
    """The tests' own enumeration (:func:`_free_forms`) finds every free form: A000228 /
    A000577 / A057786; and its hole-free forms are the library's, from every cell type."""
    from tilekit.lattice import get_grid

    grid = get_grid(grid) if isinstance(grid, str) else grid
    for n in range(1, upto + 1):
        forms = _free_forms(grid, n)
        assert len(forms) == counts[n - 1]
    mine = {encode(grid, p) for p in _hole_free(grid, upto)}
    theirs = set()
    for root in range(len(grid.roots)):
        polys, holes, _ = enumerate_free(grid, upto, root=root, maxsize=upto, with_holes=True)
        theirs |= {encode(grid, p) for p, h in zip(polys, holes) if len(p) == upto and not h}
    assert mine == theirs


@pytest.mark.slow
def test_the_hole_free_12_iamonds_include_the_one_from_the_second_cell_type():
    """All 3,334 free 12-iamonds (A000577), 3,226 of them hole-free; one of those is reached by
    the library's enumeration only from the down-pointing cell type (the helper before this
    test enumerated from the first type alone and found 3,225)."""
    assert len(_free_forms(TRIANGULAR, 12)) == A000577[11]
    forms = _hole_free(TRIANGULAR, 12)
    assert len(forms) == 3226
    polys, holes, _ = enumerate_free(TRIANGULAR, 12, root=0, maxsize=12, with_holes=True)
    first = {encode(TRIANGULAR, p) for p, h in zip(polys, holes) if len(p) == 12 and not h}
    assert len({encode(TRIANGULAR, p) for p in forms} - first) == 1


def _isohedral_count(grid, n):
    return sum(analyse(grid, p, construct=False)["isohedral"] for p in _hole_free(grid, n))


@pytest.mark.parametrize("n", range(1, 8))
def test_isohedral_polyhexes_equal_a075214(n):
    assert _isohedral_count(HEXAGONAL, n) == A075214[n - 1]


@pytest.mark.slow
@pytest.mark.parametrize("n", [8, 9])
def test_isohedral_polyhexes_equal_a075214_slow(n):
    assert _isohedral_count(HEXAGONAL, n) == A075214[n - 1]


@pytest.mark.parametrize("n", range(1, 11))
def test_isohedral_polyiamonds_equal_a075223(n):
    assert _isohedral_count(TRIANGULAR, n) == A075223[n - 1]


@pytest.mark.slow
@pytest.mark.parametrize("n", [11, 12, 13])
def test_isohedral_polyiamonds_equal_a075223_slow(n):
    assert _isohedral_count(TRIANGULAR, n) == A075223[n - 1]


@pytest.mark.slow
@pytest.mark.exhaustive
def test_isohedral_14_iamonds_equal_a075223():
    """6,073 of the 24,453 hole-free 14-iamonds (A000577(14) - A070764(14)) tile isohedrally
    (A075223(14)); the tests' own enumeration finds all 26,166 free ones (A000577(14))."""
    assert len(_free_forms(TRIANGULAR, 14)) == A000577[13]
    assert _isohedral_count(TRIANGULAR, 14) == A075223[13]


def test_the_polyhex_sequences_add_up():
    """Myers' polyhex counts as transcribed above are consistent to n = 10, as for the iamonds."""
    for n in range(1, 11):
        assert A070766[n - 1] == A075214[n - 1] + A075215[n - 1]
        assert A000228[n - 1] == A070766[n - 1] + A070768[n - 1] + A038144[n - 1]


def test_the_polyiamond_sequences_add_up():
    """Myers' polyiamond counts as transcribed above are consistent: every tiler is isohedral or
    anisohedral, and every free form tiles, is a hole-free non-tiler, or has holes."""
    for n in range(1, 17):
        assert A071332[n - 1] == A075223[n - 1] + A075224[n - 1]
        assert A000577[n - 1] == A071332[n - 1] + A071334[n - 1] + A070764[n - 1]


#: The stored runs' count tables in docs/benchmarks.md, by the free-form column's sequence:
#: (free, tile, isohedral, anisohedral, hole-free non-tilers, with holes) per grid.
_STORED = {"A000577": (A000577, A071332, A075223, A075224, A071334, A070764),
           "A000228": (A000228, A070766, A075214, A075215, A070768, A038144)}


def _stored_run_rows():
    """Every row of the docs' stored-run tables (header ``| n | free (A...) | tile ...``) as
    (sequence name, n, [free, tile, isohedral, anisohedral, hole-free non-tilers, holes],
    [Hc counts], [Hh counts])."""
    text = (Path(__file__).resolve().parents[1] / "docs" / "benchmarks.md").read_text()
    rows, seq = [], None
    for line in text.splitlines():
        head = re.match(r"\| n \| free \((A\d{6})\) \| tile", line)
        if head:
            seq = head.group(1)
            continue
        if seq and line.startswith("|---"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")] if seq and line.startswith("| ") else None
        if not cells:
            seq = None
            continue
        nums = [int(re.match(r"[\d,]+", c).group(0).replace(",", "")) for c in cells[:7]]
        heesch = [[int(x.replace(",", "")) for x in c.split(" / ")] for c in cells[7:9]]
        rows.append((seq, nums[0], nums[1:], *heesch))
    return rows


def test_the_stored_runs_in_the_docs_equal_myers():
    """The count tables of the stored classification runs in docs/benchmarks.md (polyiamonds
    n = 10 to 16, and any polyhex table) state Myers' counts, column by column (the OEIS terms above),
    and each Heesch column (Hc, Hh) sums to the hole-free non-tilers."""
    rows = _stored_run_rows()
    assert {(seq, n) for seq, n, *_ in rows} >= {("A000577", 15), ("A000577", 16), ("A000228", 9), ("A000228", 10)}
    for seq, n, counts, hc, hh in rows:
        assert counts == [s[n - 1] for s in _STORED[seq]], (seq, n)
        assert sum(hc) == sum(hh) == counts[4], (seq, n)


def test_templates_follow_the_grid_turns():
    """The quarter-turn template needs 90-degree turns (absent from the hexagonal point group);
    the third- and sixth-turn templates need 60/120-degree ones (absent from the square grid)."""
    usable = {g.name: {t[0] for t in _template_arrays(g)[5]} for g in (SQUARE, HEXAGONAL, TRIANGULAR)}
    assert "quarterturn" in usable["square"] and not usable["square"] & {"threefold", "sixfold-1", "sixfold-2"}
    for name in ("hex", "iamond"):
        assert "quarterturn" not in usable[name]
        assert {"threefold", "sixfold-1", "sixfold-2"} <= usable[name]


def test_sixfold_iamonds_need_both_orders():
    """Seven 9-iamonds tile isohedrally only with type CC3C3C6C6 (IH21, p6, six tiles a unit).
    Five of them read C C6 C6 C3 C3 counter-clockwise, the mirror order of the other two: with
    one order only, the count was 128, not A075223(9) = 133."""
    from tilekit.lattice import canonical

    orders = []
    for p in _hole_free(TRIANGULAR, 9):  # in the library's canonical image (the orders are chiral)
        a = analyse(TRIANGULAR, canonical(TRIANGULAR, p), construct=True)
        if a["isohedral"] and not any(a[k] for k in ("translation", "halfturn", "reflection", "threefold")):
            assert a["ih_types"] == [21]
            orders.append(sorted({t.factorisation.template for t in a["tilings"]}))
    assert sorted(orders) == [["sixfold-1"]] * 2 + [["sixfold-2"]] * 5


@pytest.mark.parametrize("grid,n", [(HEXAGONAL, 6), (TRIANGULAR, 9)])
def test_every_built_tiling_is_a_tiling(grid, n):
    """Independent check of the integer proof in ``build``: every tiling built for the
    hole-free n-forms, drawn in the plane, has no gap and no overlap (Patch.validate)."""
    import shapely

    for p in _hole_free(grid, n):
        a = analyse(grid, p, construct=True)
        for bt in a["tilings"][:1]:
            t = periodic_tiling(grid, p, bt)
            region = shapely.box(-6, -6, 6, 6)
            assert t.patch(region).validate(region)


def _classified(grid, n, **bounds):
    """Counts of the classification of every free n-form, each verdict checked independently:
    a torus tiling drawn in the plane has no gap and no overlap (Patch.validate), and a
    non-tiler's corona witness has no overlap."""
    import shapely

    from tilekit.plugins.polyomino.classify import classify, corona_patch, torus_tiling

    polys, holes, _ = enumerate_free(grid, n, maxsize=n, with_holes=True)
    counts = dict.fromkeys(("tiles", "isohedral", "anisohedral", "holefree_nontilers", "holey", "undecided"), 0)
    for p, h in zip(polys, holes):
        if len(p) != n:
            continue
        a = None if h else analyse(grid, p, construct=False)
        c = classify(grid, p, a, has_holes=bool(h), **bounds)
        if c.tiles == "true":
            counts["tiles"] += 1
            counts["isohedral" if c.isohedral else "anisohedral"] += 1
            if c.witness is not None:  # a torus tiling: check it geometrically
                t = torus_tiling(grid, p, c.witness)
                x0, y0, x1, y1 = shapely.MultiPoint(np.vstack([t.v1, t.v2, -t.v1, -t.v2])).bounds
                region = shapely.box(x0, y0, x1, y1)
                assert t.patch(region).validate(region), p.tolist()
        elif c.tiles == "false":
            counts["holey" if h else "holefree_nontilers"] += 1
            if not h:
                assert c.witness["hc"] is None or corona_patch(grid, p, c.witness["hc"]).validate()
        else:
            counts["undecided"] += 1
    return counts


def _expected(n, tiles, iso, aniso, nontilers, holey):
    return {"tiles": tiles[n - 1], "isohedral": iso[n - 1], "anisohedral": aniso[n - 1],
            "holefree_nontilers": nontilers[n - 1], "holey": holey[n - 1], "undecided": 0}


@pytest.mark.parametrize("n", [5, 6])
def test_polyhexes_classified_as_myers(n):
    """Tilers, isohedral, anisohedral, hole-free non-tilers and holey n-hexes equal A070766,
    A075214, A075215, A070768 and A038144."""
    assert _classified(HEXAGONAL, n) == _expected(n, A070766, A075214, A075215, A070768, A038144)


@pytest.mark.slow
@pytest.mark.exhaustive
@pytest.mark.parametrize("n", [7, 8, 9])
def test_polyhexes_7_to_9_classified_as_myers(n):
    """All 333, 1,448 and 6,572 free 7-, 8- and 9-hexes (A000228): tilers, isohedral, anisohedral,
    hole-free non-tilers and holey ones equal A070766, A075214, A075215, A070768 and A038144,
    nothing undecided at the search's default bounds, 300 CPU seconds a form (the stored run of
    docs/benchmarks.md took 1,759 CPU seconds for n = 8 and 9; at ``classify``'s own default of
    120 s one anisohedral 8-hex comes out undecided); every torus witness drawn and validated."""
    got = _classified(HEXAGONAL, n, time_limit=300.0)
    assert got == _expected(n, A070766, A075214, A075215, A070768, A038144)


@pytest.mark.parametrize("n", [7, 8])
def test_polyiamonds_classified_as_myers(n):
    """The V-heptiamond is the one hole-free non-tiler to n = 8 (A071334; Gardner)."""
    holey = [0] * 13
    assert _classified(TRIANGULAR, n) == _expected(n, A071332, A075223, A075224, A071334, holey)


@pytest.mark.slow
def test_polyiamonds_9_classified_as_myers():
    """139 of the 160 9-iamonds tile, 6 only anisohedrally; 20 hole-free ones do not tile, and
    one has a hole (A000577(9) = 160; A071332, A075224, A071334)."""
    assert _classified(TRIANGULAR, 9) == _expected(9, A071332, A075223, A075224, A071334, A070764)


@pytest.mark.slow
@pytest.mark.exhaustive
def test_polyiamonds_13_classified_as_myers():
    """All 9,235 free 13-iamonds (A000577(13)): 2,495 tile (A071332), 97 of them only
    anisohedrally (A075224), 6,290 hole-free ones do not tile (A071334) and 450 have holes
    (A070764), nothing undecided at the default bounds (300 CPU seconds a form). The stored run
    of the same classification took 0.12 CPU hours (docs/benchmarks.md); this test also draws
    and validates every torus witness."""
    assert _classified(TRIANGULAR, 13) == _expected(13, A071332, A075223, A075224, A071334, A070764)


#: The hat (Smith, Myers, Kaplan and Goodman-Strauss, "An aperiodic monotile", 2023) as eight
#: cells of the kite grid: the cells whose union is the outline of tilekit's hat data
#: (catalogue/substitution hat, [tile] outline) scaled onto the grid.
HAT = "kite:1,1;-1,2;-5,4;1,4;-4,5;-1,5;-2,7;-1,8"


def test_the_hat_is_eight_kites_of_the_grid():
    from tilekit.lattice import KITE, outline, parse_polyform

    cells = parse_polyform(KITE, HAT)
    proto = outline(KITE, cells)
    assert len(proto.outline) == 13  # the hat's 13 corners (its 14th vertex is on a straight side)
    kite = KITE.cell_polygons(KITE.roots[:1])[0]
    x, y = kite[:, 0], kite[:, 1]
    kite_area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    assert abs(abs(proto.area) - 8 * kite_area) < 1e-9
    # it is one of the 873 free 8-kites (A057786), found by the enumeration from its cell types
    found = {encode(KITE, p)
             for r in range(len(KITE.roots)) for p in enumerate_free(KITE, 8, root=r, maxsize=8)[0] if len(p) == 8}
    assert len(found) == 873 and HAT in found


def test_the_hat_is_undecided_never_a_non_tiler():
    """The hat tiles, only aperiodically: surrounded to the level limit, and no torus up to 12
    tiles per translational unit has a cover, so the classification must stop at 'undecided'
    with those bounds, never 'false' and never a periodic tiling. The corona witness is checked
    for overlaps and has the hat at its centre."""
    from tilekit.lattice import KITE, parse_polyform
    from tilekit.plugins.polyomino.classify import classify, corona_patch

    cells = parse_polyform(KITE, HAT)
    a = analyse(KITE, cells, construct=False)
    assert not a["isohedral"]
    c = classify(KITE, cells, a, probe=2, max_level=3, torus_tiles=12, time_limit=300)
    assert c.tiles == "undecided"
    assert c.verdict.startswith("undecided up to 3 coronas and 12 tiles per translational unit")
    hc = c.witness["hc"]
    assert hc["k"] == 3 and not hc["holes"]
    patch = corona_patch(KITE, cells, hc)
    assert patch.validate()


def test_bad_grid_inputs_are_one_line_errors():
    from tilekit.errors import GeometryError, NotFoundError, ParameterError
    from tilekit.plugins.polyomino.classify_search import check_params
    from tilekit.plugins.polyomino.model import Polyomino

    with pytest.raises(NotFoundError, match="grids: square, hex, iamond, kite"):
        check_params({"max_cells": 5, "grid": "pentagonal"})
    # past the square grid's 14 cells in free forms: refused with the estimate, before any run
    with pytest.raises(ParameterError, match=r"13 on the hex grid means about [\d,]+ free forms \(estimated\)"):
        check_params({"max_cells": 13, "grid": "hex"})
    with pytest.raises(ParameterError, match="max_cells.*beyond the classification.s limit of 14 cells on the square grid"):
        check_params({"max_cells": 15, "grid": "square"})
    check_params({"max_cells": 16, "grid": "iamond"})  # polyiamonds to 16: about 10^5 forms
    # the grids with cells of several shapes are classified too (tests/test_multigrid_classify.py)
    check_params({"max_cells": 4, "grid": "octasquare"})
    with pytest.raises(GeometryError, match="disconnected"):
        Polyomino.parse("hex:0,0;9,0")
    with pytest.raises(GeometryError, match="not a cell"):
        Polyomino.parse("iamond:1,1;3,3")


@pytest.mark.parametrize("code", ["hex:0,0;3,0;6,0", "iamond:1,1;2,2;4,1", "kite:1,1;4,1;1,4"])
def test_a_one_class_torus_tiling_is_isohedral(code):
    """Without the boundary-word test (an empty analysis) the torus search alone must find
    these isohedral tilers' one-class tilings and call them isohedral, not 'anisohedral with
    1 class' (what the 9-iamonds got before): the exact one-class torus test."""
    import shapely

    from tilekit.lattice import get_grid, parse_polyform
    from tilekit.plugins.polyomino.classify import classify, torus_tiling

    grid = get_grid(code.split(":")[0])
    cells = parse_polyform(grid, code)
    c = classify(grid, cells, {}, probe=1, max_level=2)
    assert c.tiles == "true" and c.isohedral and c.anisohedral_k is None
    # on the kite grid (no complete boundary-word test) the direct isohedral test answers first
    how = "a first corona closed under" if grid.name == "kite" else "a torus tiling with one transitivity class"
    assert c.verdict.startswith(f"tiles isohedrally: {how}")
    assert c.witness["k"] == 1
    t = torus_tiling(grid, cells, c.witness)
    region = shapely.box(-2, -2, 2, 2)
    assert t.patch(region).validate(region)


def test_hex_rows_list_show_render_and_web(catalogue_cli, tmp_path):
    """The classification search on the hex grid stores rows with grid=hex that `list`,
    `show`, `render` and the web pages read as for polyominoes (A070768(6) = 4 hole-free
    non-tilers to 6 cells, one with Heesch number 2; A075215(6) = 1 anisohedral)."""
    import json
    from urllib.parse import quote

    from starlette.testclient import TestClient

    from tilekit.web import create_app

    run = catalogue_cli.run
    res = run("search", "polyomino-classify", "--grid", "hex", "--max-cells", "6")
    assert res.exit_code == 0, res.output

    def count(*where):
        return catalogue_cli.count("polyform", "grid=hex", *where)

    assert count() == 1 + 1 + 3 + 7 + 22 + 82  # A000228
    assert count("tiles=false", "holes=false") == 4
    assert count("tiles=true", "isohedral=false") == 1
    assert count("heesch=2") == 1
    # `polyomino` is the square grid's rows alone, `polyform` every grid's: in list, keys and
    # the web's family counts
    assert catalogue_cli.count("polyomino", "grid=square") == 0
    assert catalogue_cli.count("polyomino") == 0
    assert catalogue_cli.count("polyform") == count()
    keys = {k["key"]: k for k in json.loads(run("keys", "polyomino", "--format", "json").output)}
    assert keys["grid"]["tilings"] == 0
    keys = {k["key"]: k for k in json.loads(run("keys", "polyform", "--format", "json").output)}
    assert keys["grid"]["tilings"] == count()
    r = run("list", "--family", "polyform", "--where", "grid=hex", "--where", "heesch=2", "--format", "json")
    code = json.loads(r.output)[0]["code"]
    assert code == "hex:0,0;3,0;6,0;-3,3;6,3;-6,6"
    res = run("show", code)
    assert res.exit_code == 0 and "6-hex" in res.output and "Heesch number 2" in res.output
    for view, name in ((None, "h2.svg"), ("holes", "hh.png")):
        out = tmp_path / name
        res = run("render", code, *(("--set", f"view={view}") if view else ()), "-o", str(out))
        assert res.exit_code == 0 and out.stat().st_size > 0, res.output
    r = run("list", "--family", "polyform", "--where", "grid=hex", "--where", "isohedral=false",
            "--where", "tiles=true", "--format", "json")
    aniso = json.loads(r.output)[0]["code"]
    res = run("render", aniso, "-o", str(tmp_path / "aniso.svg"))
    assert res.exit_code == 0, res.output
    with TestClient(create_app(catalogue_cli.url)) as client:
        for url in (f"/tiling/{quote(code, safe='')}", f"/thumb/{quote(aniso, safe='')}.svg"):
            assert client.get(url).status_code == 200, url
        fams = {f["name"]: f["tilings"] for f in client.get("/api/families").json()["families"]}
        assert fams["polyomino"] == 0  # the family's rows, as on its page: the square grid's
        assert client.get("/api/query?family=polyomino").json()["total"] == 0
        assert client.get("/api/query?family=polyform").json()["total"] == count()
