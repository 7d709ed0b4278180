# Left turn across traffic in the rain. An oncoming truck keeps going straight and does not yield.
# BEGIN HEADER
param map = localPath('maps/arise_straight.xodr')
param carla_map = 'arise_straight'
model scenic.simulators.carla.model
# END HEADER
# BEGIN WEATHER
# kb: weather.mid_rainy_noon
param weather = 'MidRainyNoon'
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
# kb: geometry.two_way_inner_lane
param OPT_EGO_SPEED = Range(7, 10)
param OPT_EGO_START = Range(10, 40)
egoSection = Uniform(*[s for lane in network.lanes if lane.centerline.length > 80 for s in lane.sections if s._laneToLeft is not None and s._laneToLeft.isForward != s.isForward])
egoLane = egoSection.lane
oncomingSection = egoSection._laneToLeft
egoStart = new OrientedPoint at egoLane.centerline.pointAlongBy(globalParameters.OPT_EGO_START), facing roadDirection
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=globalParameters.OPT_EGO_SPEED)
# END GEOMETRY
# BEGIN SPAWN
# kb: spawn.oncoming_lane_ahead
param OPT_SPAWN_AHEAD = Range(45, 65)
advRef = new OrientedPoint following roadDirection from egoStart for globalParameters.OPT_SPAWN_AHEAD
advStart = new OrientedPoint at oncomingSection.centerline.project(advRef.position), facing roadDirection
advLane = oncomingSection.lane
adversary = new Truck at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
