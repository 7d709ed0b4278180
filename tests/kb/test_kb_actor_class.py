"""The knowledge base speaks ActorClass: entries' adversaries and copies' actor classes are
validated as classes of the model, and composing takes a class, not a free string."""

from __future__ import annotations

import pytest
from pydantic import ValidationError

from arise.errors import AriseError
from arise.kb.actors import ActorCopyError, for_actor
from arise.kb.compose import compose, composition_problems
from arise.kb.loader import load_kb
from arise.kb.plan import plan_validation
from arise.kb.schema import Component, Entry
from arise.vocabulary import ActorClass

KB = load_kb(strict=True)
CORE = ["behavior.cross_and_stop", "geometry.straight_road", "spawn.roadside_right_near"]
CAR_CORE = ["geometry.straight_road", "spawn.lead_same_lane", "behavior.slow_to_block"]


def _entry(**fields: object) -> Entry:
    base: dict[str, object] = {
        "id": "spawn.test",
        "component": Component.SPAWN,
        "descriptions": ["a test spawn"],
        "snippet": "adversary = new {{ADVERSARY_CLASS}} on road",
    }
    return Entry.model_validate(base | fields)


def test_every_entry_of_the_knowledge_base_reads_its_adversaries_as_classes() -> None:
    named = [cls for entry in list(KB) for cls in entry.adversaries]
    assert named and all(isinstance(cls, ActorClass) and cls.is_adversary for cls in named)


def test_adversaries_read_from_text_become_classes() -> None:
    entry = _entry(adversaries=["Car", "Motorcycle"])
    assert entry.adversaries == [ActorClass.CAR, ActorClass.MOTORCYCLE]
    assert entry.suits(ActorClass.MOTORCYCLE) and not entry.suits(ActorClass.PEDESTRIAN)
    assert entry.model_dump(mode="json")["adversaries"] == ["Car", "Motorcycle"]


@pytest.mark.parametrize("name", ["Van", "Cone", "NPCCar", "car", "Tractor"])
def test_an_adversary_must_be_one_of_the_five_adversary_classes(name: str) -> None:
    with pytest.raises(ValidationError, match="unknown adversary class") as raised:
        _entry(adversaries=[name])
    assert "Car, Truck, Motorcycle, Bicycle, Pedestrian" in str(raised.value)


def test_a_copys_actor_class_is_a_road_users_class() -> None:
    assert _entry(actor="actor2", actor_class="Bus").actor_class is ActorClass.BUS
    with pytest.raises(ValidationError, match="a prop, not a road user"):
        _entry(actor="actor2", actor_class="Cone")
    with pytest.raises(ValidationError):
        _entry(actor="actor2", actor_class="Spaceship")


def test_for_actor_records_the_class_and_refuses_a_prop_or_an_unknown_name() -> None:
    spawn = KB.get("spawn.lead_same_lane")
    copy = for_actor(spawn, "actor2", ActorClass.VAN)
    assert copy.actor_class is ActorClass.VAN and "new Van" in copy.snippet
    for bad in ("Cone", "Spaceship"):
        with pytest.raises(ActorCopyError, match="not a road user's class") as raised:
            for_actor(spawn, "actor2", bad)  # type: ignore[arg-type]
        assert isinstance(raised.value, AriseError)


def test_a_van_composes_where_a_car_does_and_a_prop_does_not() -> None:
    entries = [KB.get(i) for i in CAR_CORE]
    assert composition_problems(entries, ActorClass.CAR) == []
    assert composition_problems(entries, ActorClass.VAN) == []  # a van drives like a car
    assert "adversary = new Van" in compose(entries, ActorClass.VAN, "arise_straight")
    problems = composition_problems(entries, ActorClass.CONE)
    assert any("adversary class 'Cone' is not one of" in p for p in problems)
    problems = composition_problems(entries, "Spaceship")  # type: ignore[arg-type]
    assert any("adversary class 'Spaceship' is not one of" in p for p in problems)


def test_an_actor_copy_of_each_class_is_checked_against_its_entries() -> None:
    entries = [KB.get(i) for i in CORE]
    spawn, behavior = KB.get("spawn.lead_same_lane"), KB.get("behavior.slow_to_block")
    trucks = [for_actor(spawn, "actor2", ActorClass.BUS), for_actor(behavior, "actor2", "Bus")]
    assert composition_problems([*entries, *trucks], ActorClass.PEDESTRIAN) == []


def test_the_validation_plan_picks_a_class_each_core_suits() -> None:
    entries = [KB.get(i) for i in dict.fromkeys([*CORE, *CAR_CORE])]
    plan = plan_validation(entries, {"arise_straight": {"straight", "sidewalk", "multilane"}})
    assert not plan.uncovered
    used = {c.adversary_class for c in plan.compositions}
    assert all(isinstance(cls, ActorClass) and cls.is_adversary for cls in used)
    assert ActorClass.PEDESTRIAN in used and len(used) > 1  # the crossing and the lead car
