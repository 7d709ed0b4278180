# Right turn: the ego turns right while a car from the left crosses straight through the
# intersection into the ego's target road.
# BEGIN HEADER
param map = localPath('../../maps/Town10HD.xodr')
param carla_map = 'Town10HD'
model scenic.simulators.carla.model
param weather = 'ClearNoon'
# END HEADER
# BEGIN BEHAVIOR
param OPT_ADV_SPEED = Range(7, 10)
behavior CrossFromLeft(route):
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_ADV_SPEED, trajectory=route)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED)
# END BEHAVIOR
# BEGIN GEOMETRY
turnPairs = [(m, a) for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.RIGHT_TURN for a in i.maneuvers if a.type is ManeuverType.STRAIGHT and a.endLane.road is m.endLane.road]
chosenPair = Uniform(*turnPairs)
egoManeuver = chosenPair[0]
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint in egoManeuver.startLane.centerline
ego = new Car at egoStart, with behavior FollowTrajectoryBehavior(target_speed=6, trajectory=egoRoute)
# END GEOMETRY
# BEGIN SPAWN
advManeuver = chosenPair[1]
advRoute = [advManeuver.startLane, advManeuver.connectingLane, advManeuver.endLane]
advStart = new OrientedPoint in advManeuver.startLane.centerline
adversary = new Car at advStart, with behavior CrossFromLeft(advRoute)
# END SPAWN
# BEGIN REQUIREMENTS
require 8 <= (distance from ego to intersection) <= 25
require 10 <= (distance from adversary to intersection) <= 30
terminate when (distance to egoStart) > 60
# END REQUIREMENTS
