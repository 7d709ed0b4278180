"""How each Scenic class becomes an OpenSCENARIO entity: its kind, category, height, mass
and the CARLA blueprint ScenarioRunner spawns for it."""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from arise.vocabulary import ActorClass


class EntityKind(StrEnum):
    """The three kinds of ScenarioObject OpenSCENARIO has."""

    VEHICLE = "vehicle"
    PEDESTRIAN = "pedestrian"
    MISC = "misc"


@dataclass(frozen=True)
class Entity:
    """What the exporter writes for one class."""

    kind: EntityKind
    category: str  # VehicleCategory / PedestrianCategory / MiscObjectCategory value
    height: float  # metres, when the blueprint table does not know
    mass: float  # kg: OpenSCENARIO wants one, the trace has none
    blueprint: str  # used when the trace names none
    max_speed: float = 70.0  # m/s, the vehicle performance limits a player may enforce


_CAR = Entity(EntityKind.VEHICLE, "car", 1.5, 1500, "vehicle.lincoln.mkz_2017")
#: Every wheeled class (ActorClass.is_vehicle): four-wheeled and two-wheeled.
VEHICLES: dict[ActorClass, Entity] = {
    ActorClass.CAR: _CAR,
    ActorClass.NPC_CAR: _CAR,
    ActorClass.TRUCK: Entity(
        EntityKind.VEHICLE, "truck", 3.0, 12000, "vehicle.carlamotors.carlacola"
    ),
    ActorClass.VAN: Entity(EntityKind.VEHICLE, "van", 2.0, 2500, "vehicle.mercedes.sprinter"),
    ActorClass.BUS: Entity(EntityKind.VEHICLE, "bus", 4.0, 12000, "vehicle.mitsubishi.fusorosa"),
    ActorClass.MOTORCYCLE: Entity(
        EntityKind.VEHICLE, "motorbike", 1.5, 250, "vehicle.yamaha.yzf", max_speed=50.0
    ),
    ActorClass.BICYCLE: Entity(
        EntityKind.VEHICLE, "bicycle", 1.5, 90, "vehicle.bh.crossbike", max_speed=12.0
    ),
}
PEDESTRIAN = Entity(EntityKind.PEDESTRIAN, "pedestrian", 1.8, 80, "walker.pedestrian.0001")
PROP = Entity(EntityKind.MISC, "obstacle", 0.5, 50, "static.prop.streetbarrier")


def entity_of(kind: str) -> Entity:
    """The entity of a Scenic class named in a trace (untrusted text): a vehicle's or a
    walker's; anything else, a prop or a class the vocabulary does not know, is a prop."""
    cls = ActorClass.of(kind)
    if cls is None or cls.is_prop:
        return PROP
    if cls.is_walker:
        return PEDESTRIAN
    return VEHICLES[cls]


def height_of(kind: str, blueprint: str | None) -> float:
    """The blueprint's height from CARLA's table (as the world model sizes agents), else
    the class's usual height."""
    default = entity_of(kind).height
    if not blueprint:
        return default
    try:
        from scenic.simulators.carla.blueprints import height
    except ImportError:
        return default
    return float(height(blueprint, default))
