"""A safe evaluator for the numeric expressions in substitution-system files.

Exact values (phi**-1, sqrt3/2, cos(pi/5) ...) are written as text and evaluated once, by
walking Python's ``ast`` with a whitelist: numbers, + - * / **, unary minus, parentheses,
named constants and the functions sqrt, cos, sin. Nothing else is accepted (never ``eval``).
"""

from __future__ import annotations

import ast
import math
from collections.abc import Mapping

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

_BINOPS = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.Pow: lambda a, b: a**b,
}


#: Longest expression text, and deepest nesting of operations, the evaluator accepts: exact
#: values in system files are short; the bounds keep the parser and the walk from recursing
#: or allocating without limit on a long ``1+1+...`` or a run of ``-``.
MAX_LENGTH = 1000
MAX_DEPTH = 40


def _show(text: str) -> str:
    return repr(text) if len(text) <= 60 else repr(text[:57] + "...")


def evaluate(text: str | int | float, names: Mapping[str, float] | None = None) -> float:
    """The value of ``text`` (or a plain number) with ``names`` (default: CONSTANTS)."""
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
    if len(text) > MAX_LENGTH:
        raise ParseError(f"expression {_show(text)} is longer than {MAX_LENGTH} characters")
    env = CONSTANTS if names is None else names
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        raise ParseError(f"expression {_show(text)} is not valid arithmetic") from None
    try:
        value = _walk(tree.body, env, text, 0)
    except ParseError:
        raise
    except (ZeroDivisionError, OverflowError, ValueError, TypeError) as exc:
        raise ParseError(f"expression {_show(text)} cannot be evaluated: {exc}") from None
    except RecursionError:
        raise ParseError(f"expression {_show(text)} nests deeper than {MAX_DEPTH} levels") from None
    return value


def _real(value: complex | float, text: str) -> float:
    """``value`` as a finite float (every intermediate result must be one)."""
    if isinstance(value, complex) or not math.isfinite(value):
        raise ParseError(f"expression {_show(text)} is not a finite real number"
                         + (" (a power of a negative number)" if isinstance(value, complex) else ""))
    return float(value)


def _walk(node: ast.AST, env: Mapping[str, float], text: str, depth: int) -> float:
    if depth > MAX_DEPTH:
        raise ParseError(f"expression {_show(text)} nests deeper than {MAX_DEPTH} levels")
    if isinstance(node, ast.Constant) and isinstance(node.value, int | float) and not isinstance(
        node.value, bool
    ):
        return _real(float(node.value), text)
    if isinstance(node, ast.Name):
        if node.id not in env:
            raise ParseError(
                f"expression {_show(text)} uses unknown name {node.id!r}; known: {', '.join(sorted(env))}"
            )
        return float(env[node.id])
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
        v = _walk(node.operand, env, text, depth + 1)
        return -v if isinstance(node.op, ast.USub) else v
    if isinstance(node, ast.BinOp) and type(node.op) in _BINOPS:
        left = _walk(node.left, env, text, depth + 1)
        right = _walk(node.right, env, text, depth + 1)
        return _real(_BINOPS[type(node.op)](left, right), text)
    if (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Name)
        and node.func.id in FUNCTIONS
        and len(node.args) == 1
        and not node.keywords
    ):
        return _real(FUNCTIONS[node.func.id](_walk(node.args[0], env, text, depth + 1)), text)
    raise ParseError(
        f"expression {_show(text)} contains {type(node).__name__}; allowed are numbers, names, "
        "+ - * / **, parentheses and sqrt/cos/sin"
    )


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
