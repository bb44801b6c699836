"""Declarative schemas for the project's own TOML / JSON data: what each field is (its kind,
required or optional, its default, its choices or range, the items of a list, the fields of
a table), checked by one loader, :func:`check`, that raises one-line ParseErrors naming the
file and the field.

A schema is data, written next to the loader of a format:

>>> POINT = Field("list", items=Field("number"), length=(2, 2))
>>> TILE = Field("table", fields={"name": Field("str", default="tile"),
...                               "outline": Field("list", required=True, items=POINT, length=(3, None))})
>>> check(TILE, {"outline": [[0, 0], [1, 0], [0, 1]]}, "tiles.toml")["name"]
'tile'
>>> check(TILE, {"outline": [[0, 0], [1, 0]]}, "tiles.toml")
Traceback (most recent call last):
...
tilekit.errors.ParseError: tiles.toml: outline must be a list of at least 3 items, got [[0, 0], [1, 0]]

Documents a user gives are parsed by :func:`parse_json` and :func:`parse_toml`: a syntax error,
nesting deeper than ``limits.MAX_NESTING`` (Python's parsers recurse once per level), a
non-finite number or an integer too long to convert are one ParseError, never a
RecursionError or ValueError. Numbers checked by a schema must be finite (a 400-digit integer
or ``inf`` is not a parameter), and integers fit in 64 bits unless the field's range says
otherwise.

Paths are TOML's dotted keys (``placement.steps[3]``, counting list items from 1). A field's
``error`` (and ``missing``) replaces the generic message where a format has a message of its
own; it may name ``{path}``, ``{value}`` and ``{n}`` (the 1-based number of the list item the
field belongs to). Line numbers come from the TOML parser where it gives one
(:func:`tilekit.resources.read_toml`: syntax errors); parsed values carry none.
"""

from __future__ import annotations

import json
import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from tilekit.errors import ParseError
from tilekit.limits import MAX_NESTING

#: The largest integer a schema's "int" field takes unless its range says otherwise (int64).
INT_LIMIT = 2**63 - 1


def finite_number(value: Any, what: str) -> float:
    """``value`` as a finite float, or a one-line ParseError naming ``what``."""
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError):
        raise ParseError(f"{what} {value!r} is not a number") from None
    if not math.isfinite(x):
        raise ParseError(f"{what} {value!r} is not a finite number")
    return x

__all__ = ["MISSING", "Field", "check", "check_nesting", "finite_number", "parse_json", "parse_toml", "shown"]


def check_nesting(value: Any, where: str, max_depth: int = MAX_NESTING) -> Any:
    """``value`` unchanged when its lists and tables nest at most ``max_depth`` deep (walked
    without recursion), else a one-line ParseError naming ``where``."""
    stack = [(value, 0)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, Mapping):
            children: Any = item.values()
        elif isinstance(item, list | tuple):
            children = item
        else:
            continue
        if depth >= max_depth:
            raise ParseError(f"{where}: lists and tables nest more than {max_depth} deep")
        stack.extend((child, depth + 1) for child in children)
    return value


def _bounded_int(digits: str, limit: int) -> int:
    n = len(digits.lstrip("-"))
    if n > limit:
        raise ParseError(f"an integer of {n:,} digits is out of range (at most {limit})")
    return int(digits)


def _no_constant(name: str) -> Any:
    raise ParseError(f"{name} is not a JSON number; give a finite number")


def parse_json(text: str | bytes, where: str, max_depth: int = MAX_NESTING, max_int_digits: int | None = None) -> Any:
    """JSON text as Python values, or a one-line ParseError naming ``where``: bad syntax,
    ``NaN`` / ``Infinity``, an integer of more digits than Python converts (or than
    ``max_int_digits``, checked before converting), nesting deeper than ``max_depth``."""
    extra: dict[str, Any] = {}
    if max_int_digits is not None:
        extra["parse_int"] = lambda digits: _bounded_int(digits, max_int_digits)
    try:
        value = json.loads(text, parse_constant=_no_constant, **extra)
    except ParseError as exc:
        raise ParseError(f"{where}: {exc}") from None
    except json.JSONDecodeError as exc:
        raise ParseError(f"{where}: not valid JSON ({exc.msg}, line {exc.lineno} column {exc.colno})") from None
    except RecursionError:
        raise ParseError(f"{where}: lists and tables nest more than {max_depth} deep") from None
    except (ValueError, UnicodeDecodeError) as exc:  # e.g. an integer of over 4,300 digits
        raise ParseError(f"{where}: not valid JSON ({str(exc)[:100]})") from None
    return check_nesting(value, where, max_depth)


def parse_toml(text: str, where: str, max_depth: int = MAX_NESTING) -> dict[str, Any]:
    """TOML text as a table, or a one-line ParseError naming ``where`` (with tomllib's line
    and column): bad syntax, an integer of more digits than Python converts, nesting deeper
    than ``max_depth``."""
    try:
        value = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParseError(f"{where}: not valid TOML ({exc})") from None
    except RecursionError:
        raise ParseError(f"{where}: lists and tables nest more than {max_depth} deep") from None
    except ValueError as exc:  # e.g. an integer of over 4,300 digits
        raise ParseError(f"{where}: not valid TOML ({str(exc)[:100]})") from None
    return check_nesting(value, where, max_depth)


class _Missing:
    def __repr__(self) -> str:
        return "MISSING"


#: The value of a key a table does not have.
MISSING: Any = _Missing()

_TYPES: dict[str, tuple[type, ...]] = {
    "str": (str,),
    "int": (int,),
    "number": (int, float),
    "bool": (bool,),
    "table": (Mapping,),
    "list": (list, tuple),
    "expr": (int, float, str),  # a number or an expression in named constants
    "ref": (int, str),  # a reference by index or by name
    "any": (object,),
}

_NAMES = {
    "str": "a string",
    "int": "an integer",
    "number": "a number",
    "bool": "true or false",
    "table": "a table",
    "list": "a list",
    "expr": "a number or an expression",
    "ref": "a name or an index",
    "any": "a value",
}


@dataclass(frozen=True)
class Field:
    """One field of a data format: ``kind`` (str, int, number, bool, table, list, expr, ref,
    any), whether it is ``required``, its ``default`` when absent, the ``choices`` or the
    inclusive ``range`` of its value, the ``items`` schema and ``length`` (min, max or None)
    of a list, the ``fields`` of a table and the schema of its other ``values``."""

    kind: str = "any"
    required: bool = False
    default: Any = MISSING
    choices: tuple[Any, ...] | None = None
    range: tuple[float | None, float | None] | None = None
    items: Field | None = None
    length: tuple[int, int | None] | None = None
    fields: Mapping[str, Field] = field(default_factory=dict)
    values: Field | None = None
    error: str | None = None
    missing: str | None = None

    def __post_init__(self) -> None:
        if self.kind not in _TYPES:
            raise ValueError(f"schema kind {self.kind!r} is not one of {', '.join(_TYPES)}")


def check(schema: Field, value: Any, where: str, path: str = "") -> Any:
    """``value`` checked against ``schema``: tables come back as new dicts with the defaults
    of absent optional fields filled in, lists as lists; anything else as it is. ``where``
    (e.g. ``"substitution system spectre.toml"``) begins every error message."""
    return _check(schema, value, where, path, 0)


def _fail(schema: Field, where: str, path: str, value: Any, n: int, problem: str, missing: bool = False) -> ParseError:
    template = (schema.missing if missing and schema.missing else None) or schema.error
    if template:
        shown = value
        if isinstance(value, int) and value.bit_length() > 200:
            shown = shown(value)
        elif isinstance(value, str) and len(value) > 60:
            shown = value[:57] + "..."
        msg = template.format(path=path, value=shown, n=n)
    else:
        msg = f"{path or 'top level'} {problem}"
    return ParseError(f"{where}: {msg}")


def shown(value: Any) -> str:
    """``value`` for an error message: its repr cut to 60 characters; an integer of more than
    200 bits by its number of digits (Python refuses to print one of over 4,300)."""
    if isinstance(value, int) and value.bit_length() > 200:
        return f"an integer of about {int(value.bit_length() * math.log10(2)) + 1} digits"
    try:
        text = repr(value)
    except (ValueError, RecursionError):
        text = f"a {type(value).__name__}"
    return text if len(text) <= 60 else text[:57] + "..."


def _check(schema: Field, value: Any, where: str, path: str, n: int) -> Any:
    if value is MISSING:
        if schema.required:
            raise _fail(schema, where, path, value, n, "is missing", missing=True)
        return schema.default
    kind = schema.kind
    if not isinstance(value, _TYPES[kind]) or (isinstance(value, bool) and kind not in ("bool", "any")):
        raise _fail(schema, where, path, value, n, f"must be {_NAMES[kind]}, got {shown(value)}")
    if kind in ("int", "number", "expr") and isinstance(value, int | float) and not isinstance(value, bool):
        _check_number(schema, value, where, path, n)
    if schema.choices is not None and value not in schema.choices:
        raise _fail(schema, where, path, value, n,
                    f"{shown(value)} is not one of {', '.join(map(str, schema.choices))}")
    if schema.range is not None and kind in ("int", "number"):
        lo, hi = schema.range
        if (lo is not None and value < lo) or (hi is not None and value > hi):
            span = f"{'' if lo is None else lo}..{'' if hi is None else hi}"
            raise _fail(schema, where, path, value, n, f"{shown(value)} is outside {span}")
    if kind == "list":
        return _check_list(schema, value, where, path, n)
    if kind == "table":
        return _check_table(schema, value, where, path, n)
    return value


def _check_number(schema: Field, value: int | float, where: str, path: str, n: int) -> None:
    """A number must be finite, and an int within INT_LIMIT unless the field's range bounds it."""
    try:
        finite = math.isfinite(value)
    except OverflowError:  # an int too large for a float
        finite = False
    if not finite:
        raise _fail(schema, where, path, value, n, f"must be a finite number, got {shown(value)}")
    if isinstance(value, int) and abs(value) > INT_LIMIT and schema.range is None:
        raise _fail(schema, where, path, value, n, f"{shown(value)} is outside -{INT_LIMIT}..{INT_LIMIT}")


def _check_list(schema: Field, value: Any, where: str, path: str, n: int) -> list[Any]:
    if schema.length is not None:
        lo, hi = schema.length
        if len(value) < lo or (hi is not None and len(value) > hi):
            size = f"exactly {lo}" if lo == hi else (f"at least {lo}" if hi is None else f"{lo} to {hi}")
            raise _fail(schema, where, path, value, n, f"must be a list of {size} items, got {shown(value)}")
    if schema.items is None:
        return list(value)
    return [_check(schema.items, item, where, f"{path}[{i + 1}]", i + 1) for i, item in enumerate(value)]


def _check_table(schema: Field, value: Mapping[str, Any], where: str, path: str, n: int) -> dict[str, Any]:
    out = dict(value)
    for name, sub in schema.fields.items():
        checked = _check(sub, value.get(name, MISSING), where, f"{path}.{name}" if path else name, n)
        if checked is MISSING:
            out.pop(name, None)
        else:
            out[name] = checked
    if schema.values is not None:
        for name, item in value.items():
            if name not in schema.fields:
                out[name] = _check(schema.values, item, where, f"{path}.{name}" if path else str(name), n)
    return out
