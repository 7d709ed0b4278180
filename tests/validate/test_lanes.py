"""Lane changes, oncoming-lane use and weaving read from traces on a real road network.

The traces are drawn by hand on our straight map (`arise_straight`: two lanes each way,
eastbound lanes at y = -1.75 and -5.25, westbound at +1.75 and +5.25, x from 0 to 300), so
the expected answer is known without a simulator.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path

import pytest

from arise.maps.registry import MapRegistry, cached_copy
from arise.validate.lanes import find_weaving, read_lanes
from arise.validate.types import LaneChange, TracePoint
from arise.vocabulary import Side

EAST = -math.pi / 2  # Scenic headings: 0 faces +y, counter-clockwise


@pytest.fixture(scope="module")
def straight_network() -> Iterator[object]:
    from scenic.domains.driving.roads import Network

    path = Path(cached_copy(Path(MapRegistry().entries["arise_straight"].path)))
    yield Network.fromFile(path, useCache=True, writeCache=False)


def _drive(lateral: list[float], speed: float = 10.0, heading: float = EAST) -> list[TracePoint]:
    """Points 0.1 s apart moving east from x = 20, at the given y per step."""
    forward = -1.0 if abs(heading - EAST) > 1 else 1.0
    start = 280.0 if forward < 0 else 20.0
    return [
        TracePoint(step=i, x=start + forward * speed * 0.1 * i, y=y, heading=heading, speed=speed)
        for i, y in enumerate(lateral)
    ]


def test_one_held_move_is_one_lane_change_to_the_left(straight_network: object) -> None:
    reading = read_lanes(straight_network, _drive([-5.25] * 20 + [-1.75] * 30))
    assert [(c.side, c.into_opposite) for c in reading.changes] == [(Side.LEFT, False)]
    assert reading.same_direction_changes == 1 and reading.opposite_steps == 0


def test_a_blip_across_the_line_shorter_than_the_hold_is_no_change(
    straight_network: object,
) -> None:
    reading = read_lanes(straight_network, _drive([-1.75] * 20 + [-5.0, -5.0] + [-1.75] * 20))
    assert reading.changes == []


def test_bypass_through_the_oncoming_lane_is_read_as_out_and_back(
    straight_network: object,
) -> None:
    lateral = [-1.75] * 20 + [1.75] * 30 + [-1.75] * 20
    reading = read_lanes(straight_network, _drive(lateral))
    assert [(c.side, c.into_opposite, c.from_opposite) for c in reading.changes] == [
        (Side.LEFT, True, False),
        (Side.RIGHT, False, True),
    ]
    assert reading.same_direction_changes == 0
    assert 28 <= reading.opposite_steps <= 32


def test_a_car_driving_its_own_westbound_lane_is_not_against_traffic(
    straight_network: object,
) -> None:
    reading = read_lanes(straight_network, _drive([1.75] * 40, heading=math.pi / 2))
    assert reading.changes == [] and reading.opposite_steps == 0


def test_weaving_is_a_move_undone_within_a_second_and_a_half() -> None:
    def change(step: int, side: Side) -> LaneChange:
        return LaneChange(step=step, side=side)

    assert find_weaving([change(10, Side.LEFT), change(22, Side.RIGHT)], 0.1)
    assert not find_weaving([change(10, Side.LEFT), change(60, Side.RIGHT)], 0.1)
    assert not find_weaving([change(10, Side.LEFT), change(14, Side.LEFT)], 0.1)
    assert not find_weaving([], 0.1)
