"""A small kinematic simulator that stands in for CARLA when no server is available.

Scenic's Newtonian simulator moves only cars and renders by default; CARLA scripts also
drive trucks, bicycles and motorcycles, walk pedestrians, switch on autopilot and set
traffic lights. This simulator does all of that with simple physics, never renders, and
records what it could not act out.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from scenic.core.vectors import Vector
from scenic.domains.driving.controllers import (
    PIDLateralController,
    PIDLongitudinalController,
)
from scenic.domains.driving.simulators import DrivingSimulation, DrivingSimulator

from arise.agents.dynamics import MAX_ACCELERATION, MAX_BRAKING, MIN_WHEELBASE
from arise.agents.loader import AgentFactory, make_agent
from arise.validate.worldmodel.blueprints import check_blueprint
from arise.validate.worldmodel.curves import CurveSpeedGovernor, GovernedLongitudinalController
from arise.validate.worldmodel.driver import EgoDriver
from arise.validate.worldmodel.feedforward import (
    FollowedPath,
    feed_forward_steer,
    heading_damping,
)
from arise.validate.worldmodel.linegeometry import wrap_angle
from arise.validate.worldmodel.route import read_route
from arise.validate.worldmodel.signals import SignalModel
from arise.validate.worldmodel.weather import check_weather

DEFAULT_TIMESTEP = 0.1
DEFAULT_STEPS = 300  # what a route is made long enough for when no step limit is given
# Actions of the ego's own behavior still applied while an agent drives: they change the
# world or only get recorded, never the ego's motion (`actions`).
WORLD_ACTIONS = frozenset(
    {
        "SetTrafficLightAction",
        "SetVehicleLightStateAction",
        "SetGearAction",
        "SetManualGearShiftAction",
        "SetManualFirstGearShiftAction",
    }
)
AUTOPILOT_LOOKAHEAD_MIN = 5.0  # metres
AUTOPILOT_GAP = 8.0  # metres kept to whatever is ahead
# Speed up to which the lateral gains apply as tuned; above it they shrink with 1/v^2.
LATERAL_REFERENCE_SPEED = 15.0  # m/s
# The same for lane changes, whose gains are twice as high.
LANE_CHANGE_REFERENCE_SPEED = 12.0  # m/s


class SpeedScheduledLateralController(PIDLateralController):
    """Scenic's lateral PID, scheduled with speed, plus a steer for the lane's curve.

    Above v_ref (15 m/s for lane following, 12 m/s for lane changes, whose gains are twice
    as high; None for turns) the PID's output is scaled by (v_ref / v)^2. In this physics
    (as on a real car) the yaw rate a steering input gives grows with speed, and the
    cross-track error the PID sees grows with speed again: the loop gain grows with v^2.
    Gains that hold the lane at 15 m/s made the car weave from lane to lane at 21 m/s and
    above (the derivative term overshoots within one 0.1 s step). Scaling keeps the loop
    as it is at v_ref, so the car keeps its lane at any speed up to the KB's 35 m/s;
    CARLA's own agents schedule their gains similarly.

    With a `path`, the steer that holds the curvature of the followed lane and a heading
    term at low speed are added after the scaling (`feedforward`).
    """

    def __init__(
        self,
        agent: Any,
        K_P: float,
        K_D: float,
        K_I: float,
        dt: float,
        clock: Callable[[], int] | None = None,
        reference_speed: float | None = LATERAL_REFERENCE_SPEED,
        path: FollowedPath | None = None,
    ):
        super().__init__(K_P=K_P, K_D=K_D, K_I=K_I, dt=dt)
        self.agent = agent
        self.reference_speed = reference_speed
        self.clock = clock
        self.last_step: int | None = None
        self.path = path

    def run_step(self, cte: float) -> float:
        # A behavior that hands the car to another one (FollowTrajectoryBehavior gives it
        # to TurnBehavior inside a junction) comes back to an error and an integral from
        # before: without a fresh start the derivative kicks the car across the lane it
        # has just entered.
        now = self.clock() if self.clock is not None else None
        if now is not None and self.last_step is not None and now - self.last_step > 1:
            self.last_error = cte
            self.ITerm = 0.0
        self.last_step = now
        output = float(super().run_step(cte))
        speed = float(getattr(self.agent, "speed", 0.0) or 0.0)
        if self.reference_speed is not None and speed > self.reference_speed:
            output *= (self.reference_speed / speed) ** 2
        point = self.path.read(cte) if self.path is not None else None
        if point is not None:
            wheelbase = max(float(getattr(self.agent, "length", 0.0) or 0.0), MIN_WHEELBASE)
            output += feed_forward_steer(point.curvature, wheelbase)
            output += heading_damping(self.Kp, self.Kd, speed, wheelbase) * point.heading_error
        return max(-1.0, min(1.0, output))


def _seat_behavior(scene: Any) -> Any:
    """`AgentDrivesBehavior` of the world model's behaviors, as compiled for this scene
    (Scenic compiles its modules per scenario and keeps them out of sys.modules)."""
    for namespaces in dict(scene.behaviorNamespaces).values():
        for namespace in namespaces if isinstance(namespaces, tuple) else (namespaces,):
            if isinstance(namespace, dict) and "AgentDrivesBehavior" in namespace:
                return namespace["AgentDrivesBehavior"]
    from arise.agents.loader import AgentError

    raise AgentError("the world model's AgentDrivesBehavior is missing from the scene")


class OfflineCarlaSimulator(DrivingSimulator):
    """Scenic simulator interface for the offline CARLA world model."""

    def __init__(self, network: Any = None, timestep: float = DEFAULT_TIMESTEP):
        super().__init__()
        self.network = network
        self.timestep = float(timestep)
        # Who drives the ego (set by the worker): the agent's name and what makes one per
        # simulation; None leaves the script's own behavior at the wheel.
        self.arise_agent: tuple[str, AgentFactory] | None = None

    def createSimulation(self, scene: Any, **kwargs: Any) -> OfflineCarlaSimulation:
        check_weather(scene.params.get("weather"))
        if kwargs.get("timestep") is None:
            kwargs["timestep"] = self.timestep
        return OfflineCarlaSimulation(scene, self.network, agent=self.arise_agent, **kwargs)


class OfflineCarlaSimulation(DrivingSimulation):
    def __init__(
        self,
        scene: Any,
        network: Any,
        agent: tuple[str, AgentFactory] | None = None,
        **kwargs: Any,
    ):
        self.network = network
        self.arise_events: list[dict[str, Any]] = []
        self.arise_lights: dict[str, str] = {}
        timestep = float(kwargs.get("timestep") or DEFAULT_TIMESTEP)
        self.arise_signals = SignalModel(network, timestep)
        self.arise_route: Any = None  # the ego's EgoRoute, read at setup
        self.arise_driver: EgoDriver | None = None
        self._arise_agent = agent
        self._arise_steps = int(kwargs.get("maxSteps") or DEFAULT_STEPS)
        super().__init__(scene, **kwargs)

    def setup(self) -> None:
        """Create the objects, read the ego's route, and seat the agent if one drives."""
        super().setup()
        ego = self.scene.egoObject
        if ego is None or ego not in self.objects:
            return
        try:
            self.arise_route = read_route(
                self.scene, ego, self.network, self._arise_steps, self.timestep
            )
        except Exception:  # an odd map or scene must not cost a scripted run its facts
            self.arise_route = None
        if self._arise_agent is None:
            return
        name, factory = self._arise_agent
        if self.arise_route is None:
            from arise.agents.loader import AgentError

            raise AgentError(
                f"agent '{name}' cannot drive: the ego starts on no lane of the map, so it has "
                "no route"
            )
        # The agent drives: the script's ego behavior runs inside the seat for its effects
        # on the world; its driving actions are dropped (`executeActions`).
        ego.behavior = _seat_behavior(self.scene)(ego.behavior)
        ego.arise_autopilot = None
        self.arise_driver = EgoDriver(
            make_agent(factory, name),
            name,
            self.arise_route,
            ego,
            self.objects,
            self.arise_signals,
            self.network,
            self.timestep,
        )

    # --- object life cycle -------------------------------------------------------
    def createObjectInSimulator(self, obj: Any) -> None:
        check_blueprint(obj)
        obj.speed = math.hypot(obj.velocity.x, obj.velocity.y)
        if hasattr(obj, "elevation"):
            obj.elevation = 0.0

    def getProperties(self, obj: Any, properties: Any) -> dict[str, Any]:
        yaw, _, _ = obj.parentOrientation.globalToLocalAngles(obj.heading, 0, 0)
        values = dict(
            position=obj.position,
            yaw=yaw,
            pitch=0,
            roll=0,
            velocity=obj.velocity,
            speed=obj.speed,
            angularSpeed=obj.angularSpeed,
            angularVelocity=obj.angularVelocity,
        )
        if "elevation" in properties:
            values["elevation"] = 0.0
        return values

    def executeActions(self, allActions: Any) -> None:
        """With an agent at the wheel, the ego's scripted actions keep only their effects
        on the world (lights, recorded settings): nothing else may move the ego."""
        if self.arise_driver is not None:
            ego = self.arise_driver.ego
            if ego in allActions:
                allActions[ego] = tuple(
                    action for action in allActions[ego] if type(action).__name__ in WORLD_ACTIONS
                )
        super().executeActions(allActions)

    # --- physics -------------------------------------------------------------------
    def step(self) -> None:
        dt = self.timestep
        if self.arise_driver is not None:
            self.arise_driver.drive(self.currentTime)
        for obj in self.objects:
            if getattr(obj, "arise_autopilot", None):
                self._drive_autopilot(obj)
            walk = getattr(obj, "arise_walk", None)
            if walk is not None and (walk[0] is not None or walk[1] is not None):
                self._move_walker(obj, walk)
            elif getattr(obj, "arise_steers", False):
                self._move_vehicle(obj, dt)
            else:
                obj.speed = obj.velocity.norm()
            override = getattr(obj, "arise_angular_override", None)
            if override is not None:
                obj.angularSpeed = override
            obj.position += obj.velocity * dt
            obj.heading += obj.angularSpeed * dt

    @staticmethod
    def _move_walker(obj: Any, walk: list[Any]) -> None:
        heading = obj.heading if walk[0] is None else walk[0]
        speed = obj.speed if walk[1] is None else walk[1]
        obj.heading = heading
        obj.velocity = Vector(0, speed).rotatedBy(heading)
        obj.speed = abs(speed)
        obj.angularSpeed = 0

    @staticmethod
    def _move_vehicle(obj: Any, dt: float) -> None:
        forward_axis = Vector(0, 1).rotatedBy(obj.heading)
        speed = obj.velocity.norm()
        signed = speed if obj.velocity.dot(forward_axis) >= 0 else -speed
        braking = max(obj.brake or 0, obj.hand_brake or 0)
        if braking > 0:
            decel = MAX_BRAKING * braking * dt
            signed = 0.0 if decel >= abs(signed) else signed - math.copysign(decel, signed)
        else:
            accel = (obj.throttle or 0) * MAX_ACCELERATION
            signed += (-accel if obj.reverse else accel) * dt
        obj.velocity = Vector(0, signed).rotatedBy(obj.heading)
        obj.speed = abs(signed)
        steer = max(-1.0, min(1.0, obj.steer or 0))
        if steer:
            # Controllers are tuned for cars: short vehicles (bikes) steer with a car's
            # wheelbase, or their yaw rate doubles and lane following oscillates.
            wheelbase = max(obj.length, MIN_WHEELBASE)
            obj.angularSpeed = -signed * math.sin(steer * math.pi / 2) / wheelbase
        else:
            obj.angularSpeed = 0

    # --- autopilot (approximation of CARLA's Traffic Manager) ----------------------
    def _drive_autopilot(self, obj: Any) -> None:
        settings = obj.arise_autopilot
        target_speed = settings["speed"]
        aim = self._lane_point_ahead(obj, max(AUTOPILOT_LOOKAHEAD_MIN, obj.speed))
        if aim is None:
            obj.setThrottle(0.0)
            obj.setBraking(1.0)
            return
        direction = aim - obj.position
        desired = math.atan2(direction.y, direction.x) - math.pi / 2
        error = wrap_angle(desired - obj.heading)
        obj.setSteering(max(-1.0, min(1.0, -1.5 * error)))
        if self._blocked_ahead(obj):
            obj.setThrottle(0.0)
            obj.setBraking(1.0)
        elif obj.speed < target_speed:
            obj.setThrottle(min(1.0, 0.3 * (target_speed - obj.speed) + 0.2))
            obj.setBraking(0.0)
        else:
            obj.setThrottle(0.0)
            obj.setBraking(min(1.0, 0.2 * (obj.speed - target_speed)))

    def _lane_point_ahead(self, obj: Any, distance: float) -> Vector | None:
        if self.network is None:
            return None
        lane = self.network.laneAt(obj.position)
        if lane is None:
            return None
        line = lane.centerline.lineString
        from shapely.geometry import Point

        s = line.project(Point(obj.position.x, obj.position.y)) + distance
        while s > line.length:
            s -= line.length
            lane = self._next_lane(obj, lane)
            if lane is None:
                end = line.coords[-1]
                return Vector(end[0], end[1])
            line = lane.centerline.lineString
        point = line.interpolate(s)
        return Vector(point.x, point.y)

    @staticmethod
    def _next_lane(obj: Any, lane: Any) -> Any:
        if not lane.maneuvers:
            return getattr(lane, "_successor", None)  # `successor` rejects at a dead end
        choices = getattr(obj, "arise_turns", None)
        if choices is None:
            choices = obj.arise_turns = {}
        if lane.uid not in choices:
            straight = [m for m in lane.maneuvers if m.type.name == "STRAIGHT"]
            chosen = (straight or list(lane.maneuvers))[0]
            choices[lane.uid] = chosen.connectingLane or chosen.endLane
        return choices[lane.uid]

    def _blocked_ahead(self, obj: Any) -> bool:
        forward = Vector(0, 1).rotatedBy(obj.heading)
        for other in self.objects:
            if other is obj:
                continue
            offset = other.position - obj.position
            ahead = offset.dot(forward)
            if (
                0 < ahead < AUTOPILOT_GAP + obj.length / 2
                and abs(offset.x * forward.y - offset.y * forward.x) < (obj.width + other.width) / 2
            ):
                return True
        return False

    # --- traffic lights: stored and recorded -------------------------------------
    def _signals_near(self, obj: Any) -> list[Any]:
        if self.network is None:
            return []
        lane = self.network.laneAt(obj.position)
        found = []
        if lane is not None:
            for maneuver in lane.maneuvers:
                if maneuver.intersection is not None:
                    found.extend(maneuver.intersection.signals)
                    break
        if not found:
            inter = self.network.intersectionAt(obj.position)
            if inter is not None:
                found.extend(inter.signals)
        return [s for s in found if s.isTrafficLight]

    def arise_set_closest_light(self, obj: Any, color: str, distance: float = 100) -> None:
        signals = self._signals_near(obj)
        for signal in signals:
            self.arise_lights[str(signal.openDriveID)] = color
        approach = self.arise_signals.light_for(self.network, obj.position)
        if approach is not None:
            self.arise_signals.hold(approach, color, self.currentTime)
        self.arise_events.append(
            {
                "step": self.currentTime,
                "agent": str(getattr(obj, "name", obj)),
                "kind": "traffic_light",
                "color": color,
                "signals": [str(s.openDriveID) for s in signals],
            }
        )

    def arise_light_of(self, obj: Any) -> str | None:
        approach = self.arise_signals.light_for(self.network, obj.position)
        if approach is not None:
            return self.arise_signals.state(approach, self.currentTime).value
        signals = self._signals_near(obj)
        if not signals:
            return None
        return self.arise_lights.get(str(signals[0].openDriveID), "green")

    def arise_set_signal(self, signal: Any, color: str) -> None:
        self.arise_lights[str(signal.openDriveID)] = color
        for inter in getattr(self.network, "intersections", ()):
            if signal in inter.signals:
                self.arise_signals.hold_intersection(str(inter.uid), color, self.currentTime)
        self.arise_events.append(
            {
                "step": self.currentTime,
                "agent": "world",
                "kind": "traffic_light",
                "color": color,
                "signals": [str(signal.openDriveID)],
            }
        )

    # --- controllers tuned for this physics ------------------------------------------
    def _pid_pair(
        self, agent: Any, lateral: tuple[float, float, float], scheduled: float | None = None
    ) -> tuple[Any, Any]:
        dt = self.timestep
        # Every controlled vehicle slows for the curves on its lane ahead (`curves`).
        governor = CurveSpeedGovernor(self.network, agent)
        lon: PIDLongitudinalController
        if getattr(agent, "isCar", False):
            lon = GovernedLongitudinalController(governor, K_P=0.5, K_D=0.1, K_I=0.7, dt=dt)
        else:
            lon = GovernedLongitudinalController(governor, K_P=0.25, K_D=0.025, K_I=0.0, dt=dt)
        kp, kd, ki = lateral
        return lon, SpeedScheduledLateralController(
            agent,
            K_P=kp,
            K_D=kd,
            K_I=ki,
            dt=dt,
            clock=lambda: int(self.currentTime),
            reference_speed=scheduled,
            path=FollowedPath(self.network, agent),
        )

    def getLaneFollowingControllers(self, agent: Any) -> tuple[Any, Any]:
        # Turns are not scheduled: they run slowly, and their agility is what lets a fast
        # adversary follow its connecting lane through a junction.
        return self._pid_pair(agent, (0.1, 0.1, 0.02), scheduled=LATERAL_REFERENCE_SPEED)

    def getTurningControllers(self, agent: Any) -> tuple[Any, Any]:
        # No integral term: the curvature feed-forward holds the arc, and the integral
        # wound up over a slow turn and carried the car across it (`feedforward`).
        return self._pid_pair(agent, (0.2, 0.2, 0.0))

    def getLaneChangingControllers(self, agent: Any) -> tuple[Any, Any]:
        # Twice the lane-following gains: scheduled from a lower speed, or a lane change
        # at 15 m/s and above overshoots into the lane beyond and comes back.
        return self._pid_pair(agent, (0.2, 0.2, 0.02), scheduled=LANE_CHANGE_REFERENCE_SPEED)
