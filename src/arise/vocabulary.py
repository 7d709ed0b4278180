"""The domain's words, in one place: who takes part, where they start, what the ego does,
which roads and weathers exist.

The spec (what extraction fills), the knowledge-base schema (what entries declare), the
repair rules and the offline world model all import these, so a new adversary class or
weather preset is added here once. This module imports nothing from arise.
"""

from __future__ import annotations

from enum import StrEnum

# -- who ------------------------------------------------------------------------------------


# No docstrings on these enums: their JSON schema is part of the extraction request, and
# recorded cassettes (and caches) are keyed on it.
class AdversaryType(StrEnum):
    CAR = "car"
    TRUCK = "truck"
    MOTORCYCLE = "motorcycle"
    BICYCLE = "bicycle"
    PEDESTRIAN = "pedestrian"

    @property
    def scenic_class(self) -> ActorClass:
        """The CARLA model's class for it (`new Car`, `new Pedestrian`, ...)."""
        return ActorClass(self.value.capitalize())


class ActorGroup(StrEnum):
    """How consumers tell the classes apart: what a renderer draws, what an exporter
    declares and what a check may ask of an actor (a walker has no throttle, a prop no
    route)."""

    VEHICLE = "vehicle"  # four-wheeled motor vehicles
    TWO_WHEELER = "two_wheeler"  # motorcycles and bicycles: steered like vehicles, slimmer
    WALKER = "walker"  # pedestrians
    PROP = "prop"  # static objects


class ActorClass(StrEnum):
    """Every class of CARLA's Scenic model (and our offline world model) that a script may
    create for a road user or a prop; its value is the class name in `new X`.

    Code outside the extraction schema compares these, never bare class-name strings."""

    CAR = "Car"
    NPC_CAR = "NPCCar"
    TRUCK = "Truck"
    VAN = "Van"
    BUS = "Bus"
    MOTORCYCLE = "Motorcycle"
    BICYCLE = "Bicycle"
    PEDESTRIAN = "Pedestrian"
    TRASH = "Trash"
    CONE = "Cone"
    DEBRIS = "Debris"
    VENDING_MACHINE = "VendingMachine"
    CHAIR = "Chair"
    BUS_STOP = "BusStop"
    ADVERTISEMENT = "Advertisement"
    GARBAGE = "Garbage"
    CONTAINER = "Container"
    TABLE = "Table"
    BARRIER = "Barrier"
    PLANT_POT = "PlantPot"
    MAILBOX = "Mailbox"
    GNOME = "Gnome"
    CREASED_BOX = "CreasedBox"
    CASE = "Case"
    BOX = "Box"
    BENCH = "Bench"
    BARREL = "Barrel"
    ATM = "ATM"
    KIOSK = "Kiosk"
    IRON_PLATE = "IronPlate"
    TRAFFIC_WARNING = "TrafficWarning"

    @classmethod
    def of(cls, name: object) -> ActorClass | None:
        """The member named `name` (a class name from a script, a trace, a label or an
        entry), or None for anything else (Scenic's own Object/Point, a typo, a value of
        the wrong type: untrusted input never raises here)."""
        if not isinstance(name, str):
            return None
        try:
            return cls(name)
        except ValueError:
            return None

    @property
    def group(self) -> ActorGroup:
        """Which group the class belongs to."""
        return _GROUPS.get(self, ActorGroup.PROP)

    @property
    def is_vehicle(self) -> bool:
        """A wheeled road user: cars, trucks, vans, buses, motorcycles and bicycles."""
        return self.group in (ActorGroup.VEHICLE, ActorGroup.TWO_WHEELER)

    @property
    def is_two_wheeler(self) -> bool:
        return self.group is ActorGroup.TWO_WHEELER

    @property
    def is_walker(self) -> bool:
        return self.group is ActorGroup.WALKER

    @property
    def is_prop(self) -> bool:
        return self.group is ActorGroup.PROP

    @property
    def is_road_user(self) -> bool:
        """Moves in traffic (a vehicle or a walker), as against a prop."""
        return not self.is_prop

    @property
    def is_place(self) -> bool:
        """A prop that names where others stand ("a bus standing at a bus stop on the
        right"): the words after it still belong to the road user named before it."""
        return self is ActorClass.BUS_STOP

    @property
    def is_adversary(self) -> bool:
        """One of the classes an extracted adversary may have (see AdversaryType)."""
        return self in ADVERSARY_CLASSES

    @property
    def as_adversary(self) -> ActorClass:
        """The class whose knowledge-base entries act it out: a van drives like a car, a
        bus like a truck; every other class is itself."""
        return _REFINED.get(self, self)


_GROUPS: dict[ActorClass, ActorGroup] = {
    ActorClass.CAR: ActorGroup.VEHICLE,
    ActorClass.NPC_CAR: ActorGroup.VEHICLE,
    ActorClass.TRUCK: ActorGroup.VEHICLE,
    ActorClass.VAN: ActorGroup.VEHICLE,
    ActorClass.BUS: ActorGroup.VEHICLE,
    ActorClass.MOTORCYCLE: ActorGroup.TWO_WHEELER,
    ActorClass.BICYCLE: ActorGroup.TWO_WHEELER,
    ActorClass.PEDESTRIAN: ActorGroup.WALKER,
}  # every other member is a prop
_REFINED: dict[ActorClass, ActorClass] = {
    ActorClass.VAN: ActorClass.CAR,
    ActorClass.BUS: ActorClass.TRUCK,
}


# The tuples below are ActorClass's groupings as plain names, for code that matches text
# (regexes, lints, the rules' class list) and for what recorded cassettes hold.

#: Classes an adversary may have (the scenic_class of each AdversaryType, in order).
ADVERSARY_CLASSES: tuple[str, ...] = tuple(kind.scenic_class.value for kind in AdversaryType)
#: Classes a description may name for an adversary, and the class whose entries fit them
#: (a van drives like a car, a bus like a truck).
REFINED_CLASSES: dict[str, str] = {cls.value: cls.as_adversary.value for cls in _REFINED}
#: Classes of road users in CARLA's Scenic model (and in our offline world model).
ACTOR_CLASSES: tuple[str, ...] = tuple(cls.value for cls in ActorClass if cls.is_road_user)
#: Static objects of CARLA's Scenic model.
PROP_CLASSES: tuple[str, ...] = tuple(cls.value for cls in ActorClass if cls.is_prop)
#: Scenic's own classes a script may create.
POINT_CLASSES: tuple[str, ...] = ("Object", "Point", "OrientedPoint")

# -- where ----------------------------------------------------------------------------------


class RoadType(StrEnum):
    STRAIGHT = "straight_road"
    INTERSECTION = "intersection"
    T_JUNCTION = "t_junction"
    HIGHWAY = "highway"
    MERGE = "merge"  # a highway where an on-ramp joins (read from words, not asked of the model)


class RelativePosition(StrEnum):  # where the adversary starts, seen from the ego
    AHEAD_SAME_LANE = "ahead_same_lane"
    BEHIND_SAME_LANE = "behind_same_lane"
    ADJACENT_LANE_LEFT = "adjacent_lane_left"
    ADJACENT_LANE_RIGHT = "adjacent_lane_right"
    ONCOMING = "oncoming"
    ROADSIDE_RIGHT = "roadside_right"
    ROADSIDE_LEFT = "roadside_left"
    CROSSING_FROM_LEFT = "crossing_road_from_left"
    CROSSING_FROM_RIGHT = "crossing_road_from_right"


#: The starts of a road user that crosses the ego's road from a side.
CROSSING_STARTS = frozenset(
    {RelativePosition.CROSSING_FROM_LEFT, RelativePosition.CROSSING_FROM_RIGHT}
)


class StartDetail(StrEnum):
    """A finer point of where the adversary starts, when the description says it: which
    end of the lane beside the ego, which corner of the street a turning ego enters, or
    that it waits in the lane that ego turns into."""

    FROM_BEHIND = "from_behind"  # comes up from behind ("approaching from behind on its right")
    AHEAD = "ahead"  # ends up ahead of the ego ("merged into its lane ahead of it")
    EXIT_CROSSING = "exit_crossing"  # on the crossing of the street a turning ego enters
    EXIT_FAR_CORNER = "exit_far_corner"  # from that crossing's far corner
    EXIT_LANE = "exit_lane"  # ahead in the lane a turning ego enters ("just past the corner")


class ActorRole(StrEnum):
    """What a road user or object is for in a scene (the adversary causes the danger)."""

    ADVERSARY = "adversary"
    LEAD = "lead"  # drives ahead of the ego in its lane
    SLOW = "slow"  # a slow vehicle the ego may have to pass
    STOPPED = "stopped"  # stalled, broken down or stopped in the road
    PARKED = "parked"  # parked at the roadside
    ONCOMING = "oncoming"  # comes the other way
    CROSSING = "crossing"  # crosses the ego's path (or waits to)
    FOLLOWING = "following"  # behind the ego
    OCCLUDER = "occluder"  # hides the adversary from the ego
    OBSTACLE = "obstacle"  # a prop in or beside the road


#: Features a map may have and a knowledge-base entry may need.
MAP_FEATURES: tuple[str, ...] = (
    "straight",
    "multilane",
    "sidewalk",
    "intersection4",
    "tjunction",
    "signalized",
    "highway",
    "curve",
    "merge",  # an on-ramp whose lane joins the rightmost lane of a multi-lane road
)


class Approach(StrEnum):
    """Where an adversary comes from, seen from the ego at the start. Knowledge-base entries
    state it so that retrieval can honour the side a description asks for."""

    LEFT = "left"  # crosses the ego's path from its left (a road from the left, the left kerb)
    RIGHT = "right"  # crosses the ego's path from its right
    OPPOSITE = "opposite"  # oncoming, driving toward the ego
    AHEAD = "same_direction_ahead"  # in the ego's lane or route, ahead of it
    BEHIND = "same_direction_behind"  # in the ego's lane, behind it
    ADJACENT_LEFT = "adjacent_left"  # same direction, in the lane to the ego's left
    ADJACENT_RIGHT = "adjacent_right"  # same direction, in the lane to the ego's right
    ROADSIDE_LEFT = "roadside_left"  # stays beside the road on the left (parked, walking along)
    ROADSIDE_RIGHT = "roadside_right"  # stays beside the road on the right
    # on the side the ego turns to: the street a turning ego enters (its kerbs and crossing)
    TURN_SIDE = "turn_side"


# -- what the ego does ----------------------------------------------------------------------


class EgoManeuver(StrEnum):
    GO_STRAIGHT = "go_straight"
    TURN_LEFT = "turn_left"
    TURN_RIGHT = "turn_right"
    CHANGE_LANE = "change_lane"


class EgoPlan(StrEnum):
    """What the ego does besides driving its route, when the description says so; each is
    a tag of the geometry entries that act it out."""

    CHANGE_AND_RETURN = "ego_returns"  # changes lanes, then back to its own
    BYPASS = "ego_bypass"  # goes round a blocker through the oncoming lane, then back
    STOP_THEN_GO = "ego_stop_then_go"  # stops at the stop line or a red light, then goes
    YIELD_THEN_GO = "ego_yields"  # waits for the way to be clear, then turns or goes
    PULL_OVER = "ego_pulls_over"  # pulls over to the kerb and stops


class Timing(StrEnum):
    """When the adversary makes its move, seen from the ego, when the description says."""

    LATE = "late"  # at the last moment: "just as the ego passes", "without warning"
    EARLY = "early"  # with time to spare: "well ahead", "in the distance"


class Unit(StrEnum):
    """The unit of a number the description states ("17 mph", "30 feet")."""

    MPH = "mph"
    KMH = "kmh"
    MPS = "mps"
    METRE = "metre"
    FOOT = "foot"
    YARD = "yard"
    SECOND = "second"

    @property
    def is_speed(self) -> bool:
        return self in (Unit.MPH, Unit.KMH, Unit.MPS)

    @property
    def is_distance(self) -> bool:
        return self in (Unit.METRE, Unit.FOOT, Unit.YARD)

    @property
    def in_si(self) -> float:
        """One of this unit in metres, metres per second or seconds."""
        return _SI[self]


_SI = {
    Unit.MPH: 0.44704,
    Unit.KMH: 1 / 3.6,
    Unit.MPS: 1.0,
    Unit.METRE: 1.0,
    Unit.FOOT: 0.3048,
    Unit.YARD: 0.9144,
    Unit.SECOND: 1.0,
}


# A constraint the description states in words (a requirement the semantic gate checks).
# No docstring: it would change the extraction schema the model is given.
class RequirementKind(StrEnum):
    VISIBLE_AT_START = "visible_at_start"
    NOT_VISIBLE_AT_START = "not_visible_at_start"
    DISTANCE_AT_START = "distance_at_start"
    EVENTUALLY_CLOSE = "eventually_close"
    IN_INTERSECTION = "in_intersection"
    SAME_DIRECTION = "same_direction"
    OPPOSITE_DIRECTION = "opposite_direction"


class Side(StrEnum):
    """Which way the ego changes lanes, when the description says."""

    LEFT = "left"
    RIGHT = "right"


class AdversaryManeuver(StrEnum):
    """Which way the adversary goes through a junction, when the description says so."""

    UNSTATED = "unstated"
    STRAIGHT = "straight"
    TURN_LEFT = "turn_left"
    TURN_RIGHT = "turn_right"


# -- weather (CARLA 0.9.16) -----------------------------------------------------------------

WEATHER_PRESETS: tuple[str, ...] = (
    "ClearNoon",
    "CloudyNoon",
    "WetNoon",
    "WetCloudyNoon",
    "SoftRainNoon",
    "MidRainyNoon",
    "HardRainNoon",
    "ClearSunset",
    "CloudySunset",
    "WetSunset",
    "WetCloudySunset",
    "SoftRainSunset",
    "MidRainSunset",
    "HardRainSunset",
    "ClearNight",
    "CloudyNight",
    "WetNight",
    "WetCloudyNight",
    "SoftRainNight",
    "MidRainyNight",
    "HardRainNight",
    "DustStorm",
    "Default",
)
WEATHER_FIELDS: tuple[str, ...] = (
    "cloudiness",
    "precipitation",
    "precipitation_deposits",
    "wind_intensity",
    "sun_azimuth_angle",
    "sun_altitude_angle",
    "fog_density",
    "fog_distance",
    "fog_falloff",
    "wetness",
    "scattering_intensity",
    "mie_scattering_scale",
    "rayleigh_scattering_scale",
    "dust_storm",
)
DEFAULT_WEATHER = "ClearNoon"


#: The paper's eight scenario categories, in the order of its Table I.
PAPER_CATEGORIES: tuple[str, ...] = (
    "straight_obstacle",
    "turning_obstacle",
    "lane_changing",
    "vehicle_passing",
    "red_light_running",
    "unprotected_left_turn",
    "right_turn",
    "crossing_negotiation",
)
