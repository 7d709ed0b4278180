"""How each Scenic class becomes an OpenSCENARIO entity: its kind, category, height, mass
and the CARLA blueprint ScenarioRunner spawns for it."""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum


class EntityKind(StrEnum):
    VEHICLE = "vehicle"
    PEDESTRIAN = "pedestrian"
    MISC = "misc"


@dataclass(frozen=True)
class ActorClass:
    kind: EntityKind
    category: str  # VehicleCategory / PedestrianCategory / MiscObjectCategory value
    height: float  # metres, when the blueprint table does not know
    mass: float  # kg: OpenSCENARIO wants one, the trace has none
    blueprint: str  # used when the trace names none
    max_speed: float = 70.0  # m/s, the vehicle performance limits a player may enforce


_VEHICLES = {
    "Car": ActorClass(EntityKind.VEHICLE, "car", 1.5, 1500, "vehicle.lincoln.mkz_2017"),
    "NPCCar": ActorClass(EntityKind.VEHICLE, "car", 1.5, 1500, "vehicle.lincoln.mkz_2017"),
    "Truck": ActorClass(EntityKind.VEHICLE, "truck", 3.0, 12000, "vehicle.carlamotors.carlacola"),
    "Van": ActorClass(EntityKind.VEHICLE, "van", 2.0, 2500, "vehicle.mercedes.sprinter"),
    "Bus": ActorClass(EntityKind.VEHICLE, "bus", 4.0, 12000, "vehicle.mitsubishi.fusorosa"),
    "Motorcycle": ActorClass(
        EntityKind.VEHICLE, "motorbike", 1.5, 250, "vehicle.yamaha.yzf", max_speed=50.0
    ),
    "Bicycle": ActorClass(
        EntityKind.VEHICLE, "bicycle", 1.5, 90, "vehicle.bh.crossbike", max_speed=12.0
    ),
}
_PEDESTRIAN = ActorClass(EntityKind.PEDESTRIAN, "pedestrian", 1.8, 80, "walker.pedestrian.0001")
_PROP = ActorClass(EntityKind.MISC, "obstacle", 0.5, 50, "static.prop.streetbarrier")


def actor_class(kind: str) -> ActorClass:
    """The entity of a Scenic class; anything that is no vehicle or walker is a prop."""
    if kind in _VEHICLES:
        return _VEHICLES[kind]
    if kind == "Pedestrian":
        return _PEDESTRIAN
    return _PROP


def height_of(kind: str, blueprint: str | None) -> float:
    """The blueprint's height from CARLA's table (as the world model sizes agents), else
    the class's usual height."""
    default = actor_class(kind).height
    if not blueprint:
        return default
    try:
        from scenic.simulators.carla.blueprints import height
    except ImportError:
        return default
    return float(height(blueprint, default))
