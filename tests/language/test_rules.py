"""Rule values that take a slot's word are checked for every word of the slot's class."""

from __future__ import annotations

import pytest

from arise.language.errors import RuleError
from arise.language.rules import Rule, _check_value, load_rules

RULE = """
- id: test.rule
  fact: {fact}
  value: "{value}"
  about: actor
  when: [{when}]
  examples:
    - text: An example.
      gives: {{}}
"""


def _rule(fact: str, value: str, when: str) -> Rule:
    """One rule, loaded (its patterns compile); its value not yet checked."""
    return load_rules(RULE.format(fact=fact, value=value, when=when), "test.yaml")[0]


def test_a_slot_value_is_checked_for_every_word_of_its_class() -> None:
    _check_value(_rule("heading", "{compass}", "from north to <compass>"), "test.yaml")
    _check_value(_rule("start", "adjacent_lane_{side}", "in the <side> lane"), "test.yaml")


@pytest.mark.parametrize(
    ("fact", "value", "when"),
    [
        ("start", "adjacent_lane_{compass}", "<compass> lane"),  # no start is "..._north"
        ("heading", "{nowhere}", "northbound"),  # no such lexicon class
        ("requirement", "close", "near miss"),  # not a RequirementKind
        ("start", "adjacent_lane_{side}", "undertakes"),  # no <side> to fill the value with
    ],
)
def test_a_value_the_fact_cannot_take_is_a_rule_error(fact: str, value: str, when: str) -> None:
    with pytest.raises(RuleError):
        _check_value(_rule(fact, value, when), "test.yaml")


def test_no_pattern_is_cut_short_by_a_yaml_comment() -> None:
    """`- within # feet` is the pattern "within" to YAML: the number slot `#` must be quoted.
    A comment after a pattern is set off by two spaces."""
    from pathlib import Path

    import arise.language

    folder = Path(arise.language.__file__).parent / "data" / "rules"
    cut = [
        f"{path.name}:{number}"
        for path in sorted(folder.glob("*.yaml"))
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1)
        if line.lstrip().startswith("- ")
        and not line.lstrip()[2:].startswith(("'", '"'))
        and " # " in line
        and "  # " not in line
    ]
    assert not cut, cut
