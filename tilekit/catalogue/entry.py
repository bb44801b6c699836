"""What a catalogue read returns, without SQLAlchemy: the :class:`Entry` of one tiling, how a
typed property row is restored, and the names of the ``tilings`` columns that filters and
orderings may name. The catalogue's SQLite read path (:mod:`tilekit.catalogue.reading`)
imports only this, the filters and the standard library."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

from tilekit.plugins import get_family

#: The properties mirrored in indexed columns of ``tilings`` and their Python types.
SHARED_COLUMNS: dict[str, type] = {
    "periodic": bool,
    "k_hedral": int,
    "k_isohedral": int,
    "edge_to_edge": bool,
    "symmetry_group": str,
}

#: Columns of ``tilings`` a filter or ``order_by`` may name directly (besides SHARED_COLUMNS).
TEXT_COLUMNS: tuple[str, ...] = ("name", "family", "title")


@dataclass
class Entry:
    """One catalogue tiling as a query returns it (properties with their lists restored)."""

    name: str
    family: str
    title: str
    spec: dict[str, Any]
    properties: dict[str, Any] = field(default_factory=dict)
    aliases: list[str] = field(default_factory=list)
    id: int | None = None

    def flat(self) -> dict[str, Any]:
        """``{"name", "family", "title", **properties}`` (the shape ``tilekit list`` prints)."""
        return {"name": self.name, "family": self.family, "title": self.title, **self.properties}

    def full(self) -> dict[str, Any]:
        """Everything, spec included (the shape ``export`` writes)."""
        return {
            "name": self.name,
            "family": self.family,
            "title": self.title,
            "aliases": list(self.aliases),
            "properties": dict(self.properties),
            "spec": self.spec,
        }

    def _repr_mimebundle_(self, include: Any = None, exclude: Any = None) -> dict[str, str]:
        """Jupyter shows the entry's name and title over a drawing of its tiling (the tiling's
        own picture, under limits.MAX_REPR_TILES; a line of text above it)."""
        from html import escape

        text = f"{self.name} ({self.family}): {self.title}"
        head = f"<div><b>{escape(self.name)}</b> <i>{escape(self.family)}</i> — {escape(self.title)}</div>"
        drawn = get_family(self.family).from_spec(self.spec)._repr_mimebundle_()
        svg = drawn.get("image/svg+xml")
        body = svg if svg is not None else f"<div>{escape(drawn['text/plain'])}</div>"
        return {"text/plain": text, "text/html": head + body}

    def _repr_svg_(self) -> str | None:
        """The tiling's picture alone (None over limits.MAX_REPR_TILES)."""
        return get_family(self.family).from_spec(self.spec)._repr_svg_()


def restore_value(kind: str, text: str | None, num: float | None, flag: bool | None) -> Any:
    """A property value from its typed row (``kind`` says which of the three columns holds it)."""
    if kind == "str":
        return text
    if kind == "int":
        return int(num) if num is not None else None
    if kind == "float":
        return num
    if kind == "bool":
        return bool(flag) if flag is not None else None
    if kind == "json":
        return json.loads(text) if text is not None else None
    return None
