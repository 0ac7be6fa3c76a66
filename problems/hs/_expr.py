"""Safe translation of the vendored Hock–Schittkowski expression strings into CasADi.

The JSON stores each function as a Python expression over ``x[0] .. x[n-1]`` using only
``+ - * / **``, numbers, parentheses and ``sin cos tan exp log sqrt abs atan``
(hock_schittkowski.md, "JSON format"). We never ``eval`` those strings: they are parsed
with :mod:`ast`, every node is checked against a whitelist, and the tree is walked to
build a CasADi expression from the symbol ``x``. Anything else (attribute access, names
other than ``x`` and the listed functions, keyword arguments, comprehensions, ...) raises
`ExpressionError` naming the offending construct.
"""

from __future__ import annotations

import ast
import operator
from collections.abc import Callable
from typing import Any

import casadi as ca

__all__ = ["ExpressionError", "parse", "to_casadi", "FUNCTIONS"]

#: The only functions an expression may call, mapped to their CasADi versions.
FUNCTIONS: dict[str, Callable[[Any], Any]] = {
    "sin": ca.sin,
    "cos": ca.cos,
    "tan": ca.tan,
    "exp": ca.exp,
    "log": ca.log,
    "sqrt": ca.sqrt,
    "abs": ca.fabs,
    "atan": ca.atan,
}

_BINOPS: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.Pow: operator.pow,
}
_UNARY: dict[type, Callable[[Any], Any]] = {ast.USub: operator.neg, ast.UAdd: operator.pos}


class ExpressionError(ValueError):
    """An expression string uses something outside the allowed grammar."""


def parse(text: str, n: int) -> ast.Expression:
    """Parse and validate ``text`` (an expression in ``x[0..n-1]``); return its AST."""
    if not isinstance(text, str):
        raise ExpressionError(f"expression must be a string, got {type(text).__name__}")
    try:
        tree = ast.parse(text, mode="eval")
    except SyntaxError as exc:
        raise ExpressionError(f"cannot parse {text!r}: {exc.msg}") from exc
    _check(tree.body, text, n)
    return tree


def _check(node: ast.AST, text: str, n: int) -> None:
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            raise ExpressionError(f"{text!r}: only numeric constants are allowed, got {node.value!r}")
    elif isinstance(node, ast.BinOp):
        if type(node.op) not in _BINOPS:
            raise ExpressionError(f"{text!r}: operator {type(node.op).__name__} is not allowed")
        _check(node.left, text, n)
        _check(node.right, text, n)
    elif isinstance(node, ast.UnaryOp):
        if type(node.op) not in _UNARY:
            raise ExpressionError(f"{text!r}: unary operator {type(node.op).__name__} is not allowed")
        _check(node.operand, text, n)
    elif isinstance(node, ast.Subscript):
        if not (isinstance(node.value, ast.Name) and node.value.id == "x"):
            raise ExpressionError(f"{text!r}: only x[i] may be indexed")
        idx = node.slice
        if not (isinstance(idx, ast.Constant) and type(idx.value) is int and 0 <= idx.value < n):
            raise ExpressionError(f"{text!r}: index must be an integer literal in 0..{n - 1}")
    elif isinstance(node, ast.Call):
        if not (isinstance(node.func, ast.Name) and node.func.id in FUNCTIONS):
            raise ExpressionError(
                f"{text!r}: only the functions {', '.join(FUNCTIONS)} may be called"
            )
        if node.keywords or len(node.args) != 1:
            raise ExpressionError(f"{text!r}: {node.func.id} takes exactly one positional argument")
        _check(node.args[0], text, n)
    else:
        raise ExpressionError(f"{text!r}: {type(node).__name__} is not allowed in an expression")


def _build(node: ast.AST, x: Any) -> Any:
    if isinstance(node, ast.Constant):
        return float(node.value)  # type: ignore[arg-type]  # _check admitted numbers only
    if isinstance(node, ast.BinOp):
        left, right = _build(node.left, x), _build(node.right, x)
        if isinstance(node.op, ast.Pow) and isinstance(right, float) and right.is_integer():
            # integer powers as ca.constpow keep derivatives exact at x = 0 (x**2 etc.)
            return ca.constpow(left, right) if not isinstance(left, float) else left**right
        return _BINOPS[type(node.op)](left, right)
    if isinstance(node, ast.UnaryOp):
        return _UNARY[type(node.op)](_build(node.operand, x))
    if isinstance(node, ast.Subscript):
        return x[node.slice.value]  # type: ignore[attr-defined]  # _check allowed only x[<int constant>]
    if isinstance(node, ast.Call):
        return FUNCTIONS[node.func.id](_build(node.args[0], x))  # type: ignore[attr-defined]  # _check: a Name
    raise ExpressionError(f"unexpected node {type(node).__name__}")  # unreachable after _check


def to_casadi(tree: ast.Expression, x: Any) -> Any:
    """The CasADi expression of a validated tree, in the symbol (SX/MX) ``x``."""
    out = _build(tree.body, x)
    return out if not isinstance(out, float) else (x[0] * 0 + out)
