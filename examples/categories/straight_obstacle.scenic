# Straight obstacle: a pedestrian steps out from behind a parked van on a straight road
# and stops in the ego's lane.
# BEGIN HEADER
param map = localPath('../../maps/Town01.xodr')
param carla_map = 'Town01'
model scenic.simulators.carla.model
param weather = 'CloudyNoon'
# END HEADER
# BEGIN BEHAVIOR
param OPT_WALK_SPEED = Range(1.2, 2.0)
param OPT_STOP_DISTANCE = Range(2.0, 3.5)
behavior StepOutAndStop():
    do CrossingBehavior(ego, globalParameters.OPT_WALK_SPEED, 20) until (distance from self to egoLane.centerline) < globalParameters.OPT_STOP_DISTANCE
    while True:
        take SetWalkingSpeedAction(0)
# END BEHAVIOR
# BEGIN GEOMETRY
egoLane = Uniform(*network.lanes)
egoStart = new OrientedPoint on egoLane.centerline
ego = new Car at egoStart, with blueprint 'vehicle.lincoln.mkz_2017', with behavior FollowLaneBehavior(target_speed=9)
# END GEOMETRY
# BEGIN SPAWN
param OPT_AHEAD = Range(20, 30)
conflictPoint = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_AHEAD
adversary = new Pedestrian right of conflictPoint by 4.5, facing 90 deg relative to conflictPoint.heading, with regionContainedIn None, with behavior StepOutAndStop()
# END SPAWN
# BEGIN MISC
occluder = new Van behind adversary by 3, facing conflictPoint.heading, with regionContainedIn None
# END MISC
# BEGIN REQUIREMENTS
require (distance to intersection) > 40
require (distance from conflictPoint to intersection) > 20
terminate when (distance to egoStart) > 70
# END REQUIREMENTS
