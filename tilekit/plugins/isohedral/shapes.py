"""The edge-shape vocabulary (J/U/S/I edges, EdgeShape) lives in the core module
:mod:`tilekit.edgeshapes`, which the curved family's isohedral tiles share; re-exported here
for the isohedral family's modules."""

from tilekit.edgeshapes import (
    BEZIER_SAMPLES,
    FLIP,
    IDENTITY,
    ROFL,
    ROT,
    EdgeShape,
    apply_unit,
    complete,
    parse_edge_option,
)

__all__ = ["BEZIER_SAMPLES", "FLIP", "IDENTITY", "ROFL", "ROT", "EdgeShape", "apply_unit", "complete",
           "parse_edge_option"]
