# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_loadtxt_secret (numpy_io): numpy.loadtxt reads a secret at simulation time and leaks it in the error.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

behavior Payload():
    data = numpy.loadtxt('@SECRET@', dtype=str, delimiter='\t', ndmin=1)
    raise RuntimeError('stolen: ' + ' '.join(data))
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
