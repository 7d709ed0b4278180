"""Colours and words shared by the raster pictures and the HTML replay."""

from __future__ import annotations

from arise.render.model import LineKind, RegionKind, Role, Track
from arise.vocabulary import ActorClass, ActorGroup

BACKGROUND = "#eef1ea"  # off-road ground
REGION_COLORS: dict[RegionKind, str] = {
    RegionKind.SHOULDER: "#d3d3cb",
    RegionKind.SIDEWALK: "#c9d6e3",
    RegionKind.DRIVABLE: "#8d9094",
    RegionKind.JUNCTION: "#7c7f84",
    RegionKind.CROSSING: "#b5b8bc",
}
LINE_COLORS: dict[LineKind, str] = {LineKind.LANE: "#ffffff", LineKind.DIVIDER: "#f2c14e"}
ROLE_COLORS: dict[Role, str] = {
    Role.EGO: "#d62728",
    Role.ADVERSARY: "#1f63c6",
    Role.VEHICLE: "#5b6f86",
    Role.CYCLIST: "#8e44ad",
    Role.WALKER: "#1a9e4a",
    Role.PROP: "#a0662b",
}
CONTACT_COLOR = "#111111"
PATH_COLOR = "#d62728"  # the ego's whole path, drawn faint

#: How an agent that is neither the ego nor the adversary is drawn, by its class's group:
#: a motorcycle or a bicycle is slimmer and slower than a car and easy to miss among them.
GROUP_ROLES: dict[ActorGroup, Role] = {
    ActorGroup.VEHICLE: Role.VEHICLE,
    ActorGroup.TWO_WHEELER: Role.CYCLIST,
    ActorGroup.WALKER: Role.WALKER,
    ActorGroup.PROP: Role.PROP,
}


def role_of(kind: str, is_ego: bool, behavior: str | None) -> Role:
    """The role an agent plays, from what the trace says about it (`kind` is untrusted:
    a class the vocabulary does not know is drawn as a prop)."""
    if is_ego:
        return Role.EGO
    if behavior == "AdversaryBehavior":
        return Role.ADVERSARY
    cls = ActorClass.of(kind)
    return GROUP_ROLES[cls.group] if cls is not None else Role.PROP


def label(track: Track) -> str:
    """`name (Class)`, or just the name when it already says the class."""
    return track.name if track.name.startswith(track.kind) else f"{track.name} ({track.kind})"


def legend_text(track: Track) -> str:
    suffix = " - adversary" if track.role is Role.ADVERSARY else ""
    return label(track) + suffix
