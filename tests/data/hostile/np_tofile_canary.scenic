# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_tofile_canary (numpy_io): ndarray.tofile writes raw bytes outside scratch.
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

monitor Payload():
    numpy.arange(4, dtype=numpy.uint8).tofile('@CANARY@')
    while True:
        wait

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require monitor Payload()
