"""The polyomino family: free polyominoes, their enumeration, and the isohedral test.

Modules: ``model`` (Polyomino, the usual names, PolyominoTiling), ``isohedral`` (boundary
factorisations after Langerman and Winslow, tilings proved exact), ``search`` (the
``polyominoes`` search: Redelmeier chunks, rows, counting mode), ``tables`` (the result
table) and ``migrations/`` (its Alembic branch ``polyomino``). The lattice machinery
(square, hexagonal, triangular grids) is ``tilekit.lattice``.
"""

from __future__ import annotations

from pathlib import Path

from tilekit.hookspecs import hookimpl
from tilekit.plugins import CatalogueRecord, Family
from tilekit.plugins.polyomino.model import USUAL, Polyomino, from_spec, tiling_of
from tilekit.plugins.polyomino.search import SEARCH
from tilekit.plugins.polyomino.tables import result_table

FAMILY = "polyomino"


@hookimpl
def tilekit_families():

    return [Family(FAMILY, "Polyominoes: free n-ominoes, holes, symmetry, boundary words, isohedral tilings",
                   from_spec,
                   description="Redelmeier enumeration; isohedral test after Langerman and Winslow (SoCG 2016)")]


@hookimpl
def tilekit_catalogue_records():

    out = []
    for name in USUAL:
        poly = Polyomino.parse(name)
        a = poly.analysis
        til = tiling_of(poly)
        props = {
            "periodic": bool(a["isohedral"]),
            "k_hedral": 1,
            "cells": poly.n,
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

    return [SEARCH]


@hookimpl
def tilekit_migration_locations():
    return [str(Path(__file__).parent / "migrations")]


@hookimpl
def tilekit_result_tables():
    """The polyominoes result table (needs tilekit.plugins.ResultTable; empty until the run layer has it)."""

    rt = result_table()
    return [rt] if rt is not None else []
