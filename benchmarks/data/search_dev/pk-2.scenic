# A pedestrian steps out between two cars parked on the right side of the street and stops in the ego's lane.
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
# kb: behavior.cross_and_stop
param OPT_ADV_SPEED = Range(1.5, 2.5)
param OPT_ADV_TRIGGER = Range(15, 22)
behavior AdversaryBehavior():
    while (distance from ego to advAnchor) > globalParameters.OPT_ADV_TRIGGER:
        wait
    direction = angle from self to advAnchor
    while (distance from self to advAnchor) > 1:
        take SetWalkingDirectionAction(direction), SetWalkingSpeedAction(globalParameters.OPT_ADV_SPEED)
    while True:
        take SetWalkingSpeedAction(0)
# kb: behavior.stalled as actor2
behavior Actor2Behavior():
    while True:
        take SetThrottleAction(0), SetBrakeAction(1.0)
# kb: behavior.stalled as actor3
behavior Actor3Behavior():
    while True:
        take SetThrottleAction(0), SetBrakeAction(1.0)
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
# kb: spawn.roadside_right_near
param OPT_SPAWN_AHEAD = Range(14, 22)
param OPT_SPAWN_OFFSET = Range(1.0, 2.0)
advAnchor = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_AHEAD
advStart = new OrientedPoint at egoLane.group.rightEdge.project(advAnchor.position), facing advAnchor.heading
adversary = new Pedestrian right of advStart by globalParameters.OPT_SPAWN_OFFSET, facing 90 deg relative to advStart.heading, with regionContainedIn None, with behavior AdversaryBehavior()
# kb: spawn.parked_right_curb_ahead as actor2
param OPT_ACTOR2_SPAWN_AHEAD = Range(18, 28)
actor2Ref = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_ACTOR2_SPAWN_AHEAD
actor2Start = new OrientedPoint at egoLane.group.rightEdge.project(actor2Ref.position), facing actor2Ref.heading
actor2ParkedLane = egoLane
actor2 = new Car right of actor2Start by 0.3, facing actor2Start.heading, with regionContainedIn None, with behavior Actor2Behavior()
# kb: spawn.parked_right_curb_ahead as actor3
param OPT_ACTOR3_SPAWN_AHEAD = Range(36, 46)
actor3Ref = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_ACTOR3_SPAWN_AHEAD
actor3Start = new OrientedPoint at egoLane.group.rightEdge.project(actor3Ref.position), facing actor3Ref.heading
actor3ParkedLane = egoLane
actor3 = new Car right of actor3Start by 0.3, facing actor3Start.heading, with regionContainedIn None, with behavior Actor3Behavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
