"""The polyomino family: free polyominoes, their enumeration, and the isohedral test.

Modules: ``model`` (Polyomino, the usual names, PolyominoTiling), ``isohedral`` (boundary
factorisations after Langerman and Winslow, tilings proved exact), ``search`` (the
``polyominoes`` search: Redelmeier chunks, rows, counting mode), ``polyforms`` (the same
enumeration on any grid of ``tilekit.lattice``), ``tables`` (the result
table) and ``migrations/`` (its Alembic branch ``polyomino``). The lattice machinery
(square, hexagonal, triangular grids) is ``tilekit.lattice``.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from tilekit.hookspecs import hookimpl
from tilekit.plugins import CatalogueRecord, Family

FAMILY = "polyomino"


def _from_spec(spec: Mapping[str, Any]) -> Any:
    # measured start-up cost: the model and the lattice load numba (~0.25 s), which every
    # `tilekit` command would pay when the plugins are loaded; they load when a polyomino is built
    code = spec.get("code") if isinstance(spec, Mapping) else None
    classified = isinstance(spec, Mapping) and (spec.get("classified") or any(k in spec for k in _CLASSIFIED))
    if isinstance(code, str) and ":" in code and not classified:
        # a polyform on another grid ("kite:1,1;5,2") that no classification has touched;
        # start-up cost: numba, as above
        from tilekit.plugins.polyomino.polyform import from_spec as polyform_spec

        return polyform_spec(spec)
    # start-up cost: numba, as above
    from tilekit.plugins.polyomino.model import from_spec

    if isinstance(spec, Mapping) and "classified" in spec:
        spec = {k: v for k, v in spec.items() if k != "classified"}
    return from_spec(spec)


def polyomino(spec: Any) -> Any:
    """A polyomino from a usual name (``pentomino-F``), a code (``.xx/xx./.x.``) or (column, row)
    cells; ``tilekit.polyomino`` (this family's public name, tilekit_public_names)."""
    # start-up cost: numba, as in _from_spec
    from tilekit.plugins.polyomino.model import polyomino as _polyomino

    return _polyomino(spec)


@hookimpl
def tilekit_public_names():
    return {"polyomino": polyomino}


#: Spec keys that only the classified forms' model reads (its tilings and witnesses).
_CLASSIFIED = ("witness", "view", "tiling")


@hookimpl
def tilekit_families():
    return [Family(FAMILY, "Polyominoes: free n-ominoes, holes, symmetry, boundary words, isohedral tilings",
                   _from_spec,
                   description="Redelmeier enumeration; isohedral test after Langerman and Winslow (SoCG 2016)")]


@hookimpl
def tilekit_catalogue_records():
    # measured start-up cost: numba, as in _from_spec (records are built only when seeding)
    from tilekit.plugins.polyomino.model import USUAL, Polyomino, tiling_of

    out = []
    for name in USUAL:
        poly = Polyomino.parse(name)
        a = poly.analysis
        til = tiling_of(poly)
        props = {
            "periodic": bool(a["isohedral"]),
            "k_hedral": 1,
            "cells": poly.n,
            "sides": [len(poly.prototile().outline)],
            "code": poly.code,
            "symmetry": poly.symmetry,
            "holes": poly.has_holes,
            "isohedral": bool(a["isohedral"]),
            "translation": bool(a["translation"]),
            "halfturn": bool(a["halfturn"]),
            "quarterturn": bool(a["quarterturn"]),
            "reflection": bool(a["reflection"]),
            "ih_types": [f"IH{i}" for i in a["ih_types"]],
        }
        if a["isohedral"]:
            props["k_isohedral"] = 1
        out.append(CatalogueRecord(FAMILY, name, til.spec() | {"name": name},
                                   title=f"the {name} ({poly.n} cells)", properties=props,
                                   aliases=[poly.code]))
    return out


@hookimpl
def tilekit_searches():
    # measured start-up cost: numba, as in _from_spec
    from tilekit.plugins.polyomino.classify_search import SEARCH as CLASSIFY
    from tilekit.plugins.polyomino.polyforms import SEARCH as POLYFORMS
    from tilekit.plugins.polyomino.search import SEARCH

    return [SEARCH, CLASSIFY, POLYFORMS]


@hookimpl
def tilekit_migration_locations():
    return [str(Path(__file__).parent / "migrations")]


@hookimpl
def tilekit_result_tables():
    """The polyominoes result table."""
    # measured start-up cost: the table module imports SQLAlchemy (~0.15 s), which `tilekit
    # --help` and the commands that open no catalogue should not pay
    from tilekit.plugins.polyomino.tables import result_table

    rt = result_table()
    return [rt] if rt is not None else []


@hookimpl
def tilekit_normalise(key: str, value: str) -> tuple[str, str] | None:
    """A polyomino code in any orientation or position (``x../xxx``) as its canonical code, in
    ``code`` filters and as a name (each polyomino's record has its code as an alias)."""
    text = value.strip()
    if key not in ("code", "name") or not text or not set(text) <= set("x./") or "x" not in text:
        return None
    # measured start-up cost: the model loads NumPy and the lattice code; only for a code
    from tilekit.errors import TilekitError
    from tilekit.plugins.polyomino.model import Polyomino

    try:
        return key, Polyomino.parse(text).code
    except TilekitError:
        return None
