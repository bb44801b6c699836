"""Typed filters: ``KEY=VALUE``-style expressions parsed into :class:`Filter`, and turned into
SQLAlchemy conditions (bound parameters only: a user's text never reaches SQL) over the
tilings' property rows or over the typed columns of a plugin's result table."""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

import sqlalchemy as sa

from tilekit.catalogue.tables import PROPS, TILINGS
from tilekit.errors import ParameterError, ParseError
from tilekit.models import SHARED_COLUMNS, TEXT_COLUMNS

#: ``KEY=N`` on a numeric property matches values within this relative tolerance, so a
#: float written with 10 significant digits finds the stored double.
NUMBER_RTOL = 1e-9

#: Longest number a filter takes (Python refuses int() of 4,300 digits and more).
_MAX_DIGITS = 400

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
    if len(stripped) > _MAX_DIGITS and (_INT_RE.match(stripped) or _FLOAT_RE.match(stripped)):
        raise ParseError(f"the number {stripped[:20]}... has {len(stripped)} characters; at most {_MAX_DIGITS}")
    if _INT_RE.match(stripped):
        return int(stripped)
    if _FLOAT_RE.match(stripped):
        return float(stripped)
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
        raise ParseError(f"filter {expr!r} is not of the form {FILTER_FORMS}")
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




def _type_error(f: Filter, wanted: str) -> ParameterError:
    return ParameterError(f"filter {f}: {f.key} {wanted}, got {f.raw!r}")


def _compare(column: Any, op: str, value: Any) -> Any:
    if op == "=":
        return column == value
    if op == "!=":
        return column != value
    if op == ">":
        return column > value
    if op == "<":
        return column < value
    if op == ">=":
        return column >= value
    return column <= value


def condition(f: Filter) -> Any:
    """The SQLAlchemy condition of one filter (values are always bound parameters)."""
    t, p = TILINGS, PROPS
    if f.key in TEXT_COLUMNS or f.key in SHARED_COLUMNS:
        return column_condition(t.c[f.key], f)

    # Uncorrelated "id IN (SELECT tiling_id ...)" subqueries: each is evaluated once through
    # the (key, value) indexes, instead of once per tiling.
    def having(*conditions: Any) -> Any:
        return t.c.id.in_(sa.select(p.c.tiling_id).where(p.c.key == f.key, *conditions))

    if f.op == "~":
        return having(sa.func.lower(p.c.value_text).contains(f.raw.lower(), autoescape=True))
    if f.op in ("=", "!="):
        # each alternative is its own indexed subquery (an OR inside one would defeat the index)
        if isinstance(f.value, bool):
            alternatives = [p.c.value_bool == f.value, p.c.value_text == f.raw]
        elif isinstance(f.value, int | float):
            v = float(f.value)
            eps = NUMBER_RTOL * max(1.0, abs(v))
            alternatives = [p.c.value_num.between(v - eps, v + eps), p.c.value_text == f.raw]
        else:
            alternatives = [p.c.value_text == f.raw]
        equal = sa.or_(*(having(c) for c in alternatives))
        if f.op == "=":
            return equal
        return sa.and_(having(), ~equal)
    return having(_compare(p.c.value_num, f.op, float(f.value)))


def column_condition(column: Any, f: Filter) -> Any:
    """The condition of one filter on a typed column (a result table's, or a shared one of
    ``tilings``): text columns take ``=``, ``!=`` and ``~``; booleans ``=true``/``=false``;
    numbers every comparison; JSON columns only ``~`` on their text."""
    typ = column.type
    if isinstance(typ, sa.Boolean):
        if f.op not in ("=", "!=") or not isinstance(f.value, bool):
            raise _type_error(f, "takes =true, =false or !=")
        return _compare(column, f.op, f.value)
    if isinstance(typ, sa.Integer | sa.Float | sa.Numeric):
        if f.op == "~" or isinstance(f.value, bool) or not isinstance(f.value, int | float):
            raise _type_error(f, "is a number")
        if f.op in ("=", "!=") and isinstance(typ, sa.Float):
            v = float(f.value)
            eps = NUMBER_RTOL * max(1.0, abs(v))
            near = column.between(v - eps, v + eps)
            return near if f.op == "=" else ~near
        return _compare(column, f.op, f.value)
    if isinstance(typ, sa.JSON):
        if f.op != "~":
            raise _type_error(f, "is JSON and takes only ~TEXT")
        return sa.func.lower(sa.cast(column, sa.Text)).contains(f.raw.lower(), autoescape=True)
    if f.op == "~":
        return sa.func.lower(column).contains(f.raw.lower(), autoescape=True)
    if f.op in ("=", "!="):
        return _compare(column, f.op, f.raw)
    raise _type_error(f, f"is text and takes =, != or ~ (not {f.op})")
