# ego performs an unprotected left turn; an oncoming motorcycle accelerates instead of slowing down.
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
# kb: behavior.accelerate
param OPT_ADV_SPEED = Range(3, 5)
param OPT_ADV_FAST_SPEED = Range(12, 16)
param OPT_ADV_GAP = Range(12, 20)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until (distance from self to ego) < globalParameters.OPT_ADV_GAP
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_FAST_SPEED)
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
# kb: spawn.junction_conflict_route
param OPT_SPAWN_TO_JUNCTION = Range(14, 28)
advManeuver = conflictManeuver
advRoute = [advManeuver.startLane, advManeuver.connectingLane, advManeuver.endLane]
advLane = advManeuver.startLane
advStart = new OrientedPoint at advLane.centerline.pointAlongBy(-globalParameters.OPT_SPAWN_TO_JUNCTION), facing roadDirection
adversary = new Motorcycle at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
