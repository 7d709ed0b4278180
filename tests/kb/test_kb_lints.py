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
