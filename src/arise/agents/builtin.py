"""The agents arise ships, from the floor (`blind`) to a rule-abiding driver (`idm`).

`scripted` is not here: it is the script's own ego behavior, left as it is (the
reference). Every agent here drives the route it is given at `reset` and knows the world
model's dynamics (`arise.agents.dynamics`), so its control gives the acceleration and
curvature it computed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from arise.agents.control import (
    IdmParameters,
    RoutePath,
    idm_acceleration,
    pure_pursuit_curvature,
)
from arise.agents.dynamics import (
    MAX_ACCELERATION,
    MAX_BRAKING,
    pedals_for_acceleration,
    steer_for_curvature,
)
from arise.agents.types import (
    ActorClass,
    ActorView,
    BuiltinAgent,
    Control,
    EgoRoute,
    LightState,
    LightView,
    Observation,
    SignalKind,
)


class _RouteFollower:
    """What every built-in shares: the route as a path, and where the ego is along it."""

    lookahead_time = 1.0  # s: pure pursuit looks this far ahead (at least `min_lookahead`)
    min_lookahead = 5.0  # m

    def __init__(self) -> None:
        self.path = RoutePath([(0.0, 0.0)])
        self.target_speed = 0.0
        self.station: float | None = None

    def reset(self, route: EgoRoute) -> None:
        self.path = RoutePath(route.waypoints)
        self.target_speed = route.target_speed
        self.station = None

    def locate(self, observation: Observation) -> float:
        """The ego's station on the route, searched near the last one (a route may cross
        itself or pass close to a point twice)."""
        self.station, _ = self.path.project(observation.x, observation.y, near=self.station)
        return self.station

    def steer(self, observation: Observation, station: float) -> float:
        """Pure pursuit of the route point one look-ahead distance ahead."""
        lookahead = max(self.min_lookahead, self.lookahead_time * observation.speed)
        target = self.path.point_at(station + lookahead)
        curvature = pure_pursuit_curvature(
            observation.x, observation.y, observation.heading, target
        )
        return steer_for_curvature(curvature, observation.length)

    def act(self, observation: Observation) -> Control:
        raise NotImplementedError


class BlindAgent(_RouteFollower):
    """Keeps its route and its target speed and reacts to nothing: no actor, no light, no
    stop sign, no curve. The floor every scenario should be able to hurt. Speed is held
    by a proportional controller (1 s time constant), steering by pure pursuit (Coulter
    1992)."""

    def act(self, observation: Observation) -> Control:
        station = self.locate(observation)
        wanted = max(-3.0, min(2.0, self.target_speed - observation.speed))
        throttle, brake = pedals_for_acceleration(wanted)
        return Control(throttle=throttle, brake=brake, steer=self.steer(observation, station))


@dataclass(frozen=True)
class _Hazard:
    """Something the ego must stay behind: metres of free road to it and its speed along
    the route."""

    gap: float
    speed: float


class IdmAgent(_RouteFollower):
    """A law-abiding driver: the Intelligent Driver Model (Treiber, Hennecke & Helbing,
    Phys. Rev. E 62, 2000) for speed and pure pursuit (Coulter 1992) for steering.

    It follows the route at its target speed, slowing for curves (lateral acceleration at
    most 3 m/s^2). Anything it must not hit becomes an IDM leader: an actor in its path
    now (with its speed along the route), an actor whose straight-line course enters its
    path within 4 s (a crossing pedestrian: a standing leader where it will enter), a red
    light (a standing leader at the stop line), a yellow one it can still stop for
    comfortably, and a stop sign until it has stopped at it. IDM's braking is clipped to
    what the world model's brakes give (6.8 m/s^2).
    """

    prediction_horizon = 4.0  # s
    prediction_step = 0.25  # s
    path_margin = 0.4  # m added to the half widths when telling "in my path"
    sensing_range = 80.0  # m along the route
    lateral_acceleration = 3.0  # m/s^2 allowed in curves

    def __init__(self, parameters: IdmParameters | None = None) -> None:
        super().__init__()
        self.parameters = parameters or IdmParameters()
        self.stopped_at: set[str] = set()

    def reset(self, route: EgoRoute) -> None:
        super().reset(route)
        self.stopped_at = set()

    def act(self, observation: Observation) -> Control:
        station = self.locate(observation)
        hazards = [
            h
            for h in (
                *(self._actor_hazard(observation, station, a) for a in observation.actors),
                *(self._light_hazard(observation, light) for light in observation.lights),
            )
            if h is not None
        ]
        desired = min(self.target_speed, self._curve_speed(observation, station))
        if hazards:
            nearest = min(hazards, key=lambda h: h.gap)
            acceleration = idm_acceleration(
                observation.speed, desired, nearest.gap, nearest.speed, self.parameters
            )
        else:
            acceleration = idm_acceleration(observation.speed, desired, None, 0.0, self.parameters)
        acceleration = max(-MAX_BRAKING, min(MAX_ACCELERATION, acceleration))
        if observation.speed < 0.05 and acceleration < 0:
            acceleration = -MAX_BRAKING  # standing: hold the brake rather than creep
        throttle, brake = pedals_for_acceleration(acceleration)
        return Control(throttle=throttle, brake=brake, steer=self.steer(observation, station))

    def _curve_speed(self, observation: Observation, station: float) -> float:
        """The speed at which the sharpest curve within the next few seconds stays under
        the lateral acceleration allowed."""
        reach = max(15.0, 3.0 * observation.speed)
        sharpest = 0.0
        s = station
        while s < station + reach and s < self.path.length:
            turn = self.path.heading_at(s + 5.0) - self.path.heading_at(s)
            turn = math.atan2(math.sin(turn), math.cos(turn))
            sharpest = max(sharpest, abs(turn) / 5.0)
            s += 2.5
        if sharpest < 1e-3:
            return math.inf
        return math.sqrt(self.lateral_acceleration / sharpest)

    def _actor_hazard(
        self, observation: Observation, station: float, actor: ActorView
    ) -> _Hazard | None:
        half_width = observation.width / 2 + actor.width / 2 + self.path_margin
        vx = -math.sin(actor.heading) * actor.speed
        vy = math.cos(actor.heading) * actor.speed
        steps = int(self.prediction_horizon / self.prediction_step) + 1
        for i in range(steps):
            t = i * self.prediction_step
            if i and actor.speed < 0.05:
                break  # a standing actor stays where it is
            s, lateral = self.path.project(
                actor.x + vx * t, actor.y + vy * t, near=station, window=self.sensing_range
            )
            ahead = s - station
            if lateral > half_width or ahead < 0 or ahead > self.sensing_range:
                continue
            along = math.cos(actor.heading - self.path.heading_at(s)) * actor.speed
            extent = _extent_along(actor, actor.heading - self.path.heading_at(s))
            gap = ahead - observation.length / 2 - extent
            if i == 0:
                return _Hazard(gap=gap, speed=max(0.0, along))
            return _Hazard(gap=gap, speed=0.0)  # it will be in the way: stop short of it
        return None

    def _light_hazard(self, observation: Observation, light: LightView) -> _Hazard | None:
        gap = light.distance - observation.length / 2
        if gap < -0.5 or light.id in self.stopped_at:
            return None  # past the line (or already stopped at this stop sign)
        if light.kind is SignalKind.STOP_SIGN:
            if observation.speed < 0.2 and gap < 4.0:
                self.stopped_at.add(light.id)
                return None
            return _Hazard(gap=gap, speed=0.0)
        if light.state is LightState.RED:
            return _Hazard(gap=gap, speed=0.0)
        if light.state is LightState.YELLOW:
            stopping = observation.speed**2 / (2 * self.parameters.comfortable_deceleration)
            if gap > stopping:
                return _Hazard(gap=gap, speed=0.0)
        return None


class CautiousAgent(_RouteFollower):
    """The world model's own lane follower with emergency braking, as its autopilot has
    driven cars since the first offline release (`OfflineCarlaSimulation._drive_autopilot`,
    an approximation of CARLA's Traffic Manager), but on the ego's route.

    It aims at the route point max(5 m, v * 1 s) ahead and steers 1.5 x the heading error;
    it brakes fully while anything is within 8 m of its front along its heading and
    overlaps its width, and otherwise closes on its target speed. It does not look at
    lights, stop signs or actors that are about to cross: it reacts to what is in front
    of it now.
    """

    gap = 8.0  # m kept to whatever is ahead

    def act(self, observation: Observation) -> Control:
        station = self.locate(observation)
        aim = self.path.point_at(station + max(5.0, observation.speed))
        desired = math.atan2(aim[1] - observation.y, aim[0] - observation.x) - math.pi / 2
        error = math.atan2(
            math.sin(desired - observation.heading), math.cos(desired - observation.heading)
        )
        steer = max(-1.0, min(1.0, -1.5 * error))
        if any(self._blocking(observation, actor) for actor in observation.actors):
            return Control(throttle=0.0, brake=1.0, steer=steer)
        if observation.speed < self.target_speed:
            throttle = min(1.0, 0.3 * (self.target_speed - observation.speed) + 0.2)
            return Control(throttle=throttle, brake=0.0, steer=steer)
        brake = min(1.0, 0.2 * (observation.speed - self.target_speed))
        return Control(throttle=0.0, brake=brake, steer=steer)

    def _blocking(self, observation: Observation, actor: ActorView) -> bool:
        fx, fy = -math.sin(observation.heading), math.cos(observation.heading)
        dx, dy = actor.x - observation.x, actor.y - observation.y
        ahead = dx * fx + dy * fy
        side = abs(dx * fy - dy * fx)
        return (
            0 < ahead < self.gap + observation.length / 2
            and side < (observation.width + actor.width) / 2
        )


def _extent_along(actor: ActorView, relative_heading: float) -> float:
    """Half the actor's extent along the route's direction."""
    if actor.cls is ActorClass.PEDESTRIAN:
        return max(actor.width, actor.length) / 2
    return (
        abs(math.cos(relative_heading)) * actor.length
        + abs(math.sin(relative_heading)) * actor.width
    ) / 2


#: The built-ins that drive (`scripted` leaves the script's own behavior in place).
BUILTIN_AGENTS: dict[BuiltinAgent, type[_RouteFollower]] = {
    BuiltinAgent.IDM: IdmAgent,
    BuiltinAgent.CAUTIOUS: CautiousAgent,
    BuiltinAgent.BLIND: BlindAgent,
}
