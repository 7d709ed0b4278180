"""What the offline world model does with a `Control`: its constants, in one place.

The world model (`arise.validate.worldmodel.simulator`) moves every vehicle as a kinematic
single-track ("bicycle") model: throttle gives a constant acceleration, brake a constant
deceleration, steer a path curvature over a wheelbase of the vehicle's length (at least
`MIN_WHEELBASE`). The built-in agents turn a wanted acceleration and curvature into a
control with the same numbers, so they drive exactly what they compute.
"""

from __future__ import annotations

import math

MAX_ACCELERATION = 5.6  # m/s^2 at full throttle
MAX_BRAKING = 6.8  # m/s^2 at full brake
MIN_WHEELBASE = 4.0  # metres: short vehicles (bikes) steer with a car's wheelbase


def wheelbase(length: float) -> float:
    """The wheelbase the world model steers a vehicle of this length with."""
    return max(length, MIN_WHEELBASE)


def steer_for_curvature(curvature: float, length: float) -> float:
    """The steer (-1..1, positive to the right) that makes the world model drive a path of
    this curvature (1/m, positive to the left). Its yaw rate is v * sin(steer * pi/2) / L
    turning right, so sin(steer * pi/2) = -L * curvature; beyond 1/L it saturates."""
    amount = max(-1.0, min(1.0, -wheelbase(length) * curvature))
    return math.asin(amount) * 2 / math.pi


def pedals_for_acceleration(acceleration: float) -> tuple[float, float]:
    """(throttle, brake) that give this acceleration (m/s^2) in the world model."""
    if acceleration >= 0:
        return min(1.0, acceleration / MAX_ACCELERATION), 0.0
    return 0.0, min(1.0, -acceleration / MAX_BRAKING)
