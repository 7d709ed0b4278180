# NHTSA pre-crash typology, "lead vehicle stopped / decelerating": the ego follows a car
# in its lane that brakes hard; the ego brakes when the gap closes. Written in the style of
# Scenic's VerifAI examples (parameters sampled by VerifAI, not by Scenic).
param map = localPath('../../../assets/maps/CARLA/Town01.xodr')
param carla_map = 'Town01'
model scenic.simulators.carla.model

param verifaiSamplerType = 'halton'

EGO_MODEL = "vehicle.lincoln.mkz_2017"
param EGO_SPEED = VerifaiRange(7, 10)
param EGO_BRAKE = VerifaiRange(0.5, 1.0)
param LEAD_SPEED = VerifaiRange(5, 8)
param LEAD_GAP = VerifaiDiscreteRange(12, 20)
param LEAD_MODEL = VerifaiOptions(['vehicle.audi.a2', 'vehicle.nissan.micra', 'vehicle.toyota.prius'])
BRAKE_TRIGGER = 10
SAFETY_GAP = 8

behavior EgoBehavior(speed):
    try:
        do FollowLaneBehavior(target_speed=speed)
    interrupt when withinDistanceToAnyObjs(self, SAFETY_GAP):
        take SetBrakeAction(globalParameters.EGO_BRAKE)

behavior LeadBehavior(speed):
    do FollowLaneBehavior(target_speed=speed) for BRAKE_TRIGGER seconds
    while True:
        take SetBrakeAction(1.0)

lane = Uniform(*network.lanes)
start = new OrientedPoint on lane.centerline
ego = new Car at start,
    with blueprint EGO_MODEL,
    with behavior EgoBehavior(globalParameters.EGO_SPEED)
lead = new Car following roadDirection from start for globalParameters.LEAD_GAP,
    with blueprint globalParameters.LEAD_MODEL,
    with behavior LeadBehavior(globalParameters.LEAD_SPEED)

require (distance to intersection) > 50
terminate when (distance to start) > 80
