"""tilekit.lattice: the grid tables, Redelmeier enumeration, canonical forms, holes, boundary words.

Counts are checked against the OEIS: free polyominoes A000105, fixed A001168, with holes
A001419, one-sided A000988; fixed polyhexes A001207 and polyiamonds A001420, free polyhexes
A000228 and polyiamonds A000577, all through the same grid interface.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit.errors import GeometryError, ParseError
from tilekit.lattice import (
    HEXAGONAL,
    SQUARE,
    TRIANGULAR,
    as_cells,
    boundary_cycles,
    boundary_word,
    canonical,
    count_fixed,
    decode,
    encode,
    enumerate_free,
    hole_count,
    holes,
    images,
    outline,
    prefixes,
    symmetry_elements,
    symmetry_name,
)

# OEIS A000105 (free), A001168 (fixed), A001419 (with holes), from n = 1
A000105 = [1, 1, 2, 5, 12, 35, 108, 369, 1285, 4655, 17073, 63600, 238591, 901971]
A001168 = [1, 2, 6, 19, 63, 216, 760, 2725, 9910, 36446, 135268, 505861, 1903890, 7204874,
           27394666, 104592937]
A001419 = [0, 0, 0, 0, 0, 0, 1, 6, 37, 195, 979, 4663, 21474, 96496]
A001207 = [1, 3, 11, 44, 186, 814, 3652, 16689]  # fixed polyhexes
A001420 = [2, 3, 6, 14, 36, 94, 250, 675]  # fixed polyiamonds
A000228 = [1, 1, 3, 7, 22, 82, 333, 1448]  # free polyhexes
A000577 = [1, 1, 1, 3, 4, 12, 24, 66]  # free polyiamonds
A000988 = [1, 1, 2, 7, 18, 60, 196, 704]  # one-sided polyominoes


def test_point_groups_are_groups_of_the_grid():
    for grid, order in ((SQUARE, 8), (HEXAGONAL, 12), (TRIANGULAR, 12)):
        assert len(grid.group) == order
        # closed under composition, and every element maps cell centres to cell centres
        mats = {m.tobytes() for m in grid.group}
        for a in grid.group:
            for b in grid.group:
                assert (a @ b).tobytes() in mats
            assert grid.is_cell(np.vstack([grid.roots, grid.neighbours[0] + grid.roots[0]]) @ a.T).all()
        # letters permute edge directions; reflections reverse orientation
        assert sorted(grid.letter_perm[1].tolist()) == list(range(len(grid.edge_dirs)))
        assert (grid.det[: order // 2] == 1).all() and (grid.det[order // 2:] == -1).all()


def test_square_counts_to_12():
    c = count_fixed(SQUARE, 12, free=True)
    assert c["fixed"][1:].tolist() == A001168[:12]
    assert c["free"][1:].tolist() == A000105[:12]
    assert c["holey"][1:].tolist() == A001419[:12]


@pytest.mark.slow
def test_square_counts_13_14():
    c = count_fixed(SQUARE, 14, free=True)
    assert c["free"][13:].tolist() == A000105[12:14]
    assert c["holey"][13:].tolist() == A001419[12:14]
    assert c["fixed"][13:].tolist() == A001168[12:14]


def test_counting_only_beyond_the_stored_limit():
    c = count_fixed(SQUARE, 16)
    assert c["fixed"][15:].tolist() == A001168[14:16]


def test_hex_and_triangle_grids_through_the_same_interface():
    h = count_fixed(HEXAGONAL, 8, free=True)
    t = count_fixed(TRIANGULAR, 8, free=True)
    assert h["fixed"][1:].tolist() == A001207
    assert t["fixed"][1:].tolist() == A001420
    assert h["free"][1:].tolist() == A000228
    assert t["free"][1:].tolist() == A000577


def test_one_sided_and_fixed_equivalences():
    polys, _ = enumerate_free(SQUARE, 8)
    for n in range(1, 9):
        these = [p for p in polys if len(p) == n]
        one_sided = {tuple(map(tuple, canonical(SQUARE, im, "one-sided").tolist()))
                     for p in these for im in images(SQUARE, p, "free")}
        fixed = {tuple(map(tuple, im.tolist())) for p in these for im in images(SQUARE, p, "free")}
        assert len(one_sided) == A000988[n - 1]
        assert len(fixed) == A001168[n - 1]


def test_chunks_partition_the_search_tree():
    """Each free polyomino is emitted by exactly one chunk (top chunk + one per depth-4 node)."""
    n, depth = 9, 4
    codes: list[str] = []
    polys, _ = enumerate_free(SQUARE, n, maxsize=depth - 1)
    codes += [encode(SQUARE, p) for p in polys]
    for pre in prefixes(SQUARE, n, depth, 0):
        polys, _ = enumerate_free(SQUARE, n, prefix=pre)
        codes += [encode(SQUARE, p) for p in polys]
    assert len(codes) == len(set(codes)) == sum(A000105[:n])
    assert len(prefixes(SQUARE, n, depth, 0)) == A001168[depth - 1]


def test_symmetry_groups_of_the_pentominoes():
    expect = {".x./xxx/.x.": "D4", "xxxxx": "D2", ".xx/xx./.x.": "C1", "xx./.x./.xx": "C2",
              "x.x/xxx": "D1", "x../xx./.xx": "D1", "xx/xx/x.": "C1"}
    for code, name in expect.items():
        assert symmetry_name(SQUARE, symmetry_elements(SQUARE, decode(SQUARE, code))) == name


def test_boundary_word_is_a_closed_ccw_cycle_of_the_perimeter():
    polys, _ = enumerate_free(SQUARE, 7)
    for p in polys:
        if holes(SQUARE, p):
            continue
        verts, letters = boundary_word(SQUARE, p)
        steps = SQUARE.edge_dirs[letters]
        assert (verts[0] + steps.cumsum(axis=0)[-1] == verts[0]).all()
        # perimeter = 4n - 2 * (number of adjacent pairs)
        keys = {tuple(c) for c in p.tolist()}
        adj = sum((x + 2, y) in keys for x, y in keys) + sum((x, y + 2) in keys for x, y in keys)
        assert len(letters) == 4 * len(p) - 2 * adj
        assert outline(SQUARE, p).area == pytest.approx(len(p))
        assert boundary_cycles(SQUARE, p)[0][1].tolist() == letters.tolist()


def test_holes_and_the_holey_heptomino():
    p = decode(SQUARE, "xxx/x.x/xx.")
    h = holes(SQUARE, p)
    assert len(h) == 1 and h[0].tolist() == [[3, 3]]
    assert len(boundary_cycles(SQUARE, p)) == 2


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 4), st.integers(0, 4)), min_size=1, max_size=10, unique=True),
       st.integers(0, 7))
def test_codes_round_trip_and_canonical_is_invariant(pairs, g):
    cells = 2 * np.array(pairs) + 1
    try:
        as_cells(SQUARE, cells)
    except GeometryError:
        return  # disconnected draws are rejected, which is tested below
    moved = cells @ SQUARE.group[g].T + np.array([6, -4])
    assert encode(SQUARE, moved) == encode(SQUARE, cells)
    assert encode(SQUARE, decode(SQUARE, encode(SQUARE, cells))) == encode(SQUARE, cells)


def test_bad_cells_and_codes():
    with pytest.raises(GeometryError, match="empty"):
        as_cells(SQUARE, [])
    with pytest.raises(GeometryError, match="disconnected"):
        as_cells(SQUARE, [[1, 1], [5, 1]])
    with pytest.raises(GeometryError, match="not a cell centre"):
        as_cells(SQUARE, [[0, 0]])
    with pytest.raises(ParseError, match="equal length"):
        decode(SQUARE, "xx/x")
    with pytest.raises(ParseError, match="malformed"):
        decode(SQUARE, "xq")


@pytest.mark.parametrize("grid,n", [(SQUARE, 10), (TRIANGULAR, 10), (HEXAGONAL, 7)])
def test_compiled_hole_count_and_outer_boundary_agree_with_the_python_ones(grid, n):
    """hole_count (compiled flood fill) == len(holes); the compiled outer trace of a polyform
    with holes or a pinch vertex == boundary_cycles' outer cycle, vertex for vertex."""
    polys, flags, _ = enumerate_free(grid, n, with_holes=True)
    holey = 0
    for p, h in zip(polys, flags):
        assert hole_count(grid, p) == len(holes(grid, p))
        if h:
            v, w = boundary_word(grid, p)
            v2, w2 = boundary_cycles(grid, p)[0]
            assert v.tolist() == v2.tolist() and w.tolist() == w2.tolist()
            holey += 1
    if grid is SQUARE:
        assert holey == 1 + 6 + 37 + 195  # A001419, n <= 10
    elif grid is TRIANGULAR:
        assert holey == int(sum(flags)) > 0


def test_unique_keys_equals_numpy_unique():
    """lattice.unique_keys is np.unique's sorted distinct values, by a sort (NumPy >= 2.3 hashes
    plain integer np.unique calls, 20x slower on 10^5 keys): empty, one, repeated and spread
    keys, negative ones, and any shape (flattened like np.unique)."""
    from tilekit.lattice import unique_keys

    rng = np.random.default_rng(7)
    cases = [np.zeros(0, np.int64), np.array([5]), np.array([3, 3, 3]), rng.integers(-50, 50, 1000),
             rng.integers(-(2**40), 2**40, 5000), rng.integers(0, 9, (40, 7))]
    for keys in cases:
        got = unique_keys(keys)
        assert got.dtype == np.int64 and np.array_equal(got, np.unique(keys))
