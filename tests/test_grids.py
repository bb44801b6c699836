"""The grid tables of tilekit.lattice: geometry checked by shapely, counts by the OEIS and by an
independent enumerator.

Published counts (free polyforms, holes allowed, n = 1, 2, ...):
polyhexes A000228, polyiamonds A000577, polykites A057786 (the deltoidal trihexagonal tiling),
poly-(4.8.8) octasquare forms A343577 ("generalized polyforms on the truncated square tiling",
offset 0: a(0) = 1 is dropped), polyaboloes on the tetrakis square grid A197465; polyhexes
with holes A038144.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from shapely.geometry import Polygon, box
from shapely.ops import unary_union

from tilekit.errors import GeometryError, NotFoundError, ParseError
from tilekit.lattice import (
    GRIDS,
    KITE,
    as_cells,
    boundary_cycles,
    boundary_word,
    canonical,
    count_fixed,
    decode,
    encode,
    free_polyforms,
    get_grid,
    hole_count,
    holes,
    outline,
    parse_polyform,
)

A000228 = [1, 1, 3, 7, 22, 82, 333, 1448, 6572, 30490]  # free polyhexes
A000577 = [1, 1, 1, 3, 4, 12, 24, 66, 160, 448, 1186, 3334]  # free polyiamonds
A057786 = [1, 2, 4, 10, 27, 85, 262, 873, 2917, 10011]  # free polykites
A343577 = [2, 2, 7, 22, 93, 413, 2073, 10741]  # octasquare forms, n >= 1
A197465 = [1, 2, 2, 6, 8, 22, 42, 112, 252, 650, 1584]  # tetrakis polyaboloes
#: free polyhexes with at least one hole, A038144
A038144 = [0, 0, 0, 0, 0, 1, 2, 13, 67, 404, 2323, 13517]

ALL = list(GRIDS.values())


def _window(grid, reach: int) -> np.ndarray:
    """Every cell centre in a square of +-reach periods around the origin."""
    r = np.arange(-reach, reach + 1) * grid.period
    xs, ys = np.meshgrid(r, r, indexing="ij")
    base = np.column_stack([xs.ravel(), ys.ravel()])
    return np.concatenate([base + root for root in grid.roots])


@pytest.mark.parametrize("grid", ALL, ids=lambda g: g.name)
def test_cells_tile_the_plane_without_gap_or_overlap(grid):
    """The cells near the origin, drawn with their exact coordinates, cover a box exactly once."""
    polys = [Polygon(p) for p in grid.cell_polygons(_window(grid, 3))]
    assert all(p.is_valid and p.area > 0 for p in polys)
    assert all(shapely.is_ccw(p.exterior) for p in polys)
    union = unary_union(polys)
    assert sum(p.area for p in polys) == pytest.approx(union.area, rel=1e-9)  # no overlap
    # no gap: a box well inside the window is covered
    xy = grid.xy(np.array([[grid.period, grid.period]]))[0]
    inner = box(-abs(xy).max(), -abs(xy).max(), abs(xy).max(), abs(xy).max())
    assert union.intersection(inner).area == pytest.approx(inner.area, rel=1e-9)
    # one period cell holds one cell of each type: the area of a fundamental domain
    a = abs(np.linalg.det(grid.to_xy * grid.period))
    cells = [Polygon(p) for p in grid.cell_polygons(grid.roots)]
    assert sum(c.area for c in cells) == pytest.approx(a, rel=1e-9)


@pytest.mark.parametrize("grid", ALL, ids=lambda g: g.name)
def test_neighbours_share_a_full_edge(grid):
    """Each type's neighbour across each edge meets it in exactly that edge (shapely), and
    no other cell does."""
    for r, root in enumerate(grid.roots):
        me = Polygon(grid.cell_polygons(root[None])[0])
        verts = grid.vertex_xy(root + grid.vertices[r][: grid.degrees[r]])
        nbrs = root + grid.neighbours[r][: grid.degrees[r]]
        assert len({tuple(q) for q in nbrs.tolist()}) == grid.degrees[r]
        for k, q in enumerate(nbrs):
            other = Polygon(grid.cell_polygons(q[None])[0])
            meet = me.intersection(other)
            assert meet.geom_type == "LineString" and me.intersection(other).area == 0
            edge = np.linalg.norm(verts[(k + 1) % len(verts)] - verts[k])
            assert meet.length == pytest.approx(edge, rel=1e-9)
        # cells that are not neighbours share at most a point
        others = [c for c in _window(grid, 1).tolist() if c not in nbrs.tolist() and c != root.tolist()]
        for c in others:
            meet = me.intersection(Polygon(grid.cell_polygons(np.array([c]))[0]))
            assert meet.length == pytest.approx(0, abs=1e-9) and meet.area == pytest.approx(0, abs=1e-12)


@pytest.mark.parametrize("grid", ALL, ids=lambda g: g.name)
def test_point_group_maps_the_grid_onto_itself(grid):
    """Every group element maps each cell to a cell of the same shape and its vertices to that
    cell's vertices; the elements form a group; letters permute."""
    mats = {m.tobytes() for m in grid.group}
    for a in grid.group:
        for b in grid.group:
            assert (a @ b).tobytes() in mats
    cells = _window(grid, 1)
    for g, m in enumerate(grid.group):
        img = cells @ m.T
        t0, t1 = grid.cell_type(cells), grid.cell_type(img)
        assert (t1 >= 0).all()
        assert [grid.shapes[t] for t in t0] == [grid.shapes[t] for t in t1]
        for c, i, a, b in zip(cells[:12], img[:12], t0[:12], t1[:12]):
            mine = {tuple(v) for v in ((c + grid.vertices[a][: grid.degrees[a]]) @ m.T).tolist()}
            theirs = {tuple(v) for v in (i + grid.vertices[b][: grid.degrees[b]]).tolist()}
            assert mine == theirs
        assert sorted(grid.letter_perm[g].tolist()) == list(range(len(grid.edge_dirs)))


def test_grid_names_and_unknown_grid():
    assert get_grid("hexagonal") is get_grid("hex") and get_grid("triangular") is get_grid("iamond")
    assert get_grid("Kite") is KITE
    with pytest.raises(NotFoundError) as e:
        get_grid("pentagon")
    msg = str(e.value)
    assert "\n" not in msg and all(name in msg for name in GRIDS)


def test_published_counts_fast():
    """Free counts (holes allowed) equal the OEIS: A000228, A000577, A057786, A343577, A197465."""
    for name, seq, n in (("hex", A000228, 8), ("iamond", A000577, 10), ("kite", A057786, 8),
                         ("octasquare", A343577, 7), ("abolo", A197465, 9)):
        c = count_fixed(get_grid(name), n, free=True)
        assert c["free"][1:].tolist() == seq[:n], name
    h = count_fixed(get_grid("hex"), 9, free=True)
    assert h["holey"][1:].tolist() == A038144[:9]


@pytest.mark.slow
def test_published_counts_slow():
    for name, seq, n in (("hex", A000228, 10), ("iamond", A000577, 12), ("kite", A057786, 10),
                         ("octasquare", A343577, 8), ("abolo", A197465, 11)):
        c = count_fixed(get_grid(name), n, free=True)
        assert c["free"][1:].tolist() == seq[:n], name
        if name == "hex":
            assert c["holey"][1:].tolist() == A038144[:n]


def _naive_free(grid, n: int) -> list[set[tuple]]:
    """An independent enumerator: grow every free form by one neighbour, keep the distinct
    canonical forms as sets (plain Python sets and the grid's neighbour tables, no Redelmeier)."""
    def key(cells):
        return frozenset(map(tuple, canonical(grid, np.array(sorted(cells)), "free").tolist()))

    levels = [{key([tuple(r)]) for r in grid.roots.tolist()}]
    for _ in range(n - 1):
        nxt = set()
        for form in levels[-1]:
            cells = set(form)
            for c in form:
                for q in grid.neighbours_of(c).tolist():
                    if tuple(q) not in cells:
                        nxt.add(key(cells | {tuple(q)}))
        levels.append(nxt)
    return levels


def _shapely_holes(grid, cells) -> int:
    union = unary_union([Polygon(p) for p in grid.cell_polygons(cells)])
    return len(union.interiors) if union.geom_type == "Polygon" else -1


@pytest.mark.parametrize("grid,n", [(g, {"drafter": 5, "bevelhex": 4, "halfcairo": 5}.get(g.name, 6)) for g in ALL],
                         ids=lambda v: getattr(v, "name", str(v)))
def test_enumeration_equals_an_independent_enumerator(grid, n):
    """Redelmeier (compiled) and the naive growth give the same free forms on every grid, and
    the compiled hole flags agree with shapely's holes of the union of the cell polygons."""
    levels = _naive_free(grid, n)
    polys, flags, free = free_polyforms(grid, n, with_holes=True)
    for size in range(1, n + 1):
        got = {frozenset(map(tuple, p.tolist())) for p in polys if len(p) == size}
        assert got == levels[size - 1], size
        assert free[size] == len(levels[size - 1])
    for p, h in zip(polys, flags):
        k = _shapely_holes(grid, p)
        assert k >= 0 and bool(k) == bool(h) and hole_count(grid, p) == len(holes(grid, p)) == k


@pytest.mark.parametrize("grid", ALL, ids=lambda g: g.name)
def test_codes_round_trip_and_outlines_have_the_cells_area(grid):
    polys, flags, _ = free_polyforms(grid, 5, with_holes=True)
    for p, h in zip(polys, flags):
        code = encode(grid, p)
        assert encode(grid, decode(grid, code)) == code
        back = canonical(grid, as_cells(grid, decode(grid, code)))
        assert {tuple(c) for c in back.tolist()} == {tuple(c) for c in p.tolist()}
        moved = p @ grid.group[-1].T + grid.period * np.array([3, -2])
        assert encode(grid, moved) == code
        if not h:
            area = sum(Polygon(c).area for c in grid.cell_polygons(p))
            assert outline(grid, p).area == pytest.approx(area, rel=1e-9)


def test_bad_codes_name_the_cell():
    with pytest.raises(GeometryError, match=r"cell \(0, 0\) is not a cell centre of the kite grid"):
        parse_polyform("kite", "kite:1,1;0,0")
    with pytest.raises(GeometryError, match=r"cell \(13, 1\) is not edge-connected to cell \(1, 1\)"):
        parse_polyform("kite", "kite:1,1;13,1")
    with pytest.raises(GeometryError, match=r"cell \(1, 1\) is repeated"):
        parse_polyform(KITE, "1,1;5,2;1,1")
    with pytest.raises(ParseError, match="is for the hex grid, not the kite grid"):
        decode(KITE, "hex:0,0")
    with pytest.raises(ParseError, match="malformed kite polyform code"):
        decode(KITE, "kite:1;2")
    with pytest.raises(GeometryError, match="no cells"):
        decode(KITE, "kite:")


@pytest.mark.parametrize("grid", ALL, ids=lambda g: g.name)
def test_outer_boundary_of_forms_with_holes(grid):
    """The compiled outer trace of a form with a hole equals boundary_cycles' outer cycle, and
    the cycles enclose the cells' area (outer minus holes)."""
    n = {"bevelhex": 6, "octasquare": 6}.get(grid.name, 8)
    polys, flags, _ = free_polyforms(grid, n, with_holes=True)
    for p in (p for p, h in zip(polys, flags) if h):
        v, w = boundary_word(grid, p)
        cycles = boundary_cycles(grid, p)
        assert v.tolist() == cycles[0][0].tolist() and w.tolist() == cycles[0][1].tolist()
        area = sum(Polygon(c).area for c in grid.cell_polygons(p))
        signed = [Polygon(grid.vertex_xy(c[0])).area * (1 if k == 0 else -1) for k, c in enumerate(cycles)]
        assert sum(signed) == pytest.approx(area, rel=1e-9)

