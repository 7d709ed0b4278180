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


def test_the_drive_metrics_are_names_too_and_empty_ones_read_neutral() -> None:
    from arise.drive.metrics_types import DrivingMetrics
    from arise.evaluate.search.expression import DRIVE_METRICS, NAMES
    from arise.evaluate.search.objective import drive_values

    # Every metric of `arise drive` by its column name; `collision` stays the trace's.
    assert set(DRIVE_METRICS) == set(DrivingMetrics.model_fields) - {"collision"}
    assert {"min_ttc", "min_distance", "collision", "overall_score", "red_lights_run"} <= set(NAMES)
    values = drive_values({"overall_score": 0.4, "red_lights_run": 2, "min_ttc_s": None})
    assert values["overall_score"] == 0.4 and values["red_lights_run"] == 2.0
    assert values["min_ttc_s"] == 10.0 and values["pet_s"] == 10.0  # no conflict
    assert values["lane_invasions"] == 0.0  # not measured: 0
    goal = parse_expression("overall_score + red_lights_run - min(min_ttc_s, 5) / 10")
    assert goal.needs_metrics and not parse_expression("min_ttc * 2").needs_metrics
    metrics = {"overall_score": 0.4, "red_lights_run": 2, "min_ttc_s": None}
    assert score(
        Objective.CUSTOM, False, 3.0, 2.0, metrics=metrics, expression=goal
    ) == pytest.approx(1.9)


def test_an_unknown_name_lists_the_drive_metrics() -> None:
    with pytest.raises(SearchError, match="unknown name 'os'.*red_lights_run.*overall_score"):
        parse_expression("os + 1")


def test_the_score_objective_is_safebenchs_overall_score_as_it_is() -> None:
    assert score(Objective.SCORE, True, 0.0, 0.0, metrics={"overall_score": 0.3244}) == 0.3244
    assert score(Objective.SCORE, False, 5.0, 9.0, metrics={"overall_score": 0.95}) == 0.95
    with pytest.raises(SearchError, match="driving metrics"):
        score(Objective.SCORE, False, 5.0, 9.0)
