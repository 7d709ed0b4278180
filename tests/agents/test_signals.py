"""The world model's signals on our own maps: where they stand and how they cycle."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from scenic.domains.driving.roads import Network

from arise.agents.types import LightState, SignalKind
from arise.maps.registry import MapRegistry
from arise.validate.map_cache import prepare_map
from arise.validate.worldmodel.signals import CYCLE_SECONDS, SignalModel, cycle_state


def _network(name: str) -> Network:
    choice = MapRegistry(None).resolve(name)
    prepare_map(Path(choice.path))
    return Network.fromFile(choice.path)


@pytest.fixture(scope="module")
def four_way() -> SignalModel:
    return SignalModel(_network("arise_intersection4"), timestep=0.1)


def test_a_four_way_junction_has_a_light_per_entry_in_two_phases(four_way: SignalModel) -> None:
    lights = [a for a in four_way.approaches if a.kind is SignalKind.TRAFFIC_LIGHT]
    assert len(lights) == 4
    # Opposite entries share a phase, crossing ones do not.
    by_road = {a.id.split("/")[-1]: a.phase for a in lights}
    assert by_road["road4"] == by_road["road2"] != by_road["road1"] == by_road["road3"]


def test_stop_lines_are_ordered_right_then_left_for_the_traffic_they_stop(
    four_way: SignalModel,
) -> None:
    # road4 brings traffic north into the junction (its stop line lies at y = -14).
    road4 = next(a for a in four_way.approaches if a.id.endswith("/road4"))
    (ax, ay), (bx, by) = road4.stop_line
    assert ay == by == pytest.approx(-14.0)
    travel = (by - ay, -(bx - ax))  # p2 - p1 turned clockwise
    assert travel[1] > 0 and math.isclose(travel[0], 0.0, abs_tol=1e-9)


def test_the_cycle_is_fixed_and_never_green_for_both_phases() -> None:
    assert cycle_state(0, 0.0) is LightState.GREEN
    assert cycle_state(0, 11.0) is LightState.YELLOW
    assert cycle_state(0, 13.5) is LightState.RED
    assert cycle_state(1, 0.0) is LightState.RED
    assert cycle_state(1, 14.0) is LightState.GREEN
    for tenth in range(int(CYCLE_SECONDS * 10)):
        states = {cycle_state(0, tenth / 10), cycle_state(1, tenth / 10)}
        assert states != {LightState.GREEN} and LightState.RED in states


def test_the_trace_records_each_change_of_the_cycle() -> None:
    model = SignalModel(_network("arise_intersection4"), timestep=0.1)
    road1 = next(t for t in model.traces(300) if t.id.endswith("/road1"))
    assert [state for _, state in road1.states[:3]] == [
        LightState.RED,
        LightState.GREEN,
        LightState.YELLOW,
    ]
    assert road1.states[1][0] == 140  # phase B turns green after A's 10 + 3 + 1 s


def test_a_light_a_script_sets_holds_and_switches_its_junction() -> None:
    model = SignalModel(_network("arise_intersection4"), timestep=0.1)
    entry = {a.id.split("/")[-1]: a for a in model.approaches}
    assert model.state(entry["road4"], 0) is LightState.GREEN
    model.hold(entry["road4"], "red", 50)  # e.g. an adversary about to run its red
    assert model.state(entry["road4"], 49) is LightState.GREEN
    for step in (50, 139, 400):  # held past both phases' own changes
        assert model.state(entry["road4"], step) is LightState.RED
        assert model.state(entry["road2"], step) is LightState.RED  # its phase follows
        assert model.state(entry["road1"], step) is LightState.GREEN  # the crossing has green
        assert model.state(entry["road3"], step) is LightState.GREEN
    trace = next(t for t in model.traces(400) if t.id == entry["road4"].id)
    assert trace.states == [(0, LightState.GREEN), (50, LightState.RED)]
    model.hold(entry["road1"], "off", 60)  # a dark light is dark alone
    assert model.state(entry["road1"], 60) is LightState.OFF
    assert model.state(entry["road3"], 60) is LightState.GREEN


def test_two_approaches_set_red_at_one_step_both_stay_red() -> None:
    """An adversary sets its light red to run it, and the ego sets its own red too: what a
    script set on an approach beats what the other set implied for it (an all-red junction)."""
    model = SignalModel(_network("arise_intersection4"), timestep=0.1)
    entry = {a.id.split("/")[-1]: a for a in model.approaches}
    model.hold(entry["road4"], "red", 0)
    model.hold(entry["road1"], "red", 0)
    assert model.state(entry["road4"], 10) is LightState.RED
    assert model.state(entry["road1"], 10) is LightState.RED
    model.hold(entry["road1"], "green", 20)  # later, a new set wins, and switches the junction
    assert model.state(entry["road1"], 20) is LightState.GREEN
    assert model.state(entry["road4"], 20) is LightState.RED
    model.hold(entry["road1"], "yellow", 30)
    model.hold(entry["road1"], "red", 30)  # two sets at one step: the later one
    assert model.state(entry["road1"], 30) is LightState.RED


def test_a_stop_sign_of_the_map_stops_one_entry() -> None:
    model = SignalModel(_network("arise_tjunction"), timestep=0.1)
    signs = [a for a in model.approaches if a.kind is SignalKind.STOP_SIGN]
    assert len(signs) == 1 and not any(a.kind is SignalKind.TRAFFIC_LIGHT for a in model.approaches)
    (trace,) = model.traces(300)
    assert trace.states == [(0, LightState.RED)]
