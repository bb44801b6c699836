"""Catalogue records of the 93 isohedral types and their indexed properties.

Cheap properties come straight from the templates; the symmetry facts (wallpaper group,
perfect default colouring, Heesch type) are computed by :mod:`.analysis` and stored in
catalogue/isohedral/properties.tsv so that seeding a catalogue stays fast. Regenerate with
``python -m tilekit.plugins.isohedral.records`` (a test recomputes and compares).
"""

from __future__ import annotations

import sys
from typing import Any

from tilekit.plugins import CatalogueRecord
from tilekit.plugins.isohedral.analysis import (
    ORBIFOLD_TO_IUC,
    heesch_type,
    is_perfect_colouring,
    wallpaper_group,
)
from tilekit.plugins.isohedral.properties import (
    _COLUMNS,
    PROPERTIES_FILE,
    stored_properties,
    type_properties,
)
from tilekit.plugins.isohedral.spec import tiling_from_spec
from tilekit.plugins.isohedral.templates import data_dir, load_templates
from tilekit.polygon import edge_to_edge

__all__ = ["computed_properties", "properties_table_text", "records", "stored_properties", "type_properties"]



def computed_properties(ih: int) -> dict[str, Any]:
    """Recompute the symmetry facts of one type from its tiling."""
    tiling = tiling_from_spec({"ih": ih})
    group = wallpaper_group(tiling)  # type: ignore[arg-type]
    out: dict[str, Any] = {"symmetry_group": group, "orbifold": group, "wallpaper_group": ORBIFOLD_TO_IUC[group]}
    # §4.1: the default tile's corners and the tiling vertices coincide (read from a patch)
    patch = tiling.patch(tiling.default_region())
    out["edge_to_edge"] = edge_to_edge(pts for _, _, pts in patch.groups())
    if load_templates()[ih].marked:  # no default colouring in the book for these
        return out
    out["perfect_colouring"] = is_perfect_colouring(tiling)  # type: ignore[arg-type]
    heesch = heesch_type(tiling)  # type: ignore[arg-type]
    if heesch is not None:
        out["heesch_type"] = heesch
    return out


def properties_table_text() -> str:
    """The text of properties.tsv, recomputed."""
    lines = [
        "# Symmetry facts of the isohedral types, computed by tilekit.plugins.isohedral.analysis",
        "# (regenerate: python -m tilekit.plugins.isohedral.records). Columns: " + " ".join(_COLUMNS),
    ]
    for ih in sorted(load_templates()):
        p = computed_properties(ih)
        lines.append(
            "\t".join(
                [
                    str(ih),
                    p["symmetry_group"],
                    p["wallpaper_group"],
                    {True: "yes", False: "no", None: "-"}[p.get("perfect_colouring")],
                    p.get("heesch_type", "-"),
                    "yes" if p["edge_to_edge"] else "no",
                ]
            )
        )
    return "\n".join(lines) + "\n"


def records() -> list[CatalogueRecord]:
    """One record per isohedral type, named IH1..IH93 (aliases ih16, IH016)."""
    out = []
    for ih, t in sorted(load_templates().items()):
        title = f"Isohedral type IH{ih} ({t.topology} {t.symbol})" if t.symbol else f"Isohedral type IH{ih} ({t.topology}, marked)"
        out.append(
            CatalogueRecord(
                family="isohedral",
                name=f"IH{ih}",
                spec={"ih": ih},
                title=title,
                properties=type_properties(ih),
                aliases=[f"ih{ih}", f"IH{ih:03d}"],
            )
        )
    return out


def main() -> None:  # pragma: no cover - maintenance script
    path = data_dir() / PROPERTIES_FILE
    path.write_text(properties_table_text(), encoding="utf-8")
    print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":  # pragma: no cover
    main()
