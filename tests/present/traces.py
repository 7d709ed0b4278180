"""Hand-made traces for fast tests: motion we know exactly, on a map we ship."""

from __future__ import annotations

import math
from pathlib import Path

from arise.maps.registry import MapRegistry
from arise.present.source import Origin, TraceSource
from arise.validate.facts import ego_pair_facts, find_collisions
from arise.validate.types import AgentTrace, MapChoice, SimulationFacts, TracePoint

TIMESTEP = 0.1
STEPS = 80


def straight(
    x0: float, y0: float, heading: float, speed: float, steps: int = STEPS
) -> list[TracePoint]:
    """Constant speed along a Scenic heading (0 = +y, counter-clockwise)."""
    dx, dy = -math.sin(heading) * speed * TIMESTEP, math.cos(heading) * speed * TIMESTEP
    return [
        TracePoint(
            step=i, x=round(x0 + dx * i, 3), y=round(y0 + dy * i, 3), heading=heading, speed=speed
        )
        for i in range(steps + 1)
    ]


def braking_then_turning() -> list[TracePoint]:
    """A car that slows down and bends: a path a simplifier must keep vertices of."""
    points, x, y, heading, speed = [], 20.0, 5.25, math.pi / 2, 8.0
    for i in range(STEPS + 1):
        points.append(
            TracePoint(
                step=i,
                x=round(x, 3),
                y=round(y, 3),
                heading=round(heading, 4),
                speed=round(speed, 3),
            )
        )
        speed = max(2.0, speed - 0.05)
        heading += 0.004 if i > 40 else 0.0
        x += -math.sin(heading) * speed * TIMESTEP
        y += math.cos(heading) * speed * TIMESTEP
    return points


def agents() -> list[AgentTrace]:
    return [
        AgentTrace(
            name="ego",
            kind="Car",
            blueprint="vehicle.lincoln.mkz_2017",
            width=2.0,
            length=4.5,
            is_ego=True,
            trajectory=straight(10.0, -5.25, -math.pi / 2, 10.0),  # drives along +x
        ),
        AgentTrace(
            name="Pedestrian1",
            kind="Pedestrian",
            blueprint="walker.pedestrian.0001",
            width=0.5,
            length=0.5,
            behavior="AdversaryBehavior",
            trajectory=straight(60.0, -10.0, 0.0, 1.0),  # steps off the kerb into the ego
        ),
        AgentTrace(
            name="Car1",
            kind="Car",
            width=2.0,
            length=4.5,
            trajectory=braking_then_turning(),
        ),
        AgentTrace(
            name="Cone1",
            kind="Cone",
            blueprint="static.prop.constructioncone",
            width=0.4,
            length=0.4,
            trajectory=straight(40.0, -9.0, 0.0, 0.0),
        ),
    ]


def simulation(weather: str | None = "HardRainNight") -> SimulationFacts:
    traces = agents()
    return SimulationFacts(
        steps=STEPS,
        timestep=TIMESTEP,
        termination_type="timeLimit",
        termination_reason="maximum steps",
        agents=traces,
        collisions=find_collisions(traces, TIMESTEP),
        ego_pairs=ego_pair_facts(traces),
        params={"weather": weather} if weather else {},
    )


def straight_map() -> MapChoice:
    return MapRegistry(None).resolve("arise_straight")


def source(script: Path, weather: str | None = "HardRainNight") -> TraceSource:
    if not script.exists():
        script.write_text("# a hand-made trace stands for this script\n", encoding="utf-8")
    return TraceSource(
        script=script,
        simulation=simulation(weather),
        map=straight_map(),
        origin=Origin.CHECKED,
        seed=0,
        steps=STEPS,
    )
