# ego makes a left turn at a four-way junction while a cyclist crosses the destination road from right to left.
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
# kb: geometry.junction_left_turn_oncoming
param OPT_EGO_SPEED = Range(5, 8)
param OPT_EGO_TO_JUNCTION = Range(10, 22)
behavior EgoJunctionBehavior():
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_EGO_SPEED, trajectory=egoRoute)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
junctionPairs = [(m, c) for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.LEFT_TURN for c in m.conflictingManeuvers if c.type is ManeuverType.STRAIGHT and c.endLane.road is m.startLane.road]
chosenPair = Uniform(*junctionPairs)
egoManeuver = chosenPair[0]
conflictManeuver = chosenPair[1]
junction = egoManeuver.intersection
egoLane = egoManeuver.startLane
egoRoute = [egoManeuver.startLane, egoManeuver.connectingLane, egoManeuver.endLane]
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(-globalParameters.OPT_EGO_TO_JUNCTION), facing roadDirection
ego = new Car at egoStart, with behavior EgoJunctionBehavior()
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.junction_exit_roadside
param OPT_SPAWN_INTO_EXIT = Range(6, 12)
param OPT_SPAWN_OFFSET = Range(1.0, 2.0)
advAnchor = new OrientedPoint at egoManeuver.endLane.centerline.pointAlongBy(globalParameters.OPT_SPAWN_INTO_EXIT), facing roadDirection
advStart = new OrientedPoint at egoManeuver.endLane.group.rightEdge.project(advAnchor.position), facing advAnchor.heading
adversary = new Bicycle right of advStart by globalParameters.OPT_SPAWN_OFFSET, facing 90 deg relative to advStart.heading, with regionContainedIn None, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
