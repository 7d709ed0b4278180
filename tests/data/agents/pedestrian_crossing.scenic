# A pedestrian walks across the ego's lane from the right sidewalk as the ego arrives, and
# keeps walking to the far side: a driver who looks can stop for it, a blind one cannot.
Town = 'arise_straight'
param map = localPath(f'../maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
param weather = 'ClearNoon'

behavior CrossAhead():
    do CrossingBehavior(ego, 1.6, 22)

egoLane = Uniform(*network.lanes)
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(30), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=9)

crossPoint = new OrientedPoint following roadDirection from egoStart for 45
walker = new Pedestrian right of crossPoint by 4, facing 90 deg relative to crossPoint.heading,
    with regionContainedIn None, with behavior CrossAhead()

terminate when (distance from ego to egoStart) > 90
