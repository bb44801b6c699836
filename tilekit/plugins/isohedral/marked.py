"""The 12 isohedral types realisable only with marked tiles (§5.3.1), drawn as Laves tiles.

Their edges are all straight (I edges), so the tile is the Laves tile of the topology; the
tiling is laid out like the fully symmetric unmarked type of the same topology (the Laves
tiling itself), and each tile carries a small central ring as its marking, flagging that the
type needs marked tiles. The ring is symmetric: it does not encode the marked type's smaller
symmetry group, which would need the type's incidence symbol (not transcribed; see README).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from tilekit.errors import ParameterError
from tilekit.geometry import centroid
from tilekit.plugins.isohedral.templates import get_template, load_templates
from tilekit.tiling import PeriodicTiling, Prototile


def laves_host(topology: str) -> int:
    """The unmarked all-I type of a topology with the most aspects (the Laves tiling's own)."""
    best = None
    for ih, t in sorted(load_templates().items()):
        if t.marked or t.topology != topology or t.symbol is None:
            continue
        if set(t.symbol.edge_kinds()) != {"I"}:
            continue
        if best is None or len(t.aspects) > len(load_templates()[best].aspects):
            best = ih
    if best is None:
        raise ParameterError(f"no unmarked all-I type has topology {topology}")
    return best


class MarkedTiling(PeriodicTiling):
    """A marked isohedral type drawn as the Laves tiling with ringed tiles."""

    def __init__(self, ih: int) -> None:
        from tilekit.plugins.isohedral.engine import IsohedralTiling

        self.template = get_template(ih)
        if not self.template.marked:
            raise ParameterError(f"IH{ih} is unmarked; use IsohedralTiling")
        host = IsohedralTiling(laves_host(self.template.topology))
        outline = host.prototile.outline
        c = centroid(outline)
        r = 0.12 * np.sqrt(abs(host.prototile.area))
        ang = np.linspace(0, 2 * np.pi, 17)
        ring = np.column_stack([c[0] + r * np.cos(ang), c[1] + r * np.sin(ang)])
        proto = Prototile(outline, marking=(ring,), name=f"IH{ih}", corners=host.prototile.corners)
        super().__init__(
            [proto], host.unit_prototile, host.unit_transform, host.v1, host.v2, host.colouring,
            host.unit_aspect, family="isohedral", name=f"IH{ih}",
        )
        self.host = host.template.ih

    def spec(self) -> dict[str, Any]:
        return {"ih": self.template.ih}

    def describe(self) -> str:
        return self.template.text() + f"\ndrawn as the Laves tiling of IH{self.host} with marked tiles"

    def properties(self) -> dict[str, Any]:
        from tilekit.plugins.isohedral.records import type_properties

        return type_properties(self.template.ih)


def marked_tiling(ih: int) -> MarkedTiling:
    return MarkedTiling(ih)
