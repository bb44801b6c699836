"""Catalogue records of the 93 isohedral types and their indexed properties.

Cheap properties come straight from the templates; the symmetry facts (wallpaper group,
perfect default colouring, Heesch type) are computed by :mod:`.analysis` and stored in
catalogue/isohedral/properties.tsv so that seeding a catalogue stays fast. Regenerate with
``python -m tilekit.plugins.isohedral.records`` (a test recomputes and compares).
"""

from __future__ import annotations

import sys
from functools import cache, lru_cache
from typing import Any

from tilekit.errors import ParseError
from tilekit.plugins import CatalogueRecord
from tilekit.plugins.isohedral.templates import (
    data_dir,
    load_parameterizations,
    load_templates,
    topology_valences,
)

PROPERTIES_FILE = "properties.tsv"
_COLUMNS = ("ih", "symmetry_group", "symmetry_group_iuc", "perfect_colouring", "heesch_type")


def computed_properties(ih: int) -> dict[str, Any]:
    """Recompute the symmetry facts of one type from its tiling."""
    from tilekit.plugins.isohedral.analysis import (
        ORBIFOLD_TO_IUC,
        heesch_type,
        is_perfect_colouring,
        wallpaper_group,
    )
    from tilekit.plugins.isohedral.engine import tiling_from_spec

    tiling = tiling_from_spec({"ih": ih})
    group = wallpaper_group(tiling)  # type: ignore[arg-type]
    out: dict[str, Any] = {"symmetry_group": group, "orbifold": group, "wallpaper_group": ORBIFOLD_TO_IUC[group]}
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
                ]
            )
        )
    return "\n".join(lines) + "\n"


@lru_cache(maxsize=1)
def stored_properties() -> dict[int, dict[str, Any]]:
    path = data_dir() / PROPERTIES_FILE
    out: dict[int, dict[str, Any]] = {}
    for lineno, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if not raw.strip() or raw.startswith("#"):
            continue
        parts = raw.split("\t")
        if len(parts) != len(_COLUMNS) or parts[3] not in ("yes", "no", "-"):
            raise ParseError(f"{PROPERTIES_FILE}, line {lineno}: expected {len(_COLUMNS)} tab-separated columns {_COLUMNS}")
        # catalogue-wide keys: symmetry_group and orbifold in orbifold notation,
        # wallpaper_group in IUC notation (as the archimedean and other families report them)
        row: dict[str, Any] = {"symmetry_group": parts[1], "orbifold": parts[1], "wallpaper_group": parts[2]}
        if parts[3] != "-":
            row["perfect_colouring"] = parts[3] == "yes"
        if parts[4] != "-":
            row["heesch_type"] = parts[4]
        out[int(parts[0])] = row
    return out


@cache
def type_properties(ih: int) -> dict[str, Any]:
    """The catalogue properties of IHn (JSON scalars only)."""
    t = load_templates()[ih]
    n = len(topology_valences(t.topology))
    props: dict[str, Any] = {
        "ih": ih,
        "topology": t.topology,
        "marked": t.marked,
        "periodic": True,
        "k_hedral": 1,
        "k_isohedral": 1,
        "edges": n,
    }
    if t.symbol is not None:
        kinds = t.symbol.edge_kinds()
        props.update(
            incidence_symbol=str(t.symbol),
            canonical_symbol=str(t.symbol.canonical()),
            edge_kinds=kinds,
            j_edges=kinds.count("J"),
            u_edges=kinds.count("U"),
            s_edges=kinds.count("S"),
            i_edges=kinds.count("I"),
        )
    if t.marked:
        props.update(stored_properties().get(ih, {}))
        return props
    tv = load_parameterizations()[t.parameterization or ""]
    col = t.colouring
    props.update(
        parameterization=t.parameterization,
        parameters=tv.parameters,
        aspects=len(t.aspects),
        tiles_per_unit=len(t.aspects),
        colours=col.colours if col else 1,
    )
    props.update(stored_properties().get(ih, {}))
    return props


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
