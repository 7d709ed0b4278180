# Cloudy afternoon. The ego changes lanes to the right while an adversary car in the right lane accelerates to close the gap.
# BEGIN HEADER
param map = localPath('maps/arise_straight.xodr')
param carla_map = 'arise_straight'
model scenic.simulators.carla.model
# END HEADER
# BEGIN WEATHER
# kb: weather.cloudy_noon
param weather = 'CloudyNoon'
# END WEATHER
# BEGIN BEHAVIOR
# kb: behavior.accelerate
param OPT_ADV_SPEED = Range(3, 5)
param OPT_ADV_FAST_SPEED = Range(12, 16)
param OPT_ADV_GAP = Range(12, 20)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until (distance from self to ego) < globalParameters.OPT_ADV_GAP
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_FAST_SPEED)
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
