# The ego drives straight at a four-way junction whose lights a monitor holds red.
Town = 'arise_intersection4'
param map = localPath(f'../maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
param weather = 'ClearNoon'

junction = network.intersections[0]
egoManeuver = Uniform(*[m for m in junction.maneuvers if m.type is ManeuverType.STRAIGHT])
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint at egoManeuver.startLane.centerline.pointAlongBy(-45), facing roadDirection
ego = new Car at egoStart, with behavior FollowTrajectoryBehavior(target_speed=8, trajectory=egoRoute)

monitor HoldRed():
    setAllIntersectionTrafficLightsStatus(junction, "red")
    while True:
        wait
require monitor HoldRed()

terminate when (distance from ego to egoStart) > 90
