# NHTSA pre-crash typology, "pedestrian crossing, vehicle going straight": a pedestrian
# steps off the right sidewalk ahead of the ego. Parameters are VerifAI's; the
# cross-entropy sampler draws them (a falsifier would feed it the scene's robustness).
param map = localPath('../../../assets/maps/CARLA/Town01.xodr')
param carla_map = 'Town01'
model scenic.simulators.carla.model

param verifaiSamplerType = 'ce'

param EGO_SPEED = VerifaiRange(6, 10)
param WALK_SPEED = VerifaiRange(1.0, 2.0, buckets=4)
param TRIGGER_DIST = VerifaiRange(10, 25)
param PED_AHEAD = VerifaiDiscreteRange(20, 35)
BRAKE_DIST = 6

behavior EgoBehavior(speed):
    try:
        do FollowLaneBehavior(target_speed=speed)
    interrupt when withinDistanceToObjsInLane(self, BRAKE_DIST):
        take SetBrakeAction(1.0)

behavior Walker(speed, trigger):
    do CrossingBehavior(ego, speed, trigger)

lane = Uniform(*network.lanes)
spot = new OrientedPoint on lane.centerline
ego = new Car behind spot by globalParameters.PED_AHEAD,
    with behavior EgoBehavior(globalParameters.EGO_SPEED)
walker = new Pedestrian right of spot by 4,
    facing 90 deg relative to spot.heading,
    with regionContainedIn None,
    with behavior Walker(globalParameters.WALK_SPEED, globalParameters.TRIGGER_DIST)

require (distance to intersection) > 40
terminate when (distance to spot) > 40
