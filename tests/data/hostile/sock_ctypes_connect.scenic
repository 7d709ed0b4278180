# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# sock_ctypes_connect (socket): libc socket()/connect() through numpy.ctypeslib, below Python's socket module.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy

def dial(port):
    ct = numpy.ctypeslib.ctypes
    libc = ct.CDLL(None, use_errno=True)
    handle = libc.socket(2, 1, 0)
    if handle < 0:
        raise OSError(ct.get_errno(), 'socket refused')
    address = bytes([2, 0, port >> 8, port & 255, 127, 0, 0, 1]) + bytes(8)
    if libc.connect(handle, address, 16) != 0:
        raise OSError(ct.get_errno(), 'connect refused')
    libc.close(handle)
    return 1

dial(@PORT@)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
