# The ego's own behavior gives it green at a four-way junction, then drives straight on.
Town = 'arise_intersection4'
param map = localPath(f'../maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
param weather = 'ClearNoon'

behavior EgoOnGreenBehavior():
    take SetTrafficLightAction("green")
    do FollowTrajectoryBehavior(target_speed=8, trajectory=egoRoute)
    do FollowLaneBehavior(target_speed=8)

junction = network.intersections[0]
egoManeuver = Uniform(*[m for m in junction.maneuvers if m.type is ManeuverType.STRAIGHT])
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint at egoManeuver.startLane.centerline.pointAlongBy(-45), facing roadDirection
ego = new Car at egoStart, with behavior EgoOnGreenBehavior()

terminate when (distance from ego to egoStart) > 90
