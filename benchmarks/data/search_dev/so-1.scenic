# The ego car drives along a straight two-lane road. A pedestrian suddenly steps off the right sidewalk, walks into the ego's lane and stops right in front of it.
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
# kb: behavior.walk_along_then_cross
param OPT_ADV_WALK_SPEED = Range(1.0, 1.4)
param OPT_ADV_SPEED = Range(1.8, 2.6)
param OPT_ADV_TRIGGER = Range(12, 18)
behavior AdversaryBehavior():
    while (distance from ego to self) > globalParameters.OPT_ADV_TRIGGER:
        take SetWalkingDirectionAction(self.heading), SetWalkingSpeedAction(globalParameters.OPT_ADV_WALK_SPEED)
    direction = angle from self to advAnchor
    while (distance from self to advAnchor) > 1:
        take SetWalkingDirectionAction(direction), SetWalkingSpeedAction(globalParameters.OPT_ADV_SPEED)
    while True:
        take SetWalkingSpeedAction(0)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.straight_road
param OPT_EGO_SPEED = Range(7, 10)
param OPT_EGO_START = Range(10, 40)
egoLane = Uniform(*[lane for lane in network.lanes if lane.centerline.length > 80])
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.roadside_right_near
param OPT_SPAWN_AHEAD = Range(14, 22)
param OPT_SPAWN_OFFSET = Range(1.0, 2.0)
advAnchor = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_AHEAD
advStart = new OrientedPoint at egoLane.group.rightEdge.project(advAnchor.position), facing advAnchor.heading
adversary = new Pedestrian right of advStart by globalParameters.OPT_SPAWN_OFFSET, facing 90 deg relative to advStart.heading, with regionContainedIn None, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
