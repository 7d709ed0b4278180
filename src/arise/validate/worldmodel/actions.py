"""CARLA-only actions, re-implemented for the offline simulator.

Each action changes plain attributes on the agent; the simulator's physics reads them.
Actions with no offline effect (gears, lights, traffic lights) are recorded on the
simulation so a report can say they happened.
"""

from __future__ import annotations

import math
from typing import Any

from scenic.core.simulators import Action
from scenic.core.vectors import Vector
from scenic.domains.driving.actions import *  # noqa: F403  (scripts expect the driving actions too)
from scenic.domains.driving.actions import RegulatedControlAction, SetPositionAction

from arise.validate.worldmodel.simulator import OfflineCarlaSimulation

TRAFFIC_LIGHT_COLORS = ("red", "yellow", "green", "off", "unknown")

SetLocationAction = SetPositionAction


def record_event(sim: Any, obj: Any, kind: str, **details: Any) -> None:
    """Remember an action the offline simulator cannot act out (e.g. a light change)."""
    events = getattr(sim, "arise_events", None)
    if events is not None:
        events.append(
            {
                "step": sim.currentTime,
                "agent": str(getattr(obj, "name", obj)),
                "kind": kind,
                **details,
            }
        )


class BrakingRegulatedControlAction(RegulatedControlAction):
    """Scenic's regulated control, except that a negative signal brakes offline.

    Scenic 3.1's `RegulatedControlAction` sets the throttle to 0 before it computes
    `brake = min(abs(throttle), max_brake)`, so FollowLane, FollowTrajectory, TurnBehavior
    and LaneChangeBehavior can only coast; the offline physics has no drag, so a car
    never slowed for a turn. This does what CARLA's agents do (their PID controller gives
    one signal: throttle when positive, brake `min(-signal, max_brake)` when negative).
    `scenic_patches` puts it in Scenic's driving actions, where those behaviors find it;
    on any other simulator (CARLA itself) it acts exactly as Scenic's own action.
    """

    def __init__(
        self,
        throttle: float,
        steer: float,
        past_steer: float,
        max_throttle: float = 0.5,
        max_brake: float = 0.5,
        max_steer: float = 0.8,
    ):
        super().__init__(throttle, steer, past_steer, max_throttle, max_brake, max_steer)
        self.arise_brake = min(max(-float(throttle), 0.0), max_brake)

    def applyTo(self, obj: Any, sim: Any) -> None:
        super().applyTo(obj, sim)
        if isinstance(sim, OfflineCarlaSimulation):
            obj.setBraking(self.arise_brake)


class _CarlaVehicle:
    """Marker mixin, as in the CARLA interface, for vehicle-only actions."""


class _CarlaPedestrian:
    """Marker mixin for pedestrian-only actions."""


class VehicleAction(Action):
    def canBeTakenBy(self, agent: Any) -> bool:
        return isinstance(agent, _CarlaVehicle)


class PedestrianAction(Action):
    def canBeTakenBy(self, agent: Any) -> bool:
        return isinstance(agent, _CarlaPedestrian)


class SetAngularVelocityAction(Action):
    def __init__(self, angularVel: float):
        self.angularVel = angularVel

    def applyTo(self, obj: Any, sim: Any) -> None:
        obj.arise_angular_override = float(self.angularVel)


class SetTransformAction(Action):
    def __init__(self, pos: Vector, heading: float):
        self.pos = pos
        self.heading = heading

    def applyTo(self, obj: Any, sim: Any) -> None:
        obj.setPosition(self.pos, obj.elevation)
        obj.heading = self.heading


class SetManualGearShiftAction(VehicleAction):
    def __init__(self, manualGearShift: bool):
        if not isinstance(manualGearShift, bool):
            raise TypeError("Manual gear shift must be a boolean.")
        self.manualGearShift = manualGearShift

    def applyTo(self, obj: Any, sim: Any) -> None:
        record_event(sim, obj, "manual_gear_shift", value=self.manualGearShift)


class SetGearAction(VehicleAction):
    def __init__(self, gear: int):
        if not isinstance(gear, int):
            raise TypeError("Gear must be an int.")
        self.gear = gear

    def applyTo(self, obj: Any, sim: Any) -> None:
        record_event(sim, obj, "gear", value=self.gear)


class SetManualFirstGearShiftAction(VehicleAction):
    def applyTo(self, obj: Any, sim: Any) -> None:
        record_event(sim, obj, "manual_first_gear")


def _check_color(color: str) -> str:
    if not isinstance(color, str) or color.lower() not in TRAFFIC_LIGHT_COLORS:
        raise ValueError("Color must be red/yellow/green/off/unknown.")
    return color.lower()


class SetTrafficLightAction(VehicleAction):
    """Set the light nearest the vehicle; offline the state is stored and recorded."""

    def __init__(self, color: str, distance: float = 100, group: bool = False):
        self.color = _check_color(color)
        self.distance = distance

    def applyTo(self, obj: Any, sim: Any) -> None:
        sim.arise_set_closest_light(obj, self.color, self.distance)


class SetAutopilotAction(VehicleAction):
    """Approximates CARLA's Traffic Manager: the simulator keeps the car on its lane."""

    def __init__(self, enabled: bool, **kwargs: Any):
        if not isinstance(enabled, bool):
            raise TypeError("Enabled must be a boolean.")
        self.enabled = enabled
        self.speed = kwargs.get("speed")
        self.speed_difference = kwargs.get("vehicle_percentage_speed_difference")
        self.path = kwargs.get("path")
        self.options = {k: v for k, v in kwargs.items() if k not in ("speed", "path")}

    def applyTo(self, obj: Any, sim: Any) -> None:
        if not self.enabled:
            obj.arise_autopilot = None
            return
        speed = self.speed
        if speed is None:
            speed = 8.0
            if self.speed_difference is not None:
                speed *= 1 - float(self.speed_difference) / 100
        obj.arise_autopilot = {"speed": float(speed), "path": self.path}
        record_event(
            sim,
            obj,
            "autopilot",
            speed=float(speed),
            **{k: v for k, v in self.options.items() if isinstance(v, (int, float, bool, str))},
        )


class SetVehicleLightStateAction(VehicleAction):
    def __init__(self, vehicleLightState: Any):
        self.state = vehicleLightState

    def applyTo(self, obj: Any, sim: Any) -> None:
        record_event(sim, obj, "light_state", value=str(self.state))


class SetJumpAction(PedestrianAction):
    def __init__(self, jump: bool):
        if not isinstance(jump, bool):
            raise TypeError("Jump must be a boolean.")
        self.jump = jump

    def applyTo(self, obj: Any, sim: Any) -> None:
        record_event(sim, obj, "jump", value=self.jump)


class SetWalkAction(PedestrianAction):
    """CARLA's AI walker wanders the sidewalks; offline the walker keeps walking ahead."""

    def __init__(self, enabled: bool, maxSpeed: float = 1.4):
        if not isinstance(enabled, bool):
            raise TypeError("Enabled must be a boolean.")
        self.enabled = enabled
        self.maxSpeed = maxSpeed

    def applyTo(self, obj: Any, sim: Any) -> None:
        if self.enabled:
            obj.setWalkingDirection(obj.heading)
            obj.setWalkingSpeed(float(self.maxSpeed))
        else:
            obj.setWalkingSpeed(0.0)


class TrackWaypointsAction(VehicleAction):
    """Steer along a list of waypoints at a cruising speed (pure pursuit offline)."""

    def __init__(self, waypoints: Any, cruising_speed: float = 10):
        self.waypoints = [Vector(*w[:2]) if not isinstance(w, Vector) else w for w in waypoints]
        self.cruising_speed = cruising_speed

    def applyTo(self, obj: Any, sim: Any) -> None:
        if not self.waypoints:
            return
        target = min(self.waypoints, key=lambda w: (w - obj.position).norm())
        index = self.waypoints.index(target)
        if index + 1 < len(self.waypoints):
            target = self.waypoints[index + 1]
        direction = target - obj.position
        desired = math.atan2(direction.y, direction.x) - math.pi / 2
        error = (desired - obj.heading + math.pi) % (2 * math.pi) - math.pi
        obj.setSteering(max(-1.0, min(1.0, -error)))
        obj.setThrottle(0.6 if obj.speed < self.cruising_speed else 0.0)
        obj.setBraking(0.0)
