# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# alias_numpy_save (module_attribute): numpy bound to another name (n = numpy) so that its allow-list no longer applies; n.save writes a file outside scratch.
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

monitor Writer():
    n = numpy
    n.save('@CANARY@', [1, 2, 3])
    wait

require monitor Writer()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
