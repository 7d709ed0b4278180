"""Lane invasions and out-of-road distance on our real maps, from traces drawn by hand.

`arise_straight`: one road along x from 0 to 300, two lanes each way, eastbound lanes
centred at y = -1.75 and -5.25, westbound at +1.75 and +5.25; the drivable area ends at
y = +-7. `arise_intersection4`: a four-way junction filling |x|, |y| <= 14, with the same
lanes on its arms (eastbound at y = -1.75, -5.25).
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from arise.agents.types import LightState, SignalKind, SignalTrace
from arise.drive.metrics import DrivingMetrics, LaneRef, ScenicRoad, compute_metrics
from arise.drive.metrics_road import lane_invasions, out_of_road_length
from arise.errors import AriseError
from arise.maps.registry import MapRegistry, cached_copy
from tests.drive.test_metrics import DT, EAST, NORTH, Pose, car, facts


def _shipped(name: str) -> Path:
    path = MapRegistry().entries[name].path
    assert path is not None
    return Path(path)


def _road(name: str) -> ScenicRoad:
    return ScenicRoad.from_map(cached_copy(_shipped(name)))


@pytest.fixture(scope="module")
def straight() -> ScenicRoad:
    return _road("arise_straight")


@pytest.fixture(scope="module")
def crossroads() -> ScenicRoad:
    return _road("arise_intersection4")


def east(x0: float, lateral: list[float], step_m: float = 1.0) -> list[Pose]:
    """Poses moving east `step_m` per step from x0, at the given y per step."""
    return [(x0 + step_m * i, y, EAST) for i, y in enumerate(lateral)]


def drive(road: ScenicRoad, poses: list[Pose], y_route: float = -1.75) -> DrivingMetrics:
    route = ((poses[0][0], y_route), (poses[0][0] + 400.0, y_route))
    got = compute_metrics(facts([car("ego", poses, ego=True)], route=route), road, timeout_s=60)
    assert got.road_checked
    return got


def glide(start: float, end: float, steps: int) -> list[float]:
    return [start + (end - start) * (i + 1) / steps for i in range(steps)]


def test_the_network_answers_the_point_queries(straight: ScenicRoad) -> None:
    assert straight.lane_at(50, -1.75) == straight.lane_at(250, -1.75)
    assert straight.lane_at(50, -1.75) != straight.lane_at(50, -5.25)
    assert isinstance(straight.lane_at(50, 1.75), LaneRef)
    assert straight.lane_at(50, -9) is None
    assert straight.on_drivable(50, -6.9) and not straight.on_drivable(50, -7.1)
    assert not straight.in_junction(50, -1.75)


def test_keeping_a_lane_invades_nothing_and_stays_on_the_road(straight: ScenicRoad) -> None:
    got = drive(straight, east(20, [-1.75] * 100))
    assert got.lane_invasions == 0 and got.out_of_road_m == 0


def test_one_lane_change_is_one_invasion(straight: ScenicRoad) -> None:
    got = drive(straight, east(20, [-5.25] * 20 + glide(-5.25, -1.75, 10) + [-1.75] * 30))
    assert got.lane_invasions == 1 and got.out_of_road_m == 0


def test_out_into_the_oncoming_lane_and_back_is_two(straight: ScenicRoad) -> None:
    lateral = [-1.75] * 20 + glide(-1.75, 1.75, 6) + [1.75] * 30 + glide(1.75, -1.75, 6)
    got = drive(straight, east(20, lateral + [-1.75] * 20))
    assert got.lane_invasions == 2


def test_across_the_whole_road_is_three_boundaries(straight: ScenicRoad) -> None:
    lateral = [-5.25] * 10 + glide(-5.25, 5.25, 30) + [5.25] * 10
    assert drive(straight, east(20, lateral)).lane_invasions == 3


def test_a_blip_over_the_line_shorter_than_the_hold_is_no_invasion(straight: ScenicRoad) -> None:
    # 0.2 s over the line (two steps) is shorter than the 0.3 s a crossing must hold.
    lateral = [-1.75] * 20 + [-3.6, -3.6] + [-1.75] * 20
    assert drive(straight, east(20, lateral)).lane_invasions == 0


def test_leaving_the_road_counts_the_metres_driven_off_it(straight: ScenicRoad) -> None:
    # On the road to x = 50 (y = -6 there, midpoint -5.6: on it); the next move to
    # (51, -9) has its midpoint at y = -7.5, off the road: sqrt(1 + 9) m; then 29 m at
    # y = -9 to x = 80.
    poses = east(20, [-5.25] * 30) + [(50.0, -6.0, EAST), (51.0, -9.0, EAST)]
    poses += [(52.0 + i, -9.0, EAST) for i in range(29)]
    got = drive(straight, poses, y_route=-5.25)
    assert got.out_of_road_m == pytest.approx(29 + 10**0.5, abs=1e-3)
    # the car left its lane for no lane: no invasion, and 3.75 m from its route
    assert got.lane_invasions == 0
    assert got.overall_score < 1


def test_lanes_cross_each_other_in_a_junction_without_an_invasion(crossroads: ScenicRoad) -> None:
    # Straight across, then a lane change inside the junction (|x| < 14).
    straight_on = drive(crossroads, east(-60, [-1.75] * 120))
    assert straight_on.lane_invasions == 0 and straight_on.out_of_road_m == 0
    inside = [-1.75] * 55 + glide(-1.75, -5.25, 10) + [-5.25] * 55  # x from -5 to 5
    assert drive(crossroads, east(-60, inside)).lane_invasions == 0
    # the same change on the far arm (x from 35 to 45) is one
    outside = [-1.75] * 95 + glide(-1.75, -5.25, 10) + [-5.25] * 15
    assert drive(crossroads, east(-60, outside)).lane_invasions == 1


def test_the_helpers_work_on_any_road_queries(straight: ScenicRoad) -> None:
    xs = [20.0 + i for i in range(50)]
    assert lane_invasions(straight, xs, [-1.75] * 50, DT) == 0
    assert out_of_road_length(straight, xs, [-20.0] * 50) == pytest.approx(49.0)


def test_a_map_outside_the_cache_is_parsed_and_its_pickle_never_read(tmp_path: Path) -> None:
    # A run folder may hold a `.snet` beside a map: loading it would unpickle it.
    source = _shipped("arise_straight")
    copy = tmp_path / "arise_straight.xodr"
    shutil.copyfile(source, copy)
    copy.with_suffix(".snet").write_bytes(b"not a pickle: reading it would fail")
    road = ScenicRoad.from_map(copy)
    assert road.lane_at(50, -1.75) is not None


def test_a_file_that_is_no_map_is_one_clear_error(tmp_path: Path) -> None:
    planted = tmp_path / "map.snet"
    planted.write_bytes(b"\x80\x04")
    with pytest.raises(AriseError, match="not an OpenDRIVE map"):
        ScenicRoad.from_map(planted)
    broken = tmp_path / "broken.xodr"
    broken.write_text("<OpenDRIVE><road>")
    with pytest.raises(AriseError, match="cannot read the road network"):
        ScenicRoad.from_map(broken)


def test_the_point_queries_agree_with_scenic_s_own(crossroads: ScenicRoad) -> None:
    from arise.render.outline import load_network

    network = load_network(cached_copy(_shipped("arise_intersection4")))
    points = [(x * 1.3 - 30.0, y * 1.7 - 20.0) for x in range(47) for y in range(25)]
    lanes, junctions = 0, 0
    for x, y in points:
        lane = network.laneAt((x, y))
        assert crossroads.lane_at(x, y) == (
            None if lane is None else LaneRef(road=lane.road.uid, lane=lane.uid)
        )
        inside = network.intersectionAt((x, y)) is not None
        assert crossroads.in_junction(x, y) == inside
        assert crossroads.on_drivable(x, y) == network.drivableRegion.containsPoint((x, y))
        lanes += lane is not None
        junctions += inside
    assert lanes > 100 and junctions > 50  # the grid covers arms and the junction


# The northbound entry into the junction: lanes x in [0, 7], the junction from y = -14.
NORTH_ENTRY = ((0.0, -14.0), (7.0, -14.0))  # left edge first: the order says southbound


@pytest.mark.parametrize(
    "ends", [NORTH_ENTRY, NORTH_ENTRY[::-1]], ids=["left-first", "right-first"]
)
def test_the_junction_says_which_way_a_stop_line_stops_traffic(
    crossroads: ScenicRoad, ends: tuple[tuple[float, float], tuple[float, float]]
) -> None:
    light = SignalTrace(
        id="north", kind=SignalKind.TRAFFIC_LIGHT, stop_line=ends, states=[(0, LightState.RED)]
    )
    northbound = [(5.25, -40.0 + i, NORTH) for i in range(60)]
    southbound = [(5.25, 19.0 - i, NORTH + 3.14159) for i in range(60)]  # the wrong way
    for poses, runs in ((northbound, 1), (southbound, 0)):
        route = (poses[0][:2], poses[-1][:2])
        trace = facts([car("ego", poses, ego=True)], route=route, signals=[light])
        assert compute_metrics(trace, crossroads, timeout_s=60).red_lights_run == runs
    # without a network only the order tells: left-first reads as a southbound line
    route = (northbound[0][:2], northbound[-1][:2])
    alone = facts([car("ego", northbound, ego=True)], route=route, signals=[light])
    assert compute_metrics(alone, None, timeout_s=60).red_lights_run == (ends != NORTH_ENTRY)
