"""Safe arithmetic expressions in the project's data files and options (never ``eval``).

Python's ``ast`` is parsed and walked against a whitelist (a :class:`Grammar`): numbers,
allowed names, + - * / ** (and % or one comparison where the grammar says so), unary signs,
parentheses and allowed functions with their arities. One parser serves the exact values of
substitution-system files (scalars, each intermediate checked finite and real) and the
sampling densities in x and y (NumPy arrays). Texts and nesting are bounded so that a long
``1+1+...`` or a run of ``-`` is a one-line ParseError, never a RecursionError.
"""

from __future__ import annotations

import ast
import operator
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from tilekit.errors import ParseError

#: Longest expression text, and deepest nesting of operations, any grammar accepts.
MAX_LENGTH = 1000
MAX_DEPTH = 40

#: Binary operators by AST node type, and comparisons (a grammar chooses which it allows);
#: ``operator`` functions work on floats and on NumPy arrays alike.
BINARY: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
    ast.Pow: operator.pow, ast.Mod: operator.mod,
}
COMPARE: dict[type, Callable[[Any, Any], Any]] = {
    ast.Lt: operator.lt, ast.LtE: operator.le, ast.Gt: operator.gt, ast.GtE: operator.ge,
}


@dataclass(frozen=True)
class Grammar:
    """What an expression may contain: ``names`` (variables and constants), ``functions``
    (name -> number of arguments), ``%`` and comparisons when ``modulo`` / ``compare``;
    ``what`` names the expression in messages ("expression", "density expression")."""

    names: tuple[str, ...]
    functions: Mapping[str, int] = field(default_factory=dict)
    modulo: bool = False
    compare: bool = False
    what: str = "expression"

    def allowed(self) -> str:
        ops = "+ - * / **" + (" %" if self.modulo else "")
        parts = ["numbers", ", ".join(self.names) or "no names", ops + ", parentheses"]
        if self.compare:
            parts.append("< <= > >=")
        if self.functions:
            parts.append("/".join(self.functions))
        return ", ".join(parts)


def show(text: str) -> str:
    """``text`` quoted for a one-line message (long texts cut)."""
    return repr(text) if len(text) <= 60 else repr(text[:57] + "...")


def parse(text: str, grammar: Grammar, *, syntax_hint: str = "") -> ast.expr:
    """The checked expression tree of ``text``, or a one-line ParseError naming what is wrong
    and what ``grammar`` allows (``syntax_hint`` is added when the text is no Python at all)."""
    what = grammar.what
    if len(text) > MAX_LENGTH:
        raise ParseError(f"{what} {show(text)} is longer than {MAX_LENGTH} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        raise ParseError(f"{what} {show(text)} is not valid arithmetic{syntax_hint}") from None
    binary = {ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow} | ({ast.Mod} if grammar.modulo else set())

    def check(node: ast.AST, depth: int) -> None:
        if depth > MAX_DEPTH:
            raise ParseError(f"{what} {show(text)} nests deeper than {MAX_DEPTH} levels")
        if isinstance(node, ast.Constant) and isinstance(node.value, int | float) and not isinstance(node.value, bool):
            return
        if isinstance(node, ast.Name):
            if node.id not in grammar.names:
                raise ParseError(f"{what} {show(text)} uses unknown name {node.id!r}; "
                                 f"known: {', '.join(sorted(grammar.names))}")
            return
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
            return check(node.operand, depth + 1)
        if isinstance(node, ast.BinOp) and type(node.op) in binary:
            check(node.left, depth + 1)
            return check(node.right, depth + 1)
        if (grammar.compare and isinstance(node, ast.Compare) and len(node.ops) == 1
                and type(node.ops[0]) in COMPARE):
            check(node.left, depth + 1)
            return check(node.comparators[0], depth + 1)
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in grammar.functions
                and not node.keywords and len(node.args) == grammar.functions[node.func.id]):
            for a in node.args:
                check(a, depth + 1)
            return
        raise ParseError(f"{what} {show(text)} contains {type(node).__name__}; allowed are {grammar.allowed()}")

    try:
        check(tree.body, 0)
    except RecursionError:
        raise ParseError(f"{what} {show(text)} nests deeper than {MAX_DEPTH} levels") from None
    return tree.body


def run(node: ast.expr, env: Mapping[str, Any], functions: Mapping[str, Callable[..., Any]],
        step: Callable[[Any], Any] = lambda v: v) -> Any:
    """The value of a tree from :func:`parse`: names from ``env``, calls to ``functions``;
    ``step`` sees every number and intermediate result (a scalar grammar checks finiteness
    there). Comparisons give 1.0 / 0.0 (arrays of them)."""

    def value(n: ast.AST) -> Any:
        if isinstance(n, ast.Constant):
            return step(float(n.value))
        if isinstance(n, ast.Name):
            return env[n.id]
        if isinstance(n, ast.UnaryOp):
            v = value(n.operand)
            return -v if isinstance(n.op, ast.USub) else v
        if isinstance(n, ast.BinOp):
            return step(BINARY[type(n.op)](value(n.left), value(n.right)))
        if isinstance(n, ast.Compare):
            return COMPARE[type(n.ops[0])](value(n.left), value(n.comparators[0])) * 1.0
        assert isinstance(n, ast.Call) and isinstance(n.func, ast.Name)
        return step(functions[n.func.id](*(value(a) for a in n.args)))

    return value(node)
