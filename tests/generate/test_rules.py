"""Rule-based repairs: each rule in milliseconds on hand-written diagnostics, and the broken
catalogue scripts repaired until they execute (real validator, slow)."""

from __future__ import annotations

import pytest

from arise.generate.rules import (
    RULES,
    RuleContext,
    apply_rules,
    fix_blueprint,
    fix_close_name,
    fix_forbidden_import,
    fix_overlap,
    fix_placeholders,
    fix_scenic2_new,
    fix_tight_requirement,
    fix_undeclared_param,
    fix_weather,
)
from arise.validate import CheckOptions, Diagnostic, Stage, WorkerPool, check_text
from arise.validate.types import Rejection
from arise.vocabulary import ActorClass
from tests.conftest import DATA

BASE = (DATA / "base_crossing.scenic").read_text()
OPTIONS = CheckOptions(seed=3, timeout=30, spawn_attempts=4, sample_iterations=300)


def _variant(old: str, new: str) -> str:
    assert old in BASE
    return BASE.replace(old, new)


CASES = {
    "scenic2_no_new": (DATA / "broken" / "scenic2_no_new.scenic").read_text(),
    "unknown_blueprint": (DATA / "broken" / "unknown_blueprint.scenic").read_text(),
    "bad_weather": (DATA / "broken" / "bad_weather.scenic").read_text(),
    "undefined_name_behavior": (DATA / "broken" / "undefined_name_behavior.scenic").read_text(),
    "forbidden_import": (DATA / "broken" / "forbidden_import.scenic").read_text(),
    "unsatisfiable_requirement": (DATA / "broken" / "unsatisfiable_requirement.scenic").read_text(),
    "overlapping_spawn": _variant(
        "AdvAgent = new Pedestrian right of AdvSpawnPt by 4",
        "AdvAgent = new Pedestrian right of EgoSpawnPt by 0.5",
    ),
    "placeholder": _variant("AdvAgent = new Pedestrian", "AdvAgent = new {{ADVERSARY_CLASS}}"),
    "undeclared_param": _variant("param OPT_TRIGGER = Range(12, 18)\n", ""),
}


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CASES))
def test_rules_repair_until_the_script_runs(name: str, validator_pool: WorkerPool) -> None:
    text = CASES[name]
    context = RuleContext(
        adversary_class="Pedestrian", param_defaults={"OPT_TRIGGER": "Range(12, 18)"}
    )
    applied = []
    for _ in range(6):
        result = check_text(text, OPTIONS, pool=validator_pool)
        if result.ok:
            break
        assert result.diagnostic is not None
        fix = apply_rules(result.diagnostic, text, context)
        assert fix is not None, f"no rule for {result.diagnostic.one_line()}"
        applied.append(fix.rule)
        text = fix.text
    assert result.ok, result.diagnostic
    assert applied, "the broken script must have needed at least one rule"


def test_scenic2_rule_adds_new_everywhere_but_in_comments() -> None:
    script = (
        "ego = Car at spot, with behavior Go()  # Car at spot\n"
        "other = Pedestrian ahead of ego by 5\nthird = new Car behind ego by 5\n"
    )
    diagnostic = Diagnostic(
        stage=Stage.PARSE, error_type="ScenicParseError", message="invalid syntax", line=1
    )
    fix = fix_scenic2_new(diagnostic, script, RuleContext())
    assert fix is not None
    assert fix.text.splitlines() == [
        "ego = new Car at spot, with behavior Go()  # Car at spot",
        "other = new Pedestrian ahead of ego by 5",
        "third = new Car behind ego by 5",
    ]


# -- every rule on its own, in milliseconds (hand-written diagnostics, no validator) -------


def _diagnostic(
    stage: Stage = Stage.COMPILE, error_type: str = "Error", message: str = "", **fields: object
) -> Diagnostic:
    return Diagnostic(stage=stage, error_type=error_type, message=message, **fields)  # type: ignore[arg-type]


def test_placeholder_rule_fills_the_adversary_class_and_known_values() -> None:
    text = "adv = new {{ADVERSARY_CLASS}} at {{SPOT}}\nx = {{UNKNOWN}}\n"
    context = RuleContext(adversary_class=ActorClass.BICYCLE, placeholders={"SPOT": "p"})
    fix = fix_placeholders(_diagnostic(), text, context)
    assert fix is not None and fix.rule == "placeholder"
    assert fix.text == "adv = new Bicycle at p\nx = {{UNKNOWN}}\n"
    assert fix_placeholders(_diagnostic(), "x = {{UNKNOWN}}\n", RuleContext()) is None


def test_scenic2_rule_needs_a_parse_error_on_a_scenic2_line() -> None:
    text = "ego = Car at spot\n"
    assert fix_scenic2_new(_diagnostic(Stage.COMPILE, line=1), text, RuleContext()) is None
    assert fix_scenic2_new(_diagnostic(Stage.PARSE, line=1), "x = 1\n", RuleContext()) is None
    hinted = _diagnostic(Stage.PARSE, message="forgot 'new'?", line=None)
    fix = fix_scenic2_new(hinted, text, RuleContext())
    assert fix is not None and fix.text == "ego = new Car at spot\n"


def test_undeclared_param_rule_declares_it_above_the_block_that_reads_it() -> None:
    text = "behavior B():\n    wait for globalParameters.OPT_GAP_SPEED\nego = new Car\n"
    diagnostic = _diagnostic(
        Stage.SIMULATE, "AttributeError", "'Params' has no attribute 'OPT_GAP_SPEED'"
    )
    fix = fix_undeclared_param(diagnostic, text, RuleContext())
    assert fix is not None and fix.note == "declared param OPT_GAP_SPEED"
    assert fix.text.splitlines()[0] == "param OPT_GAP_SPEED = Range(5, 10)"
    known = RuleContext(param_defaults={"OPT_GAP_SPEED": "7"})
    assert fix_undeclared_param(diagnostic, text, known).text.startswith(  # type: ignore[union-attr]
        "param OPT_GAP_SPEED = 7\n"
    )
    declared = "param OPT_GAP_SPEED = 3\n" + text
    assert fix_undeclared_param(diagnostic, declared, RuleContext()) is None
    assert fix_undeclared_param(_diagnostic(message="no name here"), text, RuleContext()) is None


def test_close_name_rule_takes_the_one_suggestion() -> None:
    text = "a = Pedestrain\nb = Pedestrain\n"
    diagnostic = _diagnostic(
        Stage.COMPILE,
        "NameError",
        "name 'Pedestrain' is not defined",
        line=2,
        hint="'Pedestrain' is not defined; did you mean Pedestrian?",
    )
    fix = fix_close_name(diagnostic, text, RuleContext())
    assert fix is not None and fix.text == "a = Pedestrain\nb = Pedestrian\n"
    no_hint = diagnostic.model_copy(update={"hint": None})
    assert fix_close_name(no_hint, text, RuleContext()) is None
    param = diagnostic.model_copy(
        update={"message": "name 'OPT_X' is not defined", "hint": "did you mean OPT_Y?"}
    )
    assert fix_close_name(param, "x = OPT_X\n", RuleContext()) is None


def test_blueprint_rule_takes_the_closest_or_drops_the_specifier() -> None:
    text = "adv = new Car at p, with blueprint 'vehicle.tesla.modl3'\n"
    close = _diagnostic(
        Stage.COMPILE,
        "UnknownBlueprintError",
        "unknown blueprint 'vehicle.tesla.modl3'; close valid ones: "
        "vehicle.tesla.model3, vehicle.tesla.cybertruck",
    )
    fix = fix_blueprint(close, text, RuleContext())
    assert fix is not None and "'vehicle.tesla.model3'" in fix.text
    none_close = close.model_copy(update={"message": "unknown blueprint 'vehicle.tesla.modl3'"})
    fix = fix_blueprint(none_close, text, RuleContext())
    assert fix is not None and fix.text == "adv = new Car at p\n"


def test_weather_rule_picks_the_nearest_preset() -> None:
    text = "param weather = 'ClearNite'\n"
    diagnostic = _diagnostic(
        Stage.COMPILE, "WeatherError", "unknown CARLA weather preset 'ClearNite'"
    )
    fix = fix_weather(diagnostic, text, RuleContext())
    assert fix is not None and fix.text == "param weather = 'ClearNight'\n"
    assert fix_weather(_diagnostic(error_type="WeatherError"), text, RuleContext()) is None


def test_overlap_rule_moves_the_later_object_apart() -> None:
    text = "ego = new Car\nadv = new Car ahead of ego by 1.5\n"
    diagnostic = _diagnostic(
        Stage.SAMPLE,
        "RejectionException",
        "rejected",
        rejections=[Rejection(reason="adv intersects ego", count=30, line=2)],
    )
    fix = fix_overlap(diagnostic, text, RuleContext())
    assert fix is not None and fix.text.endswith("adv = new Car ahead of ego by 3\n")


def test_tight_requirement_is_relaxed_twice_then_dropped() -> None:
    text = "require (distance to adv) < 10\n"
    diagnostic = _diagnostic(
        Stage.SAMPLE,
        "RejectionException",
        "rejected",
        rejections=[
            Rejection(
                reason="requirement on line 1",
                count=90,
                line=1,
                code="require (distance to adv) < 10",
            )
        ],
    )
    context = RuleContext()
    first = fix_tight_requirement(diagnostic, text, context)
    assert first is not None and first.text == "require (distance to adv) < 15\n"
    second = fix_tight_requirement(diagnostic, first.text, context)
    assert second is not None and second.text == "require (distance to adv) < 22.5\n"
    third = fix_tight_requirement(diagnostic, second.text, context)
    assert third is not None and third.note == "dropped requirement on line 1"
    assert third.text.startswith("pass  # arise: dropped over-tight")


@pytest.mark.xfail(
    strict=True,
    reason="known: `a <= x <= b` takes the `<` branch, so the "
    "lower bound is raised (4 -> 6) instead of lowered; kept as it is so the "
    "refactor changes no generated script",
)
def test_tight_two_sided_requirement_is_widened_at_both_ends() -> None:
    diagnostic = _diagnostic(
        Stage.SAMPLE,
        "RejectionException",
        "rejected",
        rejections=[
            Rejection(reason="requirement on line 1", count=90, line=1, code="require ...")
        ],
    )
    widened = fix_tight_requirement(
        diagnostic, "require 4 <= (distance to adv) <= 8\n", RuleContext()
    )
    assert widened is not None and "2.66667 <= (distance to adv) <= 12" in widened.text


def test_forbidden_import_rule_removes_the_refused_line() -> None:
    text = "import os\nego = new Car\n"
    diagnostic = _diagnostic(Stage.GATE, "ForbiddenImport", "import of 'os' refused", line=1)
    fix = fix_forbidden_import(diagnostic, text, RuleContext())
    assert fix is not None and fix.text == "# arise: removed refused `import os`\nego = new Car\n"
    elsewhere = diagnostic.model_copy(update={"line": 2})
    assert fix_forbidden_import(elsewhere, text, RuleContext()) is None


def test_apply_rules_returns_the_first_rule_that_changes_the_text() -> None:
    text = "adv = new {{ADVERSARY_CLASS}}\nimport os\n"
    diagnostic = _diagnostic(Stage.GATE, "ForbiddenImport", "import of 'os' refused", line=2)
    fix = apply_rules(diagnostic, text, RuleContext(adversary_class=ActorClass.CAR))
    assert fix is not None and fix.rule == "placeholder"
    assert (
        apply_rules(_diagnostic(Stage.SIMULATE, "TypeError", "odd"), "x = 1\n", RuleContext())
        is None
    )
    assert len(RULES) == 9, "a new rule needs a test here"
