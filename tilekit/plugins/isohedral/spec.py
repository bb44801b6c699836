"""Any isohedral tiling, marked or not, from its catalogue spec ``{"ih": 16, ...}``."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from tilekit.plugins.isohedral.engine import _spec_ih, unmarked_from_spec
from tilekit.plugins.isohedral.marked import marked_tiling
from tilekit.plugins.isohedral.templates import get_template
from tilekit.tiling import PeriodicTiling


def tiling_from_spec(spec: Mapping[str, Any]) -> PeriodicTiling:
    """Rebuild an isohedral tiling from ``{"ih": 16, "params": [...], "edges": {...}}``."""
    t = get_template(_spec_ih(spec))
    if t.marked:
        return marked_tiling(t.ih)
    return unmarked_from_spec(spec)
