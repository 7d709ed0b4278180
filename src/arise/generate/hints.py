"""Keyword evidence for the spec's enums, used to overrule a small model's guesses.

The 1.5B model follows the JSON format reliably but often picks the wrong side, lane or
road type. Where the description states these plainly ("from the left", "oncoming",
"highway", "turns right"), the words win; where it is silent, the model's answer stands.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from arise.generate.spec import Requirement, RequirementKind, ScenarioSpec
from arise.vocabulary import AdversaryType, EgoManeuver, RelativePosition, RoadType

_ADVERSARY = [
    (AdversaryType.PEDESTRIAN, r"pedestrian|walker|person|child|kid|man|woman|jogger|people"),
    (AdversaryType.BICYCLE, r"cyclist|bicycle|bike(?!r)|biker"),
    (AdversaryType.MOTORCYCLE, r"motorcycl\w*|motorbike|motorcyclist|scooter|moped"),
    (AdversaryType.TRUCK, r"truck|lorry|semi|bus"),
    (AdversaryType.CAR, r"car|vehicle|van|suv|sedan|taxi"),
]
_ROAD = [
    (RoadType.HIGHWAY, r"highway|motorway|freeway|expressway"),
    (RoadType.T_JUNCTION, r"t-junction|t junction|t-intersection"),
    (
        RoadType.INTERSECTION,
        r"intersection|junction|crossroads|crossing road|red light|"
        r"traffic light|signal|turns? (left|right)|(left|right) turn",
    ),
]
_MANEUVER = [
    (
        EgoManeuver.TURN_LEFT,
        r"ego\w*(?: \w+){0,4} (turns?|turning|makes a|performs an?"
        r"(?: unprotected)?) left|(?:unprotected )?left turn|unprotected left",
    ),
    (
        EgoManeuver.TURN_RIGHT,
        r"ego\w*(?: \w+){0,4} (turns?|turning|makes a|takes a) right|"
        r"right turn",
    ),
    (
        EgoManeuver.CHANGE_LANE,
        r"ego\w*(?: \w+){0,4} chang\w* (?:to the \w+ )?lanes?|"
        r"ego wants to change",
    ),
]
_SPAWN = [
    (
        RelativePosition.ONCOMING,
        r"oncoming|opposite direction|coming the other way|"
        r"from the opposite",
    ),
    (RelativePosition.CROSSING_FROM_LEFT, r"from the left(?! sidewalk)|left side of the"),
    (RelativePosition.CROSSING_FROM_RIGHT, r"from the right(?! sidewalk)|from right"),
    (
        RelativePosition.ROADSIDE_RIGHT,
        r"right sidewalk|parked (?:\w+ )?on the right|"
        r"roadside on the right|right side of the street",
    ),
    (RelativePosition.ROADSIDE_LEFT, r"left sidewalk|parked (?:\w+ )?on the left"),
    (RelativePosition.ADJACENT_LANE_LEFT, r"(?:in )?the left lane|lane to the left"),
    (
        RelativePosition.ADJACENT_LANE_RIGHT,
        r"(?:in )?the right lane|adjacent right lane|"
        r"lane to the right",
    ),
    (RelativePosition.BEHIND_SAME_LANE, r"from behind(?= in|,|\.| the ego)|behind the ego"),
    (
        RelativePosition.AHEAD_SAME_LANE,
        r"ahead in (?:the )?(?:same|ego'?s?) lane|"
        r"in front of the ego|ahead of the ego",
    ),
]


def _first(table: Sequence[tuple[object, str]], text: str) -> object | None:
    for value, pattern in table:
        if re.search(rf"\b(?:{pattern})\b", text):
            return value
    return None


def apply_hints(description: str, spec: ScenarioSpec) -> tuple[ScenarioSpec, list[str]]:
    """The spec with enums the description states plainly; and a note per change."""
    text = description.lower()
    changes: dict[str, object] = {}
    for field, table in (
        ("adversary_type", _ADVERSARY),
        ("road_type", _ROAD),
        ("ego_maneuver", _MANEUVER),
        ("spawn_position", _SPAWN),
    ):
        found = _first(table, text)
        if found is not None and found != getattr(spec, field):
            changes[field] = found
    if (
        "ego_maneuver" not in changes
        and spec.ego_maneuver is not EgoManeuver.GO_STRAIGHT
        and _first(_MANEUVER, text) is None
    ):
        changes["ego_maneuver"] = EgoManeuver.GO_STRAIGHT
    road = changes.get("road_type", spec.road_type)
    maneuver = changes.get("ego_maneuver", spec.ego_maneuver)
    if maneuver in (EgoManeuver.TURN_LEFT, EgoManeuver.TURN_RIGHT) and road in (
        RoadType.STRAIGHT,
        RoadType.HIGHWAY,
    ):
        changes["road_type"] = RoadType.INTERSECTION
    notes = [
        f"{name}: {getattr(spec, name)} -> {value} (stated in the description)"
        for name, value in changes.items()
    ]
    return spec.model_copy(update=changes), notes


# A requirement is kept only when the description says it in words like these: the small
# model otherwise copies the few-shot examples' requirements into every spec.
_REQUIREMENT_EVIDENCE: dict[RequirementKind, str] = {
    RequirementKind.VISIBLE_AT_START: r"visible|in (?:plain |clear )?(?:view|sight)|"
    r"can see|sees|spots",
    RequirementKind.NOT_VISIBLE_AT_START: r"hidden|hides|occlud\w*|out of (?:view|sight)|"
    r"obscured|not visible|invisible|unseen|blind spot|"
    r"(?:from )?behind (?:a|an|the) (?:parked|stopped|"
    r"bus|van|truck|wall|hedge|car)",
    RequirementKind.DISTANCE_AT_START: r"\d+(?:\.\d+)?\s*(?:m|meters?|metres?)\b|"
    r"(?:meters?|metres?) (?:ahead|away|behind)",
    RequirementKind.EVENTUALLY_CLOSE: r"comes? (?:very )?close|gets? (?:very )?close|"
    r"near miss|close call|within \d",
    RequirementKind.IN_INTERSECTION: r"(?:in|inside|in the middle of) the (?:intersection|"
    r"junction|crossroads)",
    RequirementKind.SAME_DIRECTION: r"same direction|same way|side by side|alongside",
    RequirementKind.OPPOSITE_DIRECTION: r"oncoming|opposite direction|the other way|"
    r"head-on|towards? the ego",
}
# Kinds that cannot hold for an adversary that starts at this position.
_REQUIREMENT_CONFLICTS: dict[RequirementKind, set[RelativePosition]] = {
    RequirementKind.SAME_DIRECTION: {
        RelativePosition.ONCOMING,
        RelativePosition.CROSSING_FROM_LEFT,
        RelativePosition.CROSSING_FROM_RIGHT,
    },
    RequirementKind.OPPOSITE_DIRECTION: {
        RelativePosition.AHEAD_SAME_LANE,
        RelativePosition.BEHIND_SAME_LANE,
        RelativePosition.ADJACENT_LANE_LEFT,
        RelativePosition.ADJACENT_LANE_RIGHT,
        RelativePosition.CROSSING_FROM_LEFT,
        RelativePosition.CROSSING_FROM_RIGHT,
    },
}


def keep_stated_requirements(
    description: str, spec: ScenarioSpec
) -> tuple[ScenarioSpec, list[str]]:
    """The spec without requirements the description does not state or its spawn rules out."""
    text = description.lower()
    kept: list[Requirement] = []
    notes: list[str] = []
    for requirement in spec.requirements:
        if requirement.kind in {r.kind for r in kept}:
            continue
        if not re.search(rf"\b(?:{_REQUIREMENT_EVIDENCE[requirement.kind]})", text):
            notes.append(
                f"requirements: dropped {requirement.kind} (not stated in the description)"
            )
        elif spec.spawn_position in _REQUIREMENT_CONFLICTS.get(requirement.kind, set()):
            notes.append(
                f"requirements: dropped {requirement.kind} (contradicts {spec.spawn_position})"
            )
        else:
            kept.append(requirement)
    if len(kept) == len(spec.requirements):
        return spec, notes
    return spec.model_copy(update={"requirements": kept}), notes
