"""Tilings named in other people's notations: a GomJau-Hogg string (:mod:`.gomjau`), a
Gavrog D-symbol (``<1.1:...>``) or a tes-catalog file (:mod:`.tes`) read to a minimal D-symbol, and the catalogue filter that
finds its record; the two notations of the eleven Archimedean tilings, added to the
archimedean family's records from a shipped table that
:func:`tilekit.plugins.kuniform.search.archimedean_table` rebuilds.
"""

from __future__ import annotations

import json
import re
from functools import cache
from pathlib import Path
from typing import Any

from tilekit.errors import ParseError
from tilekit.plugins.kuniform.dsymbol import DSymbol, from_gavrog, to_gavrog

#: A GomJau-Hogg notation: a seed polygon, phases, and at least one '/' transform.
GOMJAU = re.compile(r"^\s*\d+(\s*-\s*[\d,\s]*)*/")
ARCHIMEDEAN_TABLE = Path(__file__).parent / "archimedean_notations.json"


def symbol_of(text: str) -> DSymbol | None:
    """The minimal D-symbol a notation names, None if ``text`` is in neither notation.
    ParseError (one line) for text that is one of them but malformed; GeometryError for a
    GomJau-Hogg arrangement that is not a tiling."""
    t = text.strip()
    if t.startswith("<"):
        try:
            return from_gavrog(t).minimal_image()
        except ValueError as exc:
            raise ParseError(f"Gavrog D-symbol {t[:60]!r}: {exc}") from None
    if GOMJAU.match(t):
        # start-up cost: the notation and search modules (NumPy, shapely) load only when used
        from tilekit.plugins.kuniform.gomjau import parse

        return parse(t).symbol
    if t.lower().endswith(".tes"):
        # start-up cost: the notation and search modules (NumPy, shapely) load only when used
        from tilekit.plugins.kuniform.tes import read_tes

        return read_tes(t)[1]
    return None


def resolve(name: str) -> list[str] | None:
    """The ``--where`` filter finding the tiling a notation names (its D-symbol text)."""
    sym = symbol_of(name)
    return None if sym is None else [f"dsymbol={sym.encode()}"]


def notation_properties(sym: DSymbol) -> dict[str, Any]:
    """``dsymbol`` (this plugin's text), ``gavrog`` and ``gomjau`` where the writer finds one;
    where it does not, ``gomjau_missing`` says why (no notation can exist, or none was found
    within the writer's budget)."""
    # start-up cost: the notation and search modules (NumPy, shapely) load only when used
    from tilekit.plugins.kuniform.gomjau import write_outcome

    props: dict[str, Any] = {"dsymbol": sym.encode(), "gavrog": to_gavrog(sym)}
    text, why = write_outcome(sym)
    if text is not None:
        props["gomjau"] = text
    else:
        props["gomjau_missing"] = why
    return props


def archimedean_properties(record: Any) -> dict[str, Any] | None:
    """The shipped notations for an archimedean-family tiling record (by its vertex type)."""
    if getattr(record, "family", None) != "archimedean" or record.properties.get("kind") != "tiling":
        return None
    return _table().get(str(record.properties.get("vertex_type")))


@cache
def _table() -> dict[str, dict[str, Any]]:
    return json.loads(ARCHIMEDEAN_TABLE.read_text())
