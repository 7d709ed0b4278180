"""Our generated OpenDRIVE maps: they rebuild identically, Scenic parses them,
they have the features maps.json advertises, and CARLA-style scenes that need
those features compile and sample on them."""

from __future__ import annotations

import json
import math
import os
import shutil
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("scenariogeneration")

import scenic  # noqa: E402
from scenic.domains.driving.roads import ManeuverType, Network  # noqa: E402

from arise.maps import features, generate  # noqa: E402

DATA = Path(generate.__file__).with_name("data")
CATALOGUE: list[dict[str, Any]] = json.loads((DATA / "maps.json").read_text())
NAMES = [entry["name"] for entry in CATALOGUE]


@pytest.fixture(scope="module")
def regenerated(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The maps built afresh by the generator."""
    out = tmp_path_factory.mktemp("regenerated")
    generate.generate(out)
    return out


@pytest.fixture(scope="module")
def shipped(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A copy of the shipped maps: Scenic writes a .snet cache next to a map."""
    out = tmp_path_factory.mktemp("shipped")
    for entry in CATALOGUE:
        shutil.copyfile(DATA / entry["file"], out / entry["file"])
    return out


@pytest.fixture(scope="module")
def networks(regenerated: Path) -> dict[str, Network]:
    return {name: features.load_network(regenerated / f"{name}.xodr") for name in NAMES}


def test_catalogue_matches_generator() -> None:
    assert NAMES == [
        "arise_straight",
        "arise_intersection4",
        "arise_tjunction",
        "arise_highway",
        "arise_merge",
    ]
    assert generate.catalogue() == CATALOGUE
    for entry in CATALOGUE:
        assert set(entry) == {
            "name",
            "file",
            "description",
            "features",
            "lanes_per_direction",
            "has_sidewalks",
            "signalized",
        }
        assert set(entry["features"]) <= set(features.FEATURES)
        assert ("sidewalk" in entry["features"]) == entry["has_sidewalks"]
        assert ("signalized" in entry["features"]) == entry["signalized"]


def test_regeneration_is_reproducible(regenerated: Path) -> None:
    """The committed files are exactly what the generator writes."""
    for entry in CATALOGUE:
        assert (regenerated / entry["file"]).read_bytes() == (DATA / entry["file"]).read_bytes()
    assert (regenerated / "maps.json").read_text() == (DATA / "maps.json").read_text()


def test_generating_twice_in_one_process_keeps_signal_ids(tmp_path: Path) -> None:
    """scenariogeneration numbers signals process-wide; we reset it per map."""
    generate.generate(tmp_path, ["arise_intersection4"])
    assert (tmp_path / "arise_intersection4.xodr").read_bytes() == (
        DATA / "arise_intersection4.xodr"
    ).read_bytes()


def test_cli_writes_maps(tmp_path: Path) -> None:
    assert generate.main([str(tmp_path), "--map", "arise_straight"]) == 0
    assert (tmp_path / "arise_straight.xodr").is_file()
    assert json.loads((tmp_path / "maps.json").read_text())[0]["name"] == "arise_straight"


@pytest.mark.parametrize("name", NAMES)
def test_measured_features_match_catalogue(regenerated: Path, name: str) -> None:
    entry = next(e for e in CATALOGUE if e["name"] == name)
    measured = features.measure_features(regenerated / entry["file"])
    assert measured["features"] == entry["features"]
    assert measured["lanes_per_direction"] == entry["lanes_per_direction"]
    assert measured["has_sidewalks"] == entry["has_sidewalks"]
    assert measured["signalized"] == entry["signalized"]


def test_intersection4_has_all_maneuvers_and_traffic_lights(networks: dict[str, Network]) -> None:
    network = networks["arise_intersection4"]
    assert len(network.intersections) == 1
    intersection = network.intersections[0]
    assert len(intersection.roads) == 4
    kinds = [m.type for m in intersection.maneuvers]
    # From each of 4 approaches: 2 straight lanes, 1 left turn, 1 right turn.
    assert kinds.count(ManeuverType.STRAIGHT) == 8
    assert kinds.count(ManeuverType.LEFT_TURN) == 4
    assert kinds.count(ManeuverType.RIGHT_TURN) == 4
    assert len(intersection.incomingLanes) == 8
    for lane in intersection.incomingLanes:
        assert lane.maneuvers, lane
        # Inner lane: straight + left; outer lane: straight + right.
        assert {m.type for m in lane.maneuvers} in (
            {ManeuverType.STRAIGHT, ManeuverType.LEFT_TURN},
            {ManeuverType.STRAIGHT, ManeuverType.RIGHT_TURN},
        )
        for maneuver in lane.maneuvers:
            assert maneuver.connectingLane.predecessor is lane
            assert maneuver.connectingLane.successor is maneuver.endLane
    assert len(intersection.signals) == 4
    assert all(signal.isTrafficLight for signal in intersection.signals)
    assert len(features.junction_arms(intersection)) == 4


def test_tjunction_has_turns_and_a_stop_sign(networks: dict[str, Network]) -> None:
    network = networks["arise_tjunction"]
    (intersection,) = network.intersections
    kinds = sorted(m.type.name for m in intersection.maneuvers)
    assert kinds == ["LEFT_TURN", "LEFT_TURN", "RIGHT_TURN", "RIGHT_TURN", "STRAIGHT", "STRAIGHT"]
    assert [s.type for s in intersection.signals] == [generate.STOP_SIGN_TYPE]
    assert len(features.junction_arms(intersection)) == 3


def test_straight_and_highway_lanes(networks: dict[str, Network]) -> None:
    straight = networks["arise_straight"]
    (road,) = straight.roads
    assert len(road.forwardLanes.lanes) == len(road.backwardLanes.lanes) == 2
    assert len(straight.sidewalks) == 2 and len(straight.shoulders) == 2
    assert features.road_length(road) == pytest.approx(300, abs=0.5)

    highway = networks["arise_highway"]
    (road,) = highway.roads
    assert len(road.forwardLanes.lanes) == len(road.backwardLanes.lanes) == 4
    assert highway.sidewalks == ()
    assert features.road_length(road) == pytest.approx(525, abs=1)
    assert features.total_turn(road) == pytest.approx(math.degrees(175 / 500), abs=1)


def test_merge_ramp_joins_the_rightmost_lane(networks: dict[str, Network]) -> None:
    network = networks["arise_merge"]
    (zone,) = network.intersections
    assert features.classify_intersection(zone) == "other"
    ((ramp, through),) = features.on_ramp_merges(zone)
    assert len(ramp.startLane.group.lanes) == 1
    assert len(through.startLane.group.lanes) == generate.MERGE_LANES
    # The lane both maneuvers end in is the motorway's rightmost (curb-side) lane.
    assert ramp.endLane is through.endLane is through.endLane.group.lanes[0]
    assert ramp.endLane.sections[0]._laneToRight is None
    # Scenic links ramp -> connecting lane -> motorway lane, and calls it straight,
    # so FollowLaneBehavior keeps its speed through the merge zone.
    assert ramp.type is ManeuverType.STRAIGHT
    assert ramp.startLane.maneuvers == (ramp,)
    assert ramp.connectingLane.predecessor is ramp.startLane
    assert ramp.connectingLane.successor is ramp.endLane
    # The lanes line up: each connecting lane starts where its lane ends and ends where
    # the next one starts (within the polyline's sampling).
    for maneuver in zone.maneuvers:
        lane = maneuver.connectingLane
        assert (maneuver.startLane.centerline[-1] - lane.centerline[0]).norm() < 0.05
        assert (lane.centerline[-1] - maneuver.endLane.centerline[0]).norm() < 0.05
    # Where the ramp runs beside the motorway, the point is on the ramp lane, and the
    # direction of travel there is the motorway's.
    beside = ramp.connectingLane.centerline.pointAlongBy(generate.MERGE_PARALLEL / 2)
    assert network.laneAt(beside) is ramp.connectingLane
    assert network.nominalDirectionsAt(beside)[0] == pytest.approx(
        network.nominalDirectionsAt(through.startLane.centerline[-1])[0], abs=0.02
    )


def test_merge_map_traffic_follows_the_ramp_into_the_motorway(shipped: Path) -> None:
    """FollowLaneBehavior from the ramp, in Scenic's Newtonian simulator, ends up in the
    motorway's rightmost lane at speed."""
    from scenic.simulators.newtonian import NewtonianSimulator

    path = shipped / "ramp_follow.scenic"
    path.write_text(
        "param map = localPath('arise_merge.xodr')\n"
        "param render = 0\n"
        "model scenic.simulators.newtonian.driving_model\n"
        "rampLane = [lane for lane in network.lanes if len(lane.group.lanes) == 1][0]\n"
        "ego = new Car at rampLane.centerline.pointAlongBy(60), "
        "with behavior FollowLaneBehavior(target_speed=15)\n"
    )
    scenario = scenic.scenarioFromFile(str(path), mode2D=True)
    scene, _ = scenario.generate(maxIterations=20)
    network = scene.workspace.network
    result = NewtonianSimulator().simulate(scene, maxSteps=200, maxIterations=1)
    assert result is not None
    positions = [state[0] for state in result.trajectory]
    start, end = network.laneAt(positions[0]), network.laneAt(positions[-1])
    (ramp, through) = features.on_ramp_merges(network.intersections[0])[0]
    assert start is ramp.startLane
    assert end is through.endLane
    # 20 s at up to 15 m/s; slowing to a turning speed through the zone would lose ~40 m.
    assert positions[-1].x - positions[0].x > 220


# CARLA-style scenes. The model line and params are the CARLA ones; the test
# compiles them against Scenic's generic driving model (map content only).
HEADER = """\
param map = localPath('{name}.xodr')
param carla_map = '{name}'
model scenic.simulators.carla.model
"""

SCENES = {
    "arise_straight": """
lane = Uniform(*network.lanes)
ego = new Car on lane.centerline
lead = new Car following roadDirection from ego for Range(10, 25)
# A lane change must be possible: there is a lane beside ego going the same way.
beside = new Car on ego.laneSection.fasterLane.centerline
require (distance from ego to beside) > 6
walker = new Pedestrian on sidewalk
""",
    "arise_intersection4": """
intersection = network.intersections[0]
require len(intersection.signals) > 0
leftTurns = filter(lambda m: m.type is ManeuverType.LEFT_TURN, intersection.maneuvers)
maneuver = Uniform(*leftTurns)
# Start a few metres before the stop line, whichever lane it is.
ego = new Car following roadDirection from maneuver.startLane.centerline[-1] for Range(-25, -6)
oncoming = Uniform(*filter(lambda m: m.type is ManeuverType.STRAIGHT,
                           maneuver.conflictingManeuvers))
other = new Car following roadDirection from oncoming.startLane.centerline[-1] for Range(-30, -6)
walker = new Pedestrian on sidewalk
""",
    "arise_tjunction": """
intersection = network.intersections[0]
rightTurns = filter(lambda m: m.type is ManeuverType.RIGHT_TURN, intersection.maneuvers)
maneuver = Uniform(*rightTurns)
ego = new Car following roadDirection from maneuver.startLane.centerline[-1] for Range(-20, -6)
crossing = new Car following roadDirection from maneuver.endLane.centerline[0] for Range(8, 30)
walker = new Pedestrian on sidewalk
""",
    "arise_highway": """
lane = Uniform(*network.lanes)
ego = new Car on lane.centerline
require len(ego.laneGroup.lanes) == 4
left = new Car on ego.laneSection.fasterLane.centerline
right = new Car on ego.laneSection.slowerLane.centerline
require (distance from ego to left) > 6 and (distance from ego to right) > 6
lead = new Car following roadDirection from ego for Range(15, 40)
""",
    "arise_merge": """
zone = network.intersections[0]
ramp = Uniform(*[m for m in zone.maneuvers if len(m.startLane.group.lanes) == 1])
ego = new Car following roadDirection from ramp.startLane.centerline[-1] for Range(-60, -20)
through = new Car on ramp.endLane.centerline
""",
}


def _sample(shipped: Path, name: str) -> Any:
    path = shipped / f"{name}_scene.scenic"
    path.write_text(HEADER.format(name=name) + SCENES[name])
    scenario = scenic.scenarioFromFile(
        str(path),
        params={"map": str(shipped / f"{name}.xodr"), "carla_map": name},
        model="scenic.domains.driving.model",
        mode2D=True,
    )
    scene, _ = scenario.generate(maxIterations=200)
    return scene


@pytest.mark.parametrize("name", NAMES)
def test_feature_scene_samples(shipped: Path, name: str) -> None:
    scene = _sample(shipped, name)
    network = scene.workspace.network
    ego = scene.egoObject
    assert network.laneAt(ego.position) is not None
    walkers = [o for o in scene.objects if type(o).__name__ == "Pedestrian"]
    if name in ("arise_highway", "arise_merge"):
        assert not walkers
    else:
        assert len(walkers) == 1
        assert network.sidewalkRegion.containsPoint(walkers[0].position)
    turn = {"arise_intersection4": "LEFT_TURN", "arise_tjunction": "RIGHT_TURN"}.get(name)
    if turn:
        assert ego.lane in network.intersections[0].incomingLanes
        assert turn in {m.type.name for m in ego.lane.maneuvers}
        assert 5.5 <= network.intersections[0].distanceTo(ego.position) <= 25.5


CARLA_DIR = Path(os.environ.get("ARISE_CARLA_MAPS", features.DEFAULT_CARLA_DIR))


def test_carla_towns_catalogue() -> None:
    towns = {e["name"]: e for e in json.loads((DATA / "carla_towns.json").read_text())}
    assert set(towns) == set(features.CARLA_TOWNS)
    for name in ("Town03", "Town05"):
        assert towns[name]["available"] is False
        assert "intersection4" in towns[name]["features"]
    assert "roundabout" in towns["Town03"]["features"]
    assert "highway" in towns["Town05"]["features"]
    for entry in towns.values():
        assert set(entry["features"]) <= set(features.FEATURES)
        assert entry["file"] == f"{entry['name']}.xodr"
    assert "highway" in towns["Town04"]["features"]
    assert towns["Town01"]["lanes_per_direction"] == 1
    # Town04 and Town06 have on-ramps, as our arise_merge has; the town maps do not.
    for name in ("Town04", "Town06"):
        assert "merge" in towns[name]["features"]
        assert towns[name]["stats"]["on_ramp_merges"] >= 3
    assert not {"merge"} & set(towns["Town01"]["features"] + towns["Town10HD"]["features"])


@pytest.mark.carla_towns
@pytest.mark.skipif(not (CARLA_DIR / "Town02.xodr").is_file(), reason="no CARLA towns here")
def test_carla_town_measure_is_current(tmp_path: Path) -> None:
    """Re-measure the smallest town; carla_towns.json must agree."""
    towns = {e["name"]: e for e in json.loads((DATA / "carla_towns.json").read_text())}
    copy = tmp_path / "Town02.xodr"
    shutil.copyfile(CARLA_DIR / "Town02.xodr", copy)
    measured = features.measure_features(copy)
    for key in ("features", "lanes_per_direction", "has_sidewalks", "signalized"):
        assert measured[key] == towns["Town02"][key]
