"""A user's own objective: an arithmetic expression over a trial's trace facts and its
driving metrics.

`--objective custom --expression "min_ttc + 0.2 * min_distance"` minimises what the user
writes, with the same facts the built-in objectives read, and the metrics of `arise
drive` (docs/agents.md) by their column names (`overall_score`, `red_lights_run`, ...).
It is parsed once, before any trial, into a small tree of allowed nodes (numbers, the
names, + - * / **, unary minus, comparisons, `a if c else b`, min, max, abs); nothing
else is evaluated, so the expression cannot reach Python.
"""

from __future__ import annotations

import ast
import math
import operator
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from arise.drive.metrics_types import DrivingMetrics
from arise.evaluate.search.errors import SearchError

#: The trace facts of the ego against the adversary (`arise.evaluate.criticality`).
FACTS: dict[str, str] = {
    "min_ttc": "smallest time-to-collision, s (10 when the two never close in)",
    "min_distance": "closest approach of the footprints, m (0 at contact)",
    "collision": "1 when ego and adversary touched, else 0",
}

#: What the driving metrics mean (`arise drive`'s columns, docs/agents.md#metrics); the
#: names an expression may use are the metrics' own fields, so a new metric is usable at
#: once (with "a driving metric" as its description until it is added here).
_METRIC_HELP: dict[str, str] = {
    "collision_count": "contacts of the ego with any other agent",
    "red_lights_run": "red lights the ego ran (RR)",
    "stop_signs_run": "stop signs the ego ran (SS)",
    "out_of_road_m": "metres driven off the drivable area (OR)",
    "distance_to_route_m": "mean distance of the ego to its route, m",
    "route_following": "1 - min(1, distance_to_route_m / 5), 0 to 1 (RF)",
    "route_completion": "share of its route the ego drove, 0 to 1 (Comp)",
    "time_spent_s": "the episode's duration, s (TS)",
    "mean_acceleration": "mean magnitude of the ego's acceleration, m/s^2 (ACC)",
    "mean_yaw_velocity": "mean magnitude of the ego's yaw rate, rad/s (YV)",
    "lane_invasions": "lane boundaries crossed outside junctions (LI)",
    "overall_score": "SafeBench's overall score, 0 to 1, higher is better (OS)",
    "min_ttc_s": "smallest TTC with any agent, s (10 when none)",
    "pet_s": "post-encroachment time with the adversary, s (10 when none)",
    "road_checked": "1 when a road network was at hand, else 0",
}

#: The driving metrics of the run by `arise drive`'s names (`arise.drive.measure`), every
#: field of `DrivingMetrics` but the trace facts' own `collision` (the ego against the
#: adversary here, as the built-in objectives read it; `collision_count` counts contacts
#: with anyone). `route_completion` is SafeBench's, along the ego's route.
DRIVE_METRICS: dict[str, str] = {
    name: _METRIC_HELP.get(name, "a driving metric (docs/agents.md#metrics)")
    for name in DrivingMetrics.model_fields
    if name != "collision"
}
#: What a metric without a value reads: a time (`_s`: never on course to touch, paths that
#: never cross) NEUTRAL_TIME, as far from a conflict as `min_ttc` gets; a distance (`_m`)
#: NEUTRAL_DISTANCE; anything else 0.
NEUTRAL_TIME = 10.0
NEUTRAL_DISTANCE = 50.0


def no_value(name: str) -> float:
    """What a driving metric reads when the run gives it none."""
    if name.endswith("_s"):
        return NEUTRAL_TIME
    return NEUTRAL_DISTANCE if name.endswith("_m") else 0.0


#: Every name an expression may use, and what each means (shown in the help and errors).
NAMES: dict[str, str] = {**FACTS, **DRIVE_METRICS}

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

    @property
    def names(self) -> frozenset[str]:
        """The names it reads."""
        nodes = ast.walk(self.tree)
        return frozenset(n.id for n in nodes if isinstance(n, ast.Name) and n.id in NAMES)

    @property
    def needs_metrics(self) -> bool:
        """Does it read a driving metric (measured on the road network)?"""
        return any(name in DRIVE_METRICS for name in self.names)

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
    allowed = ", ".join(NAMES)
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, int | float):
            raise SearchError(f"only numbers may appear as constants, not {node.value!r}")
    elif isinstance(node, ast.Name):
        if node.id not in NAMES:
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
