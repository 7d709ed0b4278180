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
