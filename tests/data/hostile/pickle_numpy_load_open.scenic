# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# pickle_numpy_load_open (pickle): a pickle that calls builtins.open(canary, 'w') when numpy.load unpickles it.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

behavior Payload():
    blob = b"cbuiltins\nopen\n(V@CANARY@\nVw\ntR."
    numpy.frombuffer(blob, dtype=numpy.uint8).tofile('opener.pkl')
    handle = numpy.load('opener.pkl', allow_pickle=True)
    handle.close()
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
