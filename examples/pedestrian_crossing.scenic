# A pedestrian crosses in front of the ego on a straight road and stops in its lane.
# Run: arise check examples/pedestrian_crossing.scenic --png out/scene.png
# BEGIN HEADER
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
param weather = 'ClearNoon'
# END HEADER
# BEGIN BEHAVIOR
param OPT_ADV_SPEED = Range(1.5, 2.5)
param OPT_TRIGGER = Range(12, 18)
behavior AdversaryBehavior():
    do CrossingBehavior(ego, globalParameters.OPT_ADV_SPEED, globalParameters.OPT_TRIGGER) until (distance from self to ego) < 4
    while True:
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
# The crossing point must still be on the ego's lane (not past the end of the road).
require AdvSpawnPt in egoLane
terminate when (distance to EgoSpawnPt) > 60
# END REQUIREMENTS
