"""Cell grids as a few integer tables, and polyforms on them.

A grid is data, in the manner of Kaplan's heesch-sat: every algorithm below (Redelmeier
enumeration, canonical forms, symmetry groups, boundary words, holes, outlines) reads only
these tables, so a new grid is one more table. Ten grids: square, hex, iamond (tabled by
hand) and kite, octasquare, trihex, drafter, abolo, halfcairo, bevelhex (each one
:func:`grid_from_cells` table: prototype cells, the point group and the period; the cell
types, edge neighbours and edge directions are derived). Cell types may differ in shape and
number of edges (``Grid.degree``).

Coordinates are *fine* integer coordinates in which cell reference points and cell vertices
are both lattice points and the grid's point group acts by integer 2x2 matrices about the
origin:

- square: centres (2x+1, 2y+1), vertices (2x, 2y); Cartesian = fine / 2.
- hex and iamond: coordinates in the basis u = (1, 0), v = (1/2, sqrt(3)/2) scaled
  by 3, so hexagon centres are (3a, 3b) and triangle centroids (3a+1, 3b+1) (pointing up) or
  (3a+2, 3b+2) (pointing down).
- the others: see each table's comment (60-degree basis for kite, trihex, drafter, bevelhex;
  square basis for octasquare, abolo, halfcairo); ``Grid.vertex_xy`` gives exact Cartesian
  vertices (regular octagons and dodecagons through a per-residue shift).

The translations of a grid are ``period * Z^2``; a cell's *type* is its reference point
modulo the period, and neighbour offsets and vertex offsets are tabled per type. Boundary
words are written over the grid's edge directions (``edge_dirs``; counter-clockwise
boundary, interior on the left). Redelmeier's tree is rooted at one cell type
(:func:`enumerate_free` ``root=``); :func:`free_polyforms` walks every type's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache, cached_property

import numpy as np

from tilekit.errors import GeometryError, NotFoundError, ParameterError, ParseError
from tilekit.jit import njit
from tilekit.tiling import Prototile


@dataclass(frozen=True, eq=False)
class Grid:
    """One cell lattice as integer tables (see the module docstring for the coordinates)."""

    name: str
    period: int
    roots: np.ndarray  # (R, 2) one centre per cell type, in [0, period)^2
    neighbours: np.ndarray  # (R, D, 2) offsets from a centre of each type to its edge neighbours
    vertices: np.ndarray  # (R, V, 2) counter-clockwise vertex offsets from a centre of each type
    edge_dirs: np.ndarray  # (E, 2) edge vectors of the grid, indexed by boundary-word letter
    group: np.ndarray  # (G, 2, 2) the point group about the origin; group[0] is the identity
    group_names: tuple[str, ...]  # e.g. "r1" (rotation by one step), "s0" (reflection)
    to_xy: np.ndarray  # (2, 2) fine coordinates -> Cartesian
    cell_name: str = "cell"
    #: (R,) edges (= vertices = edge neighbours) of each cell type; None: all R types have V.
    #: Shorter types are padded: their vertex list repeats its last vertex and their neighbour
    #: list its last neighbour, so set-like uses (floods, Redelmeier's untried set) need no care.
    degree: np.ndarray | None = None
    #: (R,) name of each cell type's shape, e.g. "octagon" / "square"
    shapes: tuple[str, ...] = ()
    #: other names :func:`get_grid` accepts
    aliases: tuple[str, ...] = ()
    #: (period, period, 2) Cartesian offset added to a *vertex* by its residue class: grids whose
    #: exact drawing is not an integer lattice (regular octagons) are drawn through it; None: linear
    vertex_shift: np.ndarray | None = None
    #: least size of a polyform with a hole (enumeration skips the hole test below it)
    hole_min: int = 1
    #: where the grid's cells and counts are published (cited by the tests and docs)
    reference: str = ""

    # -- derived tables -------------------------------------------------------
    @cached_property
    def letter_perm(self) -> np.ndarray:
        """(G, E): group element g maps edge letter e to letter_perm[g, e]."""
        out = np.zeros((len(self.group), len(self.edge_dirs)), dtype=np.int64)
        for g, m in enumerate(self.group):
            for e, d in enumerate(self.edge_dirs):
                img = m @ d
                hit = np.nonzero((self.edge_dirs == img).all(axis=1))[0]
                out[g, e] = hit[0]
        return out

    @cached_property
    def det(self) -> np.ndarray:
        return np.round(np.linalg.det(self.group.astype(float))).astype(np.int64)

    @cached_property
    def neg(self) -> np.ndarray:
        """letter of the reversed edge direction."""
        out = np.zeros(len(self.edge_dirs), dtype=np.int64)
        for e, d in enumerate(self.edge_dirs):
            out[e] = np.nonzero((self.edge_dirs == -d).all(axis=1))[0][0]
        return out

    @cached_property
    def rotation_order(self) -> int:
        return len(self.group) // 2

    @cached_property
    def type_table(self) -> np.ndarray:
        """(period * period,) cell type at residue ``(x % period) + period * (y % period)``, -1: none."""
        out = np.full(self.period * self.period, -1, dtype=np.int64)
        for r, (x, y) in enumerate(np.asarray(self.roots, dtype=np.int64).tolist()):
            out[y * self.period + x] = r
        return out

    def cell_type(self, c: np.ndarray) -> np.ndarray:
        """Type index of each centre (k, 2) (ValueError-free: -1 for a non-centre)."""
        c = np.asarray(c, dtype=np.int64).reshape(-1, 2)
        m = np.mod(c, self.period)
        return self.type_table[m[:, 1] * self.period + m[:, 0]]

    def is_cell(self, c: np.ndarray) -> np.ndarray:
        return self.cell_type(c) >= 0

    def is_translation(self, t: np.ndarray) -> np.ndarray:
        """Whether each vector ``(..., 2)`` is a translation of the grid (in ``period * Z^2``).

        The grid's symmetries are exactly ``x -> g x + t`` with g in ``group`` and t such a
        vector (each g maps the grid onto itself about the origin, and ``period`` is the least
        period): they map every cell onto a cell of the same shape, and on the grids drawn
        through ``vertex_shift`` they are the only maps of fine coordinates that are isometries.
        A polyform's copies on the grid are its images under these maps.
        """
        return (np.mod(np.asarray(t, dtype=np.int64), self.period) == 0).all(axis=-1)

    def neighbours_of(self, c: tuple[int, int]) -> np.ndarray:
        t = int(self.cell_type(np.array([c]))[0])
        if t < 0:
            raise ParameterError(f"{c} is not a cell centre of the {self.name} grid")
        return np.asarray(c, dtype=np.int64)[None] + self.neighbours[t]

    def xy(self, pts: np.ndarray) -> np.ndarray:
        return np.asarray(pts, dtype=float) @ self.to_xy.T

    def vertices_of(self, c: np.ndarray) -> np.ndarray:
        """(k, V, 2) fine vertices of each cell (a type with fewer repeats its last vertex)."""
        c = np.asarray(c, dtype=np.int64).reshape(-1, 2)
        t = self.cell_type(c)
        return c[:, None, :] + self.vertices[t]

    @cached_property
    def degrees(self) -> np.ndarray:
        """(R,) the number of edges of each cell type."""
        if self.degree is None:
            return np.full(len(self.roots), self.vertices.shape[1], dtype=np.int64)
        return np.asarray(self.degree, dtype=np.int64)

    def vertex_xy(self, pts: np.ndarray) -> np.ndarray:
        """Exact Cartesian position of fine *vertices* (the linear map plus ``vertex_shift``)."""
        p = np.asarray(pts, dtype=np.int64)
        out = self.xy(p)
        if self.vertex_shift is not None:
            m = np.mod(p, self.period)
            out = out + self.vertex_shift[m[..., 0], m[..., 1]]
        return out

    def cell_polygons(self, cells: np.ndarray) -> list[np.ndarray]:
        """Each cell's polygon, counter-clockwise, in exact Cartesian coordinates."""
        c = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
        t = self.cell_type(c)
        if (t < 0).any():
            bad = c[t < 0][0].tolist()
            raise GeometryError(f"{tuple(bad)} is not a cell centre of the {self.name} grid")
        deg = self.degrees
        return [self.vertex_xy(ci + self.vertices[ti][: deg[ti]]) for ci, ti in zip(c, t)]

    def describe_cells(self) -> str:
        """The cell centres as text: their residues modulo the period (for error messages)."""
        res = ", ".join(f"({x}, {y})" for x, y in self.roots.tolist())
        return f"cell centres of the {self.name} grid are (x, y) = one of {res} modulo {self.period}"


def _rot_group(r: np.ndarray, s: np.ndarray, order: int) -> tuple[np.ndarray, tuple[str, ...]]:
    mats, names = [], []
    m = np.eye(2, dtype=np.int64)
    for k in range(order):
        mats.append(m.copy())
        names.append(f"r{k}")
        m = r @ m
    m = s.copy()
    for k in range(order):
        mats.append(m.copy())
        names.append(f"s{k}")
        m = r @ m
    return np.array(mats, dtype=np.int64), tuple(names)


_SQ_G, _SQ_N = _rot_group(np.array([[0, -1], [1, 0]]), np.array([[1, 0], [0, -1]]), 4)
_TR_R = np.array([[0, -1], [1, 1]])  # 60 degrees in the (u, v) basis: u -> v, v -> v - u
_TR_S = np.array([[0, 1], [1, 0]])  # the mirror through the 30-degree line: u <-> v
_HX_G, _HX_N = _rot_group(_TR_R, _TR_S, 6)
_UV = np.array([[1.0, 0.5], [0.0, math.sqrt(3) / 2]]) / 3.0

SQUARE = Grid(
    "square", 2,
    roots=np.array([[1, 1]]),
    neighbours=np.array([[[2, 0], [0, 2], [-2, 0], [0, -2]]]),
    vertices=np.array([[[-1, -1], [1, -1], [1, 1], [-1, 1]]]),
    edge_dirs=np.array([[2, 0], [0, 2], [-2, 0], [0, -2]]),
    group=_SQ_G, group_names=_SQ_N, to_xy=np.eye(2) / 2.0, cell_name="omino",
    shapes=("square",), aliases=("omino",), hole_min=7,
    reference="polyominoes: OEIS A000105 (free), A001168 (fixed), A001419 (with holes)",
)

HEXAGONAL = Grid(
    "hex", 3,
    roots=np.array([[0, 0]]),
    neighbours=np.array([[[3, 0], [0, 3], [-3, 3], [-3, 0], [0, -3], [3, -3]]]),
    vertices=np.array([[[1, 1], [-1, 2], [-2, 1], [-1, -1], [1, -2], [2, -1]]]),
    edge_dirs=np.array([[-2, 1], [-1, -1], [1, -2], [2, -1], [1, 1], [-1, 2]]),
    group=_HX_G, group_names=_HX_N, to_xy=_UV / math.sqrt(1 / 3) * 1.0 / 1.0, cell_name="hex",
    shapes=("hexagon",), aliases=("hexagonal",), hole_min=3,
    reference="polyhexes: OEIS A000228 (free), A001207 (fixed), A038144 (free, with holes)",
)

TRIANGULAR = Grid(
    "iamond", 3,
    roots=np.array([[1, 1], [2, 2]]),
    neighbours=np.array([[[1, 1], [-2, 1], [1, -2]], [[-1, -1], [2, -1], [-1, 2]]]),
    vertices=np.array([[[-1, -1], [2, -1], [-1, 2]], [[1, -2], [1, 1], [-2, 1]]]),
    edge_dirs=np.array([[3, 0], [0, 3], [-3, 3], [-3, 0], [0, -3], [3, -3]]),
    group=_HX_G, group_names=_HX_N, to_xy=_UV * 1.0, cell_name="iamond",
    shapes=("triangle", "triangle"), aliases=("triangular",), hole_min=3,
    reference="polyiamonds: OEIS A000577 (free), A001420 (fixed), A070764 (free, with holes)",
)


# --------------------------------------------------------------------------- grids from cell tables

def _angle_order(v: np.ndarray) -> np.ndarray:
    return np.argsort(np.mod(np.arctan2(v[:, 1], v[:, 0]), 2 * math.pi), kind="stable")


def grid_from_cells(name: str, period: int, cells: list[tuple[str, tuple[int, int], list[tuple[int, int]]]],
                    symmetry: str, to_xy: np.ndarray, *, cell_name: str, aliases: tuple[str, ...] = (),
                    regular: tuple[int, float] | None = None, reference: str = "") -> Grid:
    """A :class:`Grid` from one table: a few prototype cells (shape name, an integer reference
    point inside the cell, its vertices counter-clockwise, all in fine coordinates), the point
    group (``"square"``: the 8 symmetries of Z^2, ``"hex"``: the 12 of the triangular lattice,
    both about the origin) and ``period`` (the translations are ``period * Z^2``).

    Everything else is derived: the cell types are the images of the prototypes under the
    group, reduced modulo the period; the edge neighbours are the cells sharing each edge
    (found geometrically: the cell holding the reversed edge); the edge directions are the
    distinct edge vectors. ``regular = (i, inradius)`` draws prototype i as a regular polygon
    of that Cartesian inradius (a vertex shift per residue class), for grids whose regular
    drawing has no integer coordinates (4.8.8, 4.6.12). A table that does not describe an
    edge-to-edge tiling (an edge with no twin, two cells on one residue) raises ValueError.
    """
    if symmetry == "square":
        group, names = _SQ_G, _SQ_N
    elif symmetry == "hex":
        group, names = _HX_G, _HX_N
    else:
        raise ValueError(f"grid {name}: symmetry must be 'square' or 'hex', not {symmetry!r}")
    P = period
    types: dict[tuple[int, int], tuple[str, np.ndarray]] = {}
    for shape, centre, verts in cells:
        c = np.array(centre, dtype=np.int64)
        vs = np.array(verts, dtype=np.int64) - c
        for m in group:
            gc, gv = m @ c, vs @ m.T
            if np.linalg.det(m) < 0:
                gv = gv[::-1]
            res = tuple(int(v) for v in np.mod(gc, P))
            if res in types:
                old = types[res]
                same = old[0] == shape and {tuple(v) for v in old[1].tolist()} == {tuple(v) for v in gv.tolist()}
                if not same:
                    raise ValueError(f"grid {name}: two different cells on residue {res}")
                continue
            types[res] = (shape, gv)
    roots = np.array(list(types), dtype=np.int64)
    shapes = tuple(types[tuple(r)][0] for r in roots.tolist())
    vlists = [types[tuple(r)][1] for r in roots.tolist()]
    deg = np.array([len(v) for v in vlists], dtype=np.int64)
    V = int(deg.max())
    # every directed edge (absolute, of the cells near the origin) -> its cell
    span = range(-2, 3)
    owner: dict[tuple, tuple[int, int]] = {}
    for root, vs in zip(roots, vlists):
        for i in span:
            for j in span:
                c = root + P * np.array([i, j])
                pts = c + vs
                for k in range(len(pts)):
                    a, b = pts[k], pts[(k + 1) % len(pts)]
                    owner[(*a.tolist(), *b.tolist())] = tuple(c.tolist())
    nbrs = np.zeros((len(roots), V, 2), dtype=np.int64)
    verts_out = np.zeros((len(roots), V, 2), dtype=np.int64)
    dirs: set[tuple[int, int]] = set()
    for r, (root, vs) in enumerate(zip(roots, vlists)):
        pts = root + vs
        for k in range(len(pts)):
            a, b = pts[k], pts[(k + 1) % len(pts)]
            twin = owner.get((*b.tolist(), *a.tolist()))
            if twin is None:
                raise ValueError(f"grid {name}: edge {a.tolist()}-{b.tolist()} of cell {root.tolist()} has no twin")
            nbrs[r, k] = np.array(twin) - root
            dirs.add(tuple((b - a).tolist()))
        nbrs[r, len(pts):] = nbrs[r, len(pts) - 1]
        verts_out[r, : len(pts)] = vs
        verts_out[r, len(pts):] = vs[-1]
    d = np.array(sorted(dirs), dtype=np.int64)
    d = d[_angle_order(d.astype(float) @ to_xy.T)]
    shift = None
    if regular is not None:
        shift = _regular_shift(group, to_xy, P, roots, vlists, *regular)
    return Grid(name, P, roots=roots, neighbours=nbrs, vertices=verts_out, edge_dirs=d, group=group,
                group_names=names, to_xy=to_xy, cell_name=cell_name, degree=deg, shapes=shapes,
                aliases=aliases, vertex_shift=shift, hole_min=1, reference=reference)


def _regular_shift(group, to_xy, P, roots, vlists, which: int, inradius: float) -> np.ndarray:
    """The vertex shift table drawing cell type ``which`` as a regular polygon (the vertices'
    directions from its centre snapped to the regular k-gon's), spread over every vertex
    residue class by the group."""
    root, vs = roots[which], vlists[which]
    k = len(vs)
    lin = vs.astype(float) @ to_xy.T
    ang = np.arctan2(lin[:, 1], lin[:, 0])
    step = math.pi / k
    snapped = (2 * np.round((ang / step - 1) / 2) + 1) * step
    exact = (inradius / math.cos(step)) * np.column_stack([np.cos(snapped), np.sin(snapped)])
    inv = np.linalg.inv(to_xy)
    shift = np.full((P, P, 2), np.nan)
    for m in group:
        cart = to_xy @ m @ inv  # the group element as a Cartesian isometry
        for v, e in zip(vs, exact):
            gv = m @ (root + v)
            off = cart @ e - to_xy @ (m @ v)
            res = tuple(np.mod(gv, P).tolist())
            if np.isnan(shift[res]).any():
                shift[res] = off
            elif not np.allclose(shift[res], off):
                raise ValueError(f"regular drawing is not consistent at vertex residue {res}")
    for r, vl in zip(roots, vlists):
        for v in vl:
            res = tuple(np.mod(r + v, P).tolist())
            if np.isnan(shift[res]).any():
                raise ValueError(f"regular drawing: vertex residue {res} is on no regular cell")
    return np.nan_to_num(shift)


# The grids of Kaplan's heesch-sat beyond the three above, each one table (shape, reference
# point, vertices counter-clockwise, in fine coordinates); the tests check that the cells
# tile the plane (no gap, no overlap), that neighbours share a full edge, and the counts.
KITE = grid_from_cells(
    "kite", 6,
    # the deltoidal trihexagonal tiling (dual of 3.4.6.4): each hexagon (centres 6 Z^2 in the
    # 60-degree basis) cut into six kites from its centre to two edge midpoints and a corner
    [("kite", (1, 1), [(0, 0), (3, 0), (2, 2), (0, 3)])],
    "hex", _UV / 2.0, cell_name="kite",
    reference="polykites: OEIS A057786 (free)",
)

OCTASQUARE = grid_from_cells(
    "octasquare", 4,
    # the truncated square tiling 4.8.8: octagons centred on 4 Z^2, squares between them
    [("octagon", (0, 0), [(2, -1), (2, 1), (1, 2), (-1, 2), (-2, 1), (-2, -1), (-1, -2), (1, -2)]),
     ("square", (2, 2), [(2, 1), (3, 2), (2, 3), (1, 2)])],
    "square", np.eye(2) / 4.0, cell_name="octasquare", regular=(0, 0.5),
    reference="poly-(4.8.8) octasquare forms: Kaplan's heesch-sat (-octasquare)",
)

TRIHEX = grid_from_cells(
    "trihex", 6,
    # the trihexagonal tiling 3.6.3.6: hexagons centred on 6 Z^2, two triangles per hexagon
    [("hexagon", (0, 0), [(3, 0), (0, 3), (-3, 3), (-3, 0), (0, -3), (3, -3)]),
     ("triangle", (2, 2), [(3, 0), (3, 3), (0, 3)])],
    "hex", _UV / 2.0, cell_name="trihex",
    reference="poly-(3.6.3.6) trihex forms: Kaplan's heesch-sat (-trihex)",
)

DRAFTER = grid_from_cells(
    "drafter", 18,
    # the kisrhombille tiling (dual of 4.6.12): each hexagon (centres 18 Z^2) cut into twelve
    # 30-60-90 triangles from its centre, an edge midpoint and a corner
    [("drafter", (5, 2), [(0, 0), (9, 0), (6, 6)])],
    "hex", _UV / 6.0, cell_name="drafter",
    reference="polydrafters on the kisrhombille grid: Kaplan's heesch-sat (-drafter)",
)

ABOLO = grid_from_cells(
    "abolo", 6,
    # the tetrakis square tiling (dual of 4.8.8): each square (centres 6 Z^2) cut by its
    # diagonals into four right isosceles triangles
    [("abolo", (0, -2), [(-3, -3), (3, -3), (0, 0)])],
    "square", np.eye(2) / 6.0, cell_name="abolo",
    reference="polyaboloes on the tetrakis square grid: Kaplan's heesch-sat (-abolo)",
)

HALFCAIRO = grid_from_cells(
    "halfcairo", 12,
    # each square of side 12 around a hub (12 Z^2) cut into four triangles (hub and a side's
    # middle third) and four corner quadrilaterals; two of each make a Cairo pentagon
    [("triangle", (4, 0), [(0, 0), (6, -3), (6, 3)]),
     ("quadrilateral", (4, 4), [(0, 0), (6, 3), (6, 6), (3, 6)])],
    "square", np.eye(2) / 12.0, cell_name="halfcairo",
    reference="half-Cairo cells: Kaplan's heesch-sat (-halfcairo)",
)

BEVELHEX = grid_from_cells(
    "bevelhex", 6,
    # the truncated trihexagonal tiling 4.6.12: dodecagons centred on 6 Z^2 (60-degree basis),
    # hexagons at the triangle centres, squares at the edge midpoints
    [("dodecagon", (0, 0), [(2, 1), (1, 2), (-1, 3), (-2, 3), (-3, 2), (-3, 1),
                            (-2, -1), (-1, -2), (1, -3), (2, -3), (3, -2), (3, -1)]),
     ("hexagon", (2, 2), [(2, 1), (3, 1), (3, 2), (2, 3), (1, 3), (1, 2)]),
     ("square", (3, 0), [(3, -1), (4, -1), (3, 1), (2, 1)])],
    "hex", _UV / 2.0, cell_name="bevelhex", regular=(0, (2 + math.sqrt(3)) / (2 * (3 + math.sqrt(3)))),
    reference="poly-(4.6.12) bevelhex forms: Kaplan's heesch-sat (-bevelhex)",
)

GRIDS = {g.name: g for g in (SQUARE, HEXAGONAL, TRIANGULAR, KITE, OCTASQUARE, TRIHEX, DRAFTER, ABOLO,
                             HALFCAIRO, BEVELHEX)}
_ALIASES = {a: g for g in GRIDS.values() for a in g.aliases}


def get_grid(name: str | Grid) -> Grid:
    """A grid by name (``square``, ``hex``, ``iamond``, ``kite``, ...; or an alias such as
    ``hexagonal``); NotFoundError lists the grids."""
    if isinstance(name, Grid):
        return name
    key = str(name).strip().lower()
    if key in GRIDS:
        return GRIDS[key]
    if key in _ALIASES:
        return _ALIASES[key]
    err = NotFoundError("grid", str(name), list(GRIDS))
    err.args = (f"{err.args[0].split(';')[0]}; grids: {', '.join(GRIDS)}",)
    raise err


# --------------------------------------------------------------------------- canonical forms

def _order_key(cells: np.ndarray) -> np.ndarray:
    return np.lexsort((cells[:, 0], cells[:, 1]))


def fixed_form(grid: Grid, cells: np.ndarray) -> np.ndarray:
    """The translation-canonical form: sorted by (y, x), the least cell moved into [0, p)^2."""
    c = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    c = c[_order_key(c)]
    c0 = c[0]
    t = c0 - np.mod(c0, grid.period)
    return c - t


def _key(cells: np.ndarray) -> tuple:
    """Order of forms: the (y, x) pairs in (y, x) order, compared lexicographically (the compiled
    canonical test uses the same order, so both pick the same representative)."""
    return tuple((y, x) for x, y in cells.tolist())


def images(grid: Grid, cells: np.ndarray, which: str = "free") -> list[np.ndarray]:
    idx = range(len(grid.group)) if which == "free" else range(grid.rotation_order) if which == "one-sided" else [0]
    return [fixed_form(grid, np.asarray(cells) @ grid.group[g].T) for g in idx]


def canonical(grid: Grid, cells: np.ndarray, which: str = "free") -> np.ndarray:
    """The canonical cells of a polyform under ``which`` in {'free', 'one-sided', 'fixed'}.

    The minimum, by the sorted tuple of centres, over the images under the rotations and
    reflections (free), rotations (one-sided) or identity (fixed), each in fixed form.
    """
    if which not in ("free", "one-sided", "fixed"):
        raise ParameterError(f"equivalence must be free, one-sided or fixed, not {which!r}")
    return min(images(grid, cells, which), key=_key)


def symmetry_elements(grid: Grid, cells: np.ndarray) -> list[int]:
    """Indices of the point-group elements mapping the polyform onto a translate of itself."""
    base = _key(fixed_form(grid, cells))
    return [g for g, im in enumerate(images(grid, cells, "free")) if _key(im) == base]


def symmetry_name(grid: Grid, elements: list[int]) -> str:
    """Schoenflies-style name of a polyform's own point group: C1, C2, C4, D1, D2, D4, C3, C6, D3, D6."""
    k = len(elements)
    refl = any(grid.det[g] < 0 for g in elements)
    return f"D{k // 2}" if refl else f"C{k}"


# --------------------------------------------------------------------------- validation, holes

def as_cells(grid: Grid, cells) -> np.ndarray:
    """Validate a cell list: non-empty, cell centres of the grid, distinct, edge-connected."""
    try:
        c = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    except (TypeError, ValueError):
        raise ParseError(f"cells must be (x, y) integer pairs, got {cells!r}") from None
    if len(c) == 0:
        raise GeometryError("a polyform needs at least one cell; the cell set is empty")
    if not grid.is_cell(c).all():
        bad = c[~grid.is_cell(c)][0].tolist()
        raise GeometryError(f"cell {tuple(bad)} is not a cell centre of the {grid.name} grid ({grid.describe_cells()})")
    keys = {tuple(p) for p in c.tolist()}
    if len(keys) != len(c):
        seen_once: set[tuple] = set()
        rep = next(k for k in map(tuple, c.tolist()) if k in seen_once or seen_once.add(k))
        raise GeometryError(f"a polyform's cells must be distinct: cell {rep} is repeated")
    seen = {tuple(c[0].tolist())}
    stack = [c[0]]
    while stack:
        p = stack.pop()
        for q in grid.neighbours_of(tuple(p.tolist())):
            k = tuple(q.tolist())
            if k in keys and k not in seen:
                seen.add(k)
                stack.append(q)
    if len(seen) != len(keys):
        lost = next(k for k in map(tuple, c.tolist()) if k not in seen)
        raise GeometryError(
            f"the cells are disconnected: cell {lost} is not edge-connected to cell "
            f"{tuple(c[0].tolist())} ({len(seen)} of {len(keys)} cells are)"
        )
    return c


def holes(grid: Grid, cells: np.ndarray) -> list[np.ndarray]:
    """The holes: edge-connected components of empty cells not connected to the outside."""
    c = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    return [unpack(h) for h in holes_of(grid, pack(c))]


def _components(grid: Grid, cells: np.ndarray):
    c = np.ascontiguousarray(np.asarray(cells, dtype=np.int64).reshape(-1, 2))
    return _empty_components(c, grid.type_table, grid.neighbours.astype(np.int64), np.int64(grid.period))


def hole_count(grid: Grid, cells: np.ndarray) -> int:
    """``len(holes(grid, cells))`` by the compiled flood fill (the bulk enumeration's hole column)."""
    return int(_components(grid, cells)[4]) - 1


@njit(cache=True)
def _empty_components(c, at, nbr, period):
    """Edge-connected components of the empty cells in the bounding box of ``c`` plus a margin
    of two periods: (label per box position, -1 where no empty cell; x0, y0, w, count).
    Label 0 is the outside (every component reaching beyond one period of the cells; holes
    never do); labels 1.. are the holes."""
    n = c.shape[0]
    x0 = c[0, 0]
    x1 = x0
    y0 = c[0, 1]
    y1 = y0
    for k in range(n):
        x0 = min(x0, c[k, 0])
        x1 = max(x1, c[k, 0])
        y0 = min(y0, c[k, 1])
        y1 = max(y1, c[k, 1])
    # the inner box: within one period of the cells; every empty cell beyond it is outside
    ix0 = x0 - period
    ix1 = x1 + period
    iy0 = y0 - period
    iy1 = y1 + period
    m = 2 * period
    x0 = x0 - (x0 % period) - m
    y0 = y0 - (y0 % period) - m
    x1 = x1 - (x1 % period) + m + period - 1
    y1 = y1 - (y1 % period) + m + period - 1
    w = x1 - x0 + 1
    h = y1 - y0 + 1
    # -1: not a cell centre, 0: empty, 1: filled, 2: visited
    buf = np.full(w * h, -1, np.int64)
    typ = np.zeros(w * h, np.int64)
    # ``at``: the cell type at each residue modulo the period, -1: no cell centre (Grid.type_table)
    for yy in range(y0, y1 + 1):
        row = (yy % period) * period
        for xx in range(x0, x1 + 1):
            r = at[row + xx % period]
            if r >= 0:
                buf[(yy - y0) * w + xx - x0] = 0
                typ[(yy - y0) * w + xx - x0] = r
    for k in range(n):
        buf[(c[k, 1] - y0) * w + c[k, 0] - x0] = 1
    stack = np.zeros(w * h, np.int64)
    lab = np.full(w * h, -1, np.int64)
    comps = 0
    for v in range(w * h):
        if buf[v] != 0:
            continue
        buf[v] = 2
        lab[v] = comps
        stack[0] = v
        top = 1
        while top > 0:
            top -= 1
            p = stack[top]
            px = p % w + x0
            py = p // w + y0
            t = typ[p]
            for j in range(nbr.shape[1]):
                qx = px + nbr[t, j, 0]
                qy = py + nbr[t, j, 1]
                if qx < x0 or qx > x1 or qy < y0 or qy > y1:
                    continue
                q = (qy - y0) * w + (qx - x0)
                if buf[q] == 0:
                    buf[q] = 2
                    lab[q] = comps
                    stack[top] = q
                    top += 1
        comps += 1
    # a component with a cell outside the inner box is the outside (label 0; on grids whose
    # cells at the box's far edge have all their neighbours beyond it, such cells come out as
    # components of their own); the others, renumbered 1.., are the holes
    outside = np.zeros(comps, np.uint8)
    for v in range(w * h):
        if lab[v] >= 0:
            px = v % w + x0
            py = v // w + y0
            if px < ix0 or px > ix1 or py < iy0 or py > iy1:
                outside[lab[v]] = 1
    new = np.zeros(comps, np.int64)
    k = 1
    for i in range(comps):
        if outside[i] == 0:
            new[i] = k
            k += 1
    for v in range(w * h):
        if lab[v] >= 0:
            lab[v] = new[lab[v]]
    return lab, x0, y0, w, k


# --------------------------------------------------------------------------- boundary

def boundary_cycles(grid: Grid, cells: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """Every boundary cycle as (vertices (k, 2), letters (k,)), counter-clockwise for the outer one.

    Interior on the left; at a vertex where two cycles touch (a hole meeting the outside
    at a corner), the traversal turns right first, so the two cycles come out separate.
    """
    c = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    keys = {tuple(p) for p in c.tolist()}
    t = grid.cell_type(c)
    ea, eb, en, _ = _edge_tables(grid)
    out_edges: dict[tuple, list[tuple]] = {}
    for ci, ti in zip(c, t):
        for k in range(int(grid.degrees[ti])):
            if tuple((ci + en[ti, k]).tolist()) in keys:
                continue
            out_edges.setdefault(tuple((ci + ea[ti, k]).tolist()), []).append(tuple((ci + eb[ti, k]).tolist()))
    dirs = grid.edge_dirs
    angle = np.arctan2(*(grid.xy(dirs)[:, ::-1].T))
    cycles = []
    used: set[tuple] = set()
    for start in sorted(out_edges, key=lambda p: (p[1], p[0])):
        for nxt in out_edges[start]:
            if (start, nxt) in used:
                continue
            verts, letters = [], []
            a, b = start, nxt
            while (a, b) not in used:
                used.add((a, b))
                verts.append(a)
                d = np.subtract(b, a)
                e = int(np.nonzero((dirs == d).all(axis=1))[0][0])
                letters.append(e)
                choices = [q for q in out_edges[b] if (b, q) not in used]
                if not choices:
                    break
                if len(choices) > 1:
                    def turn(q, e=e, b=b):
                        e2 = int(np.nonzero((dirs == np.subtract(q, b)).all(axis=1))[0][0])
                        return (angle[e2] - angle[e] + math.pi) % (2 * math.pi)
                    choices.sort(key=turn)
                a, b = b, choices[0]
            cycles.append((np.array(verts, dtype=np.int64), np.array(letters, dtype=np.int64)))
    cycles.sort(key=lambda cyc: -_signed_area(grid.xy(cyc[0])))
    return cycles


def _across(grid: Grid, r: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Offset of the neighbour across the edge (a, b) (offsets from a root of type r): the
    neighbour whose own vertex list holds the edge reversed (exact, no distances)."""
    root = grid.roots[r]
    for off in grid.neighbours[r]:
        q = root + off
        t = int(grid.cell_type(q[None])[0])
        vs = (q + grid.vertices[t][: grid.degrees[t]] - root).tolist()
        k = len(vs)
        for i in range(k):
            if vs[i] == b.tolist() and vs[(i + 1) % k] == a.tolist():
                return off
    raise GeometryError(f"the {grid.name} grid's tables have no neighbour across edge {a.tolist()}-{b.tolist()}")


def _signed_area(p: np.ndarray) -> float:
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def boundary_word(grid: Grid, cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The outer boundary: (vertices, letters), counter-clockwise from the least vertex.

    Hole-free polyforms (one simple boundary cycle) are traced in compiled code; others
    through :func:`boundary_cycles`.
    """
    c = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    ea, eb, en, el = _edge_tables(grid)
    out_v = np.zeros((8 * len(c) + 8, 2), np.int64)
    out_l = np.zeros(8 * len(c) + 8, np.int64)
    types = grid.cell_type(c)
    m = _trace(c, types, ea, eb, en, el, np.int64(grid.period), out_v, out_l)
    if m <= 0 and (types >= 0).all():
        # holes or a pinch vertex: the outer cycle as boundary_cycles traces it, compiled
        m = _trace_outer(c, types, ea, eb, en, el, np.int64(grid.period), _turn_table(grid), out_v, out_l)
    if m > 0:
        return out_v[:m].copy(), out_l[:m].copy()
    return boundary_cycles(grid, cells)[0]


_TURN_CACHE: dict[str, np.ndarray] = {}


def _turn_table(grid: Grid) -> np.ndarray:
    """turn[e, e2]: boundary_cycles' preference for leaving a vertex by e2 after arriving by e
    (smaller first: the sharpest right turn)."""
    if grid.name not in _TURN_CACHE:
        angle = np.arctan2(*(grid.xy(grid.edge_dirs)[:, ::-1].T))
        E = len(angle)
        t = np.zeros((E, E))
        for e in range(E):
            for e2 in range(E):
                t[e, e2] = (angle[e2] - angle[e] + math.pi) % (2 * math.pi)
        _TURN_CACHE[grid.name] = t
    return _TURN_CACHE[grid.name]


@njit(cache=True)
def _occupancy(c, period):
    """The cells ``c`` as a 0/1 raster with a margin of two periods: (raster, x0, y0, w, h),
    cell (x, y) at index (y - y0) * w + x - x0."""
    n = c.shape[0]
    x0 = c[0, 0]
    y0 = c[0, 1]
    x1 = x0
    y1 = y0
    for i in range(n):
        x0 = min(x0, c[i, 0])
        y0 = min(y0, c[i, 1])
        x1 = max(x1, c[i, 0])
        y1 = max(y1, c[i, 1])
    m = 2 * period
    x0 -= m
    y0 -= m
    w = x1 - x0 + m + 1
    h = y1 - y0 + m + 1
    occ = np.zeros(w * h, np.uint8)
    for i in range(n):
        occ[(c[i, 1] - y0) * w + c[i, 0] - x0] = 1
    return occ, x0, y0, w, h


@njit(cache=True)
def _trace_outer(c, types, ea, eb, en, el, period, turn, out_v, out_l):
    """The outer boundary cycle, exactly as :func:`boundary_cycles` returns it first: from the
    least vertex (y, x), interior on the left, the sharpest right turn at a vertex where
    cycles touch. Returns its length (-1 if more than six edges leave one vertex)."""
    n = c.shape[0]
    occ, x0, y0, w, h = _occupancy(c, period)
    S = 6
    nout = np.zeros(w * h, np.int64)
    nxt = np.full((w * h, S), -1, np.int64)
    let = np.zeros((w * h, S), np.int64)
    used = np.zeros((w * h, S), np.uint8)
    for i in range(n):
        t = types[i]
        for k in range(ea.shape[1]):
            qx = c[i, 0] + en[t, k, 0]
            qy = c[i, 1] + en[t, k, 1]
            if occ[(qy - y0) * w + qx - x0] == 1:
                continue
            a = (c[i, 1] + ea[t, k, 1] - y0) * w + c[i, 0] + ea[t, k, 0] - x0
            b = (c[i, 1] + eb[t, k, 1] - y0) * w + c[i, 0] + eb[t, k, 0] - x0
            if nout[a] == S:
                return -1
            nxt[a, nout[a]] = b
            let[a, nout[a]] = el[t, k]
            nout[a] += 1
    start = -1
    for v in range(w * h):  # row by row: the least (y, x)
        if nout[v] > 0:
            start = v
            break
    a = start
    j = 0
    cnt = 0
    while used[a, j] == 0:
        used[a, j] = 1
        out_v[cnt, 0] = a % w + x0
        out_v[cnt, 1] = a // w + y0
        e = let[a, j]
        out_l[cnt] = e
        cnt += 1
        b = nxt[a, j]
        best = -1
        for j2 in range(nout[b]):
            if used[b, j2] == 0 and (best < 0 or turn[e, let[b, j2]] < turn[e, let[b, best]]):
                best = j2
        if best < 0:
            break
        a = b
        j = best
    return cnt


_EDGE_CACHE: dict[str, tuple] = {}


def _edge_tables(grid: Grid):
    """Per cell type and edge: start and end vertex offsets, neighbour offset, letter."""
    if grid.name not in _EDGE_CACHE:
        R, V = grid.vertices.shape[:2]
        ea = np.zeros((R, V, 2), np.int64)
        eb = np.zeros((R, V, 2), np.int64)
        en = np.zeros((R, V, 2), np.int64)  # padding edges (a type with < V) point at the cell itself
        el = np.zeros((R, V), np.int64)
        for r in range(R):
            k_r = int(grid.degrees[r])
            for k in range(k_r):
                a, b = grid.vertices[r, k], grid.vertices[r, (k + 1) % k_r]
                ea[r, k], eb[r, k], en[r, k] = a, b, _across(grid, r, a, b)
                el[r, k] = int(np.nonzero((grid.edge_dirs == b - a).all(axis=1))[0][0])
            ea[r, k_r:] = eb[r, k_r:] = grid.vertices[r, 0]
        _EDGE_CACHE[grid.name] = (ea, eb, en, el)
    return _EDGE_CACHE[grid.name]


@njit(cache=True)
def _trace(c, types, ea, eb, en, el, period, out_v, out_l):
    """Trace the single boundary cycle; returns its length, or -1 if there is more than one."""
    n = c.shape[0]
    occ, x0, y0, w, h = _occupancy(c, period)
    nxt = np.full(w * h, -1, np.int64)
    let = np.zeros(w * h, np.int64)
    edges = 0
    for i in range(n):
        t = types[i]
        for k in range(ea.shape[1]):
            qx = c[i, 0] + en[t, k, 0]
            qy = c[i, 1] + en[t, k, 1]
            if occ[(qy - y0) * w + qx - x0] == 1:
                continue
            a = (c[i, 1] + ea[t, k, 1] - y0) * w + c[i, 0] + ea[t, k, 0] - x0
            b = (c[i, 1] + eb[t, k, 1] - y0) * w + c[i, 0] + eb[t, k, 0] - x0
            if nxt[a] != -1:
                return -1  # a pinch vertex: not a simple boundary
            nxt[a] = b
            let[a] = el[t, k]
            edges += 1
    start = -1
    for v in range(w * h):
        if nxt[v] != -1:
            start = v
            break
    v = start
    cnt = 0
    while True:
        out_v[cnt, 0] = v % w + x0
        out_v[cnt, 1] = v // w + y0
        out_l[cnt] = let[v]
        cnt += 1
        v = nxt[v]
        if v == start or cnt > edges:
            break
    if cnt != edges:
        return -1
    return cnt


#: The letters of boundary words as text: digits, then lower- and upper-case letters.
WORD_ALPHABET = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"


def word_text(letters) -> str:
    """A boundary word as text, one character per letter (0-9, then a-z, A-Z)."""
    a = np.asarray(letters, dtype=np.int64)
    if a.size and (a.min() < 0 or a.max() >= len(WORD_ALPHABET)):
        raise ValueError(f"boundary letters must be 0-{len(WORD_ALPHABET) - 1}, got {a.tolist()}")
    return "".join(WORD_ALPHABET[i] for i in a.tolist())


def outline(grid: Grid, cells: np.ndarray, name: str = ""):
    """The polyform's outer outline as a Prototile (corners only, Cartesian coordinates)."""

    verts, letters = boundary_word(grid, cells)
    keep = letters != np.roll(letters, 1)
    return Prototile(grid.vertex_xy(verts[keep]), name=name)


# --------------------------------------------------------------------------- Redelmeier

def redelmeier_board(grid: Grid, n: int, root: int) -> tuple[np.ndarray, np.ndarray]:
    """Cells reachable in < n steps from the root among cells after it in (y, x) order.

    Returns (centres (B, 2), neighbour table (B, D) of board indices, -1 for none). Board
    cell 0 is the root; the index order (breadth-first, neighbours in table order) is
    deterministic, so a path of choices names the same search-tree node in every process.
    """
    r = grid.roots[root]
    index = {tuple(r.tolist()): 0}
    cells = [r]
    dist = [0]
    head = 0
    while head < len(cells):
        p = cells[head]
        if dist[head] < n - 1:
            for q in p + grid.neighbours[int(grid.cell_type(p[None])[0])]:
                if q[1] < r[1] or (q[1] == r[1] and q[0] < r[0]):
                    continue
                k = tuple(q.tolist())
                if k not in index:
                    index[k] = len(cells)
                    cells.append(q)
                    dist.append(dist[head] + 1)
        head += 1
    cells_a = np.array(cells, dtype=np.int64)
    types = grid.cell_type(cells_a)
    nb = np.full((len(cells), grid.neighbours.shape[1]), -1, dtype=np.int64)
    for i, (p, ti) in enumerate(zip(cells_a, types)):
        for j, q in enumerate(p + grid.neighbours[ti]):
            nb[i, j] = index.get(tuple(q.tolist()), -1)
    return cells_a, nb


@njit(cache=True)
def _canon_check(poly, size, bx, by, mats, period, keys, tmp):
    """True if the fixed polyform (board indices poly[:size]) is the least image of its class.

    Also returns the bitmask of the group elements whose image equals it (its own symmetry).
    """
    ng = mats.shape[0]
    span = 8 * period * (size + 2)
    sym = 0
    for g in range(ng):
        a, b, c, d = mats[g, 0, 0], mats[g, 0, 1], mats[g, 1, 0], mats[g, 1, 1]
        # least cell in (y, x) order of the image
        mx = 0
        my = 0
        for k in range(size):
            x = bx[poly[k]]
            y = by[poly[k]]
            X = a * x + b * y
            Y = c * x + d * y
            if k == 0 or Y < my or (Y == my and X < mx):
                mx = X
                my = Y
        tx = mx - (mx % period)
        ty = my - (my % period)
        for k in range(size):
            x = bx[poly[k]]
            y = by[poly[k]]
            X = a * x + b * y - tx
            Y = c * x + d * y - ty
            v = Y * span + X
            # insertion sort into tmp
            j = k
            while j > 0 and tmp[j - 1] > v:
                tmp[j] = tmp[j - 1]
                j -= 1
            tmp[j] = v
        if g == 0:
            for k in range(size):
                keys[k] = tmp[k]
            sym = 1
        else:
            cmp = 0
            for k in range(size):
                if tmp[k] != keys[k]:
                    cmp = -1 if tmp[k] < keys[k] else 1
                    break
            if cmp < 0:
                return False, 0
            if cmp == 0:
                sym |= 1 << g
    return True, sym


@njit(cache=True)
def _has_hole(poly, size, bx, by, roots, nbr, period, grid_buf, stack, restype):
    """Flood fill of the empty cells of a bounding box (plus a margin) from its corner.
    ``restype[(y % period) * period + x % period]`` is the cell type at a position (-1: none)."""
    x0 = bx[poly[0]]
    x1 = x0
    y0 = by[poly[0]]
    y1 = y0
    for k in range(size):
        x = bx[poly[k]]
        y = by[poly[k]]
        x0 = min(x0, x)
        x1 = max(x1, x)
        y0 = min(y0, y)
        y1 = max(y1, y)
    ix0 = x0 - period  # the inner box (see _empty_components)
    ix1 = x1 + period
    iy0 = y0 - period
    iy1 = y1 + period
    m = 2 * period
    x0 = x0 - (x0 % period) - m
    y0 = y0 - (y0 % period) - m
    x1 = x1 - (x1 % period) + m + period - 1
    y1 = y1 - (y1 % period) + m + period - 1
    w = x1 - x0 + 1
    h = y1 - y0 + 1
    if w * h > grid_buf.shape[0]:
        raise ValueError("the hole test's box is larger than its buffer")
    # 0 unknown/empty, 1 filled, 2 reached-from-outside
    for i in range(w * h):
        grid_buf[i] = 0
    for k in range(size):
        grid_buf[(by[poly[k]] - y0) * w + (bx[poly[k]] - x0)] = 1
    # start: a cell centre of root type 0 in the margin row
    sx = x0 + roots[0, 0]
    sy = y0 + roots[0, 1]
    grid_buf[(sy - y0) * w + (sx - x0)] = 2
    stack[0] = (sy - y0) * w + (sx - x0)
    top = 1
    reached = 0  # reached cells of the inner box (the start, in the margin, is not one)
    while top > 0:
        top -= 1
        p = stack[top]
        px = p % w + x0
        py = p // w + y0
        t = restype[(py % period) * period + px % period]
        for j in range(nbr.shape[1]):
            qx = px + nbr[t, j, 0]
            qy = py + nbr[t, j, 1]
            if qx < x0 or qx > x1 or qy < y0 or qy > y1:
                continue
            q = (qy - y0) * w + (qx - x0)
            if grid_buf[q] == 0:
                grid_buf[q] = 2
                stack[top] = q
                top += 1
                if qx >= ix0 and qx <= ix1 and qy >= iy0 and qy <= iy1:
                    reached += 1
    # count the cell centres of the inner box: one not reached from outside is in a hole
    total = 0
    for yy in range(iy0, iy1 + 1):
        for xx in range(ix0, ix1 + 1):
            if restype[(yy % period) * period + xx % period] >= 0:
                total += 1
    return reached + size < total


@njit(cache=True)
def _redelmeier(nb, bx, by, n, prefix, plen, maxsize, mats, period, roots, nbr, hole_min, mode, out, outcap):
    """Redelmeier's algorithm over one subtree of the search tree.

    The node reached by taking choice ``prefix[d]`` (an offset into the untried list) at each
    level d < plen is the subtree root; plen = 0 is the whole tree. Nodes of size up to
    ``maxsize`` are visited. mode 0: count fixed only; mode 1: also free and holey (canonical
    check at every node); mode 2: as 1 and write each free representative's board indices
    to ``out`` (row-major, n per row) while rows < outcap; mode 3: record the paths of the
    nodes of size == maxsize (chunk generation) in ``out``.
    Returns (fixed[n+1], free[n+1], holey[n+1], rows written).
    """
    B = nb.shape[0]
    D = nb.shape[1]
    fixed = np.zeros(n + 1, np.int64)
    free = np.zeros(n + 1, np.int64)
    holey = np.zeros(n + 1, np.int64)
    seen = np.zeros(B, np.uint8)
    cap = n * (n * D + 2) + 8
    buf = np.empty(cap, np.int64)
    start = np.zeros(n + 2, np.int64)
    end = np.zeros(n + 2, np.int64)
    pos = np.zeros(n + 2, np.int64)
    newfrom = np.zeros(n + 2, np.int64)
    poly = np.zeros(n + 1, np.int64)
    keys = np.zeros(n + 1, np.int64)
    tmp = np.zeros(n + 1, np.int64)
    # the hole test's box: the cells span at most (n - 1) neighbour steps, plus the period
    # alignment and the two-period margin on each side (see _has_hole), so this side bounds it
    step = 0
    for t in range(nbr.shape[0]):
        for j in range(nbr.shape[1]):
            step = max(step, abs(nbr[t, j, 0]), abs(nbr[t, j, 1]))
    side = (n + 1) * step + 8 * period
    gbuf = np.zeros(side * side, np.int64)
    restype = np.full(period * period, -1, np.int64)
    for r in range(roots.shape[0]):
        restype[roots[r, 1] * period + roots[r, 0]] = r
    path = np.zeros(n + 1, np.int64)
    entered = np.zeros(n + 2, np.uint8)
    stack = np.empty(gbuf.shape[0], np.int64)
    rows = 0
    seen[0] = 1
    buf[0] = 0
    start[0] = 0
    end[0] = 1
    pos[0] = 0
    newfrom[0] = 0
    d = 0
    while d >= 0:
        if d < plen:
            if entered[d] == 0:
                entered[d] = 1
                pos[d] = start[d] + prefix[d]
                if pos[d] >= end[d]:
                    break
            elif pos[d] > start[d] + prefix[d]:
                break  # back from the prefix node's subtree: the chunk is done
        if pos[d] < end[d]:
            c = buf[pos[d]]
            path[d] = pos[d] - start[d]
            pos[d] += 1
            poly[d] = c
            size = d + 1
            if size >= plen:
                fixed[size] += 1
                if mode == 3 and size == maxsize:
                    if rows < outcap:
                        for k in range(size):
                            out[rows * n + k] = path[k]
                    rows += 1
                if mode == 1 or mode == 2:
                    ok, sym = _canon_check(poly, size, bx, by, mats, period, keys, tmp)
                    if ok:
                        free[size] += 1
                        hh = size >= hole_min and _has_hole(poly, size, bx, by, roots, nbr, period, gbuf, stack,
                                                            restype)
                        if hh:
                            holey[size] += 1
                        if mode == 2:
                            if rows < outcap:
                                w = n + 2
                                for k in range(size):
                                    out[rows * w + k] = poly[k]
                                for k in range(size, n):
                                    out[rows * w + k] = -1
                                out[rows * w + n] = 1 if hh else 0
                                out[rows * w + n + 1] = sym
                            rows += 1
            if size < maxsize:
                s = end[d]
                e = s
                for k in range(pos[d], end[d]):
                    buf[e] = buf[k]
                    e += 1
                nf = e
                for j in range(D):
                    q = nb[c, j]
                    if q >= 0 and seen[q] == 0:
                        seen[q] = 1
                        buf[e] = q
                        e += 1
                d += 1
                start[d] = s
                end[d] = e
                pos[d] = s
                newfrom[d] = nf
        else:
            for k in range(newfrom[d], end[d]):
                seen[buf[k]] = 0
            d -= 1
    return fixed, free, holey, rows


def _tables(grid: Grid):
    return (grid.group.astype(np.int64), np.int64(grid.period), grid.roots.astype(np.int64),
            grid.neighbours.astype(np.int64), np.int64(grid.hole_min))


def count_fixed(grid: Grid, n: int, *, free: bool = False, prefix=(), root: int | None = None,
                maxsize: int | None = None) -> dict[str, np.ndarray]:
    """Counts of fixed (and with ``free``, free and holey) polyforms of sizes 1..n.

    Redelmeier's algorithm (D. H. Redelmeier, "Counting polyominoes: yet another attack",
    Discrete Math. 36, 1981) from each cell type's root; ``prefix`` restricts to one subtree.
    """
    mats, period, roots, nbr, hmin = _tables(grid)
    fixed = np.zeros(n + 1, np.int64)
    fr = np.zeros(n + 1, np.int64)
    ho = np.zeros(n + 1, np.int64)
    for r in range(len(grid.roots)) if root is None else [root]:
        cells, nb = redelmeier_board(grid, n, r)
        pre = np.asarray(list(prefix) or [0], dtype=np.int64)
        f, a, h, _ = _redelmeier(nb, cells[:, 0].copy(), cells[:, 1].copy(), n, pre, len(prefix),
                                 n if maxsize is None else maxsize, mats, period, roots, nbr, hmin,
                                 1 if free else 0, np.zeros(1, np.int64), 0)
        fixed += f
        fr += a
        ho += h
    return {"fixed": fixed, "free": fr, "holey": ho}


def prefixes(grid: Grid, n: int, depth: int, root: int) -> list[list[int]]:
    """The paths of choices naming every node of size ``depth`` in the root's search tree."""
    mats, period, roots, nbr, hmin = _tables(grid)
    cells, nb = redelmeier_board(grid, n, root)
    bx, by = cells[:, 0].copy(), cells[:, 1].copy()
    pre = np.zeros(1, np.int64)
    _, _, _, rows = _redelmeier(nb, bx, by, n, pre, 0, depth, mats, period, roots, nbr, hmin, 3,
                                np.zeros(1, np.int64), 0)
    out = np.zeros(max(rows, 1) * n, np.int64)
    _redelmeier(nb, bx, by, n, pre, 0, depth, mats, period, roots, nbr, hmin, 3, out, rows)
    return [out[i * n:i * n + depth].tolist() for i in range(rows)]


def enumerate_free(grid: Grid, n: int, prefix=(), root: int = 0, maxsize: int | None = None,
                   with_holes: bool = False, with_symmetry: bool = False):
    """The free polyforms (canonical representatives, as centres) in one subtree of the tree
    rooted at cell type ``root``, with counts (all types: :func:`free_polyforms`).

    Returns (polyforms, counts), or with ``with_holes`` (polyforms, has-hole flags, counts),
    or with ``with_symmetry`` (polyforms, has-hole flags, symmetry bitmasks, counts). The
    polyforms are already canonical (each is the least image of its class).
    """
    mats, period, roots, nbr, hmin = _tables(grid)
    cells, nb = redelmeier_board(grid, n, root)
    bx, by = cells[:, 0].copy(), cells[:, 1].copy()
    pre = np.asarray(list(prefix) or [0], dtype=np.int64)
    ms = n if maxsize is None else maxsize
    args = (nb, bx, by, n, pre, len(prefix), ms, mats, period, roots, nbr, hmin, 2)
    f, a, h, rows = _redelmeier(*args, np.zeros(1, np.int64), 0)
    out = np.zeros(max(rows, 1) * (n + 2), np.int64)
    _redelmeier(*args, out, rows)
    out = out.reshape(-1, n + 2)[:rows]
    polys = [cells[r[:n][r[:n] >= 0]] for r in out]
    counts = {"fixed": f, "free": a, "holey": h}
    if with_symmetry:
        return polys, out[:, n].astype(bool), out[:, n + 1].copy(), counts
    if with_holes:
        return polys, out[:, n].astype(bool), counts
    return polys, counts


def free_polyforms(grid: Grid, n: int, *, with_holes: bool = False):
    """Every free polyform of 1..n cells on ``grid``: :func:`enumerate_free` from each cell
    type (a form comes from the type of the least cell of its canonical image, once).

    Returns (polyforms, free counts (n + 1,)), or with ``with_holes`` (polyforms, has-hole
    flags, free counts). On a grid with several cell types, ``enumerate_free(grid, n)``
    alone walks only type 0's tree and misses the rest.
    """
    polys: list[np.ndarray] = []
    flags: list[np.ndarray] = []
    free = np.zeros(n + 1, np.int64)
    for r in range(len(grid.roots)):
        p, f, c = enumerate_free(grid, n, root=r, with_holes=True)
        polys += p
        flags.append(f)
        free += c["free"]
    if with_holes:
        return polys, np.concatenate(flags), free
    return polys, free


def symmetry_from_mask(grid: Grid, mask: int) -> str:
    """symmetry_name of the group elements in a bitmask (as enumerate_free reports them)."""
    return symmetry_name(grid, [g for g in range(len(grid.group)) if mask >> g & 1])


# --------------------------------------------------------------------------- codes

def encode(grid: Grid, cells: np.ndarray, *, is_canonical: bool = False) -> str:
    """Text code of the canonical free form: rows top to bottom, 'x' a cell, '.' none (square);
    ``GRID:x,y;x,y;...`` for the other grids, the grid's name and the fine centres of the
    canonical cells in (y, x) order, e.g. ``kite:1,1;5,2`` (``is_canonical`` skips the
    minimisation). :func:`decode` reads both forms back."""
    c = np.asarray(cells, dtype=np.int64) if is_canonical else canonical(grid, cells, "free")
    if grid is SQUARE:
        q = (c - 1) // 2
        q = q - q.min(axis=0)
        w, h = (q.max(axis=0) + 1).tolist()
        board = np.full((h, w + 1), ord("/"), np.uint8)  # each row ends in '/', the last one dropped
        board[:, :w] = ord(".")
        board[h - 1 - q[:, 1], q[:, 0]] = ord("x")
        return board.tobytes()[:-1].decode("ascii")
    return f"{grid.name}:" + ";".join(f"{x},{y}" for x, y in c.tolist())


#: Largest |coordinate| of a cell in a code: fine coordinates (2x + 1 on the square grid)
#: must stay within the +-2^20 that :func:`pack` holds.
MAX_CODE_COORDINATE = 1 << 18


def decode(grid: Grid, code: str) -> np.ndarray:
    """Cells (fine centres) of a code in either form; ParseError names what is wrong."""
    text = str(code).strip()
    if not text:
        raise ParseError("empty polyform code")
    if grid is SQUARE and set(text) <= set("x./"):
        rows = text.split("/")
        if len({len(r) for r in rows}) != 1:
            raise ParseError(f"polyomino code {code!r}: rows must have equal length (rows of 'x' and '.', joined by '/')")
        h = len(rows)
        pts = [(2 * x + 1, 2 * (h - 1 - y) + 1) for y, r in enumerate(rows) for x, ch in enumerate(r) if ch == "x"]
        if not pts:
            raise GeometryError(f"polyomino code {code!r} has no cells (the cell set is empty)")
        return np.array(pts, dtype=np.int64)
    if ":" in text:
        head, _, text = text.partition(":")
        if get_grid(head.strip()) is not grid:
            raise ParseError(f"polyform code {str(code)[:60]!r} is for the {head.strip()} grid, not the {grid.name} grid")
    try:
        pts = [tuple(int(v) for v in part.split(",")) for part in text.split(";") if part.strip()]
        if any(len(p) != 2 for p in pts):
            raise ValueError
    except ValueError:
        hint = ("rows of 'x' and '.' joined by '/', e.g. 'xx/x.'" if grid is SQUARE
                else f"'{grid.name}:x,y;x,y;...' of cell centres")
        raise ParseError(f"malformed {grid.name} polyform code {code!r}: expected {hint}") from None
    if any(abs(v) > MAX_CODE_COORDINATE for p in pts for v in p):
        raise ParseError(f"{grid.name} polyform code {str(code)[:60]!r}: a coordinate is outside "
                         f"±{MAX_CODE_COORDINATE:,} (cells are packed into 21-bit fields)")
    if not pts:
        raise GeometryError(f"{grid.name} polyform code {code!r} has no cells (the cell set is empty)")
    if len(pts) > MAX_CODE_CELLS:
        raise ParseError(f"{grid.name} polyform code has {len(pts):,} cells, over the limit of {MAX_CODE_CELLS:,}")
    return np.array(pts, dtype=np.int64).reshape(-1, 2)


#: Most cells a polyform code may name (a polyform search stores at most a few dozen).
MAX_CODE_CELLS = 10_000


def parse_polyform(grid: Grid | str, code: str) -> np.ndarray:
    """The validated cells of a code: cells of the grid, distinct and edge-connected; the
    error (ParseError / GeometryError, one line) names the cell that is wrong."""
    g = get_grid(grid)
    return as_cells(g, decode(g, code))


def square_cells(pairs) -> np.ndarray:
    """Fine centres of square cells given as integer (column, row) pairs."""
    p = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    return 2 * p + 1


# --------------------------------------------------------------------------- packed cells, halos, holes

_OFF = 1 << 20
_M = 1 << 21


def pack(c: np.ndarray) -> np.ndarray:
    """Fine cell coordinates ``(..., 2)`` -> int64 keys (coordinates within +-2^20)."""
    c = np.asarray(c, dtype=np.int64)
    return (c[..., 0] + _OFF) * _M + (c[..., 1] + _OFF)


def unpack(k: np.ndarray) -> np.ndarray:
    k = np.asarray(k, dtype=np.int64)
    return np.stack([k // _M - _OFF, k % _M - _OFF], axis=-1)


def unique_keys(keys: np.ndarray) -> np.ndarray:
    """The distinct values of an int array, sorted: ``np.unique(keys)`` by one sort and a mask.

    NumPy >= 2.3 answers a plain ``np.unique`` of integers through a hash table, measured here
    (NumPy 2.4) at 10 ms for 10^5 packed keys and 2.2 s for 3 * 10^6 spread ones, against
    0.4 ms and 15 ms for a sort; the Heesch and torus encoders call it on every formula.
    """
    k = np.sort(np.asarray(keys, dtype=np.int64), axis=None)
    if len(k) < 2:
        return k
    return k[np.r_[True, k[1:] != k[:-1]]]


@cache
def _vertex_neighbours(grid: Grid) -> tuple[np.ndarray, ...]:
    """Per cell type, the offsets to the cells sharing at least one vertex with it."""
    out = []
    span = 3 * grid.period
    rng = np.arange(-span, span + 1)
    xs, ys = np.meshgrid(rng, rng, indexing="ij")
    for r, root in enumerate(grid.roots):
        cand = np.column_stack([xs.ravel(), ys.ravel()]) + root
        cand = cand[grid.is_cell(cand)]
        cand = cand[(cand != root).any(axis=1)]
        mine = pack(root[None] + grid.vertices[r])
        theirs = pack(grid.vertices_of(cand))
        hit = np.isin(theirs, mine).any(axis=1)
        out.append(cand[hit] - root)
    return tuple(out)


@cache
def vertex_neighbour_table(grid: Grid) -> np.ndarray:
    """(R, K, 2): :func:`_vertex_neighbours` as one array, each type's list padded by repeating
    its last offset (a set-like table: duplicates vanish in any union)."""
    nb = _vertex_neighbours(grid)
    k = max(len(o) for o in nb)
    return np.stack([np.concatenate([o, np.repeat(o[-1:], k - len(o), axis=0)]) for o in nb]).astype(np.int64)


def halo_of(grid: Grid, cells: np.ndarray) -> np.ndarray:
    """The cells sharing a vertex with ``cells`` and not in it (sorted by key)."""
    cells = np.asarray(cells, dtype=np.int64).reshape(-1, 2)
    tab = vertex_neighbour_table(grid)
    cand = unique_keys(pack(cells[:, None, :] + tab[grid.cell_type(cells)]))
    own = np.sort(pack(cells))
    pos = np.minimum(np.searchsorted(own, cand), len(own) - 1) if len(own) else None
    if pos is not None:
        cand = cand[own[pos] != cand]
    return unpack(cand)


def holes_of(grid: Grid, keys: np.ndarray) -> list[np.ndarray]:
    """Holes of the union of the cells ``keys`` (packed): the edge-connected components of
    empty cells that cannot reach the outside; each an array of packed keys, sorted, the holes
    in the order of their least key."""
    cells = unpack(unique_keys(keys))
    lab, x0, y0, w, comps = _components(grid, cells)
    at = np.flatnonzero(lab > 0)
    if not len(at):
        return []
    found = pack(np.column_stack([at % w + x0, at // w + y0]))
    order = np.lexsort((found, lab[at]))
    found, labels = found[order], lab[at][order]
    parts = np.split(found, np.flatnonzero(np.diff(labels)) + 1)
    return sorted(parts, key=lambda h: int(h[0]))
