# On a multi-lane highway, a car in the lane to the left cuts in front of the ego and then brakes.
# BEGIN HEADER
param map = localPath('maps/arise_highway.xodr')
param carla_map = 'arise_highway'
model scenic.simulators.carla.model
# END HEADER
# BEGIN WEATHER
# kb: weather.clear_noon
param weather = 'ClearNoon'
# END WEATHER
# BEGIN BEHAVIOR
# kb: behavior.cut_in_and_brake
param OPT_ADV_SPEED = Range(9, 12)
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
# kb: geometry.highway_cruise
param OPT_EGO_SPEED = Range(18, 24)
param OPT_EGO_START = Range(10, 60)
egoSection = Uniform(*[s for lane in network.lanes if lane.centerline.length > 300 for s in lane.sections if s._laneToLeft is not None and s._laneToLeft.isForward == s.isForward])
egoLane = egoSection.lane
leftSection = egoSection._laneToLeft
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.left_lane_ahead
param OPT_SPAWN_AHEAD = Range(6, 14)
advRef = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_AHEAD
advStart = new OrientedPoint at leftSection.centerline.project(advRef.position), facing roadDirection
advLane = leftSection.lane
adversary = new Car at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
