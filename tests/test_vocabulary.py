"""The domain vocabulary is one list, and the offline world model has every class in it."""

from __future__ import annotations

import re
from importlib import resources

from arise.generate.rules import CLASS_NAMES
from arise.kb.lints import OBJECT_CLASSES
from arise.validate.worldmodel import weather
from arise.vocabulary import (
    ACTOR_CLASSES,
    ADVERSARY_CLASSES,
    POINT_CLASSES,
    PROP_CLASSES,
    WEATHER_PRESETS,
    AdversaryType,
)


def test_every_carla_class_is_defined_by_the_offline_world_model() -> None:
    model = resources.files("arise.validate.worldmodel").joinpath("model.scenic").read_text()
    defined = set(re.findall(r"^class (\w+)", model, re.M))
    assert set(ACTOR_CLASSES) | set(PROP_CLASSES) <= defined
    assert set(ADVERSARY_CLASSES) <= set(ACTOR_CLASSES)


def test_adversary_classes_follow_the_adversary_types() -> None:
    assert ADVERSARY_CLASSES == ("Car", "Truck", "Motorcycle", "Bicycle", "Pedestrian")
    assert AdversaryType.PEDESTRIAN.scenic_class == "Pedestrian"


def test_the_users_of_the_vocabulary_read_the_same_lists() -> None:
    assert set(CLASS_NAMES) == set(ACTOR_CLASSES + POINT_CLASSES + PROP_CLASSES)
    assert set(CLASS_NAMES) | {"Prop"} <= set(OBJECT_CLASSES)
    assert weather.WEATHER_PRESETS is WEATHER_PRESETS
