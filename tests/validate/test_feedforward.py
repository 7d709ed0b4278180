"""The lateral controllers steer for the curve of the lane they follow (issue 13, ul-4).

A left turn on the green at 2.6 m/s used to swing 0.9 m either side of its 16 m arc and
leave the junction 0.5 rad short of the exit lane's heading; lane following then wove
across the lane line, and the trace counted two lane changes for a plain left turn.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from scenic.core.vectors import Vector
from scenic.domains.driving.roads import Network
from shapely.geometry import LineString, Point

from arise.kb.compose import compose
from arise.kb.loader import load_kb
from arise.validate import CheckOptions, WorkerPool, check_text
from arise.validate.worldmodel.feedforward import (
    DAMPING_RATIO,
    FollowedPath,
    feed_forward_steer,
    heading_damping,
)
from arise.validate.worldmodel.linegeometry import signed_curvatures

MAPS = Path(__file__).resolve().parents[2] / "src" / "arise" / "maps" / "data"
RADIUS = 20.0


def _arc(left: bool) -> LineString:
    """A quarter circle of RADIUS driven from (0, 0) northwards, bending left or right."""
    sign = 1 if left else -1
    centre = -sign * RADIUS
    return LineString(
        [
            (centre + sign * RADIUS * math.cos(a / 50), RADIUS * math.sin(a / 50))
            for a in range(0, 79)
        ]
    )


def test_curvature_is_positive_where_the_line_bends_left() -> None:
    _, left = signed_curvatures(_arc(left=True), 1.0, 3.0)
    _, right = signed_curvatures(_arc(left=False), 1.0, 3.0)
    assert left[5:-5] == pytest.approx(1 / RADIUS, rel=0.02)
    assert right[5:-5] == pytest.approx(-1 / RADIUS, rel=0.02)
    _, straight = signed_curvatures(LineString([(0, 0), (0, 50)]), 1.0, 3.0)
    assert straight == pytest.approx(0.0)


def test_the_feed_forward_steer_gives_the_yaw_rate_of_the_curve() -> None:
    """In the offline physics, yaw rate = -v sin(steer pi / 2) / wheelbase."""
    wheelbase, speed = 4.9, 8.0
    steer = feed_forward_steer(1 / RADIUS, wheelbase)
    assert steer < 0  # negative steers left
    yaw_rate = -speed * math.sin(steer * math.pi / 2) / wheelbase
    assert yaw_rate == pytest.approx(speed / RADIUS)
    assert feed_forward_steer(-1 / RADIUS, wheelbase) == pytest.approx(-steer)
    assert feed_forward_steer(10.0, wheelbase) == pytest.approx(-1.0)  # tighter than a car


def test_heading_damping_tops_up_the_derivative_term_only_at_low_speed() -> None:
    k_p, k_d, wheelbase = 0.2, 0.2, 4.9
    c = math.pi / (2 * wheelbase)
    standing = heading_damping(k_p, k_d, 0.0, wheelbase)
    assert standing * math.sqrt(c) / (2 * math.sqrt(k_p)) == pytest.approx(DAMPING_RATIO)
    slow = heading_damping(k_p, k_d, 2.0, wheelbase)
    assert slow + k_d * 2.0 == pytest.approx(standing)  # together: the same damping
    assert heading_damping(k_p, k_d, 15.0, wheelbase) == 0.0


class _Car:
    def __init__(self, x: float, y: float, heading: float, speed: float = 3.0):
        self.position = Vector(x, y)
        self.heading = heading
        self.speed = speed


@pytest.fixture(scope="module")
def junction() -> Network:
    return Network.fromFile(MAPS / "arise_intersection4.xodr", useCache=False)


def _left_turn(network: Network) -> LineString:
    lane = network.laneAt(Vector(1.75, -20))
    turn = next(m for m in lane.maneuvers if m.type.name == "LEFT_TURN")
    return LineString(turn.connectingLane.centerline.lineString.coords)


def _on(line: LineString, along: float, left: float) -> tuple[float, float, float]:
    """A point `left` metres left of the line, and the line's Scenic heading there."""
    a, b = line.interpolate(along - 0.5), line.interpolate(along + 0.5)
    angle = math.atan2(b.y - a.y, b.x - a.x)
    p = line.interpolate(along)
    return p.x - left * math.sin(angle), p.y + left * math.cos(angle), angle - math.pi / 2


def test_the_path_is_found_from_the_error_the_behavior_measured(junction: Network) -> None:
    """Halfway round the left turn, 0.3 m inside: the turning lane, not the straight one."""
    turn = _left_turn(junction)
    x, y, heading = _on(turn, turn.length / 2, 0.3)
    car = _Car(x, y, heading + 0.1)
    point = FollowedPath(junction, car).read(0.3)
    assert point is not None
    assert point.curvature == pytest.approx(1 / 15.75, rel=0.05)  # the arc's radius
    assert point.heading_error == pytest.approx(0.1, abs=0.01)
    assert FollowedPath(junction, car).read(2.5) is None  # no lane lies 2.5 m right


def test_a_car_against_its_lane_reads_the_curve_its_own_way(junction: Network) -> None:
    """Driving the turning lane backwards, its left bend is a right bend for the car."""
    turn = _left_turn(junction)
    x, y, heading = _on(turn, turn.length / 2, 0.0)
    car = _Car(x, y, heading + math.pi)
    point = FollowedPath(junction, car).read(0.0)
    assert point is not None
    assert point.curvature == pytest.approx(-1 / 15.75, rel=0.05)
    assert Point(x, y).distance(turn) < 0.01


@pytest.mark.slow
def test_a_slow_left_turn_follows_its_arc_and_leaves_on_the_exit_heading(
    validator_pool: WorkerPool, junction: Network
) -> None:
    """The ul-4 turn: the ego's 5.3 m/s gives a 2.65 m/s turn on the 16 m arc."""
    entry = load_kb().get("geometry.signalized_left_turn_on_green")
    script = compose([entry], None, "arise_intersection4").replace(
        "param OPT_EGO_SPEED = Range(5, 8)", "param OPT_EGO_SPEED = 5.3"
    )
    for seed in (0, 1):
        result = check_text(
            script, CheckOptions(seed=seed, steps=200, timeout=120), pool=validator_pool
        )
        assert result.ok and result.simulation is not None, result.diagnostic
        ego = next(agent for agent in result.simulation.agents if agent.is_ego)
        assert ego.lane_changes == 0 and not ego.weaving
        start = Vector(ego.trajectory[0].x, ego.trajectory[0].y)
        lane = junction.laneAt(start)
        turn = next(m for m in lane.maneuvers if m.type.name == "LEFT_TURN")
        arc = LineString(turn.connectingLane.centerline.lineString.coords)
        inside = [p for p in ego.trajectory if junction.intersectionAt(Vector(p.x, p.y))]
        assert inside, "the ego never reached the junction"
        worst = max(arc.distance(Point(p.x, p.y)) for p in inside)
        assert worst < 0.5, f"seed {seed}: {worst:.2f} m off the turning lane's centre"
        leaving = inside[-1]
        exit_line = list(turn.endLane.centerline.lineString.coords)  # a straight lane
        (x0, y0), (x1, y1) = exit_line[0][:2], exit_line[1][:2]
        wanted = math.atan2(y1 - y0, x1 - x0) - math.pi / 2
        error = abs((leaving.heading - wanted + math.pi) % (2 * math.pi) - math.pi)
        assert error < 0.15, f"seed {seed}: left the junction {error:.2f} rad off the exit lane"
