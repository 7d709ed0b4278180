"""What a knowledge-base entry is: a validated description-snippet pair with its interface.

An entry states what it defines and needs, so the assembler can tell which entries compose
without reading their code, and the validator can prove every entry runs.
"""

from __future__ import annotations

import re
from enum import StrEnum

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from arise.vocabulary import (
    ADVERSARY_CLASSES,
    MAP_FEATURES,
    ActorClass,
    AdversaryManeuver,
    Approach,
)


class Component(StrEnum):
    """The six kinds of snippet; their order is the order of the script's sections."""

    WEATHER = "weather"
    BEHAVIOR = "behavior"
    GEOMETRY = "geometry"
    SPAWN = "spawn"
    MISC = "misc"
    REQUIREMENTS = "requirements"

    @property
    def section(self) -> str:
        """The `# BEGIN NAME` section this component's snippets go into."""
        return self.value.upper()


COMPONENT_ORDER: tuple[Component, ...] = tuple(Component)


ID_PATTERN = re.compile(r"^[a-z][a-z0-9_]*(\.[a-z0-9_]+)*$")
NAME_PATTERN = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
PLACEHOLDER_PATTERN = re.compile(r"\{\{([A-Z][A-Z0-9_]*)\}\}")
#: The name a geometry defines for the route its adversary should take; a spawn that needs
#: it puts the adversary on that route, so the geometry decides the adversary's side.
CONFLICT_ROUTE = "conflictManeuver"
#: Components that may say where the adversary comes from and which way it goes.
SIDED_COMPONENTS = frozenset(
    {Component.GEOMETRY, Component.SPAWN, Component.BEHAVIOR, Component.MISC}
)


class Entry(BaseModel):
    """One description-snippet pair of one component."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    id: str = Field(description="unique id, lower_snake_case, e.g. 'behavior.sudden_brake'")
    component: Component
    descriptions: list[str] = Field(
        min_length=1, description="natural-language descriptions (paraphrases)"
    )
    snippet: str = Field(min_length=1, description="Scenic 3 code of this entry's section")
    defines: list[str] = Field(default_factory=list, description="global names the snippet defines")
    needs: list[str] = Field(
        default_factory=list, description="names the snippet uses that other entries define"
    )
    params: list[str] = Field(
        default_factory=list, description="the OPT_* global parameters the snippet declares"
    )
    placeholders: list[str] = Field(
        default_factory=list, description="{{NAME}} placeholders the assembler fills"
    )
    adversaries: list[ActorClass] = Field(
        default_factory=list, description="adversary classes it suits (empty: any)"
    )
    map_features: list[str] = Field(
        default_factory=list, description="map features the snippet needs"
    )
    tags: list[str] = Field(default_factory=list)
    companions: list[str] = Field(
        default_factory=list,
        description="ids of entries it is known to compose well with (tried first when "
        "validating; a hint for the generator)",
    )
    approach: Approach | None = Field(
        default=None,
        description="where the adversary comes from, seen from the ego (geometry: the start "
        "of its conflict route; spawn: where it places the adversary; misc: where its road "
        "user stands); None: not fixed",
    )
    adversary_maneuver: AdversaryManeuver | None = Field(
        default=None,
        description="which way the adversary goes through the junction (geometry: its "
        "conflict route; behavior: the turn it acts out); None: any",
    )
    source: str | None = Field(
        default=None, description="file the entry came from (set by the loader)"
    )
    actor: str | None = Field(
        default=None,
        description="set on a copy made by `arise.kb.actors.for_actor`: the other actor "
        "('actor2') it places or moves instead of the adversary; never in the data files",
    )
    actor_class: ActorClass | None = Field(
        default=None, description="that actor's Scenic class, a road user's (set with `actor`)"
    )
    row: str | None = Field(
        default=None,
        description="set on a copy made by `arise.kb.props.prop_row`: the suffix ('P2') of "
        "its names, one per obstacle of the scene; never in the data files",
    )

    @field_validator("id")
    @classmethod
    def _id_shape(cls, value: str) -> str:
        if not ID_PATTERN.match(value):
            raise ValueError(
                "must be lower_snake_case words joined by dots, e.g. 'behavior.sudden_brake'"
            )
        return value

    @field_validator("descriptions")
    @classmethod
    def _descriptions_not_blank(cls, value: list[str]) -> list[str]:
        if any(not text.strip() for text in value):
            raise ValueError("descriptions must not be blank")
        return [" ".join(text.split()) for text in value]

    @field_validator("defines", "needs")
    @classmethod
    def _names(cls, value: list[str]) -> list[str]:
        bad = [name for name in value if not NAME_PATTERN.match(name)]
        if bad:
            raise ValueError(f"not a Scenic name: {', '.join(bad)}")
        return value

    @field_validator("params")
    @classmethod
    def _params(cls, value: list[str]) -> list[str]:
        bad = [name for name in value if not re.match(r"^OPT_[A-Z0-9_]+$", name)]
        if bad:
            raise ValueError(f"params must be named OPT_<UPPER_CASE>: {', '.join(bad)}")
        return value

    @field_validator("placeholders")
    @classmethod
    def _placeholders(cls, value: list[str]) -> list[str]:
        bad = [name for name in value if not re.match(r"^[A-Z][A-Z0-9_]*$", name)]
        if bad:
            raise ValueError(f"placeholders are UPPER_CASE names: {', '.join(bad)}")
        return value

    @field_validator("adversaries", mode="before")
    @classmethod
    def _adversaries(cls, value: object) -> object:
        """Checked before the enum's own check, so the error lists the five adversary
        classes rather than every class of the model."""
        if isinstance(value, list):
            bad = [str(name) for name in value if name not in ADVERSARY_CLASSES]
            if bad:
                raise ValueError(
                    f"unknown adversary class {', '.join(bad)}; choose from "
                    f"{', '.join(ADVERSARY_CLASSES)}"
                )
        return value

    @field_validator("actor", "row")
    @classmethod
    def _copy_name(cls, value: str | None) -> str | None:
        # it is written into the script's `# kb:` mark: one plain word, never more
        if value is not None and not re.fullmatch(r"[A-Za-z][A-Za-z0-9]{0,15}", value):
            raise ValueError(f"{value!r} is not a plain name like 'actor2' or 'P2'")
        return value

    @field_validator("actor_class")
    @classmethod
    def _road_user(cls, value: ActorClass | None) -> ActorClass | None:
        if value is not None and not value.is_road_user:
            raise ValueError(f"{value} is a prop, not a road user's class")
        return value

    @field_validator("map_features")
    @classmethod
    def _features(cls, value: list[str]) -> list[str]:
        bad = [name for name in value if name not in MAP_FEATURES]
        if bad:
            raise ValueError(
                f"unknown map feature {', '.join(bad)}; choose from {', '.join(MAP_FEATURES)}"
            )
        return value

    @field_validator("adversary_maneuver")
    @classmethod
    def _stated_maneuver(cls, value: AdversaryManeuver | None) -> AdversaryManeuver | None:
        if value is AdversaryManeuver.UNSTATED:
            raise ValueError("leave adversary_maneuver out when the entry fixes no maneuver")
        return value

    @model_validator(mode="after")
    def _sides_only_where_they_mean_something(self) -> Entry:
        """Side and maneuver belong to the entries that place or move the adversary; a
        geometry states them for its conflict route, so it must define one."""
        stated = self.approach is not None or self.adversary_maneuver is not None
        if stated and self.component not in SIDED_COMPONENTS:
            raise ValueError(f"a {self.component.value} entry cannot state approach or maneuver")
        if self.component is Component.MISC and self.adversary_maneuver is not None:
            raise ValueError("a misc entry moves no adversary: drop its adversary_maneuver")
        if self.component is Component.BEHAVIOR and self.approach is not None:
            raise ValueError("a behavior does not place the adversary: drop its approach")
        if stated and self.component is Component.GEOMETRY and CONFLICT_ROUTE not in self.defines:
            raise ValueError(
                f"a geometry states approach or maneuver only for the {CONFLICT_ROUTE} it defines"
            )
        return self

    @property
    def label(self) -> str:
        """How the script's `# kb:` mark names it: the id, and the actor or row a copy places."""
        copy = self.actor or self.row
        return f"{self.id} as {copy}" if copy else self.id

    def suits(self, adversary_class: ActorClass) -> bool:
        """True when this entry works with that adversary class."""
        return not self.adversaries or adversary_class in self.adversaries

    @property
    def search_text(self) -> str:
        """What retrieval indexes: the descriptions and tags (never the code)."""
        return " ".join([*self.descriptions, *(tag.replace("_", " ") for tag in self.tags)])
