# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_save_canary (numpy_io): numpy.save writes a .npy file outside scratch.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

behavior Payload():
    numpy.save('@CANARY@', numpy.arange(3))
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
