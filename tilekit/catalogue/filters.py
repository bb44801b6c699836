"""Typed filters: ``KEY=VALUE``-style expressions parsed into :class:`Filter`, and turned into
SQL conditions over the tilings' property rows or over the typed columns of a plugin's result
table.

The conditions are SQL text with named parameters (``:p0``, ``:p1``, ...): a user's text only
ever reaches the database as a bound value. The same text runs through SQLAlchemy
(``sa.text``, on SQLite and PostgreSQL) and through the standard library's ``sqlite3`` (the
catalogue's read path without SQLAlchemy, :mod:`tilekit.catalogue.reading`), so this module
imports neither: one copy of what a filter means, whichever connection runs it."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

from tilekit.catalogue.entry import SHARED_COLUMNS, TEXT_COLUMNS
from tilekit.errors import ParameterError, ParseError

#: ``KEY=N`` on a numeric property matches values within this relative tolerance, so a
#: float written with 10 significant digits finds the stored double.
NUMBER_RTOL = 1e-9


_FILTER_RE = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_\-]*)\s*(!=|>=|<=|=|>|<|~)(.*)$", re.S)
_INT_RE = re.compile(r"^[+-]?\d+$")
_FLOAT_RE = re.compile(r"^[+-]?(\d+\.\d*|\.\d+|\d+)([eE][+-]?\d+)?$")

FILTER_FORMS = "KEY=VALUE, KEY!=VALUE, KEY>=N, KEY<=N, KEY>N, KEY<N or KEY~TEXT"


def auto_type(text: str) -> bool | int | float | str:
    """``true``/``false`` -> bool, integers -> int, decimals -> float, anything else -> str."""
    low = text.strip().lower()
    if low in ("true", "false"):
        return low == "true"
    stripped = text.strip()
    if _INT_RE.match(stripped) and len(stripped) <= 18:
        return int(stripped)
    if _INT_RE.match(stripped) or _FLOAT_RE.match(stripped):
        value = float(stripped)  # a huge integer compares as a float
        if not math.isfinite(value):
            raise ParseError(f"number {stripped[:24]}{'...' if len(stripped) > 24 else ''} is out of range")
        return value
    return text


@dataclass(frozen=True)
class Filter:
    """A parsed filter: property ``key``, operator, auto-typed ``value`` and the ``raw`` text."""

    key: str
    op: str
    value: bool | int | float | str
    raw: str

    def __str__(self) -> str:
        return f"{self.key}{self.op}{self.raw}"


def parse_filter(expr: str | Filter) -> Filter:
    """Parse ``KEY=VALUE``, ``KEY!=V``, ``KEY>=N``, ``KEY<=N``, ``KEY>N``, ``KEY<N``, ``KEY~TEXT``.

    Values are auto-typed (``true``/``false`` -> bool, numbers -> number, else text); a value
    in matching quotes is always text (``name="6"``). ``~`` is a case-insensitive substring
    match. Keys are snake_case; dashes are read as underscores (``k-hedral``).
    """
    if isinstance(expr, Filter):
        return expr
    m = _FILTER_RE.match(str(expr))
    if not m:
        raise ParseError(f"filter {expr!r} is not of the form {FILTER_FORMS}{_shell_hint(str(expr))}")
    key = m.group(1).replace("-", "_").lower()
    op = m.group(2)
    raw = m.group(3).strip()
    quoted = len(raw) >= 2 and raw[0] == raw[-1] and raw[0] in "'\""
    if quoted:
        raw = raw[1:-1]
        value: bool | int | float | str = raw
    elif op == "~":
        value = raw
    else:
        value = auto_type(raw)
    if op in (">", "<", ">=", "<=") and (isinstance(value, bool) or not isinstance(value, int | float)):
        raise ParseError(f"filter {expr!r}: {op} needs a number, got {raw!r}")
    return Filter(key, op, value, raw)


_BARE_KEY = re.compile(r"^\s*[A-Za-z_][A-Za-z0-9_\-]*\s*$")


def _shell_hint(text: str) -> str:
    """A hint for a filter a shell has mangled: unquoted, ``heesch>=2`` reaches tilekit as the
    bare key ``heesch`` (the shell takes ``>=2`` as a redirection to a file named ``=2``)."""
    if not _BARE_KEY.match(text):
        return ""
    key = text.strip()
    return (f"; a shell leaves only the key of an unquoted {key}>=2 (it reads >=2 as a redirection "
            f"to a file '=2'): quote the filter, e.g. --where '{key}>=2'")


class Params(dict):
    """The bound values of one statement, named ``p0``, ``p1``, ... in the order they are bound."""

    def bind(self, value: Any) -> str:
        """Hold ``value`` and return its placeholder."""
        name = f"p{len(self)}"
        self[name] = value
        return ":" + name

    def many(self, values: list[Any]) -> str:
        """``(:pI, :pJ, ...)`` for an IN list."""
        return "(" + ", ".join(self.bind(v) for v in values) + ")"


_ORDER_KEY = re.compile(r"^-?[A-Za-z_][A-Za-z0-9_\-]*$")


def parse_order(order_by: str | None) -> tuple[str, bool]:
    """``--order KEY`` or ``-KEY`` -> (key in snake case, descending?): one optional leading
    ``-`` before a name of letters, digits, ``_`` and ``-``; anything else (an empty key,
    ``--name``, spaces) is a ParseError naming the valid form. None means ``name``."""
    text = "name" if order_by is None else str(order_by).strip()
    if not _ORDER_KEY.match(text):
        raise ParseError(f"order key {text[:60]!r} is not KEY or -KEY (a column or property name, "
                         "e.g. name, -polygons)")
    return text.lstrip("-").replace("-", "_").lower(), text.startswith("-")


_DIGITS = re.compile(r"(\d+)")


def natural_key(text: str) -> tuple[tuple[int, int, str], ...]:
    """A sort key reading runs of digits as numbers: IH2 before IH10, multigrid-5 before
    multigrid-10 (text compared case-insensitively)."""
    return tuple((0, int(part), "") if part.isdigit() else (1, 0, part.lower())
                 for part in _DIGITS.split(text) if part)


def quote(name: str) -> str:
    """An SQL identifier, double-quoted (the same on SQLite and PostgreSQL)."""
    return '"' + name.replace('"', '""') + '"'


def like_contains(params: Params, expression: str, needle: str) -> str:
    """Case-insensitive substring test: ``lower(expression)`` contains ``needle``, with
    ``%``, ``_`` and the escape character itself matched literally."""
    escaped = needle.lower().replace("/", "//").replace("%", "/%").replace("_", "/_")
    return f"lower({expression}) LIKE {params.bind('%' + escaped + '%')} ESCAPE '/'"


_OPS = ("=", "!=", ">", "<", ">=", "<=")


def _compare(params: Params, expression: str, op: str, value: Any) -> str:
    assert op in _OPS
    return f"{expression} {'<>' if op == '!=' else op} {params.bind(value)}"


def _near(params: Params, expression: str, value: float) -> str:
    eps = NUMBER_RTOL * max(1.0, abs(value))
    return f"{expression} BETWEEN {params.bind(value - eps)} AND {params.bind(value + eps)}"


def _type_error(f: Filter, wanted: str) -> ParameterError:
    return ParameterError(f"filter {f}: {f.key} {wanted}, got {f.raw!r}")


#: The kinds of typed column a filter distinguishes.
COLUMN_KINDS = ("bool", "int", "float", "json", "text")


def column_condition(params: Params, expression: str, kind: str, f: Filter) -> str:
    """The condition of one filter on a typed column (a result table's, or a shared one of
    ``tilings``): text columns take ``=``, ``!=`` and ``~``; booleans ``=true``/``=false``;
    numbers every comparison (floats ``=`` within NUMBER_RTOL); JSON columns only ``~`` on
    their text. ``kind`` is one of COLUMN_KINDS."""
    if kind == "bool":
        if f.op not in ("=", "!=") or not isinstance(f.value, bool):
            raise _type_error(f, "takes =true, =false or !=")
        return _compare(params, expression, f.op, f.value)
    if kind in ("int", "float"):
        if f.op == "~" or isinstance(f.value, bool) or not isinstance(f.value, int | float):
            raise _type_error(f, "is a number")
        if f.op in ("=", "!=") and kind == "float":
            near = _near(params, expression, float(f.value))
            return near if f.op == "=" else f"NOT ({near})"
        return _compare(params, expression, f.op, f.value)
    if kind == "json":
        if f.op != "~":
            raise _type_error(f, "is JSON and takes only ~TEXT")
        return like_contains(params, f"CAST({expression} AS TEXT)", f.raw)
    if f.op == "~":
        return like_contains(params, expression, f.raw)
    if f.op in ("=", "!="):
        return _compare(params, expression, f.op, f.raw)
    raise _type_error(f, f"is text and takes =, != or ~ (not {f.op})")


_SHARED_KINDS = {bool: "bool", int: "int", float: "float", str: "text"}


def condition(params: Params, f: Filter) -> str:
    """The condition of one filter on a tiling (a row of ``tilings``): a column of ``tilings``,
    or any property through its typed rows in ``tiling_properties``. On a list property ``=``
    means "some element equals", ``!=`` "has the property and no element equals", ranges
    "some element is in range"."""
    if f.key in TEXT_COLUMNS or f.key in SHARED_COLUMNS:
        column = "tilings." + quote(f.key)
        names = group_names(f.key, f.raw) if f.op in ("=", "!=") else [f.raw]
        if len(names) > 1:  # p6m or *632
            listed = params.many(names)
            return f"{column} IN {listed}" if f.op == "=" else f"({column} IS NOT NULL AND {column} NOT IN {listed})"
        kind = _SHARED_KINDS[SHARED_COLUMNS[f.key]] if f.key in SHARED_COLUMNS else "text"
        return column_condition(params, column, kind, f)

    # Uncorrelated "id IN (SELECT tiling_id ...)" subqueries: each is evaluated once through
    # the covering (key, value, tiling_id) indexes, instead of once per tiling.
    def having(*conditions: str) -> str:
        where = " AND ".join([f"tiling_properties.key = {params.bind(f.key)}", *conditions])
        return f"tilings.id IN (SELECT tiling_properties.tiling_id FROM tiling_properties WHERE {where})"

    if f.op == "~":
        return having(like_contains(params, "tiling_properties.value_text", f.raw))
    if f.op in ("=", "!="):
        # each alternative is its own indexed subquery (an OR inside one would defeat the index)
        text = "tiling_properties.value_text"
        if isinstance(f.value, bool):
            alternatives = [f"tiling_properties.value_bool = {params.bind(f.value)}",
                            f"{text} = {params.bind(f.raw)}"]
        elif isinstance(f.value, int | float):
            alternatives = [_near(params, "tiling_properties.value_num", float(f.value)),
                            f"{text} = {params.bind(f.raw)}"]
        else:
            alternatives = [f"{text} = {params.bind(name)}" for name in group_names(f.key, f.raw)]
        equal = " OR ".join(having(c) for c in alternatives)
        if f.op == "=":
            return f"({equal})"
        return f"({having()} AND NOT ({equal}))"
    return having(_compare(params, "tiling_properties.value_num", f.op, float(f.value)))


def group_names(key: str, value: str) -> list[str]:
    """A wallpaper group matches by its IUC name (p6m) and its orbifold symbol (*632) alike."""
    if key not in ("symmetry_group", "wallpaper_group", "orbifold"):
        return [value]
    # start-up cost: tilekit.symmetry loads NumPy; only group filters need it. orbifold_spellings
    # writes a curved group both ways (*1032 and *10,3,2)
    from tilekit.symmetry import IUC, ORBIFOLD
    from tilekit.symmetry.names import orbifold_spellings

    return sorted({ORBIFOLD.get(value, value), IUC.get(value, value), *orbifold_spellings(value)})
