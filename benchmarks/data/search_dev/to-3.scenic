# At a T-junction the ego turns left. Just after the turn, a pedestrian dashes out from behind a bus stop and stops in the ego's path.
# BEGIN HEADER
param map = localPath('maps/arise_tjunction.xodr')
param carla_map = 'arise_tjunction'
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
# kb: geometry.tjunction_stem_left_turn
param OPT_EGO_SPEED = Range(5, 7)
param OPT_EGO_TO_JUNCTION = Range(10, 20)
behavior EgoJunctionBehavior():
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_EGO_SPEED, trajectory=egoRoute)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
junctionPairs = [(m, c) for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.LEFT_TURN and not any(s.type is ManeuverType.STRAIGHT for s in i.maneuvers if s.startLane is m.startLane) for c in m.conflictingManeuvers if c.type is ManeuverType.STRAIGHT]
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
adversary = new Pedestrian right of advStart by globalParameters.OPT_SPAWN_OFFSET, facing 90 deg relative to advStart.heading, with regionContainedIn None, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# kb: misc.occluder_bus_stop
stopSpot = new OrientedPoint behind advStart by 2.5
busStop = new BusStop right of stopSpot by 2.5, facing stopSpot.heading, with regionContainedIn None
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
