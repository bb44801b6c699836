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


def evaluate(text: str | int | float, names: Mapping[str, float] | None = None) -> float:
    """The value of ``text`` (or a plain number) with ``names`` (default: CONSTANTS)."""
    if isinstance(text, bool):
        raise ParseError(f"expression {text!r} is a boolean, not a number")
    if isinstance(text, int | float):
        return float(text)
    if not isinstance(text, str):
        raise ParseError(f"expression {text!r} is not a number or a text expression")
    env = CONSTANTS if names is None else names
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError:
        raise ParseError(f"expression {text!r} is not valid arithmetic") from None
    try:
        value = _walk(tree.body, env, text)
    except (ZeroDivisionError, OverflowError, ValueError) as exc:
        raise ParseError(f"expression {text!r} cannot be evaluated: {exc}") from None
    if isinstance(value, complex) or not math.isfinite(value):
        raise ParseError(f"expression {text!r} is not a finite real number")
    return float(value)


def _walk(node: ast.AST, env: Mapping[str, float], text: str) -> float:
    if isinstance(node, ast.Constant) and isinstance(node.value, int | float) and not isinstance(
        node.value, bool
    ):
        return float(node.value)
    if isinstance(node, ast.Name):
        if node.id not in env:
            raise ParseError(
                f"expression {text!r} uses unknown name {node.id!r}; known: {', '.join(sorted(env))}"
            )
        return float(env[node.id])
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
        v = _walk(node.operand, env, text)
        return -v if isinstance(node.op, ast.USub) else v
    if isinstance(node, ast.BinOp) and type(node.op) in _BINOPS:
        return _BINOPS[type(node.op)](_walk(node.left, env, text), _walk(node.right, env, text))
    if (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Name)
        and node.func.id in FUNCTIONS
        and len(node.args) == 1
        and not node.keywords
    ):
        return FUNCTIONS[node.func.id](_walk(node.args[0], env, text))
    raise ParseError(
        f"expression {text!r} contains {type(node).__name__}; allowed are numbers, names, "
        "+ - * / **, parentheses and sqrt/cos/sin"
    )


def constants_with(extra: Mapping[str, str | float] | None) -> dict[str, float]:
    """CONSTANTS extended by a file's own named constants (each may use earlier ones)."""
    env = dict(CONSTANTS)
    for key, value in (extra or {}).items():
        if not key.isidentifier() or key in FUNCTIONS:
            raise ParseError(f"constant name {key!r} is not a valid identifier")
        env[key] = evaluate(value, env)
    return env
