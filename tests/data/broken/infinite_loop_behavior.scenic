# BEGIN HEADER
Town = 'Town01'
param map = localPath(f'../maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
param weather = 'ClearNoon'
# END HEADER
# BEGIN BEHAVIOR
param OPT_ADV_SPEED = Range(1.5, 2.5)
param OPT_TRIGGER = Range(12, 18)
behavior AdversaryBehavior():
    while True:
        speed = 0
    take SetWalkingSpeedAction(0)
# END BEHAVIOR
# BEGIN GEOMETRY
EGO_MODEL = "vehicle.lincoln.mkz_2017"
egoLane = Uniform(*network.lanes)
EgoSpawnPt = new OrientedPoint on egoLane.centerline
ego = new Car at EgoSpawnPt, with blueprint EGO_MODEL, with behavior FollowLaneBehavior(target_speed=8)
# END GEOMETRY
# BEGIN SPAWN
param OPT_GEO_Y_DISTANCE = Range(15, 25)
AdvSpawnPt = new OrientedPoint following roadDirection from EgoSpawnPt for globalParameters.OPT_GEO_Y_DISTANCE
AdvAgent = new Pedestrian right of AdvSpawnPt by 4, facing 90 deg relative to AdvSpawnPt.heading, with regionContainedIn None, with behavior AdversaryBehavior()
# END SPAWN
# BEGIN REQUIREMENTS
require (distance to intersection) > 30
require (distance from AdvAgent to intersection) > 15
terminate when (distance to EgoSpawnPt) > 60
# END REQUIREMENTS
