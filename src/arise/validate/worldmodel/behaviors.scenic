"""CARLA-only behaviors, written for the offline world model.

The driving domain's behaviors (FollowLaneBehavior, FollowTrajectoryBehavior,
LaneChangeBehavior, TurnBehavior, ...) come along unchanged.
"""

from scenic.domains.driving.behaviors import *
from arise.validate.worldmodel.actions import *

behavior AutopilotBehavior(enabled = True, **kwargs):
    """Offline: the simulator keeps the vehicle on its lane at a cruising speed."""
    take SetAutopilotAction(enabled=enabled, **kwargs)

behavior WalkForwardBehavior(speed=0.5):
    take SetWalkingDirectionAction(self.heading), SetWalkingSpeedAction(speed)

behavior WalkBehavior(maxSpeed=1.4):
    take SetWalkAction(True, maxSpeed)

behavior CrossingBehavior(reference_actor, min_speed=1, threshold=10, final_speed=None):
    """Cross ahead of reference_actor, timed so both reach the conflict point together."""
    if not final_speed:
        final_speed = min_speed
    while (distance from self to reference_actor) > threshold:
        wait
    while True:
        # Express our position in the reference actor's frame: y ahead of it, x to its side.
        relative = (self.position - reference_actor.position).rotatedBy(-reference_actor.heading)
        gap_along = relative.y
        if gap_along < 0:
            break
        gap_side = abs(relative.x)
        arrival_time = gap_along / max(reference_actor.speed, 0.1)
        wanted = max(min_speed, gap_side / max(arrival_time, 0.1))
        if isinstance(self, Walks):
            take SetWalkingDirectionAction(self.heading), SetWalkingSpeedAction(wanted)
        else:
            take SetSpeedAction(wanted)
    if isinstance(self, Walks):
        do WalkForwardBehavior(final_speed)
    else:
        take SetSpeedAction(final_speed)

behavior AgentDrivesBehavior(original=None):
    """Holds the ego's seat while a driving agent drives it (`driver`). The script's own
    ego behavior still runs beside it for what it does to the world (a traffic light it
    sets, the scenario it ends); the simulator drops its driving actions, and the agent's
    control moves the ego. Should it fail (it may expect the ego where the agent did not
    go), the seat simply waits."""
    if original is not None:
        try:
            do original
        except Exception:
            pass
    while True:
        wait
