# A cyclist runs a red light from the right side of a four-way intersection just as the ego enters it.
# BEGIN HEADER
param map = localPath('maps/arise_intersection4.xodr')
param carla_map = 'arise_intersection4'
model scenic.simulators.carla.model
# END HEADER
# BEGIN WEATHER
# kb: weather.clear_noon
param weather = 'ClearNoon'
# END WEATHER
# BEGIN BEHAVIOR
# kb: behavior.cyclist_cross_road
param OPT_ADV_SPEED = Range(3, 5)
param OPT_ADV_TRIGGER = Range(16, 24)
behavior AdversaryBehavior():
    while (distance from ego to advAnchor) > globalParameters.OPT_ADV_TRIGGER:
        wait
    while True:
        take SetSpeedAction(globalParameters.OPT_ADV_SPEED)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.signalized_straight_on_green
param OPT_EGO_SPEED = Range(7, 10)
param OPT_EGO_TO_JUNCTION = Range(15, 28)
behavior EgoOnGreenBehavior():
    take SetTrafficLightAction("green")
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_EGO_SPEED, trajectory=egoRoute)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
junctionPairs = [(m, c) for i in network.intersections if i.isSignalized for m in i.maneuvers if m.type is ManeuverType.STRAIGHT for c in m.conflictingManeuvers if c.type is ManeuverType.STRAIGHT]
chosenPair = Uniform(*junctionPairs)
egoManeuver = chosenPair[0]
conflictManeuver = chosenPair[1]
junction = egoManeuver.intersection
egoLane = egoManeuver.startLane
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(-globalParameters.OPT_EGO_TO_JUNCTION), facing roadDirection
ego = new Car at egoStart, with behavior EgoOnGreenBehavior()
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.roadside_right_near
param OPT_SPAWN_AHEAD = Range(14, 22)
param OPT_SPAWN_OFFSET = Range(1.0, 2.0)
advAnchor = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_AHEAD
advStart = new OrientedPoint at egoLane.group.rightEdge.project(advAnchor.position), facing advAnchor.heading
adversary = new Bicycle right of advStart by globalParameters.OPT_SPAWN_OFFSET, facing 90 deg relative to advStart.heading, with regionContainedIn None, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
