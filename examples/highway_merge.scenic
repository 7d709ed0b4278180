# The AV was travelling in the right lane of the freeway when a car merging from the
# on-ramp changed into the AV's lane from the acceleration lane, beside it.
# (Composed from the knowledge base: arise kb show ID prints each entry.)
# BEGIN HEADER
param map = localPath('maps/arise_merge.xodr')
param carla_map = 'arise_merge'
model scenic.simulators.carla.model
# END HEADER
# BEGIN WEATHER
# END WEATHER
# BEGIN BEHAVIOR
# kb: behavior.merge_from_ramp
param OPT_ADV_SPEED = Range(18, 22)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=rampRoute[0]) until self.position in rampRoute[-1]
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.highway_merge_through_lane
param OPT_EGO_SPEED = Range(14, 17)
param OPT_EGO_TO_MERGE = Range(30, 45)
mergePairs = [(ramp, through) for zone in network.intersections for through in zone.maneuvers if through.type is ManeuverType.STRAIGHT and len(through.startLane.group.lanes) > 1 and through.endLane.sections[0]._laneToRight is None for ramp in zone.maneuvers if ramp.endLane is through.endLane and ramp.startLane.road is not through.startLane.road and len(ramp.startLane.group.lanes) < len(through.startLane.group.lanes) and abs((ramp.connectingLane.centerline[1] - ramp.connectingLane.centerline[0]).angleWith(through.connectingLane.centerline[1] - through.connectingLane.centerline[0])) < 1.05]
chosenMerge = Uniform(*mergePairs)
mergingManeuver = chosenMerge[0]
egoLane = chosenMerge[1].startLane
egoRoute = [egoLane, chosenMerge[1].connectingLane, chosenMerge[1].endLane]
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(-globalParameters.OPT_EGO_TO_MERGE), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.on_ramp_beside_right
param OPT_SPAWN_BEHIND = Range(-2, 5)
rampRoute = [mergingManeuver.startLane, mergingManeuver.connectingLane, mergingManeuver.endLane]
advLane = mergingManeuver.startLane
advStart = new OrientedPoint at advLane.centerline.pointAlongBy(-((distance from egoStart to egoLane.centerline[-1]) + globalParameters.OPT_SPAWN_BEHIND)), facing roadDirection
adversary = new Car at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
