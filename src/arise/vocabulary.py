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
    def scenic_class(self) -> str:
        """The CARLA model's class for it (`new Car`, `new Pedestrian`, ...)."""
        return self.value.capitalize()


#: Classes an adversary may have (the scenic_class of each AdversaryType, in order).
ADVERSARY_CLASSES: tuple[str, ...] = tuple(kind.scenic_class for kind in AdversaryType)
#: Classes a description may name for an adversary, and the class whose entries fit them
#: (a van drives like a car, a bus like a truck).
REFINED_CLASSES: dict[str, str] = {"Van": "Car", "Bus": "Truck"}
#: Classes of road users in CARLA's Scenic model (and in our offline world model).
ACTOR_CLASSES: tuple[str, ...] = (
    "Car",
    "NPCCar",
    "Truck",
    "Van",
    "Bus",
    "Motorcycle",
    "Bicycle",
    "Pedestrian",
)
#: Static objects of CARLA's Scenic model.
PROP_CLASSES: tuple[str, ...] = (
    "Trash",
    "Cone",
    "Debris",
    "VendingMachine",
    "Chair",
    "BusStop",
    "Advertisement",
    "Garbage",
    "Container",
    "Table",
    "Barrier",
    "PlantPot",
    "Mailbox",
    "Gnome",
    "CreasedBox",
    "Case",
    "Box",
    "Bench",
    "Barrel",
    "ATM",
    "Kiosk",
    "IronPlate",
    "TrafficWarning",
)
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


class StartDetail(StrEnum):
    """A finer point of where the adversary starts, when the description says it: which
    end of the lane beside the ego, or which corner of the street a turning ego enters."""

    FROM_BEHIND = "from_behind"  # comes up from behind ("approaching from behind on its right")
    AHEAD = "ahead"  # ends up ahead of the ego ("merged into its lane ahead of it")
    EXIT_CROSSING = "exit_crossing"  # on the crossing of the street a turning ego enters
    EXIT_FAR_CORNER = "exit_far_corner"  # from that crossing's far corner


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
