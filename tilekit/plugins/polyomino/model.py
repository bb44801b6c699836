"""Polyforms as objects: parse a code or a usual name, analyse, and build their isohedral tilings.

``tilekit.polyomino("pentomino-F")`` (or a code such as ``".xx/xx./.x."``) returns a
:class:`Polyomino`; ``.is_isohedral()`` runs the boundary-word test and ``.tilings()`` gives one
:class:`PolyominoTiling` (a ``PeriodicTiling``) per Heesch type found. The same class holds a
polyform of any grid of :mod:`tilekit.lattice`: a code ``hex:0,0;3,0`` (the grid's name, a
colon, then the fine cell centres) is a dihex, ``iamond:1,1;2,2`` a diamond.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from functools import cached_property
from typing import Any

import numpy as np
import shapely

from tilekit.errors import GeometryError, NotFoundError, ParameterError, ParseError
from tilekit.lattice import (
    SQUARE,
    Grid,
    as_cells,
    boundary_word,
    canonical,
    decode,
    encode,
    get_grid,
    holes,
    outline,
    symmetry_elements,
    symmetry_name,
    word_text,
)
from tilekit.plugins.polyomino.classify import MAX_INTERACTIVE, classify, corona_patch, torus_tiling
from tilekit.plugins.polyomino.isohedral import FAMILIES, analyse, periodic_tiling
from tilekit.schema import Field, check, parse_json, shown
from tilekit.tiling import Patch, PeriodicTiling, Tiling

FAMILY = "polyomino"

#: The usual names: Golomb's and Conway's letters for the pentominoes, the tetromino letters.
USUAL = {
    "monomino": "x",
    "domino": "xx",
    "I-tromino": "xxx",
    "L-tromino": "xx/x.",
    "I-tetromino": "xxxx",
    "O-tetromino": "xx/xx",
    "T-tetromino": "xxx/.x.",
    "S-tetromino": ".xx/xx.",
    "L-tetromino": "x./x./xx",
    "pentomino-F": ".xx/xx./.x.",
    "pentomino-I": "xxxxx",
    "pentomino-L": "x./x./x./xx",
    "pentomino-N": ".x/.x/xx/x.",
    "pentomino-P": "xx/xx/x.",
    "pentomino-T": "xxx/.x./.x.",
    "pentomino-U": "x.x/xxx",
    "pentomino-V": "x../x../xxx",
    "pentomino-W": "x../xx./.xx",
    "pentomino-X": ".x./xxx/.x.",
    "pentomino-Y": ".x/xx/.x/.x",
    "pentomino-Z": "xx./.x./.xx",
}


def grid_of(name: str | Grid) -> Grid:
    """A grid by name (``square``, ``hex``, ``iamond``, ``kite``, ... or an alias); an unknown
    one is a one-line NotFoundError listing the grids (:func:`tilekit.lattice.get_grid`)."""
    return get_grid(name)


def _name_index() -> dict[str, str]:
    return {encode(SQUARE, decode(SQUARE, c)): name for name, c in USUAL.items()}


_NAMES: dict[str, str] | None = None


def usual_name(code: str) -> str | None:
    global _NAMES
    if _NAMES is None:
        _NAMES = _name_index()
    return _NAMES.get(code)


class Polyomino:
    """A free polyform (a polyomino by default; any grid of :mod:`tilekit.lattice`), its cells
    validated: non-empty, distinct, cell centres of the grid, edge-connected."""

    def __init__(self, cells, name: str | None = None, grid: str | Grid = SQUARE) -> None:
        self.grid = grid_of(grid)
        c = as_cells(self.grid, cells)
        self.cells = canonical(self.grid, c, "free")
        self.code = encode(self.grid, self.cells)
        self.name = name or (usual_name(self.code) if self.grid.name == SQUARE.name else None)

    @classmethod
    def parse(cls, text: str) -> Polyomino:
        """A usual name (``pentomino-F``, ``T-tetromino``), a code (``.xx/xx./.x.``), cells
        ``x,y;x,y`` of (column, row) pairs, or ``grid:x,y;x,y`` of another grid's fine centres
        (``hex:0,0;3,0``)."""
        t = str(text).strip()
        head, sep, rest = t.partition(":")
        if sep and head.strip() and not set(head) <= set("x./"):
            grid = grid_of(head)
            if grid.name != SQUARE.name:
                return cls(decode(grid, t), grid=grid)
            t = rest.strip()
        if t in USUAL:
            return cls(decode(SQUARE, USUAL[t]), name=t)
        lowered = {k.lower(): k for k in USUAL}
        if t.lower() in lowered:
            k = lowered[t.lower()]
            return cls(decode(SQUARE, USUAL[k]), name=k)
        if set(t) <= set("x./") and "x" in t:
            return cls(decode(SQUARE, t))
        if t and (set(t) <= set("0123456789,;- ")):
            pairs = decode(SQUARE, t)
            return cls(2 * pairs + 1)
        if t and set(t) <= set("./"):
            raise GeometryError(f"polyomino code {text!r} has no cells (the cell set is empty)")
        raise NotFoundError("polyomino name or code", t, list(USUAL))

    # -- facts ---------------------------------------------------------------
    @property
    def n(self) -> int:
        return len(self.cells)

    @cached_property
    def hole_list(self) -> list[np.ndarray]:
        return holes(self.grid, self.cells)

    @property
    def has_holes(self) -> bool:
        return bool(self.hole_list)

    @cached_property
    def symmetry(self) -> str:
        return symmetry_name(self.grid, symmetry_elements(self.grid, self.cells))

    @cached_property
    def boundary(self) -> str:
        return word_text(boundary_word(self.grid, self.cells)[1])

    def cell_pairs(self) -> list[list[int]]:
        """(column, row) pairs on the square grid; fine cell centres on the others."""
        if self.grid.name != SQUARE.name:
            return sorted(self.cells.tolist(), key=lambda p: (p[1], p[0]))
        q = (self.cells - 1) // 2
        q = q - q.min(axis=0)
        return sorted(q.tolist(), key=lambda p: (p[1], p[0]))

    def prototile(self):
        return outline(self.grid, self.cells, name=self.name or self.code)

    @cached_property
    def analysis(self) -> dict:
        """The isohedral analysis (boundary factorisations and the tilings built from them);
        refused past MAX_ANALYSIS_BOUNDARY boundary steps, as its cost grows with the cube of
        the boundary (a 128-cell bar, 258 steps: 1.3 s; 200 cells: 4.6 s; 400: a minute)."""
        steps = len(boundary_word(self.grid, self.cells)[1]) if not self.has_holes else 0
        if steps > MAX_ANALYSIS_BOUNDARY:
            raise ParameterError(f"the isohedral analysis of a polyomino with a boundary of {steps} steps is refused "
                                 f"(limit {MAX_ANALYSIS_BOUNDARY}: its cost grows with the cube of the boundary)")
        if self.has_holes:
            return dict.fromkeys(FAMILIES, False) | {"isohedral": False, "ih_types": [], "factorisations": [],
                                                     "tilings": []}
        return analyse(self.grid, self.cells, construct=True)

    def is_isohedral(self) -> bool:
        return bool(self.analysis["isohedral"])

    def factorisations(self) -> list[dict]:
        return list(self.analysis["factorisations"])

    def tilings(self) -> list[PolyominoTiling]:
        """One periodic tiling per Heesch type found (empty if the polyomino is not isohedral)."""
        return [PolyominoTiling(self, i) for i in range(len(self.analysis["tilings"]))]

    def classification(self, **bounds: Any):
        """Tiles or not, Heesch numbers, anisohedral k (see :mod:`classify`); cached per bounds.

        Sizes beyond :data:`classify.MAX_INTERACTIVE` cells are refused: their SAT searches
        can take minutes each, which belongs in ``tilekit search polyomino-classify``."""
        if self.n > MAX_INTERACTIVE:
            raise ParameterError(f"classifying a {self.n}-omino here is refused (limit {MAX_INTERACTIVE} cells); "
                                 f"run `tilekit search polyomino-classify` for larger sizes")
        key = tuple(sorted(bounds.items()))
        cache = self.__dict__.setdefault("_classifications", {})
        if key not in cache:
            analysis = None if self.has_holes else self.analysis
            cache[key] = classify(self.grid, self.cells, analysis, has_holes=self.has_holes, **bounds)
        return cache[key]

    def row(self) -> dict[str, Any]:
        """The polyominoes table row of this polyomino."""
        return make_row(self.cells, self.has_holes, len(self.hole_list), self.analysis, name=self.name,
                        grid=self.grid)

    def __repr__(self) -> str:
        return f"<Polyomino {self.name or self.code} n={self.n}>"


def make_row(cells: np.ndarray, has_holes: bool, hole_count: int, analysis: dict | None,
             name: str | None = None, code: str | None = None, symmetry: str | None = None,
             grid: Grid = SQUARE) -> dict[str, Any]:
    """One row of the polyominoes table from canonical cells and an analysis (None for a holey
    one). ``cell_list`` is (column, row) pairs on the square grid, fine centres elsewhere."""

    square = grid.name == SQUARE.name
    code = code or encode(grid, cells)
    if square:
        q = (cells - 1) // 2
        q = q - q.min(axis=0)
    else:
        q = np.asarray(cells)
    a = analysis or {}
    iso = bool(a.get("isohedral", False))
    row = {
        "code": code,
        "name": name if name is not None else (usual_name(code) if square else None),
        "grid": grid.name,
        "cells": int(len(cells)),
        "cell_list": json.dumps(q.tolist()),
        "holes": bool(has_holes),
        "hole_count": int(hole_count),
        "symmetry": symmetry or symmetry_name(grid, symmetry_elements(grid, cells)),
        "boundary": word_text(a["boundary"]) if "boundary" in a else word_text(boundary_word(grid, cells)[1]),
        "translation": bool(a.get("translation", False)),
        "halfturn": bool(a.get("halfturn", False)),
        "quarterturn": bool(a.get("quarterturn", False)),
        "reflection": bool(a.get("reflection", False)),
        "isohedral": iso,
        "ih_types": ",".join(f"IH{i}" for i in a.get("ih_types", [])),
        "factorisations": json.dumps(a.get("factorisations", [])),
    }
    # The verdicts the enumeration alone can give; the others (anisohedral tilers, Heesch
    # numbers) are the classification search's, and an enumeration re-run must not erase them.
    if iso:
        row |= {"tiles": "true", "verdict": "tiles isohedrally (boundary factorisation)"}
    elif has_holes:
        row |= {"tiles": "false", "heesch": None, "heesch_holes": None,
                "verdict": "does not tile: it has a hole, and no copy fits in a hole"}
    return row


# --------------------------------------------------------------------------- tilings

class PolyominoTiling(PeriodicTiling):
    """An isohedral tiling by one polyomino (built from a boundary factorisation)."""

    def __init__(self, poly: Polyomino, index: int = 0) -> None:
        built = poly.analysis["tilings"]
        if not built:
            raise GeometryError(f"polyomino {poly.name or poly.code} has no isohedral tiling")
        if not 0 <= index < len(built):
            raise ParameterError(f"polyomino {poly.name or poly.code} has {len(built)} tilings; index {index} is out of range")
        self.poly = poly
        self.index = index
        self.built = built[index]
        base = periodic_tiling(poly.grid, poly.cells, self.built, name=poly.name or poly.code, family=FAMILY)
        super().__init__(base.prototiles, base.unit_prototile, base.unit_transform, base.v1, base.v2,
                         unit_aspect=np.arange(len(base.unit_prototile)), family=FAMILY,
                         name=poly.name or poly.code)

    def _default_colours(self) -> list[int]:
        """One colour per tile of the unit (the tile's orientations), so neighbours differ."""
        return list(range(int(self.unit_aspect.max()) + 1))

    @property
    def ih(self) -> int | None:
        return self.built.ih

    @property
    def heesch_type(self) -> str:
        return "".join(self.built.factorisation.signature())

    def spec(self) -> dict[str, Any]:
        return {"code": self.poly.code, "name": self.name, "tiling": self.index}

    def properties(self) -> dict[str, Any]:
        out = {**super().properties(), "k_isohedral": 1, "cells": self.poly.n,
               "heesch_type": self.heesch_type, "factorisation": self.built.factorisation.template}
        if self.ih is not None:
            out["ih"] = self.ih
        return out

    def describe(self) -> str:
        return (f"isohedral tiling {self.index + 1} of {len(self.poly.analysis['tilings'])}: "
                f"{self.built.factorisation.template} factorisation, Heesch type {self.heesch_type}"
                + (f", IH{self.ih}" if self.ih else ""))

    def configure(self, **options: Any) -> Tiling:
        return _configure(self.poly, options)


class PolyominoShape(Tiling):
    """A polyomino with no isohedral tiling: its patch is the tile itself (for show / render)."""

    def __init__(self, poly: Polyomino) -> None:
        self.poly = poly
        self.family = FAMILY
        self.name = poly.name or poly.code
        self._proto = poly.prototile()

    @property
    def prototiles(self):
        return [self._proto]

    def patch(self, region: Any) -> Patch:
        return Patch([self._proto], np.zeros(1, np.int64), np.eye(3)[None])

    def default_region(self):
        x0, y0 = self._proto.outline.min(axis=0)
        x1, y1 = self._proto.outline.max(axis=0)
        return shapely.box(x0 - 0.5, y0 - 0.5, x1 + 0.5, y1 + 0.5)

    def spec(self) -> dict[str, Any]:
        return {"code": self.poly.code, "name": self.name}

    def properties(self) -> dict[str, Any]:
        return {"periodic": False, "k_hedral": 1, "cells": self.poly.n, "isohedral": False,
                "holes": self.poly.has_holes}

    def describe(self) -> str:
        why = "it has a hole" if self.poly.has_holes else "no boundary factorisation exists"
        return f"{self.poly.n}-{self.poly.grid.cell_name} with no isohedral tiling ({why}); the render shows the tile"

    def configure(self, **options: Any) -> Tiling:
        return _configure(self.poly, options)


class CoronaPatch(Tiling):
    """A Heesch witness: the polyomino surrounded by its coronas, coloured by corona number
    (Kaplan 2022). Its patch is the stored witness itself; the region is ignored."""

    def __init__(self, poly: Polyomino, corona: dict, *, which: str = "hc") -> None:
        self.poly = poly
        self.corona = dict(corona)
        self.which = which
        self.family = FAMILY
        self.name = poly.name or poly.code
        self._patch = corona_patch(poly.grid, poly.cells, self.corona, name=self.name)

    @property
    def prototiles(self):
        return self._patch.prototiles

    def patch(self, region: Any) -> Patch:
        return self._patch

    def default_region(self):
        x0, y0, x1, y1 = self._patch.bounds()
        return shapely.box(x0 - 0.5, y0 - 0.5, x1 + 0.5, y1 + 0.5)

    def estimate_tiles(self, region: Any = None) -> float:
        return float(len(self._patch))

    def spec(self) -> dict[str, Any]:
        return {"code": self.poly.code, "name": self.name, "view": self.which, "witness": self.corona}

    def properties(self) -> dict[str, Any]:
        return {"periodic": False, "k_hedral": 1, "cells": self.poly.n, "coronas": int(self.corona.get("k", 0)),
                "hole_free": not self.corona.get("holes", False)}

    def describe(self) -> str:
        k = int(self.corona.get("k", 0))
        holes = "with a hole in the outermost corona" if self.corona.get("holes") else "hole-free"
        return f"{self.poly.n}-{self.poly.grid.cell_name} surrounded by {k} corona(s), {holes}: {len(self._patch)} tiles, coloured by corona"

    def configure(self, **options: Any) -> Tiling:
        return _configure(self.poly, options)


class AnisohedralTiling(PeriodicTiling):
    """A periodic tiling found on a torus; aspects (and default colours) are the tiles'
    transitivity classes under the tiling's symmetry group."""

    def __init__(self, poly: Polyomino, witness: dict) -> None:
        self.poly = poly
        self.witness = dict(witness)
        base = torus_tiling(poly.grid, poly.cells, self.witness, name=poly.name or poly.code)
        super().__init__(base.prototiles, base.unit_prototile, base.unit_transform, base.v1, base.v2,
                         base.colouring, unit_aspect=base.unit_aspect, family=FAMILY, name=poly.name or poly.code)

    def spec(self) -> dict[str, Any]:
        return {"code": self.poly.code, "name": self.name, "view": "tiling", "witness": self.witness}

    def properties(self) -> dict[str, Any]:
        return super().properties() | {"cells": self.poly.n, "isohedral": False,
                                       "k_isohedral": int(self.unit_aspect.max()) + 1}

    def describe(self) -> str:
        a, b, d = self.witness["lattice"]
        return (f"anisohedral tiling: {len(self.unit_prototile)} tiles per translational unit "
                f"(period lattice ({a},{b}),(0,{d})), {int(self.unit_aspect.max()) + 1} transitivity classes")

    def configure(self, **options: Any) -> Tiling:
        return _configure(self.poly, options)


#: What ``--set view=...`` shows of a polyomino that has no isohedral tiling.
VIEWS = ("shape", "coronas", "holes", "tiling")


def witness_tiling(poly: Polyomino, witness: dict | None, view: str | None) -> Tiling:
    """The tiling showing a stored classification ``witness`` (or ``view`` of it)."""
    if view is not None and view not in VIEWS:
        raise ParameterError(f"view must be one of {', '.join(VIEWS)}, not {view!r}")
    if view == "shape" or witness is None:
        return PolyominoShape(poly)
    if not isinstance(witness, Mapping):
        raise ParseError(f"a polyomino witness is a JSON object with 'kind', not {shown(witness)}")
    kind = witness.get("kind")
    if kind == "torus":
        if view not in (None, "tiling"):
            raise ParameterError(f"{poly.name or poly.code} tiles the plane: its witness is a tiling (view=tiling), not {view}")
        return AnisohedralTiling(poly, witness)
    if kind == "coronas":  # one corona patch, stored as such
        return CoronaPatch(poly, witness, which=view or "coronas")
    if kind == "heesch":
        if view == "tiling":
            raise ParameterError(f"{poly.name or poly.code} does not tile: it has coronas to show (view=coronas or holes)")
        part = witness.get("hh") if view == "holes" else witness.get("hc")
        if part is None:
            part = witness.get("hc")
        if part is None:
            return PolyominoShape(poly)
        if not isinstance(part, Mapping):
            raise ParseError(f"a polyomino heesch witness's corona is a JSON object, not {shown(part)}")
        return CoronaPatch(poly, part, which=view or "coronas")
    raise ParameterError(f"unknown polyomino witness kind {shown(kind)}: expected heesch, coronas or torus")


def _configure(poly: Polyomino, options: dict[str, Any]) -> Tiling:
    """``--set tiling=N`` (1-based) or ``--set tiling=IH41`` picks one of the tilings; ``--set shape=1`` the tile;
    ``--set view=coronas|holes|tiling`` classifies the polyomino (Heesch numbers, torus search) and shows its witness."""
    opts = dict(options)
    choice = opts.pop("tiling", None)
    shape = opts.pop("shape", None)
    view = opts.pop("view", None)
    if opts:
        raise ParameterError(f"polyomino takes the settings tiling=N|IHn, shape=1 and view={'|'.join(VIEWS)}, "
                             f"not {', '.join(sorted(opts))}")
    if shape:
        return PolyominoShape(poly)
    if view is not None:
        view = str(view).strip()
        if view not in VIEWS:
            raise ParameterError(f"view must be one of {', '.join(VIEWS)}, not {view!r}")
        if poly.is_isohedral() and view in ("tiling",):
            return tiling_of(poly)
        return witness_tiling(poly, poly.classification().witness, view)
    if choice is None:
        return tiling_of(poly)
    built = poly.analysis["tilings"]
    text = str(choice).strip()
    if text.upper().startswith("IH"):
        for i, b in enumerate(built):
            if b.ih is not None and f"IH{b.ih}" == text.upper():
                return PolyominoTiling(poly, i)
        have = ", ".join(f"IH{b.ih}" for b in built if b.ih) or "none"
        raise ParameterError(f"polyomino {poly.name or poly.code} has no tiling of type {text} (it has {have})")
    try:
        i = int(text) - 1
    except ValueError:
        raise ParameterError(f"tiling must be a number 1..{len(built)} or an IH type, not {text!r}") from None
    return PolyominoTiling(poly, i)


#: Boundary steps past which a polyomino's isohedral analysis is refused (see Polyomino.analysis).
MAX_ANALYSIS_BOUNDARY = 256


def tiling_of(poly: Polyomino, index: int = 0) -> Tiling:
    return PolyominoTiling(poly, index) if poly.is_isohedral() else PolyominoShape(poly)


#: A polyomino tiling's spec: the polyomino by ``code`` or usual ``name``, the 0-based index
#: of its isohedral ``tiling``, or the ``witness`` (JSON text or value) and ``view`` of one
#: that tiles only anisohedrally or not at all.
SPEC = Field("table", fields={
    "code": Field("str"), "name": Field("str"), "tiling": Field("int", range=(0, 1 << 20)),
    "witness": Field("any"), "view": Field("str"),
})


def from_spec(spec) -> Tiling:
    if not isinstance(spec, Mapping):
        raise ParseError(f'a polyomino spec is a JSON object like {{"name": "pentomino-F"}}, not {shown(spec)}')
    spec = check(SPEC, {k: v for k, v in spec.items() if v is not None}, "polyomino spec")
    if not spec.get("code") and not spec.get("name"):
        raise ParseError("a polyomino spec needs a 'code' or a 'name'")
    poly = Polyomino.parse(spec.get("code") or spec.get("name"))
    if spec.get("name") and not poly.name:
        poly.name = spec["name"]
    if not poly.is_isohedral():
        witness = spec.get("witness")
        if isinstance(witness, str):
            witness = parse_json(witness, "polyomino spec witness")
        return witness_tiling(poly, witness, spec.get("view"))
    return PolyominoTiling(poly, spec.get("tiling", 0))


def polyomino(spec) -> Polyomino:
    """A polyomino from a usual name, a code, or a list of (column, row) cells."""
    if isinstance(spec, Polyomino):
        return spec
    if isinstance(spec, str):
        return Polyomino.parse(spec)
    pairs = np.asarray(spec, dtype=np.int64).reshape(-1, 2) if len(spec) else np.zeros((0, 2), np.int64)
    return Polyomino(2 * pairs + 1)
