"""A user's agent as the docs show it: drives its route at 5 m/s, looks at nothing."""

import math

from arise.agents.types import Control, EgoRoute, Observation


class SteadyAgent:
    def reset(self, route: EgoRoute) -> None:
        self.speed = 5.0

    def act(self, observation: Observation) -> Control:
        ahead = observation.route_ahead[min(3, len(observation.route_ahead) - 1)]
        bearing = math.atan2(ahead[1] - observation.y, ahead[0] - observation.x) - math.pi / 2
        error = math.atan2(
            math.sin(bearing - observation.heading), math.cos(bearing - observation.heading)
        )
        throttle = 0.3 if observation.speed < self.speed else 0.0
        return Control(throttle=throttle, brake=0.0, steer=max(-1.0, min(1.0, -2.0 * error)))


class Crashing:
    def reset(self, route: EgoRoute) -> None:
        pass

    def act(self, observation: Observation) -> Control:
        raise RuntimeError("sensor fault")


class ReadsLate:
    """Reads a file of its own only once the run has started, i.e. after confinement."""

    def reset(self, route: EgoRoute) -> None:
        pass

    def act(self, observation: Observation) -> Control:
        with open(__file__, encoding="utf-8") as source:
            source.read()
        return Control()
