"""Incidence symbols (§5.2): the core's :mod:`tilekit.incidence`, shared with the curved
family's isohedral tiles; re-exported here under the family's old module name."""

from tilekit.incidence import MAX_EDGES, MAX_TEXT, Edge, IncidenceSymbol, all_relabellings

__all__ = ["MAX_EDGES", "MAX_TEXT", "Edge", "IncidenceSymbol", "all_relabellings"]
