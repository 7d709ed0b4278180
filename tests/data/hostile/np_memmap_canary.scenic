# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_memmap_canary (numpy_io): numpy.memmap(mode='w+') creates and maps a file outside scratch.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

def mapped():
    block = numpy.memmap('@CANARY@', dtype=numpy.uint8, mode='w+', shape=(16,))
    block[:] = 7
    block.flush()
    return 1

mapped()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
