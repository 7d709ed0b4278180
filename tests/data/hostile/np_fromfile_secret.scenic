# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_fromfile_secret (numpy_io): numpy.fromfile reads a secret file; the text leaks through the error message.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

def steal(path):
    data = numpy.fromfile(path, dtype=numpy.uint8).tobytes().decode()
    raise RuntimeError('stolen: ' + data)

steal('@SECRET@')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
