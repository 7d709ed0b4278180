# A truck in the adjacent right lane drifts into the ego's lane without signalling while both travel side by side.
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
# kb: behavior.oncoming_drift_into_lane
param OPT_ADV_SPEED = Range(7, 10)
param OPT_ADV_TRIGGER = Range(25, 35)
param OPT_ADV_STEER = Range(0.15, 0.3)
behavior Steer(amount, throttle):
    while True:
        take SetThrottleAction(throttle), SetSteerAction(amount)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until (distance from self to ego) < globalParameters.OPT_ADV_TRIGGER
    side = ((ego.position - self.position).rotatedBy(-self.heading)).x
    amount = globalParameters.OPT_ADV_STEER if side > 0 else -globalParameters.OPT_ADV_STEER
    do Steer(amount, 0.4) for 1 seconds
    do Steer(-amount, 0.3) for 1 seconds
    # Back to its own lane (the lane it is in now may be the ego's, the other way);
    # once it is well past the ego the encounter is over and the scene ends.
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until (distance from self to ego) > 30 and ((self.position - ego.position).rotatedBy(-ego.heading)).y < 0
    terminate
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
# kb: spawn.junction_waiting_at_line
param OPT_SPAWN_TO_JUNCTION = Range(3, 7)
advManeuver = conflictManeuver
advRoute = [advManeuver.startLane, advManeuver.connectingLane, advManeuver.endLane]
advLane = advManeuver.startLane
advStart = new OrientedPoint at advLane.centerline.pointAlongBy(-globalParameters.OPT_SPAWN_TO_JUNCTION), facing roadDirection
adversary = new Truck at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
