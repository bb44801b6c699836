"""Options and tables as text, shared by the command line and the web API: comma lists of
numbers (``--param``), regions ``x0,y0,x1,y1`` (``--region``, ``?region=``), ``KEY=VALUE``
settings (``--set``), and the plain fixed-width table the listing commands print."""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from typing import Any

from tilekit import limits
from tilekit.errors import ParseError

__all__ = ["MAX_PARAM", "configure_options", "format_value", "parse_floats", "parse_region", "parse_settings", "text_table"]

#: Largest |value| of a tiling parameter (--param): shapes are unit-sized, so beyond this a
#: value is a typo and would only overflow the geometry.
MAX_PARAM = 1e6


def parse_floats(text: str, what: str, bound: float = limits.MAX_COORDINATE) -> list[float]:
    """``"x,y,..."`` -> finite floats within ±``bound``; ``what`` names the option in errors."""
    out: list[float] = []
    for part in text.split(","):
        part = part.strip()
        if not part:
            continue
        try:
            value = float(part)
        except ValueError:
            raise ParseError(f"{what} {text!r}: {part!r} is not a number") from None
        if not math.isfinite(value):
            raise ParseError(f"{what} {text!r}: {part!r} is not a finite number")
        if abs(value) > bound:
            raise ParseError(f"{what} {text!r}: {part!r} is outside ±{bound:g}")
        out.append(value)
    return out


def parse_region(text: str) -> tuple[float, float, float, float]:
    """``x0,y0,x1,y1`` -> a box with x0 < x1 and y0 < y1."""
    values = parse_floats(text, "--region")
    if len(values) != 4:
        raise ParseError(f"--region {text!r} needs four numbers x0,y0,x1,y1")
    x0, y0, x1, y1 = values
    if not (x0 < x1 and y0 < y1):
        raise ParseError(f"--region {text!r} needs x0 < x1 and y0 < y1")
    return x0, y0, x1, y1


def parse_settings(items: Sequence[str]) -> dict[str, str]:
    """``KEY=VALUE`` strings -> a dict (values stay text; the family parses them)."""
    out: dict[str, str] = {}
    for item in items:
        key, sep, value = item.partition("=")
        key = key.strip()
        if not sep or not key:
            raise ParseError(f"--set {item!r} is not KEY=VALUE")
        out[key] = value.strip()
    return out


def configure_options(params: Sequence[str] = (), edges: Sequence[str] = (), settings: Sequence[str] = (),
                      which: str | None = None, depth: int | None = None) -> dict[str, Any]:
    """The options of ``Tiling.configure`` from their text on the command line: ``--param``
    (comma lists, each within ±MAX_PARAM), ``--edge`` shapes, ``--depth``, ``--set KEY=VALUE``
    and ``--tiling WHICH`` (the same as ``--set tiling=WHICH``); only the ones given."""
    options: dict[str, Any] = {}
    if params:
        options["params"] = [v for p in params for v in parse_floats(p, "--param", MAX_PARAM)]
    if edges:
        options["edges"] = list(edges)
    if depth is not None:
        options["depth"] = depth
    options.update(parse_settings(settings))
    if which is not None:
        options["tiling"] = which
    return options


def format_value(value: Any) -> str:
    """A property value as one table cell (true/false, ``-`` for None, 6 significant digits)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, list) and any(isinstance(v, list | dict) for v in value):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list):
        return ", ".join(format_value(v) for v in value) if value else "[]"
    if isinstance(value, dict):
        return json.dumps(value, ensure_ascii=False)
    return str(value)


def text_table(headers: Sequence[str], rows: Sequence[Sequence[Any]], widths: dict[int, int] | None = None) -> str:
    """A plain fixed-width table (column i clipped to ``widths[i]`` characters)."""
    widths = widths or {}
    cells = [[format_value(c) if not isinstance(c, str) else c for c in row] for row in rows]
    for row in cells:
        for i, limit in widths.items():
            if len(row[i]) > limit:
                row[i] = row[i][: limit - 1] + "…"
    sizes = [len(h) for h in headers]
    for row in cells:
        sizes = [max(s, len(c)) for s, c in zip(sizes, row)]
    lines = ["  ".join(h.upper().ljust(s) for h, s in zip(headers, sizes)).rstrip()]
    for row in cells:
        lines.append("  ".join(c.ljust(s) for c, s in zip(row, sizes)).rstrip())
    return "\n".join(lines)
