# Crossing negotiation: at an intersection the ego and a car from the crossing road both go
# straight; the adversary does not yield and accelerates.
# BEGIN HEADER
param map = localPath('../../maps/Town07.xodr')
param carla_map = 'Town07'
model scenic.simulators.carla.model
param weather = 'CloudySunset'
# END HEADER
# BEGIN BEHAVIOR
param OPT_ADV_SPEED = Range(8, 11)
behavior DoNotYield(route):
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_ADV_SPEED, trajectory=route) until (distance from self to ego) < 12
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_ADV_SPEED + 4, trajectory=route)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED)
# END BEHAVIOR
# BEGIN GEOMETRY
straights = [m for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.STRAIGHT and any(c.type is ManeuverType.STRAIGHT for c in m.conflictingManeuvers)]
egoManeuver = Uniform(*straights)
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint in egoManeuver.startLane.centerline
ego = new Car at egoStart, with behavior FollowTrajectoryBehavior(target_speed=8, trajectory=egoRoute)
# END GEOMETRY
# BEGIN SPAWN
crossing = filter(lambda m: m.type is ManeuverType.STRAIGHT, egoManeuver.conflictingManeuvers)
advManeuver = Uniform(*crossing)
advRoute = [advManeuver.startLane, advManeuver.connectingLane, advManeuver.endLane]
advStart = new OrientedPoint in advManeuver.startLane.centerline
adversary = new Car at advStart, with behavior DoNotYield(advRoute)
# END SPAWN
# BEGIN REQUIREMENTS
require 10 <= (distance from ego to intersection) <= 25
require 10 <= (distance from adversary to intersection) <= 25
terminate when (distance to egoStart) > 70
# END REQUIREMENTS
