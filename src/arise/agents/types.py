"""The typed contract between a driving agent, the world model and the trace.

An agent drives the ego in place of its scripted behavior: before the run it gets the
ego's `EgoRoute`, at every step an `Observation`, and it answers with a `Control`.
`SignalTrace` records the traffic lights and stop signs of the run so the metrics can
tell a red light run from a green one.

Conventions, the same as Scenic's: x east, y north, metres; a heading is in radians,
0 facing +y (north), growing counter-clockwise; a positive yaw rate turns left; a
positive steer turns right (as in CARLA).

`EgoRoute` and `SignalTrace` are part of a trace, which a script may forge and a run
folder may bring from anyone: their schemas are strict and bounded (`arise.limits`).
`Observation` and `Control` live only inside the worker, between the world model and the
user's own agent, so they are plain frozen dataclasses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Annotated, Protocol, runtime_checkable

from pydantic import BaseModel, ConfigDict, Field, StringConstraints

from arise.limits import MAX_EVENTS, MAX_MAGNITUDE, MAX_NAME, MAX_STEPS
from arise.vocabulary import ActorClass, ActorGroup

#: Points of a route's centreline (a few metres apart: 2,000 is several kilometres).
MAX_ROUTE_POINTS = 2000
#: Lane ids along a route.
MAX_ROUTE_LANES = 64
#: Traffic lights and stop signs recorded for one run.
MAX_SIGNALS = 512
#: The fastest target speed a route may ask for, m/s (360 km/h).
MAX_TARGET_SPEED = 100.0

Coordinate = Annotated[float, Field(allow_inf_nan=False, ge=-MAX_MAGNITUDE, le=MAX_MAGNITUDE)]
Point = tuple[Coordinate, Coordinate]
Step = Annotated[int, Field(ge=0, le=MAX_STEPS)]
Name = Annotated[str, StringConstraints(min_length=1, max_length=MAX_NAME)]
# A maneuver's name (Scenic's ManeuverType, lower case: straight, left_turn, ...).
ManeuverName = Annotated[str, StringConstraints(pattern=r"^\w{1,64}$")]


class _Strict(BaseModel):
    """No unknown fields, never changed after it is made."""

    model_config = ConfigDict(extra="forbid", frozen=True)


class EgoRoute(_Strict):
    """Where the ego is meant to drive: its lane centreline from the start through its
    maneuver, and how fast. Recorded in the trace; an agent gets it before the first step."""

    waypoints: list[Point] = Field(min_length=1, max_length=MAX_ROUTE_POINTS)
    lanes: list[Name] = Field(default_factory=list, max_length=MAX_ROUTE_LANES)
    target_speed: Annotated[float, Field(allow_inf_nan=False, ge=0, le=MAX_TARGET_SPEED)]
    maneuver: ManeuverName | None = None

    @property
    def length(self) -> float:
        """Metres along the waypoints."""
        return sum(
            math.dist(a, b) for a, b in zip(self.waypoints, self.waypoints[1:], strict=False)
        )


class LightState(StrEnum):
    """A traffic light's state; a stop sign is always `red` to the one who reaches it."""

    RED = "red"
    YELLOW = "yellow"
    GREEN = "green"
    OFF = "off"


class SignalKind(StrEnum):
    TRAFFIC_LIGHT = "traffic_light"
    STOP_SIGN = "stop_sign"


class SignalTrace(_Strict):
    """One signal of the map during a run: where traffic must stop for it and when its
    state changed. `states` holds (step, new state) pairs in step order, the first at
    step 0; a stop sign has the single pair (0, red)."""

    id: Name
    kind: SignalKind
    # A segment across the lane(s) it controls, at the stop line.
    stop_line: tuple[Point, Point]
    states: list[tuple[Step, LightState]] = Field(default_factory=list, max_length=MAX_EVENTS)

    def state_at(self, step: int) -> LightState:
        """The state in force at `step` (off before the first recorded change)."""
        current = LightState.OFF
        for changed, state in self.states:
            if changed > step:
                break
            current = state
        return current


@dataclass(frozen=True, slots=True)
class ActorView:
    """Another road user within the sensing radius, in ground truth."""

    name: str
    cls: ActorClass  # the Scenic class (Car, Van, Pedestrian, Cone, ...); see `group`
    x: float
    y: float
    heading: float
    speed: float
    width: float
    length: float
    # Centre to centre, metres.
    distance: float

    @property
    def group(self) -> ActorGroup:
        """Vehicle, two-wheeler, walker or prop."""
        return self.cls.group


@dataclass(frozen=True, slots=True)
class LightView:
    """A signal on the route ahead: its state now and how far its stop line is, metres
    along the route from the ego's centre (negative once the ego has passed it)."""

    id: str
    kind: SignalKind
    state: LightState
    distance: float


@dataclass(frozen=True, slots=True)
class Observation:
    """What an agent knows at one step: its own state, the route ahead, the actors near
    it, the signals ahead and the speed limit, all in ground truth."""

    step: int
    time: float  # seconds since the start
    timestep: float  # seconds per step
    x: float
    y: float
    heading: float
    speed: float  # m/s, along the heading
    yaw_rate: float  # rad/s, positive to the left
    width: float
    length: float
    # Route points every 2 m ahead of the ego's nearest point on it, 60 m of them; past
    # the route's end they go on straight along its last direction.
    route_ahead: tuple[tuple[float, float], ...]
    # Metres left along the route from the ego's nearest point to its end.
    route_remaining: float
    speed_limit: float  # m/s
    actors: tuple[ActorView, ...] = field(default_factory=tuple)
    lights: tuple[LightView, ...] = field(default_factory=tuple)


@dataclass(frozen=True, slots=True)
class Control:
    """An agent's command for one step, as CARLA's VehicleControl: throttle 0..1, brake
    0..1 (either may be set; brake wins, as offline physics applies it first) and steer
    -1..1, positive to the right."""

    throttle: float = 0.0
    brake: float = 0.0
    steer: float = 0.0

    def clamped(self) -> Control:
        """The control in range; a non-finite value is a fault of the agent."""
        for name in ("throttle", "brake", "steer"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise TypeError(f"Control.{name} must be a number, not {type(value).__name__}")
            if not math.isfinite(value):
                raise ValueError(f"Control.{name} is not finite: {value}")
        return Control(
            throttle=min(1.0, max(0.0, float(self.throttle))),
            brake=min(1.0, max(0.0, float(self.brake))),
            steer=min(1.0, max(-1.0, float(self.steer))),
        )


@runtime_checkable
class Agent(Protocol):
    """A driver for the ego. `reset` is called once before the first step with the route
    it should follow, `act` once per step. The world model applies the returned control
    with its own vehicle dynamics (docs/agents.md)."""

    def reset(self, route: EgoRoute) -> None: ...

    def act(self, observation: Observation) -> Control: ...


class BuiltinAgent(StrEnum):
    """The agents arise ships (`arise.agents.builtin`)."""

    SCRIPTED = "scripted"  # the script's own ego behavior: the reference
    IDM = "idm"  # Intelligent Driver Model + pure pursuit
    CAUTIOUS = "cautious"  # the world model's lane follower with emergency braking
    BLIND = "blind"  # keeps route and speed, reacts to nothing
