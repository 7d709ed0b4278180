# Turning obstacle: the ego turns right at an intersection and a cyclist crosses the road
# it turns into.
# BEGIN HEADER
param map = localPath('../../maps/Town10HD.xodr')
param carla_map = 'Town10HD'
model scenic.simulators.carla.model
param weather = 'WetNoon'
# END HEADER
# BEGIN BEHAVIOR
param OPT_RIDE_SPEED = Range(3, 5)
behavior CrossWhenEgoTurns():
    while (distance from self to ego) > 18:
        wait
    while True:
        take SetSpeedAction(globalParameters.OPT_RIDE_SPEED)
# END BEHAVIOR
# BEGIN GEOMETRY
turnManeuvers = [m for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.RIGHT_TURN]
egoManeuver = Uniform(*turnManeuvers)
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint in egoManeuver.startLane.centerline
ego = new Car at egoStart, with behavior FollowTrajectoryBehavior(target_speed=6, trajectory=egoRoute)
# END GEOMETRY
# BEGIN SPAWN
param OPT_INTO_EXIT = Range(8, 14)
crossingPoint = new OrientedPoint following roadDirection from egoManeuver.endLane.centerline[0] for globalParameters.OPT_INTO_EXIT
adversary = new Bicycle right of crossingPoint by 5, facing 90 deg relative to crossingPoint.heading, with regionContainedIn None, with behavior CrossWhenEgoTurns()
# END SPAWN
# BEGIN REQUIREMENTS
require 10 <= (distance from ego to intersection) <= 25
terminate when (distance to egoStart) > 60
# END REQUIREMENTS
