# ego wants to change to the left lane, but a motorcycle approaching fast from behind in that lane blocks the maneuver.
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
# kb: behavior.overtake_and_cut_back
param OPT_ADV_SPEED = Range(13, 17)
param OPT_ADV_CUT_GAP = Range(3, 6)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until ((self.position - ego.position).rotatedBy(-ego.heading)).y > globalParameters.OPT_ADV_CUT_GAP
    here = self._laneSection
    target = ego._laneSection
    if here is not None and target is not None and (target is here._laneToLeft or target is here._laneToRight):
        do LaneChangeBehavior(laneSectionToSwitch=target, target_speed=globalParameters.OPT_ADV_SPEED)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED - 3)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.ego_lane_change_left
param OPT_EGO_SPEED = Range(8, 11)
param OPT_EGO_START = Range(10, 30)
param OPT_EGO_CHANGE_AFTER = Range(2, 4)
behavior EgoLaneChangeBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED) for globalParameters.OPT_EGO_CHANGE_AFTER seconds
    do LaneChangeBehavior(laneSectionToSwitch=leftSection, target_speed=globalParameters.OPT_EGO_SPEED)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
egoSection = Uniform(*[s for lane in network.lanes if lane.centerline.length > 120 for s in lane.sections if s._laneToLeft is not None and s._laneToLeft.isForward == s.isForward])
egoLane = egoSection.lane
leftSection = egoSection._laneToLeft
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior EgoLaneChangeBehavior()
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.behind_same_lane
param OPT_SPAWN_GAP = Range(10, 18)
advStart = new OrientedPoint following roadDirection from egoStart for -globalParameters.OPT_SPAWN_GAP
advLane = egoLane
adversary = new Motorcycle at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
