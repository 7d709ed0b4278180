"""ScenarioSpec: what module A extracts from a description.

Enums carry the decisions a small model must get right (who, where, which way); free text
carries the details retrieval ranks on. Both are validated, so a nonsense answer is caught
at the boundary instead of deep in the assembler.
"""

from __future__ import annotations

from enum import StrEnum

from pydantic import BaseModel, Field, field_validator

from arise.validate.worldmodel.weather import WEATHER_PRESETS


class AdversaryType(StrEnum):
    CAR = "car"
    TRUCK = "truck"
    MOTORCYCLE = "motorcycle"
    BICYCLE = "bicycle"
    PEDESTRIAN = "pedestrian"

    @property
    def scenic_class(self) -> str:
        return {"car": "Car", "truck": "Truck", "motorcycle": "Motorcycle",
                "bicycle": "Bicycle", "pedestrian": "Pedestrian"}[self.value]


class RoadType(StrEnum):
    STRAIGHT = "straight_road"
    INTERSECTION = "intersection"
    T_JUNCTION = "t_junction"
    HIGHWAY = "highway"


class EgoManeuver(StrEnum):
    GO_STRAIGHT = "go_straight"
    TURN_LEFT = "turn_left"
    TURN_RIGHT = "turn_right"
    CHANGE_LANE = "change_lane"


class RelativePosition(StrEnum):
    AHEAD_SAME_LANE = "ahead_same_lane"
    BEHIND_SAME_LANE = "behind_same_lane"
    ADJACENT_LANE_LEFT = "adjacent_lane_left"
    ADJACENT_LANE_RIGHT = "adjacent_lane_right"
    ONCOMING = "oncoming"
    ROADSIDE_RIGHT = "roadside_right"
    ROADSIDE_LEFT = "roadside_left"
    CROSSING_FROM_LEFT = "crossing_road_from_left"
    CROSSING_FROM_RIGHT = "crossing_road_from_right"


class RequirementKind(StrEnum):
    VISIBLE_AT_START = "visible_at_start"
    NOT_VISIBLE_AT_START = "not_visible_at_start"
    DISTANCE_AT_START = "distance_at_start"
    EVENTUALLY_CLOSE = "eventually_close"
    IN_INTERSECTION = "in_intersection"
    SAME_DIRECTION = "same_direction"
    OPPOSITE_DIRECTION = "opposite_direction"


class Requirement(BaseModel):
    kind: RequirementKind
    text: str = Field(description="the constraint in the description's own words")


class ScenarioSpec(BaseModel):
    """The seven components of a scenario, as the paper splits them."""

    adversary_type: AdversaryType
    behavior: str = Field(description="what the adversary does, in a short sentence")
    road_type: RoadType
    ego_maneuver: EgoManeuver
    geometry: str = Field(description="the road layout and the ego's route, in words")
    spawn_position: RelativePosition
    spawn: str = Field(description="where the adversary starts relative to the ego, in words")
    participants: list[str] = Field(default_factory=list,
                                    description="other road users and objects, one per item")
    weather: str = Field(default="ClearNoon", description="a CARLA weather preset")
    requirements: list[Requirement] = Field(default_factory=list)

    @field_validator("weather")
    @classmethod
    def _known_weather(cls, value: str) -> str:
        """Map free words ('rainy night') to a preset; unknown text becomes ClearNoon."""
        if value in WEATHER_PRESETS:
            return value
        words = value.lower()
        rain = "HardRain" if "heavy" in words or "hard" in words else (
            "MidRainy" if "rain" in words else None)
        time = "Night" if "night" in words or "dark" in words else (
            "Sunset" if "sunset" in words or "dusk" in words else "Noon")
        if rain:
            preset = f"{rain}{time}" if f"{rain}{time}" in WEATHER_PRESETS else f"HardRain{time}"
        elif "wet" in words:
            preset = f"Wet{time}"
        elif "cloud" in words or "overcast" in words or "fog" in words:
            preset = f"Cloudy{time}"
        else:
            preset = f"Clear{time}"
        return preset if preset in WEATHER_PRESETS else "ClearNoon"
