# Right turn at a signalized intersection in heavy rain; a motorcyclist waiting in the target lane suddenly pulls out and brakes.
# BEGIN HEADER
param map = localPath('maps/arise_intersection4.xodr')
param carla_map = 'arise_intersection4'
model scenic.simulators.carla.model
# END HEADER
# BEGIN WEATHER
# kb: weather.hard_rain_noon
param weather = 'HardRainNoon'
# END WEATHER
# BEGIN BEHAVIOR
# kb: behavior.cut_in_and_brake
param OPT_ADV_SPEED = Range(9, 12)
param OPT_ADV_CUT_GAP = Range(4, 8)
param OPT_ADV_BRAKE = Range(0.8, 1.0)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until ((self.position - ego.position).rotatedBy(-ego.heading)).y > globalParameters.OPT_ADV_CUT_GAP
    here = self._laneSection
    target = ego._laneSection
    if here is not None and target is not None and (target is here._laneToLeft or target is here._laneToRight):
        do LaneChangeBehavior(laneSectionToSwitch=target, target_speed=globalParameters.OPT_ADV_SPEED)
    while True:
        take SetThrottleAction(0), SetBrakeAction(globalParameters.OPT_ADV_BRAKE)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.signalized_straight_cross_from_right
param OPT_EGO_SPEED = Range(7, 10)
param OPT_EGO_TO_JUNCTION = Range(15, 28)
behavior EgoOnGreenBehavior():
    take SetTrafficLightAction("green")
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_EGO_SPEED, trajectory=egoRoute)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
junctionPairs = [(m, c) for i in network.intersections if i.isSignalized for m in i.maneuvers if m.type is ManeuverType.STRAIGHT for c in m.conflictingManeuvers if c.type is ManeuverType.STRAIGHT and 45 deg < (relative heading of c.startLane.centerline.end from m.startLane.centerline.end) < 135 deg]
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
# kb: spawn.lead_same_lane
param OPT_SPAWN_GAP = Range(15, 25)
advStart = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_GAP
advLane = egoLane
adversary = new Motorcycle at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
