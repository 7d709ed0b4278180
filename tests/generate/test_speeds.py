"""Stated speeds set the speed parameters without a tuning call; other numbers still go to
the model. Every sentence here is written for these tests."""

from __future__ import annotations

from arise.generate.assemble import declared_params, range_bounds
from arise.generate.grounding import ground
from arise.generate.spec import ScenarioSpec
from arise.generate.speeds import stated_speeds
from arise.kb.loader import KnowledgeBase, load_kb
from arise.language.condense import condense
from tests.generate.test_grounding import answer


def _spec(text: str) -> ScenarioSpec:
    return ground(condense(text).text, answer()).spec


def test_the_egos_and_the_adversarys_speeds_are_read_from_their_own_clauses() -> None:
    spec = _spec(
        "The AV was travelling at 25 mph on Keel Street when a pickup doing about 40 mph "
        "ran the red light from the left."
    )
    assert spec.ego_speed == 11.2 and spec.adversary_speed == 17.9
    assert not spec.quantities_stated  # nothing left for the model to tune


def test_a_distance_keeps_the_defaults_and_a_time_goes_to_the_models_tuning() -> None:
    # a distance tells the moment of the conflict, which the behaviors time to the ego
    assert not _spec(
        "A removal van stops about 30 feet ahead of the ego in its lane."
    ).quantities_stated
    spec = _spec("A removal van ahead of the ego brakes hard 2 seconds after the lights.")
    assert spec.ego_speed is None and spec.quantities_stated


def test_a_stated_speed_is_a_narrow_range_and_a_far_one_keeps_the_default() -> None:
    kb: KnowledgeBase = load_kb(builtin=True)
    entry = next(e for e in kb.entries.values() if "OPT_EGO_SPEED" in declared_params([e]))
    bounds = range_bounds(declared_params([entry])["OPT_EGO_SPEED"][0])
    assert bounds is not None
    low, high = bounds
    inside = _spec(f"The ego drives at {(low + high) / 2 / 0.44704:.0f} mph; a van brakes.")
    values = stated_speeds(inside, [entry])
    assert values["OPT_EGO_SPEED"].startswith("Range(")
    far = _spec("The ego drives at 200 mph; a van brakes.")
    assert stated_speeds(far, [entry]) == {}
