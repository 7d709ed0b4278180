"""An agent in the ego's seat: what it observes each step and how its control is applied.

The world model builds an `Observation` from ground truth (the ego's state, its route
ahead, the actors within `SENSING_RADIUS`, the signals on its route and the speed limit),
asks the agent for a `Control` and puts it on the ego's pedals and wheel; the physics
then moves the ego exactly as it moves every other vehicle (`simulator._move_vehicle`).
The ego's scripted behavior is switched off for the run, so nothing else drives it.
"""

from __future__ import annotations

import math
from typing import Any

from arise.agents.control import RoutePath
from arise.agents.loader import AgentError
from arise.agents.types import (
    ActorClass,
    ActorView,
    Agent,
    Control,
    EgoRoute,
    LightView,
    Observation,
)
from arise.validate.worldmodel.signals import Approach, SignalModel

SENSING_RADIUS = 60.0  # metres, centre to centre
ROUTE_AHEAD = 60.0  # metres of route in each observation
ROUTE_SPACING = 2.0  # metres between its points
LIGHTS_AHEAD = 100.0  # metres along the route
DEFAULT_SPEED_LIMIT = 50 / 3.6  # m/s, where the map gives none


def actor_class(obj: Any) -> ActorClass:
    """The class an agent sees: the object's class, or its nearest base that is one (a
    subclass of Car is a Car, any other vehicle a Car); anything else a prop (Debris)."""
    for cls in type(obj).__mro__:
        known = ActorClass.of(cls.__name__)
        if known is not None:
            return known
        if cls.__name__ == "Vehicle":
            return ActorClass.CAR
    return ActorClass.DEBRIS


class EgoDriver:
    """Runs one agent for one simulation."""

    def __init__(
        self,
        agent: Agent,
        name: str,
        route: EgoRoute,
        ego: Any,
        objects: list[Any],
        signals: SignalModel,
        network: Any,
        timestep: float,
    ):
        self.agent = agent
        self.name = name
        self.route = route
        self.path = RoutePath(route.waypoints)
        self.ego = ego
        self.network = network
        self.timestep = timestep
        self.station: float | None = None
        self.others = _named(objects, ego)
        self.signals = signals
        self.lights = self._lights_on_route(signals)
        self._call("reset", lambda: agent.reset(route))

    def _call(self, method: str, call: Any) -> Any:
        """The agent's own failure, said as such (never blamed on the script)."""
        try:
            return call()
        except AgentError:
            raise
        except Exception as error:  # noqa: BLE001  (the user's code may raise anything)
            raise AgentError(
                f"agent '{self.name}' raised {type(error).__name__} in {method}(): {error}"
            ) from None

    def _lights_on_route(self, signals: SignalModel) -> list[tuple[Approach, float]]:
        """The signals whose lanes the route takes, with their stop line's station."""
        lanes = set(self.route.lanes)
        found = []
        for approach in signals.approaches:
            if approach.lanes & lanes:
                station, _ = self.path.project(*approach.midpoint)
                found.append((approach, station))
        return found

    def drive(self, step: int) -> Control:
        """Ask the agent and set the ego's controls for the physics of this step."""
        observation = self.observe(step)
        control = self._call("act", lambda: self.agent.act(observation))
        if not isinstance(control, Control):
            raise AgentError(
                f"agent '{self.name}' returned {type(control).__name__} from act(), not a Control"
            )
        try:
            control = control.clamped()
        except (TypeError, ValueError) as error:
            raise AgentError(f"agent '{self.name}' returned a bad control: {error}") from None
        ego = self.ego
        ego.throttle, ego.brake, ego.steer = control.throttle, control.brake, control.steer
        ego.hand_brake, ego.reverse = 0, False
        ego.arise_autopilot = None
        return control

    def observe(self, step: int) -> Observation:
        ego = self.ego
        x, y = float(ego.position.x), float(ego.position.y)
        self.station, _ = self.path.project(x, y, near=self.station)
        station = self.station
        # Every ROUTE_SPACING metres ahead; past the route's end it goes on straight.
        ahead = [
            self.path.point_at(station + k * ROUTE_SPACING)
            for k in range(1, int(ROUTE_AHEAD / ROUTE_SPACING) + 1)
        ]
        actors = []
        for name, obj in self.others:
            ox, oy = float(obj.position.x), float(obj.position.y)
            distance = math.hypot(ox - x, oy - y)
            if distance > SENSING_RADIUS:
                continue
            actors.append(
                ActorView(
                    name=name,
                    cls=actor_class(obj),
                    x=ox,
                    y=oy,
                    heading=float(obj.heading),
                    speed=float(getattr(obj, "speed", 0.0) or 0.0),
                    width=float(obj.width),
                    length=float(obj.length),
                    distance=distance,
                )
            )
        lights = [
            LightView(
                id=approach.id,
                kind=approach.kind,
                state=self.signals.state(approach, step),
                distance=stop - station,
            )
            for approach, stop in self.lights
            if -10.0 < stop - station < LIGHTS_AHEAD
        ]
        return Observation(
            step=step,
            time=step * self.timestep,
            timestep=self.timestep,
            x=x,
            y=y,
            heading=float(ego.heading),
            speed=float(getattr(ego, "speed", 0.0) or 0.0),
            yaw_rate=float(getattr(ego, "angularSpeed", 0.0) or 0.0),
            width=float(ego.width),
            length=float(ego.length),
            route_ahead=tuple(ahead),
            route_remaining=max(0.0, self.path.length - station),
            speed_limit=self._speed_limit(ego),
            actors=tuple(sorted(actors, key=lambda a: a.distance)),
            lights=tuple(sorted(lights, key=lambda light: light.distance)),
        )

    def _speed_limit(self, ego: Any) -> float:
        lane = self.network.laneAt(ego.position) if self.network is not None else None
        for element in (lane, getattr(lane, "road", None)):
            limit = getattr(element, "speedLimit", None)
            if isinstance(limit, int | float) and math.isfinite(limit) and limit > 0:
                return float(limit)
        return DEFAULT_SPEED_LIMIT


def _named(objects: list[Any], ego: Any) -> list[tuple[str, Any]]:
    """Every other object with the name the trace gives it (Car1, Pedestrian2, ...)."""
    counts: dict[str, int] = {}
    named = []
    for obj in objects:
        kind = type(obj).__name__
        counts[kind] = counts.get(kind, 0) + 1
        if obj is not ego:
            named.append((f"{kind}{counts[kind]}", obj))
    return named
