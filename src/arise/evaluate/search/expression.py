"""A user's own objective: an arithmetic expression over a trial's trace facts.

`--objective custom --expression "min_ttc + 0.2 * min_distance"` minimises what the user
writes, with the same facts the built-in objectives read. It is parsed once, before any
trial, into a small tree of allowed nodes (numbers, the fact names, + - * / **, unary
minus, comparisons, `a if c else b`, min, max, abs); nothing else is evaluated, so the
expression cannot reach Python.
"""

from __future__ import annotations

import ast
import math
import operator
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from arise.evaluate.search.errors import SearchError

#: The names an expression may use, and what each means (shown in the help and errors).
FACTS: dict[str, str] = {
    "min_ttc": "smallest time-to-collision, s (10 when the two never close in)",
    "min_distance": "closest approach of the footprints, m (0 at contact)",
    "collision": "1 when ego and adversary touched, else 0",
    "route_completion": "share of its route the ego drove, 0 to 1",
}

_BINARY: dict[type[ast.operator], Callable[[float, float], float]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.Pow: operator.pow,
}
_COMPARE: dict[type[ast.cmpop], Callable[[float, float], bool]] = {
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
}
_FUNCTIONS: dict[str, Callable[..., float]] = {"min": min, "max": max, "abs": abs}
_MAX_LENGTH = 300


@dataclass(frozen=True)
class Expression:
    text: str
    tree: ast.expr

    def value(self, facts: Mapping[str, float]) -> float:
        """The score of one trial; a value that is not a finite number is an error."""
        try:
            result = float(_evaluate(self.tree, facts))
        except (ZeroDivisionError, OverflowError, ValueError) as error:
            raise SearchError(f"the objective '{self.text}' cannot be computed: {error}") from None
        if not math.isfinite(result):
            raise SearchError(f"the objective '{self.text}' gave {result}")
        return round(result, 4)


def parse_expression(text: str) -> Expression:
    """The checked expression, or a SearchError that names what is not allowed."""
    source = text.strip()
    if not source:
        raise SearchError("--objective custom needs --expression, e.g. 'min_ttc + min_distance'")
    if len(source) > _MAX_LENGTH:
        raise SearchError(f"the expression is longer than {_MAX_LENGTH} characters")
    try:
        tree = ast.parse(source, mode="eval").body
    except SyntaxError as error:
        raise SearchError(f"the expression '{source}' is not valid: {error.msg}") from None
    _check(tree)
    return Expression(source, tree)


def _check(node: ast.AST) -> None:
    allowed = ", ".join(FACTS)
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, int | float):
            raise SearchError(f"only numbers may appear as constants, not {node.value!r}")
    elif isinstance(node, ast.Name):
        if node.id not in FACTS:
            raise SearchError(f"unknown name '{node.id}' in the expression; use {allowed}")
    elif isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        _check(node.left)
        _check(node.right)
    elif isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
        _check(node.operand)
    elif isinstance(node, ast.Compare) and all(type(op) in _COMPARE for op in node.ops):
        for part in (node.left, *node.comparators):
            _check(part)
    elif isinstance(node, ast.IfExp):
        for part in (node.test, node.body, node.orelse):
            _check(part)
    elif (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Name)
        and node.func.id in _FUNCTIONS
        and not node.keywords
        and node.args
    ):
        for part in node.args:
            _check(part)
    else:
        shown = ast.unparse(node) if isinstance(node, ast.expr) else type(node).__name__
        raise SearchError(
            f"'{shown}' is not allowed in an objective: use numbers, {allowed}, "
            "+ - * / **, comparisons, 'a if c else b', min, max and abs"
        )


def _evaluate(node: ast.expr, facts: Mapping[str, float]) -> Any:
    if isinstance(node, ast.Constant):
        return float(node.value)  # type: ignore[arg-type]  # checked numeric; floats overflow with an error; ints would grow unbounded
    if isinstance(node, ast.Name):
        return facts[node.id]
    if isinstance(node, ast.BinOp):
        return _BINARY[type(node.op)](_evaluate(node.left, facts), _evaluate(node.right, facts))
    if isinstance(node, ast.UnaryOp):
        value = _evaluate(node.operand, facts)
        return -value if isinstance(node.op, ast.USub) else value
    if isinstance(node, ast.Compare):
        left = _evaluate(node.left, facts)
        for op, right_node in zip(node.ops, node.comparators, strict=True):
            right = _evaluate(right_node, facts)
            if not _COMPARE[type(op)](left, right):
                return 0.0
            left = right
        return 1.0
    if isinstance(node, ast.IfExp):
        branch = node.body if _evaluate(node.test, facts) else node.orelse
        return _evaluate(branch, facts)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
        return _FUNCTIONS[node.func.id](*(_evaluate(arg, facts) for arg in node.args))
    raise SearchError(f"cannot evaluate {ast.unparse(node)}")  # _check keeps this unreachable
