# A cyclist riding ahead in the ego's lane suddenly swerves left toward the middle of the road.
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
# kb: behavior.swerve
param OPT_ADV_SPEED = Range(7, 10)
param OPT_ADV_TRIGGER = Range(12, 20)
param OPT_ADV_STEER = Range(0.3, 0.5)
behavior Steer(amount, throttle):
    while True:
        take SetThrottleAction(throttle), SetSteerAction(amount)
behavior AdversaryBehavior():
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED, laneToFollow=advLane) until (distance from self to ego) < globalParameters.OPT_ADV_TRIGGER
    side = ((ego.position - self.position).rotatedBy(-self.heading)).x
    amount = globalParameters.OPT_ADV_STEER if side > 0 else -globalParameters.OPT_ADV_STEER
    do Steer(amount, 0.3) for 0.6 seconds
    do Steer(-amount, 0.3) for 0.6 seconds
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED)
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
adversary = new Bicycle at advStart, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN MISC
# END MISC
# BEGIN REQUIREMENTS
terminate after 20 seconds
# END REQUIREMENTS
