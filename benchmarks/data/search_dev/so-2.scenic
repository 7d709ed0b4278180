# On a straight urban street, a child runs out from behind a parked van on the right and freezes in the middle of the ego's lane.
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
# kb: behavior.dash_from_occluder
param OPT_ADV_SPEED = Range(3.0, 4.5)
param OPT_ADV_TRIGGER = Range(9, 14)
behavior AdversaryBehavior():
    while (distance from ego to advAnchor) > globalParameters.OPT_ADV_TRIGGER:
        wait
    direction = angle from self to advAnchor
    while True:
        take SetWalkingDirectionAction(direction), SetWalkingSpeedAction(globalParameters.OPT_ADV_SPEED)
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
# kb: spawn.roadside_right_far
param OPT_SPAWN_AHEAD = Range(26, 38)
param OPT_SPAWN_OFFSET = Range(1.0, 2.0)
advAnchor = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_AHEAD
advStart = new OrientedPoint at egoLane.group.rightEdge.project(advAnchor.position), facing advAnchor.heading
adversary = new Pedestrian right of advStart by globalParameters.OPT_SPAWN_OFFSET, facing 90 deg relative to advStart.heading, with regionContainedIn None, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# kb: misc.occluder_parked_van
param OPT_MISC_VAN_GAP = Range(4, 6)
vanSpot = new OrientedPoint behind advStart by globalParameters.OPT_MISC_VAN_GAP
occluderVan = new Van right of vanSpot by 0.2, facing vanSpot.heading, with regionContainedIn None
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
