"""SafeBench's driving metrics of one run, computed by the parent from the trace.

`compute_metrics` is pure: the validated `SimulationFacts` (trajectories, the ego's route,
the signals' states) and a road network the parent loaded itself from its own map. The
worker only reports where everyone went; every metric is derived here, so a script can
move a metric only by what its agents did. Definitions, units and sources:
docs/agents.md, "## Metrics".

The episode ends, as in SafeBench, at the ego's first collision or when it completes its
route, else at the end of the simulation; everything but `collision_count` is measured
over the episode.
"""

from __future__ import annotations

import math

import numpy as np
from pydantic import ValidationError

from arise.drive.metrics_encounters import contacts, min_gap, min_ttc, post_encroachment
from arise.drive.metrics_road import (
    LaneRef,
    RoadQueries,
    ScenicRoad,
    lane_invasions,
    out_of_road_length,
)
from arise.drive.metrics_route import distances_to_route, follow_route
from arise.drive.metrics_signals import red_lights_run, stop_signs_run
from arise.drive.metrics_track import Track
from arise.drive.metrics_types import (
    DrivingMetrics,
    MetricsError,
    overall_score,
    route_following,
)
from arise.generate.conflict import REACH_GAP_M, REACH_TTC_S
from arise.validate.types import AgentTrace, SimulationFacts

__all__ = [
    "DrivingMetrics",
    "LaneRef",
    "MetricsError",
    "RoadQueries",
    "ScenicRoad",
    "compute_metrics",
    "overall_score",
]

#: The behavior our scripts give their adversary (arise.kb.actors.ADVERSARY_BEHAVIOR).
ADVERSARY_BEHAVIOR = "AdversaryBehavior"


def adversaries(agents: list[AgentTrace]) -> list[AgentTrace]:
    """The agents a PET is measured against: those running our `AdversaryBehavior`, else
    every other agent (the bench's criticality picks the same adversary first)."""
    others = [agent for agent in agents if not agent.is_ego]
    marked = [agent for agent in others if agent.behavior == ADVERSARY_BEHAVIOR]
    return marked or others


def compute_metrics(
    facts: SimulationFacts, road: RoadQueries | None, *, timeout_s: float
) -> DrivingMetrics:
    """The metrics of one run (see the module doc). `road` None: no network to check the
    lanes against (lane invasions and out of road read 0, `road_checked` False).
    `timeout_s` is the run's time limit, which normalises the running time.

    Raises MetricsError for a trace without an ego, an ego without a trajectory or a
    route, or numbers no metric can be made of."""
    if not (math.isfinite(timeout_s) and timeout_s > 0):
        raise MetricsError(f"the time-out must be a positive number of seconds, not {timeout_s}")
    ego_trace = next((agent for agent in facts.agents if agent.is_ego), None)
    if ego_trace is None:
        raise MetricsError("the trace has no ego: nothing to measure")
    if facts.route is None:
        raise MetricsError("the trace has no route for the ego: route metrics cannot be made")
    dt = facts.timestep
    whole = Track.of(ego_trace, dt)
    if not len(whole):
        raise MetricsError("the ego has no trajectory: nothing to measure")
    others = [Track.of(agent, dt) for agent in facts.agents if not agent.is_ego]

    # The drive ends when the route is complete; the episode also at the first contact.
    progress = follow_route(facts.route, whole.x, whole.y)
    drive_end = int(whole.steps[-1])
    if progress.completed_at is not None:
        drive_end = int(whole.steps[progress.completed_at])
    met = contacts(whole.upto(drive_end), [other.upto(drive_end) for other in others])
    end = drive_end if met.first_step is None else min(drive_end, met.first_step)
    ego = whole.upto(end)
    near = [other.upto(end) for other in others]
    named = {agent.name for agent in adversaries(facts.agents)}

    last = len(ego) - 1
    completion = progress.completion(last)
    distance = float(np.mean(distances_to_route(facts.route, ego.x, ego.y)))
    seconds = float(ego.steps[-1] - ego.steps[0]) * dt
    out_of_road, lane_crossings = 0.0, 0
    if road is not None:
        xs, ys = ego.x.tolist(), ego.y.tolist()
        out_of_road = out_of_road_length(road, xs, ys)
        lane_crossings = lane_invasions(road, xs, ys, dt)
    opponents = [o for o in near if o.name in named]
    gap, ttc = min_gap(ego, opponents), min_ttc(ego, opponents)
    reached = None
    if opponents:
        reached = int(
            (gap is not None and gap < REACH_GAP_M) or (ttc is not None and ttc < REACH_TTC_S)
        )
    try:
        return DrivingMetrics(
            collision=int(met.count > 0),
            collision_count=met.count,
            red_lights_run=red_lights_run(facts.signals, ego, road),
            stop_signs_run=stop_signs_run(facts.signals, ego, road),
            out_of_road_m=round(out_of_road, 3),
            distance_to_route_m=round(distance, 3),
            route_following=round(route_following(distance), 4),
            route_completion=round(completion, 4),
            time_spent_s=round(seconds, 3),
            mean_acceleration=round(_mean_acceleration(ego, dt), 4),
            mean_yaw_velocity=round(_mean_yaw_velocity(ego, dt), 4),
            lane_invasions=lane_crossings,
            overall_score=round(
                overall_score(
                    collision=float(met.count > 0),
                    out_of_road_m=out_of_road,
                    distance_to_route_m=distance,
                    route_completion=completion,
                    time_spent_s=seconds,
                    timeout_s=timeout_s,
                ),
                4,
            ),
            min_ttc_s=_rounded(min_ttc(ego, near)),
            pet_s=_rounded(post_encroachment(ego, opponents, dt)),
            adversary_gap_m=_rounded(gap),
            adversary_ttc_s=_rounded(ttc),
            conflict_reached=reached,
            road_checked=road is not None,
        )
    except ValidationError as error:
        problem = error.errors()[0]
        where = ".".join(str(part) for part in problem["loc"])
        raise MetricsError(f"the trace gives no valid {where}: {problem['msg']}") from None


def _rounded(value: float | None) -> float | None:
    return None if value is None else round(value, 3)


def _mean_acceleration(ego: Track, dt: float) -> float:
    """Mean magnitude of the change of velocity per second between consecutive intervals
    (SafeBench averages |a| over the episode's ticks)."""
    if len(ego) < 3:
        return 0.0
    middles = (ego.steps[:-1] + ego.steps[1:]).astype(np.float64) / 2  # of each interval
    seconds = np.diff(middles) * dt
    with np.errstate(over="ignore", invalid="ignore"):
        change = np.hypot(np.diff(ego.vx[1:]), np.diff(ego.vy[1:])) / seconds
    return float(np.mean(change))


def _mean_yaw_velocity(ego: Track, dt: float) -> float:
    """Total turning (each step's heading change, wrapped to +-pi, in magnitude) over the
    episode's duration, rad/s: SafeBench's mean yaw velocity."""
    if len(ego) < 2:
        return 0.0
    turned = np.abs((np.diff(ego.heading) + math.pi) % (2 * math.pi) - math.pi)
    return float(np.sum(turned) / (float(ego.steps[-1] - ego.steps[0]) * dt))
