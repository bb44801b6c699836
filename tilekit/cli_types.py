"""Bounded click option types: values outside a sane range are one-line errors, never an
OverflowError deep in SQLite or NumPy.

``BoundedInt`` rejects huge integers (``--limit 10**30``) and over-long digit strings before
converting them (Python refuses ``int()`` of more than 4,300 digits with a ValueError whose
text is about the interpreter, not the option); ``FiniteFloat`` rejects ``inf``, ``nan`` and
magnitudes beyond a bound.
"""

from __future__ import annotations

import math
from typing import Any

import click

from tilekit.errors import ParameterError, TilekitError
from tilekit.files import check_output

#: The largest integer any option accepts by default (SQLite's and NumPy's int64).
INT64_MAX = 2**63 - 1


class BoundedInt(click.ParamType):
    """An integer in ``[min, max]`` (defaults: 0 .. 2**63 - 1)."""

    name = "integer"

    def __init__(self, min: int = 0, max: int = INT64_MAX, what: str = "") -> None:
        self.min = min
        self.max = max
        self.what = what

    def get_metavar(self, param: click.Parameter, ctx: click.Context | None = None) -> str:  # type: ignore[override]
        return "N"

    def _range(self) -> str:
        return f"{self.min}..{self.max}"

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> int:
        if isinstance(value, int) and not isinstance(value, bool):
            number = value
        else:
            text = str(value).strip().replace("_", "")
            digits = text[1:] if text[:1] in ("+", "-") else text  # one sign at most
            if not digits.isascii() or not digits.isdigit():
                self.fail(f"{str(value)[:40]!r} is not a valid integer ({self._range()})", param, ctx)
            if len(digits) > 19:
                self.fail(f"{text[:20]}... ({len(digits)} digits) is out of range {self._range()}", param, ctx)
            number = int(text)
        if not self.min <= number <= self.max:
            self.fail(f"{number} is out of range {self._range()}", param, ctx)
        return number

    def __repr__(self) -> str:
        return f"BoundedInt({self.min}, {self.max})"


class FiniteFloat(click.ParamType):
    """A finite float with ``|x| <= bound`` (default 1e9) and optionally ``x >= min``."""

    name = "number"

    def __init__(self, bound: float = 1e9, min: float | None = None) -> None:
        self.bound = bound
        self.min = min

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> float:
        try:
            number = float(value)
        except (TypeError, ValueError, OverflowError):
            self.fail(f"{str(value)[:40]!r} is not a valid number", param, ctx)
        if not math.isfinite(number) or abs(number) > self.bound:
            self.fail(f"{str(value)[:40]} is not a finite number within ±{self.bound:g}", param, ctx)
        if self.min is not None and number < self.min:
            self.fail(f"{number:g} is below the minimum {self.min:g}", param, ctx)
        return number

    def __repr__(self) -> str:
        return f"FiniteFloat({self.bound})"


class OutputPath(click.Path):
    """A file to write: click's path checks, and an existing path that is not a regular file
    (a FIFO would block the command until something reads it; a device or a socket is no
    file) refused in one line before any work (:func:`tilekit.files.check_output`)."""

    def __init__(self) -> None:
        super().__init__(dir_okay=False)

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> Any:
        path = super().convert(value, param, ctx)
        try:
            check_output(path, "file")
        except TilekitError as exc:
            self.fail(str(exc), param, ctx)
        return path


#: Counts and sizes: 0 or more / 1 or more, int64-bounded.
COUNT = BoundedInt(0)
POSITIVE = BoundedInt(1)
#: A run id (SQLite integer primary key).
RUN_ID = BoundedInt(1)
#: A file a command writes.
OUTPUT = OutputPath()

#: ``--geometry`` values and the curved families' names for them.
GEOMETRY_CHOICES = {"sphere": "spherical", "plane": "euclidean", "hyperbolic": "hyperbolic"}


def geometry_option(tiling: Any, geometry: str | None) -> dict[str, str]:
    """``render --geometry G`` as tiling options: a curved tiling (one whose ``kind`` is
    'spherical' or 'hyperbolic') checks it itself (``geometry=G``); any other tiling is
    Euclidean, so 'plane' needs no option and anything else is a one-line error."""
    if geometry is None:
        return {}
    kind = getattr(tiling, "kind", None)
    if kind in ("spherical", "hyperbolic"):
        return {"geometry": geometry}
    if GEOMETRY_CHOICES.get(geometry) == "euclidean":
        return {}
    name = getattr(tiling, "name", "") or "this tiling"
    raise ParameterError(f"{name} tiles the Euclidean plane, not {GEOMETRY_CHOICES.get(geometry, geometry)}: "
                         "--geometry sphere / hyperbolic applies to the curved families")
