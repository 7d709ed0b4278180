"""ScenarioSpec: what module A extracts from a description.

Enums carry the decisions a small model must get right (who, where, which way); they come
from `arise.vocabulary`. Free text carries the details retrieval ranks on. Both are validated, so a nonsense answer is caught
at the boundary instead of deep in the assembler.
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, Field, field_validator

from arise.language.facts import FactSource, GroundedFact
from arise.vocabulary import (
    DEFAULT_WEATHER,
    WEATHER_PRESETS,
    ActorClass,
    ActorRole,
    AdversaryManeuver,
    AdversaryType,
    EgoManeuver,
    EgoPlan,
    RelativePosition,
    RequirementKind,
    RoadType,
    Side,
    StartDetail,
    Timing,
)
from arise.weather import Weather

__all__ = [
    "Actor",
    "ActorRole",
    "AdversaryManeuver",
    "ExtractionAnswer",
    "AdversaryType",
    "EgoManeuver",
    "RelativePosition",
    "Requirement",
    "RequirementKind",
    "RoadType",
    "ScenarioSpec",
]


class Requirement(BaseModel):
    kind: RequirementKind
    text: str = Field(description="the constraint in the description's own words")


class Actor(BaseModel):
    """One road user or object the description names besides the ego and the adversary,
    read by fixed rules from its own words (`quote` is where the text names it)."""

    role: ActorRole
    scenic_class: ActorClass = Field(description="the Scenic class (Car, Van, Bus, Cone, ...)")
    count: int = Field(default=1, ge=1, description="how many the text names")
    count_stated: bool = Field(
        default=True,
        description="the count is stated (a number or one); False for a plural or a group "
        "with no number, which stands for any number of them",
    )
    start: RelativePosition | None = Field(
        default=None, description="where it starts, seen from the ego; None: not stated"
    )
    start_detail: StartDetail | None = Field(
        default=None,
        description="a finer point of its start, when the text gives one (in the lane a "
        "turning ego enters)",
    )
    stationary: bool = Field(default=False, description="the text says it stays put")
    quote: str = Field(description="the words of the description that name it")

    def describe(self) -> str:
        """One line for the CLI: 'actor: 2 Truck, slow, ahead same lane ("Two slow trucks")'."""
        where = self.start.value.replace("_", " ") if self.start else "start not stated"
        still = ", stays put" if self.stationary and self.road_user else ""
        return (
            f"actor: {self.count} {self.scenic_class}, {self.role.value}, {where}{still} "
            f"({self.quote!r})"
        )

    @property
    def road_user(self) -> bool:
        """A vehicle or a pedestrian (which gets its own spawn), not a prop."""
        return self.scenic_class.is_road_user


#: Road types that only the description's words set (see ExtractionAnswer.model_json_schema).
WORDS_ONLY_ROADS = frozenset({RoadType.MERGE.value})


class ExtractionAnswer(BaseModel):
    """What the model is asked for: the parts of the description, in its own words."""

    adversary: str = Field(description="the exact words of the description that name the adversary")
    adversary_type: AdversaryType
    behavior: str = Field(description="the exact words that say what the adversary does")
    road_type: RoadType
    ego_maneuver: EgoManeuver
    geometry: str = Field(description="the exact words about the road and the ego's route")
    spawn_position: RelativePosition
    spawn: str = Field(description="the exact words that say where the adversary starts, or ''")
    participants: list[str] = Field(
        default_factory=list,
        description="the exact words naming each other road user or object, one per item",
    )
    requirements: list[Requirement] = Field(default_factory=list)

    @classmethod
    def model_json_schema(cls, *args: Any, **kwargs: Any) -> dict[str, Any]:
        """The schema the model answers in, without the road types it is never asked for.

        Why: `merge` is read from the description's words ("on-ramp", "merging"), not from
        the model; offering it would also change every recorded extraction request.
        """
        schema = super().model_json_schema(*args, **kwargs)
        road = schema.get("$defs", {}).get(RoadType.__name__)
        if road is not None:
            road["enum"] = [value for value in road["enum"] if value not in WORDS_ONLY_ROADS]
        return schema


class ScenarioSpec(BaseModel):
    """The seven components of a scenario, as the paper splits them, each grounded in the
    description (`grounding` says which words each fact rests on, or that it defaulted)."""

    adversary_type: AdversaryType
    behavior: str = Field(description="what the adversary does, in a short sentence")
    road_type: RoadType
    ego_maneuver: EgoManeuver
    geometry: str = Field(description="the road layout and the ego's route, in words")
    spawn_position: RelativePosition
    spawn: str = Field(description="where the adversary starts relative to the ego, in words")
    adversary_maneuver: AdversaryManeuver = Field(
        default=AdversaryManeuver.UNSTATED,
        description="which way the adversary goes through a junction, if the text says",
    )
    no_adversary: bool = Field(
        default=False,
        description="the text names no road user that causes the danger (debris, a slippery road)",
    )
    adversary_stationary: bool = Field(
        default=False, description="the text says the adversary is parked, stalled or stopped"
    )
    adversary_turns_back: bool = Field(
        default=False,
        description="the text says the adversary goes back the way it came (steps back)",
    )
    ego_lane_side: Side | None = Field(
        default=None, description="the side the ego changes lanes to, if the text says"
    )
    start_detail: StartDetail | None = Field(
        default=None,
        description="which end of the lane beside the ego, or which corner of the street a "
        "turning ego enters, the adversary starts at, if the text says",
    )
    ego_plan: EgoPlan | None = Field(
        default=None,
        description="what the ego does besides driving its route (pull over, bypass, ...)",
    )
    ego_on_ramp: bool = Field(
        default=False, description="the text says the ego comes up an on-ramp and merges"
    )
    quantities_stated: bool = Field(
        default=True,
        description="the text states a number the fixed rules do not place (a time, a "
        "speed of someone else); if not, the script's tunable numbers keep their defaults, "
        "the stated speeds and the timing words aside (no tuning call)",
    )
    ego_speed: float | None = Field(
        default=None, description="the ego's speed in m/s, when the text states it"
    )
    adversary_speed: float | None = Field(
        default=None, description="the adversary's speed in m/s, when the text states it"
    )
    ego_stopped: bool = Field(
        default=False,
        description="the text says the ego stands still (at a red light, in traffic)",
    )
    timing: Timing | None = Field(
        default=None,
        description="when the adversary moves, seen from the ego ('at the last moment' is "
        "late), if the text says: its trigger is then taken from that end of its range",
    )
    contact_stated: bool = Field(
        default=False,
        description="the text says the adversary and the ego touched or nearly did "
        "('struck', 'made contact', 'a near miss'): the run must show contact or a "
        "time-to-collision under 1.5 s",
    )
    participants: list[str] = Field(
        default_factory=list, description="other road users and objects, one per item"
    )
    actors: list[Actor] = Field(
        default_factory=list,
        description="the participants as actors (role, class, count, start), in the same order",
    )
    weather: str = Field(default=DEFAULT_WEATHER, description="a CARLA weather preset")
    weather_parameters: Weather | None = Field(
        default=None,
        description="the full weather when the words need more than a preset (fog, dusk, "
        "glare); `weather` is then its closest preset",
    )
    requirements: list[Requirement] = Field(default_factory=list)
    adversary_class: ActorClass | None = Field(
        default=None, description="the Scenic class the text names (Van, Bus, ...), if any"
    )
    grounding: list[GroundedFact] = Field(default_factory=list)

    def rests_on_words(self, name: str) -> bool:
        """Whether the fact `name` is backed by words of the description (read by a rule or
        quoted by the model), so that a script contradicting it contradicts the text. A spec
        without grounding (an older report) counts every fact as stated."""
        sources = {fact.source for fact in self.grounding if fact.name == name}
        if not self.grounding:
            return True
        return bool(sources & {FactSource.TEXT, FactSource.MODEL})

    @property
    def scenic_class(self) -> ActorClass:
        """The adversary's Scenic class: the one named (a van is a Van), else its type's."""
        return self.adversary_class or self.adversary_type.scenic_class

    @field_validator("weather")
    @classmethod
    def _known_weather(cls, value: str) -> str:
        """Map free words ('rainy night') to a preset; unknown text becomes ClearNoon."""
        if value in WEATHER_PRESETS:
            return value
        words = value.lower()
        rain = (
            "HardRain"
            if "heavy" in words or "hard" in words
            else ("MidRainy" if "rain" in words else None)
        )
        time = (
            "Night"
            if "night" in words or "dark" in words
            else ("Sunset" if "sunset" in words or "dusk" in words else "Noon")
        )
        if rain:
            preset = f"{rain}{time}" if f"{rain}{time}" in WEATHER_PRESETS else f"HardRain{time}"
        elif "wet" in words:
            preset = f"Wet{time}"
        elif "cloud" in words or "overcast" in words or "fog" in words:
            preset = f"Cloudy{time}"
        else:
            preset = f"Clear{time}"
        return preset if preset in WEATHER_PRESETS else DEFAULT_WEATHER
