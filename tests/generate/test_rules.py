"""Rule-based repairs turn broken catalogue scripts into scripts that execute (real validator)."""

from __future__ import annotations

import pytest

from arise.generate.rules import RuleContext, apply_rules, fix_scenic2_new
from arise.validate import CheckOptions, Diagnostic, Stage, WorkerPool, check_text
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
    "overlapping_spawn": _variant("AdvAgent = new Pedestrian right of AdvSpawnPt by 4",
                                  "AdvAgent = new Pedestrian right of EgoSpawnPt by 0.5"),
    "placeholder": _variant("AdvAgent = new Pedestrian", "AdvAgent = new {{ADVERSARY_CLASS}}"),
    "undeclared_param": _variant("param OPT_TRIGGER = Range(12, 18)\n", ""),
}


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CASES))
def test_rules_repair_until_the_script_runs(name: str, validator_pool: WorkerPool) -> None:
    text = CASES[name]
    context = RuleContext(adversary_class="Pedestrian",
                          param_defaults={"OPT_TRIGGER": "Range(12, 18)"})
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
    script = ("ego = Car at spot, with behavior Go()  # Car at spot\n"
              "other = Pedestrian ahead of ego by 5\nthird = new Car behind ego by 5\n")
    diagnostic = Diagnostic(stage=Stage.PARSE, error_type="ScenicParseError",
                            message="invalid syntax", line=1)
    fix = fix_scenic2_new(diagnostic, script, RuleContext())
    assert fix is not None
    assert fix.text.splitlines() == [
        "ego = new Car at spot, with behavior Go()  # Car at spot",
        "other = new Pedestrian ahead of ego by 5",
        "third = new Car behind ego by 5",
    ]
