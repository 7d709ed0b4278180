"""The control laws of the built-in agents, against answers worked out by hand."""

from __future__ import annotations

import math

import pytest

from arise.agents.control import IdmParameters, RoutePath, idm_acceleration, pure_pursuit_curvature
from arise.agents.dynamics import (
    MAX_ACCELERATION,
    MAX_BRAKING,
    pedals_for_acceleration,
    steer_for_curvature,
)

P = IdmParameters()  # a = 1.5, b = 2.0, s0 = 2, T = 1.5, delta = 4


def test_idm_free_road_from_standstill_is_the_maximum_acceleration() -> None:
    assert idm_acceleration(0.0, 10.0) == pytest.approx(1.5)


def test_idm_free_road_at_the_desired_speed_is_zero() -> None:
    assert idm_acceleration(10.0, 10.0) == pytest.approx(0.0)


def test_idm_free_road_at_half_the_desired_speed() -> None:
    # a (1 - 0.5^4) = 1.5 * 0.9375
    assert idm_acceleration(5.0, 10.0) == pytest.approx(1.40625)


def test_idm_behind_a_leader_at_equal_speed() -> None:
    # v = 10, v0 = 20, s = 20, dv = 0: s* = 2 + 10 * 1.5 = 17;
    # a = 1.5 * (1 - (0.5)^4 - (17/20)^2) = 1.5 * (1 - 0.0625 - 0.7225) = 0.3225
    assert idm_acceleration(10.0, 20.0, gap=20.0, leader_speed=10.0) == pytest.approx(0.3225)


def test_idm_closing_on_a_standing_obstacle() -> None:
    # v = 10, v0 = 10, s = 30, dv = 10: s* = 2 + 15 + 10 * 10 / (2 sqrt(3)) = 17 + 28.8675
    # a = 1.5 * (0 - (45.8675 / 30)^2) = -3.5064
    wanted = 17 + 100 / (2 * math.sqrt(3.0))
    expected = 1.5 * (0 - (wanted / 30) ** 2)
    assert idm_acceleration(10.0, 10.0, gap=30.0, leader_speed=0.0, p=P) == pytest.approx(expected)
    assert expected == pytest.approx(-3.5064, abs=1e-3)


def test_idm_standing_at_the_minimum_gap_does_not_move() -> None:
    # v = 0, s = s0: s* = s0, a = 1.5 * (1 - 0 - 1) = 0
    assert idm_acceleration(0.0, 10.0, gap=2.0, leader_speed=0.0) == pytest.approx(0.0)


def test_pure_pursuit_straight_ahead_is_no_curvature() -> None:
    # Heading 0 faces +y: a target straight north needs no turn.
    assert pure_pursuit_curvature(0.0, 0.0, 0.0, (0.0, 10.0)) == pytest.approx(0.0)


def test_pure_pursuit_target_at_45_degrees_left() -> None:
    # alpha = 45 deg, l_d = sqrt(50): kappa = 2 sin(45 deg) / sqrt(50) = 0.2
    assert pure_pursuit_curvature(0.0, 0.0, 0.0, (-5.0, 5.0)) == pytest.approx(0.2)


def test_pure_pursuit_target_to_the_right_is_negative_and_rotates_with_heading() -> None:
    assert pure_pursuit_curvature(0.0, 0.0, 0.0, (5.0, 5.0)) == pytest.approx(-0.2)
    # Facing east (heading -90 deg), a target 5 m east and 5 m north is 45 deg to the left.
    assert pure_pursuit_curvature(0.0, 0.0, -math.pi / 2, (5.0, 5.0)) == pytest.approx(0.2)


def test_steer_for_curvature_inverts_the_world_models_yaw_rate() -> None:
    # The world model turns at v sin(steer pi/2) / L to the right; L = max(length, 4).
    assert steer_for_curvature(0.0, 4.5) == 0.0
    assert steer_for_curvature(1 / 4.5, 4.5) == pytest.approx(-1.0)  # full left
    assert steer_for_curvature(-0.5 / 4.5, 4.5) == pytest.approx(1 / 3)  # asin(0.5) = pi/6
    assert steer_for_curvature(1.0, 4.5) == -1.0  # beyond the lock: saturated


def test_pedals_give_the_acceleration_asked() -> None:
    assert pedals_for_acceleration(MAX_ACCELERATION / 2) == (0.5, 0.0)
    assert pedals_for_acceleration(-MAX_BRAKING) == (0.0, 1.0)
    assert pedals_for_acceleration(-100.0) == (0.0, 1.0)


def test_route_path_projects_and_interpolates() -> None:
    path = RoutePath([(0.0, 0.0), (0.0, 10.0), (10.0, 10.0)])
    assert path.length == pytest.approx(20.0)
    assert path.project(1.0, 4.0) == pytest.approx((4.0, 1.0))
    assert path.point_at(15.0) == pytest.approx((5.0, 10.0))
    assert path.heading_at(5.0) == pytest.approx(0.0)  # north
    assert path.heading_at(15.0) == pytest.approx(-math.pi / 2)  # east


def test_route_path_projects_near_the_last_station_on_a_route_that_doubles_back() -> None:
    # Up 10 m, 1 m across, back down: (0.5, 2) is 0.5 m from both legs.
    path = RoutePath([(0.0, 0.0), (0.0, 10.0), (1.0, 10.0), (1.0, 0.0)])
    assert path.project(0.4, 2.0, near=1.0, window=5.0)[0] == pytest.approx(2.0)
    assert path.project(0.4, 2.0, near=18.0, window=5.0)[0] == pytest.approx(19.0)
    # Past the end the path goes on straight (down, along its last segment).
    assert path.point_at(23.0) == pytest.approx((1.0, -2.0))
