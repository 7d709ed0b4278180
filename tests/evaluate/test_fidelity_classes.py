"""Fidelity's labels and observations are ActorClass members: a label names a class of the
model, and what a trace agent is comes from its blueprint, then its class."""

from __future__ import annotations

import math

import pytest

from arise.evaluate.fidelity import DevsetError, LabeledActor, Truth, observed_class
from arise.validate.types import AgentTrace, TracePoint
from arise.vocabulary import ActorClass


def _agent(kind: str, blueprint: str | None = None) -> AgentTrace:
    point = TracePoint(step=0, x=0.0, y=0.0, heading=math.pi / 2, speed=0.0)
    return AgentTrace(
        name="a", kind=kind, blueprint=blueprint, width=1.0, length=2.0, trajectory=[point]
    )


def test_a_labels_class_is_read_as_an_actor_class_and_written_as_its_name() -> None:
    truth = Truth.from_dict({"actors": [{"class": "Motorcycle"}, {"class": "Cone", "count": 2}]})
    assert [a.cls for a in truth.actors] == [ActorClass.MOTORCYCLE, ActorClass.CONE]
    assert [a["class"] for a in truth.as_dict()["actors"]] == ["Motorcycle", "Cone"]
    assert Truth.from_dict(truth.as_dict()) == truth


@pytest.mark.parametrize("bad", ["Motorbike", "car", 5, None, ["Car"]])
def test_a_label_with_no_class_of_the_model_is_one_clear_error(bad: object) -> None:
    with pytest.raises(DevsetError, match=r"actors\[0\]\.class: unknown class"):
        Truth.from_dict({"actors": [{"class": bad}]})


def test_a_labeled_actor_made_in_code_takes_a_name_or_a_class() -> None:
    assert LabeledActor("Truck").cls is ActorClass.TRUCK  # type: ignore[arg-type]
    assert LabeledActor(ActorClass.BUS).cls is ActorClass.BUS
    with pytest.raises(DevsetError, match="unknown class 'Tractor'"):
        LabeledActor("Tractor")  # type: ignore[arg-type]


def test_the_observed_class_is_the_blueprints_then_the_scenic_class() -> None:
    # the blueprint tells: a motorbike blueprint is a Motorcycle whatever the script said
    assert observed_class(_agent("Car", "vehicle.yamaha.yzf")) is ActorClass.MOTORCYCLE
    assert observed_class(_agent("Car", "vehicle.bh.crossbike")) is ActorClass.BICYCLE
    assert observed_class(_agent("Pedestrian", "walker.pedestrian.0001")) is ActorClass.PEDESTRIAN
    assert observed_class(_agent("Cone", "static.prop.constructioncone")) is ActorClass.CONE
    # without a known blueprint the class decides; an NPCCar is a Car to the text
    assert observed_class(_agent("NPCCar")) is ActorClass.CAR
    assert observed_class(_agent("Van", "vehicle.not.in.the.table")) is ActorClass.VAN
    # a class the vocabulary does not know is reported as the trace names it
    assert observed_class(_agent("MyOwnThing")) == "MyOwnThing"
