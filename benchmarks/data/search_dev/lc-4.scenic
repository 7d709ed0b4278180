# On a four-lane road a car weaves between lanes in front of the ego, changing lanes twice in quick succession.
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
# kb: behavior.weave_between_lanes
param OPT_ADV_SPEED = Range(10, 14)
param OPT_ADV_HOLD_SECONDS = Range(1, 2)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) for globalParameters.OPT_ADV_HOLD_SECONDS seconds
    while True:
        here = self._laneSection
        target = None
        if here is not None:
            if here._laneToLeft is not None and here._laneToLeft.isForward == here.isForward:
                target = here._laneToLeft
            elif here._laneToRight is not None and here._laneToRight.isForward == here.isForward:
                target = here._laneToRight
        if target is not None:
            do LaneChangeBehavior(laneSectionToSwitch=target, target_speed=globalParameters.OPT_ADV_SPEED) for 3 seconds
        do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED) for globalParameters.OPT_ADV_HOLD_SECONDS seconds
        here = self._laneSection
        if here is not None and here._laneToRight is not None and here._laneToRight.isForward == here.isForward:
            do LaneChangeBehavior(laneSectionToSwitch=here._laneToRight, target_speed=globalParameters.OPT_ADV_SPEED) for 3 seconds
        do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED) for globalParameters.OPT_ADV_HOLD_SECONDS seconds
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.ego_lane_change_right
param OPT_EGO_SPEED = Range(8, 11)
param OPT_EGO_START = Range(10, 30)
param OPT_EGO_CHANGE_AFTER = Range(2, 4)
behavior EgoLaneChangeBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED) for globalParameters.OPT_EGO_CHANGE_AFTER seconds
    do LaneChangeBehavior(laneSectionToSwitch=rightSection, target_speed=globalParameters.OPT_EGO_SPEED)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
egoSection = Uniform(*[s for lane in network.lanes if lane.centerline.length > 120 for s in lane.sections if s._laneToRight is not None and s._laneToRight.isForward == s.isForward])
egoLane = egoSection.lane
rightSection = egoSection._laneToRight
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior EgoLaneChangeBehavior()
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.lead_same_lane
param OPT_SPAWN_GAP = Range(15, 25)
advStart = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_GAP
advLane = egoLane
adversary = new Car at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
