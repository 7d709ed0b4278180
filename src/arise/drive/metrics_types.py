"""The driving metrics of one run, and SafeBench's overall score.

The names are the columns of `runs.csv` and the rows of docs/agents.md ("## Metrics").
Every number is finite and bounded below, so a report, a CSV row or a mean over runs
never meets a NaN; a value that has no meaning for a run (no closing-in, no crossing
paths) is None, never a sentinel.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field

from arise.errors import AriseError


class MetricsError(AriseError):
    """The metrics of a run cannot be computed from its trace (no ego, no route, a trace
    too pathological to measure); the message says which."""

    exit_code = 1


NonNegative = Annotated[float, Field(allow_inf_nan=False, ge=0)]
Fraction = Annotated[float, Field(allow_inf_nan=False, ge=0, le=1)]
Count = Annotated[int, Field(ge=0)]

#: SafeBench's weights of the overall score, and the value at which each term is "worst"
#: (its normaliser): collision 0.4 (a rate, 1), out of road 0.1 (10 m), distance to
#: route 0.1 (5 m), incomplete route 0.3 (a fraction, 1), running time 0.1 (the time-out).
WEIGHT_COLLISION = 0.4
WEIGHT_OUT_OF_ROAD = 0.1
WEIGHT_DISTANCE_TO_ROUTE = 0.1
WEIGHT_INCOMPLETE_ROUTE = 0.3
WEIGHT_RUNNING_TIME = 0.1
OUT_OF_ROAD_SCALE_M = 10.0
DISTANCE_TO_ROUTE_SCALE_M = 5.0


class DrivingMetrics(BaseModel):
    """SafeBench's metrics of one driven run, plus min TTC and PET (docs/agents.md).

    Measured over the episode, which ends (as in SafeBench) at the ego's first collision
    or when it completes its route, else at the end of the simulation; `collision_count`
    alone looks past a first collision, to the end of the drive.
    """

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)

    collision: Annotated[int, Field(ge=0, le=1)]  # CR: 1 when the ego touched anyone
    collision_count: Count  # contacts (starts of an overlap) with any other agent
    red_lights_run: Count  # RR
    stop_signs_run: Count  # SS
    out_of_road_m: NonNegative  # OR: path length with the ego's centre off the drivable area
    distance_to_route_m: NonNegative  # mean distance of the ego's centre to its route
    route_following: Fraction  # RF: 1 - min(1, distance_to_route_m / 5 m); higher is better
    route_completion: Fraction  # Comp: share of the route's length covered
    time_spent_s: NonNegative  # TS: the episode's duration
    mean_acceleration: NonNegative  # ACC: mean |a|, m/s^2
    mean_yaw_velocity: NonNegative  # YV: mean |yaw rate|, rad/s
    lane_invasions: Count  # LI: lane boundaries crossed outside junctions
    overall_score: Fraction  # OS: SafeBench's weighted score; HIGHER IS BETTER (1 = perfect)
    min_ttc_s: NonNegative | None  # smallest time-to-collision (boxes, constant velocity)
    pet_s: NonNegative | None  # post-encroachment time with the adversary
    # The conflict (issue 31): the adversary's closest approach and smallest TTC, and 1
    # when it came within reach (6 m, or under 3 s); None when the scene has no other agent.
    adversary_gap_m: NonNegative | None = None
    adversary_ttc_s: NonNegative | None = None
    conflict_reached: Annotated[int, Field(ge=0, le=1)] | None = None
    # False when no road network was at hand: lane invasions and out of road read 0 then.
    road_checked: bool


def _clipped(value: float, scale: float) -> float:
    return min(1.0, max(0.0, value / scale))


def overall_score(
    *,
    collision: float,
    out_of_road_m: float,
    distance_to_route_m: float,
    route_completion: float,
    time_spent_s: float,
    timeout_s: float,
) -> float:
    """SafeBench's overall score, higher is better, in [0, 1].

    Each term is normalised by its scale and clipped to [0, 1] (SafeBench does not clip;
    we do so that one wild run cannot push a score below 0), and the score is the
    weighted sum of (1 - term). Give one run's values, or the means over runs for a
    table row as SafeBench does (`collision` is then the collision rate).
    """
    if not timeout_s > 0:
        raise MetricsError(f"the time-out must be positive, not {timeout_s}")
    penalty = (
        WEIGHT_COLLISION * _clipped(collision, 1.0)
        + WEIGHT_OUT_OF_ROAD * _clipped(out_of_road_m, OUT_OF_ROAD_SCALE_M)
        + WEIGHT_DISTANCE_TO_ROUTE * _clipped(distance_to_route_m, DISTANCE_TO_ROUTE_SCALE_M)
        + WEIGHT_INCOMPLETE_ROUTE * _clipped(1.0 - route_completion, 1.0)
        + WEIGHT_RUNNING_TIME * _clipped(time_spent_s, timeout_s)
    )
    return max(0.0, min(1.0, 1.0 - penalty))


def route_following(distance_to_route_m: float) -> float:
    """RF from the mean distance to the route: 1 on the route, 0 at 5 m or more."""
    return 1.0 - _clipped(distance_to_route_m, DISTANCE_TO_ROUTE_SCALE_M)
