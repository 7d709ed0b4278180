"""Composing entries into a script: sections in order, names checked, errors name entries."""

from __future__ import annotations

import pytest

from arise.kb.compose import (
    ComposeError,
    compose,
    composition_problems,
    entry_at_line,
    pick_map,
)
from arise.kb.loader import load_kb
from arise.sections import find_sections

KB = load_kb(strict=True)
CORE = ["behavior.cross_and_stop", "geometry.straight_road", "spawn.roadside_right_near"]


def _entries(*ids: str):
    return [KB.get(i) for i in ids]


def test_compose_follows_the_script_format() -> None:
    text = compose(
        _entries(*CORE, "weather.dense_fog", "misc.occluder_parked_van"),
        "Pedestrian",
        "arise_straight",
        description="a test",
    )
    assert text.startswith(
        "# a test\n# BEGIN HEADER\nparam map = localPath('maps/arise_straight.xodr')"
    )
    names = [s.name for s in sorted(find_sections(text), key=lambda s: s.first_line)]
    assert names == ["HEADER", "WEATHER", "BEHAVIOR", "GEOMETRY", "SPAWN", "MISC", "REQUIREMENTS"]
    assert "adversary = new Pedestrian" in text and "{{" not in text
    assert "terminate after 20 seconds" in text
    line = next(n for n, t in enumerate(text.splitlines(), 1) if "occluderVan" in t)
    assert entry_at_line(text, line) == "misc.occluder_parked_van"
    assert entry_at_line(text, 3) is None  # the header belongs to no entry


def test_missing_need_names_the_entry() -> None:
    with pytest.raises(ComposeError) as raised:
        compose(
            _entries("behavior.run_red_light", "geometry.straight_road", "spawn.lead_same_lane"),
            "Car",
            "arise_straight",
        )
    assert "behavior.run_red_light: needs advRoute" in str(raised.value)


def test_spawn_needs_come_from_geometry() -> None:
    problems = composition_problems(
        _entries("behavior.drive_route", "geometry.straight_road", "spawn.junction_conflict_route"),
        "Car",
    )
    assert any(
        p.startswith("spawn.junction_conflict_route: needs conflictManeuver") for p in problems
    )


def test_adversary_class_must_suit_every_entry() -> None:
    problems = composition_problems(_entries(*CORE), "Truck")
    assert any("behavior.cross_and_stop" in p and "not Truck" in p for p in problems)


def test_one_behavior_geometry_and_spawn() -> None:
    problems = composition_problems(
        _entries("behavior.cross_and_stop", "behavior.slow_crossing", "geometry.straight_road"),
        "Pedestrian",
    )
    text = "\n".join(problems)
    assert "only one behavior" in text and "no spawn entry" in text


def test_pick_map_prefers_the_most_specific_map() -> None:
    maps = {
        "arise_straight": {"straight", "multilane", "sidewalk"},
        "arise_intersection4": {"straight", "multilane", "sidewalk", "intersection4", "signalized"},
        "arise_highway": {"straight", "multilane", "highway", "curve"},
    }
    assert pick_map(_entries("geometry.straight_road"), maps) == "arise_straight"
    assert (
        pick_map(_entries("geometry.signalized_straight_on_green"), maps) == "arise_intersection4"
    )
    assert pick_map(_entries("geometry.tjunction_main_left_turn"), maps) is None


def test_unfilled_placeholder_is_an_error() -> None:
    entry = KB.get("spawn.lead_same_lane").model_copy(
        update={"snippet": KB.get("spawn.lead_same_lane").snippet + "# {{COLOUR}}\n"}
    )
    with pytest.raises(ComposeError, match="COLOUR"):
        compose(
            [KB.get("behavior.sudden_brake"), KB.get("geometry.straight_road"), entry],
            "Car",
            "arise_straight",
        )
