"""The archimedean family plugin: Archimedean and Laves tilings and the vertex-species search.

Modules: ``notation`` (vertex types: parse, print, canonical form, species, enumeration),
``construct`` (tilings built from vertex types with the shared builder; Laves duals),
``species`` (the vertex-species search), ``records`` (families and catalogue records),
``generate`` (writes the shipped construction data).
"""

from __future__ import annotations

from tilekit.hookspecs import hookimpl
from tilekit.plugins.archimedean.construct import (
    archimedean_tiling,
    laves_prototile,
    laves_tiling,
)
from tilekit.plugins.archimedean.notation import VertexType, parse_vertex_type

__all__ = ["VertexType", "archimedean_tiling", "laves_prototile", "laves_tiling", "parse_vertex_type"]


@hookimpl
def tilekit_families():
    from tilekit.plugins.archimedean.records import FAMILIES

    return FAMILIES


@hookimpl
def tilekit_catalogue_records():
    from tilekit.plugins.archimedean.records import catalogue_records

    return catalogue_records()


@hookimpl
def tilekit_searches():
    from tilekit.plugins.archimedean.species import SEARCH

    return [SEARCH]


@hookimpl
def tilekit_result_tables():
    from tilekit.plugins.archimedean.tables import RESULT_TABLE

    return [RESULT_TABLE]


@hookimpl
def tilekit_migration_locations():
    from tilekit.plugins.archimedean.tables import MIGRATIONS

    return [str(MIGRATIONS)]
