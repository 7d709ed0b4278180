"""The conflict check on hand-built traces whose answers are known by construction."""

from __future__ import annotations

import math

import pytest

from arise.generate.conflict import (
    ConflictLevel,
    conflict_facts,
    conflict_level,
)
from arise.generate.spec import Requirement, ScenarioSpec
from arise.validate.types import AgentTrace, TracePoint
from arise.vocabulary import RequirementKind

SPEC = ScenarioSpec.model_validate(
    dict(
        adversary_type="car",
        behavior="crosses",
        road_type="intersection",
        ego_maneuver="go_straight",
        geometry="a crossroads",
        spawn_position="crossing_road_from_right",
        spawn="from the right",
    )
)


def _north(name: str, x: float, y0: float, speed: float, steps: int, ego: bool) -> AgentTrace:
    """A 2 m x 4 m box driving north (+y) at `speed` m/s, sampled every 0.1 s."""
    points = [
        TracePoint(step=i, x=x, y=y0 + speed * 0.1 * i, heading=0.0, speed=speed)
        for i in range(steps)
    ]
    return AgentTrace(name=name, kind="Car", width=2.0, length=4.0, is_ego=ego, trajectory=points)


def test_a_car_standing_in_the_lane_ahead_is_close_without_contact() -> None:
    ego = _north("ego", 0.0, 0.0, 10.0, 30, True)
    # Stands 36 m ahead (centres) in the ego's lane: a 32 m gap the ego closes at 10 m/s
    # for 29 steps of 1 m, so 3 m are left at the end, 0.3 s from contact.
    lead = _north("Car2", 0.0, 36.0, 0.0, 30, False)
    facts = conflict_facts(ego, lead)
    assert facts.contact is False
    assert facts.closest_m == pytest.approx(3.0, abs=1e-6)
    assert facts.min_ttc_s == pytest.approx(0.3, abs=1e-3)
    assert facts.meets(ConflictLevel.REACH) and facts.meets(ConflictLevel.CLOSE)


def test_a_car_in_the_next_lane_going_the_same_speed_is_out_of_reach() -> None:
    ego = _north("ego", 0.0, 0.0, 8.0, 50, True)
    beside = _north("Car2", 8.0, 0.0, 8.0, 50, False)  # 6 m between the boxes, never closing
    facts = conflict_facts(ego, beside)
    assert facts.closest_m == pytest.approx(6.0) and facts.min_ttc_s is None
    assert not facts.meets(ConflictLevel.REACH)
    assert facts.meets(ConflictLevel.NONE)
    assert facts.describe() == "closest 6.0 m, never closing"


def test_a_car_one_metre_nearer_is_in_reach_but_not_close() -> None:
    ego = _north("ego", 0.0, 0.0, 8.0, 50, True)
    beside = _north("Car2", 7.0, 0.0, 8.0, 50, False)
    facts = conflict_facts(ego, beside)
    assert facts.meets(ConflictLevel.REACH) and not facts.meets(ConflictLevel.CLOSE)


def test_touching_boxes_are_contact() -> None:
    ego = _north("ego", 0.0, 0.0, 5.0, 20, True)
    other = _north("Car2", 1.5, 0.0, 5.0, 20, False)  # overlapping by half a metre
    facts = conflict_facts(ego, other)
    assert facts.contact and facts.closest_m == 0.0 and facts.describe() == "contact"
    assert facts.as_dict(ConflictLevel.CLOSE)["met"] is True


def test_crossing_at_right_angles_has_the_ttc_of_the_gap_over_the_closing_speed() -> None:
    ego = _north("ego", 0.0, 0.0, 10.0, 40, True)
    points = [
        TracePoint(step=i, x=40.0 - 10.0 * 0.1 * i, y=40.0, heading=math.pi / 2, speed=10.0)
        for i in range(40)
    ]
    crosser = AgentTrace(name="Car2", kind="Car", width=2.0, length=4.0, trajectory=points)
    facts = conflict_facts(ego, crosser)
    assert facts.min_ttc_s is not None and facts.min_ttc_s < 1.5


def test_the_level_follows_the_spec() -> None:
    assert conflict_level(SPEC) is ConflictLevel.REACH
    assert conflict_level(SPEC.model_copy(update={"contact_stated": True})) is ConflictLevel.CLOSE
    close = [Requirement(kind=RequirementKind.EVENTUALLY_CLOSE, text="nearly collide")]
    assert conflict_level(SPEC.model_copy(update={"requirements": close})) is ConflictLevel.CLOSE
    assert conflict_level(SPEC.model_copy(update={"adversary_stationary": True})) is (
        ConflictLevel.NONE
    )
    assert conflict_level(SPEC.model_copy(update={"no_adversary": True})) is ConflictLevel.NONE
