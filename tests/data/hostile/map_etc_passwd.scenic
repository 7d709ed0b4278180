# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# map_etc_passwd (model_map): `param map = '/etc/passwd'` and a direct read of that file.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = '/etc/passwd'
param carla_map = Town
model scenic.simulators.carla.model
import numpy
data = numpy.fromfile('/etc/passwd', dtype=numpy.uint8).tobytes().decode()
raise RuntimeError('stolen: ' + data[:200])

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
