# Highway driving: a truck ahead in the ego's lane slows down sharply.
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
# kb: behavior.slow_down_when_overtaken
param OPT_ADV_SPEED = Range(7, 9)
param OPT_ADV_SLOW_SPEED = Range(1, 3)
param OPT_ADV_GAP = Range(10, 16)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until (distance from self to ego) < globalParameters.OPT_ADV_GAP
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SLOW_SPEED)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.highway_slow_lane
param OPT_EGO_SPEED = Range(15, 20)
param OPT_EGO_START = Range(10, 60)
egoSection = Uniform(*[s for lane in network.lanes if lane.centerline.length > 300 for s in lane.sections if s._laneToRight is None and s._laneToLeft is not None and s._laneToLeft.isForward == s.isForward])
egoLane = egoSection.lane
leftSection = egoSection._laneToLeft
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.lead_same_lane
param OPT_SPAWN_GAP = Range(15, 25)
advStart = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_GAP
advLane = egoLane
adversary = new Truck at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
