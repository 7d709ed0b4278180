"""The domain vocabulary is one list, and the offline world model has every class in it."""

from __future__ import annotations

import re
from importlib import resources
from pathlib import Path

import pytest

from arise.generate.rules import CLASS_NAMES
from arise.kb.lints import OBJECT_CLASSES
from arise.validate.worldmodel import weather
from arise.vocabulary import (
    ACTOR_CLASSES,
    ADVERSARY_CLASSES,
    POINT_CLASSES,
    PROP_CLASSES,
    REFINED_CLASSES,
    WEATHER_PRESETS,
    ActorClass,
    ActorGroup,
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


# -- the typed cast: ActorClass and its groups ------------------------------------------------

_CARLA_BASES = {"CarlaActor", "Vehicle", "Prop"}  # the model's abstract classes


_TWO_WHEELED_CATEGORIES = ("bicycle", "motorcycle")  # blueprint categories


def _classes_of(model_text: str) -> dict[str, tuple[str, str | None]]:
    """class name -> (its first parent, the blueprint category its body names), from a
    model.scenic's `class X(Parent, ...):` blocks."""
    classes: dict[str, tuple[str, str | None]] = {}
    for block in re.split(r"^(?=class )", model_text, flags=re.M):
        head = re.match(r"class (\w+)\((\w+)", block)
        if head:
            category = re.search(r'blueprintsInCategory\("(\w+)"\)', block)
            classes[head[1]] = (head[2], category[1] if category else None)
    return classes


def _group_by_model(classes: dict[str, tuple[str, str | None]], name: str) -> ActorGroup:
    """The group the model gives a class: by its base class, and a Vehicle whose
    blueprints are bicycles or motorcycles is a two-wheeler."""
    category = classes[name][1]
    while name in classes and name not in ("Vehicle", "Prop", "Pedestrian"):
        name = classes[name][0]
    if name == "Vehicle":
        two = category in _TWO_WHEELED_CATEGORIES
        return ActorGroup.TWO_WHEELER if two else ActorGroup.VEHICLE
    return ActorGroup.PROP if name == "Prop" else ActorGroup.WALKER


def _carla_model_text() -> str:
    import scenic

    return (Path(scenic.__file__).parent / "simulators" / "carla" / "model.scenic").read_text()


def _world_model_text() -> str:
    return resources.files("arise.validate.worldmodel").joinpath("model.scenic").read_text()


@pytest.mark.parametrize("text", [_carla_model_text, _world_model_text], ids=["carla", "ours"])
def test_actor_class_is_exactly_the_concrete_classes_of_the_model(text) -> None:
    classes = _classes_of(text())
    concrete = {name for name in classes if name not in _CARLA_BASES} - set(POINT_CLASSES)
    assert concrete == {cls.value for cls in ActorClass}


@pytest.mark.parametrize("text", [_carla_model_text, _world_model_text], ids=["carla", "ours"])
def test_each_group_follows_the_models_class_hierarchy(text) -> None:
    classes = _classes_of(text())
    for cls in ActorClass:
        assert cls.group is _group_by_model(classes, cls.value), cls


def test_every_class_has_a_group_and_the_groups_partition_them() -> None:
    groups = {group: {cls for cls in ActorClass if cls.group is group} for group in ActorGroup}
    assert all(groups.values())  # no empty group
    assert groups[ActorGroup.TWO_WHEELER] == {ActorClass.MOTORCYCLE, ActorClass.BICYCLE}
    assert groups[ActorGroup.WALKER] == {ActorClass.PEDESTRIAN}
    assert groups[ActorGroup.VEHICLE] == {
        ActorClass.CAR,
        ActorClass.NPC_CAR,
        ActorClass.TRUCK,
        ActorClass.VAN,
        ActorClass.BUS,
    }
    for cls in ActorClass:
        assert cls.is_vehicle == (cls.group in (ActorGroup.VEHICLE, ActorGroup.TWO_WHEELER))
        assert cls.is_road_user == (cls.is_vehicle or cls.is_walker)
        assert cls.is_prop != cls.is_road_user


def test_two_wheelers_are_the_models_motorcycle_and_bicycle_blueprints() -> None:
    import scenic.simulators.carla.blueprints as table

    categories = {"motorcycle": ActorClass.MOTORCYCLE, "bicycle": ActorClass.BICYCLE}
    for category, cls in categories.items():
        assert cls.is_two_wheeler and cls.is_vehicle and not cls.is_walker
        assert getattr(table, f"{category}Models")  # CARLA has blueprints for it


def test_the_derived_lists_are_the_groupings_as_plain_names() -> None:
    assert tuple(c.value for c in ActorClass if c.is_road_user) == ACTOR_CLASSES
    assert tuple(c.value for c in ActorClass if c.is_prop) == PROP_CLASSES
    assert all(type(name) is str for name in ACTOR_CLASSES + PROP_CLASSES + ADVERSARY_CLASSES)
    assert REFINED_CLASSES == {"Van": "Car", "Bus": "Truck"}
    assert ActorClass.VAN.as_adversary is ActorClass.CAR
    assert ActorClass.PEDESTRIAN.as_adversary is ActorClass.PEDESTRIAN
    assert [c for c in ActorClass if c.is_adversary] == [
        kind.scenic_class for kind in AdversaryType
    ]
    assert isinstance(AdversaryType.MOTORCYCLE.scenic_class, ActorClass)


@pytest.mark.parametrize("text", ["Object", "car", "", "Car ", None, 3, ["Car"], {"a": 1}])
def test_of_refuses_anything_but_a_class_name_without_raising(text: object) -> None:
    assert ActorClass.of(text) is None
    assert ActorClass.of("Motorcycle") is ActorClass.MOTORCYCLE


@pytest.mark.slow  # compiles through Scenic and prepares a map
def test_every_class_is_creatable_by_new_on_a_real_map_with_a_blueprint_of_its_group() -> None:
    import scenic

    from arise.maps.registry import MapRegistry
    from arise.validate.map_cache import prepare_map
    from arise.validate.worker import OFFLINE_MODEL
    from arise.validate.worldmodel.blueprints import _required_prefixes, check_blueprint

    choice = MapRegistry(None).resolve("arise_straight")
    prepare_map(Path(choice.path))
    lines = [
        "param map = localPath('straight.xodr')",
        "model scenic.simulators.carla.model",
        "ego = new Car on road",
    ]
    for cls in ActorClass:
        where = "on sidewalk" if cls.is_walker else "on road"
        lines.append(f"new {cls.value} {where}, with allowCollisions True")
    scenario = scenic.scenarioFromString(
        "\n".join(lines) + "\n",
        params={"map": choice.path, "carla_map": choice.name},
        model=OFFLINE_MODEL,
        mode2D=True,
    )
    scene, _ = scenario.generate(maxIterations=200)
    created = {ActorClass.of(type(obj).__name__): obj for obj in scene.objects[1:]}
    assert set(created) == set(ActorClass)
    prefix = {
        ActorGroup.VEHICLE: "vehicle.",
        ActorGroup.TWO_WHEELER: "vehicle.",
        ActorGroup.WALKER: "walker.",
        ActorGroup.PROP: "static.",
    }
    import scenic.simulators.carla.blueprints as table

    two_wheeled = {*table.motorcycleModels, *table.bicycleModels}
    for cls, obj in created.items():
        assert obj.blueprint.startswith(prefix[cls.group]), (cls, obj.blueprint)
        assert _required_prefixes(obj) == (prefix[cls.group],)
        check_blueprint(obj)  # the world model accepts what it chose
        assert (obj.blueprint in two_wheeled) == cls.is_two_wheeler, (cls, obj.blueprint)
