"""Colours and words shared by the raster pictures and the HTML replay."""

from __future__ import annotations

from arise.render.model import LineKind, RegionKind, Role, Track

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

_CYCLES = ("Bicycle", "Motorcycle")
_WALKERS = ("Pedestrian",)
_VEHICLES = ("Car", "Truck", "Van", "Bus", "NPCCar", "Vehicle")


def role_of(kind: str, is_ego: bool, behavior: str | None) -> Role:
    """The role an agent plays, from what the trace says about it."""
    if is_ego:
        return Role.EGO
    if behavior == "AdversaryBehavior":
        return Role.ADVERSARY
    if kind in _WALKERS:
        return Role.WALKER
    if kind in _CYCLES:
        return Role.CYCLIST
    if kind in _VEHICLES:
        return Role.VEHICLE
    return Role.PROP


def label(track: Track) -> str:
    """`name (Class)`, or just the name when it already says the class."""
    return track.name if track.name.startswith(track.kind) else f"{track.name} ({track.kind})"


def legend_text(track: Track) -> str:
    suffix = " - adversary" if track.role is Role.ADVERSARY else ""
    return label(track) + suffix
