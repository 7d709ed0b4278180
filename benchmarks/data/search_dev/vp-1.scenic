# The ego overtakes a slow truck on a straight road; while the ego is beside it, the truck swerves toward the ego.
# BEGIN HEADER
param map = localPath('maps/arise_straight.xodr')
param carla_map = 'arise_straight'
model scenic.simulators.carla.model
# END HEADER
# BEGIN WEATHER
# kb: weather.clear_noon
param weather = 'ClearNoon'
# END WEATHER
# BEGIN BEHAVIOR
# kb: behavior.block_lanes_slowly
param OPT_ADV_STEER = Range(0.15, 0.3)
param OPT_ADV_TURN_SECONDS = Range(2, 3)
behavior Steer(amount, throttle):
    while True:
        take SetThrottleAction(throttle), SetSteerAction(amount)
behavior AdversaryBehavior():
    while (distance from self to ego) > 25 and (distance from advLane.centerline to self) < 3:
        take SetThrottleAction(0.3)
    do Steer(-globalParameters.OPT_ADV_STEER, 0.3) for globalParameters.OPT_ADV_TURN_SECONDS seconds
    do Steer(0, 0.2) for 2 seconds
    while True:
        take SetThrottleAction(0), SetBrakeAction(1.0)
# END BEHAVIOR
# BEGIN GEOMETRY
# kb: geometry.multilane_right_neighbor
param OPT_EGO_SPEED = Range(8, 11)
param OPT_EGO_START = Range(10, 40)
egoSection = Uniform(*[s for lane in network.lanes if lane.centerline.length > 80 for s in lane.sections if s._laneToRight is not None and s._laneToRight.isForward == s.isForward])
egoLane = egoSection.lane
rightSection = egoSection._laneToRight
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.right_lane_ahead
param OPT_SPAWN_AHEAD = Range(6, 14)
advRef = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_AHEAD
advStart = new OrientedPoint at rightSection.centerline.project(advRef.position), facing roadDirection
advLane = rightSection.lane
adversary = new Truck at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
