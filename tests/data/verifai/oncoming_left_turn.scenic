# NHTSA pre-crash typology, "left turn across path, opposite direction": the ego goes
# straight through a junction while an oncoming car turns left across its path. The car's
# speed has a prior (VerifaiParameter.withPrior), its model is a VerifaiOptions choice.
param map = localPath('../../../assets/maps/CARLA/Town05.xodr')
param carla_map = 'Town05'
model scenic.simulators.carla.model

param verifaiSamplerType = 'ce'

param EGO_SPEED = VerifaiRange(6, 9)
param ADV_SPEED = VerifaiParameter.withPrior(Normal(7, 1.5))
param ADV_MODEL = VerifaiOptions({'vehicle.tesla.model3': 2, 'vehicle.audi.tt': 1})
param EGO_DIST = VerifaiRange(10, 20)
param ADV_DIST = VerifaiRange(10, 20)

intersection = Uniform(*filter(lambda i: i.is4Way, network.intersections))
egoManeuver = Uniform(*filter(lambda m: m.type is ManeuverType.STRAIGHT, intersection.maneuvers))
egoInit = egoManeuver.startLane
egoRoute = [egoInit, egoManeuver.connectingLane, egoManeuver.endLane]
advManeuvers = filter(lambda m: m.type is ManeuverType.LEFT_TURN, egoManeuver.conflictingManeuvers)
advManeuver = Uniform(*advManeuvers)
advRoute = [advManeuver.startLane, advManeuver.connectingLane, advManeuver.endLane]

egoStart = new OrientedPoint following roadDirection from egoInit.centerline[-1] for -globalParameters.EGO_DIST
advStart = new OrientedPoint following roadDirection from advManeuver.startLane.centerline[-1] for -globalParameters.ADV_DIST

ego = new Car at egoStart,
    with behavior FollowTrajectoryBehavior(globalParameters.EGO_SPEED, egoRoute)
adversary = new Car at advStart,
    with blueprint globalParameters.ADV_MODEL,
    with behavior FollowTrajectoryBehavior(globalParameters.ADV_SPEED, advRoute)

terminate when (distance to egoStart) > 60
