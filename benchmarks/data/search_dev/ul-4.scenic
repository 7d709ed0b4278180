# While the ego turns left, a car from the opposite direction, hidden behind another car, appears late and goes straight.
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
# kb: behavior.yield_then_go
param OPT_ADV_SPEED = Range(6, 9)
param OPT_ADV_TRIGGER = Range(12, 20)
behavior AdversaryBehavior():
    # Up to its stop line first (a car spawned far back has to get there), then it
    # holds until the ego is close, then it goes.
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_ADV_SPEED, trajectory=advRoute) until (distance from self to advRoute[1].centerline[0]) < 4 or (distance from self to ego) < globalParameters.OPT_ADV_TRIGGER
    while (distance from self to ego) > globalParameters.OPT_ADV_TRIGGER:
        take SetThrottleAction(0), SetBrakeAction(1.0)
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_ADV_SPEED, trajectory=advRoute)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED)
# kb: behavior.cruise_constant as actor2
param OPT_ACTOR2_ADV_SPEED = Range(4, 7)
behavior Actor2Behavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ACTOR2_ADV_SPEED, laneToFollow=actor2Lane)
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
adversary = new Car at advStart, with behavior AdversaryBehavior()
# kb: spawn.lead_same_lane as actor2
param OPT_ACTOR2_SPAWN_GAP = Range(15, 25)
actor2Start = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_ACTOR2_SPAWN_GAP
actor2Lane = egoLane
actor2 = new Car at actor2Start, with behavior Actor2Behavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
