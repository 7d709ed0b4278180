# Two vehicles reach a four-way junction at the same time: the ego going straight and a motorcycle from the left going straight.
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
# kb: behavior.weave_between_lanes
param OPT_ADV_SPEED = Range(10, 14)
param OPT_ADV_HOLD_SECONDS = Range(1, 2)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) for globalParameters.OPT_ADV_HOLD_SECONDS seconds
    while True:
        here = self._laneSection
        target = None
        if here is not None:
            if here._laneToLeft is not None and here._laneToLeft.isForward == here.isForward:
                target = here._laneToLeft
            elif here._laneToRight is not None and here._laneToRight.isForward == here.isForward:
                target = here._laneToRight
        if target is not None:
            do LaneChangeBehavior(laneSectionToSwitch=target, target_speed=globalParameters.OPT_ADV_SPEED) for 3 seconds
        do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED) for globalParameters.OPT_ADV_HOLD_SECONDS seconds
        here = self._laneSection
        if here is not None and here._laneToRight is not None and here._laneToRight.isForward == here.isForward:
            do LaneChangeBehavior(laneSectionToSwitch=here._laneToRight, target_speed=globalParameters.OPT_ADV_SPEED) for 3 seconds
        do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED) for globalParameters.OPT_ADV_HOLD_SECONDS seconds
# kb: behavior.cruise_constant as actor2
param OPT_ACTOR2_ADV_SPEED = Range(4, 7)
behavior Actor2Behavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ACTOR2_ADV_SPEED, laneToFollow=actor2Lane)
# kb: behavior.cruise_constant as actor3
param OPT_ACTOR3_ADV_SPEED = Range(4, 7)
behavior Actor3Behavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ACTOR3_ADV_SPEED, laneToFollow=actor3Lane)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.junction_straight_cross_from_left
param OPT_EGO_SPEED = Range(6, 9)
param OPT_EGO_TO_JUNCTION = Range(12, 25)
behavior EgoJunctionBehavior():
    do FollowTrajectoryBehavior(target_speed=globalParameters.OPT_EGO_SPEED, trajectory=egoRoute)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
junctionPairs = [(m, c) for i in network.intersections for m in i.maneuvers if m.type is ManeuverType.STRAIGHT for c in m.conflictingManeuvers if c.type is ManeuverType.STRAIGHT and -135 deg < (relative heading of c.startLane.centerline.end from m.startLane.centerline.end) < -45 deg]
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
# kb: spawn.lead_same_lane as actor2
param OPT_ACTOR2_SPAWN_GAP = Range(15, 25)
actor2Start = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_ACTOR2_SPAWN_GAP
actor2Lane = egoLane
actor2 = new Car at actor2Start, with behavior Actor2Behavior()
# kb: spawn.lead_same_lane as actor3
param OPT_ACTOR3_SPAWN_GAP = Range(33, 43)
actor3Start = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_ACTOR3_SPAWN_GAP
actor3Lane = egoLane
actor3 = new Car at actor3Start, with behavior Actor3Behavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
