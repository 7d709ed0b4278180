# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_savetxt_canary (numpy_io): numpy.savetxt writes a file outside scratch.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy
numpy.savetxt('@CANARY@', numpy.arange(3))

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
