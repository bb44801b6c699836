"""The catalogue properties of each isohedral type: read from the templates and from the
stored symmetry facts (catalogue/isohedral/properties.tsv, written by :mod:`.records`)."""

from __future__ import annotations

from functools import cache, lru_cache
from typing import Any

from tilekit.errors import ParseError
from tilekit.plugins.isohedral.templates import (
    data_dir,
    load_parameterizations,
    load_templates,
    topology_valences,
)

PROPERTIES_FILE = "properties.tsv"
_COLUMNS = ("ih", "symmetry_group", "symmetry_group_iuc", "perfect_colouring", "heesch_type", "edge_to_edge")


@lru_cache(maxsize=1)
def stored_properties() -> dict[int, dict[str, Any]]:
    path = data_dir() / PROPERTIES_FILE
    out: dict[int, dict[str, Any]] = {}
    for lineno, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if not raw.strip() or raw.startswith("#"):
            continue
        parts = raw.split("\t")
        if len(parts) != len(_COLUMNS) or parts[3] not in ("yes", "no", "-") or parts[5] not in ("yes", "no"):
            raise ParseError(f"{PROPERTIES_FILE}, line {lineno}: expected {len(_COLUMNS)} tab-separated columns {_COLUMNS}")
        # catalogue-wide keys: symmetry_group and orbifold in orbifold notation,
        # wallpaper_group in IUC notation (as the archimedean and other families report them)
        row: dict[str, Any] = {"symmetry_group": parts[1], "orbifold": parts[1], "wallpaper_group": parts[2]}
        if parts[3] != "-":
            row["perfect_colouring"] = parts[3] == "yes"
        if parts[4] != "-":
            row["heesch_type"] = parts[4]
        row["edge_to_edge"] = parts[5] == "yes"
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
        "sides": n,  # a list of one in the catalogue (vocabulary.normalise_properties)
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
