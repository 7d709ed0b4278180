"""The static rules: our entries keep them, and each rule catches what it is for."""

from __future__ import annotations

from arise.kb.lints import lint_all, lint_entry
from arise.kb.loader import load_kb
from arise.kb.schema import Entry


def _entry(component: str, snippet: str, **fields: object) -> Entry:
    data: dict[str, object] = {
        "id": f"{component}.probe",
        "component": component,
        "descriptions": ["probe"],
        "snippet": snippet,
    }
    data.update(fields)
    return Entry.model_validate(data)


def _messages(entry: Entry) -> str:
    return "\n".join(str(problem) for problem in lint_entry(entry))


def test_our_entries_are_lint_clean() -> None:
    problems = lint_all(load_kb(strict=True))
    assert not problems, "\n".join(map(str, problems))


def test_scenic2_object_creation_is_caught() -> None:
    entry = _entry("misc", "cone = Cone ahead of ego by 10\n", defines=["cone"])
    assert "Scenic 2 object creation" in _messages(entry)
    entry = _entry("misc", "cone = new Cone ahead of ego by 10\n", defines=["cone"])
    assert not lint_entry(entry)


def test_params_are_opt_declared_and_read_via_global_parameters() -> None:
    undeclared = _entry(
        "misc", "cone = new Cone ahead of ego by globalParameters.OPT_GAP\n", defines=["cone"]
    )
    assert "does not declare `param OPT_GAP`" in _messages(undeclared)
    bare = _entry(
        "misc",
        "param OPT_GAP = Range(5, 9)\ncone = new Cone ahead of ego by OPT_GAP\n",
        defines=["cone"],
        params=["OPT_GAP"],
    )
    assert "without globalParameters" in _messages(bare)
    badly_named = _entry(
        "misc", "param gap = 5\ncone = new Cone ahead of ego by 5\n", defines=["cone"]
    )
    assert "tunables are named OPT_*" in _messages(badly_named)
    in_require = _entry(
        "requirements",
        "param OPT_D = Range(5, 9)\nrequire (distance to adversary) > globalParameters.OPT_D\n",
        params=["OPT_D"],
    )
    assert "`require` condition reads globalParameters" in _messages(in_require)


def test_adversary_behavior_name_and_placeholders() -> None:
    wrong_name = _entry(
        "behavior", "behavior Brake():\n    take SetBrakeAction(1)\n", defines=["Brake"]
    )
    assert "AdversaryBehavior" in _messages(wrong_name)
    undeclared = _entry(
        "spawn",
        "adversary = new {{ADVERSARY_CLASS}} ahead of ego by 9, "
        "with behavior AdversaryBehavior()\n",
        defines=["adversary"],
    )
    assert "placeholders" in _messages(undeclared)
    declared = _entry(
        "spawn",
        "adversary = new {{ADVERSARY_CLASS}} ahead of ego by 9, "
        "with behavior AdversaryBehavior()\n",
        defines=["adversary"],
        placeholders=["ADVERSARY_CLASS"],
    )
    assert not lint_entry(declared)


def test_interface_must_match_the_code() -> None:
    entry = _entry(
        "misc",
        "cone = new Cone ahead of ego by 10\nother = 3\n",
        defines=["cone", "missing"],
        needs=["egoLane"],
    )
    text = _messages(entry)
    assert "missing" in text and "other" in text and "egoLane" in text


def test_bad_weather_is_caught() -> None:
    assert "unknown CARLA weather preset" in _messages(
        _entry("weather", "param weather = 'SunnyNoon'\n")
    )
    assert "unknown CARLA weather parameter" in _messages(
        _entry("weather", "param weather = {'fogginess': 3.0}\n")
    )


def _behavior(body: str, **fields: object) -> Entry:
    snippet = "param OPT_ADV_SPEED = Range(5, 8)\nbehavior AdversaryBehavior():\n" + body
    return _entry(
        "behavior",
        snippet,
        defines=["AdversaryBehavior"],
        needs=["advLane"] if "advLane" in body else [],
        params=["OPT_ADV_SPEED"],
        **fields,
    )


def test_an_adversary_move_must_start_from_the_ego() -> None:
    at_once = _behavior(
        "    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, "
        "laneToFollow=advLane)\n"
    )
    assert "first move does not depend on the ego" in _messages(at_once)
    on_the_clock = _behavior(
        "    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, "
        "laneToFollow=advLane) for 3 seconds\n"
        "    while (distance from self to ego) > 10:\n"
        "        take SetBrakeAction(1.0)\n"
    )
    assert "starts on the clock" in _messages(on_the_clock)
    until_near = _behavior(
        "    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, "
        "laneToFollow=advLane) until (distance from self to ego) < 10\n"
        "    do FollowLaneBehavior(target_speed=2) for 3 seconds\n"
    )
    assert not lint_entry(until_near)
    # "ego" in a comment or a string is not a reference to it.
    commented = _behavior(
        "    # waits for the ego\n"
        "    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, "
        "laneToFollow=advLane)\n"
    )
    assert "first move does not depend on the ego" in _messages(commented)


def test_a_helper_that_reads_the_ego_counts() -> None:
    snippet = (
        "param OPT_ADV_SPEED = Range(5, 8)\n"
        "def EgoEta(point):\n"
        "    return (distance from ego to point) / max(ego.speed, 0.5)\n"
        "behavior WaitUntilDue(point, seconds):\n"
        "    while EgoEta(point) > seconds:\n"
        "        wait\n"
        "behavior AdversaryBehavior():\n"
        "    do WaitUntilDue(advLane.centerline[-1], 3)\n"
        "    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED) for 2 seconds\n"
    )
    entry = _entry(
        "behavior",
        snippet,
        defines=["EgoEta", "WaitUntilDue", "AdversaryBehavior"],
        needs=["advLane"],
        params=["OPT_ADV_SPEED"],
    )
    assert not lint_entry(entry)


def test_stationary_and_no_conflict_behaviors_are_exempt_by_tag() -> None:
    body = "    while True:\n        take SetThrottleAction(0), SetBrakeAction(1.0)\n"
    assert "does not depend on the ego" in _messages(_behavior(body))
    assert not lint_entry(_behavior(body, tags=["static"]))
    cruise = "    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED)\n"
    assert not lint_entry(_behavior(cruise, tags=["no_conflict"]))


def test_our_clock_started_behaviors_of_before_would_be_refused() -> None:
    """Two of the entries as they were before issue 31: on the clock, and at once."""
    emergency = _behavior(
        "    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, "
        "laneToFollow=advLane) for globalParameters.OPT_ADV_SPEED seconds\n"
        "    while True:\n"
        "        take SetThrottleAction(0), SetBrakeAction(1.0), SetHandBrakeAction(True)\n"
    )
    assert "starts on the clock" in _messages(emergency)
    route = _behavior(
        "    take SetTrafficLightAction('red')\n"
        "    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_ADV_SPEED, "
        "trajectory=[advLane])\n"
    )
    assert "first move does not depend on the ego" in _messages(route)
