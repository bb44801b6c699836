"""The ``polyforms`` search: free polyforms on every grid, stored in the polyominoes table.

Stored rows are checked by an independent reader (codes decoded and re-validated, canonical,
distinct; holes recounted by shapely from the exact cell polygons; boundary words closed), and
the counts per size against the OEIS: polykites A057786 (1, 2, 4, 10, 27, 85, ...), polyiamonds
A000577, polyhexes A000228.
"""

from __future__ import annotations

import json
from collections import Counter

import numpy as np
import pytest
import sqlalchemy as sa
from cliutil import assert_one_line_error
from shapely.geometry import Polygon
from shapely.ops import unary_union

from tilekit.errors import GeometryError
from tilekit.lattice import (
    GRIDS,
    KITE,
    SQUARE,
    canonical,
    count_fixed,
    encode,
    get_grid,
    parse_polyform,
)
from tilekit.plugins.polyomino import polyforms
from tilekit.plugins.polyomino import search as polyominoes
from tilekit.plugins.polyomino.polyform import PolyformCells, from_spec

A057786 = [1, 2, 4, 10, 27, 85, 262, 873, 2917, 10011]  # free polykites
A000228 = [1, 1, 3, 7, 22, 82, 333, 1448, 6572, 30490]  # free polyhexes


def test_unknown_grid_is_one_line_listing_the_grids(catalogue_cli):
    res = catalogue_cli.run("search", "polyforms", "--grid", "pentagon", "--max-cells", "4")
    assert_one_line_error(res, "unknown grid value 'pentagon'")
    assert all(name in res.stderr for name in GRIDS)
    assert "no runs" in catalogue_cli.run("runs").output


def test_oversize_is_refused_with_the_estimate_before_a_run(catalogue_cli):
    res = catalogue_cli.run("search", "polyforms", "--grid", "hex", "--max-cells", "13")
    assert_one_line_error(res, "--max-cells 13 on the hex grid would store about")
    assert "over the limit of 1,500,000" in res.stderr and "the largest size within it is --max-cells 12" in res.stderr
    assert " at 0.4 ms each" in res.stderr
    assert "no runs" in catalogue_cli.run("runs").output
    res = catalogue_cli.run("search", "polyforms", "--grid", "kite", "--max-cells", "41")
    assert_one_line_error(res, "from 1 to 40")


@pytest.mark.parametrize("name,seq,n", [("kite", A057786, 10), ("hex", A000228, 10)])
def test_estimate_is_a_close_lower_estimate(name, seq, n):
    """The estimate (exact fixed counts while small, then the last growth ratio, over the group
    order) stays below the true free counts and within a factor 2 of them."""
    est = polyforms.estimate_forms(name, n)
    for k in range(1, n + 1):
        assert est[k] <= seq[k - 1] * 1.0001
        if k >= 5:
            assert est[k] >= seq[k - 1] / 2, (k, est[k], seq[k - 1])


def test_chunks_partition_every_grid():
    """Top chunks and prefix chunks of every root emit each free form once (drafter: 12 cell
    types; bevelhex: 3 shapes)."""
    for name, n in (("drafter", 6), ("bevelhex", 5), ("trihex", 6)):
        grid = get_grid(name)
        params = {"grid": name, "max_cells": n, "prefix_depth": 3}
        codes = []
        for chunk in polyforms.chunks(params):
            rows, counts = polyforms.chunk_rows(params, chunk)
            codes += [r["code"] for r in rows["polyominoes"]]
        c = count_fixed(grid, n, free=True)
        assert len(codes) == len(set(codes)) == int(c["free"].sum())


def test_square_grid_is_the_polyominoes_search():
    chunk = polyominoes.chunks({"max_cells": 7, "prefix_depth": 3})[1]
    a = polyforms.chunk_rows({"grid": "square", "max_cells": 7, "prefix_depth": 3}, chunk)
    b = polyominoes.chunk_rows({"max_cells": 7, "prefix_depth": 3}, chunk)
    assert a == b


def _holes_by_shapely(grid, cells) -> int:
    union = unary_union([Polygon(p) for p in grid.cell_polygons(cells)])
    assert union.geom_type == "Polygon"
    return len(union.interiors)


def test_stored_kite_run_checked_independently(catalogue_cli, tmp_path):
    res = catalogue_cli.run("search", "polyforms", "--grid", "kite", "--max-cells", "7")
    assert res.exit_code == 0, res.output
    for n in range(1, 8):
        assert catalogue_cli.count("polyform", "grid=kite", f"cells={n}") == A057786[n - 1]
    engine = sa.create_engine(catalogue_cli.url)
    with engine.connect() as conn:
        rows = conn.execute(sa.text("SELECT * FROM polyominoes WHERE grid = 'kite'")).mappings().all()
    assert len(rows) == sum(A057786[:7])
    seen = set()
    for r in rows:
        cells = parse_polyform(KITE, r["code"])  # cells of the grid, distinct, edge-connected
        assert encode(KITE, canonical(KITE, cells)) == r["code"]  # stored in canonical form
        assert json.loads(r["cell_list"]) == cells.tolist()
        assert r["code"] not in seen
        seen.add(r["code"])
        assert len(cells) == r["cells"]
        k = _holes_by_shapely(KITE, cells)
        assert bool(k) == r["holes"] and k == r["hole_count"]
        assert r["isohedral"] is None and r["translation"] is None  # not tested by this search
        steps = KITE.edge_dirs[[int(ch, 36) for ch in r["boundary"]]]
        assert (steps.sum(axis=0) == 0).all()
        if not r["holes"]:
            outline = Polygon(KITE.vertex_xy(np.cumsum(steps, axis=0)))
            area = sum(Polygon(p).area for p in KITE.cell_polygons(cells))
            assert outline.area == pytest.approx(area)
    assert Counter(r["holes"] for r in rows)[True] == 1 + 4  # one 6-kite and four 7-kites
    code = next(r["code"] for r in rows if r["holes"])
    res = catalogue_cli.run("show", code)
    assert res.exit_code == 0 and "does not tile: it has a hole" in res.output
    out = tmp_path / "k.svg"
    res = catalogue_cli.run("render", code, "-o", str(out))
    assert res.exit_code == 0 and out.read_text().startswith("<")
    res = catalogue_cli.run("list", "--family", "polyform", "--where", "grid=kite", "--where", "cells=2")
    assert res.exit_code == 0 and "2-kite" in res.output and "not classified" in res.output


def test_polyform_tiling_patch_is_its_cells_without_overlap():
    for grid in GRIDS.values():
        if grid is SQUARE:
            continue
        cells = parse_polyform(grid, encode(grid, np.concatenate([grid.roots[:1], grid.roots[:1] + grid.neighbours[0][:1]])))
        til = from_spec({"code": encode(grid, cells)})
        assert isinstance(til, PolyformCells) and til.properties()["grid"] == grid.name
        p = til.patch(til.default_region())
        assert len(p.prototile) == 2
        shape = unary_union([Polygon(q) for q in grid.cell_polygons(cells)])
        assert p.validate(shape).ok  # the cells, no overlap, covering exactly the form


def test_a_code_that_is_not_a_connected_set_names_the_cell():
    with pytest.raises(GeometryError, match=r"cell \(13, 1\) is not edge-connected"):
        from_spec({"code": "kite:1,1;13,1"})
    with pytest.raises(GeometryError, match=r"cell \(1, 1\) is not a cell centre of the octasquare grid"):
        from_spec({"code": "octasquare:0,0;1,1"})


A000577 = [1, 1, 1, 3, 4, 12, 24, 66]  # free polyiamonds


def test_stored_run_on_both_databases(db_url):
    """run_search on SQLite and PostgreSQL: polyiamond rows to n = 8 per size equal A000577,
    and the isohedral flags this search leaves untested are stored as NULL."""
    from tilekit.catalogue import open_catalogue
    from tilekit.search import run_search

    cat = open_catalogue(db_url)
    run_id = run_search(cat, "polyforms", {"grid": "iamond", "max_cells": 8})
    info = cat.run(run_id)
    assert info.status == "done" and info.rows == sum(A000577)
    with cat.engine.connect() as conn:
        per_size = dict(conn.execute(sa.text(
            "SELECT cells, count(*) FROM polyominoes WHERE grid = 'iamond' GROUP BY cells")).all())
        nulls = conn.execute(sa.text("SELECT count(*) FROM polyominoes WHERE isohedral IS NULL")).scalar()
    assert [per_size[k] for k in range(1, 9)] == A000577
    assert nulls == sum(A000577)
