# NHTSA pre-crash typology, "vehicle changing lanes, same direction": a car in the
# neighbouring lane cuts in ahead of the ego. Sampled with VerifAI's Halton sequence.
param map = localPath('../../../assets/maps/CARLA/Town04.xodr')
param carla_map = 'Town04'
model scenic.simulators.carla.model

param verifaiSamplerType = 'halton'

param EGO_SPEED = VerifaiRange(8, 12)
param CUTTER_SPEED = VerifaiRange(9, 14)
param CUTTER_LEAD = VerifaiRange(-5, 5)
param CUT_AT = VerifaiDiscreteRange(1, 4)

behavior CutIn(speed, seconds):
    do FollowLaneBehavior(target_speed=speed) for seconds seconds
    do LaneChangeBehavior(laneSectionToSwitch=self.laneSection._laneToRight, target_speed=speed)
    do FollowLaneBehavior(target_speed=speed)

section = Uniform(*filter(lambda s: s._laneToRight is not None and s._laneToRight.isForward == s.isForward, network.laneSections))
start = new OrientedPoint on section.centerline
ego = new Car right of start by 3.5,
    with behavior FollowLaneBehavior(target_speed=globalParameters.EGO_SPEED)
cutter = new Car ahead of start by globalParameters.CUTTER_LEAD,
    with behavior CutIn(globalParameters.CUTTER_SPEED, globalParameters.CUT_AT)

require (distance to intersection) > 60
terminate when (distance to start) > 70
