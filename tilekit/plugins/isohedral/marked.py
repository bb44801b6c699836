"""The 12 isohedral types realisable only with marked tiles (drawn as Laves tiles with a marking)."""

from __future__ import annotations

from tilekit.errors import ParameterError
from tilekit.tiling import PeriodicTiling


def marked_tiling(ih: int) -> PeriodicTiling:
    raise ParameterError(f"IH{ih} is a marked type; marked types are not yet drawable")
