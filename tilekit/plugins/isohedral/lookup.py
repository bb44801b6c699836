"""Identify an isohedral type from its topological type and any of its incidence symbols (§5.2)."""

from __future__ import annotations

from functools import lru_cache

from tilekit.errors import NotFoundError, ParameterError, ParseError
from tilekit.incidence import IncidenceSymbol
from tilekit.plugins.isohedral.templates import load_templates, topology_valences


def _topology_key(topology: str) -> tuple[int, ...]:
    """Topological types compared as cyclic valence sequences up to rotation and reflection."""
    vals = topology_valences(topology)
    n = len(vals)
    cands = [tuple(vals[i:] + vals[:i]) for i in range(n)]
    rev = vals[::-1]
    cands += [tuple(rev[i:] + rev[:i]) for i in range(n)]
    return min(cands)


@lru_cache(maxsize=1)
def canonical_index() -> dict[tuple[tuple[int, ...], str], int]:
    out: dict[tuple[tuple[int, ...], str], int] = {}
    for ih, t in load_templates().items():
        if t.symbol is None:
            continue
        out[(_topology_key(t.topology), str(t.symbol.canonical()))] = ih
    return out


def lookup(topology: str, symbol: str | IncidenceSymbol) -> int:
    """The IH number of the type with this topology and (any form of) incidence symbol.

    Exercise 5.6: the topology matters, since different types can share a symbol.
    """
    sym = IncidenceSymbol.parse(symbol) if isinstance(symbol, str) else symbol
    n = len(topology_valences(topology))
    if len(sym) != n:
        raise ParseError(f"symbol {sym} has {len(sym)} edges but topology {topology} has {n}")
    key = (_topology_key(topology), str(sym.canonical()))
    try:
        return canonical_index()[key]
    except KeyError:
        raise NotFoundError(
            "isohedral type with topology and symbol", f"{topology} {sym}",
            [f"{t.topology} {t.symbol}" for t in load_templates().values() if t.topology == topology and t.symbol],
        ) from None


def normalised(key: str, value: str) -> tuple[str, str] | None:
    """The ``tilekit_normalise`` answer of the isohedral family: an incidence symbol filter
    becomes its canonical form (``canonical_symbol``), and a name that is an incidence symbol,
    optionally after its topology (``3^6 [a+b+c+c-b-a-; a-c+b+]``), becomes the IH name of the
    one type it describes; a bare symbol shared by types of several topologies (exercise 5.6)
    is a ParameterError naming them."""
    text = value.strip()
    if "[" not in text or ";" not in text:
        return None
    topology, _, rest = text.partition("[")
    try:
        sym = IncidenceSymbol.parse("[" + rest)
    except ParseError:
        return None
    canonical = str(sym.canonical())
    if key in ("incidence_symbol", "canonical_symbol"):
        return "canonical_symbol", canonical
    if key != "name":
        return None
    if topology.strip():
        try:
            return "name", f"IH{lookup(topology.strip(), sym)}"
        except (ParseError, NotFoundError):
            return None
    matches = sorted(ih for (_, form), ih in canonical_index().items() if form == canonical)
    if len(matches) > 1:
        templates = load_templates()
        raise ParameterError(
            f"incidence symbol {sym} describes {', '.join(f'IH{ih} ({templates[ih].topology})' for ih in matches)}; "
            f"give the topology too, e.g. '{templates[matches[0]].topology} {sym}'")
    return ("name", f"IH{matches[0]}") if matches else None
