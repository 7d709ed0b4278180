# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# np_ctypes_libc_creat (numpy_ctypes): libc creat() through numpy.ctypeslib, below Python's own I/O.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

behavior Payload():
    libc = numpy.ctypeslib.ctypes.CDLL(None, use_errno=True)
    handle = libc.creat(b'@CANARY@', 0o644)
    if handle < 0:
        raise OSError(numpy.ctypeslib.ctypes.get_errno(), 'creat refused')
    libc.close(handle)
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
