# ego turns right onto a busy road; a motorcycle from the left is heading straight into the lane the ego is entering.
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
# kb: behavior.lane_filter_past_ego
param OPT_ADV_SPEED = Range(13, 17)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.junction_right_turn_cross_from_left
param OPT_EGO_SPEED = Range(5, 7)
param OPT_EGO_TO_JUNCTION = Range(10, 22)
behavior EgoJunctionBehavior():
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_EGO_SPEED, trajectory=egoRoute)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
junctionPairs = [(m, c) for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.RIGHT_TURN for c in i.maneuvers if c.type is ManeuverType.STRAIGHT and c.endLane.road is m.endLane.road]
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
