# A fast car comes from behind in the left lane and passes the ego, then immediately brakes hard in front of it.
# BEGIN HEADER
param map = localPath('maps/arise_straight.xodr')
param carla_map = 'arise_straight'
model scenic.simulators.carla.model
# END HEADER
# BEGIN WEATHER
# kb: weather.clear_noon
param weather = 'ClearNoon'
# END WEATHER
# BEGIN BEHAVIOR
# kb: behavior.cut_in_and_brake
param OPT_ADV_SPEED = Range(10, 15)
param OPT_ADV_CUT_GAP = Range(4, 8)
param OPT_ADV_BRAKE = Range(0.8, 1.0)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until ((self.position - ego.position).rotatedBy(-ego.heading)).y > globalParameters.OPT_ADV_CUT_GAP
    here = self._laneSection
    target = ego._laneSection
    if here is not None and target is not None and (target is here._laneToLeft or target is here._laneToRight):
        do LaneChangeBehavior(laneSectionToSwitch=target, target_speed=globalParameters.OPT_ADV_SPEED)
    while True:
        take SetThrottleAction(0), SetBrakeAction(globalParameters.OPT_ADV_BRAKE)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.multilane_right_neighbor
param OPT_EGO_SPEED = Range(8, 11)
param OPT_EGO_START = Range(10, 40)
egoSection = Uniform(*[s for lane in network.lanes if lane.centerline.length > 80 for s in lane.sections if s._laneToRight is not None and s._laneToRight.isForward == s.isForward])
egoLane = egoSection.lane
rightSection = egoSection._laneToRight
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.behind_same_lane
param OPT_SPAWN_GAP = Range(10, 18)
advStart = new OrientedPoint following roadDirection from egoStart for -globalParameters.OPT_SPAWN_GAP
advLane = egoLane
adversary = new Car at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
