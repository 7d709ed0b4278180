"""The exporter writes each class as the entity of its group (a vehicle, a pedestrian, a
misc object) with the category of its class, read back from the written .xosc."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from arise.present.actors import PEDESTRIAN, PROP, VEHICLES, entity_of
from arise.present.source import Origin, TraceSource
from arise.present.verify import xsd_errors
from arise.present.xosc import write_export
from arise.validate.facts import ego_pair_facts, find_collisions
from arise.validate.types import AgentTrace, SimulationFacts
from arise.vocabulary import ActorClass, ActorGroup
from tests.present.traces import TIMESTEP, straight, straight_map

STEPS = 10  # a short trace: the entities are what is tested, not the motion

#: OpenSCENARIO's vehicle category for each wheeled class.
VEHICLE_CATEGORIES = {
    ActorClass.CAR: "car",
    ActorClass.NPC_CAR: "car",
    ActorClass.TRUCK: "truck",
    ActorClass.VAN: "van",
    ActorClass.BUS: "bus",
    ActorClass.MOTORCYCLE: "motorbike",
    ActorClass.BICYCLE: "bicycle",
}
#: The element and category attribute each group is written as.
ELEMENTS = {
    ActorGroup.VEHICLE: ("Vehicle", "vehicleCategory"),
    ActorGroup.TWO_WHEELER: ("Vehicle", "vehicleCategory"),
    ActorGroup.WALKER: ("Pedestrian", "pedestrianCategory"),
    ActorGroup.PROP: ("MiscObject", "miscObjectCategory"),
}
UNKNOWN = "MyOwnThing"  # a class of the script's own, unknown to the vocabulary


def _category(cls: ActorClass) -> str:
    if cls.is_vehicle:
        return VEHICLE_CATEGORIES[cls]
    return "pedestrian" if cls.is_walker else "obstacle"


def _agents() -> list[AgentTrace]:
    kinds = ["Car", *(cls.value for cls in ActorClass), UNKNOWN]
    return [
        AgentTrace(
            name="ego" if i == 0 else f"a{i}_{kind}",
            kind=kind,
            width=1.0,
            length=2.0,
            is_ego=i == 0,
            trajectory=straight(10.0 + 3.0 * i, -5.25, -math.pi / 2, 0.0 if i else 5.0, STEPS),
        )
        for i, kind in enumerate(kinds)
    ]


@pytest.fixture(scope="module")
def entities(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, ET.Element]]:
    folder = tmp_path_factory.mktemp("entities")
    script = folder / "scenario.scenic"
    script.write_text("# a hand-made trace stands for this script\n", encoding="utf-8")
    agents = _agents()
    facts = SimulationFacts(
        steps=STEPS,
        timestep=TIMESTEP,
        termination_type="timeLimit",
        termination_reason="maximum steps",
        agents=agents,
        collisions=find_collisions(agents, TIMESTEP),
        ego_pairs=ego_pair_facts(agents),
        params={"weather": "ClearNoon"},
    )
    trace = TraceSource(
        script=script,
        simulation=facts,
        map=straight_map(),
        origin=Origin.CHECKED,
        seed=0,
        steps=STEPS,
    )
    files = write_export(trace, folder / "out")
    root = ET.parse(files.xosc).getroot()
    return files.xosc, {o.get("name", ""): o for o in root.iter("ScenarioObject")}


def test_the_export_with_every_class_is_valid_openscenario(entities) -> None:
    xosc, objects = entities
    assert xsd_errors(xosc) == []
    assert len(objects) == len(ActorClass) + 2  # the ego, every class, the unknown one


@pytest.mark.parametrize("cls", list(ActorClass))
def test_each_class_is_written_as_its_groups_entity_with_its_category(entities, cls) -> None:
    _, objects = entities
    (name,) = [n for n in objects if n.endswith(f"_{cls.value}")]
    element, attribute = ELEMENTS[cls.group]
    entity = objects[name].find(element)
    assert entity is not None, (cls, [child.tag for child in objects[name]])
    assert entity.get(attribute) == _category(cls)
    properties = {p.get("name"): p.get("value") for p in entity.iter("Property")}
    assert properties["arise_class"] == cls.value
    prefix = {"Vehicle": "vehicle.", "Pedestrian": "walker.", "MiscObject": "static."}[element]
    assert entity.get("name", "").startswith(prefix)  # the class's default blueprint


def test_motorcycles_and_bicycles_are_two_wheeled_vehicles_in_the_file(entities) -> None:
    _, objects = entities
    for cls, category in ((ActorClass.MOTORCYCLE, "motorbike"), (ActorClass.BICYCLE, "bicycle")):
        (name,) = [n for n in objects if n.endswith(f"_{cls.value}")]
        vehicle = objects[name].find("Vehicle")
        assert vehicle is not None and vehicle.get("vehicleCategory") == category
        speed = vehicle.find("Performance")
        assert speed is not None and float(speed.get("maxSpeed", 0)) < 70  # slower than a car


def test_a_class_the_vocabulary_does_not_know_is_a_misc_object(entities) -> None:
    _, objects = entities
    (name,) = [n for n in objects if n.endswith(f"_{UNKNOWN}")]
    assert objects[name].find("MiscObject") is not None
    assert entity_of(UNKNOWN) is PROP and entity_of("") is PROP


def test_the_entity_table_covers_every_wheeled_class() -> None:
    assert set(VEHICLES) == {cls for cls in ActorClass if cls.is_vehicle}
    assert entity_of("Pedestrian") is PEDESTRIAN
