"""The ``k-uniform`` search and the k-uniform tilings as catalogue records (§4.1).

A run splits into one chunk per multiset of k vertex types (of the 21 whose angles sum to
2π); a chunk tries every choice of stabilizer class for each orbit (equal types take their
classes as a multiset, so no choice is tried twice), collects the minimal D-symbols with
exactly those vertex orbits (:mod:`.dsymbol`), merges isomorphic ones, lays each out
(:mod:`.realize`) and names it. A tiling's multiset of orbit types is an invariant, so every
tiling belongs to exactly one chunk and no two chunks write the same record.
"""

from __future__ import annotations

import itertools
import json
import time
from collections.abc import Iterator, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from tilekit.errors import ParseError
from tilekit.plugins import CatalogueRecord, ChunkResult, Search, SearchParam
from tilekit.plugins.kuniform.dsymbol import (
    DSymbol,
    Star,
    minimal_symbols,
    stabilizer_classes,
    star_numbers,
    to_gavrog,
    vertex_types,
)
from tilekit.plugins.kuniform.gomjau import MAX_PLACEMENTS
from tilekit.plugins.kuniform.names import ARCHIMEDEAN_TABLE, notation_properties
from tilekit.plugins.kuniform.realize import periodic_tiling
from tilekit.plugins.kuniform.tes import read_tes
from tilekit.plugins.kuniform.tescatalog import tes_catalog_id
from tilekit.regular.notation import VertexType, format_sequence
from tilekit.regular.tiles import unit_text
from tilekit.symmetry import ORBIFOLD, wallpaper_group
from tilekit.tiling import PeriodicTiling

if TYPE_CHECKING:
    import numpy as np

FAMILY = "k-uniform"
#: The largest k a run accepts (Galebach's published enumeration ends at 6; the tes-catalog
#: and OEIS A068599 give 1,472 for k = 7 and 2,850 for k = 8); docs/benchmarks.md has the times
#: (k = 8: hours of CPU; k = 9 would be about 10x that).
MAX_K = 8


def _order(seq: tuple[int, ...]) -> tuple:
    """Orbit types are listed by decreasing degree, then by sequence (``[3^6; 3^4.6]``,
    ``[3.4.3.12; 3.12^2]``), as in the published lists."""
    return (-len(seq), seq)


def types_text(types: Sequence[tuple[int, ...]]) -> str:
    """``[3^6; (3^4.6)^2]``: the orbit types in order, repeats as exponents."""
    parts = []
    for seq, run in itertools.groupby(sorted(types, key=_order)):
        n = len(list(run))
        text = format_sequence(seq)
        parts.append(f"({text})^{n}" if n > 1 else text)
    return "[" + "; ".join(parts) + "]"


class KUniformTiling(PeriodicTiling):
    """A k-uniform tiling, rebuilt from its D-symbol."""

    def __init__(self, *args: Any, symbol: DSymbol, name: str = "", family: str = FAMILY, **kw: Any) -> None:
        super().__init__(*args, family=family, name=name, **kw)
        self.symbol = symbol

    @property
    def orbit_types(self) -> list[tuple[int, ...]]:
        return sorted((self.symbol.vertex_type(o[0]) for o in self.symbol.vertex_orbits()), key=_order)

    def spec(self) -> dict[str, Any]:
        return {"kind": FAMILY, "dsymbol": self.symbol.encode()}

    def describe(self) -> str:
        return (
            f"{len(self.orbit_types)}-uniform: vertex orbits {types_text(self.orbit_types)}.\n"
            f"{unit_text(self, tuple(sorted(set(self.symbol.face))))}\n"
            f"D-symbol ({self.symbol.size} chambers): {self.symbol.encode()}\n"
            f"Gavrog D-symbol: {to_gavrog(self.symbol)}"
        )

    def properties(self) -> dict[str, Any]:
        props = super().properties()
        types = self.orbit_types
        props.update({
            "k": len(types),
            "k_isogonal": len(types),
            "vertex_types": len(set(types)),
            "vertex_type": sorted({format_sequence(t) for t in types}),
            "orbit_types": types_text(types),
            "sides": sorted(set(self.symbol.face)),
            "k_hedral": len(set(self.symbol.face)),
            "edge_to_edge": True,
            "chambers": self.symbol.size,
            "dsymbol": self.symbol.encode(),
            "unit_tiles": len(self.unit_prototile),
        })
        return props


def tiling_of(symbol: DSymbol, name: str = "") -> KUniformTiling:
    return periodic_tiling(symbol, name=name, cls=KUniformTiling, symbol=symbol)


def from_spec(spec: Mapping[str, Any]) -> KUniformTiling:
    text = spec.get("dsymbol") if isinstance(spec, Mapping) else None
    if not isinstance(text, str):
        raise ParseError("a k-uniform spec needs 'dsymbol': the text m01/m12/σ0/σ1/σ2")
    try:
        symbol = DSymbol.decode(text)
    except ValueError as exc:
        raise ParseError(f"k-uniform spec: {exc}") from None
    name = spec.get("name", "")
    return tiling_of(symbol, name=name if isinstance(name, str) else "")


# --------------------------------------------------------------------------- the search


def edge_pairs(seq: tuple[int, ...]) -> set[frozenset[int]]:
    """The pairs of face sizes on the edges at a vertex of type ``seq``."""
    return {frozenset((seq[j - 1], seq[j])) for j in range(len(seq))}


def linked(types: Sequence[tuple[int, ...]]) -> bool:
    """Whether the types are connected by shared edge pairs: an edge glues two vertices
    with the same pair of faces on it, and a tiling's D-symbol is connected, so a multiset
    whose graph (types joined when they share an edge pair) falls apart holds no tiling.
    This drops every mixture with 3.7.42, 3.8.24, 3.9.18, 3.10.15, 4.5.20, 5.5.10 or 4.8^2."""
    distinct = sorted(set(types))
    pairs = [edge_pairs(t) for t in distinct]
    seen, stack = {0}, [0]
    while stack:
        i = stack.pop()
        for j in range(len(distinct)):
            if j not in seen and pairs[i] & pairs[j]:
                seen.add(j)
                stack.append(j)
    return len(seen) == len(distinct)


def chunks(params: Mapping[str, Any]) -> Iterator[dict[str, Any]]:
    """One chunk per multiset of k vertex types (C(21 + k - 1, k) of them), less the 21
    multisets of a single type when k >= 2: the tilings with every vertex of one type are
    the eleven Archimedean ones (Kaplan §4.1; Grünbaum & Shephard, *Tilings and Patterns*,
    2.1.3), each 1-uniform. The search itself confirms this for k <= 3 (tests). Multisets
    that are not :func:`linked` are left out too."""
    k = int(params["k"])
    for combo in itertools.combinations_with_replacement(vertex_types(), k):
        if k >= 2 and len(set(combo)) == 1:
            continue
        if not linked([t.polygons for t in combo]):
            continue
        yield {"types": [str(t) for t in combo]}


def star_choices(types: Sequence[tuple[int, ...]]) -> Iterator[tuple[Star, ...]]:
    """Every multiset of (type, stabilizer class) with the given multiset of types."""
    groups = [(seq, len(list(run))) for seq, run in itertools.groupby(sorted(types))]
    per_group = [
        list(itertools.combinations_with_replacement(range(len(stabilizer_classes(seq))), n)) for seq, n in groups
    ]
    for pick in itertools.product(*per_group):
        yield tuple(Star(seq, i) for (seq, _n), classes in zip(groups, pick) for i in classes)


def star_rows(types: Sequence[tuple[int, ...]]) -> np.ndarray:
    """:func:`star_choices` as rows of star numbers (positions in :func:`.dsymbol.stars`),
    in the same order, built as arrays (a k = 7 chunk has up to ~10^5 of them)."""
    import numpy as np  # start-up cost: only when a search runs

    groups = [(seq, len(list(run))) for seq, run in itertools.groupby(sorted(types))]
    blocks = []
    for seq, n in groups:
        first = star_numbers([Star(seq, 0)])[0]  # a type's stars are consecutive, class order
        picks = np.array(list(itertools.combinations_with_replacement(range(len(stabilizer_classes(seq))), n)),
                         dtype=np.int64).reshape(-1, n)
        blocks.append(first + picks)
    index = np.indices([len(b) for b in blocks]).reshape(len(blocks), -1)
    return np.concatenate([b[i] for b, i in zip(blocks, index)], axis=1)


def tilings_with_types(types: Sequence[tuple[int, ...]]) -> list[DSymbol]:
    """The k-uniform tilings whose vertex orbits have exactly these types (one minimal
    D-symbol each, chambers in canonical order, in the order of their encodings)."""
    found: dict[tuple, DSymbol] = {}
    if not linked(types):
        return []
    for _row, sym in minimal_symbols(star_rows(types)):
        found.setdefault(sym.canonical_form(), sym)
    return sorted((DSymbol.decode(s.encode()) for s in found.values()), key=lambda s: s.encode())


def record_of(tiling: KUniformTiling, name: str, iuc: str) -> CatalogueRecord:
    """The catalogue record of a laid-out tiling whose wallpaper group is ``iuc``."""
    props = tiling.properties()
    props.update({"wallpaper_group": iuc, "orbifold": ORBIFOLD[iuc], "symmetry_group": ORBIFOLD[iuc]})
    props.update(notation_properties(tiling.symbol))
    ident = tes_catalog_id(props["dsymbol"])
    if ident is not None:
        props["tes_catalog"] = ident
    spec = tiling.spec()
    spec["name"] = name
    return CatalogueRecord(FAMILY, name, spec, title=f"{props['k']}-uniform tiling {props['orbit_types']}, {iuc}",
                           properties=props)


def records_for(types: Sequence[tuple[int, ...]]) -> list[CatalogueRecord]:
    """Named records for the tilings of one type multiset: ``[types] group``, with ``#i``
    when several share both (numbered in the order of their D-symbol encodings)."""
    named: dict[str, list[tuple[KUniformTiling, str]]] = {}
    for sym in tilings_with_types(types):
        tiling = tiling_of(sym)
        iuc = wallpaper_group(tiling).iuc
        named.setdefault(f"{types_text(types)} {iuc}", []).append((tiling, iuc))
    out = []
    for base, items in named.items():
        for i, (tiling, iuc) in enumerate(items, 1):
            name = base if len(items) == 1 else f"{base} #{i}"
            tiling.name = name
            out.append(record_of(tiling, name, iuc))
    return out


def run_chunk(params: Mapping[str, Any], chunk: Mapping[str, Any]) -> ChunkResult:
    started = time.perf_counter()
    types = [VertexType.parse(t).polygons for t in chunk["types"]]
    records = records_for(types)
    results = [{"name": r.name, "vertex_types": r.properties["vertex_types"],
                "wallpaper_group": r.properties["wallpaper_group"]} for r in records]
    distinct = len(set(types))
    counts: dict[str, int | float] = {"tilings": len(records), "type_multisets": 1,
                                      "seconds": round(time.perf_counter() - started, 3)}
    counts[f"with_{distinct}_types"] = len(records)
    return ChunkResult(results=results, records=records, counts=counts)


def summarize(params: Mapping[str, Any], results: list[dict[str, Any]]) -> dict[str, Any]:
    by_group: dict[str, int] = {}
    for r in results:
        by_group[r["wallpaper_group"]] = by_group.get(r["wallpaper_group"], 0) + 1
    return {"k": int(params["k"]), "found": len(results), "by_wallpaper_group": dict(sorted(by_group.items()))}


SEARCH = Search(
    name="k-uniform",
    summary=("Enumerate the k-uniform tilings by regular polygons (k vertex orbits) from their D-symbols; "
             f"each record's GomJau-Hogg notation is written from at most {MAX_PLACEMENTS} placements "
             "(else gomjau_missing says why)"),
    family=FAMILY,
    params=(SearchParam("k", int, None, "number of vertex orbits (transitivity classes)", required=True,
                        min=1, max=MAX_K),),
    chunks=chunks,
    run_chunk=run_chunk,
    summarize=summarize,
)


def tiling_from_file(path: str) -> Any:
    """The k-uniform tiling a .tes file describes (``tilekit render --system FILE.tes``)."""
    name, sym = read_tes(path)
    return tiling_of(sym, name=name)


def archimedean_table() -> dict[str, dict[str, Any]]:
    """For each Archimedean vertex type: the notations of its tiling (its 1-uniform symbol)."""
    out = {}
    for vt in vertex_types():
        for sym in tilings_with_types([vt.polygons]):
            out[format_sequence(vt.polygons)] = notation_properties(sym)
    return dict(sorted(out.items()))


if __name__ == "__main__":  # pragma: no cover - regenerates the shipped table
    ARCHIMEDEAN_TABLE.write_text(json.dumps(archimedean_table(), indent=1) + "\n")
