"""A user's driving agent: `arise drive SOURCE --agent examples/agents/careful.py:Careful`."""

import math

from arise.agents.types import Control, EgoRoute, LightState, Observation


class Careful:
    """Steers at the route 8 m ahead, brakes for a red light or anyone in its lane."""

    def reset(self, route: EgoRoute) -> None:
        self.cruise = route.target_speed  # m/s

    def act(self, obs: Observation) -> Control:
        sin, cos = math.sin(obs.heading), math.cos(obs.heading)  # Scenic: 0 faces +y

        def ahead_and_aside(x: float, y: float) -> tuple[float, float]:
            return cos * (y - obs.y) - sin * (x - obs.x), cos * (x - obs.x) + sin * (y - obs.y)

        tx, ty = obs.route_ahead[min(4, len(obs.route_ahead) - 1)]
        along, aside = ahead_and_aside(tx, ty)
        in_lane = [ahead_and_aside(a.x, a.y) for a in obs.actors]
        blocked = any(0 < d < 8 + 2 * obs.speed and abs(s) < 2 for d, s in in_lane)
        red = any(s.state is LightState.RED and 0 < s.distance < 12 for s in obs.lights)
        stop = blocked or red
        speed_up = not stop and obs.speed < self.cruise
        steer = 2.0 * math.atan2(aside, max(along, 1.0))  # positive steers right
        return Control(throttle=0.6 if speed_up else 0.0, brake=1.0 if stop else 0.0, steer=steer)
