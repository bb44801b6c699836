"""Typed filters: ``KEY=VALUE``-style expressions parsed into :class:`Filter`, and turned into
SQLAlchemy conditions (bound parameters only: a user's text never reaches SQL) over the
tilings' property rows or over the typed columns of a plugin's result table."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

import sqlalchemy as sa

from tilekit.catalogue.tables import PROPS, TILINGS
from tilekit.errors import ParameterError, ParseError
from tilekit.models import SHARED_COLUMNS, TEXT_COLUMNS, is_json

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
        names = group_names(f.key, f.raw) if f.op in ("=", "!=") else [f.raw]
        if len(names) > 1:  # p6m or *632
            column = t.c[f.key]
            return column.in_(names) if f.op == "=" else sa.and_(column.is_not(None), column.not_in(names))
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
            alternatives = [p.c.value_text == name for name in group_names(f.key, f.raw)]
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
    if is_json(typ):
        if f.op != "~":
            raise _type_error(f, "is JSON and takes only ~TEXT")
        return sa.func.lower(sa.cast(column, sa.Text)).contains(f.raw.lower(), autoescape=True)
    if f.op == "~":
        return sa.func.lower(column).contains(f.raw.lower(), autoescape=True)
    if f.op in ("=", "!="):
        return _compare(column, f.op, f.raw)
    raise _type_error(f, f"is text and takes =, != or ~ (not {f.op})")


def group_names(key: str, value: str) -> list[str]:
    """A wallpaper group matches by its IUC name (p6m) and its orbifold symbol (*632) alike."""
    if key not in ("symmetry_group", "wallpaper_group", "orbifold"):
        return [value]
    from tilekit.symmetry import (  # start-up cost: tilekit.symmetry loads NumPy; only group filters need it
        IUC,
        ORBIFOLD,
    )

    return sorted({value, ORBIFOLD.get(value, value), IUC.get(value, value)})
