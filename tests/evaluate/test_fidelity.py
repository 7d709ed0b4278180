"""Fidelity against hand-written truth: exact verdicts on hand-built traces, the three dev
sets load and validate, and (slow) real scripts on the real validator scored both ways."""

from __future__ import annotations

import math
from collections import Counter
from pathlib import Path

import pytest

from arise.evaluate.fidelity import (
    DEVSET_DIR,
    DEVSET_FILES,
    LABEL_CLASSES,
    DevSet,
    DevsetError,
    FactKind,
    Truth,
    load_devset,
    load_devsets,
    score_fidelity,
)
from arise.validate.facts import ego_pair_facts, find_collisions
from arise.validate.types import AgentTrace, CheckResult, LaneChange, SimulationFacts, TracePoint
from arise.vocabulary import ACTOR_CLASSES, PAPER_CATEGORIES, PROP_CLASSES, Side
from tests.conftest import REPO

# Scenic's frame: heading 0 faces +y, angles grow counter-clockwise, so the ego at the
# origin facing +y has its left at -x and its right at +x.
NORTH, WEST, SOUTH, EAST = 0.0, math.pi / 2, math.pi, -math.pi / 2
STEPS = 30


def straight(
    x0: float, y0: float, x1: float, y1: float, heading: float, steps: int = STEPS
) -> list[TracePoint]:
    """Constant heading from (x0, y0) to (x1, y1)."""
    speed = math.hypot(x1 - x0, y1 - y0) / max(1, steps) * 10
    return [
        TracePoint(
            step=i,
            x=x0 + (x1 - x0) * i / steps,
            y=y0 + (y1 - y0) * i / steps,
            heading=heading,
            speed=speed,
        )
        for i in range(steps + 1)
    ]


def left_turn(steps: int = STEPS) -> list[TracePoint]:
    """From (0, 0) facing north, a quarter circle of radius 15 m to the left (ends west)."""
    points = []
    for i in range(steps + 1):
        angle = (math.pi / 2) * i / steps
        points.append(
            TracePoint(
                step=i,
                x=-15 + 15 * math.cos(angle),
                y=15 * math.sin(angle),
                heading=angle,
                speed=8.0,
            )
        )
    return points


def agent(
    name: str,
    kind: str,
    points: list[TracePoint],
    *,
    ego: bool = False,
    blueprint: str | None = None,
    junction: int = 0,
    lane_changes: int | None = 0,
) -> AgentTrace:
    width, length = {"Pedestrian": (0.5, 0.5), "Bicycle": (0.7, 1.8)}.get(kind, (2.0, 4.5))
    return AgentTrace(
        name=name,
        kind=kind,
        blueprint=blueprint,
        width=width,
        length=length,
        is_ego=ego,
        behavior="FollowLaneBehavior",
        intersection_steps=junction,
        lane_changes=lane_changes,
        trajectory=points,
    )


EGO_STRAIGHT = agent("ego", "Car", straight(0, 0, 0, 40, NORTH), ego=True)


def ran(*agents: AgentTrace, weather: str | None = "ClearNoon") -> CheckResult:
    facts = SimulationFacts(
        steps=STEPS,
        timestep=0.1,
        termination_type="TIME_LIMIT",
        termination_reason="",
        agents=list(agents),
        collisions=find_collisions(list(agents), 0.1),
        ego_pairs=ego_pair_facts(list(agents)),
        params={"weather": weather} if weather else {},
    )
    return CheckResult(ok=True, script="scenario.scenic", simulation=facts)


def truth(**data: object) -> Truth:
    return Truth.from_dict(data)


def facts_of(fidelity) -> dict[str, bool | None]:
    return {v.name: v.match for v in fidelity.verdicts}


# -- exact verdicts on hand-built traces ----------------------------------------------------

CROSSER = agent("Car1", "Car", straight(15, 20, -15, 20, WEST))  # from the right, to the left


def test_a_car_from_the_right_crossing_to_the_left_matches_its_label() -> None:
    label = truth(
        actors=[
            {
                "class": "Car",
                "role": "adversary",
                "start": "right",
                "direction": "crossing_right_to_left",
            }
        ],
        ego_maneuver="straight",
        road="straight",
    )
    fidelity = score_fidelity(label, ran(EGO_STRAIGHT, CROSSER))
    assert facts_of(fidelity) == {
        "actor:Car[0]": True,
        "start:Car[0]": True,
        "direction:Car[0]": True,
        "no_extra_actors": True,
        "ego_maneuver": True,
        "road": True,
        "weather": True,
        "must_come_close": None,
    }
    assert fidelity.score == 1.0 and fidelity.mismatches == []
    start = fidelity.verdict("start:Car[0]")
    assert (
        start.observed == "Car1: 20.0 m ahead, 15.0 m right, facing +90 deg, crossing_right_to_left"
    )


def test_the_same_car_contradicts_a_label_from_the_left() -> None:
    label = truth(actors=[{"class": "Car", "start": "left", "direction": "crossing_left_to_right"}])
    fidelity = score_fidelity(label, ran(EGO_STRAIGHT, CROSSER))
    assert facts_of(fidelity)["start:Car[0]"] is False
    assert facts_of(fidelity)["direction:Car[0]"] is False
    # actor, no extras and weather hold; start and direction do not.
    assert fidelity.score == pytest.approx(3 / 5)


def test_an_extra_parked_car_counts_against_no_extra_actors() -> None:
    walker = agent("Pedestrian1", "Pedestrian", straight(6, 15, 0, 15, WEST))
    parked = agent("Car1", "Car", straight(5, 30, 5, 30, NORTH))
    label = truth(
        actors=[{"class": "Pedestrian", "start": "right", "direction": "crossing_right_to_left"}]
    )
    fidelity = score_fidelity(label, ran(EGO_STRAIGHT, walker, parked))
    extra = fidelity.verdict("no_extra_actors")
    assert (extra.expected, extra.observed, extra.match) == ("none", "Car1 (Car)", False)
    assert facts_of(fidelity)["start:Pedestrian[0]"] is True
    assert fidelity.mismatches == ["no_extra_actors: expected none, observed Car1 (Car)"]


def test_rain_nobody_asked_for_is_a_mismatch() -> None:
    fidelity = score_fidelity(truth(), ran(EGO_STRAIGHT, weather="MidRainyNoon"))
    weather = fidelity.verdict("weather")
    assert (weather.expected, weather.observed, weather.match) == (
        "ClearNoon (not stated)",
        "MidRainyNoon",
        False,
    )


@pytest.mark.parametrize(
    ("stated", "seen", "match"),
    [
        ("MidRainyNoon", "HardRainNoon", True),  # rain is rain: intensity is not judged
        ("SoftRainNight", "MidRainyNoon", False),  # night asked, noon given
        ("ClearSunset", "ClearSunset", True),
        ("CloudyNoon", "ClearNoon", False),
    ],
)
def test_stated_weather_is_compared_by_sky_and_time(stated: str, seen: str, match: bool) -> None:
    fidelity = score_fidelity(truth(weather=stated), ran(EGO_STRAIGHT, weather=seen))
    assert fidelity.verdict("weather").match is match


def test_unreadable_weather_is_not_scored() -> None:
    assert score_fidelity(truth(), ran(EGO_STRAIGHT, weather=None)).verdict("weather").match is None


def test_a_missing_second_actor_fails_its_presence_start_and_direction() -> None:
    lead = agent("Car1", "Car", straight(0, 15, 0, 45, NORTH))
    label = truth(
        actors=[
            {"class": "Car", "role": "lead", "start": "ahead", "direction": "same"},
            {
                "class": "Motorcycle",
                "role": "oncoming",
                "start": "oncoming",
                "direction": "opposite",
            },
        ]
    )
    fidelity = score_fidelity(label, ran(EGO_STRAIGHT, lead))
    assert facts_of(fidelity) == {
        "actor:Car[0]": True,
        "actor:Motorcycle[1]": False,
        "start:Car[0]": True,
        "direction:Car[0]": True,
        "start:Motorcycle[1]": False,
        "direction:Motorcycle[1]": False,
        "no_extra_actors": True,
        "ego_maneuver": None,
        "road": None,
        "weather": True,
        "must_come_close": None,
    }
    assert fidelity.verdict("start:Motorcycle[1]").observed == "absent"
    assert fidelity.score == pytest.approx(5 / 8)


def test_the_ego_turning_when_the_text_says_the_other_car_turns() -> None:
    ego = agent("ego", "Car", left_turn(), ego=True, junction=12)
    oncoming = agent("Car1", "Car", straight(-3.5, 40, -3.5, 0, SOUTH), junction=8)
    label = truth(
        actors=[{"class": "Car", "start": "oncoming", "direction": "turning_left"}],
        ego_maneuver="straight",
        road="intersection",
    )
    fidelity = score_fidelity(label, ran(ego, oncoming))
    maneuver = fidelity.verdict("ego_maneuver")
    assert (maneuver.expected, maneuver.observed, maneuver.match) == (
        "straight",
        "left_turn",
        False,
    )
    direction = fidelity.verdict("direction:Car[0]")
    assert direction.match is False and direction.observed.endswith("opposite")
    assert facts_of(fidelity)["start:Car[0]"] is True
    assert facts_of(fidelity)["road"] is True


def test_two_agents_of_one_class_are_paired_with_labels_the_kindest_way() -> None:
    oncoming = agent("Car1", "Car", straight(-3.5, 40, -3.5, 0, SOUTH))
    behind = agent("Car2", "Car", straight(0, -12, 0, 30, NORTH))
    label = truth(
        actors=[
            {"class": "Car", "start": "behind", "direction": "same"},
            {"class": "Car", "start": "oncoming", "direction": "opposite"},
        ]
    )
    fidelity = score_fidelity(label, ran(EGO_STRAIGHT, oncoming, behind))
    assert fidelity.score == 1.0
    assert fidelity.verdict("start:Car[0]").observed.startswith("Car2:")


def test_counts_are_exact_and_numbered() -> None:
    walkers = [
        agent(f"Pedestrian{i}", "Pedestrian", straight(-8, 15 + i, 0, 15 + i, EAST))
        for i in (1, 2, 3)
    ]
    label = truth(
        actors=[
            {
                "class": "Pedestrian",
                "count": 2,
                "start": "left",
                "direction": "crossing_left_to_right",
            }
        ]
    )
    fidelity = score_fidelity(label, ran(EGO_STRAIGHT, *walkers))
    verdicts = facts_of(fidelity)
    assert verdicts["actor:Pedestrian[0]"] is True
    assert verdicts["start:Pedestrian[0]#1"] and verdicts["start:Pedestrian[0]#2"]
    assert fidelity.verdict("no_extra_actors").observed == "Pedestrian3 (Pedestrian)"


def test_a_car_with_a_truck_blueprint_is_a_truck_and_a_bus_stop_is_not_a_bus() -> None:
    truck = agent(
        "Car1", "Car", straight(3.5, 20, 3.5, 40, NORTH), blueprint="vehicle.carlamotors.firetruck"
    )
    stop = agent("BusStop1", "BusStop", straight(7, 25, 7, 25, NORTH))
    label = truth(
        actors=[{"class": "Truck", "start": "right_front", "direction": "same"}],
        required_objects=["BusStop"],
    )
    fidelity = score_fidelity(label, ran(EGO_STRAIGHT, truck, stop))
    verdicts = facts_of(fidelity)
    assert verdicts["actor:Truck[0]"] and verdicts["start:Truck[0]"]
    assert verdicts["required_object:BusStop"] is True
    assert verdicts["no_extra_actors"] is True  # the named bus stop is no extra
    bus = score_fidelity(
        truth(actors=[{"class": "Bus"}], required_objects=["BusStop"]),
        ran(EGO_STRAIGHT, agent("Bus1", "Bus", straight(7, 25, 7, 25, NORTH))),
    )
    assert facts_of(bus)["required_object:BusStop"] is False


def test_must_come_close_reads_the_closest_approach() -> None:
    label = truth(actors=[{"class": "Pedestrian"}], must_come_close=True)
    hit = agent("Pedestrian1", "Pedestrian", straight(5, 20, -5, 20, WEST))
    near = agent("Pedestrian1", "Pedestrian", straight(1.75, 20, 1.75, 20, WEST))  # 0.5 m gap
    far = agent("Pedestrian1", "Pedestrian", straight(30, 20, 20, 20, WEST))
    assert (
        score_fidelity(label, ran(EGO_STRAIGHT, hit)).verdict("must_come_close").observed
        == "collision with Pedestrian1"
    )
    assert facts_of(score_fidelity(label, ran(EGO_STRAIGHT, hit)))["must_come_close"] is True
    close = score_fidelity(label, ran(EGO_STRAIGHT, near)).verdict("must_come_close")
    assert close.match is True and close.observed == "0.5 m from Pedestrian1"
    assert facts_of(score_fidelity(label, ran(EGO_STRAIGHT, far)))["must_come_close"] is False
    assert facts_of(score_fidelity(label, ran(EGO_STRAIGHT)))["must_come_close"] is False


@pytest.mark.parametrize(
    ("road", "ego_steps", "features", "match"),
    [
        ("straight", 0, None, True),
        ("straight", 10, None, False),
        ("intersection", 10, None, True),
        ("intersection", 10, {"straight", "tjunction"}, False),
        ("t_junction", 10, {"straight", "tjunction"}, True),
        ("highway", 0, None, None),
        ("highway", 0, {"straight", "multilane", "highway"}, True),
        ("highway", 0, {"straight", "multilane", "sidewalk"}, False),
        ("multilane", 0, {"straight", "multilane"}, True),
        ("multilane", 0, {"straight", "tjunction"}, False),
    ],
)
def test_road_type_from_junction_steps_and_map_features(
    road: str, ego_steps: int, features: set[str] | None, match: bool | None
) -> None:
    ego = agent("ego", "Car", straight(0, 0, 0, 40, NORTH), ego=True, junction=ego_steps)
    fidelity = score_fidelity(truth(road=road), ran(ego), features)
    assert fidelity.verdict("road").match is match


def test_map_feature_objects_need_the_map() -> None:
    label = truth(required_objects=["signalized"])
    assert facts_of(score_fidelity(label, ran(EGO_STRAIGHT)))["required_object:signalized"] is None
    signalized = score_fidelity(label, ran(EGO_STRAIGHT), {"intersection4", "signalized"})
    assert facts_of(signalized)["required_object:signalized"] is True
    assert (
        facts_of(score_fidelity(label, ran(EGO_STRAIGHT), {"tjunction"}))[
            "required_object:signalized"
        ]
        is False
    )


@pytest.mark.parametrize(
    ("points", "lane_changes", "maneuver"),
    [
        (straight(0, 0, 0, 0.5, NORTH), 0, "stopped"),
        (straight(0, 0, -3.5, 40, NORTH), 1, "lane_change_left"),
        (straight(0, 0, 3.5, 40, NORTH), 1, "lane_change_right"),
        (left_turn(), 0, "left_turn"),
        (straight(0, 0, 0, 40, NORTH), 0, "straight"),
    ],
)
def test_ego_maneuver_from_the_trace(
    points: list[TracePoint], lane_changes: int, maneuver: str
) -> None:
    ego = agent("ego", "Car", points, ego=True, lane_changes=lane_changes)
    assert score_fidelity(truth(), ran(ego)).verdict("ego_maneuver").observed == maneuver


def test_the_lane_change_side_is_the_road_networks_not_a_curves_drift() -> None:
    # drifting 6 m to the right (a right-hand curve) while the road network saw one change
    # into the lane on the left
    ego = agent("ego", "Car", straight(0, 0, 6.0, 40, NORTH), ego=True, lane_changes=1)
    ego.lane_change_log = [LaneChange(step=20, side=Side.LEFT)]
    assert score_fidelity(truth(), ran(ego)).verdict("ego_maneuver").observed == (
        "lane_change_left"
    )


def test_a_run_that_did_not_execute_has_no_score() -> None:
    failed = CheckResult(ok=False, script="scenario.scenic")
    fidelity = score_fidelity(truth(weather="ClearNoon"), failed)
    assert not fidelity.executed and fidelity.score is None
    assert fidelity.as_dict() == {
        "executed": False,
        "score": None,
        "matched": 0,
        "scored": 0,
        "mismatches": [],
        "by_fact": {},
        "verdicts": [],
    }


def test_as_dict_groups_scored_facts_by_kind() -> None:
    label = truth(actors=[{"class": "Car", "start": "left", "direction": "same"}])
    report = score_fidelity(label, ran(EGO_STRAIGHT, CROSSER)).as_dict()
    assert report["by_fact"][FactKind.START.value] == {"matched": 0, "scored": 1}
    assert report["by_fact"]["weather"] == {"matched": 1, "scored": 1}
    assert report["scored"] == 5 and report["matched"] == 3
    assert {"fact", "subject", "expected", "observed", "match"} == set(report["verdicts"][0])


# -- the dev sets ---------------------------------------------------------------------------


def test_the_dev_sets_load_and_validate() -> None:
    sets = load_devsets()
    counts = {dev_set: len(items) for dev_set, items in sets.items()}
    assert counts == {
        DevSet.SHORT: 37,
        DevSet.NHTSA: 23,
        DevSet.CRASH_REPORT: 20,
        DevSet.STYLES: 24,
        DevSet.VARIANTS: 36,
        DevSet.FRESH: 36,
        DevSet.FRESH2: 36,
        DevSet.FRESH3: 42,
        DevSet.FRESH4: 36,
        DevSet.FRESH5: 40,
        DevSet.FRESH6: 40,
        DevSet.FRESH7: 40,
        DevSet.FRESH8: 24,
        DevSet.PLACEMENT: 20,
    }
    assert sum(counts.values()) >= 66
    everything = [item for items in sets.values() for item in items]
    assert len({item.id for item in everything}) == len(everything)
    for dev_set, items in sets.items():
        assert {item.set for item in items} == {dev_set}
    classes = {actor.cls for item in everything for actor in item.truth.actors}
    assert classes <= set(LABEL_CLASSES)
    assert {"Car", "Truck", "Motorcycle", "Bicycle", "Pedestrian"} <= classes
    assert set(ACTOR_CLASSES) & classes and set(PROP_CLASSES) & classes


def test_the_held_apart_set_loads_and_covers_the_eight_categories() -> None:
    items = load_devset(REPO / "tests" / "heldapart" / "heldapart.jsonl")
    assert len(items) == 40 and {item.set for item in items} == {DevSet.HELDAPART}
    assert set(Counter(item.category for item in items).values()) == {5}
    assert set(Counter(item.category for item in items)) == set(PAPER_CATEGORIES)


def test_the_short_set_covers_the_papers_eight_categories_and_rarely_states_weather() -> None:
    short = load_devset(DEVSET_DIR / DEVSET_FILES[DevSet.SHORT])
    categories = Counter(item.category for item in short)
    assert set(categories) == set(PAPER_CATEGORIES)
    assert min(categories.values()) >= 4
    assert sum(item.truth.weather is not None for item in short) < len(short) / 4
    sides = {actor.start for item in short for actor in item.truth.actors}
    assert {"left", "right", "ahead", "oncoming", "behind"} <= {s.value for s in sides if s}


def test_a_bad_dev_set_names_every_bad_line(tmp_path: Path) -> None:
    good = (
        '{"id": "a", "set": "short", "category": "c", "text": "t", "truth": '
        '{"actors": [{"class": "Car"}]}}'
    )
    bad_lines = [
        good,
        '{"id": "b", "set": "short", "category": "c", "text": "t", "truth": '
        '{"actors": [{"class": "Lorry", "start": "north"}]}}',
        '{"id": "c", "set": "tweets", "category": "c", "text": "t", "truth": '
        '{"weather": "Drizzle", "required_objects": ["Bench", "crosswalk"]}}',
        "not json",
        good,
    ]
    path = tmp_path / "bad.jsonl"
    path.write_text("\n".join(bad_lines) + "\n", encoding="utf-8")
    with pytest.raises(DevsetError) as caught:
        load_devset(path)
    message = str(caught.value)
    assert "bad.jsonl:2: actors[0].class: unknown class 'Lorry'" in message
    assert "bad.jsonl:2: actors[0].start: unknown start 'north'" in message
    assert "bad.jsonl:3: set: unknown set 'tweets'" in message
    assert "bad.jsonl:3: weather: unknown weather preset 'Drizzle'" in message
    assert "bad.jsonl:3: required_objects: unknown prop or map feature 'crosswalk'" in message
    assert "bad.jsonl:4: not JSON" in message
    assert "bad.jsonl:5: id: 'a' appears twice" in message
    assert "'Bench'" not in message and ":1:" not in message


def test_truth_from_dict_rejects_unknown_keys_and_false_closeness() -> None:
    with pytest.raises(DevsetError, match="unknown key 'wether'"):
        Truth.from_dict({"wether": "ClearNoon"})
    with pytest.raises(DevsetError, match="must_come_close: only true or null"):
        Truth.from_dict({"must_come_close": False})


# -- real scripts on the real validator -----------------------------------------------------

HEADER = """model scenic.simulators.carla.model
Town = '{town}'
param map = localPath(f'maps/{{Town}}.xodr')
param carla_map = Town
param weather = 'ClearNoon'
"""

# A pedestrian 20 m ahead and 4 m to one side of the ego's lane crosses it; SIDE and FACING
# say which side it starts on and which way it faces.
CROSSING = (
    HEADER.format(town="arise_straight")
    + """
behavior Cross():
    do CrossingBehavior(ego, 1.5, 25) until (distance from self to ego) < 4
    while True:
        take SetWalkingSpeedAction(0)
egoLane = Uniform(*network.lanes)
start = new OrientedPoint on egoLane.centerline
ego = new Car at start, with behavior FollowLaneBehavior(target_speed=8)
spot = new OrientedPoint following roadDirection from start for 20
walker = new Pedestrian SIDE of spot by 4, facing FACING deg relative to spot.heading, with regionContainedIn None, with behavior Cross()
require spot in egoLane
terminate when (distance to start) > 40
"""
)

LEFT_TURN = (
    HEADER.format(town="arise_intersection4")
    + """
turns = [m for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.LEFT_TURN]
turn = Uniform(*turns)
route = [turn.startLane, turn.connectingLane, turn.endLane]
start = new OrientedPoint in turn.startLane.centerline
ego = new Car at start, with behavior FollowTrajectoryBehavior(target_speed=6, trajectory=route)
require 8 <= (distance from ego to intersection) <= 20
terminate when (distance to start) > 45
"""
)

FROM_THE_RIGHT = {
    "actors": [
        {
            "class": "Pedestrian",
            "role": "adversary",
            "start": "right",
            "direction": "crossing_right_to_left",
        }
    ],
    "ego_maneuver": "straight",
    "road": "straight",
    "weather": None,
    "required_objects": ["sidewalk"],
}


def _run(script: str, name: str, tmp_path: Path, pool) -> tuple[CheckResult, frozenset[str]]:
    from arise.maps.registry import MapRegistry
    from arise.validate import CheckOptions, check

    path = tmp_path / name
    path.write_text(script, encoding="utf-8")
    result = check(path, CheckOptions(seed=3, steps=150), pool=pool)
    assert result.ok, result.summary()
    assert result.map is not None
    return result, MapRegistry().entries[result.map.name].features


@pytest.mark.slow
def test_real_scripts_score_against_hand_written_truth(tmp_path: Path, validator_pool) -> None:
    right = CROSSING.replace("SIDE", "right").replace("FACING", "90")
    left = CROSSING.replace("SIDE", "left").replace("FACING", "-90")
    label = Truth.from_dict(FROM_THE_RIGHT)

    result, features = _run(right, "from_right.scenic", tmp_path, validator_pool)
    matches = score_fidelity(label, result, features)
    assert matches.mismatches == [] and matches.score == 1.0, matches.as_dict()
    assert {v.name for v in matches.scored} >= {
        "actor:Pedestrian[0]",
        "start:Pedestrian[0]",
        "direction:Pedestrian[0]",
        "no_extra_actors",
        "ego_maneuver",
        "road",
        "weather",
        "required_object:sidewalk",
    }

    result, features = _run(left, "from_left.scenic", tmp_path, validator_pool)
    wrong_side = score_fidelity(label, result, features)
    assert [m.split(":")[0] + ":" + m.split(":")[1] for m in wrong_side.mismatches] == [
        "start:Pedestrian[0]",
        "direction:Pedestrian[0]",
    ], wrong_side.as_dict()
    assert wrong_side.score is not None and wrong_side.score < 1.0

    result, features = _run(LEFT_TURN, "left_turn.scenic", tmp_path, validator_pool)
    turning = Truth.from_dict(
        {"ego_maneuver": "left_turn", "road": "intersection", "required_objects": ["signalized"]}
    )
    assert score_fidelity(turning, result, features).score == 1.0
    told_straight = score_fidelity(Truth.from_dict({"ego_maneuver": "straight"}), result, features)
    assert told_straight.verdict("ego_maneuver").match is False


@pytest.mark.parametrize(
    ("distance", "gap", "match"),
    [(0.5, 2.0, True), (0.5, 12.0, False), (40, 2.0, False), (0.5, None, False)],
)
def test_a_stopped_ego_at_the_stop_line_is_at_the_intersection(
    distance: float, gap: float | None, match: bool
) -> None:
    ego = agent("ego", "Car", straight(0, 0, 0, distance, NORTH), ego=True).model_copy(
        update={"junction_gap": gap}
    )
    fidelity = score_fidelity(truth(road="intersection"), ran(ego), {"intersection4"})
    assert fidelity.verdict("road").match is match
