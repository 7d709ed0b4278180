"""Every reading rule's examples give the facts the rule says (rules are data: adding a rule
means adding its example, and this test runs it through the real readers)."""

from __future__ import annotations

import pytest

from arise.language.examples import read_facts
from arise.language.rules import Example, Rule, rulebook

CASES = [
    pytest.param(compiled.rule, example, id=f"{compiled.rule.id}#{index}")
    for compiled in rulebook().rules
    for index, example in enumerate(compiled.rule.examples)
]


def _whose(found: dict[str, dict[str, str]], example: Example) -> dict[str, str]:
    if example.actor in (None, "scene"):
        return found["scene"]
    if example.actor == "ego":
        return found["ego"]
    word = example.actor.lower()
    named = [facts for quote, facts in found.items() if word in quote.lower()]
    assert named, f"no actor named {example.actor!r} in {sorted(found)}"
    return named[0]


@pytest.mark.parametrize(("rule", "example"), CASES)
def test_a_rules_example_gives_its_facts(rule: Rule, example: Example) -> None:
    facts = _whose(read_facts(example.text), example)
    got = {name: facts.get(name) for name in example.gives}
    assert got == example.gives, f"{rule.id}: {example.text!r}"


def test_every_rule_has_an_example_and_ids_are_unique() -> None:
    ids = [compiled.rule.id for compiled in rulebook().rules]
    assert len(ids) == len(set(ids))
    assert all(compiled.rule.examples for compiled in rulebook().rules)
