"""Timing words narrow the knowledge base's trigger ranges to the end they name."""

from __future__ import annotations

from arise.generate.timing import timed_params
from arise.kb.loader import load_kb
from arise.kb.schema import Component
from arise.vocabulary import Timing
from tests.generate.test_repair_loop import entry

CUT_IN = entry(
    "behavior.cut",
    "param OPT_ADV_SPEED = Range(7, 10)\nparam OPT_ADV_TRIGGER = Range(12, 21)\n"
    "behavior AdversaryBehavior():\n    wait",
    defines=["AdversaryBehavior"],
)


def test_late_takes_the_first_third_and_early_the_last() -> None:
    assert timed_params(Timing.LATE, [CUT_IN]) == {"OPT_ADV_TRIGGER": "Range(12, 15)"}
    assert timed_params(Timing.EARLY, [CUT_IN]) == {"OPT_ADV_TRIGGER": "Range(18, 21)"}
    assert timed_params(None, [CUT_IN]) == {}, "no timing words: the ranges stand"


def test_a_fixed_trigger_and_other_parameters_are_left_alone() -> None:
    fixed = entry("behavior.fixed", "param OPT_ADV_TRIGGER = 15\nparam OPT_ADV_SPEED = 8")
    assert timed_params(Timing.LATE, [fixed]) == {}


def test_every_trigger_of_the_knowledge_base_is_a_range_the_words_can_narrow() -> None:
    behaviors = [e for e in load_kb(builtin=True) if e.component is Component.BEHAVIOR]
    late = {
        name: value for e in behaviors for name, value in timed_params(Timing.LATE, [e]).items()
    }
    assert {"OPT_ADV_TRIGGER", "OPT_ADV_GAP", "OPT_ADV_CUT_GAP"} <= set(late)
    assert all(value.startswith("Range(") for value in late.values())


def test_a_swapped_in_behavior_gets_its_own_trigger_narrowed() -> None:
    from arise.generate.conformity import Contradiction
    from arise.generate.repair import GatedValidate, repair_loop
    from tests.fakes import FakeValidator, passed
    from tests.generate.test_repair_loop import setup, spawn

    run, draft, context = setup(spawn(1))
    context.timing = Timing.LATE
    context.retrieval.candidates[Component.BEHAVIOR].append(CUT_IN)
    late = Contradiction("conflict", "within 6 m or TTC under 3 s", "closest 20 m", "BEHAVIOR")
    found = [[late], []]
    validate = GatedValidate(FakeValidator([passed(), passed()]), lambda _: found.pop(0))
    repair_loop(run, draft.script, validate, context, max_repairs=2)
    assert run.attempts[1].detail == "behavior.cross -> behavior.cut"
    assert "param OPT_ADV_TRIGGER = Range(12, 15)" in run.attempts[1].script
