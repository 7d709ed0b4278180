# On a two-lane road the ego follows a slowly moving car that blocks both lanes by drifting across the lane line.
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
# kb: geometry.straight_road
param OPT_EGO_SPEED = Range(7, 10)
param OPT_EGO_START = Range(10, 40)
egoLane = Uniform(*[lane for lane in network.lanes if lane.centerline.length > 80])
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.lead_same_lane
param OPT_SPAWN_GAP = Range(15, 25)
advStart = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_GAP
advLane = egoLane
adversary = new Car at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
