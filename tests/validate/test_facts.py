"""Collision, minimum distance and time-to-collision from traces, against hand computation."""

from __future__ import annotations

import math

import pytest

from arise.validate.facts import ego_pair_facts, find_collisions
from arise.validate.types import AgentTrace, TracePoint


def _straight(
    name: str, x: float, y: float, heading: float, speed: float, steps: int, ego: bool = False
) -> AgentTrace:
    dx, dy = -math.sin(heading) * speed * 0.1, math.cos(heading) * speed * 0.1
    points = [
        TracePoint(step=i, x=x + dx * i, y=y + dy * i, heading=heading, speed=speed)
        for i in range(steps)
    ]
    return AgentTrace(name=name, kind="Car", width=2.0, length=4.5, is_ego=ego, trajectory=points)


def test_ttc_is_bumper_gap_over_closing_speed() -> None:
    ego = _straight("ego", 0, 0, 0.0, 10, 5, ego=True)
    parked = _straight("Car1", 0, 30, 0.0, 0, 5)
    facts = ego_pair_facts([ego, parked])[0]
    # Last step: ego at y=4, gap 30 - 4 - 4.5 = 21.5 m, closing at 10 m/s.
    assert facts.min_ttc == pytest.approx(2.15, abs=1e-3)
    assert facts.min_distance == pytest.approx(21.5) and facts.min_distance_step == 4
    assert not facts.collided


def test_head_on_cars_collide() -> None:
    ego = _straight("ego", 0, 0, 0.0, 10, 20, ego=True)
    other = _straight("Car1", 0, 30, math.pi, 10, 20)
    facts = ego_pair_facts([ego, other])[0]
    assert facts.collided and facts.min_distance == 0 and facts.min_ttc == 0
    collision = find_collisions([ego, other], 0.1)[0]
    # Bumpers meet when 20 m/s * t = 25.5 m: t = 1.275 s, first overlapping step is 13.
    assert (collision.first, collision.second, collision.step) == ("ego", "Car1", 13)
    assert collision.time == pytest.approx(1.3)


def test_parallel_cars_never_collide_and_have_no_ttc() -> None:
    ego = _straight("ego", 0, 0, 0.0, 10, 30, ego=True)
    beside = _straight("Car1", 3.5, 0, 0.0, 10, 30)
    facts = ego_pair_facts([ego, beside])[0]
    assert not facts.collided and facts.min_ttc is None
    assert facts.min_distance == pytest.approx(1.5)
    assert find_collisions([ego, beside], 0.1) == []


def test_pedestrian_crossing_ahead_is_closest_when_in_lane() -> None:
    ego = _straight("ego", 0, 0, 0.0, 5, 40, ego=True)
    walker = AgentTrace(
        name="Pedestrian1",
        kind="Pedestrian",
        width=0.5,
        length=0.5,
        trajectory=[
            TracePoint(step=i, x=6 - 0.2 * i, y=15, heading=math.pi / 2, speed=2) for i in range(40)
        ],
    )
    facts = ego_pair_facts([ego, walker])[0]
    assert facts.collided
    assert 0 < facts.min_distance_step < 40
