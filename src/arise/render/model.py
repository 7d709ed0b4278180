"""The plain data every picture is drawn from: road outline, agent tracks, contacts, frame.

Coordinates are world metres as Scenic (and OpenDRIVE) uses them; headings are Scenic's
(0 = facing +y, counter-clockwise, radians).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from typing import NamedTuple

Point = tuple[float, float]


class RegionKind(StrEnum):
    """A kind of road surface, drawn bottom to top in this order."""

    SHOULDER = "shoulder"
    SIDEWALK = "sidewalk"
    DRIVABLE = "drivable"
    JUNCTION = "junction"
    CROSSING = "crossing"


class LineKind(StrEnum):
    """A painted line: between lanes of one direction, or between the two directions."""

    LANE = "lane"
    DIVIDER = "divider"


class Role(StrEnum):
    """What an agent is in the story; sets its colour and its line in the legend."""

    EGO = "ego"
    ADVERSARY = "adversary"
    VEHICLE = "vehicle"
    CYCLIST = "cyclist"
    WALKER = "walker"
    PROP = "prop"


@dataclass(frozen=True)
class Area:
    kind: RegionKind
    exterior: list[Point]
    holes: list[list[Point]] = field(default_factory=list)


@dataclass(frozen=True)
class Line:
    kind: LineKind
    points: list[Point]


@dataclass(frozen=True)
class Outline:
    """The road network inside a window (empty: a scene without a map)."""

    areas: list[Area] = field(default_factory=list)
    lines: list[Line] = field(default_factory=list)


@dataclass(frozen=True)
class Window:
    """The part of the world a picture shows, in metres."""

    xmin: float
    ymin: float
    xmax: float
    ymax: float

    @property
    def width(self) -> float:
        return self.xmax - self.xmin

    @property
    def height(self) -> float:
        return self.ymax - self.ymin

    def grown(self, margin: float) -> Window:
        return Window(
            self.xmin - margin, self.ymin - margin, self.xmax + margin, self.ymax + margin
        )

    def contains(self, point: Point) -> bool:
        return self.xmin <= point[0] <= self.xmax and self.ymin <= point[1] <= self.ymax


class Pose(NamedTuple):
    """Where an agent is at one step. A named tuple, not a dataclass: a trace holds up to
    hundreds of thousands of them, and a tuple is made several times faster."""

    x: float
    y: float
    heading: float
    speed: float


@dataclass(frozen=True)
class Track:
    """One agent over the whole simulation: one pose per step (index = step)."""

    name: str
    kind: str  # the Scenic class (Car, Pedestrian, ...)
    role: Role
    width: float
    length: float
    poses: list[Pose]


@dataclass(frozen=True)
class Contact:
    """Two agents touching, first at `step`, at `where` (the midpoint of their centres)."""

    first: str
    second: str
    step: int
    where: Point


@dataclass(frozen=True)
class Scene:
    """Everything a picture of one run needs."""

    title: str
    timestep: float
    steps: int
    tracks: list[Track]
    outline: Outline
    window: Window
    contacts: list[Contact] = field(default_factory=list)
    # The step the picture is about (closest approach or first contact), if any.
    focus_step: int | None = None
    # What the picture leaves out (`arise.render.budget`): one line each for the legend.
    notes: list[str] = field(default_factory=list)
    # Steps of the trace per drawn step (1: every step is drawn), and then the trace's
    # length: its last drawn step may stand for fewer than `drawn_every` steps.
    drawn_every: int = 1
    trace_seconds: float | None = None

    @property
    def seconds(self) -> float:
        """How long the run lasted."""
        return self.steps * self.timestep if self.trace_seconds is None else self.trace_seconds

    def time_at(self, step: int) -> float:
        """Seconds into the run at a (drawn) step."""
        return min(step * self.timestep, self.seconds)

    def pose(self, track: Track, step: int) -> Pose:
        """The agent's pose at a step (its last one once its trace has ended)."""
        return track.poses[min(step, len(track.poses) - 1)]
