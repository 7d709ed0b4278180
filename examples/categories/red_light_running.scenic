# Red-light running: the ego crosses a signalized intersection on green while a car on the
# crossing road runs its red light.
# BEGIN HEADER
param map = localPath('../../maps/Town05.xodr')
param carla_map = 'Town05'
model scenic.simulators.carla.model
param weather = 'ClearNoon'
# END HEADER
# BEGIN BEHAVIOR
param OPT_ADV_SPEED = Range(9, 12)
behavior RunTheRed(route):
    take SetTrafficLightAction("red")
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_ADV_SPEED, trajectory=route)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED)
behavior EgoOnGreen(route):
    while withinDistanceToTrafficLight(self, 20) and getClosestTrafficLightStatus(self) == "Red":
        take SetBrakeAction(1)
    take SetTrafficLightAction("green")
    do FollowTrajectoryBehavior(target_speed=8, trajectory=route)
    do FollowLaneBehavior(target_speed=8)
# END BEHAVIOR
# BEGIN GEOMETRY
signalized = [i for i in network.intersections if i.isSignalized] or network.intersections
egoManeuver = Uniform(*[m for i in signalized for m in i.maneuvers if m.type is ManeuverType.STRAIGHT])
junction = egoManeuver.intersection
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint in egoManeuver.startLane.centerline
ego = new Car at egoStart, with behavior EgoOnGreen(egoRoute)
# END GEOMETRY
# BEGIN SPAWN
advManeuver = Uniform(*filter(lambda m: m.type is ManeuverType.STRAIGHT, egoManeuver.conflictingManeuvers))
advRoute = [advManeuver.startLane, advManeuver.connectingLane, advManeuver.endLane]
advStart = new OrientedPoint in advManeuver.startLane.centerline
adversary = new Car at advStart, with behavior RunTheRed(advRoute)
# END SPAWN
# BEGIN REQUIREMENTS
require 12 <= (distance from ego to junction) <= 30
require 12 <= (distance from adversary to junction) <= 30
terminate when (distance to egoStart) > 70
# END REQUIREMENTS
