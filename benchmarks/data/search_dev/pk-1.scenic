# A car parked at the roadside on the right pulls out into the ego's lane right in front of it.
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
# kb: behavior.cut_in
param OPT_ADV_SPEED = Range(9, 12)
param OPT_ADV_CUT_GAP = Range(4, 8)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until ((self.position - ego.position).rotatedBy(-ego.heading)).y > globalParameters.OPT_ADV_CUT_GAP
    here = self._laneSection
    target = ego._laneSection
    if here is not None and target is not None and (target is here._laneToLeft or target is here._laneToRight):
        do LaneChangeBehavior(laneSectionToSwitch=target, target_speed=globalParameters.OPT_ADV_SPEED)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED)
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
# kb: spawn.right_lane_ahead
param OPT_SPAWN_AHEAD = Range(6, 14)
advRef = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_AHEAD
advStart = new OrientedPoint at rightSection.centerline.project(advRef.position), facing roadDirection
advLane = rightSection.lane
adversary = new Car at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
