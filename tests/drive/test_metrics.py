"""The driving metrics on small traces drawn by hand, each with an answer worked out here.

The traces need no road network (`road=None`); lane invasions and out of road on a real
map are in test_metrics_road.py. Conventions: Scenic headings (0 faces +y, counter-
clockwise), 0.1 s per step, cars 2 m wide and 4.5 m long, pedestrians 0.5 x 0.5 m.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import pytest

from arise.agents.types import EgoRoute, LightState, SignalKind, SignalTrace
from arise.drive.metrics import (
    DrivingMetrics,
    MetricsError,
    compute_metrics,
    overall_score,
)
from arise.validate.types import AgentTrace, SimulationFacts, TracePoint

EAST = -math.pi / 2
WEST = math.pi / 2
NORTH = 0.0
DT = 0.1

Pose = tuple[float, float, float]  # x, y, heading


def track(poses: Sequence[Pose], speed: float = 0.0) -> list[TracePoint]:
    return [
        TracePoint(step=i, x=x, y=y, heading=h, speed=speed) for i, (x, y, h) in enumerate(poses)
    ]


def line(start: tuple[float, float], velocity: tuple[float, float], steps: int, heading: float):
    """Poses at constant velocity (m/s), one per step of DT, steps + 1 of them."""
    return [
        (start[0] + velocity[0] * DT * i, start[1] + velocity[1] * DT * i, heading)
        for i in range(steps + 1)
    ]


def car(name: str, poses: Sequence[Pose], *, ego: bool = False, behavior: str | None = None):
    return AgentTrace(
        name=name,
        kind="Car",
        width=2.0,
        length=4.5,
        is_ego=ego,
        behavior=behavior,
        trajectory=track(poses),
    )


def pedestrian(name: str, poses: Sequence[Pose], behavior: str | None = "AdversaryBehavior"):
    return AgentTrace(
        name=name,
        kind="Pedestrian",
        width=0.5,
        length=0.5,
        behavior=behavior,
        trajectory=track(poses),
    )


def facts(
    agents: list[AgentTrace],
    route: Sequence[tuple[float, float]] = ((0.0, 0.0), (200.0, 0.0)),
    signals: Sequence[SignalTrace] = (),
) -> SimulationFacts:
    steps = max(len(a.trajectory) for a in agents) - 1
    return SimulationFacts(
        steps=steps,
        timestep=DT,
        termination_type="timeLimit",
        termination_reason="hand-made",
        agents=agents,
        route=EgoRoute(waypoints=list(route), target_speed=10.0),
        signals=list(signals),
    )


def measure(*agents: AgentTrace, timeout_s: float = 10.0, **given: object) -> DrivingMetrics:
    return compute_metrics(facts(list(agents), **given), None, timeout_s=timeout_s)  # type: ignore[arg-type]


# --- a clean drive: the task and comfort metrics ---------------------------------------


def test_a_straight_drive_on_its_route_scores_only_what_it_left_undone() -> None:
    # 10 m/s east along the route for 10 s: 100 m of a 200 m route.
    got = measure(car("ego", line((0, 0), (10, 0), 100, EAST), ego=True))
    assert (got.collision, got.collision_count, got.red_lights_run, got.stop_signs_run) == (
        0,
        0,
        0,
        0,
    )
    assert got.distance_to_route_m == 0 and got.route_following == 1
    assert got.route_completion == pytest.approx(0.5)
    assert got.time_spent_s == pytest.approx(10.0)
    assert got.mean_acceleration == pytest.approx(0, abs=1e-9)
    assert got.mean_yaw_velocity == pytest.approx(0, abs=1e-9)
    assert got.min_ttc_s is None and got.pet_s is None
    # 1 - 0.3 * (1 - 0.5) incomplete - 0.1 * 10 / 10 running time
    assert got.overall_score == pytest.approx(0.75)
    assert got.road_checked is False and got.lane_invasions == 0 and got.out_of_road_m == 0


def test_completing_the_route_ends_the_episode_there() -> None:
    # Route of 50 m; at 10 m/s the ego is within 1 m of its end at step 49 (x = 49).
    got = measure(
        car("ego", line((0, 0), (10, 0), 100, EAST), ego=True),
        route=((0.0, 0.0), (50.0, 0.0)),
    )
    assert got.route_completion == 1.0
    assert got.time_spent_s == pytest.approx(4.9)
    assert got.overall_score == pytest.approx(1 - 0.1 * 4.9 / 10)


def test_a_contact_after_the_route_is_complete_is_not_counted() -> None:
    parked = car("parked", [(80.0, 0.0, EAST)] * 101)
    got = measure(
        car("ego", line((0, 0), (10, 0), 100, EAST), ego=True),
        parked,
        route=((0.0, 0.0), (50.0, 0.0)),
    )
    assert got.collision == 0 and got.collision_count == 0 and got.route_completion == 1.0


def test_driving_two_metres_beside_the_route() -> None:
    got = measure(car("ego", line((0, -2), (10, 0), 50, EAST), ego=True))
    assert got.distance_to_route_m == pytest.approx(2.0)
    assert got.route_following == pytest.approx(1 - 2 / 5)
    # progress still counts within 10 m of the route: 50 m of 200
    assert got.route_completion == pytest.approx(0.25)


def test_progress_needs_the_route_within_ten_metres() -> None:
    got = measure(car("ego", line((0, -12), (10, 0), 50, EAST), ego=True))
    assert got.route_completion == 0
    assert got.distance_to_route_m == pytest.approx(12.0)
    assert got.route_following == 0


def test_progress_does_not_jump_to_a_later_leg_of_the_route_close_by() -> None:
    # Out 50 m east, across 3.5 m, back west: 103.5 m. Driving the first 30 m passes
    # 3.5 m from the way back (arc 73.5 m there), which must not count.
    route = ((0.0, 0.0), (50.0, 0.0), (50.0, 3.5), (0.0, 3.5))
    got = measure(car("ego", line((0, 0), (10, 0), 30, EAST), ego=True), route=route)
    assert got.route_completion == pytest.approx(30 / 103.5, abs=1e-4)


def test_driving_the_route_backwards_from_its_end_completes_nothing() -> None:
    got = measure(
        car("ego", line((100, 0), (-10, 0), 50, WEST), ego=True), route=((0.0, 0.0), (100.0, 0.0))
    )
    assert got.route_completion == 0 and got.time_spent_s == pytest.approx(5.0)


def test_steady_acceleration_of_two_metres_per_second_squared() -> None:
    poses = [(0.5 * 2.0 * (i * DT) ** 2, 0.0, EAST) for i in range(51)]
    got = measure(car("ego", poses, ego=True))
    assert got.mean_acceleration == pytest.approx(2.0)


def test_a_circle_at_constant_speed_has_its_centripetal_acceleration_and_yaw_rate() -> None:
    # Radius 20 m at 10 m/s: yaw rate 0.5 rad/s, |a| = v^2 / r = 5 m/s^2.
    rate, radius = 0.5, 20.0
    poses = []
    for i in range(61):
        angle = rate * i * DT  # counter-clockwise around (0, 20), starting at the origin
        x, y = radius * math.sin(angle), radius - radius * math.cos(angle)
        poses.append((x, y, EAST + angle))
    route = [(radius * math.sin(a / 10), radius - radius * math.cos(a / 10)) for a in range(61)]
    got = measure(car("ego", poses, ego=True), route=route)
    assert got.mean_yaw_velocity == pytest.approx(0.5)
    assert got.mean_acceleration == pytest.approx(5.0, rel=0.01)
    assert got.distance_to_route_m == pytest.approx(0.0, abs=0.05)


def test_yaw_velocity_wraps_across_the_half_turn() -> None:
    # Headings step from just below pi to just above -pi: 0.02 rad per step, not 2 pi.
    poses = [(float(i), 0.0, math.pi - 0.01 + 0.02 * i) for i in range(2)]
    poses = [(x, y, (h + math.pi) % (2 * math.pi) - math.pi) for x, y, h in poses]
    got = measure(car("ego", poses, ego=True))
    assert got.mean_yaw_velocity == pytest.approx(0.02 / DT)


# --- collisions: oriented boxes -----------------------------------------------------------


def test_running_into_a_parked_car_is_one_collision_and_ends_the_episode() -> None:
    # Ego front at x + 2.25, parked car's back at 40 - 2.25: contact once x >= 35.5,
    # i.e. at step 36 (x = 36.0).
    got = measure(
        car("ego", line((0, 0), (10, 0), 100, EAST), ego=True),
        car("parked", [(40.0, 0.0, EAST)] * 101),
    )
    assert got.collision == 1 and got.collision_count == 1
    assert got.time_spent_s == pytest.approx(3.6)
    assert got.route_completion == pytest.approx(36 / 200)
    assert got.min_ttc_s == 0 and got.pet_s == 0
    incomplete, running = 1 - 36 / 200, 3.6 / 10
    assert got.overall_score == pytest.approx(1 - 0.4 - 0.3 * incomplete - 0.1 * running, abs=1e-4)


def test_driving_through_two_parked_cars_is_two_contacts_and_one_collision() -> None:
    got = measure(
        car("ego", line((0, 0), (10, 0), 100, EAST), ego=True),
        car("first", [(40.0, 0.0, EAST)] * 101),
        car("second", [(70.0, 0.0, EAST)] * 101),
    )
    assert got.collision == 1 and got.collision_count == 2


def test_boxes_tell_a_near_miss_from_a_contact_where_circles_would_not() -> None:
    # A car turned 45 degrees above the ego: its lowest corner is 2.298 m below its centre
    # (x offset +0.88, inside the ego's length). The ego's top edge is at y = 1.
    def parked_at(y: float) -> AgentTrace:
        return car("turned", [(0.0, y, math.pi / 4)] * 2)

    ego = car("ego", [(0.0, 0.0, EAST)] * 2, ego=True)
    assert measure(ego, parked_at(3.2)).collision == 1  # corner at y = 0.90
    clear = measure(ego, parked_at(3.4))  # corner at y = 1.10; circles of 2.46 m would touch
    assert clear.collision == 0 and clear.min_ttc_s is None


def test_side_by_side_in_neighbouring_lanes_is_no_collision() -> None:
    got = measure(
        car("ego", line((0, 0), (10, 0), 50, EAST), ego=True),
        car("beside", line((0, 3.5), (10, 0), 50, EAST)),
    )
    assert got.collision == 0 and got.min_ttc_s is None and got.pet_s is None


# --- time-to-collision and post-encroachment time ----------------------------------------


def test_ttc_to_a_slower_lead_car_is_the_gap_over_the_closing_speed() -> None:
    # Ego 10 m/s, lead 5 m/s, centres 30 m apart: bumper gap 25.5 m closing at 5 m/s.
    # After 2 s the gap is 15.5 m: the smallest TTC is 3.1 s.
    got = measure(
        car("ego", line((0, 0), (10, 0), 20, EAST), ego=True),
        car("lead", line((30, 0), (5, 0), 20, EAST)),
    )
    assert got.collision == 0
    assert got.min_ttc_s == pytest.approx(3.1)


def test_ttc_head_on_counts_both_speeds() -> None:
    # Oncoming at 5 m/s in the ego's lane, 50 m apart: gap 45.5 m closing at 15 m/s;
    # after one step 44 m: 2.933 s.
    got = measure(
        car("ego", line((0, 0), (10, 0), 1, EAST), ego=True),
        car("oncoming", line((50, 0), (-5, 0), 1, WEST)),
    )
    assert got.min_ttc_s == pytest.approx(44 / 15, abs=1e-3)


def crossing(ped_y0: float) -> tuple[AgentTrace, AgentTrace]:
    """The ego east along y = 0 from x = 0.3 at 10 m/s; a pedestrian north along x = 50
    at 1.5 m/s from y = ped_y0."""
    return (
        car("ego", line((0.3, 0), (10, 0), 100, EAST), ego=True),
        pedestrian("walker", line((50.0, ped_y0), (0, 1.5), 100, NORTH)),
    )


def test_pet_of_a_pedestrian_that_crossed_just_before_the_ego() -> None:
    # The walker's box is in the ego's band (|y| <= 1.25) at steps 26..41; the ego's box
    # covers x = 50 +- 0.25 at steps 48..52 (x in [47.5, 52.5]). PET = (48 - 41) * 0.1 s.
    # At constant velocities the two would never touch: no TTC.
    got = measure(*crossing(-5.03))
    assert got.collision == 0
    assert got.pet_s == pytest.approx(0.7)
    assert got.min_ttc_s is None


def test_a_pedestrian_walking_into_the_ego_is_a_collision_with_zero_pet() -> None:
    # Walker in the band at steps 48..64 (y from -8.03): the ego is at x = 48.3 at step 48.
    got = measure(*crossing(-8.03))
    assert got.collision == 1 and got.pet_s == 0 and got.min_ttc_s == 0


def test_pet_is_measured_against_the_adversary_only() -> None:
    ego, walker = crossing(-5.03)
    # The bystander is in the ego's band at steps 28..44, the ego reaches it at step 48.
    bystander = pedestrian("bystander", line((50.3, -5.43), (0, 1.5), 100, NORTH), None)
    marked = measure(ego, walker, bystander)
    assert marked.pet_s == pytest.approx(0.7)
    unmarked = walker.model_copy(update={"behavior": None})
    # with no adversary marked, every other agent counts
    assert measure(ego, unmarked, bystander).pet_s == pytest.approx(0.4)


def test_the_conflict_is_read_against_the_adversary() -> None:
    # Crossing just before the ego: the two never touch, but they come within reach.
    near = measure(*crossing(-5.03))
    assert near.adversary_gap_m is not None and 0 < near.adversary_gap_m < 6
    assert near.conflict_reached == 1
    hit = measure(*crossing(-8.03))
    assert hit.adversary_gap_m == 0 and hit.adversary_ttc_s == 0 and hit.conflict_reached == 1
    # 20 m to the side, walking the same way: out of reach, never closing.
    far = measure(
        car("ego", line((0, 0), (10, 0), 100, EAST), ego=True),
        pedestrian("walker", line((20, 20), (1.5, 0), 100, EAST)),
    )
    assert far.adversary_gap_m is not None and far.adversary_gap_m > 18
    assert far.adversary_ttc_s is None and far.conflict_reached == 0
    alone = measure(car("ego", line((0, 0), (10, 0), 100, EAST), ego=True))
    assert alone.conflict_reached is None and alone.adversary_gap_m is None


def test_a_walker_on_the_sidewalk_never_crosses_the_ego_s_path() -> None:
    got = measure(
        car("ego", line((0, 0), (10, 0), 100, EAST), ego=True),
        pedestrian("walker", line((20, 6), (1.5, 0), 100, EAST)),
    )
    assert got.pet_s is None and got.min_ttc_s is None and got.collision == 0


# --- red lights and stop signs -------------------------------------------------------------

# A stop line across the eastbound lane at x = 50: p1 on the lane's right edge (south).
EAST_LINE = ((50.0, -2.0), (50.0, 2.0))


def light(*changes: tuple[int, LightState]) -> SignalTrace:
    return SignalTrace(
        id="light", kind=SignalKind.TRAFFIC_LIGHT, stop_line=EAST_LINE, states=list(changes)
    )


def stop_sign() -> SignalTrace:
    return SignalTrace(
        id="stop", kind=SignalKind.STOP_SIGN, stop_line=EAST_LINE, states=[(0, LightState.RED)]
    )


def through() -> AgentTrace:
    """The ego east at 10 m/s: its rear (x - 2.25) passes x = 50 at step 53."""
    return car("ego", line((0, 0), (10, 0), 100, EAST), ego=True)


@pytest.mark.parametrize(
    ("changes", "runs"),
    [
        pytest.param([(0, LightState.RED)], 1, id="red"),
        pytest.param([(0, LightState.GREEN)], 0, id="green"),
        pytest.param([(0, LightState.YELLOW)], 0, id="yellow"),
        pytest.param([(0, LightState.GREEN), (53, LightState.RED)], 1, id="red-at-crossing"),
        pytest.param([(0, LightState.GREEN), (54, LightState.RED)], 0, id="red-just-after"),
        pytest.param([(0, LightState.RED), (50, LightState.GREEN)], 0, id="green-as-it-arrived"),
    ],
)
def test_a_red_light_is_run_when_the_ego_s_rear_crosses_its_line_on_red(
    changes: list[tuple[int, LightState]], runs: int
) -> None:
    got = measure(through(), signals=[light(*changes)])
    assert got.red_lights_run == runs and got.stop_signs_run == 0


def test_a_nose_over_the_line_is_not_a_red_light_run() -> None:
    # Stops with its front 1 m past the line (x = 48.75), on red all the time.
    poses = [(min(10 * DT * i, 48.75), 0.0, EAST) for i in range(101)]
    assert (
        measure(car("ego", poses, ego=True), signals=[light((0, LightState.RED))]).red_lights_run
        == 0
    )


def test_an_oncoming_car_crossing_the_line_the_other_way_runs_nothing() -> None:
    ego = car("ego", line((100, 0), (-10, 0), 100, WEST), ego=True)
    got = measure(ego, route=((100.0, 0.0), (-100.0, 0.0)), signals=[light((0, LightState.RED))])
    assert got.red_lights_run == 0


def test_a_crossing_beside_the_stop_line_is_not_through_it() -> None:
    ego = car("ego", line((0, 6), (10, 0), 100, EAST), ego=True)
    got = measure(ego, route=((0.0, 6.0), (200.0, 6.0)), signals=[light((0, LightState.RED))])
    assert got.red_lights_run == 0


def stop_then_go(stop_x: float, wait_steps: int, floor: float = 0.0) -> AgentTrace:
    """East at 10 m/s to `stop_x`, braking over its last 10 m at 5 m/s^2 to `floor` m/s,
    holding that speed for `wait_steps`, then on at 10 m/s."""
    poses: list[Pose] = []
    x, v, held = 0.0, 10.0, 0
    while x < 120:
        poses.append((x, 0.0, EAST))
        if x >= stop_x - 10 and held < wait_steps:
            v = max(floor, v - 5.0 * DT)
            if v <= floor + 1e-9:
                held += 1
        else:
            v = 10.0
        x += v * DT
        if floor == 0 and x > stop_x and held < wait_steps:
            x = stop_x
    return car("ego", poses, ego=True)


def test_a_stop_sign_passed_at_speed_is_run() -> None:
    assert measure(through(), signals=[stop_sign()]).stop_signs_run == 1


def test_a_full_stop_before_the_stop_sign_is_not_a_run() -> None:
    # The centre stops at 45.75: the front at 48, 2 m before the line, for 2 s.
    got = measure(stop_then_go(45.75, 20), signals=[stop_sign()], timeout_s=30)
    assert got.stop_signs_run == 0 and got.red_lights_run == 0


def test_rolling_through_a_stop_sign_at_walking_pace_is_a_run() -> None:
    got = measure(stop_then_go(45.75, 20, floor=1.0), signals=[stop_sign()], timeout_s=30)
    assert got.stop_signs_run == 1


def test_a_stop_far_before_the_stop_sign_does_not_count() -> None:
    # Stops with its front at 40 (10 m before the line), then drives through.
    got = measure(stop_then_go(37.75, 20), signals=[stop_sign()], timeout_s=30)
    assert got.stop_signs_run == 1


def test_waiting_at_a_red_light_then_going_on_green_runs_nothing() -> None:
    ego = stop_then_go(45.75, 40)
    got = measure(ego, signals=[light((0, LightState.RED), (60, LightState.GREEN))], timeout_s=30)
    assert got.red_lights_run == 0


# --- the overall score and refusals ------------------------------------------------------


@pytest.mark.parametrize(
    ("terms", "score"),
    [
        pytest.param((0, 0, 0, 1, 0), 1.0, id="perfect"),
        pytest.param((1, 0, 0, 1, 0), 0.6, id="collision"),
        pytest.param((0, 5, 0, 1, 0), 0.95, id="5 m out of road"),
        pytest.param((0, 50, 0, 1, 0), 0.9, id="out of road clipped at 10 m"),
        pytest.param((0, 0, 2.5, 1, 0), 0.95, id="2.5 m from the route"),
        pytest.param((0, 0, 0, 0.5, 0), 0.85, id="half the route"),
        pytest.param((0, 0, 0, 1, 15), 0.95, id="half the time-out"),
        pytest.param((1, 10, 5, 0, 30), 0.0, id="worst"),
    ],
)
def test_overall_score_weights(terms: tuple[float, ...], score: float) -> None:
    collision, out_of_road, distance, completion, seconds = terms
    got = overall_score(
        collision=collision,
        out_of_road_m=out_of_road,
        distance_to_route_m=distance,
        route_completion=completion,
        time_spent_s=seconds,
        timeout_s=30.0,
    )
    assert got == pytest.approx(score)


def _without_ego() -> SimulationFacts:
    return facts([car("other", line((0, 0), (10, 0), 10, EAST))])


def _without_route() -> SimulationFacts:
    return facts([through()]).model_copy(update={"route": None})


@pytest.mark.parametrize(
    ("make", "timeout", "message"),
    [
        pytest.param(_without_ego, 10.0, "no ego", id="no-ego"),
        pytest.param(_without_route, 10.0, "no route", id="no-route"),
        pytest.param(lambda: facts([through()]), 0.0, "time-out", id="zero-timeout"),
        pytest.param(lambda: facts([through()]), math.nan, "time-out", id="nan-timeout"),
    ],
)
def test_what_cannot_be_measured_is_one_clear_error(
    make: Callable[[], SimulationFacts], timeout: float, message: str
) -> None:
    with pytest.raises(MetricsError, match=message):
        compute_metrics(make(), None, timeout_s=timeout)


def test_an_absurd_timestep_is_an_error_not_an_infinite_metric() -> None:
    # 1e-310 s per step turns any move into an infinite speed.
    absurd = facts([through()]).model_copy(update={"timestep": 1e-310})
    with pytest.raises(MetricsError, match="valid"):
        compute_metrics(absurd, None, timeout_s=10.0)


def test_a_trace_too_tangled_for_a_pet_is_refused_not_measured_for_minutes(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The ego dwells on one spot for 200 steps and leaves; the other arrives there and
    # dwells for 200 steps: 40,000 overlapping pairs of footprints, above a bound of 10,000.
    from arise.drive import metrics_encounters

    monkeypatch.setattr(metrics_encounters, "MAX_PET_PAIRS", 10_000)
    dwell = [(0.001 * (i % 2), 0.0, EAST) for i in range(200)]
    ego = car("ego", dwell + [(30.0, 0.0, EAST)] * 200, ego=True)
    other = car("other", [(60.0, 0.0, EAST)] * 200 + dwell, behavior="AdversaryBehavior")
    with pytest.raises(MetricsError, match="too many to measure a PET"):
        measure(ego, other, timeout_s=40)


def test_the_metrics_are_finite_and_named_as_the_columns() -> None:
    got = measure(*crossing(-5.03))
    assert list(got.model_dump()) == [
        "collision",
        "collision_count",
        "red_lights_run",
        "stop_signs_run",
        "out_of_road_m",
        "distance_to_route_m",
        "route_following",
        "route_completion",
        "time_spent_s",
        "mean_acceleration",
        "mean_yaw_velocity",
        "lane_invasions",
        "overall_score",
        "min_ttc_s",
        "pet_s",
        "adversary_gap_m",
        "adversary_ttc_s",
        "conflict_reached",
        "road_checked",
    ]
    assert all(math.isfinite(v) for v in got.model_dump().values() if isinstance(v, float))
