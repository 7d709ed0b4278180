# Vehicle passing: the ego follows a slow truck; while the ego passes it on the left the
# truck drifts and brakes hard.
# BEGIN HEADER
param map = localPath('../../maps/Town06.xodr')
param carla_map = 'Town06'
model scenic.simulators.carla.model
param weather = 'CloudyNoon'
# END HEADER
# BEGIN BEHAVIOR
param OPT_TRUCK_SPEED = Range(3, 5)
param OPT_BRAKE = Range(0.6, 1.0)
behavior SlowThenBrake():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_TRUCK_SPEED) until (distance from self to ego) < 8
    while True:
        take SetThrottleAction(0), SetBrakeAction(globalParameters.OPT_BRAKE)
behavior EgoPasses(passSection):
    do FollowLaneBehavior(target_speed=9) until (distance from self to adversary) < 15
    do LaneChangeBehavior(laneSectionToSwitch=passSection, target_speed=9)
    do FollowLaneBehavior(target_speed=9)
# END BEHAVIOR
# BEGIN GEOMETRY
passable = [s for lane in network.lanes for s in lane.sections if s._laneToLeft is not None and s._laneToLeft.isForward == s.isForward]
egoSection = Uniform(*passable)
egoStart = new OrientedPoint on egoSection.centerline
ego = new Car at egoStart, with behavior EgoPasses(egoSection._laneToLeft)
# END GEOMETRY
# BEGIN SPAWN
param OPT_GAP = Range(20, 30)
adversary = new Truck following roadDirection from egoStart for globalParameters.OPT_GAP, with behavior SlowThenBrake()
# END SPAWN
# BEGIN REQUIREMENTS
require (distance to intersection) > 70
require adversary in egoSection
terminate when (distance to egoStart) > 90
# END REQUIREMENTS
