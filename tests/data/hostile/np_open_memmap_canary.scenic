# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_open_memmap_canary (numpy_io): numpy.lib.format.open_memmap in a require creates a .npy file.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require numpy.lib.format.open_memmap('@CANARY@', mode='w+', dtype='float64', shape=(2,)) is not None
