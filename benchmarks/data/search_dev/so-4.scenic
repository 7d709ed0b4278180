# While the ego vehicle cruises down a straight road at night in the rain, a pedestrian crosses diagonally from the left sidewalk toward the right one and pauses in the road.
# BEGIN HEADER
param map = localPath('maps/arise_straight.xodr')
param carla_map = 'arise_straight'
model scenic.simulators.carla.model
# END HEADER
# BEGIN WEATHER
# kb: weather.mid_rainy_night
param weather = 'MidRainyNight'
# END WEATHER
# BEGIN BEHAVIOR
# kb: behavior.cross_diagonally
param OPT_ADV_SPEED = Range(1.2, 2.0)
param OPT_ADV_TRIGGER = Range(18, 26)
param OPT_ADV_ANGLE = Range(25, 45)
behavior AdversaryBehavior():
    while (distance from ego to advAnchor) > globalParameters.OPT_ADV_TRIGGER:
        wait
    direction = (angle from self to advAnchor) - globalParameters.OPT_ADV_ANGLE * 3.14159 / 180
    while True:
        take SetWalkingDirectionAction(direction), SetWalkingSpeedAction(globalParameters.OPT_ADV_SPEED)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.urban_street_curb_lane
param OPT_EGO_SPEED = Range(6, 9)
param OPT_EGO_START = Range(10, 40)
egoLane = Uniform(*[lane for lane in network.lanes if lane.centerline.length > 80 and lane.group._sidewalk is not None and lane.sections[0]._laneToRight is None])
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.roadside_left_far_side
param OPT_SPAWN_AHEAD = Range(18, 30)
param OPT_SPAWN_OFFSET = Range(0.5, 1.5)
advAnchor = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_AHEAD
advStart = new OrientedPoint at egoLane.group.opposite.rightEdge.project(advAnchor.position), facing advAnchor.heading
adversary = new Pedestrian left of advStart by globalParameters.OPT_SPAWN_OFFSET, facing -90 deg relative to advStart.heading, with regionContainedIn None, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
