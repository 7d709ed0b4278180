# As the ego vehicle turns right, a man on the sidewalk walks into the crosswalk without looking.
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
# kb: geometry.junction_right_turn_exit_crossing
param OPT_EGO_SPEED = Range(4, 6)
param OPT_EGO_TO_JUNCTION = Range(10, 20)
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
