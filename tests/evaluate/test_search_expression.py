"""The custom objective's expressions: what they compute, and what they may not do."""

from __future__ import annotations

import pytest

from arise.evaluate.search.errors import SearchError
from arise.evaluate.search.expression import parse_expression
from arise.evaluate.search.objective import Objective, score

FACTS = {"min_ttc": 2.5, "min_distance": 4.0, "collision": 0.0, "route_completion": 0.8}


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("min_ttc + 0.5 * min_distance", 4.5),
        ("-route_completion", -0.8),
        ("min(min_ttc, min_distance / 2) ** 2", 4.0),
        ("0 if collision else min_ttc", 2.5),
        ("min_ttc if min_distance < 5 else 10", 2.5),
        ("abs(1 - route_completion) + max(1, 2, 3)", 3.2),
        ("1 < min_ttc <= 3", 1.0),
    ],
)
def test_expressions_compute_over_the_trace_facts(text: str, value: float) -> None:
    assert parse_expression(text).value(FACTS) == pytest.approx(value)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "needs --expression"),
        ("speed * 2", "unknown name 'speed'"),
        ("min_ttc.__class__", "is not allowed"),
        ("open('/etc/passwd')", "is not allowed"),
        ("[min_ttc]", "is not allowed"),
        ("'a' * 3", "only numbers"),
        ("True + min_ttc", "only numbers"),
        ("min_ttc +", "is not valid"),
        ("min(min_ttc, key=abs)", "is not allowed"),
        ("1" * 400, "longer than"),
    ],
)
def test_anything_but_arithmetic_over_facts_is_refused(text: str, message: str) -> None:
    with pytest.raises(SearchError, match=message):
        parse_expression(text)


def test_runaway_arithmetic_is_an_error_not_a_hang() -> None:
    with pytest.raises(SearchError, match="cannot be computed"):
        parse_expression("10 ** 10 ** 10").value(FACTS)
    with pytest.raises(SearchError, match="cannot be computed"):
        parse_expression("1 / (min_ttc - min_ttc)").value(FACTS)


def test_score_uses_the_expression_and_caps_like_the_built_in_objectives() -> None:
    goal = parse_expression("min_ttc + min_distance")
    assert score(Objective.CUSTOM, False, None, 3.0, expression=goal) == pytest.approx(13.0)
    assert score(Objective.CUSTOM, True, 0.0, 0.0, expression=goal) == 0.0
    collision_only = parse_expression("1 - collision")
    assert score(Objective.CUSTOM, True, 0.0, 0.0, expression=collision_only) == 0.0
    with pytest.raises(SearchError):
        score(Objective.CUSTOM, False, 1.0, 1.0)
