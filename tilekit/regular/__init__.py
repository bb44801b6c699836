"""The shared core of tilings by regular polygons (chapter 4), used by the Archimedean and
k-uniform families alike so that neither imports the other: vertex-type notation and the 21
Euclidean vertex types (:mod:`tilekit.regular.notation`, pure Python, cheap to import) and
regular polygons as prototiles with their colours and unit text (:mod:`tilekit.regular.tiles`,
NumPy and the core vocabulary; import it where it is used)."""

from tilekit.regular.notation import (
    VertexType,
    canonical,
    euclidean_species,
    euclidean_vertex_types,
    format_sequence,
    parse_sequence,
    parse_vertex_type,
    types_of_species,
)

__all__ = [
    "VertexType",
    "canonical",
    "euclidean_species",
    "euclidean_vertex_types",
    "format_sequence",
    "parse_sequence",
    "parse_vertex_type",
    "types_of_species",
]
