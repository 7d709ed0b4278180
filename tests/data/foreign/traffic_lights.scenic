# Traffic-light helpers of Scenic's CARLA model (recorded offline) and an unprotected turn.
param map = localPath('../../../assets/maps/CARLA/Town10HD.xodr')
param carla_map = 'Town10HD'
model scenic.simulators.carla.model
param weather = {'cloudiness': 30.0, 'precipitation': 0.0, 'sun_altitude_angle': 45.0}

behavior Approach(route):
    setClosestTrafficLightStatus(self, "green")
    while withinDistanceToRedYellowTrafficLight(self, 15):
        take SetBrakeAction(1.0)
    do FollowTrajectoryBehavior(target_speed=7, trajectory=route)

behavior Walker():
    take SetWalkingDirectionAction(self.heading), SetWalkingSpeedAction(1.2)

junction = Uniform(*network.intersections)
route = Uniform(*junction.maneuvers)
start = new OrientedPoint in route.startLane.centerline
ego = new Car at start, with behavior Approach([route.startLane, route.connectingLane, route.endLane])

walker = new Pedestrian on visible sidewalk, with behavior Walker()
require (distance from ego to junction) < 30
