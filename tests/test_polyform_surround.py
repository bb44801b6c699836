"""The direct isohedral test (tilekit.plugins.polyomino.surround) against the boundary-word test
where that one is complete.

On the square grid Langerman and Winslow's templates find exactly the isohedral polyominoes
(their theorem), and on the hex and iamond grids the template counts equal Myers' A075214 /
A075223 (tests/test_polyform_grids.py). The direct test is written for any grid and never reads
a boundary word, so giving the same verdict form by form there checks it independently,
including its handling of symmetric tiles (many of these forms have mirror or turn symmetry,
so the tile's stabiliser in the tiling's group matters). Every tiling it reports is checked
by tilekit.symmetry (one transitivity class) and drawn and validated (no gap, no overlap).
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from tilekit.lattice import free_polyforms, get_grid
from tilekit.plugins.polyomino.classify import torus_tiling
from tilekit.plugins.polyomino.heesch import HeeschSolver, first_corona_rows
from tilekit.plugins.polyomino.isohedral import analyse
from tilekit.plugins.polyomino.surround import SurroundTest
from tilekit.symmetry.orbits import isohedrality


def _direct(grid, cells):
    first = first_corona_rows(grid, cells)
    if not len(first):  # no corona at all: no tiling (the local test's proof)
        return False, None
    hs = HeeschSolver(grid, cells, solver="glucose4", first=first)
    try:
        r = SurroundTest(hs).run()
    finally:
        hs.close()
    return r.isohedral, r.tiling


@pytest.mark.parametrize(("name", "n", "isohedral"), [
    # isohedral tilers among the free forms of 1..n cells (OEIS)
    ("square", 6, 1 + 1 + 2 + 5 + 12 + 35),  # A075205
    ("hex", 5, 1 + 1 + 3 + 7 + 22),  # A075214
    ("iamond", 7, 1 + 1 + 1 + 3 + 4 + 12 + 23),  # A075223
])
def test_direct_test_equals_the_complete_boundary_word_test(name, n, isohedral):
    grid = get_grid(name)
    polys, holes, _ = free_polyforms(grid, n, with_holes=True)
    found = 0
    for cells, holey in zip(polys, holes):
        if holey:
            continue
        verdict, tiling = _direct(grid, cells)
        assert verdict is not None
        assert verdict == analyse(grid, cells, construct=False)["isohedral"], cells.tolist()
        if verdict:
            found += 1
            t = torus_tiling(grid, cells, tiling.to_json())
            assert isohedrality(t) == 1, cells.tolist()
            if found % 16 == 1:  # drawn and validated, a sample (each takes ~50 ms)
                r = 2.0 * float(np.abs(np.concatenate([t.v1, t.v2])).max())
                region = shapely.box(-r, -r, r, r)
                assert t.patch(shapely.box(-2 * r, -2 * r, 2 * r, 2 * r)).validate(region)
    assert found == isohedral
