"""A safe evaluator for the numeric expressions in substitution-system files.

Exact values (phi**-1, sqrt3/2, cos(pi/5) ...) are written as text and evaluated once by the
core's safe evaluator (:mod:`tilekit.expr`) with this grammar: numbers, + - * / **, unary
minus, parentheses, named constants and the functions sqrt, cos, sin (never ``eval``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from tilekit import expr
from tilekit.errors import ParseError

PHI = (1.0 + math.sqrt(5.0)) / 2.0

#: Constants every system file may use.
CONSTANTS: dict[str, float] = {
    "phi": PHI,
    "pi": math.pi,
    "sqrt2": math.sqrt(2.0),
    "sqrt3": math.sqrt(3.0),
    "sqrt5": math.sqrt(5.0),
    "sqrt15": math.sqrt(15.0),
}

FUNCTIONS = {"sqrt": math.sqrt, "cos": math.cos, "sin": math.sin}


def evaluate(text: str | int | float, names: Mapping[str, float] | None = None) -> float:
    """The value of ``text`` (or a plain number) with ``names`` (default: CONSTANTS), through
    the core's safe evaluator (:mod:`tilekit.expr`); every intermediate must be a finite real."""
    if isinstance(text, bool):
        raise ParseError(f"expression {text!r} is a boolean, not a number")
    if isinstance(text, int | float):
        try:
            value = float(text)
        except OverflowError:
            raise ParseError(f"number {str(text)[:30]}... is too large") from None
        if not math.isfinite(value):
            raise ParseError(f"number {value!r} is not finite")
        return value
    if not isinstance(text, str):
        raise ParseError(f"expression {str(text)[:60]!r} is not a number or a text expression")
    env = CONSTANTS if names is None else names
    tree = expr.parse(text, expr.Grammar(names=tuple(env), functions=dict.fromkeys(FUNCTIONS, 1)))

    def real(value: complex | float) -> float:
        if isinstance(value, complex) or not math.isfinite(value):
            raise ParseError(f"expression {expr.show(text)} is not a finite real number"
                             + (" (a power of a negative number)" if isinstance(value, complex) else ""))
        return float(value)

    try:
        return real(expr.run(tree, env, FUNCTIONS, step=real))
    except ParseError:
        raise
    except (ZeroDivisionError, OverflowError, ValueError, TypeError) as exc:
        raise ParseError(f"expression {expr.show(text)} cannot be evaluated: {exc}") from None


def constants_with(extra: Mapping[str, str | float] | None) -> dict[str, float]:
    """CONSTANTS extended by a file's own named constants (each may use earlier ones)."""
    env = dict(CONSTANTS)
    if extra is None:
        return env
    if not isinstance(extra, Mapping):
        raise ParseError(f"[constants] must be a table of name = expression, not {type(extra).__name__}")
    for key, value in extra.items():
        if not isinstance(key, str) or not key.isidentifier() or key in FUNCTIONS:
            raise ParseError(f"constant name {key!r} is not a valid identifier")
        env[key] = evaluate(value, env)
    return env
