# Unprotected left turn: the ego turns left while an oncoming motorcycle goes straight.
# BEGIN HEADER
param map = localPath('../../maps/Town05.xodr')
param carla_map = 'Town05'
model scenic.simulators.carla.model
param weather = 'SoftRainSunset'
# END HEADER
# BEGIN BEHAVIOR
param OPT_ADV_SPEED = Range(8, 12)
behavior OncomingStraight(route):
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_ADV_SPEED, trajectory=route)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED)
# END BEHAVIOR
# BEGIN GEOMETRY
turnPairs = [(m, a) for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.LEFT_TURN for a in m.conflictingManeuvers if a.type is ManeuverType.STRAIGHT and a.startLane.road is not m.startLane.road]
chosenPair = Uniform(*turnPairs)
egoManeuver = chosenPair[0]
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint in egoManeuver.startLane.centerline
ego = new Car at egoStart, with behavior FollowTrajectoryBehavior(target_speed=7, trajectory=egoRoute)
# END GEOMETRY
# BEGIN SPAWN
advManeuver = chosenPair[1]
advRoute = [advManeuver.startLane, advManeuver.connectingLane, advManeuver.endLane]
advStart = new OrientedPoint in advManeuver.startLane.centerline
adversary = new Motorcycle at advStart, with behavior OncomingStraight(advRoute)
# END SPAWN
# BEGIN REQUIREMENTS
require 10 <= (distance from ego to intersection) <= 25
require 15 <= (distance from adversary to intersection) <= 35
terminate when (distance to egoStart) > 70
# END REQUIREMENTS
