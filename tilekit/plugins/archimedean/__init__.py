"""The archimedean family plugin: Archimedean and Laves tilings and the vertex-species search.

Modules: ``notation`` (vertex types: parse, print, canonical form, species, enumeration),
``construct`` (tilings built from vertex types with the shared builder; Laves duals),
``species`` (the vertex-species search), ``records`` (families and catalogue records),
``generate`` (writes the shipped construction data).
"""

from __future__ import annotations

import re
from pathlib import Path

from tilekit.errors import ParseError
from tilekit.hookspecs import hookimpl
from tilekit.lazy import lazy_exports
from tilekit.plugins import Family
from tilekit.regular.notation import (
    VertexType,  # standard library only: cheap at start-up
)

__all__ = ["VertexType", "archimedean_tiling", "laves_prototile", "laves_tiling", "parse_vertex_type"]

#: Public names, imported on first use (PEP 562): measured start-up cost, the construction
#: loads NumPy, shapely and the builder (about 0.4 s of `python -X importtime` on the 2-core
#: dev box), which every `tilekit` command would pay when pluggy loads this plugin.
_LAZY = {
    "archimedean_tiling": "tilekit.plugins.archimedean.construct",
    "laves_prototile": "tilekit.plugins.archimedean.construct",
    "laves_tiling": "tilekit.plugins.archimedean.construct",
    "VertexType": "tilekit.regular.notation",
    "parse_vertex_type": "tilekit.regular.notation",
}
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)


def _archimedean_from_spec(spec):
    # measured start-up cost: the records load the construction (NumPy, shapely, the builder,
    # ~0.5 s); naming the families (``tilekit list --family ...``) must not pay it
    from tilekit.plugins.archimedean.records import archimedean_from_spec

    return archimedean_from_spec(spec)


def _laves_from_spec(spec):
    # measured start-up cost: as in _archimedean_from_spec
    from tilekit.plugins.archimedean.records import laves_from_spec

    return laves_from_spec(spec)


FAMILIES = [
    Family(
        name="archimedean",
        summary="The 11 Archimedean (uniform) tilings by regular polygons, named by vertex type (§4.1)",
        from_spec=_archimedean_from_spec,
        description=(
            "Edge-to-edge tilings by regular polygons with every vertex of one type p1.p2...pk. "
            "Names accept 4^4, (4^4) or 4.4.4.4; the chiral 3^4.6 comes as 3^4.6l and 3^4.6r. "
            "The vertex-species search adds every vertex type with its classification."
        ),
    ),
    Family(
        name="laves",
        summary="The 11 Laves tilings: duals of the Archimedean tilings, monohedral and isohedral (§4.2)",
        from_spec=_laves_from_spec,
        description="Named [vertex type] after the Archimedean tiling they are dual to, e.g. [3^2.4.3.4] (Cairo).",
    ),
]


@hookimpl
def tilekit_families():
    return FAMILIES


@hookimpl
def tilekit_catalogue_records():
    # measured start-up cost: as in tilekit_families (records are built only when seeding)
    from tilekit.plugins.archimedean.records import catalogue_records

    return catalogue_records()


@hookimpl
def tilekit_searches():
    # measured start-up cost: the search loads the construction and SQLAlchemy (~0.4-1 s)
    from tilekit.plugins.archimedean.species import SEARCH

    return [SEARCH]


@hookimpl
def tilekit_result_tables():
    # measured start-up cost: the table definition loads SQLAlchemy (~0.3 s), which only
    # catalogue commands need
    from tilekit.plugins.archimedean.tables import RESULT_TABLE

    return [RESULT_TABLE]


@hookimpl
def tilekit_migration_locations():
    # the folder next to tables.py (which loads SQLAlchemy: a read without it asks this too)
    return [str(Path(__file__).parent / "migrations")]


_WRAPPED = re.compile(r"^\s*([(\[]?)([^()\[\]]+?)([)\]]?)([lr]?)\s*$")


@hookimpl
def tilekit_normalise(key: str, value: str) -> tuple[str, str] | None:
    """Vertex types in any rotation, reflection or spelling (``4.3.4.6``, ``3.3.3.3.6``,
    ``3⁴.6``) as stored (``3.4.6.4``, ``3^4.6``): in ``vertex_type`` filters, and as names
    (``(4.3.4.6)`` an Archimedean tiling, ``[4.3.4.6]`` its Laves dual, a trailing l/r the hand)."""
    if key not in ("vertex_type", "name"):
        return None
    m = _WRAPPED.match(value)
    if m is None or m.group(1) + m.group(3) not in ("", "()", "[]"):
        return None
    try:
        vt = VertexType.parse(m.group(2))
    except ParseError:
        return None
    if key == "vertex_type":
        return key, str(vt)
    return "name", f"{m.group(1)}{vt}{m.group(3)}{m.group(4)}"
